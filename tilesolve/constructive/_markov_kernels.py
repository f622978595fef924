"""Inner loop of the Markov-partition codings (see :mod:`tilesolve.constructive.markov`).

A block of the window is coded row by row. Row ``r`` meets the fundamental domain on the
horizontal line ``y = yp[r]``, inside slab ``slab[r]`` of the partition (a band between two
consecutive vertex heights, where the edges crossing it keep their left-to-right order). In
slab ``s`` the line cuts ``[0, lx)`` at the breakpoints ``x0[s, k] + slope[s, k] * (y - ylo[s])``
(``k < nbreaks[s]``, the first ``0``, the last ``lx``) into intervals coded ``labels[s, k]``.
Column ``c`` of the row is the point ``x = (u[r] + v[c]) mod lx`` of that line, where ``v[c]``
is ``c`` steps of the rotation (``c hx mod lx``), shared by the rows of the block.

A row first gets a *bucket table*: ``[0, lx)`` cut into equal bins (1024 compiled), each
holding the label of the interval that covers it with a margin of ``2 tol``, or :data:`FLAG`
where a breakpoint comes that close. Most cells then cost one look-up. A cell whose bin is
marked is located among the breakpoints; one that lies within ``tol`` of a breakpoint (or a
row within ``tol`` of a slab boundary, ``slab[r] < 0``) keeps :data:`FLAG`, and the caller
decides it in exact arithmetic. The table changes the speed only, never a label: a cell in an
unmarked bin is farther than ``tol`` from every breakpoint, where the located label is the
bin's.

Callers take the function from ``KERNELS.pick(cells)``: plain Python on small windows,
numba-compiled on large ones, the same output on both (see :mod:`._jit`).
"""

from __future__ import annotations

import math

from tilesolve.constructive._jit import Kernels, kernel

#: The mark of a cell left to the exact path (no tile set here has 255 tiles).
FLAG = 255


@kernel()
def fill_table(table, bp, nb, labels, lx, margin):
    """The bucket table of one row (module docstring) for the breakpoints ``bp[:nb]``, written
    twice: bins ``n .. 2n - 1`` cover ``[lx, 2 lx)`` as bins ``0 .. n - 1`` cover ``[0, lx)``,
    so a point ``u + v`` of ``[0, 2 lx)`` needs no reduction; the last entry is :data:`FLAG`."""
    nbins = (table.shape[0] - 1) // 2
    width = lx / nbins
    for i in range(2 * nbins + 1):
        table[i] = FLAG
    for k in range(nb - 1):
        lo = max(0, int(math.ceil((bp[k] + margin) / width)))
        hi = min(nbins, int(math.floor((bp[k + 1] - margin) / width)))
        for i in range(lo, hi):
            table[i] = labels[k]
            table[i + nbins] = labels[k]


@kernel()
def locate(x, bp, nb, labels, tol):
    """The label of the interval holding ``x``, or :data:`FLAG` within ``tol`` of its ends."""
    k = 1
    while k < nb - 1 and x >= bp[k]:
        k += 1
    if x - bp[k - 1] < tol or bp[k] - x < tol:
        return FLAG
    return labels[k - 1]


@kernel(nogil=True)
def code_block(out, v, u, yp, slab, ylo, x0, slope, labels, nbreaks, lx, tol, bp, table, todo):
    """Code ``out[r, c]`` (uint8) for every row ``r`` and column ``c``; return the number of
    cells left :data:`FLAG`. ``bp`` (float64, ``nbreaks.max()`` entries), ``table`` (uint8,
    2 bins + 1) and ``todo`` (int64, ``out.shape[1]`` entries) are scratch."""
    h, w = out.shape
    scale = ((table.shape[0] - 1) // 2) / lx
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
        fill_table(table, bp, nb, labels[s], lx, 2 * tol)
        ur = u[r]
        m = 0
        for c in range(w):
            lab = table[int((v[c] + ur) * scale)]
            out[r, c] = lab
            if lab == FLAG:
                todo[m] = c
                m += 1
        for j in range(m):
            c = todo[j]
            x = v[c] + ur
            x = x - lx if x >= lx else x
            lab = locate(x, bp, nb, labels[s], tol)
            out[r, c] = lab
            if lab == FLAG:
                flagged += 1
    return flagged


#: Cells from which compiling pays: numba's import and cache load cost about 0.8 s of CPU on a
#: loaded machine, the interpreted kernel about 4 us a cell (measured on a 300x300 window).
THRESHOLD = 200_000

#: The plain and compiled namespaces of this module.
KERNELS = Kernels(globals(), THRESHOLD)
