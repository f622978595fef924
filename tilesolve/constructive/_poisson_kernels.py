"""The dart-throwing kernel of the corner-based Poisson disk tiles (:mod:`.poisson`).

:func:`dart_fill` is relaxation dart throwing (McCool and Fiume 1992; class notes §4.2.4.2)
into a region made of boxes, around fixed points, on a uniform grid of cells of the smallest
radius: darts are thrown at radius ``r0`` and the radius is reduced by ``shrink`` after
``patience`` darts in a row miss, down to ``rmin``; it stops at ``target`` points or when
``patience`` darts in a row miss at ``rmin`` (the region is then full at ``rmin``).

scipy's ``PoissonDisk`` (Bridson's algorithm) fills a box at one fixed radius; the tiles need
a point count, fixed points around the region, a region that is a box less other boxes, and a
torus: hence this kernel. Plain and compiled paths give the same points (xorshift64 random
numbers, :func:`tilesolve.constructive._jit.rand32`).
"""

from __future__ import annotations

import math

import numpy as np

from tilesolve.constructive._jit import Kernels, kernel, rand32, seed_state

__all__ = ["dart_fill", "KERNELS"]

_SCALE = 1.0 / 4294967296.0


@kernel()
def _in_boxes(x, y, boxes):
    for b in range(boxes.shape[0]):
        if boxes[b, 0] <= x < boxes[b, 1] and boxes[b, 2] <= y < boxes[b, 3]:
            return True
    return False


@kernel()
def _cell(j, n, torus):
    """Grid column or row ``j`` of ``n``: wrapped on the torus, ``-1`` off the grid otherwise."""
    if torus:
        return j % n
    if j < 0 or j >= n:
        return -1
    return j


@kernel()
def dart_fill(fixed, allow, forbid, target, r0, rmin, shrink, patience, final, torus, seed, out):
    """Throw up to ``target`` darts into ``allow`` less ``forbid``, at least the current radius
    from each other and from ``fixed``.

    Parameters
    ----------
    fixed : (m, 2) float64
        Points already placed (anywhere; those far from the region are ignored).
    allow, forbid : (k, 4) float64
        Boxes ``[x0, x1) x [y0, y1)``; darts land in the union of ``allow`` less ``forbid``.
        With ``torus`` the domain is the unit torus and ``allow`` must be ``[[0, 1, 0, 1]]``.
    target : int
    r0, rmin, shrink : float
        Starting radius, smallest radius, and the factor the radius shrinks by.
    patience, final : int
        Missed darts in a row before the radius shrinks, and at ``rmin``, before the fill stops.
    torus : bool
    seed : int
        ``0 <= seed < 2**31``.
    out : (target, 2) float64
        Receives the new points.

    Returns
    -------
    (int, float)
        How many points were placed, and the radius the last one was placed at.
    """
    state = seed_state(seed)
    if torus:
        bx0, bx1, by0, by1 = 0.0, 1.0, 0.0, 1.0
    else:
        bx0, bx1, by0, by1 = allow[0, 0], allow[0, 1], allow[0, 2], allow[0, 3]
        for b in range(1, allow.shape[0]):
            bx0 = min(bx0, allow[b, 0])
            bx1 = max(bx1, allow[b, 1])
            by0 = min(by0, allow[b, 2])
            by1 = max(by1, allow[b, 3])
    nx = max(1, int((bx1 - bx0) / rmin))
    ny = max(1, int((by1 - by0) / rmin))
    cw = (bx1 - bx0) / nx
    ch = (by1 - by0) / ny
    m = fixed.shape[0]
    pts = np.empty((m + target, 2))
    head = np.full(nx * ny, -1, np.int64)
    nxt = np.full(m + target, -1, np.int64)
    n_all = 0
    for i in range(m):
        x = fixed[i, 0]
        y = fixed[i, 1]
        if torus:
            x = x - math.floor(x)
            y = y - math.floor(y)
        elif x < bx0 - r0 or x >= bx1 + r0 or y < by0 - r0 or y >= by1 + r0:
            continue
        cx = min(nx - 1, max(0, int((x - bx0) / cw)))
        cy = min(ny - 1, max(0, int((y - by0) / ch)))
        pts[n_all, 0] = x
        pts[n_all, 1] = y
        nxt[n_all] = head[cy * nx + cx]
        head[cy * nx + cx] = n_all
        n_all += 1
    cum = np.empty(allow.shape[0])
    total = 0.0
    for b in range(allow.shape[0]):
        total += (allow[b, 1] - allow[b, 0]) * (allow[b, 3] - allow[b, 2])
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
        ok = x < allow[b, 1] and y < allow[b, 3] and not _in_boxes(x, y, forbid)
        if ok:
            cx = min(nx - 1, int((x - bx0) / cw))
            cy = min(ny - 1, int((y - by0) / ch))
            kx = int(math.ceil(r / cw))
            ky = int(math.ceil(r / ch))
            r2 = r * r
            for jy in range(cy - ky, cy + ky + 1):
                if not ok:
                    break
                jy2 = _cell(jy, ny, torus)
                if jy2 < 0:
                    continue
                for jx in range(cx - kx, cx + kx + 1):
                    jx2 = _cell(jx, nx, torus)
                    if jx2 < 0:
                        continue
                    p = head[jy2 * nx + jx2]
                    while p >= 0:
                        dx = pts[p, 0] - x
                        dy = pts[p, 1] - y
                        if torus:
                            dx -= math.floor(dx + 0.5)
                            dy -= math.floor(dy + 0.5)
                        if dx * dx + dy * dy < r2:
                            ok = False
                            break
                        p = nxt[p]
                    if not ok:
                        break
        if ok:
            pts[n_all, 0] = x
            pts[n_all, 1] = y
            nxt[n_all] = head[cy * nx + cx]
            head[cy * nx + cx] = n_all
            n_all += 1
            out[n, 0] = x
            out[n, 1] = y
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


#: Compiled from the first fill of a hundred points on (a plain fill of a tile's darts takes
#: seconds in Python).
KERNELS = Kernels(globals(), 100)
