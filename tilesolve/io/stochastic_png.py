"""PNG pictures of windows of stochastic tilings, streamed band by band (class notes ch. 3).

Each tile is drawn as :func:`tilesolve.io.png.edge_image` draws it (:func:`tilesolve.io.png.cell_pixels`):
four triangles (Wang tiles, one per edge) or four quadrants (corner tiles, one per corner) in
the notes' colours (§2.7). A window of millions of tiles is drawn a band of tile rows at a
time and streamed to the file (:func:`tilesolve.io.png.write_packed_rows`), so memory stays
that of one band, whatever the window's size.

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
import zlib

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.io.atomic import atomic_write
from tilesolve.io.png import MAX_PNG_PIXELS, caption_mask, caption_rows, cell_pixels, write_packed_rows
from tilesolve.io.svg_packing import colour_of
from tilesolve.model.tiles import TileSet

__all__ = ["write_window_png", "BAND_PIXELS"]

#: Pixels drawn at once (one band of tile rows), about 2 bytes each.
BAND_PIXELS = 1 << 23
#: Largest table of the pictures of all tiles (bytes) drawn once rather than tile by tile.
TABLE_BYTES = 1 << 22
#: zlib's strategy: runs alone (a tile's part is a run of pixels, a repeated row a run of zeros
#: with the Up filter, :func:`tilesolve.io.png.write_packed_rows`): a 160 Mpx window in a sixth
#: of the CPU of the default strategy, and a smaller file than the default at level 1.
STRATEGY = zlib.Z_RLE
_TARGET_PX = 1024


def write_window_png(path: str | os.PathLike, grid, kind: str, colors: int, *, scale: int | None = None,
                     caption=()) -> None:
    """Write the PNG of ``grid`` (eq. 2.1 / 2.5 tile numbers, row 0 at the top) atomically, with
    the lines ``caption`` under it (:func:`tilesolve.io.png.caption_mask`).

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

    # the picture of every tile once where they are few: each of its pixel rows one item (void
    # of scale bytes), so that a pixel row of the window is one look-up per tile; else the
    # pictures of each band's tiles
    by_row = None
    if ts.n_tiles * scale * scale <= TABLE_BYTES:
        by_row = np.ascontiguousarray(cell_pixels(ts.table(), kind, scale).transpose(1, 0, 2)).view(f"V{scale}")

    below = caption_rows(caption_mask(caption, cols * scale), 0, 255)  # white, dark grey

    def pixel_rows():
        for r0 in range(0, rows, band):
            part = g[r0:r0 + band]
            if by_row is not None:
                for tiles in part:
                    for y in range(scale):
                        yield by_row[y, :, 0].take(tiles).tobytes()
            else:
                colours = np.stack(ts.colors_of(part.ravel().astype(np.int64)), axis=1)
                cells = cell_pixels(colours, kind, scale).reshape(part.shape + (scale, scale))
                yield from cells.transpose(0, 2, 1, 3).reshape(-1, cols * scale)
        yield from below

    writer = png.Writer(cols * scale, rows * scale + len(below), palette=palette, bitdepth=8, compression=6)
    with atomic_write(path, "wb") as f:
        write_packed_rows(writer, f, pixel_rows(), strategy=STRATEGY)
