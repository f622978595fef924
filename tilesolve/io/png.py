"""PNG pictures of tilings, for tilings too large for SVG (files streamed row by row with pypng;
in-memory images with pillow).

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
import itertools
import os
from typing import TYPE_CHECKING, Iterable

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.io.atomic import atomic_write, write_bytes_atomic
from tilesolve.io.svg import tile_colour

if TYPE_CHECKING:  # pillow is imported by the functions that draw, not by importing this module
    from PIL import Image

__all__ = ["MAX_PNG_PIXELS", "tiling_image", "write_png", "edge_image", "cell_pixels", "write_packed_rows",
           "caption_mask", "caption_rows", "swatch_rows", "captioned",
           "write_board_png", "write_packing_png", "write_tileset_png"]

#: Largest picture written (pixels); pictures stream row by row, so this bounds time, not memory.
MAX_PNG_PIXELS = 1 << 32
_TARGET_PX = 1024
_GRID_RGB = (51, 51, 51)


def _rgb(hex_colour: str) -> tuple[int, int, int]:
    return tuple(int(hex_colour[i : i + 2], 16) for i in (1, 3, 5))  # type: ignore[return-value]


def caption_mask(lines, width: int, *, font_px: int = 12) -> np.ndarray:
    """``(height, width)`` booleans, true where ink is: ``lines`` in Pillow's bundled font, in
    black and white (the same pixels on every machine), each wrapped at word breaks (or inside
    a word longer than a line) to fit ``width`` px with a 4 px margin; ``(0, width)`` for no lines.

    >>> caption_mask([], 10).shape
    (0, 10)
    >>> m = caption_mask(["seed 0"], 60)
    >>> m.shape[1], bool(m.any()), bool(m[:, :4].any() or m[:, -4:].any())
    (60, True, False)
    """
    from PIL import Image, ImageDraw, ImageFont

    lines = [s for s in lines if s]
    if not lines or width < 16:
        return np.zeros((0, width), dtype=bool)
    try:
        font = ImageFont.load_default(size=font_px)
    except TypeError:  # Pillow before 10.1: its bitmap font, one size
        font = ImageFont.load_default()
    room = width - 8

    def length(text: str) -> float:  # measured as drawn: mode "1" (unhinted lengths run up to 6% shorter)
        return font.getlength(text, mode="1")

    wrapped: list[str] = []
    for line in lines:
        current = ""
        for word in line.split(" "):
            trial = f"{current} {word}" if current else word
            if length(trial) <= room:
                current = trial
                continue
            if current:
                wrapped.append(current)
            current = ""
            for ch in word:  # a word wider than the picture: broken where it reaches the edge
                if current and length(current + ch) > room:
                    wrapped.append(current)
                    current = ""
                current += ch
        wrapped.append(current)
    step = font_px + 4
    img = Image.new("L", (width, step * len(wrapped) + 8), 0)
    draw = ImageDraw.Draw(img)
    draw.fontmode = "1"  # no anti-aliasing: two colours, as a palette picture has them
    for i, line in enumerate(wrapped):
        draw.text((4, 4 + i * step), line, fill=255, font=font)
    return np.asarray(img) > 127


def swatch_rows(labels, colours, width: int, *, background: int = 0, ink: int = 255) -> np.ndarray:
    """``(height, width)`` palette rows of a legend: for each label a 12 px square of its palette
    index ``colours[k]`` (outlined in ``ink``) and the label beside it, as many a row as fit
    (the SVG's legend, :func:`tilesolve.io.svg.tiling_drawing`); ``(0, width)`` when the picture
    is too narrow for one.

    >>> swatch_rows(["tile 0", "tile 1"], [1, 2], 200).shape
    (20, 200)
    """
    texts = []
    for label in labels:  # each label's ink, cropped: 18 rows, as wide as it reaches
        m = caption_mask([label], 400)[2:20, 4:]
        texts.append(m[:, :int(np.flatnonzero(m.any(axis=0)).max(initial=0)) + 1])
    item = 12 + 4 + max((m.shape[1] for m in texts), default=0) + 12
    per_row = (width - 8) // item
    if not labels or per_row < 1:
        return np.zeros((0, width), dtype=np.uint8)
    out = np.full((-(-len(labels) // per_row) * 20, width), background, dtype=np.uint8)
    for k, (text, colour) in enumerate(zip(texts, colours)):
        y, x = (k // per_row) * 20, 4 + (k % per_row) * item
        out[y + 4:y + 16, x:x + 12] = ink
        out[y + 5:y + 15, x + 1:x + 11] = colour
        out[y + 1:y + 19, x + 16:x + 16 + text.shape[1]][text] = ink
    return out


def caption_rows(mask: np.ndarray, background, ink) -> np.ndarray:
    """The pixel rows of a caption: ``background`` where ``mask`` is false, ``ink`` where true
    (palette indices, greys, or RGB triples)."""
    bg, fg = np.asarray(background, dtype=np.uint8), np.asarray(ink, dtype=np.uint8)
    return np.where(mask.reshape(mask.shape + (1,) * bg.ndim), fg, bg).astype(np.uint8)


def captioned(img: Image.Image, lines) -> Image.Image:
    """``img`` with ``lines`` written under it (:func:`caption_mask`) on white, in dark grey;
    a palette image keeps its palette (its colours nearest white and dark grey are used)."""
    from PIL import Image

    mask = caption_mask(lines, img.width)
    if not mask.size:
        return img
    if img.mode == "P":
        pal = np.asarray(img.getpalette()[:768], dtype=np.int64).reshape(-1, 3)
        bg = int(np.argmin(((pal - 255) ** 2).sum(axis=1)))
        ink = int(np.argmin(((pal - np.array(_GRID_RGB)) ** 2).sum(axis=1)))
    else:
        img = img.convert("RGB")
        bg, ink = (255, 255, 255), _GRID_RGB
    rows = caption_rows(mask, bg, ink)
    out = Image.fromarray(np.concatenate([np.asarray(img), rows]))
    if img.mode == "P":
        out.putpalette(img.getpalette())
    return out


def _tiling_layout(tiling, scale: int | None, repeat: int, grid: bool | None):
    """``(palette indices per cell, scale, grid, palette)`` of a tiling picture (checks sizes)."""
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
    palette = [_rgb(tile_colour(-1))] + [_rgb(tile_colour(k)) for k in range(hi + 1)]
    palette += [(0, 0, 0)] * (255 - len(palette)) + [_GRID_RGB]
    return idx, repeat, scale, bool(grid and scale >= 3), palette


def _pixel_rows(idx: np.ndarray, repeat: int, scale: int, grid: bool):
    """The picture's pixel rows, one at a time (``scale`` rows per cell row)."""
    for _ in range(repeat):
        for row in idx:
            line = np.repeat(np.tile(row, repeat), scale)
            if grid:
                line = line.copy()
                line[::scale] = 255
            for k in range(scale):
                yield np.full_like(line, 255) if grid and k == 0 else line


def tiling_image(tiling, *, scale: int | None = None, repeat: int = 1, grid: bool | None = None) -> "Image.Image":
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
    from PIL import Image

    idx, repeat, scale, grid, palette = _tiling_layout(tiling, scale, repeat, grid)
    pixels = np.stack(list(_pixel_rows(idx, repeat, scale, grid)))
    img = Image.fromarray(np.ascontiguousarray(pixels))  # mode "L"; putpalette makes it "P"
    img.putpalette([v for rgb in palette for v in rgb])
    return img


def write_png(path: str | os.PathLike, tiling, *, scale: int | None = None, repeat: int = 1,
              grid: bool | None = None, caption=(), legend: bool = False) -> None:
    """Write the PNG picture of ``tiling`` (arguments of :func:`tiling_image`) atomically, with
    the lines ``caption`` under it (:func:`caption_mask`; on the free cells' near-white), after
    the tiles' colours where ``legend`` (:func:`swatch_rows`).

    The picture is streamed row by row (pypng), so a huge grid costs one pixel row of memory
    besides the tiling itself, however many pixels the picture has.
    """
    import png

    idx, repeat, scale, grid, palette = _tiling_layout(tiling, scale, repeat, grid)
    height, width = idx.shape[0] * repeat * scale, idx.shape[1] * repeat * scale
    below = caption_rows(caption_mask(caption, width), 0, 255)
    if legend:
        tiles = range(int(np.asarray(tiling).max()) + 1)
        below = np.concatenate([swatch_rows([f"tile {k}" for k in tiles], [k + 1 for k in tiles], width), below])
    writer = png.Writer(width, height + len(below), palette=palette, bitdepth=8, compression=6)
    rows = itertools.chain(_pixel_rows(idx, repeat, scale, grid), below)
    with atomic_write(path, "wb") as f:
        write_packed_rows(writer, f, (row.tobytes() for row in rows))


def _side_masks(scale: int, kind: str) -> np.ndarray:
    """``(4, scale, scale)`` masks of the four parts of a cell: the N, E, S, W triangles
    (Wang tiles) or the NE, SE, SW, NW quadrants (corner tiles), in that order."""
    y, x = np.mgrid[0:scale, 0:scale] + 0.5
    if kind == "corner":
        h = scale / 2
        return np.stack([(y < h) & (x >= h), (y >= h) & (x >= h), (y >= h) & (x < h), (y < h) & (x < h)])
    d1, d2 = y - x, y + x - scale
    return np.stack([(d1 < 0) & (d2 < 0), (d1 < 0) & (d2 >= 0), (d1 >= 0) & (d2 >= 0), (d1 >= 0) & (d2 < 0)])


def edge_image(colours, positions, shape: tuple[int, int], kind: str = "wang", *, scale: int | None = None,
               palette=None) -> Image.Image:
    """A palette image of cells drawn by their four side (or corner) colours.

    Parameters
    ----------
    colours : array-like of int, shape (n_cells, 4)
        N, E, S, W edge colours (Wang) or NE, SE, SW, NW corner colours (corner).
    positions : array-like of int, shape (n_cells, 2)
        ``(row, col)`` of each cell in a ``shape`` grid (cells not listed stay blank).
    """
    c = np.asarray(colours, dtype=np.int64).reshape(-1, 4)
    pos = np.asarray(positions, dtype=np.int64).reshape(-1, 2)
    rows, cols = shape
    if scale is None:
        scale = max(4, min(24, _TARGET_PX // max(rows, cols, 1)))
    if rows * cols * scale * scale > MAX_PNG_PIXELS:
        raise InvalidProblem(f"a {cols * scale}x{rows * scale} px PNG is larger than the {MAX_PNG_PIXELS:,} px limit")
    hi = int(c.max()) if c.size else 0
    if hi >= 254:
        raise InvalidProblem(f"PNG pictures support at most 254 colours, got colour {hi}")
    cells = np.zeros((rows, cols, scale, scale), dtype=np.uint8)
    cells[pos[:, 0], pos[:, 1]] = cell_pixels(c, kind, scale)
    from PIL import Image

    img = Image.fromarray(np.ascontiguousarray(cells.transpose(0, 2, 1, 3).reshape(rows * scale, cols * scale)))
    pal = [255] * (256 * 3)
    for k in range(hi + 1):
        pal[3 * (k + 1): 3 * (k + 2)] = _rgb(palette(k) if palette else tile_colour(k))
    pal[255 * 3: 256 * 3] = _GRID_RGB
    img.putpalette(pal)
    return img


def cell_pixels(colours, kind: str, scale: int) -> np.ndarray:
    """``(n, scale, scale)`` palette indices of cells drawn by their four side (Wang) or corner
    colours (``(n, 4)``, each below 254): colour ``k`` as index ``k + 1`` in its triangle or
    quadrant (:func:`_side_masks`), and from 8 px a thin outline (index 255) along the top and
    left sides.

    >>> cell_pixels([[0, 1, 2, 3]], "corner", 2)[0].tolist()  # NE, SE, SW, NW
    [[4, 1], [3, 2]]
    """
    part = np.argmax(_side_masks(scale, kind), axis=0)  # which side each pixel of a cell shows
    cells = (np.asarray(colours).reshape(-1, 4).astype(np.uint8) + 1)[:, part]
    if scale >= 8:
        cells[:, 0, :] = 255
        cells[:, :, 0] = 255
    return cells


def write_packed_rows(writer, f, rows: Iterable, *, strategy: int | None = None) -> None:
    """Write a PNG as pypng's ``writer.write_packed(f, rows)`` does (the same pixels), each
    row that repeats the row before it written with PNG's *Up* filter: a row of zeros, which
    zlib compresses many times faster and smaller than the row itself. Pictures of cells
    many pixels high repeat most of their rows.

    Parameters
    ----------
    writer : png.Writer
        Not interlaced.
    f : binary file
    rows : iterable of bytes-like
        The packed rows, top to bottom.
    strategy : int, optional
        zlib's strategy (default ``zlib.Z_DEFAULT_STRATEGY``); ``zlib.Z_RLE`` looks for runs
        alone, several times faster, and as small where the pixels come in runs.
    """
    import zlib

    import png

    writer.write_preamble(f)
    level = writer.compression if writer.compression is not None else -1
    compressor = zlib.compressobj(level, strategy=zlib.Z_DEFAULT_STRATEGY if strategy is None else strategy)
    data, previous, zeros = bytearray(), None, b""
    for row in rows:
        row = bytes(row)
        if row == previous:
            if len(zeros) != len(row):
                zeros = bytes(len(row))
            data += b"\x02"
            data += zeros
        else:
            data += b"\x00"
            data += row
            previous = row
        if len(data) > writer.chunk_limit:
            out = compressor.compress(data)
            if out:
                png.write_chunk(f, b"IDAT", out)
            data = bytearray()
    out = compressor.compress(bytes(data)) + compressor.flush()
    if out:
        png.write_chunk(f, b"IDAT", out)
    png.write_chunk(f, b"IEND")


def _save(path, img: Image.Image, caption=()) -> None:
    buf = io.BytesIO()
    captioned(img, caption).save(buf, format="PNG", optimize=False)
    write_bytes_atomic(path, buf.getvalue())


def write_board_png(path: str | os.PathLike, problem, tiling, *, window=None, caption=(), **kwargs) -> None:
    """PNG of a board tiling: bricks and mortar for a brick tile set, at any size
    (:mod:`tilesolve.io.board_png`; ``window``, where the tiling lies in the plane, colours the
    bricks by their position), else each cell's legs as N, E, S, W triangles at its ``[row, col]`` label;
    the lines ``caption`` under it."""
    if problem.tileset.is_brick:
        from tilesolve.io.board_png import brick_image

        _save(path, brick_image(problem, tiling, window=window, **kwargs), caption)
        return
    lab = np.asarray(problem.board.labels)
    shape = tuple(int(v) + 1 for v in lab.max(axis=0))
    _save(path, edge_image(np.asarray(tiling, dtype=np.int64).reshape(-1, 4), lab, shape, "wang", **kwargs), caption)


def write_packing_png(path: str | os.PathLike, grid, kind: str, colors: int, *, colors_v: int | None = None,
                      caption=(), **kwargs) -> None:
    """PNG of a packing (or any grid of tile indices, eq. 2.1 / 2.5), in the notes' colours (§2.7),
    with the lines ``caption`` under it."""
    from tilesolve.io.svg_packing import colour_of
    from tilesolve.model.tiles import TileSet

    g = np.asarray(grid, dtype=np.int64)
    colours = np.stack(TileSet(kind, colors, colors_v).colors_of(g.ravel()), axis=1)
    rows, cols = g.shape
    positions = np.stack(np.divmod(np.arange(g.size), cols), axis=1)
    _save(path, edge_image(colours, positions, (rows, cols), kind, palette=colour_of, **kwargs), caption)


def write_tileset_png(path: str | os.PathLike, tiles, *, caption=None, **kwargs) -> None:
    """PNG sheet of a :class:`~tilesolve.model.tiles.TileSet`: its tiles in index order, row by
    row, with a blank cell between neighbours (the notes' colours, §2.7), under the lines
    ``caption`` (default: ``tiles.describe()``, the SVG sheet's title)."""
    from tilesolve.io.svg_packing import colour_of

    colours = tiles.table()
    n = len(colours)
    per_row = int(np.ceil(np.sqrt(n)))
    k = np.arange(n)
    positions = np.stack([2 * (k // per_row), 2 * (k % per_row)], axis=1)
    shape = (2 * int(np.ceil(n / per_row)) - 1, 2 * per_row - 1)
    _save(path, edge_image(colours, positions, shape, tiles.kind, palette=colour_of, **kwargs),
          [tiles.describe()] if caption is None else caption)
