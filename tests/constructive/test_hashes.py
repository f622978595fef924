"""Lattice hash functions (class notes §3.4, walls 004 §4.2): scalar = vectorised, periods, uniformity."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from tilesolve.constructive.hashes import (
    FnvXorshift,
    LongPeriodHash,
    PermutationHash,
    perlin_hash,
    permutation_table,
    tiling_hash,
)
from tilesolve.errors import InvalidProblem

def chi2_z(counts) -> float:
    """Wilson-Hilferty z-score of Pearson's chi-square against uniform counts (z < 4: p > 3e-5)."""
    counts = np.asarray(counts, dtype=float)
    k = counts.size - 1
    e = counts.sum() / counts.size
    x = ((counts - e) ** 2 / e).sum()
    return ((x / k) ** (1 / 3) - (1 - 2 / (9 * k))) / math.sqrt(2 / (9 * k))


I64 = st.one_of(
    st.integers(-(2**63), 2**63 - 1),
    st.integers(-1000, 1000),
    st.integers(2**62 - 1000, 2**62 + 1000),
    st.integers(-(2**62) - 1000, -(2**62) + 1000),
)
coords = st.lists(st.tuples(I64, I64, I64), min_size=1, max_size=40)


def _arrays(pts):
    a = np.array(pts, dtype=np.int64)
    return a[:, 0], a[:, 1], a[:, 2]


@settings(max_examples=100)
@given(pts=coords, seed=st.integers(0, 2**32))
def test_permutation_hash_scalar_equals_vectorised(pts, seed):
    h = PermutationHash.from_seed(256, seed)
    x, y, z = _arrays(pts)
    for args, arr in (((0,), h(x)), ((0, 1), h(x, y)), ((0, 1, 2), h(x, y, z))):
        assert arr.tolist() == [h.scalar(*(p[i] for i in args)) for p in pts]


@settings(max_examples=100)
@given(pts=coords, seed=st.integers(0, 2**32), colors=st.integers(1, 40))
def test_long_period_hash_scalar_equals_vectorised(pts, seed, colors):
    h = tiling_hash(colors, seed=seed)
    x, y, z = _arrays(pts)
    assert h(x, y).tolist() == [h.scalar(a, b) for a, b, _ in pts]
    assert h(x, y, z).tolist() == [h.scalar(a, b, c) for a, b, c in pts]
    assert h.range % colors == 0


@settings(max_examples=100)
@given(pts=coords, seed=st.integers(0, 2**64 - 1), stream=st.integers(0, 7))
def test_fnv_xorshift_scalar_equals_vectorised(pts, seed, stream):
    h = FnvXorshift(seed, stream)
    x, y, _ = _arrays(pts)
    assert h(x, y).tolist() == [h.scalar(a, b) for a, b, _ in pts]
    assert h.colour(x, y, 5).tolist() == [h.colour_scalar(a, b, 5) for a, b, _ in pts]


def test_eq_3_1_to_3_4_by_hand():
    p = np.array([3, 0, 4, 1, 2])
    h = PermutationHash(p)
    assert h.scalar(7) == p[7 % 5]  # eq. 3.1
    assert h.scalar(7, -2) == p[(p[7 % 5] + (-2)) % 5]  # eq. 3.3
    assert h.scalar(7, -2, 9) == p[(p[(p[7 % 5] - 2) % 5] + 9) % 5]  # eq. 3.4
    lp = LongPeriodHash((p, np.array([1, 0, 2])), range_table=1)
    q = np.array([1, 0, 2])
    assert lp.scalar(4, 6) == (p[(p[4] + 6) % 5] + q[(q[4 % 3] + 6) % 3]) % 3  # eq. 3.6


def test_the_notes_long_period_hash_has_period_5930659848():
    h = tiling_hash(seed=3)
    assert h.sizes == (17, 19, 23, 24, 29, 31, 37) and h.range == 24
    period = 17 * 19 * 23 * 24 * 29 * 31 * 37
    assert period == h.period == 5_930_659_848 > 2**32
    assert sum(h.sizes) == 180
    rng = np.random.default_rng(0)
    x = rng.integers(-(2**40), 2**40, size=2000)
    y = rng.integers(-(2**40), 2**40, size=2000)
    # periodic in x and in y with that period ...
    assert (h(x + period, y) == h(x, y)).all()
    assert (h(x, y - period) == h(x, y)).all()
    # ... and with no shorter one: removing any prime factor breaks the period.
    for q in {2, 3, 17, 19, 23, 29, 31, 37}:
        assert (h(x + period // q, y) != h(x, y)).any(), q
        assert (h(x, y + period // q) != h(x, y)).any(), q


def test_perlin_hash_of_the_notes():
    h = perlin_hash(seed=0)
    assert h.period == 739_024 and h.range == 16 and sum(h.sizes) == 76


def test_tiling_hash_for_other_colour_counts_keeps_a_coprime_long_period():
    for colors in (5, 7, 10, 17, 29):
        h = tiling_hash(colors, seed=1)
        assert h.range % colors == 0
        assert h.period == math.prod(h.sizes)  # pairwise coprime


@pytest.mark.parametrize("make", [lambda s: tiling_hash(6, seed=s), lambda s: PermutationHash.from_seed(258, s)])
def test_hash_colours_are_uniform(make):
    h = make(11)
    x, y = np.meshgrid(np.arange(-150, 150), np.arange(-100, 200))
    counts = np.bincount((h(x, y) % 6).ravel(), minlength=6)
    assert chi2_z(counts) < 4


def test_fnv_colours_are_uniform_and_streams_differ():
    x, y = np.meshgrid(np.arange(-150, 150), np.arange(-100, 200))
    a, b = FnvXorshift(4, 0), FnvXorshift(4, 1)
    for k in (2, 3, 7):
        assert chi2_z(np.bincount(a.colour(x, y, k).ravel(), minlength=k)) < 4
    assert (a.colour(x, y, 2) != b.colour(x, y, 2)).mean() == pytest.approx(0.5, abs=0.01)
    # neighbours along both axes (and near 2**62) are unrelated: equal colours 1/k of the time
    for k in (2, 3):
        for xx, yy in ((x, y), (x + 2**62, y - 2**62)):
            c = a.colour(xx, yy, k)
            assert (c[1:] == c[:-1]).mean() == pytest.approx(1 / k, abs=0.01)
            assert (c[:, 1:] == c[:, :-1]).mean() == pytest.approx(1 / k, abs=0.01)
    # bit 0 of the colour is not a linear function of the coordinates' parities
    c = a.colour(x, y, 2)
    for px in (0, 1):
        for py in (0, 1):
            assert 0.45 < c[(x % 2 == px) & (y % 2 == py)].mean() < 0.55


def test_same_seed_same_tables_and_bad_input():
    assert np.array_equal(permutation_table(50, 9), permutation_table(50, 9))
    assert sorted(permutation_table(50, 9).tolist()) == list(range(50))
    assert np.array_equal(tiling_hash(seed=2)(np.arange(9), 1), tiling_hash(seed=2)(np.arange(9), 1))
    with pytest.raises(InvalidProblem):
        PermutationHash(np.array([0, 0, 1]))
    with pytest.raises(InvalidProblem):
        PermutationHash.from_seed(4, 0)(np.array([0.5]))
    with pytest.raises(InvalidProblem):
        FnvXorshift(0).scalar(2**64, 0)
    with pytest.raises(InvalidProblem):
        tiling_hash(0)


@settings(max_examples=60)
@given(xs=st.lists(I64, min_size=1, max_size=12), ys=st.lists(I64, min_size=1, max_size=12),
       seed=st.integers(0, 2**32), colors=st.integers(1, 30), long=st.booleans(), reduce=st.booleans())
def test_grid_evaluation_equals_the_pointwise_hash(xs, ys, seed, colors, long, reduce):
    h = tiling_hash(colors, seed=seed) if long else PermutationHash.from_seed(colors * 9, seed)
    x, y = np.array(xs, dtype=np.int64), np.array(ys, dtype=np.int64)
    want = h(x[None, :], y[:, None])
    if reduce:
        want = want % colors
    assert np.array_equal(h.outer(x, y, colors if reduce else None), want)
