"""Recursive Wang tiles for multi-density blue noise end to end (Kopf et al. 2006; class notes
Part V): the ``recursive-wang`` family.

Two questions (:mod:`tilesolve.model.poisson_recursive`):

* :class:`~tilesolve.model.poisson_recursive.RecursiveTilesProblem`: build a set; route
  ``build`` (:func:`tilesolve.constructive.poisson_recursive.build_recursive`). The answer is
  checked by :func:`tilesolve.verify.poisson_recursive.tileset_violations`: the corner tiles
  every level places give a Poisson disk distribution on every tiling, and the subdivision
  rules turn every tiling into a tiling.
* :class:`~tilesolve.model.poisson_recursive.RecursiveWindowProblem`: the points of a window
  at a level or a density; route ``window``. The answer is checked by
  :func:`tilesolve.verify.poisson_recursive.window_violations`: every level a Poisson disk
  distribution at its own distance. A window read from a file (version 2,
  :class:`~tilesolve.io.poisson_recursive_json.SeededRecursiveWindow`) is bound to its seed:
  its embedded set is checked and its points re-derived from the set, the density and the seed
  and compared exactly, levels and ranks too (:func:`rederived_violations`).

Examples
--------
>>> from tilesolve.model.poisson_recursive import RecursiveTilesProblem, RecursiveWindowProblem
>>> s = solve(RecursiveTilesProblem(1, 16, 0.7, 2), seed=3)
>>> s.status.value, s.method
('sat', 'build')
>>> w = solve(RecursiveWindowProblem(s.tiling, (-7, 2**40, 2, 2), level=2), seed=5)
>>> w.method, sorted(set(w.tiling.level.tolist()))
('window', [0, 1, 2])
"""

from __future__ import annotations

import math
import time
from typing import Any

from tilesolve.errors import InvalidProblem, MethodNotApplicable
from tilesolve.family import Codec, Demo, Family, RunOptions, register
from tilesolve.family import solve as _solve
from tilesolve.families.sampling_forms import RECURSIVE_FORM
from tilesolve.io.poisson_json import UNBOUND
from tilesolve.io.poisson_recursive_json import (
    TILES_FORMAT,
    VERSIONS,
    WINDOW_FORMAT,
    WINDOW_VERSIONS,
    SeededRecursiveWindow,
    set_from_dict,
    set_to_dict,
    window_from_dict,
    window_to_dict,
)
from tilesolve.model.poisson_recursive import (
    RecursiveProblem,
    RecursiveTilesProblem,
    RecursiveTileSet,
    RecursiveWindow,
    RecursiveWindowProblem,
)
from tilesolve.model.solution import Solution, Status
from tilesolve.model.window import Window
from tilesolve.progress import Progress
from tilesolve.verify.dappled import Violation

__all__ = ["FAMILY", "SOLVERS", "solve", "build", "window", "recursive_violations", "rederived_violations", "auto_method",
           "picture_distance"]


def build(problem: RecursiveTilesProblem, run: RunOptions) -> Solution:
    """Build the set: corner tiles, progressive order, subdivision rules."""
    if not isinstance(problem, RecursiveTilesProblem):
        raise MethodNotApplicable("the build route builds tile sets; a window takes the window route")
    from tilesolve.constructive.poisson_recursive import build_recursive

    t0 = time.perf_counter()
    ts = build_recursive(problem, seed=run.seed)
    return Solution(Status.SAT, ts, method="build", seed=run.seed, time_s=time.perf_counter() - t0,
                    stats={"short": ts.base.stats.get("short", 0), "tiles": problem.n_tiles, "points": ts.n_points})


def window(problem: RecursiveWindowProblem, run: RunOptions) -> Solution:
    """The points of the window at its level or density."""
    if not isinstance(problem, RecursiveWindowProblem):
        raise MethodNotApplicable("the window route samples a built set; build one with the build route")
    from tilesolve.constructive.poisson_recursive import sample_window

    t0 = time.perf_counter()
    w = sample_window(problem, seed=run.seed)
    return Solution(Status.SAT, w, method="window", seed=run.seed, time_s=time.perf_counter() - t0,
                    stats={"points": w.n_points, "level": problem.level}, window=problem.window)


#: Routes by name.
SOLVERS = {"build": build, "window": window}


def auto_method(problem: RecursiveProblem) -> str:
    """``build`` for a set, ``window`` for a window."""
    return "window" if isinstance(problem, RecursiveWindowProblem) else "build"


def recursive_violations(problem: RecursiveProblem, answer: Any) -> list[Violation]:
    """A set: :func:`~tilesolve.verify.poisson_recursive.tileset_violations`, and that it is the
    set the problem asks for; a window: :func:`~tilesolve.verify.poisson_recursive.window_violations`
    at the problem's distances (a window file's problem is the set it was drawn from)."""
    from tilesolve.verify.poisson_recursive import tileset_violations, window_violations

    if isinstance(answer, RecursiveTileSet):
        if not isinstance(problem, RecursiveTilesProblem) or answer.problem != problem:
            return [Violation("shape", "the tile set is not the one the problem asks for")]
        return tileset_violations(answer)
    if isinstance(answer, RecursiveWindow):
        p = problem.tileset.problem if isinstance(problem, RecursiveWindowProblem) else problem
        if isinstance(problem, RecursiveWindowProblem) and answer.window != problem.window:
            return [Violation("window", "the points are of another window")]
        if (answer.distance, answer.subdivision) != (p.distance, p.subdivision):
            return [Violation("shape", "the points' distances are not the set's")]
        out = window_violations(answer)
        if not isinstance(problem, RecursiveWindowProblem):
            return out + [Violation("unbound", UNBOUND.format(what="tile set or density"))]
        if isinstance(answer, SeededRecursiveWindow):
            return out + rederived_violations(problem, answer)
        return out
    return [Violation("shape", "the answer is neither a recursive Wang tile set nor a window of points")]


#: A window is sampled again for ``verify`` only while its candidate points are at most this many for
#: each point of its file, plus :data:`REDERIVE_FREE`: a small file that names a vast window costs little.
REDERIVE_PER_POINT = 256
REDERIVE_FREE = 1 << 21


def rederived_violations(problem: RecursiveWindowProblem, answer: SeededRecursiveWindow) -> list[Violation]:
    """A window file's claim that its points are the window of its set, density and seed: the
    set is checked (:func:`~tilesolve.verify.poisson_recursive.tileset_violations`), the window
    sampled again with the answer's seed and its points, levels and ranks compared with the
    file's, exactly (:func:`~tilesolve.verify.poisson.match_violations`). The sampling is the
    builder's (:func:`~tilesolve.constructive.poisson_recursive.sample_window`): it binds the
    seed, while every level's spacing is checked independently."""
    import numpy as np

    from tilesolve.constructive.poisson_recursive import sample_window
    from tilesolve.verify.poisson import match_violations
    from tilesolve.verify.poisson_recursive import label_violations, tileset_violations

    bad = tileset_violations(problem.tileset)
    if bad:
        return [Violation(v.kind, f"the file's tile set: {v.message}") for v in bad]
    p = problem.tileset.problem
    candidates = sum(bw * bh * p.density_at(k) for k, (_, _, bw, bh) in enumerate(problem.boxes()))
    if candidates > REDERIVE_PER_POINT * answer.n_points + REDERIVE_FREE:
        return [Violation("size", f"NOT confirmed: sampling the window again builds about {candidates:,.0f} candidate "
                                  f"points, too many for a file of {answer.n_points:,} points; it was not re-derived")]
    w = sample_window(problem, seed=answer.seed)
    return match_violations(np.column_stack([answer.local, answer.level, answer.rank]),
                            np.column_stack([w.local, w.level, w.rank]), f"the window of seed {answer.seed}") \
        + label_violations(problem.label, problem.density, problem.level)


def picture_distance(w: RecursiveWindow) -> float:
    """The distance a picture of the window sizes its dots by: the mean spacing of its points
    (a window at one level: about its distance; a density ramp: one size for all dots)."""
    return math.sqrt(w.window.width * w.window.height / max(w.n_points, 1))


def solve(problem: RecursiveProblem, *, method: str | Any = "auto", seed: int | None = None,
          time_limit: float | None = None, progress: Progress | bool = False) -> Solution:
    """Build a set or a window and verify it (:func:`tilesolve.family.solve`)."""
    if not isinstance(problem, RecursiveProblem):
        raise InvalidProblem(f"expected a recursive Wang problem, got {type(problem).__name__}")
    return _solve(problem, method, seed=seed, time_limit=time_limit, progress=progress)


def _write(problem, sol: Solution) -> dict:
    return window_to_dict(problem, sol) if isinstance(problem, RecursiveWindowProblem) else set_to_dict(problem, sol)


def _draw(problem: RecursiveProblem, sol: Solution, path, fmt: str, *, title: str | None = None, **_ignored) -> None:
    """A window's points; a set is drawn as the 4 x 4 window at the origin at level 1, seed 0."""
    from tilesolve.io.poisson_plots import write_points_picture

    answer = sol.tiling
    if isinstance(answer, RecursiveTileSet):
        from tilesolve.constructive.poisson_recursive import sample_window

        answer = sample_window(RecursiveWindowProblem(answer, Window(0, 0, 4, 4), level=1), seed=0)
    if not isinstance(answer, RecursiveWindow):
        raise InvalidProblem("nothing drawn: the solution holds no recursive Wang points")
    write_points_picture(path, answer.local, answer.window, picture_distance(answer),
                         title or f"{answer.n_points:,} points, {answer.window.caption()}", fmt)


def _ramp_demo() -> RecursiveWindowProblem:
    """A density ramp, 16 to 2,048 points a tile, over 8 x 2 tiles of a set built with seed 1."""
    import numpy as np

    from tilesolve.constructive.poisson_recursive import build_recursive

    ts = build_recursive(RecursiveTilesProblem(2, 16, 0.7, 4), seed=1)
    return RecursiveWindowProblem(ts, Window(0, 0, 8, 2), density=np.linspace(16, 2048, 1024)[None, :],
                                  label="a ramp from 16 to 2,048 points a tile")


DEMOS = (
    Demo("recursive-wang", "recursive Wang tiles: C = 2, N = 16, rho = 0.7, 4x4 subdivision (Kopf et al. 2006)",
         lambda: RecursiveTilesProblem(2, 16, 0.7, 4), method="build"),
    Demo("recursive-wang-ramp", "recursive Wang tiles: 16 to 2,048 points a tile, west to east (levels 0-2)",
         _ramp_demo, method="window"),
)

FAMILY = register(Family(
    name="recursive-wang",
    title="recursive Wang tiles: blue noise at any density, every level a Poisson disk distribution "
          "(Kopf et al. 2006; class notes Part V)",
    problem_type=RecursiveProblem,
    routes=SOLVERS,
    auto=auto_method,
    verify=recursive_violations,
    codecs=(Codec(TILES_FORMAT, VERSIONS, set_from_dict, _write), Codec(WINDOW_FORMAT, WINDOW_VERSIONS, window_from_dict)),
    draw=_draw,
    demos=DEMOS,
    commands=("tilesolve.cli.sample:sample",),
    form=RECURSIVE_FORM,
    route_help={
        "build": "corner-based Poisson disk tiles in progressive order, with n x n subdivision rules (Kopf et al.)",
        "window": "the points of any window at a level or a density (uniform, a ramp, an image)",
    },
    answer="point set",
))
