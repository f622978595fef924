"""What one studio solve does, in its worker process: pose, solve, verify, draw.

Everything the page shows comes from the registry (:mod:`tilesolve.family`): the family's
form builds the problem, :func:`tilesolve.family.solve` runs the pipeline, the solution file
is written with the family's codec and checked again by :func:`verify_document` (what
``tilesolve verify`` does with that file), and the picture is the family's drawing.
"""

from __future__ import annotations

import base64
import json
import shlex
import time
from typing import Any, Mapping

import numpy as np

from tilesolve import family
from tilesolve.errors import InvalidProblem
from tilesolve.progress import SILENT, Progress

__all__ = ["pose", "solve_request", "picture", "command_line", "packed_cells", "warm_families", "SVG_MAX_CELLS",
           "MAX_TIME_LIMIT"]

#: Solutions with at most this many tiling entries are drawn as SVG; larger ones as PNG.
SVG_MAX_CELLS = 2500

#: Longest time limit a page may ask for (seconds).
MAX_TIME_LIMIT = 3600.0


def warm_families() -> None:
    """Run every family's :attr:`~tilesolve.family.Family.warm` hook: a server lives long, so
    every solve should take the fast path (e.g. compiled kernels) from the first."""
    for fam in family.families():
        if fam.warm is not None:
            fam.warm()


def pose(name: str, values: Any) -> tuple[family.Family, dict, Any, Mapping]:
    """The family, checked form values, problem and solve options of a request."""
    if not isinstance(name, str):
        raise InvalidProblem("family must be a family name")
    fam = family.get(name)
    if fam.form is None:
        raise InvalidProblem(f"{fam.name} problems have no form")
    vals = fam.form.values(values if values is not None else {})
    problem, options = fam.form.build(vals)
    return fam, vals, problem, options


def check_run(fam: family.Family, method: Any, time_limit: Any) -> tuple[str, float | None]:
    """The method and time limit of a request, checked with the CLI's messages."""
    if method not in fam.methods:
        raise InvalidProblem(f"unknown method {method!r} for {fam.name} problems; choose one of {', '.join(fam.methods)}")
    if time_limit is not None:
        if isinstance(time_limit, bool) or not isinstance(time_limit, (int, float)) or \
                not 0 < time_limit <= MAX_TIME_LIMIT:
            raise InvalidProblem(f"time limit must be a number of seconds in (0, {MAX_TIME_LIMIT:g}], got {time_limit!r}")
        time_limit = float(time_limit)
    return method, time_limit


def command_line(fam: family.Family, values: Mapping, method: str, seed: int, time_limit: float | None = None) -> str:
    """The shell line that reproduces a result: the files the command reads (written by
    ``printf``, or by the ``tilesolve`` command a file's entry names as a list of words), then
    ``tilesolve`` with the form's options, method, time limit (where the command takes one,
    :attr:`~tilesolve.family.Form.time_limit`), seed and ``-o solution.json``."""
    words, files = fam.form.command(values)
    words = ["tilesolve", *words]
    if method != "auto":
        words += ["--method", method]
    if time_limit is not None and fam.form.time_limit:
        words += ["--time-limit", f"{time_limit:g}"]
    words += ["--seed", str(seed), "-o", "solution.json"]
    parts = [f"printf %s {shlex.quote(made)} > {shlex.quote(name)}" if isinstance(made, str)
             else shlex.join(["tilesolve", *made]) for name, made in files.items()]
    return " && ".join(parts + [shlex.join(words)])


def picture(problem: Any, sol, fmt: str | None = None) -> dict:
    """The family's drawing of ``sol``: SVG for small tilings, PNG for large, or the one format
    its family draws (:attr:`~tilesolve.family.Family.pictures`); ``fmt`` forces one."""
    if fmt is None:
        fmt = "svg" if getattr(sol.tiling, "size", 0) <= SVG_MAX_CELLS else "png"
        drawn = family.family_of(problem).pictures
        fmt = fmt if fmt in drawn else drawn[0]
    data = family.render(problem, sol, fmt)
    if fmt == "svg":
        return {"format": "svg", "data": data}
    return {"format": "png", "data": base64.b64encode(data).decode("ascii")}


def packed_cells(cells) -> dict:
    """A grid of ints for the page, packed: ``{"rows", "cols", "dtype", "data"}`` with ``data``
    the base64 of its little-endian values in the narrowest of int8, int16, int32 that holds
    them (a 2048 x 2048 grid is 5.6 MB of base64 rather than 12 MB of nested JSON lists, which
    the page also decodes in milliseconds)."""
    a = np.asarray(cells)
    lo, hi = (int(a.min()), int(a.max())) if a.size else (0, 0)
    dtype = next(t for t in ("<i1", "<i2", "<i4") if np.iinfo(t).min <= lo and hi <= np.iinfo(t).max)
    return {"rows": int(a.shape[0]), "cols": int(a.shape[1]) if a.ndim > 1 else 1,
            "dtype": {"<i1": "int8", "<i2": "int16", "<i4": "int32"}[dtype],
            "data": base64.b64encode(np.ascontiguousarray(a, dtype=dtype).tobytes()).decode("ascii")}


def solve_request(name: str, values: Any, method: str, time_limit: float | None, *,
                  progress: Progress = SILENT) -> dict:
    """Solve one studio request, reporting on ``progress``; the answer the page shows (JSON-ready)."""
    fam, vals, problem, options = pose(name, values)
    method, time_limit = check_run(fam, method, time_limit)
    t0 = time.perf_counter()
    sol = family.solve(problem, method, seed=vals["seed"], time_limit=time_limit, progress=progress,
                       options=options)
    out: dict[str, Any] = {
        "family": fam.name,
        "describe": problem.describe() if hasattr(problem, "describe") else fam.name,
        "status": sol.status.value,
        "report": None if sol.report is None else {"title": sol.report.title, "verdict": sol.report.verdict,
                                                   "conclusion": sol.report.conclusion},
        "method": sol.method,
        "seed": sol.seed,
        "time_s": round(sol.time_s, 4),
        "reason": sol.reason,
        "notes": list(sol.notes),
        "objective": sol.objective,
        "stats": {str(k): str(v) for k, v in sol.stats.items()},
        "window": None if sol.window is None else sol.window.to_dict(),
        "command": command_line(fam, vals, method, sol.seed, time_limit),
    }
    with progress.task("checking the solution file (tilesolve verify)", unit=None):
        text = family.solution_text(problem, sol)
        out["json"] = text
        out["verdict"] = list(family.verify_document(json.loads(text), "solution.json").lines)
    with progress.task("drawing the picture", unit=None):
        try:
            out["picture"] = picture(problem, sol) if sol.answer is not None else None
        except InvalidProblem as exc:  # an answer without a tiling to draw (e.g. a report with no witness)
            out["picture"] = None
            out["notes"].append(f"no picture: {exc}")
    cells = fam.form.cells(problem, sol) if fam.form.cells is not None and sol.status.has_tiling else None
    out["cells"] = packed_cells(cells) if cells is not None else None
    out["solve_s"] = round(time.perf_counter() - t0, 4)
    return out
