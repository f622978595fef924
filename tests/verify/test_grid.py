"""The shared grid-tiling verifier (class notes §2.7): valid tilings pass, every corruption is caught."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from tilesolve.verify.grid import count_mismatches, grid_violations, is_grid_tiling


def complete_table(c: int) -> np.ndarray:
    """Colours of the complete set, row i = digits of i in base c (eq. 2.3 / 2.6 order)."""
    return np.array(list(itertools.product(range(c), repeat=4)), dtype=np.int64)


def wang_tiling(rows, cols, c, rng, toroidal):
    """A valid tiling built from random edge colours (independent of the generators)."""
    h = rng.integers(0, c, size=(rows + 1, cols))
    v = rng.integers(0, c, size=(rows, cols + 1))
    if toroidal:
        h[-1], v[:, -1] = h[0], v[:, 0]
    n, s, w, e = h[:-1], h[1:], v[:, :-1], v[:, 1:]
    return ((n * c + e) * c + s) * c + w


def corner_tiling(rows, cols, c, rng, toroidal):
    p = rng.integers(0, c, size=(rows + 1, cols + 1))  # p[r, c] = colour of the lattice point NW of cell (r, c)
    if toroidal:
        p[-1], p[:, -1] = p[0], p[:, 0]
    nw, ne, sw, se = p[:-1, :-1], p[:-1, 1:], p[1:, :-1], p[1:, 1:]
    return ((ne * c + se) * c + sw) * c + nw


def naive_mismatches(g, table, kind, toroidal) -> int:
    """Cell-by-cell reference count of mismatched shared sides (the definition, looped)."""
    rows, cols = g.shape
    # (own side, neighbour side) towards the east and towards the south
    east, south = ([(1, 3)], [(2, 0)]) if kind == "wang" else ([(0, 3), (1, 2)], [(2, 3), (1, 0)])
    bad = 0
    for r in range(rows):
        for q in range(cols):
            for dr, dq, pairs in ((0, 1, east), (1, 0, south)):
                r2, q2 = r + dr, q + dq
                if not toroidal and (r2 >= rows or q2 >= cols):
                    continue
                other = table[g[r2 % rows, q2 % cols]]
                bad += sum(int(table[g[r, q]][a] != other[b]) for a, b in pairs)
    return bad


@pytest.mark.slow
@settings(max_examples=200)
@given(rows=st.integers(1, 7), cols=st.integers(1, 7), c=st.integers(2, 4), kind=st.sampled_from(["wang", "corner"]),
       toroidal=st.booleans(), seed=st.integers(0, 2**32 - 1), data=st.data())
def test_valid_tilings_pass_and_single_cell_corruptions_are_caught(rows, cols, c, kind, toroidal, seed, data):
    rng = np.random.default_rng(seed)
    make = wang_tiling if kind == "wang" else corner_tiling
    g = make(rows, cols, c, rng, toroidal)
    table = complete_table(c)
    assert grid_violations(table, g, kind=kind, toroidal=toroidal) == []
    assert is_grid_tiling(table, g, kind=kind, toroidal=toroidal)
    r, q = data.draw(st.integers(0, rows - 1)), data.draw(st.integers(0, cols - 1))
    new = data.draw(st.integers(0, c**4 - 1).filter(lambda t: t != g[r, q]))
    bad = g.copy()
    bad[r, q] = new
    v = grid_violations(table, bad, kind=kind, toroidal=toroidal)
    n_bad = naive_mismatches(bad, table, kind, toroidal)
    assert count_mismatches(table, bad, kind=kind, toroidal=toroidal) == len(v) == n_bad
    if n_bad:
        assert v, "corruption not caught"
        near = {((r + dr) % rows, (q + dq) % cols) for dr in (-1, 0) for dq in (-1, 0)}
        assert all(x.kind == "match" and (x.row, x.col) in near for x in v)
    else:
        assert v == []


def test_out_of_range_and_shape_problems():
    table = complete_table(2)
    v = grid_violations(table, [[0, 16], [-1, 0]])
    assert [(x.kind, x.row, x.col) for x in v] == [("tile", 0, 1), ("tile", 1, 0)]
    assert grid_violations(table, [0, 1])[0].kind == "shape"
    assert grid_violations(table[:, :3], [[0]])[0].kind == "shape"
    assert grid_violations(table, [[0.5]])[0].kind == "tile"
    assert not is_grid_tiling(table, [[99]])


def test_labels_name_tiles_of_a_sparse_set():
    # The compact Wang set over 2 colours of the notes' Fig. 3.2, named by its eq. 2.1 indices.
    labels = np.array([0, 3, 5, 6, 9, 10, 12, 15])
    table = complete_table(2)[labels]
    assert grid_violations(table, [[0, 0], [0, 0]], labels=labels) == []
    v = grid_violations(table, [[0, 1]], labels=labels)
    assert [(x.kind, x.col) for x in v] == [("tile", 1)]


def test_corner_mismatch_message_names_the_corners():
    table = complete_table(2)
    # cell 0: all corners 0; cell 1 east of it with NW = 1 (eq. 2.5: index 1)
    v = grid_violations(table, [[0, 1]], kind="corner")
    assert [str(x) for x in v] == ["(row 0, col 0) NE colour 0 meets NW colour 1 of the cell to the east"]


def test_limit_caps_the_list():
    table = complete_table(2)
    g = np.arange(16).reshape(4, 4)
    assert len(grid_violations(table, g, limit=3)) == 3
    assert len(grid_violations(table, g)) == count_mismatches(table, g) > 3
