"""Stochastic Wang and corner tilings (class notes ch. 3): every window tiles, locality,
completeness and uniformity."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from tilesolve.constructive.stochastic import (
    direct_corner,
    direct_wang,
    scanline_corner,
    scanline_wang,
    stochastic_window,
    tile_set,
)
from tilesolve.errors import InvalidProblem, MethodNotApplicable
from tilesolve.verify.grid import grid_violations

# (kind, method, variant, algorithm)
CASES = [
    ("corner", "direct", "complete", "edges"),
    ("wang", "direct", "complete", "edges"),
    ("wang", "direct", "complete", "two"),
    ("wang", "direct", "sums", "edges"),
    ("wang", "scanline", "complete", "edges"),
    ("wang", "scanline", "compact", "edges"),
    ("corner", "scanline", "complete", "edges"),
    ("corner", "scanline", "compact", "edges"),
]
#: Cases whose tile at a cell does not depend on the window (random access).
LOCAL = [c for c in CASES if c[1] == "direct" or c[2] == "complete"]
COORD = st.one_of(st.integers(-50, 50), st.integers(2**61, 2**61 + 100), st.integers(-(2**61) - 100, -(2**61)))


def window(case, region, colors, seed, hash="long"):
    kind, method, variant, algorithm = case
    return stochastic_window(kind, method, region, colors=colors, seed=seed, variant=variant,
                             algorithm=algorithm, hash=hash)


def chi2_z(counts) -> float:
    """Wilson-Hilferty z-score of Pearson's chi-square against uniform counts (z < 4: p > 3e-5)."""
    counts = np.asarray(counts, dtype=float)
    k = counts.size - 1
    e = counts.sum() / counts.size
    x = ((counts - e) ** 2 / e).sum()
    return ((x / k) ** (1 / 3) - (1 - 2 / (9 * k))) / math.sqrt(2 / (9 * k))


@pytest.mark.slow
@settings(max_examples=150)
@given(case=st.sampled_from(CASES), colors=st.integers(2, 6), x0=COORD, y0=COORD, w=st.integers(1, 25),
       h=st.integers(1, 25), seed=st.integers(0, 2**32), hash=st.sampled_from(["long", "table"]))
def test_every_window_is_a_tiling_of_its_set(case, colors, x0, y0, w, h, seed, hash):
    ts = tile_set(case[0], case[1], colors, case[2])
    g = window(case, (x0, y0, w, h), colors, seed, hash)
    assert g.shape == (h, w)
    assert grid_violations(ts.table(), g, kind=case[0], labels=ts.indices, limit=5) == []


@settings(max_examples=80)
@given(case=st.sampled_from(LOCAL), colors=st.integers(2, 5), x0=COORD, y0=COORD, seed=st.integers(0, 2**32),
       dx=st.integers(0, 19), dy=st.integers(0, 14), w=st.integers(1, 6), h=st.integers(1, 6))
def test_random_access_the_same_cell_is_the_same_tile_in_every_window(case, colors, x0, y0, seed, dx, dy, w, h):
    big = window(case, (x0, y0, 26, 21), colors, seed)
    small = window(case, (x0 + dx, y0 + dy, w, h), colors, seed)
    # the small window's rows, top first, are big rows counted from the top of the big one
    top = 21 - (dy + h)
    assert np.array_equal(big[top: top + h, dx: dx + w], small)
    cell = window(case, (x0 + dx, y0 + dy, 1, 1), colors, seed)
    assert cell[0, 0] == big[20 - dy, dx]


@pytest.mark.parametrize("case", [c for c in CASES if c not in LOCAL])
def test_compact_scanline_windows_agree_when_they_share_their_nw_corner(case):
    big = window(case, (-10, -20, 30, 25), 4, 7)  # NW corner (-10, 5)
    for w, h in ((1, 1), (7, 3), (30, 10)):
        small = window(case, (-10, 5 - h, w, h), 4, 7)
        assert np.array_equal(small, big[:h, :w])
    # a window with another NW corner is a different tiling (no random access, §3.3)
    shifted = window(case, (-9, -20, 29, 25), 4, 7)
    assert not np.array_equal(shifted, big[:, 1:])


@pytest.mark.parametrize("case", CASES)
@pytest.mark.parametrize("colors", [2, 3])
def test_completeness_every_tile_of_the_set_is_reached(case, colors):
    ts = tile_set(case[0], case[1], colors, case[2])
    g = window(case, (-40, 17, 80, 60), colors, 5)
    assert np.array_equal(np.unique(g), ts.indices)


@pytest.mark.parametrize("case", CASES)
@pytest.mark.parametrize("colors,seed", [(2, 1), (3, 2), (4, 3)])
def test_uniformity_chi_square_on_tile_frequencies(case, colors, seed):
    ts = tile_set(case[0], case[1], colors, case[2])
    # Cells far apart are close to independent (neighbours share colours): sample every 5th.
    g = window(case, (-333, 1000, 600, 600), colors, seed)[::5, ::5]
    counts = np.bincount(np.searchsorted(ts.indices, g.ravel()), minlength=ts.n_tiles)
    assert counts.size == ts.n_tiles
    assert chi2_z(counts) < 4


def test_the_notes_formulas_on_one_tile():
    # §3.3.1: corners h(x+1, y+1), h(x+1, y), h(x, y), h(x, y+1); here through the public hash.
    from tilesolve.constructive.stochastic import make_hash

    c, seed, x, y = 3, 9, -4, 11
    hsh = make_hash("long", c, seed)
    ne, se, sw, nw = (hsh.scalar(a, b) % c for a, b in ((x + 1, y + 1), (x + 1, y), (x, y), (x, y + 1)))
    assert direct_corner(x, y, 1, 1, colors=c, seed=seed)[0, 0] == ((ne * c + se) * c + sw) * c + nw
    # §3.3.2.3: N, E, S, W = h(2x+1, 2y+2), h(2x+2, 2y+1), h(2x+1, 2y), h(2x, 2y+1)
    n, e, s, w = (hsh.scalar(a, b) % c for a, b in ((2 * x + 1, 2 * y + 2), (2 * x + 2, 2 * y + 1),
                                                    (2 * x + 1, 2 * y), (2 * x, 2 * y + 1)))
    assert direct_wang(x, y, 1, 1, colors=c, seed=seed)[0, 0] == ((n * c + e) * c + s) * c + w


def test_same_seed_same_window_other_seed_other_window():
    for fn in (direct_corner, direct_wang, scanline_wang, scanline_corner):
        a = fn(3, 4, 20, 20, colors=3, seed=1)
        assert np.array_equal(a, fn(3, 4, 20, 20, colors=3, seed=1))
        assert not np.array_equal(a, fn(3, 4, 20, 20, colors=3, seed=2))


def test_bad_input():
    with pytest.raises(MethodNotApplicable, match="sums"):
        tile_set("wang", "direct", 3, "compact")
    with pytest.raises(MethodNotApplicable, match="scanline"):
        tile_set("corner", "direct", 3, "compact")
    with pytest.raises(MethodNotApplicable):
        tile_set("wang", "scanline", 3, "sums")
    with pytest.raises(InvalidProblem, match="63-bit"):
        direct_corner(2**62, 0, 2, 2, colors=2, seed=0)
    with pytest.raises(InvalidProblem, match="GiB"):
        direct_corner(0, 0, 1 << 15, 1 << 15, colors=2, seed=0)
    with pytest.raises(InvalidProblem):
        direct_wang(0, 0, 0, 3, colors=2, seed=0)
    with pytest.raises(InvalidProblem):
        direct_wang(0, 0, 3, 3, colors=2, seed=0, algorithm="three")
    with pytest.raises(InvalidProblem):
        scanline_wang(0, 0, 3, 3, colors=2, seed=0, hash="md5")
