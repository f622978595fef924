"""Hot loops of the balanced-sequence windows (private; see ``balanced.py``).

A band of lines (rows of the tiling, top to bottom) is two passes over int arrays: the floors
``G[i, c] = floor(j x_i) - floor(x0 x_i)`` of each line from its fixed-point numbers, then
each cell's tile from the floors of its line and the line below.
"""

from __future__ import annotations

import numpy as np

from tilesolve.constructive._jit import Kernels, kernel

__all__ = ["floors_kernel", "tiles_kernel", "KERNELS"]


@kernel(nogil=True)
def floors_kernel(phi, off, xt, bits, chunk, G):
    """Fill ``G[i, c] = off[i, q] + (phi[i, q] + (c - q chunk) xt[i]) >> bits``, ``q = c // chunk``.

    ``phi`` and ``xt`` are ``floor(2**bits .)`` of the exact fraction at the chunk's start and
    of ``x``, so the exact value lies in ``[V, V + 1 + c')``, ``c' = c - q chunk``: where the low
    ``bits`` of ``V`` are within ``c' + 1`` of the next unit the floor is undecided, and ``G`` is
    set to -1 there for the caller to decide exactly. Returns the number of such cells.
    """
    rows, cols = G.shape
    one = np.int64(1) << np.int64(bits)
    mask = one - np.int64(1)
    undecided = 0
    for i in range(rows):
        x = xt[i]
        for q in range((cols + chunk - 1) // chunk):
            base = phi[i, q]
            o = off[i, q]
            c0 = q * chunk
            for c in range(c0, min(c0 + chunk, cols)):
                k = np.int64(c - c0)
                v = base + k * x
                if (v & mask) + k + np.int64(1) > one:
                    G[i, c] = -1
                    undecided += 1
                else:
                    G[i, c] = o + (v >> np.int64(bits))
    return undecided


@kernel(nogil=True)
def tiles_kernel(G, s0, pr, code, lut, out):
    """``out[i, c]``: the tile reading digit ``G[i, c+1] - G[i, c]``, writing ``G[i+1, c+1] -
    G[i+1, c]``, carry in ``s0[i] + p G[i, c] - r G[i+1, c]`` (``(p, r) = pr[i]``, shifted to
    index ``lut``), from ``lut[code[i]]``. Returns the number of cells with no tile (255 there)."""
    rows, cols = out.shape
    na, nb, ns = lut.shape[1], lut.shape[2], lut.shape[3]
    bad = 0
    for i in range(rows):
        p = pr[i, 0]
        r = pr[i, 1]
        s = s0[i]
        k = code[i]
        for c in range(cols):
            a = G[i, c + 1] - G[i, c]
            b = G[i + 1, c + 1] - G[i + 1, c]
            t = s + p * G[i, c] - r * G[i + 1, c]
            if 0 <= a < na and 0 <= b < nb and 0 <= t < ns:
                out[i, c] = lut[k, a, b, t]
            else:
                out[i, c] = 255
            if out[i, c] == 255:
                bad += 1
    return bad


KERNELS = Kernels(globals(), threshold=1 << 16)
