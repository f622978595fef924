"""The GPU path against the CPU, pixel for pixel (Mesa llvmpipe through EGL in CI).

Nothing here is skipped: a machine without an OpenGL context fails
``test_a_context_can_be_created`` (CI installs ``libegl1 libegl-mesa0 libgl1 libgl1-mesa-dri``).
The references are the CPU implementations: :func:`direct_corner`, :func:`wall_window` and, for
the bricks, :func:`tilesolve.constructive.wall_maps.wall_maps`.
"""

from __future__ import annotations

import numpy as np
import pytest

from tilesolve.constructive.stochastic import direct_corner
from tilesolve.constructive.wall_maps import wall_maps
from tilesolve.constructive.walls import orientation, wall_window
from tilesolve.errors import InvalidProblem
from tilesolve.gpu.context import gpu_info
from tilesolve.gpu.texture import Atlas, TextureMapper, corner_packing, synthesis_scale, synthesize_atlas
from tilesolve.gpu import wall as wall_module
from tilesolve.gpu.wall import WallRenderer, allowed_samples, webgl_wall

HUGE = 2**61 + 12345


def test_a_context_can_be_created():
    info = gpu_info()
    assert info["renderer"] and info["version"].startswith("4.")
    assert info["extensions_int64"]
    assert info["max_texture_size"] >= 4096 and min(info["max_viewport"]) >= 4096


# ------------------------------------------------------------------------------------ texture mapping
@pytest.mark.parametrize("colors,seed,origin,hash_,tile_px", [
    (2, 0, (0, 0), "long", 1),
    (3, 1, (-1000, -77), "long", 3),
    (4, 9, (HUGE, -HUGE), "long", 1),
    (5, 2, (-3, 5), "table", 2),
    (3, 7, (-(2**40), 2**33), "table", 1),
])
def test_tile_ids_equal_the_direct_corner_tiling(colors, seed, origin, hash_, tile_px):
    w, h = 97, 61
    m = TextureMapper(colors=colors, seed=seed, origin=origin, hash=hash_, tile_px=tile_px)
    gpu = m.tile_ids(w, h)
    cols, rows = -(-w // tile_px), -(-h // tile_px)
    cpu = direct_corner(origin[0], origin[1], cols, rows, colors=colors, seed=seed, hash=hash_)
    cpu = np.repeat(np.repeat(cpu, tile_px, axis=0), tile_px, axis=1)[-h:, :w]  # pictures grow from the SW
    assert np.array_equal(gpu, cpu)


@pytest.fixture(scope="module")
def atlas():
    example = np.random.default_rng(5).integers(0, 256, (70, 90, 3), dtype=np.uint8)
    return Atlas.from_example(example, 3, tile=16, seed=2)


def _composite(at: Atlas, grid) -> np.ndarray:
    """The picture the GPU must draw at one pixel per texel: each tile's atlas image, pasted."""
    t, rows = at.tile, at.grid.shape[0]
    pos = {int(k): divmod(i, rows) for i, k in enumerate(at.grid.ravel())}
    out = np.empty((grid.shape[0] * t, grid.shape[1] * t, 4), dtype=np.uint8)
    for (r, q), k in np.ndenumerate(grid):
        ar, ac = pos[int(k)]
        out[r * t:(r + 1) * t, q * t:(q + 1) * t] = at.image[ar * t:(ar + 1) * t, ac * t:(ac + 1) * t]
    return out


@pytest.mark.parametrize("two_pass", [True, False])
@pytest.mark.parametrize("seed,origin", [(4, (-3, -9)), (11, (HUGE, 17))])
def test_texture_pixels_are_the_atlas_tiles_of_the_cpu_tiling(atlas, two_pass, seed, origin):
    m = TextureMapper(atlas, seed=seed, origin=origin, two_pass=two_pass)
    gpu = m.image(16 * 9, 16 * 5)
    cpu = _composite(atlas, direct_corner(origin[0], origin[1], 9, 5, colors=3, seed=seed))
    assert np.array_equal(gpu, cpu)


def test_pictures_larger_than_a_pass_are_drawn_in_passes(atlas):
    m = TextureMapper(atlas, seed=1, origin=(-7, 2), tile_px=5)
    whole = m.image(150, 110)
    m.max_pass = 40  # as if the context's viewport were 40 px: 4 x 3 passes, cut inside tiles
    assert np.array_equal(m.image(150, 110), whole)
    w = WallRenderer(max_line=3, seed=2, origin=(-9, 4), cell_px=7)
    whole = w.image(150, 110)
    w.max_pass = 40
    assert np.array_equal(w.image(150, 110), whole)


def _chequerboard() -> np.ndarray:
    """Squares of 16 px, with noise: a structure too large for 16 px tiles (synthesised at 32)."""
    board = np.repeat(np.repeat(np.indices((6, 6)).sum(axis=0) % 2, 16, 0), 16, 1) * 200
    noise = np.random.default_rng(2).integers(0, 56, (96, 96, 3))
    return (board[..., None] + noise).astype(np.uint8)


@pytest.mark.parametrize("example,scale", [
    (np.random.default_rng(1).integers(0, 256, (40, 40, 3), dtype=np.uint8), 1),
    (_chequerboard(), 2),
])
def test_the_atlas_is_a_packing_with_borders_set_by_the_corners(example, scale):
    c, t = 2, 16
    grid = corner_packing(c, seed=3)
    assert sorted(grid.ravel().tolist()) == list(range(c**4))
    assert grid.shape == (c * c, c * c)
    assert synthesis_scale(example, t) == scale
    img = synthesize_atlas(example, grid, c, tile=t, seed=4)
    tiles = {int(k): img[r * t:(r + 1) * t, q * t:(q + 1) * t] for (r, q), k in np.ndenumerate(grid)}
    # eq. 2.5: k = ((NE c + SE) c + SW) c + NW; a tile's east column depends on NE and SE only,
    # so every tile that can stand west of a given tile shows it the same texels (seamless).
    # Likewise the north row depends on NE and NW only.
    def east(k):
        return k // c**3, (k // c**2) % c

    def north(k):
        return k // c**3, k % c

    for k, tile in tiles.items():
        for k2, other in tiles.items():
            if east(k2) == east(k):
                assert np.array_equal(tile[:, -1], other[:, -1])
            if north(k2) == north(k):
                assert np.array_equal(tile[0], other[0])
    # the atlas wraps: the packing's east neighbour of the last column is the first column
    for r in range(c * c):
        a, b = int(grid[r, -1]), int(grid[r, 0])
        assert (a // c**3, (a // c**2) % c) == (b % c, (b // c) % c)  # NE, SE of a = NW, SW of b


def test_example_smaller_than_a_tile_is_refused():
    with pytest.raises(InvalidProblem, match="smaller than one tile"):
        Atlas.from_example(np.zeros((10, 40, 3), dtype=np.uint8), 2, tile=16)


# ------------------------------------------------------------------------------------ procedural walls
@pytest.mark.parametrize("colors,max_line,seed,origin", [
    (3, None, 0, (0, 0)),
    (3, 1, 3, (-5, -5)),
    (3, 2, 5, (-37, -11)),
    (4, 3, 7, (HUGE, -HUGE)),
    (3, 4, 1, (-1, 3)),
    (5, 6, 2, (10, -9)),
    (6, 7, 11, (123456789, -987654321)),
])
def test_wall_edge_colours_equal_the_cpu_wall(colors, max_line, seed, origin):
    r = WallRenderer(colors=colors, max_line=max_line, seed=seed, origin=origin)
    gpu = r.cell_legs(83, 47)
    cpu = wall_window(origin[0], origin[1], 83, 47, colors=colors, max_line=max_line, seed=seed)
    assert np.array_equal(gpu, cpu)


@pytest.mark.parametrize("per_fragment", [False, True])
@pytest.mark.parametrize("max_line,seed,origin", [(4, 1, (-5, -3)), (None, 8, (HUGE, -40)), (3, 2, (7, 100))])
def test_wall_bricks_distance_and_uv_equal_the_cpu_wall_maps(per_fragment, max_line, seed, origin):
    cell, w, h, nc = 12, 14, 9, 3
    r = WallRenderer(colors=nc, max_line=max_line, seed=seed, origin=origin, cell_px=cell, per_fragment=per_fragment)
    d = r.data(w * cell, h * cell)
    legs = wall_window(origin[0] - 1, origin[1] - 1, w + 2, h + 2, colors=nc, max_line=max_line, seed=seed)
    m = wall_maps(legs, nc, cell, origin=origin)
    assert np.array_equal(d["brick"][..., 0] + np.int64(origin[0]), m.vx)
    assert np.array_equal(d["brick"][..., 1] + np.int64(origin[1]), m.vy)
    assert np.array_equal(d["horizontal"], np.repeat(np.repeat(orientation(legs[1:-1, 1:-1]), cell, 0), cell, 1))
    assert np.allclose(d["distance"], m.distance, atol=1e-5)
    assert np.allclose(d["u"], m.u, atol=1e-5) and np.allclose(d["v"], m.v, atol=1e-5)
    # every brick is one colour away from its border
    inner = m.distance > 0.26  # past the bevel (0.25 cells)
    ids = m.vx[inner] * 100003 + m.vy[inner]
    cols = d["colour"][inner].astype(np.int64) @ np.array([1, 256, 65536, 0])
    for k in np.unique(ids)[:50]:
        assert len(np.unique(cols[ids == k])) == 1


@pytest.mark.parametrize("colors,max_line,seed,origin,cell", [
    (3, 3, 0, (0, 0), 24),           # the studio's view tiles: 24, 16 and 8 px a cell
    (4, None, 5, (HUGE, -HUGE), 16),
    (5, 2, 9, (-37, 11), 8),
    (3, 4, 2, (-7, 3), 6),           # edges on half pixels (1.5, 3, 4.5 px), rounded half to even
    (7, 1, 1, (5, -2), 15),          # mortar lines of round(1.5) = 2 px
    (3, None, 4, (2, 2), 1),         # one pixel a cell: all mortar, as the board pictures draw it
])
def test_the_board_look_is_the_board_pictures(colors, max_line, seed, origin, cell):
    w, h = 13, 9
    gpu = WallRenderer(colors=colors, max_line=max_line, seed=seed, origin=origin, cell_px=cell,
                       look="board").image(w * cell, h * cell)
    assert np.array_equal(gpu, _board_picture(colors, max_line, seed, origin, w, h, cell))


def _board_picture(colors, max_line, seed, origin, w, h, cell) -> np.ndarray:
    """RGBA of the board picture (:func:`brick_image`: the studio's view tiles, `tilesolve board
    --png`) of the wall's ``w x h`` window at ``origin``, ``cell`` px a cell."""
    from tilesolve.io.board_png import brick_image
    from tilesolve.model.board import Board, BoardProblem, WangTileSet
    from tilesolve.model.window import Window

    legs = wall_window(origin[0], origin[1], w, h, colors=colors, max_line=max_line, seed=seed)
    img = brick_image(BoardProblem(Board.rect(w, h), WangTileSet.brick(colors)), legs.reshape(-1, 4),
                      window=Window(origin[0], origin[1], w, h), scale=cell)
    return np.asarray(img.convert("RGBA"))


@pytest.mark.parametrize("colors,max_line,seed,origin", [(3, 3, 0, (0, 0)), (4, None, 5, (HUGE, -HUGE)),
                                                      (5, 2, 9, (-37, 11)), (3, 1, 2, (123456789, -987654321))])
def test_the_webgl2_sources_run_as_glsl_es_give_the_cpu_wall(monkeypatch, colors, max_line, seed, origin):
    # the studio's shaders (GLSL ES 3.00: products from 16-bit halves, no umulExtended), run by llvmpipe
    es = webgl_wall(colors=colors, max_line=max_line, seed=seed)
    monkeypatch.setattr(wall_module, "_HEADER", wall_module._ES_HEADER)
    monkeypatch.setattr(wall_module, "_VERTEX", es["vertex"])
    assert wall_module._fragment("cells") == es["cells"]
    assert wall_module._fragment("colour", look="board") == es["colour"]
    assert wall_module._fragment("data", look="board") == es["data"]
    cell, w, h = 9, 21, 11
    r = WallRenderer(colors=colors, max_line=max_line, seed=seed, origin=origin, cell_px=cell, look="board")
    cpu = wall_window(origin[0] - 1, origin[1] - 1, w + 2, h + 2, colors=colors, max_line=max_line, seed=seed)
    assert np.array_equal(r.cell_legs(w, h), cpu[1:-1, 1:-1])
    d, m = r.data(w * cell, h * cell), wall_maps(cpu, colors, cell, origin=origin)
    assert np.array_equal(d["brick"][..., 0] + np.int64(origin[0]), m.vx)
    assert np.array_equal(d["brick"][..., 1] + np.int64(origin[1]), m.vy)
    assert np.array_equal(r.image(w * cell, h * cell), _board_picture(colors, max_line, seed, origin, w, h, cell))


@pytest.mark.parametrize("look", wall_module.LOOKS)
def test_multisampling_as_far_as_the_context_allows(look):
    allowed = allowed_samples()
    assert allowed[0] == 1 and set(allowed) <= {1, 2, 4, 8, 16, 32}
    # 5 colours put the edges at sixths of 20 px, between pixels (with whole-pixel edges, as 3
    # colours and 20 px give, the board look has no sample on another side than its pixel's centre)
    one = WallRenderer(colors=5, max_line=4, seed=3, cell_px=20, look=look).image(120, 80).astype(int)
    for s in allowed[1:]:
        many = WallRenderer(colors=5, max_line=4, seed=3, cell_px=20, samples=s, look=look).image(120, 80).astype(int)
        diff = np.abs(many - one).max(axis=2)
        assert 0 < (diff > 0).mean() < 0.5  # only pixels on brick borders change
    too_many = [s for s in (1, 2, 4, 8, 16, 32) if s not in allowed]
    for s in too_many[:1]:
        with pytest.raises(InvalidProblem, match="at most"):
            WallRenderer(samples=s)
    with pytest.raises(InvalidProblem, match="one of"):
        WallRenderer(samples=3)


def test_an_unknown_look_is_refused():
    with pytest.raises(InvalidProblem, match="look must be one of brick, board"):
        WallRenderer(look="photo")
