"""The lattice search (periodic tilings by lattice index) against code that shares nothing with it.

Every witness is checked by the board verifier on its sheared torus (and, repeated, on the plain
torus); every "no tiling" answer of an exhaustive search agrees with the SAT solver on the same
lattice's tile-selection CNF; the plain and the compiled kernel give the same answers.
"""

from __future__ import annotations

import numpy as np
import pytest

from tilesolve.constructive import _period_kernels as K
from tilesolve.constructive.periods import lattices_by_index, rectangle, search
from tilesolve.deadline import Deadline
from tilesolve.encodings.wang_tiles import encode_tiles
from tilesolve.engine.sat import solve_cnf
from tilesolve.errors import InvalidProblem
from tilesolve.io.builtin_tilesets import load
from tilesolve.model.aperiodic import AperiodicProblem, Lattice, leg_colours
from tilesolve.model.board import BoardProblem, WangTileSet
from tilesolve.model.solution import Status
from tilesolve.verify.board import board_violations


def _tiles(lattice: Lattice, tileset: WangTileSet, tiling) -> bool:
    """The board verifier's word that ``tiling`` tiles ``lattice``'s sheared torus."""
    return not board_violations(BoardProblem(lattice.board(), tileset), leg_colours(tileset, tiling))


def _random_set(rng, m: int, colours: int) -> WangTileSet:
    return WangTileSet(rng.integers(0, colours, size=(m, 4)), colours)


def test_lattices_by_index_are_every_lattice_once_by_index():
    lats = list(lattices_by_index(12))
    assert len(lats) == len(set(lats)) == sum(sum(d for d in range(1, n + 1) if n % d == 0) for n in range(1, 13))
    index = [lat.rows * lat.cols for lat in lats]
    assert index == sorted(index) and all(0 <= lat.shear < lat.rows for lat in lats)
    every = set(AperiodicProblem(WangTileSet([[0, 0, 0, 0]], 1), 0, 12, shears=True).lattices())
    assert set(lats) == {lat for lat in every if lat.rows * lat.cols <= 12}


def test_periodic_10_35_is_one_row_of_35_tiles_shifted():
    ts, info = load("periodic-10-35")
    found = search(ts, 35)
    assert found.lattice == Lattice(35, 1, 8) and found.index == 35 == info["period"]
    assert _tiles(found.lattice, ts, found.tiling)
    torus = rectangle(found.lattice, found.tiling)
    assert torus.shape == (35, 35) and _tiles(Lattice(35, 35), ts, torus)


def test_no_smaller_lattice_than_the_one_found_is_tiled_by_sat():
    """periodic-8-20: the search tries its lattices of index below 20 and finds none; SAT on
    each of them agrees (no tiling), and tiles the one the search found."""
    ts, _ = load("periodic-8-20")
    found = search(ts, 20, node_budget=10**6)
    assert found.lattice == Lattice(10, 2, 3) and found.over_budget == 0
    for lat in list(lattices_by_index(20))[:found.tried]:
        r = solve_cnf(encode_tiles(lat.board(), ts).hard, solver="minisat22")
        assert r.status is (Status.SAT if lat == found.lattice else Status.UNSAT), lat


def test_exhaustive_answers_agree_with_sat_on_random_sets():
    rng = np.random.default_rng(7)
    seen = {0: 0, 1: 0}
    for _ in range(60):
        ts = _random_set(rng, int(rng.integers(1, 9)), int(rng.integers(1, 4)))
        col = np.ascontiguousarray(ts.tiles, dtype=np.int64)
        lat = list(lattices_by_index(8))[int(rng.integers(0, 40))]
        out = np.zeros(lat.rows * lat.cols, np.int64)
        got = K.lattice_tiling(col, lat.rows, lat.cols, lat.shear, 10**6, out)
        sat = solve_cnf(encode_tiles(lat.board(), ts).hard, solver="minisat22").status
        assert got == (1 if sat is Status.SAT else 0), (ts.tiles.tolist(), lat)
        if got == 1:
            assert _tiles(lat, ts, out.reshape(lat.rows, lat.cols))
        seen[got] += 1
    assert min(seen.values()) >= 10  # both answers were exercised


def test_plain_and_compiled_kernels_agree(monkeypatch):
    rng = np.random.default_rng(3)
    cases = [(_random_set(rng, int(rng.integers(2, 10)), int(rng.integers(2, 4))), int(rng.integers(1, 30)))
             for _ in range(40)]
    answers = []
    for mode in ("plain", "compiled"):
        monkeypatch.setattr(K.KERNELS, "mode", mode)
        answers.append([(f.lattice, None if f.tiling is None else f.tiling.tolist(), f.tried, f.over_budget)
                        for f in (search(ts, n, node_budget=20) for ts, n in cases)])
    assert answers[0] == answers[1]


def test_rectangle_is_a_plain_torus_tiling():
    rng = np.random.default_rng(5)
    done = 0
    for _ in range(200):
        ts = _random_set(rng, 6, 2)
        found = search(ts, 12)
        if found.lattice is None or found.lattice.shear == 0:
            continue
        torus = rectangle(found.lattice, found.tiling)
        p, q, s = found.lattice
        assert torus.shape == (p, q * p // np.gcd(p, s)) and _tiles(Lattice(*torus.shape), ts, torus)
        done += 1
    assert done >= 5


def test_budget_and_deadline_leave_lattices_without_a_false_witness():
    ts, _ = load("jeandel-rao")  # aperiodic: no lattice is tiled
    found = search(ts, 20, node_budget=1)
    assert found.lattice is None and found.tiling is None and found.over_budget > 0
    assert found.tried == len(list(lattices_by_index(20))) and "node budget of 1" in found.reason
    late = search(ts, 20, deadline=Deadline(0.0))
    assert late.lattice is None and late.tried == 0 and late.reason.startswith("time limit reached")


@pytest.mark.parametrize("index, budget", [(0, 5), (3, 0)])
def test_search_refuses_empty_bounds(index, budget):
    with pytest.raises(InvalidProblem, match="at least 1"):
        search(WangTileSet([[0, 0, 0, 0]], 1), index, node_budget=budget)
