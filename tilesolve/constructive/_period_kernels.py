"""Inner loop of the lattice search (see :mod:`tilesolve.constructive.periods`).

Callers take the function from ``KERNELS.pick(work)``: plain Python on a few small lattices,
numba-compiled once the search has done more (see :mod:`._jit`); both give the same answer
and the same tiling.
"""

from __future__ import annotations

import numpy as np

from tilesolve.constructive._jit import Kernels, kernel


@kernel()
def lattice_tiling(col, rows, cols, shear, max_nodes, out):
    """Tile the sheared torus ``(rows, cols, shear)`` by backtracking with arc consistency.

    Cell ``r * cols + c`` is ``(r, c)``; its S leg meets the N leg of ``((r + 1) mod rows, c)``,
    and the E leg of ``(r, cols - 1)`` meets the W leg of ``((r + shear) mod rows, 0)``
    (:class:`tilesolve.model.aperiodic.Lattice`). Each cell keeps the set of tiles still
    possible; a set that changes removes, from each neighbour's set, the tiles whose facing leg
    has a colour that no tile left here has on this leg, until nothing changes (arc
    consistency). The search then fixes the cell with the fewest tiles left (more than one) to
    each of them in turn, depth first. When every set is one tile, neighbours match: a tiling.

    Parameters
    ----------
    col : numpy.ndarray
        ``(m, 4)`` int64 colours (N, E, S, W) of the ``m`` tiles, non-negative.
    rows, cols, shear : int
        The lattice (``0 <= shear < rows``).
    max_nodes : int
        How many tiles the search may fix before it gives up.
    out : numpy.ndarray
        ``(rows * cols,)`` int64: the tile of each cell when a tiling is found.

    Returns
    -------
    int
        ``1``: tiled (``out`` holds the tiling); ``0``: no tiling exists; ``-1``: the node
        budget ran out first (nothing is known).
    """
    m = col.shape[0]
    n = rows * cols
    nbr = np.empty((n, 4), np.int64)  # the neighbour across each leg N, E, S, W
    for a in range(n):
        r = a // cols
        c = a % cols
        nbr[a, 0] = ((r - 1) % rows) * cols + c
        nbr[a, 2] = ((r + 1) % rows) * cols + c
        nbr[a, 1] = a + 1 if c < cols - 1 else ((r + shear) % rows) * cols
        nbr[a, 3] = a - 1 if c > 0 else ((r - shear) % rows) * cols + cols - 1
    n_colours = 0
    for t in range(m):
        for k in range(4):
            n_colours = max(n_colours, col[t, k] + 1)
    levels = min(n, max_nodes) + 1
    dom = np.zeros((levels, n, m), np.bool_)  # the tiles left at each depth of the search
    dom[0, :, :] = True
    cell = np.zeros(levels, np.int64)  # the cell fixed at each depth
    tried = np.zeros(levels, np.int64)  # the last tile it was fixed to
    queue = np.empty(n, np.int64)  # cells whose sets changed (a ring: each at most once)
    queued = np.zeros(n, np.bool_)
    allowed = np.zeros(n_colours, np.bool_)
    head = 0
    size = n
    for a in range(n):
        queue[a] = a
        queued[a] = True
    depth = 0
    nodes = 0
    while True:
        d = dom[depth]
        ok = True
        while size > 0 and ok:
            a = queue[head]
            head = (head + 1) % n
            size -= 1
            queued[a] = False
            for k in range(4):
                b = nbr[a, k]
                kb = (k + 2) % 4
                allowed[:] = False
                for t in range(m):
                    if d[a, t]:
                        allowed[col[t, k]] = True
                left = 0
                changed = False
                for u in range(m):
                    if d[b, u]:
                        if allowed[col[u, kb]]:
                            left += 1
                        else:
                            d[b, u] = False
                            changed = True
                if left == 0:
                    ok = False
                    break
                if changed and not queued[b]:
                    queue[(head + size) % n] = b
                    size += 1
                    queued[b] = True
        if ok:
            best = -1
            fewest = m + 1
            for a in range(n):
                count = 0
                for t in range(m):
                    if d[a, t]:
                        count += 1
                if 1 < count < fewest:
                    best = a
                    fewest = count
            if best == -1:
                for a in range(n):
                    for t in range(m):
                        if d[a, t]:
                            out[a] = t
                return 1
            cell[depth] = best
            tried[depth] = -1
        else:
            queued[:] = False
            head = 0
            size = 0
            depth -= 1  # the tile fixed one level up failed
            if depth < 0:
                return 0
        while True:  # the next tile of the cell at this depth, else back up
            a = cell[depth]
            t = tried[depth] + 1
            while t < m and not dom[depth, a, t]:
                t += 1
            if t < m:
                break
            depth -= 1
            if depth < 0:
                return 0
        tried[depth] = t
        nodes += 1
        if nodes > max_nodes or depth + 1 >= levels:
            return -1
        dom[depth + 1, :, :] = dom[depth]
        dom[depth + 1, a, :] = False
        dom[depth + 1, a, t] = True
        depth += 1
        queue[0] = a
        head = 0
        size = 1
        queued[a] = True


#: Cells of lattices searched from which the compiled kernel pays: below it, a plain search
#: costs less than importing numba and loading the cached kernel.
THRESHOLD = 2_000

KERNELS = Kernels(globals(), THRESHOLD)
