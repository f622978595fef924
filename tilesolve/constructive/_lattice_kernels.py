"""Compiled loops of the lattice hashes (:mod:`.hashes`), the stochastic tilings
(:mod:`.stochastic`) and the procedural walls (:mod:`.walls`).

They live in one module because numba's on-disk cache only notices changes to the file of the
function it caches: a kernel calling :func:`hash_row` or :func:`fnv_xorshift_u64` from another
file would keep running an old copy of it.

A 2-D permutation-table hash (eq. 3.3, or the sum of eq. 3.6) is evaluated a row at a time
from its *row tables* (see ``PermutationHash.row_tables``): ``twice[i]`` is table ``i``
written twice (so ``P[(a + b) % N] = twice[a + b]`` for ``a, b < N``), ``sizes[i]`` its size,
``px[i, c] = P_i[x_c % N_i]`` for the columns ``x_c`` of the row, and ``red[s]`` the final
reduction ``(s % range) % modulus`` of a sum ``s``, looked up instead of divided.

Lattice rows are produced from south to north; outputs are ``[row, col]`` with row 0 at the
top, tile ``(x0 + col, y0 + h - 1 - row)``.
"""

from __future__ import annotations

import numpy as np

from tilesolve._numba import njit

#: FNV-1a 64-bit prime (Fowler, Noll, Vo).
FNV_PRIME = 0x100000001B3
#: Output multiplier of xorshift64* (Vigna, 2014).
XORSHIFT_STAR = 0x2545F4914F6CDD1D


@njit(cache=True)
def hash_row(twice, sizes, px, red, y, acc, out):
    """``out[c] = red[sum_i twice[i, y % sizes[i] + px[i, c]]]``: the hash of ``(x_c, y)``.

    ``acc`` is int32 scratch of at least ``px.shape[1]`` entries. Table by table, so that the
    inner loop over the columns has no dependency between iterations.
    """
    n = px.shape[1]
    for c in range(n):
        acc[c] = 0
    for i in range(sizes.shape[0]):
        yi = y % sizes[i]
        t = twice[i]
        p = px[i]
        for c in range(n):
            acc[c] += t[yi + p[c]]
    for c in range(n):
        out[c] = red[acc[c]]


@njit(cache=True)
def outer_rows(twice, sizes, px, red, ys):
    """The hash on the grid ``ys x xs`` (rows in ``ys`` order), int32."""
    out = np.empty((ys.shape[0], px.shape[1]), dtype=np.int32)
    acc = np.empty(px.shape[1], dtype=np.int32)
    for r in range(ys.shape[0]):
        hash_row(twice, sizes, px, red, ys[r], acc, out[r])
    return out


@njit(cache=True)
def direct_corner(twice, sizes, px, red, y0, c, out):
    """§3.3.1: NE, SE, SW, NW = h(x+1, y+1), h(x+1, y), h(x, y), h(x, y+1); ``px`` covers x0 .. x0 + w."""
    h, w = out.shape
    acc = np.empty(w + 1, dtype=np.int32)
    south = np.empty(w + 1, dtype=np.int32)
    north = np.empty(w + 1, dtype=np.int32)
    hash_row(twice, sizes, px, red, y0, acc, south)
    for dy in range(h):
        hash_row(twice, sizes, px, red, y0 + dy + 1, acc, north)
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
    acc = np.empty(w + 1, dtype=np.int32)
    hs, hn = np.empty(w + 1, dtype=np.int32), np.empty(w + 1, dtype=np.int32)
    vs, vn = np.empty(w + 1, dtype=np.int32), np.empty(w + 1, dtype=np.int32)
    hash_row(t1, s1, p1, r1, y0, acc, hs)
    hash_row(t2, s2, p2, r2, y0, acc, vs)
    for dy in range(h):
        hash_row(t1, s1, p1, r1, y0 + dy + 1, acc, hn)
        hash_row(t2, s2, p2, r2, y0 + dy + 1, acc, vn)
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
    acc = np.empty(w + 1, dtype=np.int32)
    south = np.empty(w, dtype=np.int32)
    north = np.empty(w, dtype=np.int32)
    mid = np.empty(w + 1, dtype=np.int32)
    hash_row(twice, sizes, podd, red, 2 * y0, acc, south)
    for dy in range(h):
        y = y0 + dy
        hash_row(twice, sizes, podd, red, 2 * y + 2, acc, north)
        hash_row(twice, sizes, peven, red, 2 * y + 1, acc, mid)
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
    acc = np.empty(w + 1, dtype=np.int32)
    v = np.empty(w + 1, dtype=np.int32)
    south = np.empty(w, dtype=np.int64)
    hash_row(twice, sizes, px, red, y0 + h, acc, v)
    for x in range(w):
        south[x] = v[x + 1] % c if compact else (v[x + 1] // c) % c
    for r in range(h):
        hash_row(twice, sizes, px, red, y0 + h - 1 - r, acc, v)
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
    acc = np.empty(w + 1, dtype=np.int32)
    v = np.empty(w + 1, dtype=np.int32)
    above = np.empty(w + 1, dtype=np.int64)
    below = np.empty(w + 1, dtype=np.int64)
    hash_row(twice, sizes, px, red, y0 + h, acc, v)
    for x in range(w + 1):
        above[x] = v[x] % c
    for r in range(h):
        hash_row(twice, sizes, px, red, y0 + h - 1 - r, acc, v)
        below[0] = v[0] % c
        for x in range(w):
            nw, ne, sw = above[x], above[x + 1], below[x]
            pick = v[x + 1]
            se = (ne + nw + sw + (pick & 1)) % c if compact else pick % c
            below[x + 1] = se
            out[r, x] = ((ne * c + se) * c + sw) * c + nw
        above, below = below, above
    return out


# ------------------------------------------------------------------------------------ FNV + xorshift
def fnv_xorshift_u64(basis, x, y):
    """The FNV-1a / xorshift mix on ``uint64`` operands (numpy arrays, numpy scalars, or numba).

    ``basis`` is the FNV state after the seed words (see :class:`FnvXorshift`); ``x`` and
    ``y`` are the coordinates as two's-complement ``uint64``. Each coordinate is fed to
    FNV-1a as its low and its high 32-bit word; the state then seeds Vigna's xorshift64*
    generator (shifts 12, 25, 27, output multiplier 0x2545F4914F6CDD1D) and its first output
    is the hash ("peek a value", 004 §4.2). The output multiplication matters: without it the
    high bits hardly depend on the low bits of ``y``. Only operators appear here, so numpy
    and numba compile the same arithmetic.
    """
    m32 = np.uint64(0xFFFFFFFF)
    p = np.uint64(FNV_PRIME)
    h = basis
    h = (h ^ (x & m32)) * p
    h = (h ^ (x >> np.uint64(32))) * p
    h = (h ^ (y & m32)) * p
    h = (h ^ (y >> np.uint64(32))) * p
    h = h ^ (h >> np.uint64(12))
    h = h ^ (h << np.uint64(25))
    h = h ^ (h >> np.uint64(27))
    return h * np.uint64(XORSHIFT_STAR)


# ------------------------------------------------------------------------------------ walls
def d1(raw, nc, c):
    """``vd1``/``hd1`` (App. B): a colour unlike ``c`` from the hash value ``raw``."""
    m = (raw * (nc - 1)) >> 32
    return m if m < c else m + 1


def d2(raw, nc, c1, c2):
    """``vd2``/``hd2`` (App. B, ``m'`` reconstructed; see :mod:`.walls`): unlike ``c1`` and ``c2``."""
    if c1 == c2:  # vd1 (written out: the compiled form cannot call the Python one)
        m = (raw * (nc - 1)) >> 32
        return m if m < c1 else m + 1
    m = (raw * (nc - 2)) >> 32
    lo, hi = min(c1, c2), max(c1, c2)
    if m < lo:
        return m
    if m < hi - 1:
        return m + 1
    return m + 2


_fnv = njit(cache=True)(fnv_xorshift_u64)
_d1_nb = njit(cache=True)(d1)
_d2_nb = njit(cache=True)(d2)


@njit(cache=True)
def _raw(basis, i, j):
    return np.int64(_fnv(basis, np.uint64(i), np.uint64(j)) >> np.uint64(32))


@njit(cache=True)
def wall_kernel(x0, y0, w, h, nc, p, fixed, bh, bv, bo, opt, nopt, out):
    """The procedural wall of :mod:`.walls` (``_ScalarWall``) over a window, each hash evaluated once.

    Lattice arrays: ``hr[r, c]`` the ℋ value at ``(bi0 + c, bj0 - 2 + 2 r)`` (even rows, one
    block row of margin each side for the dappling neighbours), ``vr[r, s]`` the 𝒱 value at
    ``(bi0 - 2 + 2 s, bj0 + r)``; ``hp``/``vp`` the colours ``h'``/``v'``.
    """
    bi0, bj0 = x0 - x0 % 2, y0 - y0 % 2
    xl, yl = x0 + w - 1, y0 + h - 1
    nbc, nbr = (xl - xl % 2 - bi0) // 2 + 1, (yl - yl % 2 - bj0) // 2 + 1
    hr = np.empty((nbr + 3, 2 * nbc), dtype=np.int64)
    for r in range(nbr + 3):
        for c in range(2 * nbc):
            hr[r, c] = _raw(bh, bi0 + c, bj0 - 2 + 2 * r)
    vr = np.empty((2 * nbr, nbc + 3), dtype=np.int64)
    for r in range(2 * nbr):
        for s in range(nbc + 3):
            vr[r, s] = _raw(bv, bi0 - 2 + 2 * s, bj0 + r)
    # Residues modulo the dappling period of the even block coordinates (i', j').
    pp = max(p, 1)
    ires = np.empty(nbc + 1, dtype=np.int64)
    for s in range(nbc + 1):
        ires[s] = (bi0 + 2 * s) % pp
    jres = np.empty(nbr + 1, dtype=np.int64)
    for t in range(nbr + 1):
        jres[t] = (bj0 + 2 * t) % pp
    hp = np.empty((nbr + 1, 2 * nbc), dtype=np.int64)
    for t in range(nbr + 1):
        j4 = (bj0 + 2 * t) & 3
        for c in range(2 * nbc):
            v0 = hr[t + 1, c]
            if p == 2 and j4 == 2:
                hp[t, c] = _d2_nb(v0, nc, (hr[t, c] * nc) >> 32, (hr[t + 2, c] * nc) >> 32)
            elif p > 2 and ires[c // 2] == jres[t]:
                hp[t, c] = _d1_nb(v0, nc, (hr[t + 2, c] * nc) >> 32)
            else:
                hp[t, c] = (v0 * nc) >> 32
    vp = np.empty((2 * nbr, nbc + 1), dtype=np.int64)
    for r in range(2 * nbr):
        for s in range(nbc + 1):
            v0 = vr[r, s + 1]
            if p == 2 and ((bi0 + 2 * s) & 3) == 2:
                vp[r, s] = _d2_nb(v0, nc, (vr[r, s] * nc) >> 32, (vr[r, s + 2] * nc) >> 32)
            elif p > 2 and ires[s] == jres[r // 2]:
                vp[r, s] = _d1_nb(v0, nc, (vr[r, s + 2] * nc) >> 32)
            else:
                vp[r, s] = (v0 * nc) >> 32
    o = np.empty(12, dtype=np.int64)
    for tb in range(nbr):
        bj = bj0 + 2 * tb
        for sb in range(nbc):
            bi = bi0 + 2 * sb
            o[0] = vp[2 * tb + 1, sb]  # VT0
            o[1] = vp[2 * tb + 1, sb + 1]  # VT2
            o[2] = hp[tb, 2 * sb]  # HL0
            o[3] = hp[tb + 1, 2 * sb]  # HL2
            o[4] = vp[2 * tb, sb]  # VB0
            o[5] = vp[2 * tb, sb + 1]  # VB2
            o[6] = hp[tb, 2 * sb + 1]  # HR0
            o[7] = hp[tb + 1, 2 * sb + 1]  # HR2
            case = 8 * (o[3] == o[2]) + 4 * (o[6] == o[7]) + 2 * (o[0] == o[1]) + (o[4] == o[5])
            if fixed and (p == 2 or ires[sb] == jres[tb]):
                option = 0
            else:
                option = (_raw(bo, bi, bj) * nopt[case]) >> 32
            # App. B puts vd2T only in the first slot, hd2L in the second, vd2B in the third and
            # hd2R in the fourth: compute a helper only when its slot asks for it.
            if opt[case, option, 0] == 8:
                o[8] = _d2_nb(_raw(bv, bi + 1, bj + 1), nc, o[0], o[1])
            if opt[case, option, 1] == 9:
                o[9] = _d2_nb(_raw(bh, bi, bj + 1), nc, o[3], o[2])
            if opt[case, option, 2] == 10:
                o[10] = _d2_nb(_raw(bv, bi + 1, bj), nc, o[4], o[5])
            if opt[case, option, 3] == 11:
                o[11] = _d2_nb(_raw(bh, bi + 1, bj + 1), nc, o[6], o[7])
            vt1, hl1 = o[opt[case, option, 0]], o[opt[case, option, 1]]
            vb1, hr1 = o[opt[case, option, 2]], o[opt[case, option, 3]]
            for dj in range(2):
                j = bj + dj
                if j < y0 or j > yl:
                    continue
                r = yl - j
                for di in range(2):
                    i = bi + di
                    if i < x0 or i > xl:
                        continue
                    c = i - x0
                    if dj == 0 and di == 0:
                        out[r, c, 0], out[r, c, 1], out[r, c, 2], out[r, c, 3] = hl1, vb1, o[2], o[4]
                    elif dj == 0:
                        out[r, c, 0], out[r, c, 1], out[r, c, 2], out[r, c, 3] = hr1, o[5], o[6], vb1
                    elif di == 0:
                        out[r, c, 0], out[r, c, 1], out[r, c, 2], out[r, c, 3] = o[3], vt1, hl1, o[0]
                    else:
                        out[r, c, 0], out[r, c, 1], out[r, c, 2], out[r, c, 3] = o[7], o[1], hr1, vt1
    return out
