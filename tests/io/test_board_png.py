"""Brick pictures of boards at any size (tilesolve.io.board_png): every brick one colour, its
regions the bricks of the SVG (tilesolve.io.svg_board.brick_ids), neighbouring windows of one
wall agreeing, and through the console script a large board drawn as bricks."""

from __future__ import annotations

import numpy as np
import pytest
from PIL import Image

from tests.clitools import run
from tilesolve.constructive.brick import solve_linear
from tilesolve.io.board_png import HOLE, brick_image
from tilesolve.io.svg_board import brick_ids
from tilesolve.io.wall_png import MORTAR
from tilesolve.model.board import Board, BoardProblem, WangTileSet
from tilesolve.model.window import Window

S = 12


def corners(img: Image.Image, rows: int, cols: int) -> np.ndarray:
    """``(rows * cols, 4)`` palette index of each cell's corner pixels TL, TR, BL, BR."""
    px = np.asarray(img).reshape(rows, S, cols, S)
    return np.stack([px[:, 0, :, 0], px[:, 0, :, -1], px[:, -1, :, 0], px[:, -1, :, -1]], axis=-1).reshape(-1, 4)


@pytest.mark.parametrize("colors, seed", [(3, 0), (4, 1), (6, 2)])
def test_each_brick_of_the_svg_is_one_colour(colors, seed):
    p = BoardProblem(Board.rect(9, 7), WangTileSet.brick(colors))
    t = solve_linear(p, seed=seed).tiling
    img = brick_image(p, t, scale=S)
    assert img.size == (9 * S, 7 * S)
    got, ids = corners(img, 7, 9), brick_ids(p, t)
    assert not np.isin(got, [MORTAR, HOLE]).any()  # a cell's corners lie inside bricks
    for brick in np.unique(ids):
        assert len(np.unique(got[ids == brick])) == 1
    assert (np.asarray(img) == MORTAR).mean() > 0.05  # the mortar between them is drawn


def test_neighbouring_windows_agree_on_brick_colours():
    p = BoardProblem(Board.rect(8, 8), WangTileSet.brick(3))
    t = solve_linear(p, seed=3).tiling
    a = np.asarray(brick_image(p, t, window=Window(16, 0, 8, 8), scale=S))
    b = np.asarray(brick_image(p, t, window=Window(24, 0, 8, 8), scale=S))
    c = np.asarray(brick_image(p, t, window=Window(16, 0, 8, 8), scale=S))
    assert (a == c).all() and (a != b).any()  # the colour is the brick's place in the plane


def test_a_large_board_png_from_the_cli_is_bricks(tmp_path):
    r = run("brick", "solve", "--board", "rect:200x120", "--colors", "3", "--seed", "1", "-o", "b.json", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    r = run("draw", "b.json", "-o", "b.png", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    with Image.open(tmp_path / "b.png") as img:
        assert img.mode == "P" and img.width >= 4 * 200
        assert 0.05 < (np.asarray(img) == MORTAR).mean() < 0.5


@pytest.mark.parametrize("origin", [(0, 0), (-37, 11), (2**61 + 5, -(2**61))])
def test_the_board_picture_and_the_id_map_colour_each_brick_alike(origin):
    # one brick hash (tilesolve.model.brick_colour): a wall window's board picture gives every
    # brick the colour of the wall-map id map's brick (away from the edges, which the board
    # picture rounds to whole pixels)
    from tilesolve.constructive.wall_maps import wall_maps
    from tilesolve.model.brick_colour import brick_colour_index
    from tilesolve.constructive.walls import wall_window
    from tilesolve.io.wall_png import N_BRICK_COLOURS

    w, h, colors = 11, 7, 4
    halo = wall_window(origin[0] - 1, origin[1] - 1, w + 2, h + 2, colors=colors, max_line=3, seed=6)
    p = BoardProblem(Board.rect(w, h), WangTileSet.brick(colors))
    img = np.asarray(brick_image(p, halo[1:-1, 1:-1].reshape(-1, 4), window=Window(*origin, w, h), scale=S))
    m = wall_maps(halo, colors, S, origin=origin)
    inside = m.distance > 2.0 / S
    assert inside.mean() > 0.3
    assert np.array_equal(img[inside], brick_colour_index(m.vx, m.vy, N_BRICK_COLOURS)[inside])
