"""Compiled per-pixel loop of the wall maps (:mod:`tilesolve.constructive.wall_maps`).

The same arithmetic as :func:`tilesolve.constructive.wall_maps.wall_maps` followed by
:func:`tilesolve.io.wall_png.map_pixels`, one pixel at a time in float64, without the
intermediate arrays: the streamed PNG path calls it band by band. Tests compare both forms
pixel for pixel.
"""

from __future__ import annotations

import numpy as np

from tilesolve._numba import njit

#: ``kind`` codes of :func:`map_band`.
KIND_ID, KIND_DISTANCE, KIND_UV = 0, 1, 2

_M1 = np.uint64(0x9E3779B97F4A7C15)
_M2 = np.uint64(0xC2B2AE3D27D4EB4F)
_M3 = np.uint64(0xBF58476D1CE4E5B9)
_M4 = np.uint64(0x94D049BB133111EB)


@njit(cache=True)
def colour_of_vertex(vx, vy, n):
    """:func:`tilesolve.model.brick_colour.brick_colour_index` of one vertex."""
    z = np.uint64(vx) * _M1 ^ np.uint64(vy) * _M2
    z = (z ^ (z >> np.uint64(30))) * _M3
    z = (z ^ (z >> np.uint64(27))) * _M4
    z ^= z >> np.uint64(31)
    return np.int64(((z >> np.uint64(32)) * np.uint64(n)) >> np.uint64(32))


@njit(cache=True)
def map_band(legs, nc, ppc, x0, y0, kind, n_colours, mortar, mortar_px, distance_full, out):
    """Fill ``out`` with the pixels of the inner cells of ``legs`` (a window with a one-cell halo).

    ``(x0, y0)`` is the bottom-left inner cell; ``out`` is ``(rows * ppc, cols * ppc, planes)``
    uint8: one plane for ``id`` and ``distance``, three for ``uv``.
    """
    rows = legs.shape[0] - 2
    cols = legs.shape[1] - 2
    q = 1.0 / (nc + 1)
    for r in range(rows):
        for c in range(cols):
            n_ = (legs[r + 1, c + 1, 0] + 1.0) * q
            e_ = (legs[r + 1, c + 1, 1] + 1.0) * q
            s_ = (legs[r + 1, c + 1, 2] + 1.0) * q
            w_ = (legs[r + 1, c + 1, 3] + 1.0) * q
            hor = legs[r + 1, c + 1, 3] == legs[r + 1, c + 1, 1]
            for py in range(ppc):
                vv = (py + 0.5) / ppc
                for px in range(ppc):
                    uu = (px + 0.5) / ppc
                    if hor:
                        top = vv < w_
                        left = uu < (n_ if top else s_)
                    else:
                        left = uu < n_
                        top = vv < (w_ if left else e_)
                    da = 0 if top else 1
                    db = 0 if left else 1
                    ai = r + da  # the brick around halo vertex (ai + 1, bi + 1)
                    bi = c + db
                    # its edges relative to the pixel's own cell, as in wall_maps
                    lft = (db - 1) + (legs[ai + 1, bi, 0] + 1.0) * q
                    rgt = db + (legs[ai + 1, bi + 1, 0] + 1.0) * q
                    tp = (da - 1) + (legs[ai, bi, 1] + 1.0) * q
                    bot = da + (legs[ai + 1, bi, 1] + 1.0) * q
                    x = uu
                    y = vv
                    d = min(min(x - lft, rgt - x), min(y - tp, bot - y))
                    oy = r * ppc + py
                    ox = c * ppc + px
                    if kind == 0:
                        if mortar_px > 0 and d * ppc < mortar_px:
                            out[oy, ox, 0] = mortar
                        else:
                            out[oy, ox, 0] = colour_of_vertex(x0 + bi, y0 + rows - ai, n_colours)
                    elif kind == 1:
                        out[oy, ox, 0] = min(int(d * (255.0 / distance_full) + 0.5), 255)
                    else:
                        u = (x - lft) / (rgt - lft)
                        v = (bot - y) / (bot - tp)
                        out[oy, ox, 0] = min(max(int(u * 255 + 0.5), 0), 255)
                        out[oy, ox, 1] = min(max(int(v * 255 + 0.5), 0), 255)
                        out[oy, ox, 2] = 0
