"""Pictures of polyform answers: tilings of regions and tori (a few periods of a torus tiling)
and corona patches (coloured by corona), as SVG (svgwrite) or PNG (Pillow).

Pieces are rows ``(piece, label, x, y)`` (:mod:`tilesolve.io.shapes_json`); every cell is drawn
as its polygon (:meth:`tilesolve.model.shapes.Grid.vertices`), filled with its piece's colour
(:func:`tilesolve.io.svg.tile_colour`), and the pieces' outlines are drawn on top.
"""

from __future__ import annotations

import os

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.io.atomic import atomic_write
from tilesolve.io.svg import tile_colour, titled_canvas
from tilesolve.model.shapes import Grid

__all__ = ["MAX_PICTURE_CELLS", "periodic_rows", "shapes_svg_string", "write_shapes_picture"]

#: The most cells a picture draws.
MAX_PICTURE_CELLS = 50_000
_PX = 24.0


def periodic_rows(g: Grid, rows: np.ndarray, lattice, repeat: int = 3) -> np.ndarray:
    """The torus tiling ``rows`` repeated over ``repeat x repeat`` periods (pieces renumbered,
    colours kept per piece of the period: the label column becomes the piece of the period)."""
    rows = np.asarray(rows, dtype=np.int64)
    n = int(rows[:, 0].max()) + 1
    out = []
    for i in range(repeat):
        for j in range(repeat):
            shift = g.period * (i * np.asarray(lattice[0]) + j * np.asarray(lattice[1]))
            block = rows.copy()
            block[:, 1] = rows[:, 0]
            block[:, 0] = rows[:, 0] + n * (i * repeat + j)
            block[:, 2:] += shift
            out.append(block)
    return np.concatenate(out)


def _polygons(g: Grid, rows: np.ndarray):
    """Per cell ``(piece, label, polygon xy)``, and the outline segments of every piece."""
    cells, edges = [], {}
    for piece, label, x, y in rows.tolist():
        vs = g.vertices((x, y))
        cells.append((piece, label, g.to_xy(vs)))
        for a, b in zip(vs, vs[1:] + vs[:1]):
            key = (piece, min(a, b), max(a, b))
            edges[key] = edges.get(key, 0) + 1
    outline = [g.to_xy([a, b]) for (piece, a, b), k in edges.items() if k == 1]
    return cells, outline


def _frame(cells):
    pts = np.concatenate([p for _, _, p in cells])
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    return lo, hi


def shapes_svg_string(g: Grid, rows, *, colour_by: str = "piece", title: str | None = None) -> str:
    """The SVG text of the pieces ``rows``; ``colour_by`` ``"piece"`` or ``"label"`` (the
    corona level, or the shape)."""
    rows = _checked(rows)
    cells, outline = _polygons(g, rows)
    lo, hi = _frame(cells)
    w, h = (hi - lo) * _PX
    dwg, (ox, oy) = titled_canvas(float(w), float(h), title)

    def xy(p):
        return [(float((x - lo[0]) * _PX + ox), float((hi[1] - y) * _PX + oy)) for x, y in p]

    for piece, label, poly in cells:
        colour = tile_colour(piece if colour_by == "piece" else label)
        dwg.add(dwg.polygon(xy(poly), fill=colour, stroke=colour, stroke_width=0.5))
    for seg in outline:
        (x1, y1), (x2, y2) = xy(seg)
        dwg.add(dwg.line((x1, y1), (x2, y2), stroke="#222", stroke_width=1.5))
    return dwg.tostring()


def _checked(rows) -> np.ndarray:
    rows = np.asarray(rows, dtype=np.int64).reshape(-1, 4)
    if rows.shape[0] == 0:
        raise InvalidProblem("nothing to draw: no pieces")
    if rows.shape[0] > MAX_PICTURE_CELLS:
        raise InvalidProblem(f"a picture of {rows.shape[0]} cells is too large (at most {MAX_PICTURE_CELLS})")
    return rows


def write_shapes_picture(path: str | os.PathLike, fmt: str, g: Grid, rows, *, colour_by: str = "piece",
                         title: str | None = None) -> None:
    """Write the pieces as ``fmt`` (``"svg"`` or ``"png"``) atomically."""
    if fmt == "svg":
        text = shapes_svg_string(g, rows, colour_by=colour_by, title=title)
        with atomic_write(path, "w") as f:
            f.write(text)
        return
    from PIL import Image, ImageDraw

    from tilesolve.io.png import captioned

    rows = _checked(rows)
    cells, outline = _polygons(g, rows)
    lo, hi = _frame(cells)
    m = 8.0
    size = ((hi - lo) * _PX + 2 * m).astype(int) + 1
    img = Image.new("RGB", (int(size[0]), int(size[1])), "white")
    d = ImageDraw.Draw(img)

    def xy(p):
        return [(float((x - lo[0]) * _PX + m), float((hi[1] - y) * _PX + m)) for x, y in p]

    for piece, label, poly in cells:
        colour = tile_colour(piece if colour_by == "piece" else label)
        d.polygon(xy(poly), fill=colour, outline=colour)
    for seg in outline:
        d.line(xy(seg), fill="#222222", width=2)
    with atomic_write(path, "wb") as f:
        captioned(img, [title] if title else []).save(f, format="PNG")
