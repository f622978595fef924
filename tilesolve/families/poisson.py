"""Corner-based Poisson disk tiles end to end (class notes §4.3): the ``poisson`` family.

Two questions (:mod:`tilesolve.model.poisson`):

* :class:`~tilesolve.model.poisson.PoissonTilesProblem`: build a tile set of ``C`` colours,
  ``N`` points a tile, relative radius ``rho``; route ``dart`` (relaxation dart throwing and
  optional Lloyd steps, :func:`tilesolve.constructive.poisson.build_tiles`). The answer, a
  :class:`~tilesolve.model.poisson.PoissonTileSet`, is checked by
  :func:`tilesolve.verify.poisson.tileset_violations`: every point in its region, and every
  2 x 2 block of every tiling (all of them for ``C <= 2``, 4,096 random ones above) a Poisson
  disk distribution.
* :class:`~tilesolve.model.poisson.PoissonWindowProblem`: the points of a window of the
  plane tiled by a stochastic corner tiling (direct or scanline); route ``window``. The answer,
  a :class:`~tilesolve.model.poisson.PoissonWindow`, is checked by
  :func:`tilesolve.verify.poisson.point_violations` (a grid search over the window). A window
  read from a file (version 2, :class:`~tilesolve.io.poisson_json.SeededWindow`) is bound to
  its seed: its embedded set is checked (:func:`~tilesolve.verify.poisson.tileset_violations`)
  and its points re-derived from the set and the lattice the seed's corner tiling colours
  (:func:`~tilesolve.verify.poisson.placed_points`, not the builder's placement) and compared
  exactly (:func:`~tilesolve.verify.poisson.match_violations`).

Examples
--------
>>> from tilesolve.model.poisson import PoissonTilesProblem, PoissonWindowProblem
>>> s = solve(PoissonTilesProblem(1, 32, 0.7), seed=3)
>>> s.status.value, s.method
('sat', 'dart')
>>> w = solve(PoissonWindowProblem(s.tiling, (-7, 2**40, 3, 2)), seed=5)
>>> w.method, w.tiling.n_points
('window', 192)
"""

from __future__ import annotations

import time
from typing import Any

from tilesolve.errors import InvalidProblem, MethodNotApplicable
from tilesolve.family import Codec, Demo, Family, RunOptions, register
from tilesolve.family import solve as _solve
from tilesolve.families.sampling_forms import POISSON_FORM
from tilesolve.io.poisson_json import (
    TILES_FORMAT,
    UNBOUND,
    VERSIONS,
    WINDOW_FORMAT,
    WINDOW_VERSIONS,
    SeededWindow,
)
from tilesolve.model.poisson import (
    PoissonProblem,
    PoissonTilesProblem,
    PoissonTileSet,
    PoissonWindow,
    PoissonWindowProblem,
)
from tilesolve.model.solution import Solution, Status
from tilesolve.model.window import Window
from tilesolve.progress import Progress
from tilesolve.verify.dappled import Violation

__all__ = ["FAMILY", "SOLVERS", "solve", "dart", "window", "poisson_violations", "rederived_violations", "auto_method", "spectra", "achieved_rho", "objects"]


def dart(problem: PoissonTilesProblem, run: RunOptions) -> Solution:
    """Build the tile set: relaxation dart throwing, optional Lloyd steps (§4.3)."""
    if not isinstance(problem, PoissonTilesProblem):
        raise MethodNotApplicable("the dart route builds tile sets; a window takes the window route")
    from tilesolve.constructive.poisson import build_tiles

    t0 = time.perf_counter()
    ts = build_tiles(problem, seed=run.seed)
    return Solution(Status.SAT, ts, method="dart", seed=run.seed, time_s=time.perf_counter() - t0,
                    stats={"short": ts.stats["short"], "tiles": problem.n_tiles, "points": ts.n_points})


def window(problem: PoissonWindowProblem, run: RunOptions) -> Solution:
    """The points of the window, the lattice coloured by the problem's corner tiling."""
    if not isinstance(problem, PoissonWindowProblem):
        raise MethodNotApplicable("the window route places the tiles of a built set; build one with the dart route")
    from tilesolve.constructive.poisson import window_points

    t0 = time.perf_counter()
    w = window_points(problem.tileset, problem.window, tiling=problem.tiling, variant=problem.variant,
                      hash=problem.hash, seed=run.seed)
    return Solution(Status.SAT, w, method="window", seed=run.seed, time_s=time.perf_counter() - t0,
                    stats={"points": w.n_points}, window=problem.window)


#: Routes by name.
SOLVERS = {"dart": dart, "window": window}


def auto_method(problem: PoissonProblem) -> str:
    """``dart`` for a tile set, ``window`` for a window."""
    return "window" if isinstance(problem, PoissonWindowProblem) else "dart"


def poisson_violations(problem: PoissonProblem, answer: Any) -> list[Violation]:
    """A set: :func:`~tilesolve.verify.poisson.tileset_violations` and that it is the set the
    problem asks for; a window: :func:`~tilesolve.verify.poisson.point_violations` at the
    problem's distance, and for a window read from a file, :func:`rederived_violations` (version
    2) or the violation :data:`UNBOUND` (version 1, whose problem is the set's only)."""
    from tilesolve.verify.poisson import point_violations, tileset_violations

    if isinstance(answer, PoissonTileSet):
        if not isinstance(problem, PoissonTilesProblem) or answer.problem != problem:
            return [Violation("shape", "the tile set is not the one the problem asks for")]
        return tileset_violations(answer)
    if isinstance(answer, PoissonWindow):
        if isinstance(problem, PoissonWindowProblem) and answer.window != problem.window:
            return [Violation("window", "the points are of another window")]
        out = point_violations(answer.local, problem.distance, answer.window.width, answer.window.height)
        if not isinstance(problem, PoissonWindowProblem):
            return out + [Violation("unbound", UNBOUND.format(what="tile set"))]
        if isinstance(answer, SeededWindow):
            return out + rederived_violations(problem, answer)
        return out
    return [Violation("shape", "the answer is neither a Poisson tile set nor a window of points")]


def rederived_violations(problem: PoissonWindowProblem, answer: SeededWindow) -> list[Violation]:
    """A window file's claim that its points are the window of its set and seed: the set is
    checked (:func:`~tilesolve.verify.poisson.tileset_violations`), the lattice of the window
    coloured by the problem's corner tiling with the answer's seed, the set's tiles placed on it
    by :func:`~tilesolve.verify.poisson.placed_points` and the points inside the window compared
    with the file's, exactly (:func:`~tilesolve.verify.poisson.match_violations`)."""
    from tilesolve.constructive.poisson import corner_lattice
    from tilesolve.constructive.stochastic import stochastic_window
    from tilesolve.verify.poisson import match_violations, placed_points, tileset_violations, window_size_violations

    ts, w = problem.tileset, problem.window
    bad = tileset_violations(ts)
    if bad:
        return [Violation(v.kind, f"the file's tile set: {v.message}") for v in bad]
    bad = window_size_violations(ts.tiles["interior"], w.width * w.height, len(answer.local))
    if bad:  # before the lattice is coloured: a window larger than its file's points allow costs nothing
        return bad
    grid = stochastic_window("corner", problem.tiling, (w.x0, w.y0, w.width, w.height), colors=ts.problem.colors,
                             seed=answer.seed, variant=problem.variant, hash=problem.hash)
    pts = placed_points(ts, corner_lattice(grid, ts.problem.colors))
    pts = pts[(pts[:, 0] >= 0) & (pts[:, 0] < w.width) & (pts[:, 1] >= 0) & (pts[:, 1] < w.height)]
    return match_violations(answer.local, pts, f"the {problem.tiling} corner tiling of seed {answer.seed}")


def spectra(ts: PoissonTileSet, size: int, *, seed: int | None = None, runs: int = 4) -> list[dict]:
    """The set's points on ``runs`` windows of ``size x size`` tiles (the tiling's seeds
    ``seed``, ``seed + 1``, ...) beside as many runs of plain dart throwing (Cook 1986) at the
    same distance on a torus of that size: for each, ``name``, ``points`` (of the first run),
    ``rho`` (eq. 4.3 at the measured density, the least over the runs), and the radial
    ``frequency``, ``power`` and ``anisotropy`` (dB) of the averaged periodogram
    (:func:`tilesolve.verify.poisson.radial_spectrum`), with its mean ``anisotropy_db``."""
    import numpy as np

    from tilesolve.constructive.poisson import dart_throwing, window_points
    from tilesolve.verify.poisson import radial_spectrum, relative_radius

    p = ts.problem
    base = 0 if seed is None else seed
    tiles = [window_points(ts, Window(0, 0, size, size), seed=base + i).local for i in range(runs)]
    darts = [dart_throwing(2 * p.points * size * size, p.distance / size, seed=base + i, patience=100_000) * size
             for i in range(runs)]
    k_max = min(4 * size * int(np.sqrt(p.points)), 256)
    rows = []
    for name, sets in (("corner tiles", tiles), ("dart throwing", darts)):
        f, power, aniso = radial_spectrum(sets, size, k_max=k_max)
        rows.append({"name": name, "points": len(sets[0]), "rho": min(relative_radius(s, size * size) for s in sets),
                     "frequency": f, "power": power, "anisotropy": aniso, "anisotropy_db": float(np.mean(aniso))})
    return rows


def achieved_rho(w) -> float:
    """The relative radius ``rho`` (eq. 4.3, class notes §4.2) that a window's points keep,
    measured on them over the window's area (:func:`tilesolve.verify.poisson.relative_radius`):
    what a picture's caption states beside the set's asked ``rho``."""
    from tilesolve.verify.poisson import relative_radius

    return relative_radius(w.local, w.window.width * w.window.height)


def objects(ts: PoissonTileSet, window: Window, px: int, *, seed: int | None = None) -> dict:
    """The procedural object distribution function (§6.6.2) at the centres of the ``px`` pixels
    a tile of ``window`` (rows from the top): :func:`tilesolve.constructive.poisson.object_distribution`'s
    arrays, each shaped ``(rows, cols, ...)``."""
    import numpy as np

    from tilesolve.constructive.poisson import object_distribution

    rows, cols = window.height * px, window.width * px
    r, c = np.mgrid[0:rows, 0:cols]
    xy = np.column_stack([(c.ravel() + 0.5) / px, (rows - r.ravel() - 0.5) / px])
    out = object_distribution(ts, xy, origin=(window.x0, window.y0), seed=seed)
    return {k: v.reshape(rows, cols, *v.shape[1:]) for k, v in out.items()}


def solve(problem: PoissonProblem, *, method: str | Any = "auto", seed: int | None = None,
          time_limit: float | None = None, progress: Progress | bool = False) -> Solution:
    """Build a set or a window and verify it (:func:`tilesolve.family.solve`)."""
    if not isinstance(problem, PoissonProblem):
        raise InvalidProblem(f"expected a Poisson problem, got {type(problem).__name__}")
    return _solve(problem, method, seed=seed, time_limit=time_limit, progress=progress)


def _read_tiles(doc: dict, source: str):
    from tilesolve.io.poisson_json import tiles_from_dict

    return tiles_from_dict(doc, source)


def _write_tiles(problem, sol: Solution) -> dict:
    from tilesolve.io.poisson_json import tiles_to_dict, window_to_dict

    return window_to_dict(problem, sol) if isinstance(problem, PoissonWindowProblem) else tiles_to_dict(problem, sol)


def _read_window(doc: dict, source: str):
    from tilesolve.io.poisson_json import window_from_dict

    return window_from_dict(doc, source)


def _draw(problem: PoissonProblem, sol: Solution, path, fmt: str, *, title: str | None = None, **_ignored) -> None:
    """A window's points; a set is drawn as the 8 x 8 window at the origin, seed 0."""
    from tilesolve.io.poisson_plots import write_points_picture

    answer = sol.tiling
    if isinstance(answer, PoissonTileSet):
        from tilesolve.constructive.poisson import window_points

        answer = window_points(answer, Window(0, 0, 8, 8), seed=0)
    if not isinstance(answer, PoissonWindow):
        raise InvalidProblem("nothing drawn: the solution holds no Poisson points")
    write_points_picture(path, answer.local, answer.window, answer.distance,
                         title or f"{answer.n_points:,} points, {answer.window.caption()}", fmt)


DEMOS = (
    Demo("poisson-tiles", "corner-based Poisson disk tiles: C = 2, N = 64, rho = 0.75 (§4.3)",
         lambda: PoissonTilesProblem(2, 64, 0.75), method="dart"),
)

FAMILY = register(Family(
    name="poisson",
    title="corner-based Poisson disk tiles: build a set, sample any window of the plane (class notes §4.3)",
    problem_type=PoissonProblem,
    routes=SOLVERS,
    auto=auto_method,
    verify=poisson_violations,
    codecs=(Codec(TILES_FORMAT, VERSIONS, _read_tiles, _write_tiles), Codec(WINDOW_FORMAT, WINDOW_VERSIONS, _read_window)),
    draw=_draw,
    demos=DEMOS,
    commands=("tilesolve.cli.sample:sample",),
    form=POISSON_FORM,
    route_help={
        "dart": "build the C + 2C^2 + C^4 modified-region tiles by relaxation dart throwing (+ Lloyd) (§4.3)",
        "window": "the points of any window, the lattice coloured by the direct or scanline corner tiling",
    },
    answer="point set",
))
