"""Textures over aperiodic Wang sets (tilesolve/gpu/wang_texture.py): the GPU picture against the
CPU picture pixel for pixel, the tiles of both against the constructive routes' verified windows,
the shader's Markov coding against :func:`tilesolve.constructive.markov.markov_window`."""

from __future__ import annotations

import numpy as np
import pytest

from tilesolve.constructive.markov import BLOCK, markov_window
from tilesolve.errors import InvalidProblem
from tilesolve.families.aperiodic_window import tiling
from tilesolve.gpu.texture import synthesis_scale
from tilesolve.gpu.wang_texture import SINGLE_CELLS, WangAtlas, WangTexture, WangTextureMapper
from tilesolve.io.builtin_tilesets import load
from tilesolve.model.window import Window

SETS = ("jeandel-rao", "labbe-u19", "kari-14", "kari-culik-13")
TILE = 16
EXAMPLE = np.random.default_rng(5).integers(0, 256, (60, 70, 3), dtype=np.uint8)


@pytest.fixture(scope="module")
def atlases() -> dict:
    return {name: WangAtlas.from_example(EXAMPLE, load(name)[0].tiles, tile=TILE, seed=3) for name in SETS}


def route(name: str, x0: int, y0: int, width: int, height: int, seed: int) -> np.ndarray:
    """The verified window of the set's constructive route (the family's facade)."""
    _, sol = tiling(name, (x0, y0, width, height), seed=seed)
    return np.asarray(sol.tiling)


@pytest.mark.parametrize("name", SETS)
@pytest.mark.parametrize("tile_px,origin", [(TILE, (0, 0)), (5, (-37, 12)), (23, (4, -9)), (1, (100, 3))])
def test_gpu_and_cpu_pictures_are_identical(atlases, name, tile_px, origin):
    at = atlases[name]
    cpu = WangTexture(name, at, seed=2, origin=origin, tile_px=tile_px).image(101, 67)
    gpu = WangTextureMapper(name, at, seed=2, origin=origin, tile_px=tile_px)
    assert np.array_equal(gpu.image(101, 67), cpu)
    gpu.max_pass = 30  # as if the viewport were 30 px: passes cut inside tiles
    assert np.array_equal(gpu.image(101, 67), cpu)


@pytest.mark.parametrize("name", SETS)
def test_each_cell_shows_the_tile_of_the_route_window(atlases, name):
    at, origin, cols, rows = atlases[name], (-6, 4), 9, 5
    want = route(name, origin[0], origin[1], cols, rows, 7)
    for picture in (WangTexture(name, at, seed=7, origin=origin), WangTextureMapper(name, at, seed=7, origin=origin)):
        img = picture.image(cols * TILE, rows * TILE)
        for (r, c), k in np.ndenumerate(want):
            assert np.array_equal(img[r * TILE:(r + 1) * TILE, c * TILE:(c + 1) * TILE], at.block(k)), (r, c)
    assert np.array_equal(WangTextureMapper(name, at, seed=7, origin=origin).cell_tiles(0, 0, cols, rows), want)


@pytest.mark.parametrize("name", ["jeandel-rao", "labbe-u19"])
@pytest.mark.parametrize("origin", [(0, 0), (-(10**15), 3 * 10**12), (2**61, -(2**61))])
def test_the_shader_codes_the_markov_partition(atlases, name, origin):
    m = WangTextureMapper(name, atlases[name], seed=11, origin=origin)
    want = markov_window(name, Window(origin[0], origin[1], 120, 80), 11)
    got = m._markov.code(origin[0], origin[1], 120, 80)
    decided = got != 255
    assert decided.mean() > 0.99
    assert np.array_equal(got[decided], want[decided])
    assert np.array_equal(m.cell_tiles(0, 0, 120, 80), want)
    assert m.decided == decided.sum() and m.undecided == (~decided).sum()


@pytest.mark.parametrize("name", ["jeandel-rao", "labbe-u19"])
def test_the_shader_codes_passes_longer_than_a_block(atlases, name):
    """Rows and columns of more than BLOCK cells: their points come from several exact anchors."""
    m = WangTextureMapper(name, atlases[name], seed=5)
    for x, y, cols, rows in ((-(2**40), 7, BLOCK + 100, 2), (3, 2**50, 2, BLOCK + 100)):
        got = m._markov.code(x, y, cols, rows)
        decided = got != 255
        assert decided.mean() > 0.99
        assert np.array_equal(got[decided], markov_window(name, Window(x, y, cols, rows), 5)[decided])


@pytest.mark.parametrize("tile_px,tolerance,few", [(2, 0.02, False), (8, 0.003, True)])
def test_cells_the_shader_cannot_decide_come_from_the_cpu_route(atlases, tile_px, tolerance, few):
    """As if the shader's arithmetic were coarser: many undecided cells (the pass's window from
    the CPU route) or a few (one cell at a time); the picture stays the CPU's."""
    name, origin = "jeandel-rao", (-500, 77)
    m = WangTextureMapper(name, atlases[name], seed=4, origin=origin, tile_px=tile_px)
    m._markov.tolerance = tolerance
    img = m.image(160, 90)
    assert (0 < m.undecided <= SINGLE_CELLS) if few else (m.undecided > 0.1 * m.decided)
    assert np.array_equal(img, WangTexture(name, atlases[name], seed=4, origin=origin, tile_px=tile_px).image(160, 90))


@pytest.mark.parametrize("name", ["jeandel-rao", "kari-culik-13"])
def test_the_same_seed_gives_the_same_picture_and_another_seed_another(name):
    tiles = load(name)[0].tiles
    pictures = [WangTextureMapper(name, WangAtlas.from_example(EXAMPLE, tiles, tile=TILE, seed=s), seed=s).image(96, 64)
                for s in (1, 1, 2)]
    assert np.array_equal(pictures[0], pictures[1])
    assert not np.array_equal(pictures[0], pictures[2])


#: Squares of 32 px with noise: structures too large for tiles of 20 texels (synthesised at 80).
SQUARES = (np.repeat(np.repeat(np.indices((3, 3)).sum(axis=0) % 2, 32, 0), 32, 1)[..., None] * 200
           + np.random.default_rng(6).integers(0, 56, (96, 96, 3))).astype(np.uint8)


@pytest.mark.parametrize("example,scale", [(EXAMPLE, 1), (SQUARES, 4)])
def test_matching_edges_show_one_diamond(example, scale):
    """Away from the corners (where two diamonds meet), a border of a tile depends on that edge's
    colour only, and the N/S and E/W colours have diamonds of their own; so too when the tiles
    are synthesised larger and averaged down."""
    tiles = load("jeandel-rao")[0].tiles
    assert synthesis_scale(example, 20) == scale
    at = WangAtlas.from_example(example, tiles, tile=20, seed=9)
    mid = slice(2, 18)
    borders = {"N": lambda b: b[0, mid], "E": lambda b: b[mid, -1], "S": lambda b: b[-1, mid], "W": lambda b: b[mid, 0]}
    for side, (axis, border) in enumerate(borders.items()):
        for i, j in [(i, j) for i in range(len(tiles)) for j in range(len(tiles))]:
            same = np.array_equal(border(at.block(i)), border(at.block(j)))
            assert same == (tiles[i, side] == tiles[j, side]), (axis, i, j)
    if scale > 1:
        return
    # across an edge the texture goes on: the texels on either side are neighbouring pixels of the example
    for side, other in ((2, 0), (1, 3)):  # tile 0's S edge against an N edge, its E edge against a W edge
        k = next(k for k in range(len(tiles)) if tiles[k, other] == tiles[0, side])
        if side == 2:
            mine, theirs = at.block(0)[-1, mid], at.block(k)[0, mid]
        else:
            mine, theirs = at.block(0)[mid, -1], at.block(k)[mid, 0]
        hits = [(r, q) for r in range(EXAMPLE.shape[0]) for q in range(EXAMPLE.shape[1])
                if side == 2 and q + 16 <= EXAMPLE.shape[1] and np.array_equal(EXAMPLE[r, q:q + 16], mine[:, :3])
                or side == 1 and r + 16 <= EXAMPLE.shape[0] and np.array_equal(EXAMPLE[r:r + 16, q], mine[:, :3])]
        assert len(hits) == 1
        r, q = hits[0]
        assert np.array_equal(EXAMPLE[r + 1, q:q + 16] if side == 2 else EXAMPLE[r:r + 16, q + 1], theirs[:, :3])


def test_refusals():
    with pytest.raises(InvalidProblem, match="even"):
        WangAtlas.from_example(EXAMPLE, [[0, 0, 0, 0]], tile=15)
    with pytest.raises(InvalidProblem, match="smaller than a diamond"):
        WangAtlas.from_example(EXAMPLE[:15], [[0, 0, 0, 0]], tile=16)
    with pytest.raises(InvalidProblem, match="16384"):
        WangAtlas.from_example(EXAMPLE, [[0, 0, 0, 0]] * 19, tile=4096)
