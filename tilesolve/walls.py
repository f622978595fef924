"""Brick walls without long lines (dappled paper §4): the home of the wall facade.

A brick wall is a brick Wang tiling (brick paper, Def. 9) of a rectangle with a free boundary
in which no horizontal line runs through more than ``max_h`` cells and no vertical one through
more than ``max_v``. The dappled paper (§4) builds one from an L-dappled tiling with
``T = {0, 1}`` (0 = W_H, a horizontal line crosses the cell; 1 = W_V) and
``L = {H_0^max_h, V_1^max_v}``: :func:`tilesolve.constructive.brick.wall_from_dappled` turns
the classes into leg colours. Walls are board problems (:mod:`tilesolve.board`): this module
provides the board family's ``wall`` route; the procedural walls of the stochastic-wall paper
will live here too.

Examples
--------
>>> from tilesolve.verify.board import board_violations
>>> p, s = brick_wall(6, 9, 2, seed=1)
>>> board_violations(s.tiling, p), s.method
([], 'wall')
"""

from __future__ import annotations

import time

from tilesolve.errors import MethodNotApplicable
from tilesolve.model.board import Board, BoardProblem, WangTileSet
from tilesolve.model.run import RunOptions
from tilesolve.model.solution import Solution, Status

__all__ = ["wall_problem", "is_free_wall", "wall_route", "brick_wall"]


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


def brick_wall(rows: int, cols: int, max_line: int, *, max_v: int | None = None, n_colors: int = 3,
               seed: int | None = None) -> tuple[BoardProblem, Solution]:
    """A verified brick wall: ``(problem, solution)`` (see the module docstring)."""
    from tilesolve.board import solve

    problem = wall_problem(rows, cols, max_line, max_v=max_v, n_colors=n_colors)
    return problem, solve(problem, method="wall", seed=seed)
