"""SVG pictures of Wang tilings of boards (svgwrite).

* Brick walls (brick Wang tiles, Def. 9 of the brick paper) are drawn as bricks: in each
  cell a leg's colour is the position of a brick edge on that side (colour ``c`` of
  ``#C`` at ``(c + 1) / (#C + 1)`` of the side); a W_H tile has a horizontal mortar line
  through the cell and two half vertical ones, a W_V tile the converse. Every cell holds
  the corners of four bricks; corners that touch across a join are merged (union-find)
  into whole bricks, each filled with a colour from its id.
* Any other tile set is drawn as Wang tiles: four triangles per cell, one per leg colour.
* Cells are placed by their ``[row, col]`` labels; holes stay empty (hatched). Joins that
  leave the rectangle (torus, cylinder, Möbius strip, Klein bottle) are marked with
  arrows on the identified sides: same direction for a plain identification, opposite
  directions for a twisted one (Example 5).
* A tiling cut from the plane (a window of a procedural or repeatable wall) carries its
  window's coordinates in the legend (:meth:`tilesolve.model.window.Window.caption`).
"""

from __future__ import annotations

import math
import os

import numpy as np

from tilesolve.io.svg import MAX_SVG_CELLS, add_caption, canvas, caption_box, tile_colour
from tilesolve.model.board import E, S, BoardProblem
from tilesolve.model.window import Window

__all__ = ["board_drawing", "write_board_svg", "brick_ids"]

_PX = 720


def brick_ids(problem: BoardProblem, tiling) -> np.ndarray:
    """``(n_cells, 4)`` brick id of each cell's corner regions TL, TR, BL, BR.

    Regions are merged across joins between cells whose labels are grid neighbours
    (E-W: TR~TL, BR~BL; S-N: BL~TL, BR~TR).
    """
    from networkx.utils import UnionFind

    b = problem.board
    n = b.n_cells
    uf = UnionFind(range(4 * n))
    lab = b.labels
    TL, TR, BL, BR = 0, 1, 2, 3
    for a in range(n):
        for k, pairs, dr, dc in ((E, ((TR, TL), (BR, BL)), 0, 1), (S, ((BL, TL), (BR, TR)), 1, 0)):
            w = int(b.nbr_cell[a, k])
            if w < 0 or b.nbr_leg[a, k] != (k + 2) % 4:
                continue
            if lab[w, 0] - lab[a, 0] != dr or lab[w, 1] - lab[a, 1] != dc:
                continue  # a join across a seam: drawn as an identification, not merged
            for x, y in pairs:
                uf.union(4 * a + x, 4 * w + y)
    roots = np.array([uf[i] for i in range(4 * n)])
    _, ids = np.unique(roots, return_inverse=True)
    return ids.reshape(n, 4)


def board_drawing(problem: BoardProblem, tiling, *, title: str | None = None, notes=(), window: Window | None = None):
    """An :class:`svgwrite.Drawing` of ``tiling`` on ``problem.board``; ``window``, where the
    tiling lies in the plane, adds its coordinates to the legend."""
    b = problem.board
    t = np.asarray(tiling, dtype=np.int64)
    if b.n_cells > MAX_SVG_CELLS:
        from tilesolve.errors import InvalidProblem

        raise InvalidProblem(f"a board of {b.n_cells:,} cells is too large for an SVG (limit {MAX_SVG_CELLS:,})")
    rows = int(b.labels[:, 0].max()) + 1
    cols = int(b.labels[:, 1].max()) + 1
    cell = max(2.0, min(40.0, _PX / max(rows, cols)))
    m = 24.0
    legend = ([title] if title else []) + ([window.caption()] if window is not None else []) + list(notes)
    text_w, text_h = caption_box(legend)
    W, H = max(cols * cell, text_w) + 2 * m, rows * cell + 2 * m + text_h
    d = canvas(math.ceil(W), math.ceil(H))
    pat = d.pattern(id="holes", size=(6, 6), patternUnits="userSpaceOnUse")
    pat.add(d.rect((0, 0), (6, 6), fill="#FFFFFF"))
    pat.add(d.line((0, 6), (6, 0), stroke="#BBBBBB", stroke_width=1))
    d.defs.add(pat)
    d.add(d.rect((m, m), (cols * cell, rows * cell), fill="url(#holes)"))
    k = problem.n_colors
    pos = lambda c: (c + 1) / (k + 1) * cell  # noqa: E731
    if problem.tileset.is_brick:
        ids = brick_ids(problem, t)
        fills = d.add(d.g(stroke="none"))
        lines = d.add(d.g(stroke="#333333", stroke_width=max(0.6, cell / 14), stroke_linecap="square"))
        for a in range(b.n_cells):
            y0 = m + b.labels[a, 0] * cell
            x0 = m + b.labels[a, 1] * cell
            n_, e_, s_, w_ = (pos(int(c)) for c in t[a])
            if t[a, 3] == t[a, 1]:  # W_H (W = E): horizontal line at w_
                rects = [(0, 0, n_, w_), (n_, 0, cell - n_, w_), (0, w_, s_, cell - w_), (s_, w_, cell - s_, cell - w_)]
                segs = [((0, w_), (cell, w_)), ((n_, 0), (n_, w_)), ((s_, w_), (s_, cell))]
            else:  # W_V: vertical line at n_
                rects = [(0, 0, n_, w_), (n_, 0, cell - n_, e_), (0, w_, n_, cell - w_), (n_, e_, cell - n_, cell - e_)]
                segs = [((n_, 0), (n_, cell)), ((0, w_), (n_, w_)), ((n_, e_), (cell, e_))]
            for r, (rx, ry, rw, rh) in enumerate(rects):
                fills.add(d.rect((x0 + rx, y0 + ry), (max(rw, 0), max(rh, 0)),
                                 fill=_brick_colour(int(ids[a, r]))))
            for (ax, ay), (bx, by) in segs:
                lines.add(d.line((x0 + ax, y0 + ay), (x0 + bx, y0 + by)))
    else:
        g = d.add(d.g(stroke="#FFFFFF", stroke_width=0.5))
        for a in range(b.n_cells):
            y0 = m + b.labels[a, 0] * cell
            x0 = m + b.labels[a, 1] * cell
            cx, cy = x0 + cell / 2, y0 + cell / 2
            corners = [(x0, y0), (x0 + cell, y0), (x0 + cell, y0 + cell), (x0, y0 + cell)]
            for leg in range(4):  # N: top-left..top-right, E: top-right..bottom-right, ...
                p1, p2 = corners[leg], corners[(leg + 1) % 4]
                g.add(d.polygon([p1, p2, (cx, cy)], fill=tile_colour(int(t[a, leg]))))
    _identifications(d, problem, rows, cols, cell, m)
    add_caption(d, legend, m, rows * cell + 2 * m - 2)
    return d


def _brick_colour(i: int) -> str:
    hue = (0.07 + 0.618034 * i) % 1.0
    import colorsys

    r, g, bl = colorsys.hls_to_rgb(hue, 0.55 + 0.12 * ((i * 7) % 3 - 1), 0.45)
    return "#{:02X}{:02X}{:02X}".format(round(r * 255), round(g * 255), round(bl * 255))


def _identifications(d, problem, rows, cols, cell, m) -> None:
    """Arrows on sides joined across the picture (plain: same way; twisted: opposite)."""
    b = problem.board
    lab = b.labels
    for k, side in ((E, "cols"), (S, "rows")):
        a = np.flatnonzero(b.nbr_cell[:, k] >= 0)
        w = b.nbr_cell[a, k]
        dr = lab[w, 0] - lab[a, 0]
        dc = lab[w, 1] - lab[a, 1]
        seam = (dr != (1 if k == S else 0)) | (dc != (1 if k == E else 0))
        if not seam.any():
            continue
        aa, ww = a[seam], w[seam]
        if k == E:
            twisted = bool((lab[ww, 0] != lab[aa, 0]).any())
            x1, x2 = m - 10, m + cols * cell + 10
            _arrow(d, x1, m, x1, m + rows * cell, "#D55E00")
            if twisted:
                _arrow(d, x2, m + rows * cell, x2, m, "#D55E00")
            else:
                _arrow(d, x2, m, x2, m + rows * cell, "#D55E00")
        else:
            twisted = bool((lab[ww, 1] != lab[aa, 1]).any())
            y1, y2 = m - 10, m + rows * cell + 10
            _arrow(d, m, y1, m + cols * cell, y1, "#0072B2")
            if twisted:
                _arrow(d, m + cols * cell, y2, m, y2, "#0072B2")
            else:
                _arrow(d, m, y2, m + cols * cell, y2, "#0072B2")


def _arrow(d, x1, y1, x2, y2, colour) -> None:
    d.add(d.line((x1, y1), (x2, y2), stroke=colour, stroke_width=2))
    dx, dy = x2 - x1, y2 - y1
    L = max((dx * dx + dy * dy) ** 0.5, 1e-9)
    ux, uy = dx / L, dy / L
    mx, my = x1 + dx * 0.55, y1 + dy * 0.55
    p = [(mx + 7 * ux, my + 7 * uy), (mx - 5 * ux + 5 * uy, my - 5 * uy - 5 * ux), (mx - 5 * ux - 5 * uy, my - 5 * uy + 5 * ux)]
    d.add(d.polygon(p, fill=colour))


def write_board_svg(path: str | os.PathLike, problem: BoardProblem, tiling, **kwargs) -> None:
    """Write :func:`board_drawing` atomically."""
    from tilesolve.io.atomic import write_text_atomic

    write_text_atomic(path, board_drawing(problem, tiling, **kwargs).tostring())
