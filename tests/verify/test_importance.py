"""The importance-sample verifier catches what is wrong (DESIGN.md: every verifier has a test
that it catches corruption)."""

from __future__ import annotations

import numpy as np

from tilesolve.verify.importance import block_counts, importance_violations, weighted_discrepancy


def _grid_sample(n_side: int, width: float = 1.0, height: float = 1.0) -> np.ndarray:
    x, y = np.meshgrid((np.arange(n_side) + 0.5) / n_side * width, (np.arange(n_side) + 0.5) / n_side * height)
    return np.column_stack([x.ravel(), y.ravel()])


def test_a_good_sample_passes():
    v = np.ones((16, 16))
    pts = _grid_sample(40)
    assert importance_violations(pts, v, expected=1600) == []
    assert weighted_discrepancy(pts, v) < 0.03


def test_points_outside_or_not_finite_are_caught():
    v = np.ones((8, 16))  # domain 1 x 0.5
    pts = _grid_sample(10, 1.0, 0.5)
    for bad in ([0.5, 0.6], [-0.01, 0.2], [np.nan, 0.1]):
        out = importance_violations(np.vstack([pts, bad]), v)
        assert [x.kind for x in out] == ["bounds"]


def test_a_wrong_total_is_caught():
    v = np.ones((8, 8))
    assert [x.kind for x in importance_violations(_grid_sample(30), v, expected=2000)] == ["count"]


def test_points_moved_between_quadrants_are_caught():
    v = np.ones((8, 8))
    pts = _grid_sample(40)
    left = pts[:, 0] < 0.5
    moved = pts.copy()
    moved[np.flatnonzero(left)[::4], 0] += 0.5  # a quarter of the left half moves right
    out = importance_violations(moved, v, expected=1600)
    assert out and {x.kind for x in out} == {"density"}


def test_the_density_decides_the_shares():
    v = np.ones((4, 4))
    v[:, :2] = 3.0  # the left half holds three quarters of the mass
    counts, shares = block_counts(_grid_sample(20), v, 2)
    assert np.allclose(shares, [[150, 50], [150, 50]])
    assert np.allclose(counts, 100)
    assert importance_violations(_grid_sample(20), v)  # a uniform sample is wrong here
    assert weighted_discrepancy(_grid_sample(20), v) > 0.2
    assert weighted_discrepancy(np.full((10, 2), 0.99), np.ones((4, 4))) == 0.75  # the box [0, 3/4] x [0, 1]
