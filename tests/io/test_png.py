"""Streamed PNG rows (write_packed_rows) and the cell pictures of edge_image (cell_pixels)."""

from __future__ import annotations

import io

import numpy as np
import png
import pytest

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
