"""Files: atomic writes, the shared JSON helpers (tilesolve.io.jsonio), SVG and PNG pictures."""

from __future__ import annotations

import json
import os
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from tilesolve.errors import InvalidProblem
from tilesolve.io import jsonio
from tilesolve.io.atomic import atomic_write, write_text_atomic
from tilesolve.io.dappled_json import DAPPLED_FORMATS
from tilesolve.io.png import tiling_image, write_png
from tilesolve.io.svg import MAX_SVG_CELLS, PALETTE, svg_string, tile_colour, write_svg
from tilesolve.model.dappled import Condition, DappledProblem, parse_condition

SVG_NS = "{http://www.w3.org/2000/svg}"

# A 4x3 tiling satisfying H0=2 and V1=2 (checked in test_fixture_is_dappled).
TILING = np.array([[0, 0, 1, 0], [1, 0, 0, 1], [0, 1, 1, 0]])


def _problem(**kw) -> DappledProblem:
    return DappledProblem.from_strings("4x3", ["H0=2", "V1=2"], **kw)


def test_fixture_is_dappled():
    from tilesolve.verify.dappled import is_dappled

    assert is_dappled(_problem(), TILING)


# ----------------------------------------------------------------------------- atomic
def test_atomic_write_replaces_file(tmp_path):
    path = tmp_path / "a.txt"
    path.write_text("old")
    write_text_atomic(path, "new")
    assert path.read_text() == "new"
    assert os.listdir(tmp_path) == ["a.txt"]


@pytest.mark.parametrize("exc", [RuntimeError, KeyboardInterrupt])
def test_atomic_write_leaves_nothing_on_failure(tmp_path, exc):
    path = tmp_path / "a.txt"
    path.write_text("old")
    with pytest.raises(exc):
        with atomic_write(path) as f:
            f.write("half")
            raise exc()
    assert path.read_text() == "old"
    assert os.listdir(tmp_path) == ["a.txt"]
    with pytest.raises(exc):
        with atomic_write(tmp_path / "b.txt", "wb") as f:
            f.write(b"half")
            raise exc()
    assert os.listdir(tmp_path) == ["a.txt"]


def test_atomic_write_uses_umask_permissions(tmp_path):
    old = os.umask(0o022)
    try:
        write_text_atomic(tmp_path / "p.txt", "x")
    finally:
        os.umask(old)
    assert (tmp_path / "p.txt").stat().st_mode & 0o777 == 0o644


def test_atomic_write_missing_directory(tmp_path):
    with pytest.raises(OSError):
        write_text_atomic(tmp_path / "nope" / "a.txt", "x")


# ----------------------------------------------------------------------------- json
@pytest.mark.parametrize("low, high", [(0, 2), (0, 10), (-1, 3), (0, 130)])
def test_dumps_writes_numpy_grids_like_lists(low, high):
    t = np.random.default_rng(1).integers(low, high, (6, 9))
    doc = json.loads(jsonio.dumps({"tiling": t, "nested": [t], "empty": np.zeros((0, 0), int)}))
    assert doc == {"tiling": t.tolist(), "nested": [t.tolist()], "empty": []}


def test_reader_rejects_bad_json_and_missing_file(tmp_path):
    path = tmp_path / "bad.json"
    path.write_text('{"format": ')
    with pytest.raises(InvalidProblem, match="malformed JSON at line 1"):
        jsonio.load_document(path, DAPPLED_FORMATS)
    with pytest.raises(InvalidProblem, match="no such file"):
        jsonio.load_document(tmp_path / "missing.json", DAPPLED_FORMATS)
    path.write_text("[1, 2]")
    with pytest.raises(InvalidProblem, match="not a tilesolve file"):
        jsonio.load_document(path, DAPPLED_FORMATS)


# ----------------------------------------------------------------------------- svg
def _parse(text: str) -> ET.Element:
    return ET.fromstring(text)


def test_svg_is_valid_xml_with_legend():
    root = _parse(svg_string(TILING, problem=_problem(), notes=["sat by test"]))
    assert root.tag == SVG_NS + "svg"
    texts = [t.text for t in root.iter(SVG_NS + "text")]
    assert "tile 0" in texts and "tile 1" in texts
    assert any("4x3 grid" in t for t in texts) and any("H0=2, V1=2" in t for t in texts)
    assert "sat by test" in texts
    fills = {e.get("fill") for e in root.iter() if e.get("fill")}
    assert {PALETTE[0], PALETTE[1]} <= fills


def test_svg_legend_shows_per_cell_ranges():
    lim = np.array([[2, 3, 0, 5]] * 3, dtype=np.int32)
    p = DappledProblem(3, 4, conditions=(Condition("H", (0,), lim), parse_condition("V1=2")))
    texts = [t.text for t in _parse(svg_string(TILING, problem=p)).iter(SVG_NS + "text")]
    assert any("H0=2..5 per cell, V1=2" in t for t in texts)


def test_svg_cells_are_drawn_exactly():
    """Rebuild the tiling from the drawn rectangles (background = most common tile)."""
    t = np.array([[0, 1, 1, 2], [2, 2, 2, 0], [1, 0, 1, 1]])
    root = _parse(svg_string(t, cell=10, legend=False, grid=False))
    block = next(g for g in root.iter(SVG_NS + "g") if g.get("id") == "block")
    back = block.find(SVG_NS + "rect")
    colour_to_tile = {tile_colour(k): k for k in range(3)}
    out = np.full(t.shape, colour_to_tile[back.get("fill")])
    for g in block.findall(SVG_NS + "g"):
        tile = colour_to_tile[g.get("fill")]
        for r in g.findall(SVG_NS + "rect"):
            x, y, w = (int(float(r.get(k))) // 10 for k in ("x", "y", "width"))
            out[y, x : x + w] = tile
    assert np.array_equal(out, t)


def test_svg_repeat_and_grid():
    root = _parse(svg_string(TILING, repeat=3, grid=True))
    uses = list(root.iter(SVG_NS + "use"))
    assert len(uses) == 9
    dashed = [p for p in root.iter(SVG_NS + "path") if p.get("stroke-dasharray")]
    assert len(dashed) == 1  # the seams
    root = _parse(svg_string(TILING, grid=False))
    assert not list(root.iter(SVG_NS + "path"))


def test_svg_refuses_huge_tilings_and_bad_input(tmp_path):
    side = int(MAX_SVG_CELLS**0.5) + 1
    with pytest.raises(InvalidProblem, match="PNG"):
        svg_string(np.zeros((side, side), dtype=np.int8))
    with pytest.raises(InvalidProblem):
        svg_string(np.zeros(5, dtype=int))
    with pytest.raises(InvalidProblem, match="repeat"):
        svg_string(TILING, repeat=0)
    write_svg(tmp_path / "t.svg", TILING)
    assert (tmp_path / "t.svg").read_text().startswith("<?xml")


def test_palette_is_distinct():
    colours = [tile_colour(k) for k in range(40)]
    assert len(set(colours)) == 40
    assert tile_colour(-1) not in colours


# ----------------------------------------------------------------------------- png
def test_png_pixels_match_tiles(tmp_path):
    path = tmp_path / "t.png"
    write_png(path, TILING, scale=2, repeat=2, grid=False)
    from PIL import Image

    with Image.open(path) as img:
        assert img.size == (4 * 2 * 2, 3 * 2 * 2)
        rgb = np.asarray(img.convert("RGB"))
    for r in range(6):
        for c in range(8):
            want = tile_colour(int(TILING[r % 3, c % 4]))
            got = "#{:02X}{:02X}{:02X}".format(*rgb[2 * r, 2 * c])
            assert got == want


def test_png_default_scale_and_limits():
    img = tiling_image(np.zeros((2000, 1000), dtype=np.int8))
    assert img.size == (1000, 2000) and img.mode == "P"
    assert tiling_image(TILING).size == (4 * 16, 3 * 16)
    with pytest.raises(InvalidProblem, match="scale"):
        tiling_image(TILING, scale=0)


# ----------------------------------------------------------------------------- docs
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def test_readme_install_command():
    """The quick start's install command (the test command: tests/test_readme.py)."""
    with open(os.path.join(ROOT, "README.md"), encoding="utf-8") as f:
        readme = f.read()
    assert "pip install . && tilesolve demo" in readme


