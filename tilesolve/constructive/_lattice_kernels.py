"""Compiled loops of the lattice hashes (:mod:`.hashes`) and the stochastic tilings (:mod:`.stochastic`).

They live in one module because numba's on-disk cache only notices changes to the file of the
function it caches: a kernel calling :func:`hash_row` from another file would keep running an
old copy of it.

A 2-D permutation-table hash (eq. 3.3, or the sum of eq. 3.6) is evaluated a row at a time
from its *row tables* (see ``PermutationHash.row_tables``): ``twice[i]`` is table ``i``
written twice (so ``P[(a + b) % N] = twice[a + b]`` for ``a, b < N``), ``sizes[i]`` its size,
``px[c, i] = P_i[x_c % N_i]`` for the columns ``x_c`` of the row, and ``red[s]`` the final
reduction ``(s % range) % modulus`` of a sum ``s``, looked up instead of divided.

Lattice rows are produced from south to north; outputs are ``[row, col]`` with row 0 at the
top, tile ``(x0 + col, y0 + h - 1 - row)``.
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def hash_row(twice, sizes, px, red, y, ym, out):
    """``out[c] = red[sum_i twice[i, y % sizes[i] + px[c, i]]]``: the hash of ``(x_c, y)``."""
    m = sizes.shape[0]
    for i in range(m):
        ym[i] = y % sizes[i]
    for c in range(px.shape[0]):
        s = 0
        for i in range(m):
            s += twice[i, ym[i] + px[c, i]]
        out[c] = red[s]


@njit(cache=True)
def outer_rows(twice, sizes, px, red, ys):
    """The hash on the grid ``ys x xs`` (rows in ``ys`` order), int32."""
    out = np.empty((ys.shape[0], px.shape[0]), dtype=np.int32)
    ym = np.empty(sizes.shape[0], dtype=np.int64)
    for r in range(ys.shape[0]):
        hash_row(twice, sizes, px, red, ys[r], ym, out[r])
    return out


@njit(cache=True)
def direct_corner(twice, sizes, px, red, y0, c, out):
    """§3.3.1: NE, SE, SW, NW = h(x+1, y+1), h(x+1, y), h(x, y), h(x, y+1); ``px`` covers x0 .. x0 + w."""
    h, w = out.shape
    ym = np.empty(sizes.shape[0], dtype=np.int64)
    south = np.empty(w + 1, dtype=np.int32)
    north = np.empty(w + 1, dtype=np.int32)
    hash_row(twice, sizes, px, red, y0, ym, south)
    for dy in range(h):
        hash_row(twice, sizes, px, red, y0 + dy + 1, ym, north)
        r = h - 1 - dy
        for x in range(w):
            out[r, x] = ((north[x + 1] * c + south[x + 1]) * c + south[x]) * c + north[x]
        south, north = north, south
    return out


@njit(cache=True)
def direct_wang_sums(t1, s1, p1, r1, t2, s2, p2, r2, y0, c, out):
    """§3.3.2.1 (two hashes, ``hh`` from tables 1 and ``hv`` from tables 2) and §3.3.2.2 (the
    same tables twice): N = NW + NE, E = NE + SE, S = SE + SW, W = SW + NW of the corner
    values, mod C; ``px`` covers x0 .. x0 + w."""
    h, w = out.shape
    ym1 = np.empty(s1.shape[0], dtype=np.int64)
    ym2 = np.empty(s2.shape[0], dtype=np.int64)
    hs, hn = np.empty(w + 1, dtype=np.int32), np.empty(w + 1, dtype=np.int32)
    vs, vn = np.empty(w + 1, dtype=np.int32), np.empty(w + 1, dtype=np.int32)
    hash_row(t1, s1, p1, r1, y0, ym1, hs)
    hash_row(t2, s2, p2, r2, y0, ym2, vs)
    for dy in range(h):
        hash_row(t1, s1, p1, r1, y0 + dy + 1, ym1, hn)
        hash_row(t2, s2, p2, r2, y0 + dy + 1, ym2, vn)
        r = h - 1 - dy
        for x in range(w):
            n = (hn[x] + hn[x + 1]) % c
            e = (vn[x + 1] + vs[x + 1]) % c
            s = (hs[x + 1] + hs[x]) % c
            wc = (vs[x] + vn[x]) % c
            out[r, x] = ((n * c + e) * c + s) * c + wc
        hs, hn = hn, hs
        vs, vn = vn, vs
    return out


@njit(cache=True)
def direct_wang_edges(twice, sizes, podd, peven, red, y0, c, out):
    """§3.3.2.3: N, E, S, W = h(2x+1, 2y+2), h(2x+2, 2y+1), h(2x+1, 2y), h(2x, 2y+1).

    ``podd`` covers the columns 2x + 1 (x0 .. x0 + w - 1), ``peven`` the columns 2x (x0 .. x0 + w).
    """
    h, w = out.shape
    ym = np.empty(sizes.shape[0], dtype=np.int64)
    south = np.empty(w, dtype=np.int32)
    north = np.empty(w, dtype=np.int32)
    mid = np.empty(w + 1, dtype=np.int32)
    hash_row(twice, sizes, podd, red, 2 * y0, ym, south)
    for dy in range(h):
        y = y0 + dy
        hash_row(twice, sizes, podd, red, 2 * y + 2, ym, north)
        hash_row(twice, sizes, peven, red, 2 * y + 1, ym, mid)
        r = h - 1 - dy
        for x in range(w):
            out[r, x] = ((north[x] * c + mid[x + 1]) * c + south[x]) * c + mid[x]
        south, north = north, south
    return out


@njit(cache=True)
def scanline_wang(twice, sizes, px, red, y0, c, compact, out):
    """§3.2.1 west to east, north to south; ``px`` covers x0 - 1 .. x0 + w - 1 (column 0 is the
    virtual cell west of the window), ``red`` reduces to the choice range.

    A cell's choice ``v`` gives ``E = N + k, S = W + k`` with ``k = v & 1`` (compact) or
    ``E = v % C, S = (v // C) % C`` (complete). The virtual cells north of the window show their
    ``S`` colour (``v % C`` compact, ``(v // C) % C`` complete), those west of it their ``E``
    colour ``v % C``.
    """
    h, w = out.shape
    ym = np.empty(sizes.shape[0], dtype=np.int64)
    v = np.empty(w + 1, dtype=np.int32)
    south = np.empty(w, dtype=np.int64)
    hash_row(twice, sizes, px, red, y0 + h, ym, v)
    for x in range(w):
        south[x] = v[x + 1] % c if compact else (v[x + 1] // c) % c
    for r in range(h):
        hash_row(twice, sizes, px, red, y0 + h - 1 - r, ym, v)
        east = v[0] % c
        for x in range(w):
            n, wc, pick = south[x], east, v[x + 1]
            if compact:
                k = pick & 1
                e, s = (n + k) % c, (wc + k) % c
            else:
                e, s = pick % c, (pick // c) % c
            out[r, x] = ((n * c + e) * c + s) * c + wc
            south[x] = s
            east = e
    return out


@njit(cache=True)
def scanline_corner(twice, sizes, px, red, y0, c, compact, out):
    """§3.2.2 west to east, north to south; ``px`` covers x0 - 1 .. x0 + w - 1. A cell's choice
    ``v`` gives ``SE = NE + NW + SW + (v & 1)`` (compact) or ``SE = v % C`` (complete); the corners
    on the window's top and west edges are the SE corners ``v % C`` of the virtual cells north and
    west of it."""
    h, w = out.shape
    ym = np.empty(sizes.shape[0], dtype=np.int64)
    v = np.empty(w + 1, dtype=np.int32)
    above = np.empty(w + 1, dtype=np.int64)
    below = np.empty(w + 1, dtype=np.int64)
    hash_row(twice, sizes, px, red, y0 + h, ym, v)
    for x in range(w + 1):
        above[x] = v[x] % c
    for r in range(h):
        hash_row(twice, sizes, px, red, y0 + h - 1 - r, ym, v)
        below[0] = v[0] % c
        for x in range(w):
            nw, ne, sw = above[x], above[x + 1], below[x]
            pick = v[x + 1]
            se = (ne + nw + sw + (pick & 1)) % c if compact else pick % c
            below[x + 1] = se
            out[r, x] = ((ne * c + se) * c + sw) * c + nw
        above, below = below, above
    return out
