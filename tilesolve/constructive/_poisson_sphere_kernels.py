"""The dart-throwing kernel of the corner-based Poisson sphere tiles (:mod:`.poisson_sphere`).

:func:`dart_fill3` is relaxation dart throwing (McCool and Fiume 1992; class notes §4.2.4.2,
in 3-D as §4.4.1.3 says it generalizes) into a region made of boxes, around fixed points, on
a uniform grid of cells at least the smallest radius wide: darts are thrown at radius ``r0``,
which shrinks by ``shrink`` after ``patience`` darts in a row miss, down to ``rmin``; the fill
stops at ``target`` points or when ``final`` darts in a row miss at ``rmin``. scipy's
``PoissonDisk(d=3)`` fills a box at one radius and knows no point count, fixed points, holes
or torus: hence this kernel. Plain and compiled paths give the same points (xorshift64,
:func:`tilesolve.constructive._jit.rand32`).
"""

from __future__ import annotations

import math

import numpy as np

from tilesolve.constructive._jit import Kernels, kernel, rand32, seed_state

__all__ = ["dart_fill3", "KERNELS"]

_SCALE = 1.0 / 4294967296.0


@kernel()
def _in_boxes3(x, y, z, boxes):
    for b in range(boxes.shape[0]):
        if (boxes[b, 0] <= x < boxes[b, 1] and boxes[b, 2] <= y < boxes[b, 3]
                and boxes[b, 4] <= z < boxes[b, 5]):
            return True
    return False


@kernel()
def _wrap(j, n, torus):
    """Grid index ``j`` of ``n``: wrapped on the torus, ``-1`` off the grid otherwise."""
    if torus:
        return j % n
    if j < 0 or j >= n:
        return -1
    return j


@kernel()
def _free(pts, head, nxt, dims, lo, cw, x, y, z, r, torus):
    """Whether no point of the grid is closer than ``r`` to ``(x, y, z)``."""
    r2 = r * r
    q = (x, y, z)
    cell = np.empty(3, np.int64)
    reach = np.empty(3, np.int64)
    for a in range(3):
        cell[a] = min(dims[a] - 1, max(0, int((q[a] - lo[a]) / cw[a])))
        reach[a] = int(math.ceil(r / cw[a]))
    for jz in range(cell[2] - reach[2], cell[2] + reach[2] + 1):
        kz = _wrap(jz, dims[2], torus)
        if kz < 0:
            continue
        for jy in range(cell[1] - reach[1], cell[1] + reach[1] + 1):
            ky = _wrap(jy, dims[1], torus)
            if ky < 0:
                continue
            for jx in range(cell[0] - reach[0], cell[0] + reach[0] + 1):
                kx = _wrap(jx, dims[0], torus)
                if kx < 0:
                    continue
                p = head[(kz * dims[1] + ky) * dims[0] + kx]
                while p >= 0:
                    dx = pts[p, 0] - x
                    dy = pts[p, 1] - y
                    dz = pts[p, 2] - z
                    if torus:
                        dx -= math.floor(dx + 0.5)
                        dy -= math.floor(dy + 0.5)
                        dz -= math.floor(dz + 0.5)
                    if dx * dx + dy * dy + dz * dz < r2:
                        return False
                    p = nxt[p]
    return True


@kernel()
def _insert(pts, head, nxt, dims, lo, cw, n_all, x, y, z):
    cx = min(dims[0] - 1, max(0, int((x - lo[0]) / cw[0])))
    cy = min(dims[1] - 1, max(0, int((y - lo[1]) / cw[1])))
    cz = min(dims[2] - 1, max(0, int((z - lo[2]) / cw[2])))
    pts[n_all, 0] = x
    pts[n_all, 1] = y
    pts[n_all, 2] = z
    c = (cz * dims[1] + cy) * dims[0] + cx
    nxt[n_all] = head[c]
    head[c] = n_all


@kernel()
def dart_fill3(fixed, allow, forbid, target, r0, rmin, shrink, patience, final, torus, seed, out):
    """Throw up to ``target`` darts into ``allow`` less ``forbid``, at least the current radius
    from each other and from ``fixed``.

    Parameters
    ----------
    fixed : (m, 3) float64
        Points already placed (those farther than ``r0`` from the boxes' hull are ignored).
    allow, forbid : (k, 6) float64
        Boxes ``[x0, x1) x [y0, y1) x [z0, z1)``; darts land in the union of ``allow`` less
        ``forbid``. With ``torus`` the domain is the unit torus and ``allow`` is ``[[0, 1] * 3]``.
    target : int
    r0, rmin, shrink : float
    patience, final : int
    torus : bool
    seed : int
        ``0 <= seed < 2**31``.
    out : (target, 3) float64
        Receives the new points.

    Returns
    -------
    (int, float)
        How many points were placed, and the radius the last one was placed at.
    """
    state = seed_state(seed)
    lo = np.empty(3)
    hi = np.empty(3)
    for a in range(3):
        lo[a] = allow[0, 2 * a]
        hi[a] = allow[0, 2 * a + 1]
        for b in range(1, allow.shape[0]):
            lo[a] = min(lo[a], allow[b, 2 * a])
            hi[a] = max(hi[a], allow[b, 2 * a + 1])
    dims = np.empty(3, np.int64)
    cw = np.empty(3)
    for a in range(3):
        dims[a] = max(1, min(160, int((hi[a] - lo[a]) / rmin)))
        cw[a] = (hi[a] - lo[a]) / dims[a]
    m = fixed.shape[0]
    pts = np.empty((m + target, 3))
    head = np.full(dims[0] * dims[1] * dims[2], -1, np.int64)
    nxt = np.full(m + target, -1, np.int64)
    n_all = 0
    for i in range(m):
        x = fixed[i, 0]
        y = fixed[i, 1]
        z = fixed[i, 2]
        if torus:
            x = x - math.floor(x)
            y = y - math.floor(y)
            z = z - math.floor(z)
        elif (x < lo[0] - r0 or x >= hi[0] + r0 or y < lo[1] - r0 or y >= hi[1] + r0
              or z < lo[2] - r0 or z >= hi[2] + r0):
            continue
        _insert(pts, head, nxt, dims, lo, cw, n_all, x, y, z)
        n_all += 1
    cum = np.empty(allow.shape[0])
    total = 0.0
    for b in range(allow.shape[0]):
        total += (allow[b, 1] - allow[b, 0]) * (allow[b, 3] - allow[b, 2]) * (allow[b, 5] - allow[b, 4])
        cum[b] = total
    r = r0
    fails = 0
    n = 0
    while n < target:
        u = rand32(state) * _SCALE * total
        b = 0
        while b < allow.shape[0] - 1 and cum[b] <= u:
            b += 1
        x = allow[b, 0] + rand32(state) * _SCALE * (allow[b, 1] - allow[b, 0])
        y = allow[b, 2] + rand32(state) * _SCALE * (allow[b, 3] - allow[b, 2])
        z = allow[b, 4] + rand32(state) * _SCALE * (allow[b, 5] - allow[b, 4])
        ok = x < allow[b, 1] and y < allow[b, 3] and z < allow[b, 5] and not _in_boxes3(x, y, z, forbid)
        if ok:
            ok = _free(pts, head, nxt, dims, lo, cw, x, y, z, r, torus)
        if ok:
            _insert(pts, head, nxt, dims, lo, cw, n_all, x, y, z)
            n_all += 1
            out[n, 0] = x
            out[n, 1] = y
            out[n, 2] = z
            n += 1
            fails = 0
        else:
            fails += 1
            if r <= rmin:
                if fails >= final:
                    break
            elif fails >= patience:
                r = max(rmin, r * shrink)
                fails = 0
    return n, r


#: Compiled from the first fill of a hundred points on (a plain fill takes seconds in Python).
KERNELS = Kernels(globals(), 100)
