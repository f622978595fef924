"""The neighbour scan of the Poisson disk verifier's grid, compiled by numba.

:func:`tilesolve.verify.poisson.point_violations` finds close pairs on a grid of cells of
side ``d`` (class notes §4.2.1: no two points closer than ``d``): a close pair lies in one
cell or in two neighbouring ones. Its numpy scan builds every candidate pair of neighbouring
cells as arrays; this loop visits them in place, and is used where numba is already loaded
(a command that built or re-derived the points has loaded it) and the set is large
(:data:`COMPILED_FROM`). Both scans take the same sorted cells and report a superset of the
close pairs, which the caller filters by the exact distance; a test checks that they agree.
Written from the definition, sharing nothing with the sampler whose points it checks.
"""

from __future__ import annotations

import sys

import numpy as np

__all__ = ["COMPILED_FROM", "compiled", "scan"]

#: Points from which the compiled scan is used, where numba is already loaded: below it the
#: numpy scan costs less than loading the kernel from numba's cache.
COMPILED_FROM = 100_000

_COMPILED = None


def scan(x, y, ukey, start, count, rows, cell_max, distance, out_i, out_j):
    """Candidate close pairs ``(i, j)`` of the points ``(x[i], y[i])``, numbered in cell order.

    The cells are the sorted keys ``ukey`` (key ``cx * rows + cy``), the points of cell ``c``
    are ``start[c] .. start[c] + count[c] - 1``. A cell of more than ``cell_max`` points holds
    a close pair (pigeonhole); there its first ``cell_max + 1`` points are paired with one
    another and with nothing else, as in the numpy scan. Other points are paired with those of
    their own cell (``i < j``) and of the E, NW, N, NE cells (each pair of cells once) when
    closer than ``distance`` give or take a rounding: the caller decides exactly. Writes up to
    ``len(out_i)`` pairs and returns how many there are (call again with room for all).
    """
    cap = out_i.shape[0]
    found = 0
    limit = distance * distance * (1.0 + 1e-9)
    offsets = np.array([0, rows, 1 - rows, 1, rows + 1], np.int64)  # itself, E, NW, N, NE in keys
    at = np.zeros(5, np.int64)  # per offset, the first cell whose key is not below the target
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
        for k in range(5):
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
                    dx = x[a] - x[b]
                    dy = y[a] - y[b]
                    if dx * dx + dy * dy < limit:
                        if found < cap:
                            out_i[found] = a
                            out_j[found] = b
                        found += 1
    return found


def compiled(n: int):
    """:func:`scan` compiled, for ``n`` points: where numba is already loaded in this process
    and ``n >= COMPILED_FROM``; None otherwise (then the numpy scan is cheaper)."""
    global _COMPILED
    if n < COMPILED_FROM or "numba" not in sys.modules:
        return None
    if _COMPILED is None:
        from tilesolve._numba import numba

        _COMPILED = numba.njit(cache=True, nogil=True)(scan)
    return _COMPILED
