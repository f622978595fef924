"""Inner loops of the linear brick Wang algorithm (see :mod:`tilesolve.constructive.brick`).

Conditions on a leg (§4.1) are pairs ``(kind, colour)``: ``EXACT`` (c), ``NOT`` (¬c),
``ANY`` (∗) and ``EMPTY`` (no colour; only reached from an empty input).
Leg colours live in an ``(n, 4)`` array, ``-1`` = not yet chosen.

Callers take the functions from ``KERNELS.pick(cells)``: plain Python on small boards,
numba-compiled on large ones, the same output on both (see :mod:`._jit`).
"""

from __future__ import annotations

import numpy as np

from tilesolve.constructive._jit import Kernels, kernel
from tilesolve.constructive._jit import rand32 as _rand
from tilesolve.constructive._jit import seed_state as _seed_state

EXACT, NOT, ANY, EMPTY = 0, 1, 2, 3


@kernel()
def four_cycle_at(nc, a, out):
    """A chordless 4-cycle a-b-d-c through cell ``a`` using two consecutive legs of ``a``
    (a 2x2 block: four corners). Writes the cells to ``out``; False when there is none.
    The legs are tried from W round to S (W and N first)."""
    for j in range(4):
        k = (j + 3) % 4
        b = nc[a, k]
        c = nc[a, (k + 1) % 4]
        if b < 0 or c < 0 or b == a or c == a or b == c:
            continue
        for kb in range(4):
            d = nc[b, kb]
            if d < 0 or d == a or d == b or d == c:
                continue
            hit = False
            for kc in range(4):
                if nc[c, kc] == d:
                    hit = True
            if not hit:
                continue
            good = True  # chordless: each cell has exactly two legs into {a, b, c, d}
            for v in (a, b, c, d):
                cnt = 0
                for kk in range(4):
                    w = nc[v, kk]
                    if w == a or w == b or w == c or w == d:
                        cnt += 1
                if cnt != 2:
                    good = False
            if good:
                out[0] = a
                out[1] = b
                out[2] = d
                out[3] = c
                return True
    return False


@kernel()
def _dfs(nc, nl, s, label, comp, order, m, parent_leg, stack, nxt, pref, legs):
    comp[s] = label
    order[m] = s
    m += 1
    top = 0
    stack[0] = s
    while top >= 0:
        v = stack[top]
        if nxt[v] >= 4:
            top -= 1
            continue
        k = pref[nxt[v]]
        nxt[v] += 1
        w = nc[v, k]
        if w >= 0:
            legs[label] += 1
        if w >= 0 and comp[w] < 0:
            comp[w] = label
            parent_leg[w] = nl[v, k]
            order[m] = w
            m += 1
            top += 1
            stack[top] = w
    return m


@kernel()
def components(nc, nl):
    """Components of G' by depth-first search, rooted at a 4-cycle where there is one.

    Returns ``(comp, order, parent_leg, starts, has_quad, is_tree)``: ``order`` lists the cells
    component by component in DFS preorder (a parent precedes its children),
    ``parent_leg[v]`` is v's leg towards its parent (-1 at a root), the cells of component
    ``i`` are ``order[starts[i]:starts[i+1]]``, and ``has_quad[i]`` says that its root
    lies on a chordless 4-cycle (:func:`four_cycle_at`); ``is_tree[i]`` that the component
    has one edge fewer than cells. Legs are tried in the order E, S,
    W, N, which on grids walks rows back and forth and keeps memory accesses local.
    """
    n = nc.shape[0]
    comp = np.full(n, -1, np.int64)
    order = np.empty(n, np.int64)
    parent_leg = np.full(n, -1, np.int64)
    stack = np.empty(n, np.int64)
    nxt = np.zeros(n, np.int64)
    pref = np.array([1, 2, 3, 0])  # E, S, W, N
    starts = np.zeros(n + 1, np.int64)
    hq = np.zeros(n, np.bool_)
    legs = np.zeros(n, np.int64)
    q = np.empty(4, np.int64)
    m = 0
    ncomp = 0
    for s in range(n):  # components with a 2x2 block, rooted in it
        if comp[s] >= 0 or not four_cycle_at(nc, s, q):
            continue
        m = _dfs(nc, nl, s, ncomp, comp, order, m, parent_leg, stack, nxt, pref, legs)
        hq[ncomp] = True
        ncomp += 1
        starts[ncomp] = m
    for s in range(n):  # the others
        if comp[s] >= 0:
            continue
        m = _dfs(nc, nl, s, ncomp, comp, order, m, parent_leg, stack, nxt, pref, legs)
        ncomp += 1
        starts[ncomp] = m
    st = starts[: ncomp + 1].copy()
    is_tree = legs[:ncomp] // 2 == st[1:] - st[:-1] - 1
    return comp, order, parent_leg, st, hq[:ncomp].copy(), is_tree


@kernel()
def dfs_tree(nc, nl, sources, allowed):
    """Depth-first spanning forest from ``sources`` over cells with ``allowed``.

    Returns ``(order, parent_leg)``: the reached non-source cells in preorder (every cell
    after its parent) and each one's leg towards its parent.
    """
    n = nc.shape[0]
    seen = np.zeros(n, np.bool_)
    parent_leg = np.full(n, -1, np.int64)
    order = np.empty(n, np.int64)
    stack = np.empty(n, np.int64)
    nxt = np.zeros(n, np.int64)
    pref = np.array([1, 2, 3, 0])  # E, S, W, N
    m = 0
    for s in sources:
        seen[s] = True
    for s in sources:
        top = 0
        stack[0] = s
        nxt[s] = 0
        while top >= 0:
            v = stack[top]
            if nxt[v] >= 4:
                top -= 1
                continue
            k = pref[nxt[v]]
            nxt[v] += 1
            w = nc[v, k]
            if w >= 0 and allowed[w] and not seen[w]:
                seen[w] = True
                parent_leg[w] = nl[v, k]
                order[m] = w
                m += 1
                top += 1
                stack[top] = w
    return order[:m].copy(), parent_leg


@kernel()
def quad_legs(nc, nl, roots):
    """Cycle arrays (cells, ins, outs, ptr) for the 4-cycles through ``roots``."""
    L = roots.shape[0]
    cells = np.empty(4 * L, np.int64)
    ins = np.empty(4 * L, np.int64)
    outs = np.empty(4 * L, np.int64)
    ptr = np.arange(L + 1) * 4
    q = np.empty(4, np.int64)
    for t in range(L):
        four_cycle_at(nc, roots[t], q)
        for i in range(4):
            a = q[i]
            b = q[(i + 1) % 4]
            for k in range(4):
                if nc[a, k] == b:
                    cells[4 * t + i] = a
                    outs[4 * t + i] = k
                    ins[4 * t + (i + 1) % 4] = nl[a, k]
                    break
    return cells, ins, outs, ptr


@kernel()
def _in_cond(c, kind, val):
    if kind == EXACT:
        return c == val
    if kind == NOT:
        return c != val
    return kind == ANY


@kernel()
def _meet_nonempty(k1, v1, k2, v2):
    """Do two conditions share a colour? (#C >= 3)"""
    if k1 == EMPTY or k2 == EMPTY:
        return False
    if k1 == EXACT:
        return _in_cond(v1, k2, v2)
    if k2 == EXACT:
        return _in_cond(v2, k1, v1)
    return True


@kernel()
def out_cond(kinds, vals, out):
    """The weakest condition on leg ``out`` given the other three (Figure 2, §4.1).

    A tile of W_B has ``c_p = c_q and c_out != c_o`` or ``c_p != c_q and c_out = c_o``
    (``o`` opposite ``out``, ``p``/``q`` the other pair); the result is exactly the set of
    colours of leg ``out`` in some tile meeting the three input conditions.
    """
    o = (out + 2) % 4
    p = (out + 1) % 4
    q = (out + 3) % 4
    if kinds[o] == EMPTY or kinds[p] == EMPTY or kinds[q] == EMPTY:
        return EMPTY, -1
    eq = _meet_nonempty(kinds[p], vals[p], kinds[q], vals[q])
    neq = not (kinds[p] == EXACT and kinds[q] == EXACT and vals[p] == vals[q])
    if eq and neq:
        return ANY, -1
    if eq:  # c_out != c_o
        if kinds[o] == EXACT:
            return NOT, vals[o]
        return ANY, -1
    return kinds[o], vals[o]  # neq only: c_out = c_o


@kernel()
def _pick(kind, val, avoid, C, r):
    if kind == EXACT:
        if val != avoid:
            return val
        return -1
    if kind == EMPTY:
        return -1
    for i in range(C):
        c = (r + i) % C
        if c != avoid and (kind == ANY or c != val):
            return c
    return -1


@kernel()
def _pick_common(k1, v1, k2, v2, C, r):
    if k1 == EXACT:
        return v1 if _in_cond(v1, k2, v2) else -1
    if k2 == EXACT:
        return v2 if _in_cond(v2, k1, v1) else -1
    if k1 == EMPTY or k2 == EMPTY:
        return -1
    for i in range(C):
        c = (r + i) % C
        if _in_cond(c, k1, v1) and _in_cond(c, k2, v2):
            return c
    return -1


@kernel()
def choose_tile(kinds, vals, C, r, first_mode, out):
    """Fill ``out`` with a brick tile meeting the four conditions; False when none exists."""
    for t in range(2):
        mode = first_mode if t == 0 else 1 - first_mode
        ep, eq = (3, 1) if mode == 0 else (0, 2)  # the equal pair: W, E (W_H) or N, S (W_V)
        up, uq = (0, 2) if mode == 0 else (3, 1)
        x = _pick_common(kinds[ep], vals[ep], kinds[eq], vals[eq], C, r)
        if x < 0:
            continue
        y = _pick(kinds[up], vals[up], -1, C, r)
        if y < 0:
            continue
        z = _pick(kinds[uq], vals[uq], y, C, r + 1)
        if z < 0:
            z = _pick(kinds[uq], vals[uq], -1, C, r)
            if z < 0:
                continue
            y = _pick(kinds[up], vals[up], z, C, r + 1)
            if y < 0:
                continue
        out[ep] = x
        out[eq] = x
        out[up] = y
        out[uq] = z
        return True
    return False


@kernel()
def _set(col, nc, nl, a, k, c):
    col[a, k] = c
    b = nc[a, k]
    if b >= 0:
        col[b, nl[a, k]] = c


@kernel()
def _leg_conds(col, a, kinds, vals):
    for k in range(4):
        if col[a, k] >= 0:
            kinds[k] = EXACT
            vals[k] = col[a, k]
        else:
            kinds[k] = ANY
            vals[k] = -1


@kernel()
def tile_outside(order, parent_leg, skip, nc, nl, col, C, seed):
    """Theorem 7 steps 2-3: tile ``order`` from its end (leaves first); each cell's parent
    leg is still free, so by the three-boundary condition a tile always exists.
    Returns the index of a cell that could not be tiled (a self-joined leg), or -1."""
    st = _seed_state(seed)
    kinds = np.empty(4, np.int64)
    vals = np.empty(4, np.int64)
    tile = np.empty(4, np.int64)
    for i in range(order.size - 1, -1, -1):
        a = order[i]
        if skip[a]:
            continue
        _leg_conds(col, a, kinds, vals)
        kinds[parent_leg[a]] = ANY
        vals[parent_leg[a]] = -1
        rr = _rand(st)
        if not choose_tile(kinds, vals, C, (rr >> 1) % C, rr & 1, tile):
            return a
        for k in range(4):  # a leg joined to another leg of the same cell
            if nc[a, k] == a and tile[k] != tile[nl[a, k]]:
                return a
        for k in range(4):
            _set(col, nc, nl, a, k, tile[k])
    return -1


@kernel()
def solve_cycle(cells, ins, outs, nc, nl, col, C, seed):
    """§4.3: tile a chordless cycle whose other legs are already fixed (or free boundary).

    Cell ``cells[i]`` meets ``cells[i+1]`` through its leg ``outs[i]`` (their leg
    ``ins[i+1]``). For each candidate colour ``x`` of the closing edge, conditions are
    propagated round the cycle; the first ``x`` that comes back allowed is tiled backwards.
    Colours not mentioned on the cycle are interchangeable, so trying the mentioned ones
    and one other is exhaustive. Returns True on success.
    """
    st = _seed_state(seed)
    L = cells.size
    kinds = np.empty(4, np.int64)
    vals = np.empty(4, np.int64)
    tile = np.empty(4, np.int64)
    ck = np.empty(L, np.int64)
    cv = np.empty(L, np.int64)
    mentioned = np.zeros(C, np.bool_)
    for i in range(L):
        for k in range(4):
            if k != ins[i] and k != outs[i] and col[cells[i], k] >= 0:
                mentioned[col[cells[i], k]] = True
    spare = True
    for x in range(C):
        if not mentioned[x]:
            if not spare:
                continue
            spare = False
        ok = True
        for i in range(L):
            a = cells[i]
            _leg_conds(col, a, kinds, vals)
            if i == 0:
                kinds[ins[0]] = EXACT
                vals[ins[0]] = x
            else:
                kinds[ins[i]] = ck[i - 1]
                vals[ins[i]] = cv[i - 1]
            kinds[outs[i]] = ANY
            vals[outs[i]] = -1
            if ins[i] == outs[i]:
                ok = False
                break
            kd, vl = out_cond(kinds, vals, outs[i])
            ck[i] = kd
            cv[i] = vl
            if kd == EMPTY:
                ok = False
                break
        if not ok or not _in_cond(x, ck[L - 1], cv[L - 1]):
            continue
        # tile backwards: the closing edge has colour x
        nxt = x
        for i in range(L - 1, -1, -1):
            a = cells[i]
            _leg_conds(col, a, kinds, vals)
            kinds[outs[i]] = EXACT
            vals[outs[i]] = nxt
            if i == 0:
                kinds[ins[0]] = EXACT
                vals[ins[0]] = x
            else:
                kinds[ins[i]] = ck[i - 1]
                vals[ins[i]] = cv[i - 1]
            rr = _rand(st)
            if not choose_tile(kinds, vals, C, (rr >> 1) % C, rr & 1, tile):
                return False  # cannot happen: the conditions were exact
            for k in range(4):
                _set(col, nc, nl, a, k, tile[k])
            nxt = tile[ins[i]]
        return True
    return False


@kernel()
def solve_cycles(cells, ins, outs, ptr, nc, nl, col, C, seed):
    """:func:`solve_cycle` on each cycle ``ptr[i]:ptr[i+1]``; the first that fails, or -1."""
    for i in range(ptr.size - 1):
        a, b = ptr[i], ptr[i + 1]
        if not solve_cycle(cells[a:b], ins[a:b], outs[a:b], nc, nl, col, C, seed + i):
            return i
    return -1


@kernel()
def solve_trees(order, parent_leg, is_tree, comp, nc, nl, col, C, seed, cond_k, cond_v):
    """§4.2 on every tree component (cells of ``order`` whose component has ``is_tree``).

    Bottom-up, each cell's output condition on its parent leg is inferred from its other
    legs (boundary colours and its children's conditions); at the root all four legs must
    admit a tile. Then top-down, tiles are chosen to meet the conditions.
    Returns the root of the first component whose conditions clash, or -1.
    """
    st = _seed_state(seed)
    kinds = np.empty(4, np.int64)
    vals = np.empty(4, np.int64)
    tile = np.empty(4, np.int64)
    n = order.size
    # bottom-up
    for i in range(n - 1, -1, -1):
        a = order[i]
        if not is_tree[comp[a]]:
            continue
        pl = parent_leg[a]
        for k in range(4):
            b = nc[a, k]
            if k == pl:
                kinds[k] = ANY
                vals[k] = -1
            elif b < 0:
                if col[a, k] >= 0:
                    kinds[k] = EXACT
                    vals[k] = col[a, k]
                else:
                    kinds[k] = ANY
                    vals[k] = -1
            else:
                kinds[k] = cond_k[b]
                vals[k] = cond_v[b]
        if pl >= 0:
            kd, vl = out_cond(kinds, vals, pl)
            cond_k[a] = kd
            cond_v[a] = vl
        else:
            if not choose_tile(kinds, vals, C, 0, 0, tile):
                return a
    # top-down
    for i in range(n):
        a = order[i]
        if not is_tree[comp[a]]:
            continue
        pl = parent_leg[a]
        for k in range(4):
            b = nc[a, k]
            if k == pl or b < 0:
                if col[a, k] >= 0:
                    kinds[k] = EXACT
                    vals[k] = col[a, k]
                else:
                    kinds[k] = ANY
                    vals[k] = -1
            else:
                kinds[k] = cond_k[b]
                vals[k] = cond_v[b]
        rr = _rand(st)
        if not choose_tile(kinds, vals, C, (rr >> 1) % C, rr & 1, tile):
            return a  # cannot happen after a successful bottom-up pass
        for k in range(4):
            _set(col, nc, nl, a, k, tile[k])
    return -1


#: Cells from which compiling pays: numba's import, set-up and cache load cost 0.8-1.5 s of
#: CPU on a loaded machine, the linear algorithm runs at about 35 us a cell interpreted (a
#: 100x100 rectangle in 0.4 s); ``benchmarks/bench_startup.py`` measured the crossover near
#: 40,000 cells (a 200x200 rectangle).
THRESHOLD = 40_000

#: The plain and compiled namespaces of this module.
KERNELS = Kernels(globals(), THRESHOLD)
