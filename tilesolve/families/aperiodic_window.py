"""Windows of tilings of the plane by aperiodic Wang tile sets, by their constructive routes
(issue 20, §1): the ``aperiodic-window`` family.

A problem (:class:`~tilesolve.model.aperiodic_window.AperiodicWindowProblem`) is a built-in
aperiodic tile set and a window of the plane; the run's seed chooses the tiling of the plane
the window is cut from, and windows of one seed agree where they overlap. Every window is
checked by the shared grid verifier :func:`tilesolve.verify.grid.grid_violations` against the
set's tiles (not toroidally: a window is a piece of the plane), never by the routes' code.

Routes
------
``markov``
    :func:`tilesolve.constructive.markov.markov_window`: the coding of a toral Z²-rotation by a
    Markov partition (S. Labbé, *Markov partitions for toral Z²-rotations featuring Jeandel-Rao
    Wang shift and model sets*, Annales Henri Lebesgue 4 (2021), arXiv:1903.06137): the tile at
    a cell is the label of the polygon holding the seed's starting point moved by the cell.
``balanced``
    :func:`tilesolve.constructive.balanced.balanced_window`: rows that are balanced
    representations of the orbit of a piecewise linear map (J. Kari, *A small aperiodic set of
    Wang tiles*; K. Culik II, *An aperiodic set of 13 Wang tiles*; Discrete Math. 160, 1996).

Each route tiles the sets its kernel names (``NAMES``); ``auto`` takes the route of the set.

Examples
--------
>>> problem, s = tiling("jeandel-rao", "-2,5,6x3", seed=7)
>>> s.status.value, s.method, s.tiling.shape
('sat', 'markov', (3, 6))
>>> t = tiling("jeandel-rao", "-1,5,3x2", seed=7)[1].tiling   # cells x -1..1, y 5..6
>>> bool((t == s.tiling[1:, 1:4]).all())                      # windows of one seed agree
True
"""

from __future__ import annotations

import functools
import time

import numpy as np

from tilesolve.errors import InvalidProblem, MethodNotApplicable
from tilesolve.families.aperiodic_window_form import form
from tilesolve.family import Codec, Family, RunOptions, register
from tilesolve.family import solve as _solve
from tilesolve.io.aperiodic_window_json import APERIODIC_WINDOW, VERSIONS, window_from_dict, window_to_dict
from tilesolve.model.aperiodic_window import AperiodicWindowProblem
from tilesolve.model.solution import Solution, Status
from tilesolve.model.window import Window, parse_region
from tilesolve.progress import Progress
from tilesolve.verify.dappled import Violation
from tilesolve.verify.grid import grid_violations

__all__ = ["FAMILY", "SOLVERS", "AperiodicWindowProblem", "tiling", "window_problem", "solve", "route_of",
           "window_violations", "markov", "balanced"]


def _kernel(route: str):
    """``(NAMES, window function)`` of a route's kernel (imported when a route runs)."""
    if route == "markov":
        from tilesolve.constructive import markov as kernel

        return kernel.NAMES, kernel.markov_window
    from tilesolve.constructive import balanced as kernel

    return kernel.NAMES, kernel.balanced_window


def _tile(problem: AperiodicWindowProblem, run: RunOptions, route: str) -> Solution:
    """The window tiled by the kernel of ``route``, which must name the problem's set."""
    names, window_of = _kernel(route)
    if problem.name not in names:
        raise MethodNotApplicable(f"the {route!r} route tiles {', '.join(names)}, not {problem.name}; "
                                  f"{problem.name} is tiled by {route_of(problem.name)!r}")
    t0 = time.perf_counter()
    grid = window_of(problem.name, problem.window, run.seed)
    return Solution(Status.SAT, grid, method=route, seed=run.seed, time_s=time.perf_counter() - t0,
                    stats={"tiles": problem.n_cells}, window=problem.window)


def markov(problem: AperiodicWindowProblem, run: RunOptions) -> Solution:
    """A window coded by a Markov partition of the torus (Labbé 2021): Jeandel-Rao and U19."""
    return _tile(problem, run, "markov")


def balanced(problem: AperiodicWindowProblem, run: RunOptions) -> Solution:
    """A window of balanced rows (Kari 1996, Culik 1996): the Kari and Kari-Culik sets."""
    return _tile(problem, run, "balanced")


#: Routes by name.
SOLVERS = {"markov": markov, "balanced": balanced}


@functools.lru_cache(maxsize=None)
def _routes_by_set() -> dict[str, str]:
    """``{built-in set name: route}`` from the kernels' ``NAMES``."""
    return {name: route for route in SOLVERS for name in _kernel(route)[0]}


def route_of(name: str) -> str:
    """The constructive route of the built-in tile set ``name``.

    Raises
    ------
    InvalidProblem
        The set has no constructive route (the message lists the sets that have one).
    """
    by_set = _routes_by_set()
    if name not in by_set:
        raise InvalidProblem(f"the built-in set {name!r} has no constructive route; windows are built for "
                             f"{', '.join(sorted(by_set))}")
    return by_set[name]


def window_problem(name: str, window: Window | tuple | str) -> AperiodicWindowProblem:
    """The window ``window`` (a :class:`Window`, ``(x0, y0, width, height)`` or a region
    ``"X0,Y0,WxH"``) of the built-in tile set ``name``, which must have a constructive route."""
    from tilesolve.io.builtin_tilesets import load

    tileset, _ = load(name)
    route_of(name)
    return AperiodicWindowProblem(name, tileset, parse_region(window) if isinstance(window, str) else window)


def window_violations(problem: AperiodicWindowProblem, grid) -> list[Violation]:
    """Every way ``grid`` fails to be a tiling of the problem's window by its tile set: its shape
    must be the window's, every entry a tile of the set, every shared edge of one colour
    (:func:`tilesolve.verify.grid.grid_violations`, not toroidal)."""
    g = np.asarray(grid)
    if g.shape != problem.shape:
        rows, cols = problem.shape
        return [Violation("shape", f"the grid has shape {list(g.shape)}, the window {problem.window.describe()} "
                                   f"has {rows} rows of {cols} tiles")]
    return grid_violations(problem.tileset.tiles, g, kind="wang")


def solve(problem: AperiodicWindowProblem, *, method: str = "auto", seed: int | None = None,
          progress: Progress | bool = False) -> Solution:
    """Tile the problem's window and verify it (:func:`tilesolve.family.solve`).

    Parameters
    ----------
    problem : AperiodicWindowProblem
    method : {"auto", "markov", "balanced"}
    seed : int, optional
        Chooses the tiling of the plane; drawn and recorded when not given.
    """
    if not isinstance(problem, AperiodicWindowProblem):
        raise InvalidProblem(f"expected an AperiodicWindowProblem, got {type(problem).__name__}")
    return _solve(problem, method, seed=seed, progress=progress)


def tiling(name: str, window: Window | tuple | str, *, seed: int | None = None, method: str = "auto",
           progress: Progress | bool = False) -> tuple[AperiodicWindowProblem, Solution]:
    """A verified window of a tiling of the plane by the built-in aperiodic set ``name``.

    Parameters
    ----------
    name : {"jeandel-rao", "labbe-u19", "kari-14", "kari-culik-13"}
    window : Window, (x0, y0, width, height) or str
        The cells (``"X0,Y0,WxH"``: bottom-left cell, W columns, H rows; y grows upwards).
    seed : int, optional
        Which tiling of the plane: windows of one seed agree where they overlap.

    Returns
    -------
    (AperiodicWindowProblem, Solution)
        ``Solution.tiling[r, c]`` is the index (in the set's tiles) of the tile at
        ``window.cell(r, c)``.
    """
    problem = window_problem(name, window)
    return problem, solve(problem, method=method, seed=seed, progress=progress)


def _wang_numbers(problem: AperiodicWindowProblem, grid) -> np.ndarray:
    """The grid as numbers of the complete Wang set over the set's colours (eq. 2.1), the tiles
    the window pictures draw; a grid of the wrong shape or with an entry that is no tile is
    refused (there is nothing right to draw there)."""
    from tilesolve.model.tiles import wang_index

    g = np.asarray(grid)
    if g.shape != problem.shape:
        rows, cols = problem.shape
        raise InvalidProblem(f"nothing drawn: the grid has shape {list(g.shape)}, the window "
                             f"{problem.window.describe()} has {rows} rows of {cols} tiles")
    m = len(problem.tileset)
    if g.size and (int(g.min()) < 0 or int(g.max()) >= m):
        raise InvalidProblem(f"nothing drawn: the grid holds a number that is no tile of the set (0..{m - 1})")
    t = problem.tileset.tiles
    lut = wang_index(t[:, 0], t[:, 1], t[:, 2], t[:, 3], colors=problem.tileset.n_colors)
    return np.asarray(lut, dtype=np.min_scalar_type(int(lut.max())))[g]


def _draw(problem: AperiodicWindowProblem, sol: Solution, path, fmt: str, *, title: str | None = None,
          **_ignored) -> None:
    """PNG (each tile four triangles in its edge colours, streamed band by band:
    :func:`tilesolve.io.stochastic_png.write_window_png`) or SVG (the same under a caption that
    names the window)."""
    numbers = _wang_numbers(problem, sol.tiling)
    colors = problem.tileset.n_colors
    if fmt == "png":
        from tilesolve.io.stochastic_png import write_window_png

        write_window_png(path, numbers, "wang", colors,
                         caption=[title or f"{problem.describe()} ({sol.method}, seed {sol.seed})"])
        return
    from tilesolve.io.svg_packing import MAX_SVG_TILES, write_packing_svg

    if problem.n_cells > MAX_SVG_TILES:
        rows, cols = problem.shape
        raise InvalidProblem(f"a {cols}x{rows} window is too large for SVG (at most {MAX_SVG_TILES:,} tiles); "
                             "draw it as PNG")
    write_packing_svg(path, numbers, "wang", colors,
                      title=title or f"{problem.describe()} ({sol.method}, seed {sol.seed})")


FAMILY = register(Family(
    name="aperiodic-window",
    title="windows of tilings of the plane by aperiodic Wang tile sets, by their constructive routes",
    problem_type=AperiodicWindowProblem,
    routes=SOLVERS,
    auto=lambda problem: route_of(problem.name),
    verify=window_violations,
    codecs=(Codec(APERIODIC_WINDOW, VERSIONS, window_from_dict, window_to_dict),),
    draw=_draw,
    form=form(window_problem),
    route_help={
        "markov": "Jeandel-Rao and U19: the coding of a toral Z^2-rotation by a Markov partition (Labbé 2021)",
        "balanced": "Kari (14 tiles) and Kari-Culik (13 tiles): rows of balanced sequences (Kari, Culik 1996)",
    },
))
