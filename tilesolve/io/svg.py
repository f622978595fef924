"""SVG pictures of tilings (svgwrite).

One coloured square per cell, from a fixed colour-blind-friendly palette (Okabe & Ito), a
legend (tile -> colour, size, conditions), optional grid lines, and for cyclic tilings an
optional ``repeat x repeat`` view that shows the seams wrap (a faint dashed line marks each
copy's border). Horizontal runs of equal tiles are drawn as one rectangle and repeated copies
are ``<use>`` references, so files stay small; pictures above :data:`MAX_SVG_CELLS` cells are
refused in favour of PNG (:mod:`tilesolve.io.png`).

Examples
--------
>>> import numpy as np
>>> text = svg_string(np.array([[0, 1, 1], [1, 0, 0]]))
>>> text.startswith("<svg") and "tile 1" in text
True
"""

from __future__ import annotations

import colorsys
import math
import os
import textwrap
from typing import TYPE_CHECKING, Iterable, Sequence

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.io.atomic import atomic_write

if TYPE_CHECKING:  # svgwrite is imported by the functions that draw, not by importing this module
    import svgwrite

__all__ = ["PALETTE", "FREE_COLOUR", "MAX_SVG_CELLS", "BACKGROUND", "CAPTION_COLOUR", "tile_colour", "text_width",
           "canvas", "add_caption", "caption_box", "titled_canvas", "check_svg_size", "tiling_drawing", "svg_string", "write_svg"]

#: Okabe & Ito's colour-blind-safe palette, reordered so that two tiles get blue/orange.
PALETTE: tuple[str, ...] = (
    "#0072B2",  # blue
    "#E69F00",  # orange
    "#009E73",  # bluish green
    "#CC79A7",  # reddish purple
    "#56B4E9",  # sky blue
    "#D55E00",  # vermillion
    "#F0E442",  # yellow
    "#000000",  # black
)
#: Colour of a free cell (``-1``) in a partial tiling.
FREE_COLOUR = "#F4F4F4"
#: Largest tiling (cells, before repetition) drawn as SVG; bigger ones belong in a PNG.
MAX_SVG_CELLS = 250_000

#: Opaque background of every picture (SVG and PNG), so that captions read on any page.
BACKGROUND = "#FFFFFF"
#: Colour of captions and legends.
CAPTION_COLOUR = "#222222"

_TARGET_PX = 720  # longest side of the picture, before the legend
_MAX_CELL_PX = 28
_FONT_PX = 12
_LINE_PX = 16
#: Advance of the printable ASCII characters (32..126) in DejaVu Sans, the widest common
#: sans-serif font, in hundredths of an em, rounded up; other characters count 1 em, bold text
#: 1.27 times as much (DejaVu Sans Bold's widest ratio). Widths estimated from it do not fall
#: short with the fonts a viewer substitutes for ``sans-serif``.
_ADVANCE = (
    32, 41, 46, 84, 64, 96, 78, 28, 40, 40, 50, 84, 32, 37, 32, 34, 64, 64, 64, 64, 64, 64, 64, 64, 64, 64, 34, 34,
    84, 84, 84, 54, 100, 69, 69, 70, 78, 64, 58, 78, 76, 30, 30, 66, 56, 87, 75, 79, 61, 79, 70, 64, 62, 74, 69, 99,
    69, 62, 69, 40, 34, 40, 84, 50, 50, 62, 64, 55, 64, 62, 36, 64, 64, 28, 28, 58, 28, 98, 64, 62, 64, 64, 42, 53,
    40, 64, 60, 82, 60, 60, 53, 64, 34, 64, 84,
)


def tile_colour(tile: int) -> str:
    """Colour of ``tile``: the palette first, then well-spread hues (golden-angle steps)."""
    tile = int(tile)
    if tile < 0:
        return FREE_COLOUR
    if tile < len(PALETTE):
        return PALETTE[tile]
    k = tile - len(PALETTE)
    hue = (0.11 + 0.381966 * k) % 1.0
    light = (0.45, 0.62, 0.33)[k % 3]
    r, g, b = colorsys.hls_to_rgb(hue, light, 0.65)
    return "#{:02X}{:02X}{:02X}".format(round(r * 255), round(g * 255), round(b * 255))


def text_width(text: str, font_px: float, *, bold: bool = False) -> float:
    """A width no sans-serif rendering of ``text`` at ``font_px`` exceeds (px; see :data:`_ADVANCE`).

    >>> text_width("tile 10", 12)
    38.16
    """
    ems = sum(_ADVANCE[ord(c) - 32] if 32 <= ord(c) < 127 else 100 for c in text) / 100
    return round(ems * font_px * (1.27 if bold else 1.0), 2)


def canvas(width: float, height: float, *, x: float = 0.0, y: float = 0.0, profile: str = "full") -> svgwrite.Drawing:
    """A drawing whose view box is ``(x, y, width, height)``, ``width x height`` px, on an
    opaque :data:`BACKGROUND` (the first shape), so that it reads on a dark page too."""
    import svgwrite

    dwg = svgwrite.Drawing(size=(f"{width:g}", f"{height:g}"), profile=profile, debug=False)
    dwg.viewbox(x, y, width, height)
    dwg.add(dwg.rect((x, y), (width, height), fill=BACKGROUND))
    return dwg


def add_caption(dwg: svgwrite.Drawing, lines: Sequence[str], x: float, y: float, *, font_px: float = _FONT_PX,
                line_px: float = _LINE_PX) -> float:
    """Write ``lines`` at ``(x, y)`` (the first line's top), one under the other in
    :data:`CAPTION_COLOUR`; returns the height they take (``len(lines) * line_px``)."""
    if lines:
        g = dwg.add(dwg.g(font_family="sans-serif", font_size=font_px, fill=CAPTION_COLOUR))
        for i, line in enumerate(lines):
            g.add(dwg.text(line, insert=(x, y + i * line_px + font_px)))
    return len(lines) * line_px


def caption_box(lines: Sequence[str], font_px: float = _FONT_PX, line_px: float = _LINE_PX) -> tuple[float, float]:
    """``(width, height)`` that :func:`add_caption` needs for ``lines``."""
    return max((text_width(s, font_px) for s in lines), default=0.0), len(lines) * line_px


def titled_canvas(width: float, height: float, title: str | None,
                  margin: float = 8.0) -> tuple[svgwrite.Drawing, tuple[float, float]]:
    """``(drawing, (x, y))``: a canvas (:func:`canvas`) for a ``width x height`` picture under
    its ``title``, widened to the title's width where the title is wider; the picture goes at
    ``(x, y)`` (centred), with ``margin`` px all round."""
    lines = [title] if title else []
    text_w, text_h = caption_box(lines)
    head = text_h + 6 if lines else 0.0
    total_w = max(width, text_w) + 2 * margin
    dwg = canvas(math.ceil(total_w), math.ceil(height + head + 2 * margin))
    add_caption(dwg, lines, margin, margin - 2)
    return dwg, ((total_w - width) / 2, margin + head)


def check_svg_size(rows: int, cols: int) -> None:
    """Raise :class:`InvalidProblem` when a ``rows x cols`` tiling is too large for SVG."""
    if rows * cols > MAX_SVG_CELLS:
        raise InvalidProblem(
            f"a {cols}x{rows} tiling has {rows * cols:,} cells, too many for an SVG "
            f"(limit {MAX_SVG_CELLS:,}); write a PNG instead (--png)"
        )


def _condition_label(cond) -> str:
    """``H0=2``, or ``H0=2..9 per cell`` for per-cell limits (0 = no limit is skipped)."""
    text = str(cond)
    if cond.is_uniform:
        return text
    finite = cond.limit[cond.limit > 0]
    if finite.size == 0:
        return text.replace("per-cell", "inf")
    lo, hi = int(finite.min()), int(finite.max())
    return text.replace("per-cell", f"{lo}..{hi} per cell" if lo != hi else f"{lo} per cell")


def _cell_px(rows: int, cols: int) -> float:
    return float(max(1, min(_MAX_CELL_PX, _TARGET_PX // max(rows, cols))))


def _runs(row: np.ndarray) -> Iterable[tuple[int, int, int]]:
    """``(start, length, tile)`` for each maximal run of equal values in ``row``."""
    change = np.flatnonzero(np.diff(row)) + 1
    starts = np.concatenate(([0], change))
    ends = np.concatenate((change, [row.size]))
    return zip(starts.tolist(), (ends - starts).tolist(), row[starts].tolist())


def tiling_drawing(
    tiling,
    *,
    problem=None,
    n_tiles: int | None = None,
    grid: bool | None = None,
    repeat: int = 1,
    cell: float | None = None,
    legend: bool = True,
    title: str | None = None,
    notes: Sequence[str] = (),
) -> svgwrite.Drawing:
    """Build the SVG drawing of ``tiling`` (``tiling[row, col]``, row 0 at the top).

    Parameters
    ----------
    tiling : array-like of int
        Tile numbers; ``-1`` marks a free cell (drawn light grey).
    problem : DappledProblem, optional
        Supplies the legend's size, tile count and conditions.
    n_tiles : int, optional
        Tiles listed in the legend (default: from ``problem``, else ``max(tiling) + 1``).
    grid : bool, optional
        Draw cell borders; default: when cells are at least 8 px.
    repeat : int
        Show ``repeat x repeat`` copies (for cyclic tilings), with faint seams.
    cell : float, optional
        Cell size in px (default: the picture's longest side is about 720 px).
    legend : bool
        Add the legend below the picture.
    title : str, optional
        Title (tooltip) of the drawing and first legend line.
    notes : sequence of str
        Extra legend lines.

    Raises
    ------
    InvalidProblem
        The tiling is not a 2-D integer grid, is too large for SVG, or ``repeat < 1``.
    """
    t = np.asarray(tiling)
    if t.ndim != 2 or t.size == 0 or not np.issubdtype(t.dtype, np.integer):
        raise InvalidProblem("a picture needs a non-empty 2-D grid of tile numbers")
    rows, cols = t.shape
    check_svg_size(rows, cols)
    repeat = int(repeat)
    if not 1 <= repeat <= 16:
        raise InvalidProblem(f"repeat must be between 1 and 16, got {repeat}")
    if problem is not None and n_tiles is None:
        n_tiles = problem.n_tiles
    if n_tiles is None:
        n_tiles = max(int(t.max()) + 1, 2)
    px = float(cell) if cell else _cell_px(rows * repeat, cols * repeat)
    if grid is None:
        grid = px >= 8
    margin = 10.0
    block_w, block_h = cols * px, rows * px
    pic_w, pic_h = block_w * repeat, block_h * repeat

    # --- legend text, so the drawing can be made wide enough for it
    lines: list[str] = []
    if title:
        lines.append(title)
    if problem is not None:
        lines.append(f"{cols}x{rows} grid (W x H), |T| = {problem.n_tiles}" + (", cyclic" if problem.cyclic else ""))
        conds = ", ".join(_condition_label(c) for c in problem.conditions) or "none"
        lines.extend(textwrap.wrap(f"L = {{{conds}}}", 64, subsequent_indent="    "))
        if problem.counts:
            lines.append("counts: " + ", ".join(str(k) for k in problem.counts))
    else:
        lines.append(f"{cols}x{rows} grid (W x H)")
    if repeat > 1:
        lines.append(f"shown {repeat}x{repeat} (dashed lines: seams)")
    lines.extend(notes)
    shown_tiles = list(range(n_tiles)) + ([-1] if (t < 0).any() else [])
    labels = ["free" if tile < 0 else f"tile {tile}" for tile in shown_tiles]
    swatch = 14.0
    item_w = swatch + 5 + max(text_width(s, _FONT_PX) for s in labels) + 8
    text_w, text_h = caption_box(lines)
    width = max(pic_w, text_w, min(4, len(labels)) * item_w) if legend else pic_w
    per_row = max(1, int(width // item_w))
    swatch_rows = -(-len(shown_tiles) // per_row)
    legend_h = (swatch_rows * 20 + text_h + 8) if legend else 0
    total_w, total_h = width + 2 * margin, pic_h + legend_h + 2 * margin

    dwg = canvas(total_w, total_h)
    if title:
        dwg.set_desc(title=title)

    block = dwg.g(id="block", shape_rendering="crispEdges")
    # The most common tile is one background rectangle; only the other runs are drawn.
    values, freq = np.unique(t, return_counts=True)
    background = int(values[np.argmax(freq)])
    block.add(dwg.rect((0, 0), (f"{block_w:g}", f"{block_h:g}"), fill=tile_colour(background)))
    by_tile: dict[int, svgwrite.container.Group] = {}
    for r in range(rows):
        for start, length, tile in _runs(t[r]):
            if tile == background:
                continue
            g = by_tile.get(tile)
            if g is None:
                g = by_tile[tile] = dwg.g(fill=tile_colour(tile))
            g.add(dwg.rect((f"{start * px:g}", f"{r * px:g}"), (f"{length * px:g}", f"{px:g}")))
    for tile in sorted(by_tile):
        block.add(by_tile[tile])
    if grid:
        d = [f"M0,{r * px:g}H{block_w:g}" for r in range(rows + 1)]
        d += [f"M{c * px:g},0V{block_h:g}" for c in range(cols + 1)]
        block.add(dwg.path(d="".join(d), fill="none", stroke="#333333", stroke_opacity=0.45,
                           stroke_width=f"{max(0.5, min(1.5, px / 16)):g}"))
    pic = dwg.g(transform=f"translate({margin:g},{margin:g})")
    if repeat == 1:
        pic.add(block)
    else:
        dwg.defs.add(block)
        for i in range(repeat):
            for j in range(repeat):
                pic.add(dwg.use("#block", insert=(f"{j * block_w:g}", f"{i * block_h:g}")))
        seams = [f"M0,{i * block_h:g}H{pic_w:g}" for i in range(1, repeat)]
        seams += [f"M{j * block_w:g},0V{pic_h:g}" for j in range(1, repeat)]
        pic.add(dwg.path(d="".join(seams), fill="none", stroke="#000000", stroke_opacity=0.5,
                         stroke_width="2", stroke_dasharray="6,4"))
    dwg.add(pic)

    if legend:
        y = margin + pic_h + 14
        leg = dwg.add(dwg.g(font_family="sans-serif", font_size=_FONT_PX, fill=CAPTION_COLOUR))
        for k, (tile, label) in enumerate(zip(shown_tiles, labels)):
            x = margin + (k % per_row) * item_w
            yy = y + (k // per_row) * 20
            leg.add(dwg.rect((x, yy), (swatch, swatch), fill=tile_colour(tile), stroke="#555555", stroke_width=0.5))
            leg.add(dwg.text(label, insert=(x + swatch + 5, yy + 11.5)))
        add_caption(dwg, lines, margin, y + swatch_rows * 20 - 4)
    return dwg


def svg_string(tiling, **kwargs) -> str:
    """The SVG text of :func:`tiling_drawing` (same arguments)."""
    return tiling_drawing(tiling, **kwargs).tostring()


def write_svg(path: str | os.PathLike, tiling, **kwargs) -> None:
    """Write the SVG picture of ``tiling`` to ``path`` atomically (arguments of :func:`tiling_drawing`)."""
    dwg = tiling_drawing(tiling, **kwargs)
    with atomic_write(path, "w") as f:
        dwg.write(f, pretty=False)
