"""Penrose P3/P2 by substitution and by de Bruijn's pentagrid (tilesolve.constructive.penrose),
checked by the independent verifier, against each other, and against the golden ratio."""

from collections import defaultdict

import numpy as np
import pytest

from tilesolve.constructive import penrose as P
from tilesolve.errors import InvalidProblem
from tilesolve.verify.substitution import penrose_violations

PHI = (1 + 5**0.5) / 2
#: interior angle (units of 36 degrees) at corners 0..3 of a marked thin (0) and thick (1) rhomb
ANGLES = {0: (4, 1, 4, 1), 1: (2, 3, 2, 3)}


def vertex_configurations(types, v) -> set:
    """The vertex configurations of a P3 patch: at every vertex filled to 360 degrees, the
    sorted multiset of (rhomb type, corner from the marked one) that meet there."""
    at = defaultdict(list)
    for t, quad in zip(types.tolist(), v.tolist()):
        for corner, p in enumerate(quad):
            at[tuple(p)].append((t, corner))
    return {tuple(sorted(c)) for c in at.values() if sum(ANGLES[t][i] for t, i in c) == 10}


def first_coronas(types, v, inner) -> set:
    """Every tile whose centre lies in ``inner`` with its four edge neighbours, translated so that
    its marked vertex is the origin: (type, corners, the neighbours' (type, corners))."""
    edges = defaultdict(list)
    for i, q in enumerate(v.tolist()):
        for s in range(4):
            edges[frozenset((tuple(q[s]), tuple(q[(s + 1) % 4])))].append(i)
    c = P.zeta_xy(v).mean(axis=1)
    x0, y0, w, h = inner
    out = set()
    for i, q in enumerate(v.tolist()):
        if not (x0 <= c[i, 0] < x0 + w and y0 <= c[i, 1] < y0 + h):
            continue
        o = np.array(q[0])
        ring = []
        for s in range(4):
            nb = [j for j in edges[frozenset((tuple(q[s]), tuple(q[(s + 1) % 4])))] if j != i]
            assert nb, "an inner tile lacks a neighbour"
            ring.append((int(types[nb[0]]), tuple(map(tuple, (v[nb[0]] - o).tolist()))))
        out.add((int(types[i]), tuple(map(tuple, (v[i] - o).tolist())), tuple(ring)))
    return out


def tiles_of(types, v) -> set:
    return {(t, tuple(map(tuple, q))) for t, q in zip(types.tolist(), v.tolist())}


def test_phi_is_a_unit_of_the_ring():
    one = np.array([1, 0, 0, 0])
    assert np.array_equal(P._over_phi(P._times_phi(one)), one)
    assert np.allclose(P.zeta_xy(P._times_phi(one)), [PHI, 0])
    assert all(np.allclose(P.zeta_xy(P._unit(d)), [np.cos(np.pi * d / 5), np.sin(np.pi * d / 5)]) for d in range(10))


@pytest.mark.parametrize("steps", [1, 4, 7])
def test_substitution_patches_keep_the_matching_rules(steps):
    types, v = P.p3_substitution(steps)
    assert penrose_violations("p3", types, v) == []
    kd = P.p2_from_p3(types, v)
    assert len(kd[0]) > 0 and penrose_violations("p2", *kd) == []


@pytest.mark.parametrize("window,seed", [((-10, -10, 20, 20), 1), ((999_000, -300_000, 25, 15), 2),
                                         ((-40, 7, 60, 30), 99)])
def test_pentagrid_windows_keep_the_matching_rules(window, seed):
    types, v = P.pentagrid(window, seed=seed)
    assert penrose_violations("p3", types, v) == []
    assert penrose_violations("p2", *P.p2_from_p3(types, v)) == []
    x0, y0, w, h = window
    c = P.zeta_xy(v).mean(axis=1)
    assert (c[:, 0] >= x0).all() and (c[:, 0] < x0 + w).all() and (c[:, 1] >= y0).all() and (c[:, 1] < y0 + h).all()


def test_pentagrid_random_access_windows_agree_where_they_overlap():
    a, b = P.pentagrid((-30, -20, 40, 30), seed=7), P.pentagrid((0, -10, 40, 30), seed=7)
    both = P.pentagrid((0, -10, 10, 20), seed=7)  # the overlap
    sa, sb, s = tiles_of(*a), tiles_of(*b), tiles_of(*both)
    assert s and s <= sa and s <= sb and (sa & sb) == s
    assert tiles_of(*P.pentagrid((0, -10, 10, 20), seed=8)) != s  # another seed, another tiling


def test_a_singular_pentagrid_is_refused():
    with pytest.raises(InvalidProblem, match="singular"):
        P.pentagrid((-3, -3, 6, 6), gamma=[0.0] * 5)  # five lines through the origin


def test_the_two_routes_agree_on_one_region():
    """Agree: on the same window both routes give valid P3 patches (same verifier, same arrows),
    with the same eight vertex configurations, and the same thick/thin ratio to 2%."""
    window = (-25, -25, 50, 50)
    sub, grid = P.p3_substitution(window=window), P.pentagrid(window, seed=3)
    for types, v in (sub, grid):
        assert penrose_violations("p3", types, v) == []
    cs, cg = vertex_configurations(*sub), vertex_configurations(*grid)
    assert cs == cg and len(cs) == 8
    ratios = [np.count_nonzero(t == 1) / np.count_nonzero(t == 0) for t, _ in (sub, grid)]
    assert abs(ratios[0] - ratios[1]) < 0.02 * PHI


@pytest.mark.parametrize("kind", ["p3", "p2"])
def test_the_two_routes_show_the_same_first_coronas(kind):
    """Agree, patch by patch: on one window, the set of tiles with their four edge neighbours
    (up to translation, orientation and marking kept) is the same for both routes."""
    window, inner = (-20, -20, 40, 40), (-16, -16, 32, 32)
    routes = [P.p3_substitution(window=window), P.pentagrid(window, seed=3)]
    if kind == "p2":
        routes = [P.p2_from_p3(*r) for r in routes]
    a, b = (first_coronas(*r, inner) for r in routes)
    assert a == b and len(a) > 50


def inside(types, v, window):
    """The tiles whose centre lies in ``window``."""
    x0, y0, w, h = window
    c = P.zeta_xy(v).mean(axis=1)
    keep = (c[:, 0] >= x0) & (c[:, 0] < x0 + w) & (c[:, 1] >= y0) & (c[:, 1] < y0 + h)
    return types[keep], v[keep]


def same_region(a, b, window):
    """The P3 patches ``a`` and ``b`` (b covering ``window``) coincide tile for tile in ``window``, as
    rhombs and as the kites and darts of p2_from_p3 (away from the window's edge, where P2 drops
    halves)."""
    sa, sb = tiles_of(*inside(*a, window)), tiles_of(*inside(*b, window))
    x0, y0, w, h = window
    inner = (x0 + 3, y0 + 3, w - 6, h - 6)
    ka, kb = (tiles_of(*inside(*P.p2_from_p3(*p), inner)) for p in (a, b))
    return sa == sb and len(sa) > 100, ka == kb and len(ka) > 50


@pytest.mark.parametrize("window", [(-8, -8, 16, 16), (-20, -15, 40, 30), (-26, -24, 50, 47)])
def test_a_substitution_patch_is_a_pentagrid_window_tile_for_tile(window):
    """The sun that covers a window, moved by pentagrid_of's shift, is the pentagrid of the
    offsets pentagrid_of reads from it: the same rhombs with the same markings, and the same
    kites and darts (the module docstring's correspondence)."""
    types, v = P.p3_substitution(window=window)
    gamma, shift = P.pentagrid_of(types, v)
    assert abs(gamma.sum()) < 1e-12 and shift in range(5)
    moved = v + np.array([shift, 0, 0, 0])
    x0, y0, w, h = window
    grid = P.pentagrid((x0 + shift - 2, y0 - 2, w + 4, h + 4), gamma=gamma)
    here = (x0 + shift, y0, w, h)
    assert same_region((types, moved), grid, here) == (True, True)
    assert not same_region((types, v), grid, here)[0]  # unmoved, it is not


@pytest.mark.parametrize("seed", [1, 2, 3, 4])
def test_deflation_acts_on_the_pentagrid_offsets(seed):
    """de Bruijn: a pentagrid window deflated once (unit edges again) is the pentagrid of the offsets
    -gamma / phi on the phi-times larger window, tile for tile, rhombs and kites and darts; and
    pentagrid_of reads offsets back from the deflated patch that draw it too."""
    window = (-12, -10, 24, 20)
    gamma = P.pentagrid_offsets(seed)
    deflated = P.deflate_rhombs(*P.pentagrid(window, gamma=gamma))
    big = (-16, -13, 32, 26)  # inside phi times the window, away from its edge
    assert same_region(deflated, P.pentagrid(big, gamma=-gamma / PHI), big) == (True, True)
    read, shift = P.pentagrid_of(*deflated)
    assert shift == 0 and same_region(deflated, P.pentagrid(big, gamma=read), big) == (True, True)
    other = P.pentagrid(big, gamma=P.pentagrid_offsets(seed + 100))
    assert same_region(deflated, other, big) == (False, False)


def test_pentagrid_of_refuses_a_patch_no_pentagrid_draws():
    types, v = P.pentagrid((-10, -10, 20, 20), seed=1)
    with pytest.raises(InvalidProblem, match="pentagrid"):
        P.pentagrid_of(types, np.concatenate([v, v + np.array([1, 0, 0, 0])]))  # all five index classes
    far = P.pentagrid((30, -10, 20, 20), seed=2)[1]  # another tiling's vertices beside these
    with pytest.raises(InvalidProblem, match="no regular pentagrid"):
        P.pentagrid_of(types, np.concatenate([v, far]))


def test_tile_ratios_tend_to_the_golden_ratio():
    errors = []
    for steps in (3, 5, 7, 9):
        t, v = P.p3_substitution(steps)
        thick_thin = np.count_nonzero(t == 1) / np.count_nonzero(t == 0)
        k = P.p2_from_p3(t, v)[0]
        kite_dart = np.count_nonzero(k == 0) / np.count_nonzero(k == 1)
        errors.append((abs(thick_thin - PHI), abs(kite_dart - PHI)))
    assert errors[-1][0] < errors[0][0] and errors[-1][1] < errors[0][1]
    assert errors[-1][0] < 0.01 and errors[-1][1] < 0.02
    for side in (20, 80):
        t, _ = P.pentagrid((-side // 2, -side // 2, side, side), seed=11)
        assert abs(np.count_nonzero(t == 1) / np.count_nonzero(t == 0) - PHI) < (0.05 if side == 20 else 0.01)


def test_p2_from_p3_covers_the_same_region():
    t, v = P.p3_substitution(8)
    k, kv = P.p2_from_p3(t, v)
    area = lambda xy: 0.5 * np.abs(np.sum(xy[..., 0] * np.roll(xy[..., 1], -1, 1) - np.roll(xy[..., 0], -1, 1) * xy[..., 1], 1)).sum()
    a3, a2 = area(P.zeta_xy(v)), area(P.zeta_xy(kv))
    assert a2 <= a3 and a2 > 0.95 * a3  # only boundary halves are dropped
