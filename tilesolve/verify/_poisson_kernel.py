"""The neighbour scan of the Poisson disk and sphere verifiers' grids, compiled by numba.

:func:`tilesolve.verify.poisson.point_violations` and
:func:`tilesolve.verify.poisson_sphere.point_violations3` find close pairs on a grid of cells
of side ``d`` (class notes §4.2.1, §4.4: no two points closer than ``d``): a close pair lies in
one cell or in two neighbouring ones. Their numpy scans build every candidate pair of
neighbouring cells as arrays; this loop visits them in place, and is used where numba is already loaded
(a command that built or re-derived the points has loaded it) and the set is large
(:data:`COMPILED_FROM`). Both scans take the same sorted cells and report a superset of the
close pairs, which the caller filters by the exact distance; a test checks that they agree.
Written from the definition, sharing nothing with the sampler whose points it checks.
"""

from __future__ import annotations

import sys

import numpy as np

__all__ = ["COMPILED_FROM", "compiled", "scan", "candidates"]

#: Points from which the compiled scan is used, where numba is already loaded: below it the
#: numpy scan costs less than loading the kernel from numba's cache.
COMPILED_FROM = 100_000

_COMPILED = None


def scan(pts, ukey, start, count, offsets, cell_max, distance, out_i, out_j):
    """Candidate close pairs ``(i, j)`` of the points ``pts`` (``(n, dim)``, in cell order).

    The cells are the sorted keys ``ukey``; the points of cell ``c`` are rows ``start[c] ..
    start[c] + count[c] - 1``. ``offsets`` are the key offsets of the cell itself (first, 0) and
    of the neighbours that come after it (each pair of cells once). A cell of more than
    ``cell_max`` points holds a close pair (pigeonhole); there its first ``cell_max + 1`` points
    are paired with one another and with nothing else, as in the numpy scans. Other points are
    paired with those of their own cell (``i < j``) and of the neighbouring cells when closer
    than ``distance`` give or take a rounding: the caller decides exactly. Writes up to
    ``len(out_i)`` pairs and returns how many there are (call again with room for all).
    """
    cap = out_i.shape[0]
    dim = pts.shape[1]
    found = 0
    limit = distance * distance * (1.0 + 1e-9)
    at = np.zeros(offsets.shape[0], np.int64)  # per offset, the first cell whose key is not below the target
    cells = ukey.shape[0]
    for c in range(cells):
        s, m = start[c], count[c]
        if m > cell_max:
            for a in range(s, s + cell_max + 1):
                for b in range(a + 1, s + cell_max + 1):
                    if found < cap:
                        out_i[found] = a
                        out_j[found] = b
                    found += 1
            continue
        for k in range(offsets.shape[0]):
            if k == 0:
                t = c
            else:  # the targets grow with c: each offset's cell is found by a forward walk
                target = ukey[c] + offsets[k]
                t = at[k]
                while t < cells and ukey[t] < target:
                    t += 1
                at[k] = t
                if t >= cells or ukey[t] != target or count[t] > cell_max:
                    continue
            ts, tm = start[t], count[t]
            for a in range(s, s + m):
                for b in range(ts, ts + tm):
                    if k == 0 and b <= a:
                        continue
                    gap = 0.0
                    for d in range(dim):
                        step = pts[a, d] - pts[b, d]
                        gap += step * step
                    if gap < limit:
                        if found < cap:
                            out_i[found] = a
                            out_j[found] = b
                        found += 1
    return found


def candidates(kernel, points, order, ukey, start, count, offsets, cell_max, distance) -> np.ndarray:
    """The candidate pairs of :func:`scan` (by ``kernel``, its compiled copy), numbered as
    ``points`` are (``order`` sorts them by cell)."""
    pts = np.ascontiguousarray(points[order])
    offsets = np.asarray(offsets, np.int64)
    room = len(points) // 16 + 64  # a valid set has no pair: one pass; a forged one may need two
    while True:
        i, j = np.empty(room, np.int64), np.empty(room, np.int64)
        total = kernel(pts, ukey, start, count, offsets, cell_max, distance, i, j)
        if total <= room:
            return np.stack([order[i[:total]], order[j[:total]]], axis=1)
        room = total


def compiled(n: int, distance: float = 1.0):
    """:func:`scan` compiled, for ``n`` points at ``distance``: where numba is already loaded in
    this process and ``n >= COMPILED_FROM``; None otherwise (then the numpy scan is cheaper), and
    where ``distance`` squared would underflow or overflow (the scan compares squares; numpy's
    scan, by ``hypot``, does not)."""
    global _COMPILED
    if n < COMPILED_FROM or "numba" not in sys.modules or not 1e-150 < distance < 1e150:
        return None
    if _COMPILED is None:
        from tilesolve._numba import numba

        _COMPILED = numba.njit(cache=True, nogil=True)(scan)
    return _COMPILED
