"""Windows of stochastic tilings as PNG, streamed band by band."""

from __future__ import annotations

import numpy as np
import pytest
from PIL import Image

from tilesolve.io import stochastic_png
from tilesolve.io.png import edge_image
from tilesolve.io.svg_packing import colour_of
from tilesolve.model.tiles import TileSet


@pytest.mark.parametrize("kind, colors, scale", [("corner", 3, 4), ("wang", 2, 8), ("corner", 4, 5)])
def test_bands_and_tile_tables_draw_the_picture_of_edge_image(tmp_path, monkeypatch, kind, colors, scale):
    """The same pixels and palette from the table of every tile's picture and tile by tile, in
    bands of a few rows, as edge_image draws the whole window."""
    ts = TileSet(kind, colors)
    grid = np.random.default_rng(colors).integers(0, ts.n_tiles, (11, 7))
    whole = edge_image(np.stack(ts.colors_of(grid.ravel()), axis=1),
                       np.stack(np.divmod(np.arange(grid.size), 7), axis=1), grid.shape, kind, scale=scale,
                       palette=colour_of)
    monkeypatch.setattr(stochastic_png, "BAND_PIXELS", 3 * 7 * scale * scale)  # bands of 3 tile rows
    for table in (stochastic_png.TABLE_BYTES, 0):
        monkeypatch.setattr(stochastic_png, "TABLE_BYTES", table)
        stochastic_png.write_window_png(tmp_path / "w.png", grid, kind, colors, scale=scale)
        with Image.open(tmp_path / "w.png") as img:
            assert np.array_equal(np.asarray(img), np.asarray(whole))
            assert img.getpalette()[3:3 * (colors + 1)] == whole.getpalette()[3:3 * (colors + 1)]
