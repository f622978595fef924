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
def floors_kernel(phi, off, xt, bits, chunk, zero, G, where):
    """Fill ``G[i, c] = off[i, q] + (phi[i, q] + k xt[i]) >> bits``, ``q = c // chunk``,
    ``k = c - q chunk``.

    ``phi`` and ``xt`` are ``floor(2**bits .)`` of the exact fraction at the chunk's start and
    of ``x``, so the exact value lies in ``[V, V + 1 + k)``, ``V = phi + k xt``: where the low
    ``bits`` of ``V`` are within ``k + 1`` of the next unit the floor is undecided. Those cells
    but column ``zero`` (``j = 0``, which the caller fills) are listed in ``where`` (as ``i *
    G.shape[1] + c``, as many as it holds) for the caller to decide exactly. Returns how many
    there are. A chunk is filled branch-free and searched again only if it holds one.
    """
    rows, cols = G.shape
    mask = (np.int64(1) << np.int64(bits)) - np.int64(1)
    sh = np.int64(bits)
    undecided = 0
    for i in range(rows):
        x = xt[i]
        g = G[i]
        for q in range((cols + chunk - 1) // chunk):
            base = phi[i, q]
            o = np.int32(off[i, q])
            c0 = q * chunk
            n = min(chunk, cols - c0)
            flag = False
            for k in range(n):
                v = base + k * x
                g[c0 + k] = o + np.int32(v >> sh)
                flag |= ((v & mask) + k > mask) & (c0 + k != zero)
            if flag:
                for k in range(n):
                    v = base + k * x
                    if (v & mask) + k > mask and c0 + k != zero:
                        if undecided < where.shape[0]:
                            where[undecided] = i * cols + c0 + k
                        undecided += 1
    return undecided


@kernel(nogil=True)
def tiles_kernel(G, s0, pr, code, lut, out):
    """``out[i, c]``: the tile reading digit ``a = G[i, c+1] - G[i, c]``, writing ``b = G[i+1,
    c+1] - G[i+1, c]``, carry in ``t = s0[i] + p G[i, c] - r G[i+1, c]`` (``(p, r) = pr[i]``,
    ``s0`` shifted so that ``t >= 0``): ``lut[64 code[i] + 16 a + 4 b + t]``.

    The key ``16 a + 4 b + t`` is one linear form of the four floors (a vectorisable pass),
    then a table look-up. Returns the number of rows with a key outside ``0..63`` or a cell
    with no tile (255); the look-up stays inside the row's table whatever the floors.
    """
    rows, cols = out.shape
    key = np.empty(cols, np.int32)
    bad = 0
    for i in range(rows):
        k = code[i] * 64
        s = np.int32(s0[i])
        pa = np.int32(pr[i, 0]) - np.int32(16)
        rb = np.int32(pr[i, 1]) + np.int32(4)
        top = G[i]
        bottom = G[i + 1]
        o = out[i]
        chk = np.int32(0)
        for c in range(cols):
            kk = (top[c + 1] << 4) + pa * top[c] + (bottom[c + 1] << 2) - rb * bottom[c] + s
            key[c] = kk
            chk |= kk
        worst = np.uint8(0)
        for c in range(cols):
            tile = lut[k + (key[c] & 63)]
            o[c] = tile
            worst = max(worst, tile)
        if (chk & ~np.int32(63)) or worst == 255:
            bad += 1
    return bad


KERNELS = Kernels(globals(), threshold=1 << 17)
