"""Streamed PNG rows (write_packed_rows), the cell pictures of edge_image (cell_pixels), and the
captions under every command's PNG (issue 22)."""

from __future__ import annotations

import io

import numpy as np
import png
import pytest
from clitools import run
from PIL import Image

from tilesolve.io.png import cell_pixels, edge_image, write_packed_rows


def _read(data: bytes) -> np.ndarray:
    w, h, rows, info = png.Reader(bytes=data).read()
    return np.array([np.frombuffer(bytes(r), np.uint8) if info["bitdepth"] == 8 else list(r) for r in rows])


@pytest.mark.parametrize("mode", ["palette", "grey", "rgb"])
def test_rows_written_with_the_up_filter_read_back_the_same(mode):
    rng = np.random.default_rng(3)
    planes = 3 if mode == "rgb" else 1
    base = rng.integers(0, 4, (40, 30 * planes), dtype=np.uint8)
    pixels = np.repeat(base, 3, axis=0)  # every row three times
    pixels[7] = 9  # and one row that differs from both neighbours
    kw = {"palette": [(k, k, k) for k in range(10)]} if mode == "palette" else {"greyscale": mode == "grey"}
    writer = png.Writer(30, len(pixels), bitdepth=8, compression=6, **kw)
    plain, filtered = io.BytesIO(), io.BytesIO()
    writer.write_packed(plain, (r.tobytes() for r in pixels))
    write_packed_rows(writer, filtered, (r.tobytes() for r in pixels))
    assert np.array_equal(_read(filtered.getvalue()), pixels)
    assert np.array_equal(_read(filtered.getvalue()), _read(plain.getvalue()))
    head = plain.getvalue().index(b"IDAT") - 4  # up to the first IDAT chunk's length
    assert filtered.getvalue()[:head] == plain.getvalue()[:head]  # the same header and palette


@pytest.mark.parametrize("kind", ["wang", "corner"])
@pytest.mark.parametrize("scale", [2, 4, 9])
def test_cell_pixels_are_the_cells_of_edge_image(kind, scale):
    colours = np.random.default_rng(scale).integers(0, 5, (6, 4))
    img = np.asarray(edge_image(colours, [(r, c) for r in range(2) for c in range(3)], (2, 3), kind, scale=scale))
    cells = cell_pixels(colours, kind, scale).reshape(2, 3, scale, scale).transpose(0, 2, 1, 3)
    assert np.array_equal(img, cells.reshape(2 * scale, 3 * scale))
    assert (cells[..., 0, :, 0] == 255).all() == (scale >= 8)


# ----------------------------------------------------------------------------- captions (issue 22)
def test_a_caption_goes_under_the_picture_and_nothing_else_moves(tmp_path):
    from tilesolve.io.png import caption_mask, write_png

    t = np.array([[0, 1, 1], [1, 0, 2]])
    write_png(tmp_path / "plain.png", t, scale=40)
    write_png(tmp_path / "caption.png", t, scale=40, caption=["a caption long enough to wrap in 120 px", "seed 3"])
    plain, captioned = (np.asarray(Image.open(tmp_path / f).convert("RGB")) for f in ("plain.png", "caption.png"))
    assert np.array_equal(captioned[:80], plain) and len(captioned) > 80 + 3 * 16  # wrapped: three lines or more
    below = captioned[80:]
    ink = (below < 100).all(axis=2)
    assert ink.any() and ink.mean() < 0.3 and (below[~ink] > 200).all()  # dark text on near-white
    assert not ink[:, :4].any() and not ink[:, -4:].any()  # inside its margins
    assert caption_mask(["x" * 500], 120).shape[1] == 120  # a word wider than the picture breaks


def _caption_band(path) -> np.ndarray:
    rgb = np.asarray(Image.open(path).convert("RGB")).astype(int)
    return rgb[-24:]


@pytest.mark.fast_cases(2)
@pytest.mark.parametrize("args,picture", [
    (["dappled", "solve", "--size", "30x20", "--cond", "H0=2,V1=2", "--seed", "1", "--png", "p.png"], "p.png"),
    (["tiles", "--kind", "wang", "--colors", "3", "--png", "p.png"], "p.png"),
    (["tiling", "--kind", "corner", "--method", "direct", "--colors", "3", "--region", "0,0,20x10", "--seed", "1",
      "--png", "p.png"], "p.png"),
    (["penrose", "--kind", "p2", "--method", "substitution", "--steps", "3", "--png", "p.png"], "p.png"),
    (["aperiodic", "tiling", "--builtin", "kari-culik-13", "--region", "0,0,12x8", "--seed", "1", "--png", "p.png"],
     "p.png"),
    (["shapes", "tile", "--grid", "omino", "--shape", "XX/XX/X.", "--region", "5x2", "--png", "p.png"], "p.png"),
])
def test_every_png_carries_its_caption(tmp_path, args, picture):
    """The PNGs of the commands, like their SVGs, say what they show: lines of dark text on a
    light band under the picture."""
    proc = run(*args, cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    band = _caption_band(tmp_path / picture)
    luma = band @ np.array([0.299, 0.587, 0.114])
    assert (luma > 235).mean() > 0.7 and (luma < 110).mean() > 0.005, "no caption under the picture"


def test_draw_gives_packings_and_boards_their_caption(tmp_path):
    for make in (["pack", "--kind", "corner", "--colors", "3", "--seed", "1", "-o", "s.json"],
                 ["brick", "solve", "--board", "torus:12x8", "--seed", "1", "-o", "s.json"]):
        assert run(*make, cwd=tmp_path).returncode == 0
        assert run("draw", "s.json", "-o", "s.png", cwd=tmp_path).returncode == 0
        luma = _caption_band(tmp_path / "s.png") @ np.array([0.299, 0.587, 0.114])
        assert (luma > 235).mean() > 0.7 and (luma < 110).mean() > 0.005, make[0]


def test_a_dappled_png_lists_its_tiles_colours_like_its_svg(tmp_path):
    from tilesolve.io.png import write_png

    t = np.array([[0, 1, 2], [2, 1, 0]])
    write_png(tmp_path / "t.png", t, scale=60, legend=True, caption=["3 tiles"])
    with Image.open(tmp_path / "t.png") as img:
        idx = np.asarray(img)
    below = idx[120:]
    for k in range(3):  # a swatch of each tile's palette colour (index k + 1), outlined, under the picture
        assert (below == k + 1).sum() == 100
    assert (below == 255).sum() > 3 * 44  # outlines and the labels' ink


@pytest.mark.parametrize("width", [120, 216, 333])
def test_wrapped_captions_keep_their_right_margin(width):
    """Lines are measured as they are drawn (no anti-aliasing): the packing's caption at 216 px
    ran 7 px past its margin and was cut at the picture's edge (issue 22's clipped captions)."""
    from tilesolve.io.png import caption_mask

    lines = ["complete wang tile set over 3 colours (81 tiles) packed into a 9x9 torus (sat, seed 1)",
             "witness: the square 12x12 tiled (sat, seed 1) " * 3, "W" * 80]
    mask = caption_mask(lines, width)
    assert mask.any() and not mask[:, :4].any() and not mask[:, -4:].any()
