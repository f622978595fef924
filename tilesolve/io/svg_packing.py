"""SVG pictures of tile packings (svgwrite): tiles drawn with their colours, indices optional.

A Wang tile is four triangles, one per edge, meeting at the tile's centre; a corner tile is
four quarter squares, one per corner (the notes' Figs. 2.3-2.6 style). Colours 0..4 use the
notes' red, yellow, green, cyan, blue (§2.7), then :func:`tilesolve.io.svg.tile_colour`.

Examples
--------
>>> import numpy as np
>>> text = packing_svg_string(np.arange(16).reshape(4, 4), "corner", 2, indices=True)
>>> text.startswith("<svg") and ">15<" in text
True
"""

from __future__ import annotations

import os

import numpy as np
import svgwrite

from tilesolve.errors import InvalidProblem
from tilesolve.io.atomic import atomic_write
from tilesolve.io.svg import tile_colour, titled_canvas
from tilesolve.model.tiles import TileSet

__all__ = ["NOTES_COLOURS", "MAX_SVG_TILES", "colour_of", "packing_drawing", "packing_svg_string", "write_packing_svg"]

#: §2.7: "red, yellow, green, cyan and blue for respectively 0, 1, 2, 3 and 4".
NOTES_COLOURS = ("#E53935", "#FDD835", "#43A047", "#26C6DA", "#1E88E5")

_MAX_SIDE = 4096  # tiles; C = 64 packings are 4096 x 4096

#: Most tiles drawn in one SVG (C = 16 packings have 65,536 tiles).
MAX_SVG_TILES = 65536


def colour_of(k: int) -> str:
    return NOTES_COLOURS[k] if k < len(NOTES_COLOURS) else tile_colour(k + 3)


def packing_drawing(grid, kind: str, colors: int, *, colors_v: int | None = None, indices: bool = False,
                    title: str | None = None, cell: float | None = None) -> svgwrite.Drawing:
    """An svgwrite Drawing of a packing (``grid[row, col]``, row 0 at the top)."""
    g = np.asarray(grid, dtype=np.int64)
    rows, cols = g.shape
    if rows * cols > MAX_SVG_TILES:
        raise InvalidProblem(f"a {rows}x{cols} packing is too large for SVG (at most {MAX_SVG_TILES:,} tiles)")
    ts = TileSet(kind, colors, colors_v)
    a, b, c, d = ts.colors_of(g)
    px = cell or max(6.0, min(48.0, 720.0 / max(rows, cols)))
    dwg, (ox, oy) = titled_canvas(cols * px, rows * px, title)
    body = dwg.add(dwg.g(stroke="none", transform=f"translate({ox:g},{oy:g})"))
    lines = dwg.g(stroke="#222", stroke_width=max(0.4, px / 40), fill="none", transform=f"translate({ox:g},{oy:g})")
    labels = dwg.g(font_size=px * 0.32, text_anchor="middle", font_family="sans-serif", fill="#000",
                   font_weight="bold", transform=f"translate({ox:g},{oy:g})")
    for r in range(rows):
        for q in range(cols):
            x0, y0 = q * px, r * px
            x1, y1, xm, ym = x0 + px, y0 + px, x0 + px / 2, y0 + px / 2
            if kind == "wang":  # N E S W triangles
                polys = [((x0, y0), (x1, y0), (xm, ym)), ((x1, y0), (x1, y1), (xm, ym)),
                         ((x1, y1), (x0, y1), (xm, ym)), ((x0, y1), (x0, y0), (xm, ym))]
            else:  # NE SE SW NW quarters
                polys = [((xm, y0), (x1, y0), (x1, ym), (xm, ym)), ((xm, ym), (x1, ym), (x1, y1), (xm, y1)),
                         ((x0, ym), (xm, ym), (xm, y1), (x0, y1)), ((x0, y0), (xm, y0), (xm, ym), (x0, ym))]
            for pts, col in zip(polys, (a[r, q], b[r, q], c[r, q], d[r, q])):
                body.add(dwg.polygon(pts, fill=colour_of(int(col))))
            lines.add(dwg.rect((x0, y0), (px, px)))
            if indices:
                labels.add(dwg.text(str(int(g[r, q])), insert=(xm, ym + px * 0.12)))
    dwg.add(lines)
    if indices:
        dwg.add(labels)
    return dwg


def packing_svg_string(grid, kind: str, colors: int, **kwargs) -> str:
    return packing_drawing(grid, kind, colors, **kwargs).tostring()


def write_packing_svg(path: str | os.PathLike, grid, kind: str, colors: int, **kwargs) -> None:
    """Write the picture atomically."""
    text = packing_svg_string(grid, kind, colors, **kwargs)
    with atomic_write(path) as f:
        f.write(text)
