"""The Poisson disk verifier (numpy grid, :func:`tilesolve.verify.poisson.point_violations`)
against scipy's KD-tree on whole windows of the corner tiles far from the origin (class notes
§4.2.1, §4.3; issue 23 §1: "an independent verifier (a KD-tree over any window)").

This checks that its grid, by the numpy scan and by the compiled one of large sets, finds
exactly the close pairs a KD-tree range query finds, on windows of thousands of points with
pairs pushed together across tile seams, where a tiling's mistakes would be.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial import cKDTree

from tilesolve.constructive.poisson import build_tiles, window_points
from tilesolve.model.poisson import PoissonTilesProblem
from tilesolve.verify import _poisson_kernel
from tilesolve.verify.poisson import _close_pairs, point_violations


@pytest.fixture(scope="module")
def ts():
    return build_tiles(PoissonTilesProblem(2, 32, 0.7), seed=7)


def _kdtree_pairs(points, distance):
    pairs = cKDTree(points).query_pairs(distance, output_type="ndarray")
    pairs = np.sort(pairs, axis=1)
    gap = np.hypot(*(points[pairs[:, 0]] - points[pairs[:, 1]]).T)
    return np.unique(pairs[gap < distance], axis=0).reshape(-1, 2)


def _seam_pairs(points, distance, rng, count):
    """Move ``count`` points, each next to a vertical or horizontal tile seam, across it to half
    the distance from the closest point of the neighbouring tile."""
    pts = points.copy()
    frac = pts - np.floor(pts)
    near = np.flatnonzero(((frac < distance) | (frac > 1 - distance)).any(axis=1))
    tree = cKDTree(points)
    moved = 0
    for i in rng.permutation(near):
        _, nb = tree.query(points[i], k=8)
        other = [j for j in nb if (np.floor(points[j]) != np.floor(points[i])).any()]  # across a seam
        if not other:
            continue
        j = other[0]
        step = points[i] - points[j]
        pts[i] = points[j] + step / np.hypot(*step) * distance / 2
        moved += 1
        if moved == count:
            break
    assert moved == count
    return pts


@pytest.mark.parametrize("origin, seed", [((0, 0), 1), ((2**50, -(2**45)), 2), ((-(10**15), 3 * 10**14), 3)])
def test_the_grid_finds_the_kdtree_s_pairs_on_far_windows(ts, origin, seed):
    w, h = 24, 16
    d = ts.problem.distance
    pts = window_points(ts, (*origin, w, h), seed=seed).local
    assert len(pts) > 10_000
    assert len(_kdtree_pairs(pts, d)) == 0 and point_violations(pts, d, w, h) == []
    bad = _seam_pairs(pts, d, np.random.default_rng(seed), 30)
    expected = _kdtree_pairs(bad, d)
    assert len(expected) >= 30
    assert np.array_equal(_close_pairs(bad, d), expected)
    assert np.array_equal(_close_pairs(bad, d, kernel=_poisson_kernel.compiled(_poisson_kernel.COMPILED_FROM)), expected)
    found = point_violations(bad, d, w, h)
    assert found[-1].message.startswith(f"{len(expected):,} pairs in all are closer than")
