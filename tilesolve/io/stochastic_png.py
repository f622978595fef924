"""PNG pictures of windows of stochastic tilings, streamed band by band (class notes ch. 3).

Each tile is drawn as :func:`tilesolve.io.png.edge_image` draws it: four triangles (Wang
tiles, one per edge) or four quadrants (corner tiles, one per corner) in the notes' colours
(§2.7). A window of millions of tiles is drawn a band of tile rows at a time and streamed
to the file with pypng, so memory stays that of one band, whatever the window's size.

Examples
--------
>>> import numpy as np, tempfile, os
>>> path = os.path.join(tempfile.mkdtemp(), "w.png")
>>> write_window_png(path, np.arange(16).reshape(2, 8), "corner", 2, scale=4)
>>> from PIL import Image
>>> with Image.open(path) as img:
...     img.size
(32, 8)
"""

from __future__ import annotations

import os

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.io.atomic import atomic_write
from tilesolve.io.png import MAX_PNG_PIXELS, edge_image
from tilesolve.io.svg_packing import colour_of
from tilesolve.model.tiles import TileSet

__all__ = ["write_window_png", "BAND_PIXELS"]

#: Pixels drawn at once (one band of tile rows); ``edge_image`` needs about 20 bytes a pixel.
BAND_PIXELS = 1 << 23
_TARGET_PX = 1024


def write_window_png(path: str | os.PathLike, grid, kind: str, colors: int, *, scale: int | None = None) -> None:
    """Write the PNG of ``grid`` (eq. 2.1 / 2.5 tile numbers, row 0 at the top) atomically.

    Parameters
    ----------
    scale : int, optional
        Pixels per tile side (at least 4, so each triangle or quadrant shows); default about
        1024 px on the longer side, at most 24 and at least 4.
    """
    import png

    g = np.asarray(grid)
    rows, cols = g.shape
    if scale is None:
        scale = max(4, min(24, _TARGET_PX // max(rows, cols)))
    if scale < 4:
        raise InvalidProblem(f"PNG scale must be at least 4 pixels per tile, got {scale}")
    if rows * cols * scale * scale > MAX_PNG_PIXELS:
        raise InvalidProblem(f"a {cols * scale}x{rows * scale} px PNG is larger than the {MAX_PNG_PIXELS:,} px limit")
    if colors > 254:
        raise InvalidProblem(f"PNG pictures support at most 254 colours, got {colors}")
    ts = TileSet(kind, colors)
    band = max(1, BAND_PIXELS // (cols * scale * scale))
    palette = [(255, 255, 255)] + [tuple(int(colour_of(k)[i:i + 2], 16) for i in (1, 3, 5)) for k in range(colors)]
    palette += [(255, 255, 255)] * (255 - len(palette)) + [(51, 51, 51)]

    def pixel_rows():
        for r0 in range(0, rows, band):
            part = g[r0:r0 + band]
            colours = np.stack(ts.colors_of(part.ravel().astype(np.int64)), axis=1)
            positions = np.stack(np.divmod(np.arange(part.size), cols), axis=1)
            img = edge_image(colours, positions, part.shape, kind, scale=scale, palette=colour_of)
            yield from np.asarray(img)

    writer = png.Writer(cols * scale, rows * scale, palette=palette, bitdepth=8, compression=6)
    with atomic_write(path, "wb") as f:
        writer.write_packed(f, (row.tobytes() for row in pixel_rows()))
