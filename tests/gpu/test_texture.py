"""The corner-tile atlas's synthesis (class notes §5.3): the graph cut of the new patch, and the
texture of a wall against the wall."""

from __future__ import annotations

import numpy as np
import pytest
from clitools import run
from PIL import Image

from tilesolve.gpu.texture import _cut_regions, graph_cut


def test_the_cut_runs_where_the_patches_agree_and_keeps_the_border():
    t = 32
    keep, cover = _cut_regions(t)
    rng = np.random.default_rng(5)
    old = rng.integers(0, 256, (t, t, 4)).astype(np.float32)
    new = rng.integers(0, 256, (t, t, 4)).astype(np.float32)
    yy, xx = np.mgrid[0:t, 0:t] + 0.5
    ring = np.abs(np.hypot(yy - t / 2, xx - t / 2) - 11) < 1.0  # the two patches agree on a ring of radius 11
    new[ring] = old[ring]
    inside = graph_cut(old, new, keep, cover)
    assert inside[cover].all() and not inside[keep].any()
    radius = np.hypot(yy - t / 2, xx - t / 2)
    # cut along the ring, and around the ends of the cross it must cover
    assert inside[radius < 10].all() and not inside[(radius > 12) & ~cover].any()
    assert np.array_equal(graph_cut(old, new, keep, cover), inside)  # the same cut every time


def _luma(img: np.ndarray) -> np.ndarray:
    return img[..., :3].astype(np.float64) @ np.array([0.299, 0.587, 0.114])


def _mortar(luma: np.ndarray) -> np.ndarray:
    """The light texels of a wall picture: luminance above the middle of its mean and its maximum."""
    return luma > (luma.mean() + luma.max()) / 2


def _run_length(mask: np.ndarray) -> float:
    """The mean length of the vertical runs of ``mask``, each texel weighting its own run."""
    edges = np.diff(np.pad(mask.astype(np.int8), ((1, 1), (0, 0))), axis=0)
    lengths = np.flatnonzero(edges.T.ravel() == -1) - np.flatnonzero(edges.T.ravel() == 1)
    return float((lengths.astype(np.float64) ** 2).sum() / lengths.sum())


@pytest.mark.slow
@pytest.mark.parametrize("tile,options", [(32, ["--colors", "3"]), (64, ["--colors", "3"]),
                                          (64, ["--aperiodic", "jeandel-rao", "--seed", "1"])])
def test_a_texture_from_a_wall_has_the_wall_s_mortar_lines(tmp_path, tile, options):
    """`render texture` from a wall (the help's examples): mortar runs as long across as down,
    relative to the wall's (tall stripes, a tile's corner patches sharing one straight line, fail),
    no longer than the wall's and at least a quarter of them (the example at its size or half),
    and as much mortar as the wall has; at 64 texels a tile (the wall at its size) hardly a texel
    between brick and mortar (the wall has none; blended blotches have many)."""
    proc = run("render", "wall", "--size", "256x256", "--seed", "5", "-o", "bricks.png", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    proc = run("render", "texture", "--example", "bricks.png", "--tile", str(tile), *options,
               "--size", "640x480", "-o", "t.png", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    wall, texture = (_luma(np.asarray(Image.open(tmp_path / f))) for f in ("bricks.png", "t.png"))
    mw, mt = _mortar(wall), _mortar(texture)
    down, across = _run_length(mt) / _run_length(mw), _run_length(mt.T) / _run_length(mw.T)
    assert 2 / 3 < down / across < 3 / 2, (down, across)
    assert 1 / 4 < down < 2 and 1 / 4 < across < 2, (down, across)
    assert 0.8 < mt.mean() / mw.mean() < 1.25
    if tile == 64:
        top = wall.max() - wall.mean()
        between = (texture > wall.mean() + top / 4) & (texture < wall.mean() + 3 * top / 4)
        assert between.mean() < 0.01


# ------------------------------------------------------------------- the CPU's and the browser's texture
def _atlas(colors: int = 3, tile: int = 24, seed: int = 2):
    from tilesolve.gpu.texture import Atlas

    ex = np.random.default_rng(0).integers(0, 256, (60, 60, 3), dtype=np.uint8)
    return Atlas.from_example(ex, colors, tile=tile, seed=seed)


@pytest.mark.parametrize("origin", [(0, 0), (-37, 11), (2**61 + 5, -(2**61))])
def test_the_cpu_texture_is_the_gpus_at_one_texel_a_pixel(origin):
    # the studio's server tiles (texture_window) and TextureMapper, both passes: the same pixels
    from tilesolve.gpu.texture import TextureMapper, texture_window

    at = _atlas()
    cpu = texture_window(at, origin[0], origin[1], 7, 5, seed=2)
    for two_pass in (True, False):
        gpu = TextureMapper(at, seed=2, origin=origin, two_pass=two_pass).image(7 * 24, 5 * 24)
        assert np.array_equal(gpu, cpu)
    # a tile's image is its place in the packing: the tiles are direct_corner's
    from tilesolve.constructive.stochastic import direct_corner

    tiles = direct_corner(origin[0], origin[1], 7, 5, colors=3, seed=2)
    assert np.array_equal(cpu[24:48, 48:72], texture_window(at, origin[0] + 2, origin[1] + 3, 1, 1, seed=2))
    assert len(np.unique(tiles)) > 5


def test_the_webgl2_texture_shaders_run_as_glsl_es_give_the_cpu_texture(monkeypatch):
    # the studio's shaders (GLSL ES 3.00), run by llvmpipe in place of the desktop ones
    from tilesolve.constructive.stochastic import direct_corner
    from tilesolve.gpu import texture as tex

    at = _atlas()
    es = tex.webgl_texture(at, seed=2)
    assert all(es[k].startswith("#version 300 es\n") for k in ("vertex", "colour", "ids"))
    monkeypatch.setattr(tex, "_VERTEX", es["vertex"])
    monkeypatch.setattr(tex, "_FRAGMENT_DIRECT", es["colour"])
    monkeypatch.setattr(tex, "_FRAGMENT_IDS", es["ids"])
    origin = (-123456789, 987654321)
    m = tex.TextureMapper(at, seed=2, origin=origin, two_pass=False)
    assert np.array_equal(m.image(9 * 24, 4 * 24), tex.texture_window(at, *origin, 9, 4, seed=2))
    ids = tex.TextureMapper(colors=3, seed=2, origin=origin, tile_px=5).tile_ids(9 * 5, 4 * 5)
    want = direct_corner(*origin, 9, 4, colors=3, seed=2)
    assert np.array_equal(ids, np.repeat(np.repeat(want, 5, 0), 5, 1))
    tables, perm, red = tex.hash_tables(3, 2)
    assert es["perm"] == perm.tolist() and es["red"] == red.tolist() and es["tables"] == [t.tolist() for t in tables]
    assert es["where"] == at.where().tolist() and es["tile"] == 24 and es["colors"] == 3
