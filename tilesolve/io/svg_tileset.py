"""SVG sheets of tile sets (svgwrite): the tiles of a :class:`~tilesolve.model.tiles.TileSet`
in index order, row-wrapped, each labelled with its index (the notes' Figs. 2.3, 2.4 and 3.2).

A Wang tile is drawn as four triangles (N, E, S, W) meeting at its centre, a corner tile as
four quarter squares (NE, SE, SW, NW), in the colours of :func:`tilesolve.io.svg_packing.colour_of`
(the notes' red, yellow, green, cyan, blue for colours 0..4).

Examples
--------
>>> from tilesolve.model.tiles import TileSet
>>> text = tileset_svg_string(TileSet("wang", 2, variant="compact"))
>>> text.startswith("<svg") and ">15<" in text
True
"""

from __future__ import annotations

import math
import os

import svgwrite

from tilesolve.errors import InvalidProblem
from tilesolve.io.atomic import atomic_write
from tilesolve.io.svg import titled_canvas
from tilesolve.io.svg_packing import colour_of
from tilesolve.model.tiles import TileSet

__all__ = ["MAX_SHEET_TILES", "tileset_drawing", "tileset_svg_string", "write_tileset_svg"]

#: Largest tile set drawn as a sheet (the limit of :func:`tilesolve.io.svg_packing.packing_drawing`).
MAX_SHEET_TILES = 65536


def _polygons(kind: str, x0: float, y0: float, px: float) -> list[tuple]:
    """The four coloured regions of a tile, in the order of the tile's colours."""
    x1, y1, xm, ym = x0 + px, y0 + px, x0 + px / 2, y0 + px / 2
    if kind == "wang":  # N E S W triangles
        return [((x0, y0), (x1, y0), (xm, ym)), ((x1, y0), (x1, y1), (xm, ym)),
                ((x1, y1), (x0, y1), (xm, ym)), ((x0, y1), (x0, y0), (xm, ym))]
    # NE SE SW NW quarters
    return [((xm, y0), (x1, y0), (x1, ym), (xm, ym)), ((xm, ym), (x1, ym), (x1, y1), (xm, y1)),
            ((x0, ym), (xm, ym), (xm, y1), (x0, y1)), ((x0, y0), (xm, y0), (xm, ym), (x0, ym))]


def tileset_drawing(tiles: TileSet, *, columns: int | None = None, cell: float = 40.0,
                    labels: bool = True, title: str | None = None) -> svgwrite.Drawing:
    """An svgwrite Drawing of every tile of ``tiles``, in :attr:`~TileSet.indices` order.

    Parameters
    ----------
    tiles : TileSet
    columns : int, optional
        Tiles per row (default: 8, or about the square root of the set's size for large sets).
    cell : float
        Side of a tile in px.
    labels : bool
        Write each tile's index under it.
    title : str, optional
        A line of text above the sheet (default: ``tiles.describe()``; ``""`` for none).
    """
    n = tiles.n_tiles
    if n > MAX_SHEET_TILES:
        raise InvalidProblem(f"{tiles.describe()} is too large for an SVG sheet (at most {MAX_SHEET_TILES:,} tiles)")
    if columns is None:
        columns = max(8, math.ceil(math.sqrt(n)))
    if columns < 1:
        raise InvalidProblem(f"columns must be >= 1, got {columns}")
    columns = min(columns, n)
    rows = math.ceil(n / columns)
    title = tiles.describe() if title is None else title
    gap = cell / 5
    label_h = cell * 0.4 if labels else 0.0
    step_x, step_y = cell + gap, cell + label_h + gap
    dwg, (ox, oy) = titled_canvas(columns * step_x - gap, rows * step_y - gap, title or None)
    move = f"translate({ox - gap:g},{oy - gap:g})"
    body = dwg.add(dwg.g(stroke="none", transform=move))
    lines = dwg.g(stroke="#222", stroke_width=max(0.4, cell / 40), fill="none", transform=move)
    text = dwg.g(font_size=cell * 0.3, text_anchor="middle", font_family="sans-serif", fill="#000", transform=move)
    for k, (index, colours) in enumerate(zip(tiles.indices.tolist(), tiles.table().tolist())):
        x0 = gap + (k % columns) * step_x
        y0 = gap + (k // columns) * step_y
        for pts, col in zip(_polygons(tiles.kind, x0, y0, cell), colours):
            body.add(dwg.polygon(pts, fill=colour_of(col)))
        lines.add(dwg.rect((x0, y0), (cell, cell)))
        if labels:
            text.add(dwg.text(str(index), insert=(x0 + cell / 2, y0 + cell + label_h * 0.8)))
    dwg.add(lines)
    if labels:
        dwg.add(text)
    return dwg


def tileset_svg_string(tiles: TileSet, **kwargs) -> str:
    """The SVG text of :func:`tileset_drawing`."""
    return tileset_drawing(tiles, **kwargs).tostring()


def write_tileset_svg(path: str | os.PathLike, tiles: TileSet, **kwargs) -> None:
    """Write the sheet atomically (the picture is built before the file is opened)."""
    text = tileset_svg_string(tiles, **kwargs)
    with atomic_write(path) as f:
        f.write(text)
