"""Recursive Wang tiles (Kopf et al. 2006; class notes Part V): every level of every window is a
Poisson disk distribution at its own distance, levels nest, windows are random access."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.distance import pdist

from tilesolve.constructive.poisson_recursive import (
    build_recursive,
    progressive_order,
    sample_window,
    subdivide,
    subdivision_rules,
)
from tilesolve.model.poisson_recursive import RecursiveTilesProblem, RecursiveWindowProblem
from tilesolve.verify.poisson import point_violations, relative_radius
from tilesolve.verify.poisson_recursive import rule_violations, tileset_violations, window_violations


@pytest.fixture(scope="module")
def ts():
    return build_recursive(RecursiveTilesProblem(2, 16, 0.7, 2), seed=1)


def _window(ts, region, seed, **kw):
    return sample_window(RecursiveWindowProblem(ts, region, **kw), seed=seed)


def test_the_built_set_passes_the_independent_checks(ts):
    assert tileset_violations(ts) == []
    assert ts.rules.shape == (16, 3, 3)


@pytest.mark.parametrize("region, seed", [((0, 0, 3, 2), 1), ((2**45, -2**40, 2, 3), 7), ((-10**12, 5, 3, 3), 3)])
def test_every_level_is_a_poisson_disk_distribution_across_seams_far_from_the_origin(ts, region, seed):
    w = _window(ts, region, seed, level=3)
    assert window_violations(w) == []
    area = region[2] * region[3]
    for level in range(4):
        pts = w.local[w.level <= level]
        d = ts.problem.distance_at(level)
        assert point_violations(pts, d, region[2], region[3]) == []
        if len(pts) < 4000:  # and by brute force
            assert pdist(pts).min() >= d
        # about the density of the level: the new points near old ones are the only ones dropped
        # (with n = 2, a level's N n^2 new points a tile meet N old ones: about a fifth goes)
        assert 0.7 * ts.problem.density_at(level) * area <= len(pts) <= 1.05 * ts.problem.density_at(level) * area
        assert relative_radius(pts, area) > 0.6


def test_levels_nest_and_every_level_is_its_own_window(ts):
    deep = _window(ts, (4, -3, 2, 2), 5, level=3)
    for level in range(3):
        shallow = _window(ts, (4, -3, 2, 2), 5, level=level)
        mine = deep.local[deep.level <= level]
        assert {tuple(p) for p in shallow.local.tolist()} == {tuple(p) for p in mine.tolist()}


def test_overlapping_windows_agree_random_access(ts):
    big = _window(ts, (-2, 1, 4, 3), 9, level=2)
    small = _window(ts, (-1, 2, 2, 1), 9, level=2)
    inside = (big.local[:, 0] >= 1) & (big.local[:, 0] < 3) & (big.local[:, 1] >= 1) & (big.local[:, 1] < 2)
    moved = big.local[inside] - [1, 1]
    assert np.allclose(np.sort(moved, axis=0), np.sort(small.local, axis=0), atol=1e-12, rtol=0)
    assert sorted(big.level[inside].tolist()) == sorted(small.level.tolist())


def test_the_same_seed_gives_the_same_set_and_window():
    p = RecursiveTilesProblem(1, 16, 0.7, 3)
    a, b = build_recursive(p, seed=2), build_recursive(p, seed=2)
    assert (a.rules == b.rules).all()
    assert all((x == y).all() for k in a.base.tiles for x, y in zip(a.base.tiles[k], b.base.tiles[k]))
    wa, wb = _window(a, (3, 3, 2, 2), 4, level=2), _window(b, (3, 3, 2, 2), 4, level=2)
    assert (wa.local == wb.local).all() and (wa.rank == wb.rank).all()


def test_a_density_keeps_points_by_level_and_rank_and_grows_continuously(ts):
    counts = []
    for density in (4.0, 16.0, 40.0, 64.0, 200.0, 256.0):
        w = _window(ts, (0, 0, 4, 4), 3, density=density)
        assert window_violations(w) == []
        counts.append(w.n_points)
        full = _window(ts, (0, 0, 4, 4), 3, level=ts.problem.level_for(density))
        assert {tuple(p) for p in w.local.tolist()} <= {tuple(p) for p in full.local.tolist()}
    assert counts == sorted(counts)
    for density, n in zip((4.0, 16.0, 40.0, 64.0, 200.0, 256.0), counts):
        assert 0.75 * density * 16 <= n <= 1.1 * density * 16
    assert counts[1] == _window(ts, (0, 0, 4, 4), 3, level=0).n_points  # density N: all of level 0


def test_a_ramp_is_sparse_in_the_west_and_dense_in_the_east(ts):
    from scipy.spatial import cKDTree

    problem = RecursiveWindowProblem(ts, (0, 0, 8, 2), density=np.linspace(10, 250, 64)[None, :])
    # the deeper levels only where the density needs them (block cells, the window's x 0 is block x 1)
    assert [b[:3] for b in problem.boxes()] == [(0, 0, 10), (0, 0, 10), (1, 0, 9)]
    w = sample_window(problem, seed=1)
    assert window_violations(w) == []
    west, east = (w.local[:, 0] < 2).sum(), (w.local[:, 0] >= 6).sum()
    assert 5 * west < east
    full = _window(ts, (0, 0, 8, 2), 1, level=2)  # the same points as the whole window at the deepest level
    gap, k = cKDTree(full.local).query(w.local)
    assert gap.max() < 1e-12 and (full.level[k] == w.level).all() and np.allclose(full.rank[k], w.rank)


def test_subdivision_keeps_a_lattice_colouring_across_neighbouring_tiles():
    rng = np.random.default_rng(3)
    rules = subdivision_rules(3, 4, rng)
    assert rule_violations(rules, 3) == []
    lat = rng.integers(3, size=(4, 5))
    fine = subdivide(lat, rules, 3)
    assert fine.shape == (13, 17)
    assert (fine[::4, ::4] == lat).all()  # parent corners keep their colours
    # every depth-1 tile's lattice is its parent's rule, whoever the neighbours are
    t = ((lat[1, 2] * 3 + lat[0, 2]) * 3 + lat[0, 1]) * 3 + lat[1, 1]
    assert (fine[0:5, 4:9] == rules[t]).all()


def test_progressive_order_puts_spread_out_points_first():
    pts = np.random.default_rng(1).random((200, 2))
    order = progressive_order(pts)
    assert sorted(order.tolist()) == list(range(200))
    first = pts[order[:20]]
    gaps = np.hypot(*(first[:, None] - first[None]).transpose(2, 0, 1)) + np.eye(20)
    assert gaps.min() > 0.1  # 20 random points would have a pair closer than that


def test_the_far_from_kernel_agrees_with_a_kd_tree_on_both_paths():
    from scipy.spatial import cKDTree

    from tilesolve.constructive import _poisson_recursive_kernels as k

    rng = np.random.default_rng(5)
    kept, pts = rng.random((300, 2)) * [3, 2], rng.random((2000, 2)) * [3, 2]
    reach = 0.05
    gap, _ = cKDTree(kept).query(pts)
    want = gap >= reach
    for ns in (k.KERNELS.plain(), k.KERNELS.compiled()):
        got = ns.far_from(kept, pts, reach, 0.1, 30, 20, np.empty(len(pts), bool))
        assert (got == want).all()
