"""One pass of the board verifier over a tiling of a board cut from a grid with no sides
identified (a rectangle, a rectangle with holes, a ring), compiled by numba.

:func:`tilesolve.verify.board.board_violations` calls :func:`grid_clean` through
:func:`compiled` when numba is loaded already or the board is large enough to pay for
loading it (:data:`COMPILED_FROM`); otherwise it checks the same with whole-array numpy
operations. Written from the definitions (brick paper, Def. 2 and Def. 9; dappled paper §4)
with nothing shared with the solvers whose tilings it checks.
"""

from __future__ import annotations

import sys

import numpy as np

__all__ = ["COMPILED_FROM", "compiled", "grid_clean"]

#: Cells from which loading numba (a few tenths of a second, when nothing loaded it yet) pays
#: for itself against the numpy checks (about 20-40 M cells/s on one core).
COMPILED_FROM = 8_000_000

_COMPILED = None


def grid_clean(t, lab, index, rows, cols, k, brick, known, beta, max_h, max_v):
    """True when the tiling ``t`` (``(n, 4)`` integers, legs W, N, E, S) passes every check.

    The cells are the board's in row-major order of its grid: ``lab`` holds their ``[row,
    col]`` labels, unless every cell of the ``rows x cols`` grid is present (``n = rows *
    cols``; then ``lab`` is not read). ``index`` (``(rows + 2) * (cols + 2)`` int32) is scratch
    space for a board with holes. A cell's W, N, E, S legs meet the E, S, W, N legs of the cells
    at ``(r, c-1)``, ``(r-1, c)``, ``(r, c+1)``, ``(r+1, c)``, or the wall where there is none;
    the wall legs are numbered in order of cell, then of leg N, E, S, W, and ``beta`` gives each
    its colour (``-1``: free). Colours are ``0..k-1``; tiles are brick tiles (``brick``: exactly
    one of W = E, N = S) or those whose key ``((W k + N) k + E) k + S`` is ``known``. ``max_h``
    / ``max_v`` (0: none) bound the runs of W = E cells along a row and of N = S cells down a
    column. Each cell is read once; the checks of a row are or-ed without branches and looked
    at once the row is done.
    """
    n = t.shape[0]
    full = n == rows * cols
    span = cols + 2  # the index grid has a border of -1 (the wall) all round
    if not full:
        index[:] = -1
        for i in range(n):
            index[(lab[i, 0] + 1) * span + lab[i, 1] + 1] = i
    hcap = max_h if max_h > 0 else n + 1
    vcap = max_v if max_v > 0 else n + 1
    vrun = np.zeros(cols, np.int64)
    nb = beta.shape[0]
    wall = 0
    i = 0
    for r in range(rows):
        bad = False
        hrun = 0
        for c in range(cols):
            if full:
                up = i - cols if r > 0 else -1
                left = i - 1 if c > 0 else -1
                edge = (r == 0) | (c == 0) | (r + 1 == rows) | (c + 1 == cols)
            else:
                p = (r + 1) * span + c + 1
                if index[p] < 0:
                    continue
                up, left = index[p - span], index[p - 1]
                edge = (up < 0) | (left < 0) | (index[p + 1] < 0) | (index[p + span] < 0)
            w = np.int64(t[i, 0])
            nn = np.int64(t[i, 1])
            e = np.int64(t[i, 2])
            s = np.int64(t[i, 3])
            if (w < 0) | (w >= k) | (nn < 0) | (nn >= k) | (e < 0) | (e >= k) | (s < 0) | (s >= k):
                return False  # before a colour is used as an index
            h = w == e
            v = nn == s
            if brick:
                bad |= h == v
            else:
                bad |= not known[((w * k + nn) * k + e) * k + s]
            bad |= (up >= 0) & (t[max(up, 0), 3] != nn)
            bad |= (left >= 0) & (t[max(left, 0), 2] != w)
            hrun = h * (1 + hrun * (left >= 0))
            vrun[c] = v * (1 + vrun[c] * (up >= 0))
            bad |= (hrun > hcap) | (vrun[c] > vcap)
            if edge:  # wall legs, in order N, E, S, W
                if full:
                    across = (up, i + 1 if c + 1 < cols else -1, i + cols if r + 1 < rows else -1, left)
                else:
                    across = (up, index[p + 1], index[p + span], left)
                for leg in range(4):
                    if across[leg] < 0:
                        if wall >= nb:
                            return False
                        colour = (nn, e, s, w)[leg]
                        bad |= (beta[wall] >= 0) & (beta[wall] != colour)
                        wall += 1
            i += 1
        if bad:
            return False
    return wall == nb


def compiled(n: int):
    """:func:`grid_clean` compiled by numba, when numba is loaded already or ``n`` cells pay for
    loading it (:data:`COMPILED_FROM`); None otherwise, or where numba cannot be loaded."""
    global _COMPILED
    if _COMPILED is None:
        if "numba" not in sys.modules and n < COMPILED_FROM:
            return None
        try:
            import numba
        except ImportError:  # pragma: no cover - numba is a dependency
            return None
        _COMPILED = numba.njit(cache=True, nogil=True)(grid_clean)
    return _COMPILED
