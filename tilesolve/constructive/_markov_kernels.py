"""Inner loop of the Markov-partition codings (see :mod:`tilesolve.constructive.markov`).

A block of the window is coded row by row. Row ``r`` meets the fundamental domain on the
horizontal line ``y = yp[r]``, inside slab ``slab[r]`` of the partition (a band between two
consecutive vertex heights, where the edges crossing it keep their left-to-right order). In
slab ``s`` the line cuts ``[0, Lx)`` at the breakpoints ``x0[s, k] + slope[s, k] * (y - ylo[s])``
(``k < nbreaks[s]``, the first ``0``, the last ``Lx``) into intervals coded ``labels[s, k]``.
Column ``c`` of the row is the point ``(u[r] + c * hx) mod Lx`` of that line.

Every cell is decided in float64 unless it lies within ``tol`` of a breakpoint (or its row
within ``tol`` of a slab boundary, ``slab[r] < 0``): such a cell gets :data:`FLAG` and the caller
decides it in exact arithmetic.

Callers take the function from ``KERNELS.pick(cells)``: plain Python on small windows,
numba-compiled on large ones, the same output on both (see :mod:`._jit`).
"""

from __future__ import annotations

import math

from tilesolve.constructive._jit import Kernels, kernel

#: The mark of a cell left to the exact path (no tile set here has 255 tiles).
FLAG = 255


@kernel(nogil=True)
def code_block(out, u, yp, slab, ylo, x0, slope, labels, nbreaks, hx, lx, tol, bp):
    """Code ``out[r, c]`` (uint8) for every row ``r`` and column ``c``; return the number of
    cells marked :data:`FLAG`. ``bp`` is float64 scratch of at least ``nbreaks.max()`` entries."""
    h, w = out.shape
    flagged = 0
    for r in range(h):
        s = slab[r]
        if s < 0:
            for c in range(w):
                out[r, c] = FLAG
            flagged += w
            continue
        nb = nbreaks[s]
        dy = yp[r] - ylo[s]
        for k in range(nb):
            bp[k] = x0[s, k] + slope[s, k] * dy
        ur = u[r]
        for c in range(w):
            t = ur + c * hx
            x = t - math.floor(t / lx) * lx
            k = 1
            while k < nb - 1 and x >= bp[k]:
                k += 1
            if x - bp[k - 1] < tol or bp[k] - x < tol:
                out[r, c] = FLAG
                flagged += 1
            else:
                out[r, c] = labels[s, k - 1]
    return flagged


#: Cells from which compiling pays (numba's import and cache load against about 1 us a cell
#: interpreted); ``benchmarks/bench_markov.py`` prints both paths.
THRESHOLD = 200_000

#: The plain and compiled namespaces of this module.
KERNELS = Kernels(globals(), THRESHOLD)
