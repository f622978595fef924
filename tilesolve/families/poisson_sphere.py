"""Corner-based Poisson sphere tiles end to end (class notes §4.4): the ``poisson-sphere`` family.

Two questions (:mod:`tilesolve.model.poisson_sphere`):

* :class:`~tilesolve.model.poisson_sphere.PoissonSphereTilesProblem`: build the
  ``C + 3C^2 + 3C^4 + C^8`` tiles; route ``dart`` (3-D relaxation dart throwing,
  :func:`tilesolve.constructive.poisson_sphere.build_tiles`), checked by
  :func:`tilesolve.verify.poisson_sphere.tileset_violations3` (every point in its region, every
  pair of nearby slots under every colouring of their lattice points for C <= 2, 4,096 random
  colourings a pair above; the stated shortfall, ``stats["short"]``, re-counted from the tiles
  by :func:`~tilesolve.verify.poisson_sphere.shortfall_violations3`).
* :class:`~tilesolve.model.poisson_sphere.PoissonSphereWindowProblem`: the points of a box of
  space tiled by the direct 3-D corner tiling; route ``window``, checked by
  :func:`tilesolve.verify.poisson_sphere.point_violations3` (a grid search). A box read from a
  file (version 2, :class:`~tilesolve.io.poisson_sphere_json.SeededBox`) is bound to its seed:
  its embedded set is checked (:func:`~tilesolve.verify.poisson_sphere.tileset_violations3`)
  and its points re-derived from the set and the lattice the seed's hash colours
  (:func:`~tilesolve.verify.poisson_sphere.placed_points3`, not the builder's placement) and
  compared exactly (:func:`~tilesolve.verify.poisson.match_violations`).

Examples
--------
>>> from tilesolve.model.poisson_sphere import PoissonSphereTilesProblem, PoissonSphereWindowProblem
>>> s = solve(PoissonSphereTilesProblem(1, 100, 0.6), seed=3)
>>> s.status.value, s.method
('sat', 'dart')
>>> w = solve(PoissonSphereWindowProblem(s.tiling, (-7, 2**40, 0, 2, 2, 1)), seed=5)
>>> w.method, w.tiling.n_points == 4 * (100 - s.tiling.stats["short"])
('window', True)
"""

from __future__ import annotations

import time
from typing import Any

from tilesolve.errors import InvalidProblem, MethodNotApplicable
from tilesolve.family import Codec, Demo, Family, RunOptions, register
from tilesolve.family import solve as _solve
from tilesolve.families.sampling_forms import SPHERE_FORM
from tilesolve.io.poisson_json import UNBOUND
from tilesolve.io.poisson_sphere_json import TILES_FORMAT, VERSIONS, WINDOW_FORMAT, WINDOW_VERSIONS, SeededBox
from tilesolve.model.poisson_sphere import (
    Box,
    PoissonSphereProblem,
    PoissonSphereTilesProblem,
    PoissonSphereTileSet,
    PoissonSphereWindow,
    PoissonSphereWindowProblem,
)
from tilesolve.model.solution import Solution, Status
from tilesolve.progress import Progress
from tilesolve.verify.dappled import Violation

__all__ = ["FAMILY", "SOLVERS", "solve", "dart", "window", "sphere_violations", "rederived_violations3",
           "auto_method"]


def dart(problem: PoissonSphereTilesProblem, run: RunOptions) -> Solution:
    """Build the tile set by 3-D relaxation dart throwing (§4.4.3)."""
    if not isinstance(problem, PoissonSphereTilesProblem):
        raise MethodNotApplicable("the dart route builds tile sets; a box takes the window route")
    from tilesolve.constructive.poisson_sphere import build_tiles

    t0 = time.perf_counter()
    ts = build_tiles(problem, seed=run.seed)
    return Solution(Status.SAT, ts, method="dart", seed=run.seed, time_s=time.perf_counter() - t0,
                    stats={"short": ts.stats["short"], "tiles": problem.n_tiles, "points": ts.n_points})


def window(problem: PoissonSphereWindowProblem, run: RunOptions) -> Solution:
    """The points of the box, the lattice coloured by the direct 3-D corner tiling."""
    if not isinstance(problem, PoissonSphereWindowProblem):
        raise MethodNotApplicable("the window route places the tiles of a built set; build one with the dart route")
    from tilesolve.constructive.poisson_sphere import window_points

    t0 = time.perf_counter()
    w = window_points(problem.tileset, problem.box, hash=problem.hash, seed=run.seed)
    return Solution(Status.SAT, w, method="window", seed=run.seed, time_s=time.perf_counter() - t0,
                    stats={"points": w.n_points})


#: Routes by name.
SOLVERS = {"dart": dart, "window": window}


def auto_method(problem: PoissonSphereProblem) -> str:
    """``dart`` for a tile set, ``window`` for a box."""
    return "window" if isinstance(problem, PoissonSphereWindowProblem) else "dart"


def sphere_violations(problem: PoissonSphereProblem, answer: Any) -> list[Violation]:
    """A set: :func:`~tilesolve.verify.poisson_sphere.tileset_violations3` and that it is the set
    the problem asks for; a box: :func:`~tilesolve.verify.poisson_sphere.point_violations3` at
    the problem's distance, and for a box read from a file, :func:`rederived_violations3`
    (version 2) or the violation :data:`~tilesolve.io.poisson_json.UNBOUND` (version 1, whose
    problem is the set's only)."""
    from tilesolve.verify.poisson_sphere import point_violations3, tileset_violations3

    if isinstance(answer, PoissonSphereTileSet):
        if not isinstance(problem, PoissonSphereTilesProblem) or answer.problem != problem:
            return [Violation("shape", "the tile set is not the one the problem asks for")]
        return tileset_violations3(answer)
    if isinstance(answer, PoissonSphereWindow):
        if isinstance(problem, PoissonSphereWindowProblem) and answer.box != problem.box:
            return [Violation("shape", "the points are of another box than the problem's")]
        out = point_violations3(answer.local, problem.distance, answer.box.size)
        if not isinstance(problem, PoissonSphereWindowProblem):
            return out + [Violation("unbound", UNBOUND.format(what="tile set"))]
        if isinstance(answer, SeededBox):
            return out + rederived_violations3(problem, answer)
        return out
    return [Violation("shape", "the answer is neither a Poisson sphere tile set nor a box of points")]


def rederived_violations3(problem: PoissonSphereWindowProblem, answer: SeededBox) -> list[Violation]:
    """A box file's claim that its points are the box of its set and seed: the set is checked
    (:func:`~tilesolve.verify.poisson_sphere.tileset_violations3`), the lattice of the box
    coloured by the problem's hash with the answer's seed, the set's tiles placed on it by
    :func:`~tilesolve.verify.poisson_sphere.placed_points3` and the points inside the box
    compared with the file's, exactly (:func:`~tilesolve.verify.poisson.match_violations`)."""
    import numpy as np

    from tilesolve.constructive.poisson_sphere import lattice_colors
    from tilesolve.verify.poisson import match_violations, window_size_violations
    from tilesolve.verify.poisson_sphere import placed_points3, tileset_violations3

    ts, box = problem.tileset, problem.box
    bad = tileset_violations3(ts)
    if bad:
        return [Violation(v.kind, f"the file's tile set: {v.message}") for v in bad]
    bad = window_size_violations(ts.tiles["interior"], int(np.prod(box.size)), len(answer.local))
    if bad:  # before the lattice is coloured: a box larger than its file's points allow costs nothing
        return bad
    pts = placed_points3(ts, lattice_colors(box, ts.problem.colors, seed=answer.seed, hash=problem.hash))
    pts = pts[((pts >= 0) & (pts < np.array(box.size, dtype=np.float64))).all(axis=1)]
    return match_violations(answer.local, pts, f"the direct corner tiling of seed {answer.seed}")


def solve(problem: PoissonSphereProblem, *, method: str | Any = "auto", seed: int | None = None,
          time_limit: float | None = None, progress: Progress | bool = False) -> Solution:
    """Build a set or a box and verify it (:func:`tilesolve.family.solve`)."""
    if not isinstance(problem, PoissonSphereProblem):
        raise InvalidProblem(f"expected a Poisson sphere problem, got {type(problem).__name__}")
    return _solve(problem, method, seed=seed, time_limit=time_limit, progress=progress)


def _read_tiles(doc: dict, source: str):
    from tilesolve.io.poisson_sphere_json import tiles_from_dict

    return tiles_from_dict(doc, source)


def _write(problem, sol: Solution) -> dict:
    from tilesolve.io.poisson_sphere_json import tiles_to_dict, window_to_dict

    if isinstance(problem, PoissonSphereWindowProblem):
        return window_to_dict(problem, sol)
    return tiles_to_dict(problem, sol)


def _read_window(doc: dict, source: str):
    from tilesolve.io.poisson_sphere_json import window_from_dict

    return window_from_dict(doc, source)


def _draw(problem: PoissonSphereProblem, sol: Solution, path, fmt: str, *, title: str | None = None,
          **_ignored) -> None:
    """The points of a box's bottom slab, one distance thick, seen along z (a thicker slab's
    projected points would cover the picture); a set is drawn as the 6 x 6 x 1 box at the origin,
    seed 0."""
    from tilesolve.io.poisson_plots import write_points_picture
    from tilesolve.model.window import Window

    answer = sol.tiling
    if isinstance(answer, PoissonSphereTileSet):
        from tilesolve.constructive.poisson_sphere import window_points

        answer = window_points(answer, Box(0, 0, 0, 6, 6, 1), seed=0)
    if not isinstance(answer, PoissonSphereWindow):
        raise InvalidProblem("nothing drawn: the solution holds no Poisson sphere points")
    b, d = answer.box, answer.distance
    slab = answer.local[answer.local[:, 2] < d]
    caption = title or (f"{len(slab):,} points of the box {b.width}x{b.height}x{b.depth} at ({b.x0}, {b.y0}, "
                        f"{b.z0}) within {d:.3g} of its floor, seen along z")
    write_points_picture(path, slab[:, :2], Window(b.x0, b.y0, b.width, b.height), d, caption, fmt)


FAMILY = register(Family(
    name="poisson-sphere",
    title="corner-based Poisson sphere tiles: build a 3-D set, sample any box of space (class notes §4.4)",
    problem_type=PoissonSphereProblem,
    routes=SOLVERS,
    auto=auto_method,
    verify=sphere_violations,
    codecs=(Codec(TILES_FORMAT, VERSIONS, _read_tiles, _write), Codec(WINDOW_FORMAT, WINDOW_VERSIONS, _read_window)),
    demos=(Demo("poisson-spheres", "corner-based Poisson sphere tiles: C = 1, N = 100, rho = 0.6 (§4.4)",
                lambda: PoissonSphereTilesProblem(1, 100, 0.6), method="dart"),),
    draw=_draw,
    commands=("tilesolve.cli.sample:sample",),
    form=SPHERE_FORM,
    route_help={
        "dart": "build the C + 3C^2 + 3C^4 + C^8 corner, edge, face and interior tiles by 3-D relaxation dart "
                "throwing (§4.4.3)",
        "window": "the points of any box of space, the lattice coloured by the direct 3-D corner tiling (§3.4 hash)",
    },
    answer="point set",
))
