"""Every SVG picture sits on an opaque background, and every text of it lies inside its view box
(issue 22): measured with a real font, DejaVu Sans (the widest common sans-serif) where the
machine has it, else Pillow's bundled font, on the pictures ``tilesolve demo`` writes (the
console script) and on the writers' own captions."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from functools import lru_cache

import numpy as np
import pytest
from clitools import run

SVG = "{http://www.w3.org/2000/svg}"


@lru_cache(maxsize=None)
def _font(px: float, bold: bool):
    from PIL import ImageFont

    for name in (("DejaVuSans-Bold.ttf", "DejaVuSans.ttf")[not bold], "DejaVuSans.ttf"):
        try:
            return ImageFont.truetype(name, size=round(px * 8)), 8.0
        except OSError:
            continue
    return ImageFont.load_default(size=round(px * 8)), 8.0


def _width(text: str, px: float, bold: bool) -> float:
    font, k = _font(px, bold)
    return font.getlength(text) / k


def _viewbox(root) -> tuple[float, float, float, float]:
    vb = root.get("viewBox")
    if vb:
        return tuple(float(v) for v in re.split(r"[ ,]+", vb.strip()))
    return 0.0, 0.0, float(root.get("width").rstrip("px")), float(root.get("height").rstrip("px"))


def _affine(el) -> np.ndarray:
    """The 3x3 matrix of ``el``'s ``transform`` (translate, scale and matrix, composed in order)."""
    out = np.eye(3)
    for name, args in re.findall(r"(\w+)\s*\(([^)]*)\)", el.get("transform") or ""):
        v = [float(a) for a in re.split(r"[\s,]+", args.strip())]
        m = np.eye(3)
        if name == "translate":
            m[:2, 2] = v[0], v[1] if len(v) > 1 else 0.0
        elif name == "scale":
            m[0, 0], m[1, 1] = v[0], v[1] if len(v) > 1 else v[0]
        elif name == "matrix":
            m[:2] = [[v[0], v[2], v[4]], [v[1], v[3], v[5]]]
        else:
            raise AssertionError(f"unexpected transform {name}")
        out = out @ m
    return out


def _texts(el, frame=None, style=None):
    """``(text, x_left, x_right, y_top, y_bottom)`` of every text outside ``<defs>``."""
    style = dict(style or {"font-size": "16", "text-anchor": "start", "font-weight": "normal"})
    for key in style:
        if el.get(key) is not None:
            style[key] = el.get(key)
    frame = (np.eye(3) if frame is None else frame) @ _affine(el)
    if el.tag == SVG + "text":
        k = abs(np.linalg.det(frame[:2, :2])) ** 0.5  # the frame's scale
        px = float(style["font-size"].rstrip("px")) * k
        w = _width(el.text or "", px, style["font-weight"] == "bold")
        x, y, _ = frame @ [float(el.get("x", 0)), float(el.get("y", 0)), 1.0]
        left = {"start": x, "middle": x - w / 2, "end": x - w}[style["text-anchor"]]
        yield el.text, left, left + w, y - 0.8 * px, y + 0.25 * px
    for child in el:
        if child.tag != SVG + "defs":
            yield from _texts(child, frame, style)


def check_picture(text: str) -> int:
    """Assert the picture's background and texts; returns how many texts it has."""
    root = ET.fromstring(text)
    x, y, w, h = _viewbox(root)
    first = next(c for c in root if c.tag not in (SVG + "defs", SVG + "title", SVG + "desc"))
    assert first.tag == SVG + "rect", "the first shape is the background"
    box = [float(first.get(k, 0)) for k in ("x", "y", "width", "height")]
    assert box[0] <= x and box[1] <= y and box[0] + box[2] >= x + w and box[1] + box[3] >= y + h
    assert first.get("fill", "none").lower() not in ("none", "transparent") and "url(" not in first.get("fill")
    assert all(first.get(k) in (None, "1") for k in ("fill-opacity", "opacity")), "an opaque background"
    n = 0
    for s, left, right, top, bottom in _texts(root):
        assert x <= left and right <= x + w and y <= top and bottom <= y + h, (s, (left, right, top, bottom),
                                                                            (x, y, w, h))
        n += 1
    return n


def _demo_families() -> list:
    """Every family with demos, the cheap ones first."""
    from tilesolve import family

    first = ["packing", "stochastic", "board"]
    names = sorted((f.name for f in family.families() if f.demos), key=lambda n: (n not in first, first.index(n)
                                                                                  if n in first else 0, n))
    return names


@pytest.mark.fast_cases(3)
@pytest.mark.parametrize("family", _demo_families())
def test_every_demo_picture_fits_its_captions_on_a_background(tmp_path, family):
    proc = run("demo", "--family", family, "--out", "pics", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    pictures = sorted((tmp_path / "pics").glob("*.svg"))
    assert pictures
    for p in pictures:
        assert check_picture(p.read_text()) >= 1, p.name


def test_long_captions_widen_every_writer():
    """A caption far wider than its picture widens the canvas, in every writer."""
    from tilesolve.io.svg import svg_string
    from tilesolve.io.svg_packing import packing_svg_string
    from tilesolve.io.svg_tileset import tileset_svg_string
    from tilesolve.model.tiles import TileSet

    long = "W" * 30 + " a caption much wider than a tiny picture: " + "M" * 20
    pictures = [
        svg_string(np.array([[0, 1], [1, 0]]), title=long, notes=[long + "!"]),
        packing_svg_string(np.arange(4).reshape(2, 2), "corner", 2, title=long, indices=True),
        tileset_svg_string(TileSet("wang", 2, variant="compact"), title=long),
    ]
    for text in pictures:
        assert check_picture(text) >= 1
        assert long in text


def test_board_picture_widens_to_its_caption():
    from tilesolve.io.svg_board import board_drawing
    from tilesolve.model.board import Board, BoardProblem, WangTileSet

    problem = BoardProblem(Board.rect(2, 1), WangTileSet.brick(3))
    tiling = np.array([[0, 1, 0, 1], [0, 1, 0, 1]])
    text = board_drawing(problem, tiling, title="a board caption, " * 6).tostring()
    assert check_picture(text) == 1
