"""Hot loops of the dappled constructions (private; see ``dappled.py``).

Coordinates are ``g[row, col]``; the paper's ``f(i, j)`` is ``g[j, i]``. All kernels work in
place on an ``int8`` tiling and visit cells by weight ``row + col`` (anti-diagonals), as the
dappled paper's Algorithms 1 and 2 do.

Run bookkeeping
---------------
The paper's ``Violate`` scans back ``p`` cells; the paper itself suggests "book-keeping the
numbers of consecutive tiles of smaller weight" (§2). We keep, for the last three
anti-diagonals only, the horizontal run (going left) and the vertical run (going up) of equal
tiles ending at each cell, indexed by row: ``H[d % 3, r]`` is the run of cell ``[r, d - r]``.
The left and upper neighbours of a cell lie on the previous diagonal, so one look-up each
gives its runs. Step (II) rewrites a cell of the previous diagonal; its runs are recomputed
from diagonal ``d - 2`` and so are those of the at most one already-visited cell of diagonal
``d`` that depends on it. Memory: ``O(rows)`` besides the tiling.
"""

from __future__ import annotations

import numpy as np

from tilesolve.constructive._jit import Kernels, kernel, rand32, seed_state, u32

__all__ = ["alg1_kernel", "cyclic_kernel", "greedy_kernel", "KERNELS"]

#: Stands for "no limit" inside the cyclic kernel.
_NONE = 1 << 30


@kernel(nogil=True)
def alg1_kernel(g, P, Q, col_order):
    """Algorithm 1 of the dappled paper, in place on ``g`` (int8, values 0/1).

    ``P[t, r, c]`` / ``Q[t, r, c]`` are the H / V limits of tile ``t`` for runs ending at
    ``[r, c]`` (0 = unlimited, otherwise >= 2). ``col_order`` visits a diagonal by increasing
    column instead of the paper's increasing row. Returns the number of step-(II) surgeries
    that would have reached outside the grid (always 0 when every limit is >= 2).
    """
    R, C = g.shape
    Hr = np.zeros((3, R), np.int32)
    Vr = np.zeros((3, R), np.int32)
    bad = 0
    for d in range(R + C - 1):
        k = d % 3
        k1 = (d + 2) % 3  # diagonal d - 1
        k2 = (d + 1) % 3  # diagonal d - 2
        rlo = max(0, d - C + 1)
        rhi = min(d, R - 1)
        for idx in range(rhi - rlo + 1):
            r = rhi - idx if col_order else rlo + idx
            c = d - r
            t = g[r, c]
            # Branch-free run updates: the neighbours' equality is data dependent, and a
            # mispredicted branch costs more than the select (about 2x on random input).
            left = g[r, c - 1] if c > 0 else -1
            up = g[r - 1, c] if r > 0 else -1
            hp = Hr[k1, r]
            vp = Vr[k1, r - 1] if r > 0 else 0
            h = 1 + (hp if left == t else 0)
            v = 1 + (vp if up == t else 0)
            # limit 0 = unlimited: as uint32, 0 - 1 is the largest value and never < run - 1
            if (u32(P[t, r, c] - 1) < u32(h - 1)) | (u32(Q[t, r, c] - 1) < u32(v - 1)):
                # step (I): flip
                t = 1 - t
                g[r, c] = t
                h = 1 + (hp if left == t else 0)
                v = 1 + (vp if up == t else 0)
                if (u32(P[t, r, c] - 1) < u32(h - 1)) | (u32(Q[t, r, c] - 1) < u32(v - 1)):
                    if r == 0 or c == 0:
                        bad += 1
                    else:
                        # step (II): g(i,j) <- g(i-1,j-1); g(i-1,j), g(i,j-1) <- 1 - g(i,j)
                        t = g[r - 1, c - 1]
                        nv = 1 - t
                        g[r, c] = t
                        if g[r, c - 1] != nv:  # paper (i-1, j)
                            g[r, c - 1] = nv
                            Hr[k1, r] = Hr[k2, r] + 1 if (c > 1 and g[r, c - 2] == nv) else 1
                            Vr[k1, r] = Vr[k2, r - 1] + 1 if g[r - 1, c - 1] == nv else 1
                            if col_order and r + 1 <= rhi:  # [r+1, c-1] already visited
                                Vr[k, r + 1] = Vr[k1, r] + 1 if g[r + 1, c - 1] == nv else 1
                        if g[r - 1, c] != nv:  # paper (i, j-1)
                            g[r - 1, c] = nv
                            Hr[k1, r - 1] = Hr[k2, r - 1] + 1 if g[r - 1, c - 1] == nv else 1
                            Vr[k1, r - 1] = Vr[k2, r - 2] + 1 if (r > 1 and g[r - 2, c] == nv) else 1
                            if (not col_order) and r - 1 >= rlo:  # [r-1, c+1] already visited
                                Hr[k, r - 1] = Hr[k1, r - 1] + 1 if g[r - 1, c + 1] == nv else 1
                        h = Hr[k1, r] + 1 if g[r, c - 1] == t else 1
                        v = Vr[k1, r - 1] + 1 if g[r - 1, c] == t else 1
            Hr[k, r] = h
            Vr[k, r] = v
    return bad


@kernel(nogil=True, inline="always")
def _cyc_limit(lim, pos, last, strengthen, init_run):
    """ViolateCyc's limit for one condition (Algorithm 2, cases (i)-(iv) of §3.2)."""
    if lim == 0:
        return _NONE
    if strengthen:
        if pos < lim - 2:  # (i) no condition
            return _NONE
        if pos == lim - 2:  # (ii) H^{p-2}
            return lim - 2
    if pos == last:  # (iii) H^{p-k}, k = run of t starting at position 0
        return lim - init_run
    return lim  # (iv)


@kernel(nogil=True)
def _violate_cyc(g, t, h, v, r, c, p, q, strengthen):
    """ViolateCyc(g, [r, c]) for tile ``t`` with non-wrapping runs ``h`` (left), ``v`` (up)."""
    R, C = g.shape
    kh = 0
    if c == C - 1 and p[t] != 0:
        while kh < C and kh <= p[t] and g[r, kh] == t:
            kh += 1
    lh = _cyc_limit(p[t], c, C - 1, strengthen, kh)
    if h > lh:
        return True
    kv = 0
    if r == R - 1 and q[t] != 0:
        while kv < R and kv <= q[t] and g[kv, c] == t:
            kv += 1
    lv = _cyc_limit(q[t], r, R - 1, strengthen, kv)
    return v > lv


@kernel(nogil=True)
def _runs(g, Hr, Vr, k1, r, c, t):
    """Runs of tile ``t`` ending at ``[r, c]`` from the runs stored for diagonal ``d - 1``."""
    h = Hr[k1, r] + 1 if (c > 0 and g[r, c - 1] == t) else 1
    v = Vr[k1, r - 1] + 1 if (r > 0 and g[r - 1, c] == t) else 1
    return h, v


@kernel(nogil=True)
def cyclic_kernel(g, p, q, r0, c0, strengthen, col_order, recheck):
    """Algorithm 2 of the dappled paper (ViolateCyc), in place on ``g``.

    ``p[t]``, ``q[t]`` are uniform limits (0 = unlimited). Cells with ``row < r0`` or
    ``col < c0`` are a fixed frame (Remark 3.4): their runs are tracked but they are never
    checked or rewritten. ``strengthen`` applies cases (i)/(ii) of ViolateCyc.

    Re-check of dependents (our addition). A surgery (II) at ``[r, c]`` rewrites a cell of
    diagonal ``d - 1``, which lengthens by one the run of at most one already-visited cell
    of diagonal ``d`` (``[r-1, c+1]`` in row order). With limits ``>= 2`` that run stays
    ``<= 2`` and legal (the paper's argument), so the re-check never fires in Algorithms 1
    and 2. The seam conditions of Remark 3.4 with ``p = 2`` or ``q = 2`` are limits of 1,
    where it can fire; the visited cell is then rectified again (steps (I)/(II)) before the
    sweep moves on, as if it had been visited after ``[r, c]`` (the paper allows any order
    within a weight).

    ``recheck=False`` gives the paper's procedure without this re-check (it only updates the
    runs of the visited cell), for comparison.

    Returns the number of surgeries skipped because they would have touched the frame or
    left the grid, plus re-check chains cut off (the caller verifies the output).
    """
    R, C = g.shape
    Hr = np.zeros((3, R), np.int32)
    Vr = np.zeros((3, R), np.int32)
    stack = np.empty(2 * R + 4, np.int64)
    bad = 0
    for d in range(R + C - 1):
        k = d % 3
        k1 = (d + 2) % 3
        k2 = (d + 1) % 3
        rlo = max(0, d - C + 1)
        rhi = min(d, R - 1)
        budget = 8 * (rhi - rlo + 1) + 8
        for idx in range(rhi - rlo + 1):
            r = rhi - idx if col_order else rlo + idx
            stack[0] = r
            sp = 1
            while sp > 0:
                sp -= 1
                y = stack[sp]
                x = d - y
                t = g[y, x]
                h, v = _runs(g, Hr, Vr, k1, y, x, t)
                if y >= r0 and x >= c0 and _violate_cyc(g, t, h, v, y, x, p, q, strengthen):
                    t = 1 - t
                    g[y, x] = t
                    h, v = _runs(g, Hr, Vr, k1, y, x, t)
                    if _violate_cyc(g, t, h, v, y, x, p, q, strengthen):
                        if y == 0 or x == 0 or (g[y, x - 1] == g[y - 1, x - 1] and x - 1 < c0) or (
                            g[y - 1, x] == g[y - 1, x - 1] and y - 1 < r0
                        ):
                            bad += 1
                        else:
                            t = g[y - 1, x - 1]
                            nv = 1 - t
                            g[y, x] = t
                            if g[y, x - 1] != nv:  # paper (i-1, j)
                                g[y, x - 1] = nv
                                Hr[k1, y] = Hr[k2, y] + 1 if (x > 1 and g[y, x - 2] == nv) else 1
                                Vr[k1, y] = Vr[k2, y - 1] + 1 if g[y - 1, x - 1] == nv else 1
                                z = y + 1  # [y+1, x-1] reads it
                                if not recheck and col_order and z <= rhi:
                                    Vr[k, z] = Vr[k1, y] + 1 if g[z, x - 1] == nv else 1
                                elif recheck and z <= rhi and (z >= r if col_order else z <= r):
                                    budget -= 1
                                    if budget < 0:
                                        bad += 1
                                    else:
                                        stack[sp] = z
                                        sp += 1
                            if g[y - 1, x] != nv:  # paper (i, j-1)
                                g[y - 1, x] = nv
                                Hr[k1, y - 1] = Hr[k2, y - 1] + 1 if g[y - 1, x - 1] == nv else 1
                                Vr[k1, y - 1] = Vr[k2, y - 2] + 1 if (y > 1 and g[y - 2, x] == nv) else 1
                                z = y - 1  # [y-1, x+1] reads it
                                if not recheck and (not col_order) and z >= rlo:
                                    Hr[k, z] = Hr[k1, z] + 1 if g[z, x + 1] == nv else 1
                                elif recheck and z >= rlo and (z >= r if col_order else z <= r):
                                    budget -= 1
                                    if budget < 0:
                                        bad += 1
                                    else:
                                        stack[sp] = z
                                        sp += 1
                            h, v = _runs(g, Hr, Vr, k1, y, x, t)
                Hr[k, y] = h
                Vr[k, y] = v
    return bad


@kernel(nogil=True)
def _greedy_ok(g, t, hprev, vprev, r, c, P, Q, cyclic, pc, qc):
    """May tile ``t`` go at ``[r, c]`` given the (final) cells before it in row-major order?"""
    R, C = g.shape
    h = hprev + 1 if (c > 0 and g[r, c - 1] == t) else 1
    v = vprev + 1 if (r > 0 and g[r - 1, c] == t) else 1
    if not cyclic:
        lp = P[t, r, c]
        lq = Q[t, r, c]
        return (lp == 0 or h <= lp) and (lq == 0 or v <= lq)
    lp = pc[t]
    if lp != 0:
        if lp >= 2 and c == lp - 1 and h > lp - 1:
            return False  # keep the run from column 0 below p so the seam can close
        if c == C - 1:
            k = 0
            while k < C - 1 and k <= lp and g[r, k] == t:
                k += 1
            if h + k > lp:
                return False
        elif h > lp:
            return False
    lq = qc[t]
    if lq != 0:
        if lq >= 2 and r == lq - 1 and v > lq - 1:
            return False
        if r == R - 1:
            k = 0
            while k < R - 1 and k <= lq and g[k, c] == t:
                k += 1
            if v + k > lq:
                return False
        elif v > lq:
            return False
    return True


@kernel(nogil=True)
def greedy_kernel(g, n, P, Q, cyclic, pc, qc, seed):
    """The trivial algorithm for ``|T| >= 3`` (§2), in place on ``g``, row-major order.

    Keeps each initial tile that breaks no condition given the cells before it; otherwise
    picks uniformly at random among the tiles that break none (tiles differing from the left
    and upper neighbours always qualify). Returns the number of cells where no tile
    qualified (0 whenever the caller's guarantee holds).
    """
    R, C = g.shape
    state = seed_state(seed)
    vrun = np.zeros(C, np.int32)
    cand = np.empty(n, np.int64)
    fails = 0
    for r in range(R):
        hprev = 0
        for c in range(C):
            t = g[r, c]
            if not _greedy_ok(g, t, hprev, vrun[c], r, c, P, Q, cyclic, pc, qc):
                m = 0
                for s in range(n):
                    if s != t and _greedy_ok(g, s, hprev, vrun[c], r, c, P, Q, cyclic, pc, qc):
                        cand[m] = s
                        m += 1
                if m == 0:
                    fails += 1
                else:
                    t = cand[(rand32(state) * m) >> 32]  # uniform up to m / 2**32
                    g[r, c] = t
            hprev = hprev + 1 if (c > 0 and g[r, c - 1] == t) else 1
            vrun[c] = vrun[c] + 1 if (r > 0 and g[r - 1, c] == t) else 1
    return fails


#: Cells from which compiling pays. In fresh processes on a loaded machine numba's import,
#: set-up and cache load cost 0.75-1.3 s of CPU; the kernels run at about 3-5 us a cell
#: interpreted, a few ns compiled. ``benchmarks/bench_startup.py`` measured the crossover
#: near 250,000 cells for Algorithm 1 and 360,000 for the trivial algorithm.
THRESHOLD = 250_000

#: The plain and compiled namespaces of this module.
KERNELS = Kernels(globals(), THRESHOLD)
