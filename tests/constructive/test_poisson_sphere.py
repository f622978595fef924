"""Building Poisson sphere tile sets and boxes of the direct 3-D corner tiling
(tilesolve.constructive.poisson_sphere), checked by the independent verifier and by scipy."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial import cKDTree

from tilesolve.constructive.poisson_sphere import (
    build_tiles,
    dart_throwing3,
    lattice_colors,
    lattice_slots,
    window_points,
)
from tilesolve.model.poisson_sphere import Box, PoissonSphereTilesProblem, cube_index
from tilesolve.verify.poisson_sphere import point_violations3, tileset_violations3


@pytest.fixture(scope="module")
def two():
    return build_tiles(PoissonSphereTilesProblem(2, 100, 0.6), seed=1)


def test_the_set_is_complete_and_verified(two):
    p = two.problem
    assert {k: len(v) for k, v in two.tiles.items()} == p.counts()
    assert tileset_violations3(two) == []
    assert two.stats["short"] == 0


@pytest.mark.slow
def test_same_seed_same_points(two):
    again = build_tiles(two.problem, seed=1)
    assert all(np.array_equal(a, b) for k in two.tiles for a, b in zip(two.tiles[k], again.tiles[k]))
    other = build_tiles(two.problem, seed=2)
    assert not np.array_equal(other.tiles["corner"][0], two.tiles["corner"][0])


def test_every_cell_holds_n_points(two):
    w = window_points(two, (0, 0, 0, 4, 3, 2), seed=3)
    cells = np.floor(w.local).astype(np.int64)
    _, counts = np.unique(cells, axis=0, return_counts=True)
    assert len(counts) == 24 and (counts == 100).all()


@pytest.mark.parametrize("origin", [(0, 0, 0), (-17, 5, 2**40), (2**61, -(2**61), 12345678901)])
def test_boxes_far_from_the_origin_are_poisson_sphere_distributions(two, origin):
    w = window_points(two, (*origin, 5, 4, 3), seed=7)
    d = two.problem.distance
    assert point_violations3(w.local, d, w.box.size) == []
    dist, _ = cKDTree(w.local).query(w.local, k=2)  # scipy's KD-tree agrees
    assert dist[:, 1].min() >= d


def test_boxes_agree_where_they_overlap(two):
    a = window_points(two, (10, -3, 2**35, 4, 4, 4), seed=9)
    b = window_points(two, (12, -2, 2**35 + 1, 4, 4, 4), seed=9)
    pa = a.local + (10 - 12, -3 + 2, -1)  # into b's frame
    inside = ((pa >= 0) & (pa < 2)).all(axis=1)
    pb = b.local[((b.local >= 0) & (b.local < 2)).all(axis=1)]
    key = lambda p: np.round(p, 9)[np.lexsort(np.round(p, 9).T)]  # noqa: E731
    assert inside.sum() == len(pb) > 0
    assert np.array_equal(key(pa[inside]), key(pb))


def test_the_colours_are_the_long_period_hash(two):
    from tilesolve.constructive.hashes import tiling_hash

    lat = lattice_colors(Box(-3, 2**50, 7, 2, 2, 2), 2, seed=4)
    h = tiling_hash(2, seed=4)
    assert lat[1, 0, 2] == h.scalar(-2, 2**50, 9) % 2
    table = lattice_colors(Box(0, 0, 0, 3, 3, 3), 2, seed=4, hash="table")
    assert table.shape == (4, 4, 4) and set(np.unique(table)) <= {0, 1}
    assert not np.array_equal(window_points(two, (0, 0, 0, 2, 2, 2), seed=4, hash="table").local,
                              window_points(two, (0, 0, 0, 2, 2, 2), seed=4).local)


def test_lattice_slots_index_by_the_corners():
    lat = np.random.default_rng(0).integers(3, size=(3, 4, 2))
    slots = lattice_slots(lat, 3)
    off, idx = slots["interior"]
    assert len(off) == 2 * 3 * 1
    i, j, k = off[4]
    assert idx[4] == cube_index([lat[i + a, j + b, k + c] for a in (0, 1) for b in (0, 1) for c in (0, 1)], 3)
    off, idx = slots["yface"]  # normal y: corners along x, then z
    i, j, k = off[-1]
    assert idx[-1] == cube_index([lat[i, j, k], lat[i, j, k + 1], lat[i + 1, j, k], lat[i + 1, j, k + 1]], 3)
    assert len(slots["zedge"][0]) == 3 * 4 * 1 and len(slots["corner"][0]) == lat.size


def test_plain_dart_throwing3_is_a_poisson_sphere_distribution():
    pts = dart_throwing3(300, 0.15, seed=2)
    assert point_violations3(pts, 0.15, (1, 1, 1)) == []
    assert len(pts) > 100


def test_plain_and_compiled_kernels_throw_the_same_darts():
    from tilesolve.constructive import _poisson_sphere_kernels as kern

    fixed = np.array([[0.5, 0.5, 0.5], [0.2, 0.8, 0.3]])
    allow = np.array([[0.0, 1.0, 0.0, 1.0, 0.0, 0.6], [0.0, 0.4, 0.6, 1.0, 0.6, 1.0]])
    forbid = np.array([[0.4, 0.6, 0.4, 0.6, 0.4, 0.6]])
    outs = []
    for ns in (kern.KERNELS.plain(), kern.KERNELS.compiled()):
        out = np.empty((12, 3))
        n, r = ns.dart_fill3(fixed, allow, forbid, 12, 0.3, 0.1, 0.9, 50, 400, False, 7, out)
        outs.append((n, r, out[:n].copy()))
    assert outs[0][0] == outs[1][0] > 0 and outs[0][1] == outs[1][1]
    assert np.array_equal(outs[0][2], outs[1][2])
    pts = np.vstack([fixed, outs[0][2]])
    gaps = np.linalg.norm(pts[:, None] - pts[None], axis=2)[np.triu_indices(len(pts), 1)]
    assert gaps.min() >= outs[0][1] - 1e-12
