"""Wang and corner tile sets with the class notes' indexing (§2.7-2.9, eq. 2.1-2.7)."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import given, strategies as st

from tilesolve.errors import InvalidProblem
from tilesolve.model.tiles import (
    TileSet,
    corner_colors,
    corner_index,
    corner_to_wang,
    wang_colors,
    wang_index,
)


def test_complete_set_sizes_match_the_notes():
    # §2.7: "over 2, 3, 4, 5, 6, 7 and 8 colors consist of 16, 81, 256, 625, 1,296, 2,401 and 4,096 tiles"
    assert [TileSet("wang", c).n_tiles for c in range(2, 9)] == [16, 81, 256, 625, 1296, 2401, 4096]
    assert [TileSet("corner", c).n_tiles for c in range(2, 9)] == [16, 81, 256, 625, 1296, 2401, 4096]
    # (C_h C_v)^2 tiles with separate horizontal and vertical colours
    assert TileSet("wang", 2, colors_v=3).n_tiles == 36


@pytest.mark.parametrize("c", [2, 3, 5])
def test_wang_index_is_eq_2_1_and_inverts_eq_2_3(c):
    for n, e, s, w in itertools.product(range(c), repeat=4):
        i = wang_index(n, e, s, w, colors=c)
        assert i == n * c**3 + e * c**2 + s * c + w  # eq. 2.1
        assert i == ((n * c + e) * c + s) * c + w  # eq. 2.2 (Horner)
        assert wang_colors(i, colors=c) == (n, e, s, w)  # eq. 2.3/2.4


@pytest.mark.parametrize("c", [2, 3, 4])
def test_corner_index_is_eq_2_5_and_inverts_eq_2_6(c):
    for ne, se, sw, nw in itertools.product(range(c), repeat=4):
        i = corner_index(ne, se, sw, nw, colors=c)
        assert i == ne * c**3 + se * c**2 + sw * c + nw
        assert corner_colors(i, colors=c) == (ne, se, sw, nw)


def test_indices_enumerate_the_complete_set_once():
    for ts in (TileSet("wang", 3), TileSet("corner", 3), TileSet("wang", 2, colors_v=3)):
        tab = ts.table()
        assert tab.shape == (ts.n_tiles, 4)
        back = ts.index(*tab.T)
        assert back.tolist() == list(range(ts.n_tiles))
        assert len({tuple(r) for r in tab.tolist()}) == ts.n_tiles


def test_mixed_radix_reduces_to_eq_2_1():
    assert wang_index(1, 2, 0, 1, colors=3, colors_v=3) == wang_index(1, 2, 0, 1, colors=3)
    ts = TileSet("wang", 2, colors_v=3)
    # N, S in 0..1 (C_h = 2), E, W in 0..2 (C_v = 3)
    assert ts.radices == (2, 3, 2, 3)
    assert ts.table()[:, [0, 2]].max() == 1 and ts.table()[:, [1, 3]].max() == 2


@given(st.integers(2, 6), st.data())
def test_corner_to_wang_preserves_matching(c, data):
    """§2.9: two corner tiles match along an edge exactly when their Wang images do."""
    a = data.draw(st.integers(0, c**4 - 1))
    b = data.draw(st.integers(0, c**4 - 1))
    ane, ase, asw, anw = corner_colors(a, colors=c)
    bne, bse, bsw, bnw = corner_colors(b, colors=c)
    wa = wang_colors(corner_to_wang(a, colors=c), colors=c * c)
    wb = wang_colors(corner_to_wang(b, colors=c), colors=c * c)
    # b east of a
    assert ((ane, ase) == (bnw, bsw)) == (wa[1] == wb[3])
    # b south of a
    assert ((asw, ase) == (bnw, bne)) == (wa[2] == wb[0])


def test_corner_set_as_wang_set_is_figure_2_7():
    """The corner set over 2 colours is a Wang set of 16 tiles over 4 colours, injectively."""
    ts = TileSet("corner", 2)
    images = ts.wang_images()
    assert ts.as_wang() == TileSet("wang", 4)
    assert len(set(images.tolist())) == 16 and images.max() < 256


def test_bad_tile_sets_are_refused():
    with pytest.raises(InvalidProblem, match="unknown tile kind"):
        TileSet("hex", 2)
    with pytest.raises(InvalidProblem, match=">= 1"):
        TileSet("wang", 0)
    with pytest.raises(InvalidProblem, match="only for Wang"):
        TileSet("corner", 2, colors_v=3)
    with pytest.raises(InvalidProblem, match="integer"):
        TileSet("wang", 2.5)


def test_vectorised_and_scalar_agree():
    i = np.arange(81)
    n, e, s, w = wang_colors(i, colors=3)
    assert [wang_colors(int(k), colors=3) for k in i] == list(zip(n.tolist(), e.tolist(), s.tolist(), w.tolist()))
