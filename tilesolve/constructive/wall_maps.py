"""Per-pixel maps of brick walls: brick ids, distance to the brick edges, Cartesian UV (004 §3.2).

The geometry (004 §3.1, Fig. 5 and 7)
-------------------------------------
A leg colour ``k`` of ``nc`` is the position of a brick edge on that side of the cell, at
``p(k) = (k + 1) / (nc + 1)`` of the side (from the left on the N and S sides, from the top
on the W and E sides; the same drawing as :mod:`tilesolve.io.svg_board`). A horizontal tile
(``W = E``) has a mortar line across the cell at ``p(W)`` and two half lines: down from the
top at ``p(N)`` and up from the bottom at ``p(S)``; a vertical tile the converse. Each cell
thus holds one corner of four bricks (its TL, TR, BL and BR regions), and the corner regions
that touch across a cell side belong to the same brick.

So every brick is the brick *around one lattice vertex*: the vertex shared by the four cells
whose BR, BL, TR, TL regions it is (004 §3.1: "each tile models the corner junctions of four
bricks"). With ``N[r, c]`` and ``E[r, c]`` the leg positions of cell ``(r, c)`` (row 0 at the
top), the brick around the vertex at the top-left corner of cell ``(a, b)`` is the rectangle

    x in [b - 1 + p(N[a, b - 1]), b + p(N[a, b])],   y in [a - 1 + p(E[a - 1, b - 1]), a + p(E[a, b - 1])]

(cell units, ``y`` down). A pixel's brick, and with it its distance to the brick's edges and
its Cartesian UV coordinates inside the brick (Fig. 10, left), therefore needs the cells one
step around its own: maps of a window need a *halo* of one cell on every side, and strips of
a large wall can be computed one at a time (:func:`tilesolve.families.wall_render.write_wall_png`).

Brick ids are the absolute lattice coordinates ``(X, Y)`` of the brick's vertex (``Y`` grows
north, as the wall's ``j``): the same brick has the same id, and so the same colour, in every
window of the wall (Fig. 9 (b), "a color based on the brick id";
:func:`tilesolve.model.brick_colour.brick_colour_index`, which the board pictures share).

Examples
--------
>>> import numpy as np
>>> legs = np.zeros((3, 3, 4), dtype=np.int8)   # halo around one cell: all horizontal tiles ...
>>> legs[..., 0], legs[..., 2] = 0, 2            # ... with N at 1/4 and S at 3/4 of the cell
>>> m = wall_maps(legs, 3, 4, origin=(10, 20))
>>> m.vx.shape, sorted(set(zip(m.vx.ravel().tolist(), m.vy.ravel().tolist())))
((4, 4), [(10, 20), (10, 21), (11, 20), (11, 21)])
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tilesolve.errors import InvalidProblem

__all__ = ["WallMaps", "wall_maps", "MAPS"]

#: The maps :func:`wall_maps` computes, by the names the CLI uses (``--map``).
MAPS = ("id", "distance", "uv")


@dataclass(frozen=True)
class WallMaps:
    """The per-pixel maps of a window (``(H, W)`` arrays, ``H = rows * ppc``, row 0 at the top).

    Attributes
    ----------
    vx, vy : numpy.ndarray of int64
        The brick id: absolute lattice coordinates of the brick's vertex (``vy`` grows north).
    distance : numpy.ndarray of float64
        Distance from the pixel's centre to the nearest edge of its brick, in cells.
    u, v : numpy.ndarray of float64
        Cartesian UV coordinates inside the brick (004 Fig. 10, left): ``u`` from 0 at the
        brick's west edge to 1 at its east edge, ``v`` from 0 at its south edge to 1 at its
        north edge.
    """

    vx: np.ndarray
    vy: np.ndarray
    distance: np.ndarray
    u: np.ndarray
    v: np.ndarray


def _positions(legs: np.ndarray, colors: int) -> np.ndarray:
    """Leg positions ``p(k) = (k + 1) / (nc + 1)`` (float64, computed as ``(k + 1) * (1 / (nc + 1))``
    like the compiled loop), same shape as ``legs``."""
    return (legs.astype(np.float64) + 1.0) * (1.0 / (colors + 1))


def wall_maps(legs, colors: int, ppc: int, *, origin: tuple[int, int] = (0, 0)) -> WallMaps:
    """The maps of the inner cells of ``legs`` (a window with a one-cell halo), ``ppc`` pixels per cell.

    Parameters
    ----------
    legs : array-like of int, shape (rows + 2, cols + 2, 4)
        Leg colours (N, E, S, W) of a brick wall window and the ring of cells around it, row
        0 at the top (e.g. :func:`tilesolve.constructive.walls.wall_window` of the window
        grown by one cell on every side).
    colors : int
        ``nc``, the number of leg colours.
    ppc : int
        Pixels per cell side (pixel centres sample the cell at ``(k + 0.5) / ppc``).
    origin : (int, int)
        Absolute coordinates ``(i, j)`` (``j`` north) of the bottom-left *inner* cell, so that
        brick ids are the vertices' absolute coordinates.

    Returns
    -------
    WallMaps
        ``(rows * ppc, cols * ppc)`` arrays.
    """
    t = np.asarray(legs)
    if t.ndim != 3 or t.shape[2] != 4 or t.shape[0] < 3 or t.shape[1] < 3:
        raise InvalidProblem(f"wall maps need a (rows + 2, cols + 2, 4) legs array with a one-cell halo, got {t.shape}")
    ppc = int(ppc)
    if ppc < 1:
        raise InvalidProblem(f"pixels per cell must be at least 1, got {ppc}")
    rows, cols = t.shape[0] - 2, t.shape[1] - 2
    inner = t[1:-1, 1:-1]
    p = _positions(inner, colors)
    pn, pe, ps, pw = (p[..., k][:, None, :, None] for k in range(4))
    hor = (inner[..., 3] == inner[..., 1])[:, None, :, None]
    s = (np.arange(ppc, dtype=np.float64) + 0.5) / ppc
    uu, vv = s[None, None, None, :], s[None, :, None, None]
    # Which corner region of its cell each pixel is in (module docstring; 004 Fig. 7).
    top_h = vv < pw
    left = np.where(hor, uu < np.where(top_h, pn, ps), uu < pn)
    top = np.where(hor, top_h, vv < np.where(left, pw, pe))
    r = np.arange(rows)[:, None, None, None]
    c = np.arange(cols)[None, None, :, None]
    # The pixel's brick is the one around halo vertex (ai + 1, bi + 1) (module docstring).
    da, db = (~top).astype(np.int64), (~left).astype(np.int64)
    ai, bi = r + da, c + db
    pn_all, pe_all = _positions(t[..., 0], colors), _positions(t[..., 1], colors)
    # Its edges relative to the pixel's own cell (translation-invariant arithmetic: a cell's
    # pixels are the same in every window and every band).
    lft = (db - 1) + pn_all[ai + 1, bi]
    rgt = db + pn_all[ai + 1, bi + 1]
    tp = (da - 1) + pe_all[ai, bi]
    bot = da + pe_all[ai + 1, bi]
    x, y = uu, vv
    dist = np.minimum(np.minimum(x - lft, rgt - x), np.minimum(y - tp, bot - y))
    u = (x - lft) / (rgt - lft)
    v = (bot - y) / (bot - tp)
    x0, y0 = (int(q) for q in origin)
    # index (ai, bi) is halo vertex (ai + 1, bi + 1), the top-left corner of the wall cell
    # (x0 + bi, y0 + rows - 1 - ai): lattice point (x0 + bi, y0 + rows - ai).
    vx = np.int64(x0) + bi
    vy = np.int64(y0 + rows) - ai
    out = [q.reshape(rows * ppc, cols * ppc) for q in np.broadcast_arrays(vx, vy, dist, u, v)]
    return WallMaps(*out)
