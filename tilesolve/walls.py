"""Brick walls without long lines (dappled paper §4): the home of the wall facade.

A brick wall is a brick Wang tiling (brick paper, Def. 9) of a rectangle with a free boundary
in which no horizontal line runs through more than ``max_h`` cells and no vertical one through
more than ``max_v``. The dappled paper (§4) builds one from an L-dappled tiling with
``T = {0, 1}`` (0 = W_H, a horizontal line crosses the cell; 1 = W_V) and
``L = {H_0^max_h, V_1^max_v}``: :func:`tilesolve.constructive.brick.wall_from_dappled` turns
the classes into leg colours. Walls are board problems (:mod:`tilesolve.board`): this module
provides two routes of the board family:

``wall``
    the finite wall of the dappled paper (§4), from a dappled tiling of the whole rectangle;
``procedural``
    a window of the infinite procedural wall of Derouet-Jourdan, Salvati and Jonchier
    (004 §3-4, App. B; :func:`tilesolve.constructive.walls.wall_window`): every cell's tile is a
    function of its absolute coordinates and the seed, so two windows of the same seed agree
    on the cells they share. It needs one line limit ``n = max_h = max_v`` (004 §4.3).

Examples
--------
>>> from tilesolve.verify.board import board_violations
>>> p, s = brick_wall(6, 9, 2, seed=1)
>>> board_violations(s.tiling, p), s.method
([], 'wall')
>>> from tilesolve.family import solve
>>> q = wall_problem(4, 6, 3)
>>> s = solve(q, "procedural", seed=5, options={"origin": (-100, 40)})
>>> board_violations(s.tiling, q), s.method
([], 'procedural')
"""

from __future__ import annotations

import time

import numpy as np

from tilesolve.errors import InvalidProblem, MethodNotApplicable
from tilesolve.model.board import Board, BoardProblem, WangTileSet
from tilesolve.model.run import RunOptions
from tilesolve.model.solution import Solution, Status

__all__ = ["wall_problem", "is_free_wall", "wall_route", "procedural_route", "brick_wall"]


def wall_problem(rows: int, cols: int, max_line: int, *, max_v: int | None = None, n_colors: int = 3) -> BoardProblem:
    """The board problem of a ``rows x cols`` brick wall with lines of at most ``max_line``
    cells across and ``max_v`` (default ``max_line``) down."""
    return BoardProblem(Board.rect(rows, cols), WangTileSet.brick(n_colors), None, max_h=int(max_line),
                        max_v=int(max_line if max_v is None else max_v))


def is_free_wall(problem: BoardProblem) -> bool:
    """True when the ``wall`` route applies: brick tiles on a rectangle, every boundary leg
    free, both line limits set."""
    return (problem.board.kind == "rect" and problem.tileset.is_brick and problem.max_h is not None
            and problem.max_v is not None and bool((problem.boundary < 0).all()))


def wall_route(problem: BoardProblem, run: RunOptions) -> Solution:
    """Solve a free wall problem through a dappled tiling (dappled §4).

    The dappled problem goes through the dappled family's own pipeline (Algorithm 1 where it
    applies, SAT otherwise, e.g. for limit 1), so it is verified there too; its seed is the
    run's seed.
    """
    from tilesolve import dappled
    from tilesolve.constructive.brick import wall_from_dappled
    from tilesolve.model.dappled import DappledProblem, parse_condition

    if not is_free_wall(problem):
        raise MethodNotApplicable("the wall route needs brick tiles on a rectangle with a free boundary and "
                                  "both line limits; use method 'sat'")
    t0 = time.perf_counter()
    rows, cols = (int(v) + 1 for v in problem.board.labels.max(axis=0))
    dp = DappledProblem(rows, cols, 2, (parse_condition(f"H0={problem.max_h}"), parse_condition(f"V1={problem.max_v}")))
    ds = dappled.solve(dp, seed=run.seed, time_limit=run.time_limit)
    notes = tuple(f"dappled: {n}" for n in ds.notes) + (f"dappled classes by {ds.method!r}",)
    if not ds.status.has_tiling:
        return Solution(ds.status, None, "wall", ds.solver, run.seed, time.perf_counter() - t0, reason=ds.reason,
                        notes=notes)
    tiling = wall_from_dappled(ds.tiling, problem.n_colors, seed=run.seed)
    return Solution(Status.SAT, tiling, "wall", ds.solver, run.seed, time.perf_counter() - t0, notes=notes)


def _origin(value) -> tuple[int, int]:
    """The ``origin`` option: two integers ``(x0, y0)``."""
    try:
        x0, y0 = value
    except (TypeError, ValueError):
        raise InvalidProblem(f"the wall's origin must be two integers (x0, y0), got {value!r}") from None
    for v in (x0, y0):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)):
            raise InvalidProblem(f"the wall's origin must be two integers (x0, y0), got {value!r}")
    return int(x0), int(y0)


def procedural_route(problem: BoardProblem, run: RunOptions) -> Solution:
    """A window of the infinite procedural brick wall (004 §3-4, App. B).

    The tiles come from :func:`tilesolve.constructive.walls.wall_window`: 2x2 blocks whose
    outer edges are hashes of their coordinates, filled by the base-case solver of App. B,
    with procedural dappling (§4.3) so that no line runs through more than ``n`` bricks.
    ``W`` of the paper's tiles (§3.1) is the brick set ``W_B`` of ``problem.n_colors >= 3``
    colours.

    Parameters
    ----------
    problem : BoardProblem
        Brick tiles on a ``rows x cols`` rectangle, free boundary, ``max_h == max_v == n``.
    run : RunOptions
        ``run.seed`` seeds the hashes; ``run.option("origin", (0, 0))`` is the window's
        bottom-left cell ``(x0, y0)`` in the paper's coordinates (``i`` east, ``j`` north):
        board cell ``(r, c)`` is wall cell ``(x0 + c, y0 + rows - 1 - r)``.

    Returns
    -------
    Solution
        ``sat`` with the ``(rows * cols, 4)`` int8 leg colours (W, N, E, S) of the board's
        cells, row-major; a note names the window.

    Raises
    ------
    MethodNotApplicable
        The problem is not a free brick wall with one line limit (names ``wall`` or ``sat``).
    """
    from tilesolve.constructive.walls import wall_window

    if not is_free_wall(problem):
        raise MethodNotApplicable("the procedural route needs brick tiles on a rectangle with a free boundary "
                                  "and a line limit; use method 'sat'")
    if problem.max_h != problem.max_v:
        raise MethodNotApplicable(f"the procedural route limits lines to one n in both directions (004 §4.3), "
                                  f"got max_h {problem.max_h} and max_v {problem.max_v}; use method 'wall' or 'sat'")
    x0, y0 = _origin(run.option("origin", (0, 0)))
    t0 = time.perf_counter()
    rows, cols = (int(v) + 1 for v in problem.board.labels.max(axis=0))
    legs = wall_window(x0, y0, cols, rows, colors=problem.n_colors, max_line=problem.max_h, seed=run.seed)
    note = (f"window x {x0}..{x0 + cols - 1}, y {y0}..{y0 + rows - 1} (y grows upwards) "
            f"of the infinite wall of seed {run.seed}")
    return Solution(Status.SAT, legs.reshape(rows * cols, 4), "procedural", None, run.seed,
                    time.perf_counter() - t0, notes=(note,))


def brick_wall(rows: int, cols: int, max_line: int, *, max_v: int | None = None, n_colors: int = 3,
               seed: int | None = None) -> tuple[BoardProblem, Solution]:
    """A verified brick wall: ``(problem, solution)`` (see the module docstring)."""
    from tilesolve.board import solve

    problem = wall_problem(rows, cols, max_line, max_v=max_v, n_colors=n_colors)
    return problem, solve(problem, method="wall", seed=seed)
