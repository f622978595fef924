"""PNG files of GPU pictures of any size, streamed band by band (pypng, written atomically).

A picture larger than one render pass (the context's maximum viewport or texture size) is
rendered in passes (:meth:`tilesolve.gpu.texture.TextureMapper.bands`,
:meth:`tilesolve.gpu.wall.WallRenderer.bands`); the bands go to the file as they come, so
memory stays that of one band.
"""

from __future__ import annotations

import os
import re

import numpy as np

from tilesolve.constructive.hashes import check_int, check_window
from tilesolve.errors import InvalidProblem
from tilesolve.io.atomic import atomic_write
from tilesolve.io.png import MAX_PNG_PIXELS
from tilesolve.progress import Progress, as_progress

__all__ = ["parse_size", "parse_origin", "write_png", "pass_layout", "assemble_bands"]

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


def pass_layout(width, height, max_pass: int) -> tuple[int, int, int, int]:
    """``(width, height, pass_w, band_h)``: the passes that cover a picture, at most
    ``max_pass`` pixels each way and about 16 million pixels each."""
    w, h = check_int(width, "width", 1), check_int(height, "height", 1)
    return w, h, min(max_pass, w), max(1, min(max_pass, h, (1 << 24) // min(w, max_pass)))


def assemble_bands(width: int, height: int, pass_w: int, band_h: int, read_pass):
    """The picture as ``(rows, width, 4)`` uint8 bands from the top, each band put together
    from passes: ``read_pass(left, bottom, pw, bh)`` renders the ``pw x bh`` pixels whose
    bottom-left corner is ``(left, bottom)`` (GL's y grows upwards) and returns them as a
    ``(bh, pw, 4)`` array, bottom row first."""
    for top in range(0, height, band_h):
        bh = min(band_h, height - top)
        band = np.empty((bh, width, 4), dtype=np.uint8)
        for left in range(0, width, pass_w):
            pw = min(pass_w, width - left)
            band[:, left:left + pw] = read_pass(left, height - top - bh, pw, bh)[::-1]
        yield band


def write_png(path: str | os.PathLike, width: int, height: int, bands, progress: Progress | bool = False) -> None:
    """Write the RGBA ``bands`` (``(rows, width, 4)`` uint8, from the top) as one PNG, atomically;
    the rows written are counted on ``progress`` (:func:`tilesolve.progress.as_progress`) band by band."""
    import png

    writer = png.Writer(width, height, greyscale=False, alpha=True, bitdepth=8, compression=6)

    def rows():
        for band in bands:
            yield from band.reshape(band.shape[0], -1)
            bar.advance(band.shape[0])

    with atomic_write(path, "wb") as f, as_progress(progress).task(f"PNG {width:,} x {height:,} px", total=height,
                                                                   unit="row") as bar:
        writer.write(f, rows())
