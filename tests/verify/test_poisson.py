"""The independent Poisson disk verifier catches what it must (class notes §4.2, §4.3)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tilesolve.constructive.poisson import build_tiles
from tilesolve.model.poisson import PoissonTilesProblem, PoissonTileSet
from tilesolve.verify.poisson import _close_pairs as point_violations_pairs
from tilesolve.verify.poisson import min_distance, point_violations, radial_spectrum, relative_radius, tileset_violations


@pytest.fixture(scope="module")
def ts():
    return build_tiles(PoissonTilesProblem(2, 32, 0.7), seed=4)


def _copy(ts, kind, k, pts):
    tiles = {key: [a.copy() for a in arrs] for key, arrs in ts.tiles.items()}
    tiles[kind][k] = pts
    return PoissonTileSet(ts.problem, tiles)


def test_a_point_next_to_the_corner_tile_across_a_seam_is_caught(ts):
    d, a = ts.problem.distance, ts.problem.corner_half
    corner = ts.tiles["corner"][1]
    target = corner[np.argmax(corner[:, 0])]  # the corner point nearest the east strip
    new = np.array([a + 1e-6, np.clip(target[1], -d + 1e-6, d - 1e-6)])
    assert np.hypot(*(new - target)) < d  # the point lies in the strip, within d of the corner point
    bad = _copy(ts, "hedge", 1 * 2 + 0, np.vstack([ts.tiles["hedge"][2], [new]]))  # west end colour 1
    assert [v.kind for v in tileset_violations(bad)][:1] == ["distance"]


def test_two_interior_points_too_close_are_caught(ts):
    pts = ts.tiles["interior"][5]
    bad = _copy(ts, "interior", 5, np.vstack([pts, pts[:1] + [ts.problem.distance / 3, 0]]))
    assert [v.kind for v in tileset_violations(bad)][:1] == ["distance"]


def test_a_point_outside_its_region_is_caught(ts):
    bad = _copy(ts, "vedge", 0, np.vstack([ts.tiles["vedge"][0], [[0.5, 0.5]]]))
    assert [v.kind for v in tileset_violations(bad)] == ["region"]


def test_points_too_close_or_outside_the_window_are_listed():
    pts = np.array([[0.1, 0.1], [0.15, 0.1], [2.5, 0.5], [0.9, 0.9]])
    kinds = sorted(v.kind for v in point_violations(pts, 0.1, 2, 1))
    assert kinds == ["distance", "window"]
    assert point_violations(pts[[0, 3]], 0.1, 1, 1) == []
    assert point_violations(np.array([[np.nan, 0.0]]), 0.1, 1, 1)[0].kind == "shape"


def test_exactly_the_distance_apart_is_allowed():
    assert point_violations(np.array([[0.0, 0.0], [0.25, 0.0]]), 0.25, 1, 1) == []


def test_relative_radius_of_a_hexagonal_lattice_is_one():
    a = 1 / 16
    rows = [[(i + (j % 2) / 2) * a, j * a * np.sqrt(3) / 2] for j in range(18) for i in range(16)]
    pts = np.array(rows)
    area = 16 * a * 18 * a * np.sqrt(3) / 2
    assert relative_radius(pts, area) == pytest.approx(1.0, rel=1e-9)


def test_white_noise_has_a_flat_spectrum():
    pts = np.random.default_rng(0).random((4000, 2)) * 4
    f, p, aniso = radial_spectrum(pts, 4.0, k_max=32)
    assert f[0] == 0.25 and len(p) == 32
    assert 0.8 < float(p[8:].mean()) < 1.2
    assert abs(float(aniso[8:].mean())) < 1.0


@settings(max_examples=150, deadline=None)
@given(n=st.integers(0, 120), scale=st.floats(0.01, 10), d=st.floats(0.001, 2), seed=st.integers(0, 2**32 - 1),
       dup=st.booleans())
def test_the_grid_finds_a_close_pair_exactly_when_there_is_one(n, scale, d, seed, dup):
    """Against the definition, pair by pair (numpy, all pairs)."""
    pts = np.random.default_rng(seed).random((n, 2)) * scale
    if dup and n:
        pts = np.vstack([pts, np.repeat(pts[:1], 6, axis=0)])  # an overfull cell
    gaps = np.hypot(*(pts[:, None, :] - pts[None, :, :]).transpose(2, 0, 1))
    close = {(i, j) for i, j in zip(*np.nonzero(gaps < d)) if i < j}
    found = {tuple(p) for p in point_violations_pairs(pts, d)}
    assert found <= close and bool(found) == bool(close)
    if len(pts) >= 2:
        assert min_distance(pts) == pytest.approx(gaps[np.triu_indices(len(pts), 1)].min(), rel=1e-12, abs=1e-300)
    assert np.array_equal(point_violations_pairs(pts, d, kernel=_compiled_scan()), point_violations_pairs(pts, d))


def _compiled_scan():
    """The compiled neighbour scan of the verifier's grid (used for large sets)."""
    import importlib

    from tilesolve.verify import _poisson_kernel

    importlib.import_module("tilesolve._numba")  # the scan is compiled where numba is loaded

    return _poisson_kernel.compiled(_poisson_kernel.COMPILED_FROM)


def test_a_large_set_takes_the_compiled_scan_once_numba_is_loaded():
    import sys

    from tilesolve.verify import _poisson_kernel

    assert _poisson_kernel.compiled(_poisson_kernel.COMPILED_FROM - 1) is None
    assert _poisson_kernel.compiled(_poisson_kernel.COMPILED_FROM, 1e-170) is None  # its square underflows
    assert (_poisson_kernel.compiled(_poisson_kernel.COMPILED_FROM) is None) == ("numba" not in sys.modules)
    assert _compiled_scan() is not None


def test_averaged_periodograms_of_white_noise_lose_anisotropy_as_ulichney_says():
    rng = np.random.default_rng(1)
    runs = [rng.random((2000, 2)) * 4 for _ in range(4)]
    _, p, aniso = radial_spectrum(runs, 4.0, k_max=32)
    assert 0.8 < float(p[8:].mean()) < 1.2
    assert -7.5 < float(aniso[8:].mean()) < -4.5  # 10 log10(1/4) = -6 dB


def test_the_verifiers_placement_gives_the_builders_points_exactly(ts):
    from tilesolve.constructive.poisson import place_tiles
    from tilesolve.verify.poisson import match_violations, placed_points

    lat = np.random.default_rng(3).integers(2, size=(5, 7))
    offsets, frame, _, _ = place_tiles(ts, lat)
    mine = placed_points(ts, lat)
    assert len(mine) == len(offsets) and match_violations(mine, offsets + frame, "the builder") == []


def test_match_violations_finds_points_missing_added_and_moved():
    from tilesolve.verify.poisson import match_violations

    pts = np.array([[0.1, 0.2], [0.3, 0.4], [0.5, 0.6]])
    assert match_violations(pts[::-1], pts, "x") == []
    assert [v.message.split(",")[0] for v in match_violations(pts[:2], pts, "x")] == \
        ["1 point(s) x gives are missing from the file"]
    moved = pts.copy()
    moved[1, 0] = np.nextafter(moved[1, 0], 1)
    assert len(match_violations(moved, pts, "x")) == 2
    assert match_violations(np.vstack([pts, pts[:1]]), pts, "x")[0].message.startswith("1 point(s) of the file")
    assert match_violations(np.c_[pts, pts[:, :1]], pts, "x")[0].kind == "seed"


def test_the_compiled_scan_makes_room_for_every_pair_of_a_forged_set():
    """A lattice at 0.6 d: no cell is overfull, and every point has close neighbours, far more
    pairs than the scan's first guess of room: it scans again with room for all."""
    d = 1.0
    g = np.arange(30) * 0.6 * d
    pts = np.stack(np.meshgrid(g, g), axis=-1).reshape(-1, 2)
    pairs = point_violations_pairs(pts, d)
    assert len(pairs) > len(pts)
    assert np.array_equal(point_violations_pairs(pts, d, kernel=_compiled_scan()), pairs)
