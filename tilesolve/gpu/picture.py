"""PNG files of GPU pictures of any size, streamed band by band (pypng, written atomically).

A picture larger than one render pass (the context's maximum viewport or texture size) is
rendered in passes (:meth:`tilesolve.gpu.texture.TextureMapper.bands`,
:meth:`tilesolve.gpu.wall.WallRenderer.bands`); the bands go to the file as they come, so
memory stays that of one band.
"""

from __future__ import annotations

import os
import re

from tilesolve.constructive.hashes import check_window
from tilesolve.errors import InvalidProblem
from tilesolve.io.atomic import atomic_write
from tilesolve.io.png import MAX_PNG_PIXELS

__all__ = ["parse_size", "parse_origin", "write_png"]

_SIZE = re.compile(r"\s*(\d+)\s*[xX]\s*(\d+)\s*")


def parse_size(text: str) -> tuple[int, int]:
    """``"WxH"`` -> ``(W, H)``, both positive and at most :data:`MAX_PNG_PIXELS` pixels in all.

    >>> parse_size("1920x1080")
    (1920, 1080)
    """
    m = _SIZE.fullmatch(text)
    if m is None:
        raise InvalidProblem(f"a picture size is WxH in pixels (e.g. 1920x1080), got {text!r}")
    w, h = int(m.group(1)), int(m.group(2))
    if w < 1 or h < 1:
        raise InvalidProblem(f"a picture needs at least 1x1 pixels, got {w}x{h}")
    if w * h > MAX_PNG_PIXELS:
        raise InvalidProblem(f"a {w}x{h} picture is larger than the {MAX_PNG_PIXELS:,} pixel limit of PNG files")
    return w, h


def parse_origin(text: str) -> tuple[int, int]:
    """``"X0,Y0"`` -> ``(X0, Y0)``, a lattice cell the hashes address (``|X0|, |Y0| < 2**62``).

    >>> parse_origin("-8,3")
    (-8, 3)
    """
    try:
        x0, y0 = (int(p) for p in text.split(","))
    except ValueError:
        raise InvalidProblem(f"an origin is X0,Y0 (integers, e.g. -8,3), got {text!r}") from None
    x0, y0, _, _ = check_window(x0, y0, 1, 1, what="origin")
    return x0, y0


def write_png(path: str | os.PathLike, width: int, height: int, bands) -> None:
    """Write the RGBA ``bands`` (``(rows, width, 4)`` uint8, from the top) as one PNG, atomically."""
    import png

    writer = png.Writer(width, height, greyscale=False, alpha=True, bitdepth=8, compression=6)

    def rows():
        for band in bands:
            yield from band.reshape(band.shape[0], -1)

    with atomic_write(path, "wb") as f:
        writer.write(f, rows())
