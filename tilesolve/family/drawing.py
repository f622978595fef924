"""Pictures of solutions, drawn by their family."""

from __future__ import annotations

import os
from typing import Any

from tilesolve.errors import InvalidProblem, MethodNotApplicable
from tilesolve.family.registry import family_of
from tilesolve.model.solution import Solution

__all__ = ["draw_solution", "render"]


def draw_solution(path: str | os.PathLike, problem: Any, solution: Solution, *, fmt: str | None = None,
                  **options: Any) -> None:
    """Draw a solution with its family's drawing (``fmt`` from the file suffix by default)."""
    fam = family_of(problem)
    if fam.draw is None:
        raise MethodNotApplicable(f"{fam.name} solutions have no drawing")
    fmt = fmt or os.path.splitext(str(path))[1].lstrip(".").lower()
    if fmt not in ("svg", "png"):
        raise InvalidProblem(f"{path}: pictures are .svg or .png files")
    if fmt not in fam.pictures:
        raise InvalidProblem(f"{fam.name} solutions are drawn as {' or '.join(fam.pictures)} only, not {fmt}")
    if solution.answer is None:
        raise InvalidProblem(f"status {solution.status.value}: no tiling to draw")
    fam.draw(problem, solution, path, fmt, **options)


def render(problem: Any, solution: Solution, fmt: str) -> str | bytes:
    """The picture of ``solution`` as SVG text or PNG bytes (``Solution._repr_svg_`` /
    ``_repr_png_`` call it through ``Solution.renderer``)."""
    import tempfile

    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, f"picture.{fmt}")
        draw_solution(path, problem, solution, fmt=fmt)
        with open(path, "rb") as f:
            data = f.read()
    return data.decode("utf-8") if fmt == "svg" else data
