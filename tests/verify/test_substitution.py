"""The independent checker of substitution patches (tilesolve.verify.substitution) catches each
kind of corruption: a wrong shape, a broken arrow, an overlap, a gap, a tile out of place."""

import numpy as np
import pytest

from tilesolve.constructive import penrose as P
from tilesolve.constructive import reptile as R
from tilesolve.verify.substitution import penrose_violations, reptile_violations


@pytest.fixture(scope="module")
def p3():
    return P.p3_substitution(6)


def interior_tile(types, v, t):
    """A tile of type ``t`` near the patch's centre."""
    c = np.hypot(*P.zeta_xy(v).mean(axis=1).T)
    c[types != t] = np.inf
    return int(np.argmin(c))


def kinds(out):
    return {x.kind for x in out}


def test_a_valid_patch_passes(p3):
    assert penrose_violations("p3", *p3) == []


def test_a_moved_vertex_is_no_rhomb(p3):
    t, v = p3[0], p3[1].copy()
    v[5, 2, 0] += 1
    assert kinds(penrose_violations("p3", t, v)) == {"tile"}


@pytest.mark.parametrize("t", [0, 1])
def test_a_rhomb_marked_at_the_other_end_breaks_the_arrows(p3, t):
    types, v = p3[0], p3[1].copy()
    i = interior_tile(types, v, t)
    v[i] = np.roll(v[i], 2, axis=0)  # same rhomb, marking moved to the opposite vertex
    out = penrose_violations("p3", types, v)
    assert out and kinds(out) == {"matching"} and all(f"{i}" in x.message for x in out)


def test_a_thin_rhomb_called_thick_is_caught(p3):
    types = p3[0].copy()
    types[interior_tile(types, p3[1], 0)] = 1
    assert kinds(penrose_violations("p3", types, p3[1])) == {"tile"}


def test_a_missing_interior_tile_is_a_gap(p3):
    types, v = p3
    i = interior_tile(types, v, 1)
    keep = np.arange(len(types)) != i
    out = penrose_violations("p3", types[keep], v[keep])
    assert "gap" in kinds(out) and any("V - E + F" in x.message for x in out)


def test_a_doubled_tile_is_an_overlap(p3):
    types, v = p3
    out = penrose_violations("p3", np.append(types, types[3]), np.concatenate([v, v[3:4]]))
    assert kinds(out) == {"overlap"}


def test_kites_and_darts_joined_as_a_rhomb_break_the_rule():
    kd_t, kd_v = P.p2_from_p3(*P.p3_substitution(6))
    assert penrose_violations("p2", kd_t, kd_v) == []
    bad = kd_t.copy()
    bad[0] = 1 - bad[0]
    assert penrose_violations("p2", bad, kd_v)


def test_wrong_arrays_are_one_violation():
    assert kinds(penrose_violations("p3", np.zeros(2), np.zeros((2, 4, 4)))) == {"shape"}
    assert kinds(penrose_violations("p3", np.zeros(0, np.int8), np.zeros((0, 4, 4), np.int64))) == {"count"}


def test_rep_tile_corruptions():
    v = R.tiles("chair", 3)
    assert reptile_violations("chair", 3, v) == []
    assert kinds(reptile_violations("chair", 3, v[1:])) == {"gap"}
    assert kinds(reptile_violations("chair", 4, v)) == {"gap"}  # not the region 2^4 P
    moved = v.copy()
    moved[0] += 1
    assert kinds(reptile_violations("chair", 3, moved)) <= {"gap", "overlap"} and reptile_violations("chair", 3, moved)
    mirrored = v.copy()
    mirrored[0] = mirrored[0][::-1]  # clockwise
    assert kinds(reptile_violations("chair", 3, mirrored)) == {"tile"}
    s = R.tiles("sphinx", 2)
    assert reptile_violations("sphinx", 2, s) == []
    assert kinds(reptile_violations("sphinx", 2, np.concatenate([s, s[:1]]))) == {"overlap"}


def second_sheet(inner: float, outer: float, x: float = 0):
    """A disk of radius 10 of a pentagrid tiling and, over it, the ring ``inner < r < outer`` around
    ``(x, 0)`` of the same tiling moved by 5 along x: the two sheets share no vertex (a vertex ``p`` of both would
    put two points ``5`` apart in the pentagon ``p* - Gamma`` must lie in), so no edge either."""
    t, v = P.pentagrid((-30, -30, 60, 60), seed=1)
    c = P.zeta_xy(v).mean(axis=1)
    disk = np.hypot(c[:, 0], c[:, 1]) < 10
    r = np.hypot(c[:, 0] + 5 - x, c[:, 1])
    ring = (r > inner) & (r < outer)
    return np.concatenate([t[disk], t[ring]]), np.concatenate([v[disk], v[ring] + np.array([5, 0, 0, 0])])


def test_a_second_sheet_far_from_any_shared_edge_is_an_overlap():
    """A disk with a ring lying over it, no edge or vertex in common: V - E + F = 1 + 0, every edge and
    vertex locally flat, so checks 1-5 passed this file (the verifier before check 6 called it valid).
    Check 6 finds the boundary in three curves and the points where the sheets lie over each other."""
    types, v = second_sheet(5, 14)
    assert penrose_violations("p3", types[:386], v[:386]) == []  # the disk alone
    out = penrose_violations("p3", types, v)
    assert kinds(out) == {"gap", "overlap"}
    assert any("3 separate curves" in x.message for x in out)
    assert any("lie over one point" in x.message for x in out)


def test_sheets_whose_boundaries_cross_are_an_overlap():
    types, v = second_sheet(3, 9, x=4)  # the ring's outer edge crosses the disk's
    out = penrose_violations("p3", types, v)
    assert out and all("cross or touch" in x.message or "separate curves" in x.message for x in out), out[:3]
    assert any("cross or touch" in x.message for x in out)


@pytest.mark.parametrize("kind", ["p3", "p2"])
def test_windows_cut_at_a_vertex_stay_one_sheet(kind):
    """Windows whose edge leaves tiles joined at a single vertex pass check 6 (several seeds)."""
    for seed in range(1, 6):
        patch = P.pentagrid((-7, -5, 14, 10), seed=seed)
        if kind == "p2":
            patch = P.p2_from_p3(*patch)
        assert penrose_violations(kind, *patch) == []
