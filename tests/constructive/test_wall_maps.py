"""Brick maps of procedural walls (004 §3.2, Fig. 9-10, 19): bricks merged from the edge
structure, ids stable across windows, distance to the edges and Cartesian UV."""

from __future__ import annotations

import numpy as np
import pytest

from tilesolve.constructive.wall_maps import wall_maps
from tilesolve.model.brick_colour import brick_colour_index
from tilesolve.constructive.walls import wall_window
from tilesolve.errors import InvalidProblem
from tilesolve.io.svg_board import brick_ids
from tilesolve.model.board import Board, BoardProblem, WangTileSet
from tilesolve.families.wall_render import wall_map_pixels

WINDOWS = [  # (x0, y0, w, h, colors, max_line, seed)
    (0, 0, 9, 7, 3, 2, 1),
    (-1000, 37, 12, 5, 4, 3, 2),
    (1 << 40, -(1 << 41), 6, 10, 5, None, 3),
    (-17, -4, 11, 11, 3, 1, 4),
    (5, 5, 1, 1, 3, 4, 5),
]


def maps_of(x0, y0, w, h, colors, max_line, seed, ppc):
    legs = wall_window(x0 - 1, y0 - 1, w + 2, h + 2, colors=colors, max_line=max_line, seed=seed)
    return legs, wall_maps(legs, colors, ppc, origin=(x0, y0))


@pytest.mark.parametrize("win", WINDOWS)
@pytest.mark.parametrize("ppc", [1, 5, 12])
def test_every_pixel_lies_inside_its_brick(win, ppc):
    _, m = maps_of(*win, ppc)
    assert m.vx.shape == (win[3] * ppc, win[2] * ppc)
    assert (m.distance >= 0).all() and (m.distance <= 1).all()
    for q in (m.u, m.v):
        assert (q >= 0).all() and (q <= 1).all()


@pytest.mark.parametrize("win", WINDOWS[:4])
def test_bricks_are_the_regions_the_svg_merges(win):
    """The brick around a lattice vertex is what union-find over the cells' corner regions
    (the SVG drawing, tilesolve.io.svg_board.brick_ids) calls one brick: one id per brick
    both ways, for every cell corner region of the window."""
    x0, y0, w, h, colors, n, seed = win
    ppc = 24
    legs, m = maps_of(*win, ppc)
    inner = legs[1:-1, 1:-1]
    problem = BoardProblem(Board.rect(w, h), WangTileSet.brick(colors), None)
    svg_ids = brick_ids(problem, inner.reshape(-1, 4)).reshape(h, w, 4)  # TL, TR, BL, BR
    ys, xs = np.mgrid[0:h * ppc, 0:w * ppc]
    r, c = ys // ppc, xs // ppc
    # which corner of its cell the pixel's brick vertex is: cell (r, c) has corners
    # (x0 + c, y_top + 1) .. with y_top the cell's own row coordinate
    cell_x, cell_y = x0 + c, y0 + h - 1 - r
    right = m.vx - cell_x  # 0: west corner, 1: east corner
    lower = cell_y + 1 - m.vy  # 0: north corner, 1: south corner
    assert set(np.unique(right)) <= {0, 1} and set(np.unique(lower)) <= {0, 1}
    region = 2 * lower + right
    svg = svg_ids[r, c, region]
    pairs = {(int(a), int(b), int(s)) for a, b, s in zip(m.vx.ravel(), m.vy.ravel(), svg.ravel())}
    assert len({(a, b) for a, b, _ in pairs}) == len(pairs) == len({s for _, _, s in pairs})
    # and every corner region of every cell shows up at this resolution
    assert len({s for _, _, s in pairs}) == len(np.unique(svg_ids))


@pytest.mark.parametrize("win", WINDOWS[:3])
def test_windows_agree_where_they_overlap(win):
    x0, y0, w, h, colors, n, seed = win
    ppc = 6
    _, big = maps_of(x0, y0, w, h, colors, n, seed, ppc)
    _, part = maps_of(x0 + 2, y0 + 1, w - 3, h - 2, colors, n, seed, ppc)
    # part covers columns 2..w-2, rows (from the top) 1..h-2
    sl = np.s_[ppc:(h - 1) * ppc, 2 * ppc:(w - 1) * ppc]
    for name in ("vx", "vy", "distance", "u", "v"):
        assert np.array_equal(getattr(big, name)[sl], getattr(part, name)), name


def test_a_horizontal_cell_by_hand():
    """Horizontal tiles (W = E = 1 of 3 colours: the line at 1/2); the inner cell has N at 3/4
    and S at 1/4, the rows above and below N at 1/4 and S at 3/4 (004 Fig. 5, 7)."""
    legs = np.zeros((3, 3, 4), dtype=np.int8)
    legs[..., 3] = legs[..., 1] = 1  # W = E
    legs[..., 0], legs[..., 2] = 0, 2  # N, S
    legs[1, :, 0], legs[1, :, 2] = 2, 0
    m = wall_maps(legs, 3, 10, origin=(10, 20))
    # pixel (u, v) = (0.35, 0.15): top-left region, the brick around the NW vertex (10, 21),
    # spanning x -0.25..0.75 and y -0.5..0.5 around the cell
    assert (m.vx[1, 3], m.vy[1, 3]) == (10, 21)
    assert (m.distance[1, 3], m.u[1, 3], m.v[1, 3]) == pytest.approx((0.35, 0.6, 0.35))
    # pixel (0.65, 0.75): bottom-right region, the brick around the SE vertex (11, 20),
    # spanning x 0.25..1.25 and y 0.5..1.5
    assert (m.vx[7, 6], m.vy[7, 6]) == (11, 20)
    assert (m.distance[7, 6], m.u[7, 6], m.v[7, 6]) == pytest.approx((0.25, 0.4, 0.75))
    # the half lines: down from the top at 3/4, up from the bottom at 1/4
    assert (m.vx[:5, :7] == 10).all() and (m.vx[:5, 8:] == 11).all()
    assert (m.vx[5:, :2] == 10).all() and (m.vx[5:, 3:] == 11).all()
    assert (m.vy[:5] == 21).all() and (m.vy[5:] == 20).all()


@pytest.mark.parametrize("win", WINDOWS)
@pytest.mark.parametrize("kind", ["id", "distance", "uv"])
@pytest.mark.parametrize("ppc", [1, 4, 9])
def test_compiled_pixels_equal_the_numpy_maps(win, kind, ppc):
    x0, y0, w, h, colors, n, seed = win
    legs = wall_window(x0 - 1, y0 - 1, w + 2, h + 2, colors=colors, max_line=n, seed=seed)
    a = wall_map_pixels(legs, kind, colors=colors, ppc=ppc, origin=(x0, y0))
    b = wall_map_pixels(legs, kind, colors=colors, ppc=ppc, origin=(x0, y0), compiled=False)
    assert a.dtype == np.uint8 and a.shape == b.shape and np.array_equal(a, b)


def test_id_colours_are_stable_and_spread():
    vx, vy = np.meshgrid(np.arange(-50, 50), np.arange(-50, 50))
    a = brick_colour_index(vx, vy, 254)
    assert np.array_equal(a, brick_colour_index(vx, vy, 254))
    assert a.min() >= 0 and a.max() < 254
    assert len(np.unique(a)) > 240  # 10,000 vertices cover nearly every colour
    assert (a[:, 1:] != a[:, :-1]).mean() > 0.98  # neighbours differ


def test_bad_input():
    with pytest.raises(InvalidProblem, match="halo"):
        wall_maps(np.zeros((2, 5, 4), dtype=np.int8), 3, 2)
    with pytest.raises(InvalidProblem, match="at least 1"):
        wall_maps(np.zeros((3, 3, 4), dtype=np.int8), 3, 0)
    with pytest.raises(InvalidProblem, match="unknown wall map"):
        wall_map_pixels(np.zeros((3, 3, 4), dtype=np.int8), "phase", colors=3, ppc=2, origin=(0, 0))
