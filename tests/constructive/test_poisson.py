"""Corner-based Poisson disk tiles (class notes §4.3): the builder and windows of the plane.

The one property: every tiling built from a set by the project's stochastic corner tilings
(direct and scanline, complete and compact sets) is a Poisson disk distribution, checked by
the independent KD-tree verifier on random windows far from the origin.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tilesolve.constructive import _poisson_kernels as kern
from tilesolve.constructive.poisson import build_tiles, dart_throwing, lloyd, window_points
from tilesolve.model.poisson import PoissonTilesProblem
from tilesolve.verify.poisson import min_distance, point_violations, tileset_violations


@pytest.fixture(scope="module")
def set2():
    return build_tiles(PoissonTilesProblem(2, 32, 0.7), seed=11)


@pytest.fixture(scope="module")
def set3():
    return build_tiles(PoissonTilesProblem(3, 24, 0.65, lloyd=2), seed=5)


def test_the_set_has_the_notes_tiles_and_passes_the_exhaustive_check(set2):
    assert [len(set2.tiles[k]) for k in ("corner", "hedge", "vedge", "interior")] == [2, 4, 4, 16]
    assert tileset_violations(set2) == []  # all 2**9 colourings of a 2 x 2 block of cells


def test_the_same_seed_gives_the_same_set_and_another_seed_another(set2):
    again = build_tiles(PoissonTilesProblem(2, 32, 0.7), seed=11)
    other = build_tiles(PoissonTilesProblem(2, 32, 0.7), seed=12)
    for kind, arrays in set2.tiles.items():
        assert all(np.array_equal(a, b) for a, b in zip(arrays, again.tiles[kind]))
    assert not all(np.array_equal(a, b) for a, b in zip(set2.tiles["interior"], other.tiles["interior"]))


def test_every_cell_holds_n_points_when_no_interior_fell_short(set2):
    assert set2.stats["short"] == 0
    w = window_points(set2, (-3, 7, 5, 4), seed=2)
    cells = np.floor(w.local).astype(int)
    counts = np.bincount(cells[:, 1] * 5 + cells[:, 0], minlength=20)
    assert (counts == 32).all()


@settings(max_examples=40, deadline=None)
@given(x0=st.integers(-(2**60), 2**60), y0=st.integers(-(2**60), 2**60), w=st.integers(1, 6), h=st.integers(1, 6),
       tiling=st.sampled_from([("direct", "complete"), ("scanline", "complete"), ("scanline", "compact")]),
       hash_=st.sampled_from(["long", "table"]), seed=st.integers(0, 2**31 - 1), which=st.booleans())
def test_every_window_far_from_the_origin_is_a_poisson_disk_distribution(set2, set3, x0, y0, w, h, tiling, hash_,
                                                                           seed, which):
    ts = set3 if which else set2
    pts = window_points(ts, (x0, y0, w, h), tiling=tiling[0], variant=tiling[1], hash=hash_, seed=seed)
    assert point_violations(pts.local, ts.problem.distance, w, h) == []
    assert pts.n_points > 0


def test_direct_windows_agree_where_they_overlap(set2):
    a = window_points(set2, (10**12, -40, 6, 5), seed=9)
    b = window_points(set2, (10**12 + 2, -38, 6, 5), seed=9)
    inside_a = a.local[(a.local[:, 0] >= 2) & (a.local[:, 1] >= 2)] - 2
    inside_b = b.local[(b.local[:, 0] < 4) & (b.local[:, 1] < 3)]
    key = lambda p: p[np.lexsort((p[:, 1], p[:, 0]))]  # noqa: E731
    assert np.allclose(key(inside_a), key(inside_b), atol=1e-12)


def test_a_seam_pair_would_be_found(set2):
    """Guards the test above: the window's points do come within reach across tile seams."""
    pts = window_points(set2, (0, 0, 6, 6), seed=1).local
    assert min_distance(pts) < 1.3 * set2.problem.distance


def test_plain_and_compiled_kernels_throw_the_same_darts():
    fixed = np.array([[0.5, 0.5], [0.2, 0.8]])
    allow = np.array([[0.0, 1.0, 0.0, 0.6], [0.0, 0.4, 0.6, 1.0]])
    forbid = np.array([[0.4, 0.6, 0.4, 0.6]])
    outs = []
    for ns in (kern.KERNELS.plain(), kern.KERNELS.compiled()):
        out = np.empty((12, 2))
        n, r = ns.dart_fill(fixed, allow, forbid, 12, 0.3, 0.1, 0.9, 50, 400, False, 7, out)
        outs.append((n, r, out[:n].copy()))
    assert outs[0][0] == outs[1][0] and outs[0][1] == outs[1][1]
    assert np.array_equal(outs[0][2], outs[1][2])


def test_plain_dart_throwing_keeps_its_distance_on_the_torus():
    p = dart_throwing(80, 0.08, seed=3)
    shifted = np.vstack([p + [i, j] for i in (-1, 0, 1) for j in (-1, 0, 1)])
    assert min_distance(shifted) >= 0.08 and len(p) > 40


def test_lloyd_keeps_points_in_their_region_and_apart():
    rng = np.random.default_rng(0)
    allow = np.array([[0.0, 1.0, 0.0, 1.0]])
    forbid = np.array([[0.0, 0.3, 0.0, 0.3]])
    fixed = np.array([[0.1, 0.1], [0.2, 0.25]])
    start = dart_throwing(30, 0.1, seed=1)
    start = start[~((start[:, 0] < 0.3) & (start[:, 1] < 0.3))]
    start = start[np.linalg.norm(start[:, None] - fixed[None], axis=2).min(axis=1) >= 0.1]
    moved = lloyd(start, fixed, allow, forbid, 0.1, 5, rng)
    assert not np.array_equal(moved, start)
    assert not ((moved[:, 0] < 0.3) & (moved[:, 1] < 0.3)).any()
    assert min_distance(np.vstack([moved, fixed])) >= 0.1


@settings(max_examples=15, deadline=None)
@given(ox=st.integers(-(2**60), 2**60), oy=st.integers(-(2**60), 2**60), seed=st.integers(0, 2**31 - 1),
       pick=st.integers(1, 50))
def test_the_object_distribution_function_is_the_closest_point_with_random_access(set2, ox, oy, seed, pick):
    """§6.6.2: evaluations agree bit for bit whatever else is evaluated with them, and give the
    closest point of the tiled distribution (against all points of a larger window)."""
    from tilesolve.constructive.poisson import object_distribution

    q = np.random.default_rng(seed).random((200, 2)) * [5, 4]
    every = object_distribution(set2, q, origin=(ox, oy), seed=seed)
    alone = object_distribution(set2, q[:pick], origin=(ox, oy), seed=seed)
    assert all(np.array_equal(every[k][:pick], alone[k]) for k in every)
    pts = window_points(set2, (ox - 2, oy - 2, 9, 8), seed=seed).local - [2, 2]
    gaps = np.hypot(*(q[:, None, :] - pts[None]).transpose(2, 0, 1))
    assert np.allclose(every["distance"], gaps.min(axis=1), rtol=0, atol=1e-12)
    assert np.allclose(every["closest"], pts[gaps.argmin(axis=1)], rtol=0, atol=1e-12)
    r = set2.problem.distance / 2
    assert np.array_equal(every["inside"], every["distance"] < r)
    assert (np.hypot(*every["local"][every["inside"]].T) < 1).all()
    same = (every["id"][:, None, :] == every["id"][None, :, :]).all(axis=2)
    assert np.array_equal(same, (every["closest"][:, None, :] == every["closest"][None, :, :]).all(axis=2))
