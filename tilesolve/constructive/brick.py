"""The linear algorithm for brick Wang tiling (Derouet-Jourdan, Kaji, Mizoguchi 2016, §4).

For each connected component of G' (the cells and the edges between them):

1. **Cycle detection.** A depth-first search per component looks for a chordless cycle:
   first a 2x2 block of cells (a 4-cycle with four corners), which then roots the search;
   else the cycle closed by a non-tree edge, shortened along its chords until none is left.
2. **Tiling outside the cycle** (Theorem 7, steps 1-3). The cells outside the cycle are
   tiled leaves first along a depth-first tree rooted at the cycle (the wall of
   ``G|T\\U``): every cell still has its leg towards the root free when it is tiled, and
   W_B satisfies the three-boundary condition (Def. 6), so a tile always exists.
3. **The cycle solver** (§4.3). With all other legs fixed, conditions (c), (¬c), (∗) are
   propagated round the cycle from each candidate colour of one edge; a candidate that
   comes back allowed is tiled backwards. By Lemma 10 this succeeds on planar grid
   boards, and by Remark 11 on any board when the cycle has a positive even number of
   corners.
4. **The tree solver** (§4.1-4.2) when the component has no cycle: output conditions are
   inferred bottom-up (Figure 2) and checked at the root, which *decides* solvability;
   a clash is reported with the root cell. Then tiles are chosen top-down.

Every step touches each cell a bounded number of times, so the whole is linear in the
number of cells. On boards the paper does not cover (a cycle with an odd number of
corners, or none, as round a Möbius strip or a narrow torus; cells joined to themselves),
and the cycle solver fails, the algorithm raises :class:`~tilesolve.errors.MethodNotApplicable` saying why, and
:func:`tilesolve.families.board.solve` routes the problem to the SAT solver.

Examples
--------
>>> from tilesolve.model.board import Board, BoardProblem, WangTileSet
>>> p = BoardProblem(Board.rect(7, 5), WangTileSet.brick(3), [2] * 24)
>>> solve_linear(p, seed=0).status.value
'sat'
"""

from __future__ import annotations

import time

import numpy as np

from tilesolve._random import rng_from_seed
from tilesolve.errors import InternalError, MethodNotApplicable
from tilesolve.model.board import LEG_NAMES, BoardProblem
from tilesolve.model.solution import Solution, Status

__all__ = ["solve_linear", "find_cycle", "cycle_corners", "wall_from_dappled", "compile_kernels"]


def compile_kernels() -> None:
    """Load the numba-compiled kernels of the linear algorithm now (a long-lived process, such
    as the studio's server, then runs every board compiled, not only those above the one-shot
    threshold of :mod:`tilesolve.constructive._jit`)."""
    from tilesolve.constructive._brick_kernels import KERNELS

    KERNELS.compiled()


def cycle_corners(nbr_cell: np.ndarray, ins: np.ndarray, outs: np.ndarray) -> int:
    """Number of corner cells (§3): cells whose two cycle legs are consecutive."""
    d = (np.asarray(outs) - np.asarray(ins)) % 4
    return int(((d == 1) | (d == 3)).sum())


def _chordless(nc: np.ndarray, nl: np.ndarray, cells, ins, outs, max_rounds: int = 10_000):
    """Shorten a cycle along its chords until it has none; None if that is impossible."""
    cells, ins, outs = list(cells), list(ins), list(outs)
    for _ in range(max_rounds):
        L = len(cells)
        pos = {c: i for i, c in enumerate(cells)}
        chord = None
        for i, a in enumerate(cells):
            for k in range(4):
                if k == ins[i] or k == outs[i]:
                    continue
                b = int(nc[a, k])
                if b in pos:
                    chord = (i, k, pos[b])
                    break
            if chord:
                break
        if chord is None:
            return np.array(cells, np.int64), np.array(ins, np.int64), np.array(outs, np.int64)
        i, k, j = chord
        a = cells[i]
        if j == i:  # a leg joined to another leg of the same cell: a 1-cycle
            cells, ins, outs = [a], [int(nl[a, k])], [k]
            continue
        fwd = (i - j) % L + 1  # a -k-> cells[j] -> ... -> cells[i] = a, following the cycle
        bwd = (j - i) % L + 1  # a -k-> cells[j] -> ... backwards ... -> a
        if min(fwd, bwd) >= L:
            return None
        if fwd <= bwd:
            idx = [(j + t) % L for t in range(fwd - 1)]
            new_cells = [cells[t] for t in idx]
            new_ins = [int(nl[a, k])] + [ins[t] for t in idx[1:]]
            new_outs = [outs[t] for t in idx]
            # finally a itself: in from its predecessor on the cycle, out through the chord
            new_cells.append(a)
            new_ins.append(ins[i])
            new_outs.append(k)
        else:
            idx = [(j - t) % L for t in range(bwd - 1)]
            new_cells = [cells[t] for t in idx]
            new_ins = [int(nl[a, k])] + [outs[t] for t in idx[1:]]
            new_outs = [ins[t] for t in idx]
            new_cells.append(a)
            new_ins.append(outs[i])
            new_outs.append(k)
        cells, ins, outs = new_cells, new_ins, new_outs
    return None


def find_cycle(board, component_cells: np.ndarray, order: np.ndarray, parent_leg: np.ndarray):
    """A chordless cycle of one component from a non-tree edge of its DFS tree, or None.

    Returns ``(cells, ins, outs)`` with ``cells[i]`` leaving through leg ``outs[i]`` into
    leg ``ins[i+1]`` of the next cell.
    """
    nc, nl = board.nbr_cell, board.nbr_leg
    cset = component_cells
    depth = {}
    parent = {}
    for v in order:
        v = int(v)
        pl = int(parent_leg[v])
        if pl < 0:
            depth[v], parent[v] = 0, -1
        else:
            p = int(nc[v, pl])
            parent[v], depth[v] = p, depth[p] + 1
    for v in cset:
        v = int(v)
        for k in range(4):
            w = int(nc[v, k])
            if w < 0:
                continue
            tree_edge = (k == parent_leg[v]) or (int(parent_leg[w]) == int(nl[v, k]) and parent.get(w) == v)
            if tree_edge:
                continue
            if w == v:
                cyc = ([v], [int(nl[v, k])], [k])
            else:
                # path v .. lca .. w through the tree, then the edge w -> v is ... v -k-> w
                pa, pb = [v], [w]
                x, y = v, w
                while depth[x] > depth[y]:
                    x = parent[x]
                    pa.append(x)
                while depth[y] > depth[x]:
                    y = parent[y]
                    pb.append(y)
                while x != y:
                    x, y = parent[x], parent[y]
                    pa.append(x)
                    pb.append(y)
                # walk: w ... lca ... v, then v -k-> w closes it
                cells = pb + pa[::-1][1:]
                L = len(cells)
                ins = np.empty(L, np.int64)
                outs = np.empty(L, np.int64)
                for t in range(L - 1):
                    a, b = cells[t], cells[t + 1]
                    # tree edge between a and b: the child's parent leg
                    if parent.get(a) == b:
                        outs[t] = parent_leg[a]
                        ins[t + 1] = nl[a, parent_leg[a]]
                    else:
                        ins[t + 1] = parent_leg[b]
                        outs[t] = nl[b, parent_leg[b]]
                outs[L - 1] = k
                ins[0] = nl[v, k]
                cyc = (cells, list(ins), list(outs))
            res = _chordless(nc, nl, *cyc)
            if res is not None:
                return res
    return None


def solve_linear(problem: BoardProblem, *, seed=None) -> Solution:
    """Decide and solve a brick Wang tiling problem in linear time (§4).

    Parameters
    ----------
    problem : BoardProblem
        Brick Wang tiles (Def. 9), any board, boundary colours fixed or free; no
        line-length limits (those go to the SAT route).
    seed : int, optional
        Seeds the free choices (which tile among several), so walls look random.

    Returns
    -------
    Solution
        ``sat`` with the ``(n_cells, 4)`` leg colours, or ``unsat`` when a tree component's
        conditions clash (``reason`` names the cell; ``stats["clash_cell"]`` its label).

    Raises
    ------
    MethodNotApplicable
        Not brick tiles, line limits, or a non-planar board where the cycle solver fails
        (Remark 11 does not apply); the message says why.
    """
    from tilesolve.constructive._brick_kernels import KERNELS

    t0 = time.perf_counter()
    K = KERNELS.pick(problem.board.n_cells)
    if not problem.tileset.is_brick:
        raise MethodNotApplicable("the linear algorithm is for brick Wang tiles (Def. 9); use method 'sat'")
    if problem.has_line_limits:
        raise MethodNotApplicable("the linear algorithm does not limit line lengths; use method 'sat'")
    rng = rng_from_seed(seed)
    ks = [int(s) for s in rng.integers(0, 2**31 - 1, size=3)]
    board = problem.board
    nc, nl = board.nbr_cell, board.nbr_leg
    n = board.n_cells
    C = problem.n_colors
    col = np.full((n, 4), -1, np.int64)
    wa, wl = np.nonzero(nc < 0)
    col[wa, wl] = problem.boundary[nl[wa, wl]]
    comp, order, parent_leg, starts, has_quad, is_tree = K.components(nc, nl)
    ncomp = starts.size - 1
    # 1. cycles: a 2x2 block through the DFS root where there is one (then the component's
    # DFS tree is already rooted on its cycle), else a chordless cycle found in Python
    roots = order[starts[:-1][has_quad]]
    cells4, ins4, outs4, ptr4 = K.quad_legs(nc, nl, roots)
    others = []
    for ci in np.flatnonzero(~is_tree & ~has_quad):
        comp_order = order[starts[ci]:starts[ci + 1]]
        cyc = find_cycle(board, comp_order, comp_order, parent_leg)
        if cyc is None:
            a = int(comp_order[0])
            raise MethodNotApplicable(
                f"the component of cell {board.labels[a].tolist()} has cycles but none without chords "
                "(cells joined to themselves or twice); the linear algorithm does not cover it"
            )
        others.append(cyc)
    stats = {"components": int(ncomp), "trees": int(is_tree.sum()), "cycles": int(roots.size) + len(others)}
    in_cycle = np.zeros(n, bool)
    in_cycle[cells4] = True
    # 2.-3. the cells outside the cycles, leaves first
    quad_comp = has_quad[comp]
    bad = K.tile_outside(order, parent_leg, in_cycle | ~quad_comp, nc, nl, col, C, ks[0])
    if others:
        oc = np.concatenate([c[0] for c in others])
        in_cycle[oc] = True
        allowed = ~is_tree[comp] & ~quad_comp
        o_order, o_parent = K.dfs_tree(nc, nl, oc, allowed)
        bad2 = K.tile_outside(o_order, o_parent, in_cycle, nc, nl, col, C, ks[0] + 1)
        bad = bad if bad >= 0 else bad2
    if bad >= 0:
        raise MethodNotApplicable(
            f"cell {board.labels[bad].tolist()} is joined to itself; the linear algorithm covers "
            "boards without self-joined cells"
        )
    # 4. the cycles (§4.3)
    if others:
        cells = np.concatenate([cells4] + [c[0] for c in others])
        ins = np.concatenate([ins4] + [c[1] for c in others])
        outs = np.concatenate([outs4] + [c[2] for c in others])
        ptr = np.concatenate([[0], np.cumsum([4] * roots.size + [len(c[0]) for c in others])]).astype(np.int64)
    else:
        cells, ins, outs, ptr = cells4, ins4, outs4, ptr4
    failed = K.solve_cycles(cells, ins, outs, ptr, nc, nl, col, C, ks[1])
    if failed >= 0:
        a, b = ptr[failed], ptr[failed + 1]
        corners = cycle_corners(nc, ins[a:b], outs[a:b])
        raise MethodNotApplicable(
            f"the cycle through cell {board.labels[cells[a]].tolist()} ({b - a} cells, {corners} "
            "corners) could not be tiled after the cells around it: the board is not a planar grid "
            "and Remark 11 needs a positive even number of corners"
        )
    if is_tree.any():
        cond_k = np.full(n, K.ANY, np.int64)
        cond_v = np.full(n, -1, np.int64)
        clash = K.solve_trees(order, parent_leg, is_tree, comp, nc, nl, col, C, ks[2], cond_k, cond_v)
        if clash >= 0:
            lab = board.labels[clash].tolist()
            conds = []
            for k in range(4):
                b = int(nc[clash, k])
                if b < 0:
                    c = int(col[clash, k])
                    conds.append(f"{LEG_NAMES[k]}=({c})" if c >= 0 else f"{LEG_NAMES[k]}=(*)")
                else:
                    kind, v = int(cond_k[b]), int(cond_v[b])
                    conds.append(f"{LEG_NAMES[k]}=" + ("(%d)" % v if kind == K.EXACT else
                                                        "(¬%d)" % v if kind == K.NOT else "(*)"))
            stats["clash_cell"] = lab
            return Solution(
                Status.UNSAT, None, "linear", None, seed, time.perf_counter() - t0,
                reason=(f"the tree of cells containing {lab} cannot be tiled: the conditions propagated "
                        f"to cell {lab} clash ({', '.join(conds)}; §4.2 tree solver)"),
                stats=stats,
            )
    if (col < 0).any():  # pragma: no cover - every leg is coloured above
        raise InternalError("the linear algorithm left legs uncoloured")
    return Solution(Status.SAT, col, "linear", None, seed, time.perf_counter() - t0, stats=stats)


def wall_from_dappled(classes, n_colors: int = 3, *, seed=None) -> np.ndarray:
    """Turn a {W_H, W_V} tiling into a brick Wang tiling of the rectangle (dappled paper §4).

    ``classes[r, c]`` is 0 for W_H (``c1 = c3``: a horizontal line crosses the cell) and 1
    for W_V (``c2 = c4``). Cells are visited left to right, top to bottom: the W and N
    colours are forced by the neighbours already placed (or drawn at random on the free
    boundary); a W_H cell copies W to E and draws S != N at random, a W_V cell copies N to
    S and draws E != W. Each horizontal chain depends only on its row and each vertical
    chain only on its column, so both are done a column (row) at a time with numpy.

    Returns
    -------
    numpy.ndarray
        ``(rows * cols, 4)`` leg colours (N, E, S, W) of :meth:`Board.rect` cells.

    Examples
    --------
    >>> t = wall_from_dappled([[0, 1], [1, 0]], 3, seed=0)
    >>> bool(((t[:, 0] == t[:, 2]) != (t[:, 1] == t[:, 3])).all())
    True
    """
    g = np.asarray(classes)
    if g.ndim != 2 or not np.isin(g, (0, 1)).all():
        from tilesolve.errors import InvalidProblem

        raise InvalidProblem("a wall needs a 2-D tiling of classes 0 (W_H) and 1 (W_V)")
    if n_colors < 3:
        from tilesolve.errors import InvalidProblem

        raise InvalidProblem(f"brick Wang tiles need #C >= 3 colours (Def. 9), got {n_colors}")
    rng = rng_from_seed(seed)
    rows, cols = g.shape
    h = g == 0
    west = np.empty((rows, cols), np.int64)
    east = np.empty((rows, cols), np.int64)
    cur = rng.integers(0, n_colors, size=rows)
    for c in range(cols):
        west[:, c] = cur
        step = rng.integers(1, n_colors, size=rows)
        cur = np.where(h[:, c], cur, (cur + step) % n_colors)
        east[:, c] = cur
    north = np.empty((rows, cols), np.int64)
    south = np.empty((rows, cols), np.int64)
    cur = rng.integers(0, n_colors, size=cols)
    for r in range(rows):
        north[r] = cur
        step = rng.integers(1, n_colors, size=cols)
        cur = np.where(~h[r], cur, (cur + step) % n_colors)
        south[r] = cur
    return np.stack([north.ravel(), east.ravel(), south.ravel(), west.ravel()], axis=1)
