"""Substitution and Penrose tilings end to end (class notes Part II §8.1, §8.3): the
``substitution`` family.

A problem (:class:`~tilesolve.model.substitution.SubstitutionProblem`) asks for a patch of a
Penrose P3 or P2 tiling, or of a rep-tile tiling; the answer is a
:class:`~tilesolve.model.substitution.Patch` with exact coordinates, checked by the
independent verifier :mod:`tilesolve.verify.substitution` (shapes, edges, matching rules,
angles around every vertex, one piece without holes; for rep-tiles, an exact cover of
``2^n P``).

Routes
------
``substitution``
    Robinson-triangle deflation of a sun (Penrose, ``steps`` or the sun that covers a
    region), or the rep-tile's rule applied ``steps`` times (:mod:`tilesolve.constructive.penrose`,
    :mod:`tilesolve.constructive.reptile`).
``pentagrid``
    de Bruijn's pentagrid (Penrose windows): random access, offsets drawn from the run's seed.

P2 comes from P3 by the correspondence of :mod:`tilesolve.constructive.penrose` on either
route. ``auto`` takes ``pentagrid`` for a Penrose window and ``substitution`` otherwise.

Examples
--------
>>> from tilesolve.model.substitution import SubstitutionProblem
>>> s = solve(SubstitutionProblem("p3", region=(-6, -6, 12, 12)), seed=4)
>>> s.status.value, s.method, s.tiling.n_tiles > 100
('sat', 'pentagrid', True)
>>> solve(SubstitutionProblem("sphinx", steps=2)).tiling.n_tiles
16
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np

from tilesolve.errors import InvalidProblem, MethodNotApplicable
from tilesolve.family import Codec, Demo, Family, Field, Form, RunOptions, form_size, register
from tilesolve.family import solve as _solve
from tilesolve.io.substitution_json import PATCH_FORMAT, VERSIONS
from tilesolve.model.solution import Solution, Status
from tilesolve.model.substitution import KINDS, PENROSE, REPTILES, Patch, SubstitutionProblem
from tilesolve.progress import Progress
from tilesolve.verify.dappled import Violation

__all__ = ["FAMILY", "SOLVERS", "solve", "substitution", "pentagrid", "patch_violations", "auto_method"]


def _solution(problem: SubstitutionProblem, types, vertices, method: str, seed, t0: float, **stats) -> Solution:
    patch = Patch(problem.kind, types, vertices)
    return Solution(Status.SAT, patch, method=method, seed=seed, time_s=time.perf_counter() - t0,
                    stats={"tiles": patch.n_tiles, **patch.counts(), **stats})


def substitution(problem: SubstitutionProblem, run: RunOptions) -> Solution:
    """Penrose: deflate a sun (``steps`` times, or until it covers the region); rep-tiles: apply
    the rule ``steps`` times."""
    t0 = time.perf_counter()
    if problem.kind in PENROSE:
        from tilesolve.constructive.penrose import p2_from_p3, p3_substitution

        types, verts = p3_substitution(problem.steps, problem.region)
        if problem.kind == "p2":
            types, verts = p2_from_p3(types, verts)
        return _solution(problem, types, verts, "substitution", run.seed, t0)
    from tilesolve.constructive.reptile import tiles

    verts = tiles(problem.kind, problem.steps)
    return _solution(problem, np.zeros(len(verts), np.int8), verts, "substitution", run.seed, t0)


def pentagrid(problem: SubstitutionProblem, run: RunOptions) -> Solution:
    """de Bruijn's pentagrid on a Penrose window, offsets from the run's seed."""
    if problem.kind not in PENROSE or problem.region is None:
        raise MethodNotApplicable("the pentagrid cuts a window of a Penrose tiling: give a region "
                                  "(or use the substitution method)")
    from tilesolve.constructive.penrose import p2_from_p3, pentagrid as grid, pentagrid_offsets

    t0 = time.perf_counter()
    gamma = pentagrid_offsets(run.seed)
    types, verts = grid(problem.region, gamma=gamma)
    if problem.kind == "p2":
        types, verts = p2_from_p3(types, verts)
    return _solution(problem, types, verts, "pentagrid", run.seed, t0, offsets=[round(float(g), 12) for g in gamma])


#: Routes by name.
SOLVERS = {"substitution": substitution, "pentagrid": pentagrid}


def auto_method(problem: SubstitutionProblem) -> str:
    """``pentagrid`` for a Penrose window, else ``substitution``."""
    return "pentagrid" if problem.region is not None else "substitution"


def patch_violations(problem: SubstitutionProblem, patch: Patch) -> list[Violation]:
    """Every way ``patch`` fails the problem: the independent checks of
    :mod:`tilesolve.verify.substitution`, plus the patch's kind, and for a window that every
    tile's centre lies in it; for rep-tiles, that the patch covers ``2^steps P``."""
    from tilesolve.verify.substitution import penrose_violations, reptile_violations

    if not isinstance(patch, Patch) or patch.kind != problem.kind:
        return [Violation("shape", f"the answer is no {problem.kind} patch")]
    if problem.kind not in PENROSE:
        return reptile_violations(problem.kind, problem.steps, patch.vertices)
    out = penrose_violations(problem.kind, patch.types, patch.vertices)
    if not out and problem.region is not None:
        x0, y0, w, h = problem.region
        c = patch.centres()
        outside = (c[:, 0] < x0) | (c[:, 0] >= x0 + w) | (c[:, 1] < y0) | (c[:, 1] >= y0 + h)
        out += [Violation("window", f"tile {i}'s centre lies outside the region") for i in outside.nonzero()[0][:20]]
    return out


def solve(problem: SubstitutionProblem, *, method: str | Any = "auto", seed: int | None = None,
          time_limit: float | None = None, progress: Progress | bool = False) -> Solution:
    """Build the patch and verify it (:func:`tilesolve.family.solve` with this family's routes).

    Raises
    ------
    MethodNotApplicable
        ``pentagrid`` without a Penrose region.
    """
    if not isinstance(problem, SubstitutionProblem):
        raise InvalidProblem(f"expected a SubstitutionProblem, got {type(problem).__name__}")
    return _solve(problem, method, seed=seed, time_limit=time_limit, progress=progress)


def _read(doc: dict, source: str):
    from tilesolve.io.substitution_json import patch_from_dict

    return patch_from_dict(doc, source)


def _write(problem: SubstitutionProblem, sol: Solution) -> dict:
    from tilesolve.io.substitution_json import patch_to_dict

    return patch_to_dict(problem, sol)


def _draw(problem: SubstitutionProblem, sol: Solution, path, fmt: str, *, title: str | None = None,
          **_ignored) -> None:
    """SVG (svgwrite, one polygon a tile, a caption) or PNG (Pillow, the caption under it)."""
    from tilesolve.io.substitution_json import write_patch_png, write_patch_svg

    if not isinstance(sol.tiling, Patch):
        raise InvalidProblem("nothing drawn: the solution holds no patch")
    title = title or f"{problem.describe()} ({sol.method}, seed {sol.seed})"
    (write_patch_png if fmt == "png" else write_patch_svg)(path, sol.tiling, title=title)


DEMOS = (
    Demo("penrose-p3", "Penrose rhombs (P3) of a window by de Bruijn's pentagrid",
         lambda: SubstitutionProblem("p3", region=(-12, -8, 24, 16)), method="pentagrid"),
    Demo("penrose-p2", "Penrose kites and darts (P2): a sun deflated 6 times",
         lambda: SubstitutionProblem("p2", steps=6), method="substitution"),
    Demo("sphinx", "the sphinx rep-tile after 3 substitutions", lambda: SubstitutionProblem("sphinx", steps=3)),
)

def _form_build(values) -> tuple[SubstitutionProblem, dict]:
    """A Penrose window (``patch`` = window) or a patch grown by steps."""
    if values["patch"] == "window" and values["kind"] in PENROSE:  # rep-tiles grow by steps
        rows, cols = form_size(values["size"])
        return SubstitutionProblem(values["kind"], region=(values["x0"], values["y0"], cols, rows)), {}
    return SubstitutionProblem(values["kind"], steps=values["steps"]), {}


def _form_command(values) -> tuple[list[str], dict[str, str]]:
    problem, _ = _form_build(values)
    if problem.kind not in PENROSE:
        return ["reptile", "--tile", problem.kind, "--steps", str(problem.steps)], {}
    if problem.region is not None:
        x0, y0, w, h = problem.region
        return ["penrose", "--kind", problem.kind, f"--region={x0},{y0},{w}x{h}"], {}
    return ["penrose", "--kind", problem.kind, "--steps", str(problem.steps)], {}


#: When the window's fields apply: a Penrose window.
_WINDOW = ({"kind": PENROSE, "patch": ("window",)},)

FORM = Form(
    fields=(
        Field("kind", "choice", "tiling", "p3", "Penrose rhombs (p3), kites and darts (p2), or a rep-tile",
              choices=KINDS, option="--kind"),
        Field("patch", "choice", "patch", "window", "a window of the plane (Penrose) or a patch grown by steps",
              choices=("window", "steps"), when=({"kind": PENROSE},)),
        Field("x0", "int", "window x0", -20, "left edge (units: the rhomb edge)", low=-10**6, high=10**6,
              option="--region", when=_WINDOW),
        Field("y0", "int", "window y0", -12, "bottom edge (y grows upwards)", low=-10**6, high=10**6,
              option="--region", when=_WINDOW),
        Field("size", "size", "window (WxH)", "40x24", "W by H units", high=10**6, option="--region", when=_WINDOW),
        Field("steps", "int", "steps", 5, "substitution steps (patch = steps)", low=0, high=12, option="--steps",
              when=({"patch": ("steps",)}, {"kind": REPTILES})),
    ),
    build=_form_build,
    command=_form_command,
    time_limit=False,  # the command runs to its end (no --time-limit)
)

FAMILY = register(Family(
    name="substitution",
    title="substitution tilings: Penrose P3/P2 (substitution or de Bruijn's pentagrid) and rep-tiles "
          "(class notes Part II §8.1, §8.3)",
    problem_type=SubstitutionProblem,
    routes=SOLVERS,
    auto=auto_method,
    verify=patch_violations,
    codecs=(Codec(PATCH_FORMAT, VERSIONS, _read, _write),),
    draw=_draw,
    demos=DEMOS,
    commands=("tilesolve.cli.penrose:penrose", "tilesolve.cli.penrose:reptile"),
    form=FORM,
    route_help={
        "substitution": "deflation of Robinson triangles from a sun (Penrose), or the rep-tile's rule (§8.1, §8.3)",
        "pentagrid": "de Bruijn's pentagrid: any window of a Penrose tiling, random access by seed",
    },
))
