"""Tile packings: the independent verifier and the constructions (class notes §5.5)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from tilesolve.constructive.packing import (
    corner_packing_from_colors,
    corner_packing_odd,
    domino_position,
    domino_sequence,
    is_domino_packing,
    outer_product,
    random_symmetry,
    triangular_shift_rows,
    wang_packing,
    wang_position,
    wei_sequence,
)
from tilesolve.constructive.packing_known import FIG_5_11_CORNER_4, FIG_5_12_WANG_4, known_packing
from tilesolve.errors import InvalidProblem, MethodNotApplicable
from tilesolve.model.packing import PackingProblem
from tilesolve.verify.packing import is_packing, packing_violations

#: Fig. 5.10: the Eulerian Wang packing over 3 colours (row 0 at the top).
FIG_5_10 = np.array([
    [6, 15, 16, 7, 24, 17, 25, 26, 8],
    [60, 69, 70, 61, 78, 71, 79, 80, 62],
    [57, 66, 67, 58, 75, 68, 76, 77, 59],
    [33, 42, 43, 34, 51, 44, 52, 53, 35],
    [54, 63, 64, 55, 72, 65, 73, 74, 56],
    [3, 12, 13, 4, 21, 14, 22, 23, 5],
    [30, 39, 40, 31, 48, 41, 49, 50, 32],
    [27, 36, 37, 28, 45, 38, 46, 47, 29],
    [0, 9, 10, 1, 18, 11, 19, 20, 2],
])


# ----------------------------------------------------------------------------- verifier
def test_published_packings_verify():
    assert packing_violations(PackingProblem("wang", 3), FIG_5_10) == []
    assert packing_violations(PackingProblem("corner", 4), FIG_5_11_CORNER_4) == []
    assert packing_violations(PackingProblem("wang", 4), FIG_5_12_WANG_4) == []
    # the figures are printed north-up: upside down they are not packings
    assert not is_packing(PackingProblem("corner", 4), FIG_5_11_CORNER_4[::-1])
    # a Wang packing read as corner tiles is not a corner packing
    assert not is_packing(PackingProblem("corner", 4), FIG_5_12_WANG_4)


@pytest.mark.parametrize("grid,kind,c", [(FIG_5_10, "wang", 3), (FIG_5_11_CORNER_4, "corner", 4),
                                         (FIG_5_12_WANG_4, "wang", 4)])
def test_verifier_catches_swapped_tiles(grid, kind, c):
    g = grid.copy()
    g[0, 0], g[3, 5] = g[3, 5], g[0, 0]
    v = packing_violations(PackingProblem(kind, c), g)
    assert v and all(x.kind == "match" for x in v)
    # the positions name the swapped cells or their west/north neighbours
    cells = {(x.row, x.col) for x in v}
    assert cells <= {(0, 0), (3, 5), (0, g.shape[1] - 1), (g.shape[0] - 1, 0), (3, 4), (2, 5)}


def test_verifier_catches_duplicates_missing_range_shape_and_pins():
    g = FIG_5_10.copy()
    g[4, 4] = g[0, 0]
    kinds = {x.kind for x in packing_violations(PackingProblem("wang", 3), g)}
    assert {"duplicate", "missing"} <= kinds
    dup = [x for x in packing_violations(PackingProblem("wang", 3), g) if x.kind == "duplicate"]
    assert (dup[0].row, dup[0].col) == (4, 4)
    g = FIG_5_10.copy()
    g[2, 2] = 81
    assert [x.kind for x in packing_violations(PackingProblem("wang", 3), g)] == ["tile"]
    assert packing_violations(PackingProblem("wang", 3), FIG_5_10[:8])[0].kind == "shape"
    assert packing_violations(PackingProblem("wang", 2), FIG_5_10)[0].kind == "shape"
    assert packing_violations(PackingProblem("wang", 3), FIG_5_10.astype(float))[0].kind == "tile"
    v = packing_violations(PackingProblem("wang", 3, fixed=[(8, 0, 0), (0, 0, 5)]), FIG_5_10)
    assert [(x.kind, x.row, x.col) for x in v] == [("fixed", 0, 0)]


def test_verifier_checks_the_torus_seams():
    # rolling a packing keeps it a packing; cutting and re-gluing a row does not
    assert is_packing(PackingProblem("corner", 4), np.roll(FIG_5_11_CORNER_4, (5, 11), axis=(0, 1)))
    g = FIG_5_11_CORNER_4.copy()
    g[0] = np.roll(g[0], 1)
    v = packing_violations(PackingProblem("corner", 4), g)
    assert v and {x.row for x in v} <= {0, 15}


# ----------------------------------------------------------------------------- 1D packings
@pytest.mark.parametrize("c", [1, 2, 3, 4, 7])
def test_wei_sequence_and_closed_form(c):
    s = wei_sequence(c)
    assert is_domino_packing(s, c)
    for a in range(c):
        for b in range(c):
            p = domino_position(a, b)
            assert (s[p], s[(p + 1) % (c * c)]) == (a, b)


def test_wei_sequence_is_figure_5_10_axis():
    assert wei_sequence(3).tolist() == [0, 0, 1, 1, 0, 2, 1, 2, 2]
    assert wei_sequence(2).tolist() == [0, 0, 1, 1]


@given(st.integers(1, 9), st.integers(0, 2**31))
@settings(max_examples=40)
def test_random_eulerian_circuits_are_1d_packings(c, seed):
    s = domino_sequence(c, seed=seed)
    assert is_domino_packing(s, c)
    assert np.array_equal(s, domino_sequence(c, seed=seed))  # same seed, same packing


# ----------------------------------------------------------------------------- Wang
def test_outer_product_reproduces_figure_5_10():
    assert np.array_equal(wang_packing(3), FIG_5_10)


@pytest.mark.parametrize("c", [2, 3, 4, 5, 6])
def test_wang_closed_form_position(c):
    g = wang_packing(c)
    assert is_packing(PackingProblem("wang", c), g)
    t = np.arange(c**4)
    r, col = wang_position(t, c)
    assert np.array_equal(g[r, col], t)


@given(st.integers(2, 6), st.integers(1, 5), st.integers(0, 2**31))
@settings(max_examples=30)
def test_seeded_outer_products_are_packings(ch, cv, seed):
    cv = max(cv, 2)
    g = wang_packing(ch, colors_v=cv, seed=seed)
    assert g.shape == (ch * ch, cv * cv)
    assert is_packing(PackingProblem("wang", ch, colors_v=cv), g)


def test_wang_position_with_separate_colours():
    g = wang_packing(2, colors_v=3)
    r, c = wang_position(np.arange(36), 2, colors_v=3)
    assert np.array_equal(g[r, c], np.arange(36))


def test_outer_product_of_non_packings_is_caught():
    g = outer_product(np.array([0, 0, 1, 0]), wei_sequence(2), 2)
    assert not is_packing(PackingProblem("wang", 2), g)


# ----------------------------------------------------------------------------- corner
@pytest.mark.parametrize("c", [3, 5, 7])
def test_triangular_shift_torus_is_a_corner_packing(c):
    """a[i][j] = s[(j + i(i-1)/2) mod C^2] over a de Bruijn sequence B(C,2) is a corner packing."""
    for seed in (None, 0, 1):
        g = corner_packing_odd(c, seed=seed)
        assert packing_violations(PackingProblem("corner", c), g) == []


@pytest.mark.parametrize("c", [2, 3, 4, 5, 6, 7])
def test_triangular_shift_proof(c):
    """The proof, step by step, for B(C,2) = Wei's sequence and for a random one.

    1. window (i, j) reads s[k], s[k+1] over s[k+i], s[k+i+1] with k = j + T(i), T(i) = i(i-1)/2;
    2. (k, k+i) mod n determines (i, j), so the n^2 windows are distinct tiles;
    3. the torus closes (row n is row 0) iff T(n) = 0 mod n, iff C is odd.
    """
    n = c * c
    tri = lambda i: i * (i - 1) // 2  # noqa: E731
    for s in (wei_sequence(c), domino_sequence(c, seed=c)):
        a = triangular_shift_rows(s)
        i, j = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
        k = (j + tri(i)) % n
        # step 1 (inside the torus: rows i and i+1 < n)
        top = i < n - 1
        assert np.array_equal(a[i, j], s[k]) and np.array_equal(a[i, (j + 1) % n], s[(k + 1) % n])
        assert np.array_equal(a[(i + 1)[top], j[top]], s[(k + i)[top] % n])
        # step 2: (k, k + i) are all distinct pairs
        pairs = {(int(x), int(y)) for x, y in zip(k.ravel(), ((k + i) % n).ravel())}
        assert len(pairs) == n * n
        # step 3
        closes = tri(n) % n == tri(0) % n
        assert closes == (c % 2 == 1)
        assert is_packing(PackingProblem("corner", c), corner_packing_from_colors(a, c)) == (c % 2 == 1)


def test_even_corner_construction_refused():
    with pytest.raises(MethodNotApplicable, match="odd"):
        corner_packing_odd(4)


def test_absurd_constructions_refused():
    with pytest.raises(InvalidProblem, match="tiles"):
        wang_packing(1000)
    with pytest.raises(InvalidProblem, match="at least 2"):
        wang_packing(1)


# ----------------------------------------------------------------------------- symmetries
@pytest.mark.parametrize("kind,grid,c", [("corner", FIG_5_11_CORNER_4, 4), ("wang", FIG_5_12_WANG_4, 4),
                                         ("wang", FIG_5_10, 3)])
def test_symmetries_map_packings_to_packings(kind, grid, c):
    for seed in range(12):
        assert is_packing(PackingProblem(kind, c), random_symmetry(grid, kind, c, seed))


def test_known_packings():
    fig, g = known_packing("wang", 4)
    assert fig == "Fig. 5.12" and np.array_equal(g, FIG_5_12_WANG_4)
    assert not np.array_equal(known_packing("corner", 4, seed=3)[1], FIG_5_11_CORNER_4)
    with pytest.raises(MethodNotApplicable):
        known_packing("corner", 6)
