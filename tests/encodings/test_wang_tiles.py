"""The tile-selection CNF's parts: the formula of a sub-board, in the whole board's variables."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from tilesolve.encodings.wang_tiles import encode_tiles
from tilesolve.model.aperiodic import Lattice
from tilesolve.model.board import Board, WangTileSet


def _clauses(cs) -> set[frozenset[int]]:
    return {frozenset(c) for c in cs}


@settings(max_examples=30, deadline=None)
@given(st.lists(st.tuples(*[st.integers(0, 2)] * 4), min_size=1, max_size=5),
       st.integers(2, 4), st.integers(2, 5), st.integers(1, 4))
def test_a_band_of_a_torus_is_the_cylinder_formula(tiles, rows, cols, h):
    """The first h columns of a rows x cols torus give the formula of the cylinder of h columns
    whose rows wrap, its cells renamed to the torus's cells, and units that forbid a tile with
    no possible neighbour across a leg that leaves the band; all of them torus clauses."""
    h = min(h, cols - 1)
    ws = WangTileSet(np.array(tiles), 3)
    m = len(ws)
    torus = encode_tiles(Board.torus(cols, rows), ws)
    cyl = encode_tiles(Board.grid(np.ones((rows, h), bool), wrap_rows="plain"), ws)
    where = {tuple(rc): i for i, rc in enumerate(torus.labels.tolist())}
    cell = np.array([where[tuple(rc)] for rc in cyl.labels.tolist()])

    def rename(v: int) -> int:
        c, t = divmod(abs(v) - 1, m)
        return int(np.sign(v)) * (1 + cell[c] * m + t)

    part = torus.part(torus.labels[:, 1] < h)
    band = {frozenset(map(rename, c)) for c in cyl.hard}
    assert band <= _clauses(part) <= _clauses(torus.hard)
    assert all(len(c) == 1 for c in _clauses(part) - band)


def test_a_part_of_a_sheared_torus_keeps_only_clauses_inside_it():
    ws = WangTileSet([[0, 1, 1, 0], [1, 0, 0, 1]], 2)
    enc = encode_tiles(Lattice(3, 4, 1).board(), ws)
    mask = enc.labels[:, 0] < 2
    inside = set(np.flatnonzero(mask).tolist())
    part = enc.part(mask)
    assert 0 < len(part) < len(enc.hard)
    assert all((abs(v) - 1) // len(ws) in inside for c in part for v in c)
    kept = _clauses(part)
    assert all(frozenset(c) in kept for c in enc.hard if all((abs(v) - 1) // len(ws) in inside for v in c))
