"""PNG pictures of tilings (pillow), for tilings too large for SVG.

A palette image (one byte per pixel) with the same colours as :mod:`tilesolve.io.svg`;
``scale`` pixels per cell (default: about 1024 px on the longest side, at least 1 px per
cell), optional grid lines and ``repeat x repeat`` copies for cyclic tilings. Written
atomically.

Examples
--------
>>> import numpy as np, tempfile, os
>>> path = os.path.join(tempfile.mkdtemp(), "t.png")
>>> write_png(path, np.array([[0, 1], [1, 0]]), scale=3)
>>> from PIL import Image
>>> with Image.open(path) as img:
...     img.size, img.mode
((6, 6), 'P')
"""

from __future__ import annotations

import io
import os

import numpy as np
from PIL import Image

from tilesolve.errors import InvalidProblem
from tilesolve.io.atomic import write_bytes_atomic
from tilesolve.io.svg import tile_colour

__all__ = ["MAX_PNG_PIXELS", "tiling_image", "write_png"]

#: Largest picture written (pixels): 1 GiB of palette indices.
MAX_PNG_PIXELS = 1 << 30
_TARGET_PX = 1024
_GRID_RGB = (51, 51, 51)


def _rgb(hex_colour: str) -> tuple[int, int, int]:
    return tuple(int(hex_colour[i : i + 2], 16) for i in (1, 3, 5))  # type: ignore[return-value]


def tiling_image(tiling, *, scale: int | None = None, repeat: int = 1, grid: bool | None = None) -> Image.Image:
    """A palette-mode :class:`PIL.Image.Image` of ``tiling`` (``tiling[row, col]``, row 0 on top).

    Parameters
    ----------
    tiling : array-like of int
        Tile numbers (``-1`` = free cell).
    scale : int, optional
        Pixels per cell; default ``max(1, 1024 // longest side)``, at most 16.
    repeat : int
        Show ``repeat x repeat`` copies.
    grid : bool, optional
        Draw a 1 px border between cells (default: when ``scale >= 8``).
    """
    t = np.asarray(tiling)
    if t.ndim != 2 or t.size == 0 or not np.issubdtype(t.dtype, np.integer):
        raise InvalidProblem("a picture needs a non-empty 2-D grid of tile numbers")
    repeat = int(repeat)
    if not 1 <= repeat <= 16:
        raise InvalidProblem(f"repeat must be between 1 and 16, got {repeat}")
    rows, cols = t.shape[0] * repeat, t.shape[1] * repeat
    if scale is None:
        scale = max(1, min(16, _TARGET_PX // max(rows, cols)))
    scale = int(scale)
    if scale < 1:
        raise InvalidProblem(f"PNG scale must be at least 1 pixel per cell, got {scale}")
    if rows * cols * scale * scale > MAX_PNG_PIXELS:
        raise InvalidProblem(
            f"a {cols * scale}x{rows * scale} px PNG is larger than the {MAX_PNG_PIXELS:,} px limit; lower --scale"
        )
    if grid is None:
        grid = scale >= 8
    # Palette index k+1 is tile k, index 0 is a free cell, index 255 is the grid colour.
    hi = int(t.max())
    if hi >= 254:
        raise InvalidProblem(f"PNG pictures support at most 254 tile kinds, got tile {hi}")
    idx = (t.astype(np.int16) + 1).clip(0, 255).astype(np.uint8)
    if repeat > 1:
        idx = np.tile(idx, (repeat, repeat))
    if scale > 1:
        idx = np.repeat(np.repeat(idx, scale, axis=0), scale, axis=1)
    if grid and scale >= 3:
        idx[::scale, :] = 255
        idx[:, ::scale] = 255
    img = Image.fromarray(np.ascontiguousarray(idx))  # mode "L"; putpalette makes it "P"
    palette = [0] * (256 * 3)
    palette[0:3] = _rgb(tile_colour(-1))
    for k in range(hi + 1):
        palette[3 * (k + 1) : 3 * (k + 2)] = _rgb(tile_colour(k))
    palette[255 * 3 : 256 * 3] = _GRID_RGB
    img.putpalette(palette)
    return img


def write_png(path: str | os.PathLike, tiling, **kwargs) -> None:
    """Write the PNG picture of ``tiling`` to ``path`` atomically (arguments of :func:`tiling_image`)."""
    buf = io.BytesIO()
    tiling_image(tiling, **kwargs).save(buf, format="PNG", optimize=False)
    write_bytes_atomic(path, buf.getvalue())
