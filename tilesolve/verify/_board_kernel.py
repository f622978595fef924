"""One pass of the board verifier over a tiling of a board cut from a grid with no sides
identified (a rectangle, a rectangle with holes, a ring), compiled by numba.

:func:`tilesolve.verify.board.board_violations` calls :func:`grid_clean` through
:func:`compiled` once a process has checked enough cells to pay for loading it
(:data:`COMPILED_FROM`); until then it checks the same with whole-array numpy operations. Written from the definitions (brick paper, Def. 2 and Def. 9; dappled paper §4)
with nothing shared with the solvers whose tilings it checks.
"""

from __future__ import annotations

import numpy as np

__all__ = ["COMPILED_FROM", "compiled", "grid_clean"]

#: Cells of numpy checks a process makes before it loads the compiled kernel instead (the
#: ski-rental rule): loading it from numba's cache costs 0.1-0.3 s (and importing numba, where
#: nothing did, 0.5 s more), while it saves 4-20 ns a cell against the numpy checks, so one
#: file or one solve never pays for it, but the bands of a large wall do.
COMPILED_FROM = 50_000_000

_numpy_cells = 0
_COMPILED = None


def grid_clean(t, present, rows, cols, k, brick, known, beta, max_h, max_v):
    """True when the tiling ``t`` (``(n, 4)`` integers, legs N, E, S, W) passes every check.

    The cells are the board's, numbered in row-major order of the ``rows x cols`` grid's cells
    ``present`` (a ``(rows, cols)`` 0/1 array, not read where every cell is: ``n = rows *
    cols``). A cell's N, E, S, W legs meet the S, W, N, E legs of the cells
    at ``(r-1, c)``, ``(r, c+1)``, ``(r+1, c)``, ``(r, c-1)``, or the wall where there is none;
    the wall legs are numbered in order of cell, then of leg N, E, S, W, and ``beta`` gives each
    its colour (``-1``: free). Colours are ``0..k-1``; tiles are brick tiles (``brick``: exactly
    one of W = E, N = S) or those whose key ``((N k + E) k + S) k + W`` is ``known``. ``max_h``
    / ``max_v`` (0: none) bound the runs of W = E cells along a row and of N = S cells down a
    column. Each cell is read once; the checks of a row are or-ed without branches and looked
    at once the row is done.
    """
    n = t.shape[0]
    full = n == rows * cols
    hcap = max_h if max_h > 0 else n + 1
    vcap = max_v if max_v > 0 else n + 1
    vrun = np.zeros(cols, np.int64)
    if full:  # the inside first (tiles, joins, lines), then the wall legs round the border
        for r in range(rows):
            bad = False
            hrun = 0
            for c in range(cols):
                i = r * cols + c
                nn = np.int64(t[i, 0])
                e = np.int64(t[i, 1])
                s = np.int64(t[i, 2])
                w = np.int64(t[i, 3])
                if (w < 0) | (w >= k) | (nn < 0) | (nn >= k) | (e < 0) | (e >= k) | (s < 0) | (s >= k):
                    return False  # before a colour is used as an index
                h = w == e
                v = nn == s
                if brick:
                    bad |= h == v
                else:
                    bad |= not known[((nn * k + e) * k + s) * k + w]
                if c > 0:
                    bad |= t[i - 1, 1] != w
                if r > 0:
                    bad |= t[i - cols, 2] != nn
                hrun = (hrun + 1) * h
                run = (vrun[c] + 1) * v
                vrun[c] = run
                bad |= (hrun > hcap) | (run > vcap)
            if bad:
                return False
        wall = 0
        for r in range(rows):
            for c in range(0, cols, 1 if r == 0 or r == rows - 1 else max(cols - 1, 1)):
                i = r * cols + c
                for leg, out in ((0, r == 0), (1, c == cols - 1), (2, r == rows - 1), (3, c == 0)):
                    if out:
                        if wall >= beta.shape[0]:
                            return False
                        if beta[wall] >= 0 and beta[wall] != t[i, leg]:
                            return False
                        wall += 1
        return wall == beta.shape[0]
    # a board with holes: its mask, row by row (cells are numbered in row-major order of it)
    if present.shape != (rows, cols):
        return False
    above = np.empty(cols, np.int64)  # the last cell seen in each column
    nb = beta.shape[0]
    wall = 0
    i = 0
    for r in range(rows):
        bad = False
        hrun = 0
        for c in range(cols):
            if not present[r, c]:
                continue
            if i >= n:
                return False
            up = np.int64(present[r - 1, c]) if r > 0 else np.int64(0)
            down = np.int64(present[r + 1, c]) if r + 1 < rows else np.int64(0)
            left = np.int64(present[r, c - 1]) if c > 0 else np.int64(0)
            right = np.int64(present[r, c + 1]) if c + 1 < cols else np.int64(0)
            nn = np.int64(t[i, 0])
            e = np.int64(t[i, 1])
            s = np.int64(t[i, 2])
            w = np.int64(t[i, 3])
            if (w < 0) | (w >= k) | (nn < 0) | (nn >= k) | (e < 0) | (e >= k) | (s < 0) | (s >= k):
                return False
            h = w == e
            v = nn == s
            if brick:
                bad |= h == v
            else:
                bad |= not known[((nn * k + e) * k + s) * k + w]
            if up:  # cells are numbered in row-major order: the cell above is the last one seen in
                bad |= t[above[c], 2] != nn  # its column, the cell to the left the one before
            if left:
                bad |= t[i - 1, 1] != w
            above[c] = i
            hrun = (hrun + 1) * h if left else np.int64(h)
            run = (vrun[c] + 1) * v if up else np.int64(v)
            vrun[c] = run
            bad |= (hrun > hcap) | (run > vcap)
            if not (up & right & down & left):  # wall legs, in order N, E, S, W
                for across, colour in ((up, nn), (right, e), (down, s), (left, w)):
                    if not across:
                        if wall >= nb:
                            return False
                        bad |= (beta[wall] >= 0) & (beta[wall] != colour)
                        wall += 1
            i += 1
        if bad:
            return False
    return i == n and wall == nb


def compiled(n: int):
    """:func:`grid_clean` compiled by numba, for a board of ``n`` cells: once loaded, or once
    this process has checked :data:`COMPILED_FROM` cells with numpy; None otherwise, or where
    numba cannot be loaded."""
    global _COMPILED, _numpy_cells
    if _COMPILED is None:
        _numpy_cells += n
        if _numpy_cells < COMPILED_FROM:
            return None
        try:
            from tilesolve._numba import numba
        except ImportError:  # pragma: no cover - numba is a dependency
            return None
        _COMPILED = numba.njit(cache=True, nogil=True)(grid_clean)
    return _COMPILED
