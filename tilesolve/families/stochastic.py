"""Stochastic Wang and corner tilings end to end (class notes ch. 3): the ``wang`` family.

A problem (:class:`~tilesolve.model.stochastic.StochasticProblem`) is a window of the
infinite plane; the routes are the notes' two algorithms, compiled in
:mod:`tilesolve.constructive.stochastic`; every window is checked by the shared grid-tiling
verifier :func:`tilesolve.verify.grid.grid_violations` against the colour table of its tile
set (not toroidally: a window is a piece of the plane).

Routes
------
``scanline``
    §3.2 (Cohen et al. 2003; Lagae and Dutré 2006): west to east, north to south, each tile
    matching the tile above and the tile to the left, its free colours a hash of its cell.
    Complete or compact sets. Windows with the same NW corner agree where they overlap;
    with a complete set any two windows do.
``direct``
    §3.3: each tile a function of hashes of the lattice around it, so the tile of a cell is
    the same in every window (random access). Complete sets and the sums Wang set
    (§3.3.2.2); the compact sets have none (§3.5).

``auto`` takes ``direct`` where it exists (random access) and ``scanline`` for compact sets.
The run's seed draws the hash tables: the same seed gives the same tiling.

Examples
--------
>>> from tilesolve.model.stochastic import StochasticProblem
>>> s = solve(StochasticProblem("corner", 3, window=(-5, 2, 6, 4)), seed=7)
>>> s.status.value, s.method, s.tiling.shape
('sat', 'direct', (4, 6))
>>> t = solve(StochasticProblem("corner", 3, window=(-3, 3, 2, 2)), seed=7).tiling
>>> bool((t == s.tiling[1:3, 2:4]).all())      # random access: the overlap agrees
True
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.family import Codec, Demo, Family, Field, Form, RunOptions, form_size, register
from tilesolve.family import solve as _solve
from tilesolve.io.stochastic_json import STOCHASTIC_TILING, VERSIONS
from tilesolve.model.solution import Solution, Status
from tilesolve.progress import Progress
from tilesolve.model.stochastic import StochasticProblem
from tilesolve.model.window import Window
from tilesolve.verify.dappled import Violation
from tilesolve.verify.grid import grid_violations

__all__ = ["FAMILY", "SOLVERS", "METHODS", "solve", "auto_method", "scanline", "direct", "stochastic_violations"]


def _route(method: str):
    """The route running the ``method`` algorithm of
    :func:`tilesolve.constructive.stochastic.stochastic_window` on a problem (compiled kernels
    load only when a route runs)."""

    def route(problem: StochasticProblem, run: RunOptions) -> Solution:
        from tilesolve.constructive.stochastic import stochastic_window

        t0 = time.perf_counter()
        w = problem.window
        grid = stochastic_window(problem.kind, method, (w.x0, w.y0, w.width, w.height), colors=problem.colors,
                                 seed=run.seed, variant=problem.variant, algorithm=problem.algorithm, hash=problem.hash)
        return Solution(Status.SAT, grid, method=method, seed=run.seed, time_s=time.perf_counter() - t0,
                        stats={"tiles": problem.n_cells, "set_tiles": problem.tiles.n_tiles}, window=w)

    route.__name__ = method
    return route


scanline = _route("scanline")
scanline.__doc__ = """Scanline stochastic tiling of the window (§3.2.1 Wang, §3.2.2 corner); complete or compact sets."""
direct = _route("direct")
direct.__doc__ = """Direct stochastic tiling of the window (§3.3.1 corner, §3.3.2 Wang); complete or sums sets."""

#: Routes by name (the CLI's ``--method`` choices are ``auto`` plus these).
SOLVERS = {"scanline": scanline, "direct": direct}
METHODS: tuple[str, ...] = ("auto",) + tuple(SOLVERS)


def auto_method(problem: StochasticProblem) -> str:
    """``direct`` (random access, §3.3) unless the set is compact, which only ``scanline`` tiles."""
    return "scanline" if problem.variant == "compact" else "direct"


def stochastic_violations(problem: StochasticProblem, grid) -> list[Violation]:
    """Every way ``grid`` fails to be a tiling of the problem's window with its tile set.

    The grid must have the window's shape; adjoining edges (Wang) or corners (corner tiles)
    must match and every tile must belong to the set (:func:`tilesolve.verify.grid.grid_violations`,
    not toroidal).
    """
    g = np.asarray(grid)
    if g.shape != problem.shape:
        rows, cols = problem.shape
        return [Violation("shape", f"the grid has shape {list(g.shape)}, the window {problem.window.describe()} "
                                   f"has {rows} rows of {cols} tiles")]
    ts = problem.tiles
    labels = None if problem.variant == "complete" else ts.indices
    return grid_violations(ts.table(), g, kind=problem.kind, labels=labels)


def solve(problem: StochasticProblem, *, method: str | Any = "auto", seed: int | None = None,
          time_limit: float | None = None, progress: Progress | bool = False) -> Solution:
    """Tile the problem's window and verify it (:func:`tilesolve.family.solve` with this family's routes).

    Parameters
    ----------
    problem : StochasticProblem
    method : {"auto", "scanline", "direct"} or callable
    seed : int, optional
        Draws the hash tables; the same seed gives the same tiling. Drawn and recorded when
        not given.

    Raises
    ------
    MethodNotApplicable
        ``direct`` on a compact set, ``scanline`` on the sums set (the message names the route
        that works).
    """
    if not isinstance(problem, StochasticProblem):
        raise InvalidProblem(f"expected a StochasticProblem, got {type(problem).__name__}")
    return _solve(problem, method, seed=seed, time_limit=time_limit, progress=progress)


# ----------------------------------------------------------------------------- the family record
def _read(doc: dict, source: str):
    from tilesolve.io.stochastic_json import stochastic_from_dict

    return stochastic_from_dict(doc, source)


def _write(problem: StochasticProblem, sol: Solution) -> dict:
    from tilesolve.io.stochastic_json import stochastic_to_dict

    return stochastic_to_dict(problem, sol)


def _draw(problem: StochasticProblem, sol: Solution, path, fmt: str, *, indices: bool = False,
          title: str | None = None, **_ignored) -> None:
    """SVG (each tile drawn with its edge or corner colours, the notes' palette of §2.7, under a
    caption that names the window's coordinates) or PNG (the same drawing, streamed band by band:
    :func:`tilesolve.io.stochastic_png.write_window_png`). A grid that is not the window's shape,
    or a cell that holds no tile number, is refused (there is nothing right to draw there)."""
    grid = np.asarray(sol.tiling)
    if grid.shape != problem.shape:
        rows, cols = problem.shape
        raise InvalidProblem(f"nothing drawn: the grid has shape {list(grid.shape)}, the window "
                             f"{problem.window.describe()} has {rows} rows of {cols} tiles")
    problem.tiles.check_numbers(sol.tiling)
    if fmt == "png":
        from tilesolve.io.stochastic_png import write_window_png

        write_window_png(path, sol.tiling, problem.kind, problem.colors,
                         caption=[title or f"{problem.describe()} ({sol.method}, seed {sol.seed})"])
        return
    from tilesolve.io.svg_packing import MAX_SVG_TILES, write_packing_svg

    if problem.n_cells > MAX_SVG_TILES:
        rows, cols = problem.shape
        raise InvalidProblem(f"a {cols}x{rows} window is too large for SVG (at most {MAX_SVG_TILES:,} tiles); "
                             "draw it as PNG")
    write_packing_svg(path, sol.tiling, problem.kind, problem.colors, indices=indices,
                      title=title or f"{problem.describe()} ({sol.method}, seed {sol.seed})")


DEMOS = (
    Demo("wang-scanline", "scanline stochastic Wang tiling with the compact set of Fig. 3.2 (C = 2)",
         lambda: StochasticProblem("wang", 2, (0, 0, 24, 16), "compact"), method="scanline"),
    Demo("corner-direct", "direct stochastic corner tiling (§3.3.1), C = 3, a window left of the origin",
         lambda: StochasticProblem("corner", 3, (-12, -8, 24, 16)), method="direct"),
)

def _form_problem(values, window) -> StochasticProblem:
    return StochasticProblem(values["kind"], values["colors"], window, values["set"], values["hash"],
                             values["algorithm"])


def _form_build(values) -> tuple[StochasticProblem, dict]:
    """The studio form's window (the ``tiling`` options)."""
    rows, cols = form_size(values["size"])
    return _form_problem(values, (values["x0"], values["y0"], cols, rows)), {}


def _form_command(values) -> tuple[list[str], dict[str, str]]:
    rows, cols = form_size(values["size"])
    return ["tiling", "--kind", values["kind"], "--set", values["set"], "--colors", str(values["colors"]),
            f"--region={values['x0']},{values['y0']},{cols}x{rows}", "--hash", values["hash"],
            "--algorithm", values["algorithm"]], {}


def _form_window(values, window: Window):
    """Any window of the plane (the ``direct`` route gives every window the same tiles)."""
    return _form_problem(values, window), "auto", {}


FORM = Form(
    fields=(
        Field("kind", "choice", "tiles", "corner", "Wang (edges) or corner tiles", choices=("wang", "corner"),
              option="--kind"),
        Field("set", "choice", "tile set", "complete", "complete (§2.7), compact (§3.2) or sums (§3.3.2.2)",
              choices=("complete", "compact", "sums"), option="--set"),
        Field("colors", "int", "colours C", 3, "number of colours", low=2, high=8, option="--colors"),
        Field("x0", "int", "window x0", 0, "west-most cell column", low=-(1 << 40), high=1 << 40, option="--region"),
        Field("y0", "int", "window y0", 0, "south-most cell row (y grows northwards)", low=-(1 << 40),
              high=1 << 40, option="--region"),
        Field("size", "size", "window (WxH)", "32x20", "W columns by H rows", high=1 << 22, option="--region"),
        Field("hash", "choice", "hash", "long", "lattice hash of the generators (§3.4)", choices=("long", "table"),
              option="--hash"),
        Field("algorithm", "choice", "direct algorithm", "edges", "complete Wang sets: hashes at the edges "
              "(§3.3.2.3) or two at the corners (§3.3.2.1)", choices=("edges", "two"), option="--algorithm",
              when=({"kind": ("wang",), "set": ("complete",)},)),
    ),
    build=_form_build,
    command=_form_command,
    time_limit=False,  # the command runs to its end (no --time-limit)
    window=_form_window,
)

FAMILY = register(Family(
    name="stochastic",
    title="stochastic Wang and corner tilings of windows of the plane, scanline and direct (class notes ch. 3)",
    problem_type=StochasticProblem,
    routes=SOLVERS,
    auto=auto_method,
    verify=stochastic_violations,
    codecs=(Codec(STOCHASTIC_TILING, VERSIONS, _read, _write),),
    draw=_draw,
    demos=DEMOS,
    commands=("tilesolve.cli.stochastic:tiling",),
    form=FORM,
    route_help={
        "scanline": "west to east, north to south, each tile a hashed choice among those that fit (§3.2)",
        "direct": "each tile from hashes of the lattice around it: random access (§3.3)",
    },
))
