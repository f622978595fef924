"""Penrose and polyomino importance sampling (Ostromoukhov 2004, 2007; class notes Part IV)
against the definition: samples locally proportional to the density."""

from __future__ import annotations

import numpy as np
import pytest

from tilesolve.constructive.importance import MassTable, lloyd, penrose_points, polyomino_points, sample
from tilesolve.model.importance import DensityMap, ImportanceProblem, builtin_density
from tilesolve.verify.importance import block_counts, importance_violations, weighted_discrepancy

CASES = [("penrose", "chair"), ("polyomino", "x-pentomino"), ("polyomino", "chair"), ("polyomino", "p-pentomino"),
         ("rejection", "chair")]


@pytest.mark.parametrize("method,tile", CASES)
def test_same_seed_same_points_another_seed_others(method, tile):
    d = builtin_density("radial", 64)
    p = ImportanceProblem(d, 2000, method, tile)
    a, b, c = sample(p, seed=7), sample(p, seed=7), sample(p, seed=8)
    assert np.array_equal(a, b)
    assert not np.array_equal(a[: min(len(a), len(c))], c[: min(len(a), len(c))])


@pytest.mark.parametrize("image", ["radial", "gradient"])
@pytest.mark.parametrize("method,tile,tolerance", [("penrose", "chair", 0.08), ("polyomino", "x-pentomino", 0.03),
                                                   ("polyomino", "chair", 0.05)])
def test_quadrants_hold_their_share_of_the_density(image, method, tile, tolerance):
    """Every quadrant (and every block of a 4 x 4 grid) within ``tolerance`` of its share; the
    hierarchical samplers within far less than independent sampling's 4 sigma."""
    d = builtin_density(image, 128)
    pts = sample(ImportanceProblem(d, 20_000, method, tile), seed=3)
    assert abs(len(pts) - 20_000) <= 0.02 * 20_000
    for g in (2, 4):
        counts, shares = block_counts(pts, d.values, g)
        assert (np.abs(counts - shares) <= tolerance * shares + 1).all(), (g, counts, shares)
    assert importance_violations(pts, d.values, expected=20_000) == []


def test_hierarchical_samplers_beat_rejection_on_discrepancy():
    d = builtin_density("gradient", 128)
    disc = {m: weighted_discrepancy(sample(ImportanceProblem(d, 10_000, m, "x-pentomino"), seed=1), d.values)
            for m in ("polyomino", "rejection")}
    assert disc["polyomino"] < disc["rejection"] / 2, disc


@pytest.mark.parametrize("n", [300, 1_000, 3_000, 10_000, 30_000])
def test_uniform_counts_follow_the_target_across_levels(n):
    """The count is near the target between level thresholds too (the ramps of new samples)."""
    d = builtin_density("flat", 32)
    assert abs(len(polyomino_points(d, n, tile="chair", seed=2)) - n) <= 0.03 * n + 20
    assert abs(len(polyomino_points(d, n, tile="x-pentomino", seed=2)) - n) <= 0.03 * n + 20
    assert abs(len(penrose_points(d, n, seed=2)) - n) <= 0.15 * n + 20
    assert abs(len(sample(ImportanceProblem(d, n, "penrose"), seed=2)) - n) <= 0.06 * n + 20


@pytest.mark.parametrize("method", ["penrose", "polyomino"])
def test_points_inside_the_domain_of_a_wide_image(method):
    v = np.zeros((30, 90))
    v[:, 60:] = 1.0  # only the right third is dark
    d = DensityMap(v, "wide")
    pts = sample(ImportanceProblem(d, 3000, method, jitter=True), seed=4)
    assert (pts[:, 0] >= 0).all() and (pts[:, 0] < 1).all() and (pts[:, 1] >= 0).all() and (pts[:, 1] < 1 / 3).all()
    assert (pts[:, 0] >= 2 / 3 - 0.01).mean() > 0.99
    assert importance_violations(pts, v, expected=3000) == []


def test_mass_table_is_exact_on_pixel_boxes():
    rng = np.random.default_rng(0)
    v = rng.random((5, 7))
    t = MassTable(DensityMap(v), 10.0)
    px = 1 / 7
    # columns 2..4, rows 1..2 from the bottom: image rows 5-3 .. 5-1
    want = v[::-1][1:3, 2:5].sum() / v.sum() * 10
    box = t.box(np.array([2 * px]), np.array([1 * px]), np.array([5 * px]), np.array([3 * px]))
    assert box[0] == pytest.approx(want)
    assert t.peak == pytest.approx(v.max() / v.sum() * 10 * 49)


def test_lloyd_keeps_the_count_and_evens_the_spacing():
    d = builtin_density("flat", 32)
    pts = sample(ImportanceProblem(d, 500, "rejection"), seed=1)
    moved = lloyd(pts, d, 5)
    assert moved.shape == pts.shape and (moved >= 0).all() and (moved <= 1).all()

    def nearest(p):
        gap = np.hypot(*(p[:, None] - p[None]).transpose(2, 0, 1))
        np.fill_diagonal(gap, np.inf)
        return gap.min(axis=1).min()

    assert nearest(moved) > 2 * nearest(pts)
