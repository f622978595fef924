"""The independent Poisson sphere checks (tilesolve.verify.poisson_sphere): the grid search
against scipy's KD-tree, and forged tile sets caught."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial import cKDTree

from tilesolve.model.poisson_sphere import PoissonSphereTilesProblem, PoissonSphereTileSet
from tilesolve.verify.poisson_sphere import close_pairs3, point_violations3, tileset_violations3


def _kdtree_pairs(points, distance):
    pairs = cKDTree(points).query_pairs(distance, output_type="ndarray")
    pairs = np.sort(pairs, axis=1)
    gap = np.linalg.norm(points[pairs[:, 0]] - points[pairs[:, 1]], axis=1)
    return np.unique(pairs[gap < distance], axis=0).reshape(-1, 2)


@pytest.mark.parametrize("scale", [(1, 1, 1), (1e6, 1, 1), (3, 1e5, 2)])  # dense table, and sparse search
@pytest.mark.parametrize("seed", range(3))
def test_close_pairs_are_the_kdtree_s(scale, seed):
    rng = np.random.default_rng(seed)
    pts = rng.random((2000, 3)) * scale
    pts = np.vstack([pts, pts[:40] + 1e-3])  # close pairs
    d = 0.08
    assert np.array_equal(close_pairs3(pts, d), _kdtree_pairs(pts, d))
    assert np.array_equal(close_pairs3(pts, d, kernel=_compiled_scan()), _kdtree_pairs(pts, d))


def _compiled_scan():
    """The compiled neighbour scan of the verifiers' grids (used for large sets)."""
    import importlib

    from tilesolve.verify import _poisson_kernel

    importlib.import_module("tilesolve._numba")  # the scan is compiled where numba is loaded
    return _poisson_kernel.compiled(_poisson_kernel.COMPILED_FROM)


def test_an_overfull_cell_is_cut_short():
    """More than eight points in a d-cube hold a close pair (pigeonhole): the first nine are
    compared, so a file of many equal points costs no more than a valid one."""
    pts = np.vstack([np.zeros((1000, 3)), [[5.0, 5.0, 5.0]]])
    pairs = close_pairs3(pts, 0.1)
    assert len(pairs) == 36 and pairs.max() < 1000
    assert np.array_equal(close_pairs3(pts, 0.1, kernel=_compiled_scan()), pairs)


def test_point_violations3_messages():
    assert point_violations3(np.zeros((2, 2)), 0.1, (1, 1, 1))[0].kind == "shape"
    assert point_violations3([[0.5, 0.5, np.nan]], 0.1, (1, 1, 1))[0].kind == "shape"
    v = point_violations3([[0.5, 0.5, 1.5], [0.1, 0.1, 0.1], [0.1, 0.1, 0.15]], 0.1, (1, 1, 1))
    assert [x.kind for x in v] == ["window", "distance"]
    many = point_violations3(np.zeros((30, 3)), 0.1, (1, 1, 1))
    assert many[-1].message == "36 pairs in all are closer than 0.1"


@pytest.fixture(scope="module")
def good():
    """A small valid set, built by the constructive code (the verifier shares none of it)."""
    from tilesolve.constructive.poisson_sphere import build_tiles

    return build_tiles(PoissonSphereTilesProblem(2, 100, 0.6), seed=5)


def _forged(ts, kind, index, points):
    tiles = {k: [a.copy() for a in v] for k, v in ts.tiles.items()}
    tiles[kind][index] = points
    return PoissonSphereTileSet(ts.problem, tiles)


def test_a_point_outside_its_region_is_caught(good):
    pts = np.vstack([good.tiles["xedge"][1], [[0.5, 0.45, 0.0]]])  # beyond the edge bar
    v = tileset_violations3(_forged(good, "xedge", 1, pts))
    assert v and v[0].kind == "region" and "xedge tile 1" in v[0].message


def test_points_too_close_across_a_seam_are_caught(good):
    """A point added to interior tile 0, at least d from that tile's points and inside its
    region but closer than d to a point of a tile around the cell (all corners colour 0): only
    the check across the seams finds it."""
    from tilesolve.constructive.poisson_sphere import lattice_slots

    p = good.problem
    d, a, b = p.distance, p.corner_half, p.edge_half
    slots = lattice_slots(np.zeros((2, 2, 2), np.int64), 2)
    around = np.vstack([good.tiles[k][t] + o for k in slots if k != "interior" for o, t in zip(*slots[k])])
    interior = good.tiles["interior"][0]
    rng = np.random.default_rng(0)
    for q in rng.uniform(d, 1 - d, size=(20000, 3)):
        near_corner = (np.minimum(q, 1 - q) < a).all()
        near_edge = (np.sort(np.minimum(q, 1 - q))[:2] < b).all()
        if near_corner or near_edge:
            continue
        if np.linalg.norm(interior - q, axis=1).min() > 1.01 * d and np.linalg.norm(around - q, axis=1).min() < 0.9 * d:
            break
    else:
        pytest.fail("no such point found")
    v = tileset_violations3(_forged(good, "interior", 0, np.vstack([interior, q])))
    assert v and all(x.kind == "distance" and "interior tile 0" in x.message and " and " in x.message for x in v), v


def test_an_edge_point_too_close_to_its_corner_is_caught(good):
    """A point added to an x-edge tile, inside the edge's bar, just past a point of the corner
    tile at its west end: the two tiles are built against each other, and the forgery shows
    only when they are put side by side."""
    p = good.problem
    a, b, d = p.corner_half, p.edge_half, p.distance
    corners = np.vstack([good.tiles["corner"][0], good.tiles["corner"][0] + [1, 0, 0]])
    edge = good.tiles["xedge"][0]  # colours 0, 0
    rng = np.random.default_rng(1)
    cand = [q for q in rng.uniform([a, -b, -b], [1 - a, b, b], size=(20000, 3))
            if np.linalg.norm(edge - q, axis=1).min() > d and np.linalg.norm(corners - q, axis=1).min() < 0.9 * d]
    assert cand, "no such point found"
    v = tileset_violations3(_forged(good, "xedge", 0, np.vstack([edge, cand[0]])))
    assert v and all(x.kind == "distance" for x in v)
    assert any("corner tile 0" in x.message and "xedge tile 0" in x.message for x in v), v


def test_edges_meeting_at_a_corner_cannot_come_too_close(good):
    """The regions keep edges of two axes sqrt(2) (a - b) >= d apart (the design the verifier
    measures): the nearest points their bars allow are not a violation."""
    p = good.problem
    a, b = p.corner_half, p.edge_half
    x = np.vstack([good.tiles["xedge"][0], [[a, b * (1 - 1e-9), 0.0]]])
    y = np.vstack([good.tiles["yedge"][0], [[b * (1 - 1e-9), a, 0.0]]])
    forged = _forged(_forged(good, "xedge", 0, x), "yedge", 0, y)
    assert not [v for v in tileset_violations3(forged) if "xedge" in v.message and "yedge" in v.message]


def test_random_colourings_above_the_budget(good):
    assert tileset_violations3(good, max_colourings=16, seed=3) == []


@pytest.mark.parametrize("hash_", ["long", "table"])
def test_the_verifiers_placement_gives_the_builders_points_exactly(hash_):
    """Made-up tiles of several points each, some reaching past their slot's cell (the
    placement does not care where a set's points lie): the verifier's placement on the lattice
    a far box's seed colours, cropped to the box, is the builder's box, point for point."""
    from tilesolve.constructive.poisson_sphere import lattice_colors, window_points
    from tilesolve.verify.poisson import match_violations
    from tilesolve.verify.poisson_sphere import placed_points3

    p = PoissonSphereTilesProblem(2, 100, 0.6)
    rng = np.random.default_rng(8)
    ts = PoissonSphereTileSet(p, {k: [rng.random((int(rng.integers(1, 5)), 3)) * 1.4 - 0.2 for _ in range(n)]
                                  for k, n in p.counts().items()})
    box = (2**40 + 3, -17, 5, 4, 3, 2)
    built = window_points(ts, box, hash=hash_, seed=11)
    lat = lattice_colors(built.box, 2, seed=11, hash=hash_)
    inside = lambda pts: pts[((pts >= 0) & (pts < [4, 3, 2])).all(axis=1)]  # noqa: E731
    mine = placed_points3(ts, lat)
    assert 0 < len(inside(mine)) < len(mine)  # uncropped: tiles reach past the box
    assert match_violations(built.local, inside(mine), "the verifier") == []
    assert match_violations(built.local, inside(placed_points3(ts, 1 - lat)), "another colouring") != []
