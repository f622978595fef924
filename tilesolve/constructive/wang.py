"""Theorem 7 of the brick paper: any three-boundary tile set, given a core solver.

Derouet-Jourdan, Kaji, Mizoguchi, *A linear algorithm for brick Wang tiling* (2016),
Theorem 7: if ``W`` satisfies the three-boundary condition (Def. 6) and the restriction
``G|U`` (Def. 4) is solvable for every boundary, then so is ``G``. The proof is an
algorithm: take a spanning tree of ``G|T\\U`` rooted at the wall (which absorbs ``U``),
tile it leaves first — each cell still has its leg towards the root free, so a tile
exists whatever its other legs carry — and then solve ``G|U`` with the boundary colours
this induces, with any *core solver* (by default the SAT route).

If the core turns out unsolvable for the induced boundary, ``U`` was not a core that is
solvable for every boundary, and the answer is ``unknown`` (never ``unsat``: other
choices outside ``U`` might have worked).

Examples
--------
>>> from tilesolve.model.board import Board, BoardProblem, WangTileSet
>>> p = BoardProblem(Board.rect(6, 6), WangTileSet.brick(3), [0] * 24)
>>> from tilesolve.families import board  # the board family passes its SAT route as the core solver
>>> board.solve(p, method='theorem7', seed=1).status.value
'sat'
"""

from __future__ import annotations

import time
from typing import Callable

import numpy as np

from tilesolve._random import rng_from_seed
from tilesolve.errors import InvalidProblem, MethodNotApplicable
from tilesolve.model.board import BoardProblem
from tilesolve.model.run import RunOptions
from tilesolve.model.solution import Solution, Status

__all__ = ["theorem7_solve", "default_core"]


def default_core(problem: BoardProblem) -> np.ndarray:
    """Cells of ``U``: a chordless 2x2 block of cells in each component of G' (a cycle
    with four corners, which Lemma 10 / Remark 11 make a core for brick tiles), or the
    component's first cell where there is none."""
    from tilesolve.constructive._brick_kernels import KERNELS

    K = KERNELS.pick(problem.board.n_cells)
    nc, nl = problem.board.nbr_cell, problem.board.nbr_leg
    comp, order, parent_leg, starts, has_quad, is_tree = K.components(nc, nl)
    core = np.zeros(problem.board.n_cells, bool)
    q = np.empty(4, np.int64)
    for i in range(starts.size - 1):
        root = int(order[starts[i]])
        if has_quad[i] and K.four_cycle_at(nc, root, q):
            core[q] = True
        else:
            core[root] = True
    return core


def theorem7_solve(problem: BoardProblem, run: RunOptions, core=None, *,
                   core_solver: Callable[[BoardProblem, RunOptions], Solution]) -> Solution:
    """Solve a tiling problem by Theorem 7's strategy.

    Parameters
    ----------
    problem : BoardProblem
        Its tile set must satisfy the three-boundary condition (Def. 6).
    run : RunOptions
        The run: its seed draws the tiles outside the core; the core solver gets the run as it
        is (its deadline included).
    core : array-like of bool or int, optional
        The cells of ``U`` (a mask or indices); default :func:`default_core`.
    core_solver : callable
        A route, ``core_solver(subproblem, run) -> Solution``, for ``G|U`` (the board family
        passes its SAT route; constructive code never calls a solver itself).

    Returns
    -------
    Solution
        ``sat`` with all leg colours, or the core solver's ``unknown``; ``unknown`` too when
        the core is unsolvable for the induced boundary.
    """
    t0 = time.perf_counter()
    ts = problem.tileset
    if not ts.three_boundary():
        raise MethodNotApplicable("Theorem 7 needs a tile set with the three-boundary condition (Def. 6); use 'sat'")
    if problem.has_line_limits:
        raise MethodNotApplicable("Theorem 7 does not limit line lengths; use method 'sat'")
    board = problem.board
    n = board.n_cells
    nc, nl = board.nbr_cell, board.nbr_leg
    if core is None:
        keep = default_core(problem)
    else:
        keep = np.asarray(core)
        if keep.dtype != bool:
            m = np.zeros(n, bool)
            m[keep.astype(np.int64)] = True
            keep = m
        if keep.shape != (n,):
            raise InvalidProblem("the core must be a mask over cells or a list of cell indices")
    seed = run.seed
    rng = rng_from_seed(seed)
    col = np.full((n, 4), -1, np.int64)
    wa, wl = np.nonzero(nc < 0)
    col[wa, wl] = problem.boundary[nl[wa, wl]]
    # spanning forest of the cells outside U, rooted at U (the wall of G|T\U)
    from tilesolve.constructive._brick_kernels import KERNELS

    K = KERNELS.pick(n)
    sources = np.flatnonzero(keep)
    order, parent_leg = K.dfs_tree(nc, nl, sources, ~keep)
    reached = np.zeros(n, bool)
    reached[order] = True
    stray = ~keep & ~reached
    if stray.any():  # components without a core cell: give each one its first cell as core
        keep = keep.copy()
        for a in np.flatnonzero(stray):
            if not reached[a] and not keep[a]:
                keep[a] = True
                o2, p2 = K.dfs_tree(nc, nl, np.array([a]), ~keep)
                reached[o2] = True
                parent_leg[o2] = p2[o2]
                order = np.concatenate([order, o2])
    tiles = ts.tiles
    for a in order[::-1]:
        a = int(a)
        pl = int(parent_leg[a])
        ok = np.ones(len(tiles), bool)
        for k in range(4):
            if k != pl and col[a, k] >= 0:
                ok &= tiles[:, k] == col[a, k]
            if nc[a, k] == a and k < nl[a, k]:  # a leg joined to the same cell
                ok &= tiles[:, k] == tiles[:, nl[a, k]]
        cand = np.flatnonzero(ok)
        if cand.size == 0:
            raise MethodNotApplicable(
                f"cell {board.labels[a].tolist()} could not be tiled (a leg joined to the same cell); use 'sat'"
            )
        t = tiles[cand[int(rng.integers(cand.size))]]
        for k in range(4):
            col[a, k] = t[k]
            b = nc[a, k]
            if b >= 0:
                col[b, nl[a, k]] = t[k]
    # the core G|U with the induced boundary
    sub = board.restrict(keep)
    idx = np.flatnonzero(keep)
    sa, sl = np.nonzero(sub.nbr_cell < 0)
    beta = np.full(sub.n_boundary, -1, np.int64)
    beta[sub.nbr_leg[sa, sl]] = col[idx[sa], sl]
    subproblem = BoardProblem(sub, ts, beta)
    cs = core_solver(subproblem, run)
    stats = {"core_cells": int(keep.sum()), "core_method": cs.method}
    if not cs.status.has_tiling:
        reason = cs.reason if cs.status is Status.UNKNOWN else (
            f"the core G|U ({int(keep.sum())} cells) has no tiling for the boundary induced outside it, so it is "
            "not solvable for every boundary as Theorem 7 requires; other choices outside U might work")
        return Solution(Status.UNKNOWN, None, "theorem7", cs.solver, seed, time.perf_counter() - t0,
                        reason=reason, stats=stats)
    col[idx] = np.asarray(cs.tiling)
    return Solution(Status.SAT, col, "theorem7", cs.solver, seed, time.perf_counter() - t0, stats=stats)
