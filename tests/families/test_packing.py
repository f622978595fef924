"""Solver-built packings (SAT and CP-SAT), pins, unsat with proof, the facade's routes."""

from __future__ import annotations

import numpy as np
import pytest

from tilesolve.families import packing as facade
from tilesolve.encodings.packing import encode_packing
from tilesolve.errors import InvalidProblem, MethodNotApplicable
from tilesolve.model.packing import PackingProblem
from tilesolve.model.solution import Status
from tilesolve.verify.packing import is_packing, packing_violations


@pytest.mark.fast_cases(1)
@pytest.mark.parametrize("kind", ["wang", "corner"])
@pytest.mark.parametrize("c", [2, 3])
def test_sat_packings_verify(kind, c):
    s = facade.solve(PackingProblem(kind, c), method="sat", seed=2)
    assert s.status is Status.SAT and s.method == "sat"
    assert packing_violations(PackingProblem(kind, c), s.tiling) == []
    if c == 2 or kind == "wang":  # same seed, same packing
        assert np.array_equal(s.tiling, facade.solve(PackingProblem(kind, c), method="sat", seed=2).tiling)


@pytest.mark.parametrize("kind", ["wang", "corner"])
def test_cpsat_packings_verify(kind):
    s = facade.solve(PackingProblem(kind, 2), method="cpsat", seed=1, time_limit=60)
    assert s.status is Status.SAT and is_packing(PackingProblem(kind, 2), s.tiling)
    s = facade.solve(PackingProblem("wang", 3), method="cpsat", seed=1, time_limit=60, workers=2)
    assert s.status in (Status.SAT, Status.UNKNOWN)
    if s.status is Status.SAT:
        assert is_packing(PackingProblem("wang", 3), s.tiling)


@pytest.mark.slow
def test_solver_packings_are_not_separable():
    """Random-looking: a Wang outer product repeats one W/E sequence in every row; SAT's need not."""
    g = facade.solve(PackingProblem("wang", 3), method="sat", seed=11).tiling
    west = g % 3
    assert len({tuple(r) for r in west.tolist()}) > 1
    outer = facade.solve(PackingProblem("wang", 3), method="outer", seed=11).tiling
    assert len({tuple(r) for r in (outer % 3).tolist()}) == 1


@pytest.mark.slow
def test_pinned_tiles_are_respected():
    pins = ((0, 0, 5), (4, 4, 7), (2, 3, 80))
    p = PackingProblem("wang", 3, fixed=pins)
    s = facade.solve(p, seed=2)
    assert s.status is Status.SAT
    for r, c, t in pins:
        assert s.tiling[r, c] == t
    # a single pin is met by the constructions through translation
    p1 = PackingProblem("corner", 5, fixed=((3, 7, 100),))
    for method in ("euler", "outer"):
        s = facade.solve(p1, method=method, seed=4)
        assert s.tiling[3, 7] == 100


def test_contradictory_pins_are_unsat_with_a_checked_proof():
    cases = [
        ((0, 0, 0), (0, 1, 15)),  # all-0 and all-1 corner tiles cannot touch
        ((0, 0, 5), (2, 2, 5)),  # one tile at two cells
        ((1, 1, 3), (1, 1, 4)),  # two tiles at one cell
    ]
    for pins in cases:
        s = facade.solve(PackingProblem("corner", 2, fixed=pins), method="sat")
        assert s.status is Status.UNSAT, pins
        assert "checked" in s.reason
    with pytest.raises(MethodNotApplicable):
        facade.solve(PackingProblem("wang", 3, fixed=((0, 0, 1), (0, 1, 2))), method="euler")


@pytest.mark.slow
def test_time_limit_gives_unknown_not_unsat():
    s = facade.solve(PackingProblem("corner", 4), method="sat", time_limit=0.5)
    assert s.status is Status.UNKNOWN and s.tiling is None and "time limit" in s.reason


@pytest.mark.slow
def test_auto_routes():
    for kind, c, method in [("wang", 2, "sat"), ("corner", 3, "outer"), ("wang", 3, "sat"), ("corner", 2, "sat"),
                            ("wang", 4, "lift"), ("wang", 5, "outer"), ("wang", 6, "lift"), ("wang", 8, "outer"),
                            ("corner", 4, "lift"), ("corner", 5, "outer"), ("corner", 6, "lift"), ("corner", 8, "lift")]:
        assert facade.auto_method(PackingProblem(kind, c)) == method
    for kind, c in [("wang", 4), ("corner", 4), ("corner", 6), ("corner", 7), ("wang", 8)]:
        s = facade.solve(PackingProblem(kind, c), seed=3)
        assert s.status is Status.SAT and is_packing(PackingProblem(kind, c), s.tiling)


def test_bad_input():
    with pytest.raises(InvalidProblem, match="at least 2"):
        PackingProblem("wang", 1)
    with pytest.raises(InvalidProblem, match="kind"):
        PackingProblem("hex", 2)
    with pytest.raises(InvalidProblem, match="outside"):
        PackingProblem("wang", 2, fixed=((4, 0, 1),))
    with pytest.raises(InvalidProblem, match="not in"):
        PackingProblem("wang", 2, fixed=((0, 0, 16),))
    with pytest.raises(InvalidProblem, match="clauses"):
        facade.solve(PackingProblem("corner", 10), method="sat")
    with pytest.raises(InvalidProblem, match="unknown method"):
        facade.solve(PackingProblem("corner", 2), method="magic")


@pytest.mark.slow
def test_encoding_accepts_exactly_the_packings():
    """The published C=2/C=4 packings satisfy the CNF (placements and features set from them)."""
    from tilesolve.constructive.packing_known import FIG_5_11_CORNER_4

    from pysat.solvers import Solver

    for kind, c, grid in [("corner", 4, FIG_5_11_CORNER_4), ("wang", 3, facade.solve(
            PackingProblem("wang", 3), method="euler").tiling)]:
        enc = encode_packing(PackingProblem(kind, c), anchor_tile=int(grid[0, 0]), amo_tiles=False)
        cells = np.arange(grid.size)
        assumptions = enc.place_var(cells, grid.ravel()).tolist()
        with Solver(name="cadical153", bootstrap_with=enc.clauses.to_lists()) as s:
            assert s.solve(assumptions=assumptions)
        bad = grid.copy()
        bad[0, 1], bad[1, 1] = bad[1, 1], bad[0, 1]
        with Solver(name="cadical153", bootstrap_with=enc.clauses.to_lists()) as s:
            assert not s.solve(assumptions=enc.place_var(cells, bad.ravel()).tolist())


@pytest.mark.fast_cases(1)
@pytest.mark.parametrize("c", [3, 4])
def test_hybrid_wang_packings(c):
    """Random Eulerian N/S columns + SAT: valid, reproducible, and not an outer product."""
    s = facade.solve(PackingProblem("wang", c), method="hybrid", seed=1, time_limit=120, workers=1)
    assert s.status is Status.SAT and packing_violations(PackingProblem("wang", c), s.tiling) == []
    assert np.array_equal(s.tiling, facade.solve(PackingProblem("wang", c), method="hybrid", seed=1, workers=1).tiling)
    west = s.tiling % c
    north = s.tiling // c**3
    assert len({tuple(r) for r in west.tolist()}) > 1  # rows differ: not separable
    assert len({tuple(col) for col in north.T.tolist()}) > 1  # columns differ


def test_hybrid_refuses_corner_and_pins():
    with pytest.raises(MethodNotApplicable, match="Wang"):
        facade.solve(PackingProblem("corner", 3), method="hybrid")
    with pytest.raises(MethodNotApplicable, match="pinned"):
        facade.solve(PackingProblem("wang", 3, fixed=((0, 0, 1),)), method="hybrid")


def test_separate_horizontal_and_vertical_colours():
    """C_h != C_v (§2.7): a C_h^2 x C_v^2 torus of (C_h C_v)^2 tiles, by every applicable route."""
    p = PackingProblem("wang", 2, colors_v=3)
    for method in ("sat", "outer", "euler", "hybrid"):
        s = facade.solve(p, method=method, seed=1, time_limit=60)
        assert s.status is Status.SAT and s.tiling.shape == (4, 9)
        assert is_packing(PackingProblem("wang", 2, colors_v=3), s.tiling)
    with pytest.raises(MethodNotApplicable):
        facade.solve(p, method="known")
