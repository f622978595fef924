"""Grouped bar charts as SVG (svgwrite) or PNG (Pillow), e.g. the line-length histograms of 004 Fig. 22.

A chart is a grid of panels; each panel has one group of bars per label along ``x`` and one
bar per series in each group, all sharing the panel's ``y`` scale (values are shares in 0..1
or any non-negative numbers). The layout is computed once (:func:`chart_shapes`) and drawn by
either writer, both atomic (:mod:`tilesolve.io.atomic`).
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from typing import Sequence

from tilesolve.errors import InvalidProblem
from tilesolve.io.atomic import atomic_write
from tilesolve.io.svg import text_width

__all__ = ["Panel", "chart_shapes", "write_chart_svg", "write_chart_png"]

#: Series colours (colour-blind safe, Okabe-Ito).
PALETTE = ("#0072B2", "#E69F00", "#009E73", "#CC79A7", "#56B4E9", "#D55E00")
_PW, _PH, _PAD, _LEFT, _BOTTOM, _TOP = 420, 240, 24, 52, 34, 30


@dataclass(frozen=True)
class Panel:
    """One panel: ``title``, the ``labels`` along x and ``series`` ``[(name, values), ...]``
    (one value per label)."""

    title: str
    labels: Sequence[str]
    series: Sequence[tuple[str, Sequence[float]]]


def _nice_top(v: float) -> float:
    """The smallest of 1, 2, 2.5, 5 times a power of ten at or above ``v`` (``1`` for 0)."""
    if v <= 0:
        return 1.0
    e = 10 ** math.floor(math.log10(v))
    return next(m * e for m in (1, 2, 2.5, 5, 10) if m * e >= v * (1 - 1e-12))


def chart_shapes(panels: Sequence[Panel], *, columns: int, title: str = "") -> tuple[int, int, list[tuple]]:
    """``(width, height, shapes)``: ``("rect", x, y, w, h, colour)``, ``("line", x1, y1, x2, y2)``
    and ``("text", x, y, text, anchor)`` (``anchor`` ``start``/``middle``/``end``) in pixels."""
    if not panels:
        raise InvalidProblem("a chart needs at least one panel")
    columns = max(1, min(int(columns), len(panels)))
    rows = -(-len(panels) // columns)
    names = [name for name, _ in panels[0].series]
    head = 28 if title else 0
    width = columns * (_PW + _PAD) + _PAD
    shapes: list[tuple] = []
    if title:
        shapes.append(("text", width / 2, 20, title, "middle"))
    # the legend: a swatch and its name each, wrapped into as many rows as the width needs
    # (one row ran past a one-column chart's edge: "wall (Kaji dappling)" was cut off)
    x, y = _PAD, head + 8
    for k, name in enumerate(names):
        item = 16 + text_width(name, 12)
        if x > _PAD and x + item > width - _PAD:
            x, y = _PAD, y + 20
        shapes.append(("rect", x, y + 2, 12, 12, PALETTE[k % len(PALETTE)]))
        shapes.append(("text", x + 16, y + 12, name, "start"))
        x += item + 16
    legend_y = y
    height = legend_y + 22 + rows * (_PH + _PAD)
    for p, panel in enumerate(panels):
        if len(panel.series) != len(names) or any(len(v) != len(panel.labels) for _, v in panel.series):
            raise InvalidProblem("every panel needs the same series, one value per label")
        ox = _PAD + (p % columns) * (_PW + _PAD)
        oy = legend_y + 22 + (p // columns) * (_PH + _PAD)
        x0, y0 = ox + _LEFT, oy + _TOP  # plot area
        pw, ph = _PW - _LEFT - 8, _PH - _TOP - _BOTTOM
        top = _nice_top(max((float(v) for _, vals in panel.series for v in vals), default=0.0))
        shapes.append(("text", ox + _PW / 2, oy + 16, panel.title, "middle"))
        for t in range(5):
            y = y0 + ph - ph * t / 4
            shapes.append(("line", x0 - 4, y, x0 + pw, y))
            shapes.append(("text", x0 - 6, y + 4, f"{top * t / 4:g}", "end"))
        group = pw / max(1, len(panel.labels))
        bar = group * 0.8 / max(1, len(names))
        for i, label in enumerate(panel.labels):
            gx = x0 + i * group + group * 0.1
            for k, (_, vals) in enumerate(panel.series):
                v = max(0.0, float(vals[i]))
                hgt = ph * min(v, top) / top
                shapes.append(("rect", gx + k * bar, y0 + ph - hgt, bar, hgt, PALETTE[k % len(PALETTE)]))
            shapes.append(("text", x0 + (i + 0.5) * group, y0 + ph + 16, str(label), "middle"))
    return width, height, shapes


def write_chart_svg(path: str | os.PathLike, panels: Sequence[Panel], *, columns: int = 2, title: str = "") -> None:
    """Write the chart as SVG, atomically."""
    import svgwrite

    width, height, shapes = chart_shapes(panels, columns=columns, title=title)
    dwg = svgwrite.Drawing(size=(f"{width}", f"{height}"), profile="full", debug=False)
    dwg.add(dwg.rect((0, 0), (width, height), fill="white"))
    for s in shapes:
        if s[0] == "rect":
            dwg.add(dwg.rect((f"{s[1]:.2f}", f"{s[2]:.2f}"), (f"{s[3]:.2f}", f"{s[4]:.2f}"), fill=s[5]))
        elif s[0] == "line":
            dwg.add(dwg.line((s[1], s[2]), (s[3], s[4]), stroke="#ccc", stroke_width=1))
        else:
            dwg.add(dwg.text(s[3], insert=(s[1], s[2]), text_anchor=s[4], font_size=12, font_family="sans-serif"))
    with atomic_write(path, "w") as f:
        dwg.write(f, pretty=False)


def write_chart_png(path: str | os.PathLike, panels: Sequence[Panel], *, columns: int = 2, title: str = "") -> None:
    """Write the chart as PNG (Pillow, its default font), atomically."""
    from PIL import Image, ImageDraw

    width, height, shapes = chart_shapes(panels, columns=columns, title=title)
    img = Image.new("RGB", (width, height), "white")
    draw = ImageDraw.Draw(img)
    for s in shapes:
        if s[0] == "rect":
            if s[4] > 0:
                draw.rectangle([s[1], s[2], s[1] + s[3], s[2] + s[4]], fill=s[5])
        elif s[0] == "line":
            draw.line([s[1], s[2], s[3], s[4]], fill="#cccccc")
        else:
            anchor = {"start": "ls", "middle": "ms", "end": "rs"}[s[4]]
            draw.text((s[1], s[2]), s[3], fill="black", anchor=anchor)
    with atomic_write(path, "wb", encoding=None) as f:
        img.save(f, format="PNG")
