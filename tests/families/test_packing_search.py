"""The packing search routes over restricted domains: lift, recursive, and the portfolio."""

import numpy as np
import pytest

from tilesolve.families import packing as facade
from tilesolve.constructive.packing import corner_packing_odd
from tilesolve.constructive.packing_known import known_packing
from tilesolve.encodings.packing import encode_packing, features_of_packing, full_domains, packing_features
from tilesolve.families import packing_search as search
from tilesolve.engine import portfolio
from tilesolve.errors import MethodNotApplicable
from tilesolve.model.packing import PackingProblem
from tilesolve.model.run import RunOptions
from tilesolve.deadline import Deadline
from tilesolve.model.solution import Status
from tilesolve.model.tiles import TileSet
from tilesolve.verify.packing import is_packing, packing_violations


@pytest.mark.parametrize("kind, c", [("corner", 2), ("corner", 3), ("wang", 2), ("wang", 3)])
def test_features_round_trip(kind, c):
    """features_of_packing reads the pegs/edges back; every cell's four features spell its tile."""
    method = "outer" if kind == "wang" or c % 2 else "sat"
    g = facade.solve(PackingProblem(kind, c), method=method, seed=2).tiling
    p = PackingProblem(kind, c)
    f = features_of_packing(p, g)
    cf, fcol = packing_features(p)
    assert (f >= 0).all() and (f < fcol).all()
    assert np.array_equal(TileSet(kind, c).index(*f[cf].T).reshape(g.shape), g)


@pytest.mark.slow
def test_restricted_domains_shrink_the_encoding():
    p = PackingProblem("corner", 4)
    full = encode_packing(p, anchor_tile=None)
    assert full.n_placements == 256 * 256 and not full.restricted
    base = features_of_packing(PackingProblem("corner", 2),
                               facade.solve(PackingProblem("corner", 2), method="sat", seed=1).tiling)
    d = search.lift_domains(p, base, 2)
    enc = encode_packing(p, anchor_tile=None, domains=d)
    assert enc.restricted and enc.n_placements == 256 * 2**4
    # An empty domain is an empty clause, not an error.
    d2 = full_domains(p)
    d2[0] = False
    assert [] in encode_packing(p, anchor_tile=None, domains=d2).clauses.to_lists()


@pytest.mark.fast_cases(1)
@pytest.mark.parametrize("kind, c", [("corner", 4), ("wang", 4), ("corner", 6), ("wang", 6)])
def test_lift_builds_verified_packings(kind, c):
    s = facade.solve(PackingProblem(kind, c), method="lift", seed=1, workers=1)
    assert s.status is Status.SAT and packing_violations(PackingProblem(kind, c), s.tiling) == []
    assert any("base packing" in n for n in s.notes)
    again = facade.solve(PackingProblem(kind, c), method="lift", seed=1, workers=1)
    assert np.array_equal(s.tiling, again.tiling)  # the same seed gives the same packing


def test_lift_without_seed_keeps_the_base_layer():
    """Unseeded (no random symmetry), colours mod m repeat the base packing's with period m**2."""
    p = PackingProblem("corner", 4)
    s = search.solve_lift(p, RunOptions(seed=None))  # no seed: no random symmetry
    assert s.status is Status.SAT and is_packing(PackingProblem("corner", 4), s.tiling)
    low = features_of_packing(p, s.tiling).reshape(16, 16) % 2
    assert np.array_equal(low, np.tile(low[:4, :4], (4, 4)))
    assert is_packing(PackingProblem("corner", 2), TileSet("corner", 2).index(*np.stack(TileSet("corner", 4).colors_of(s.tiling[:4, :4])) % 2))


@pytest.mark.slow
def test_corner_eight_colours_by_lift():
    """The headline search: 4,096 corner tiles on a 64x64 torus (2D de Bruijn torus over 8 symbols)."""
    s = facade.solve(PackingProblem("corner", 8), method="lift", seed=4, workers=1)
    assert s.status is Status.SAT and s.tiling.shape == (64, 64)
    assert packing_violations(PackingProblem("corner", 8), s.tiling) == []


@pytest.mark.slow
def test_lift_honours_pins_it_can_hold_and_never_says_unsat():
    p = PackingProblem("wang", 4, fixed=((3, 5, 200),))
    s = facade.solve(p, method="lift", seed=3, workers=1, time_limit=60)
    assert s.status is Status.SAT and s.tiling[3, 5] == 200
    # Two tiles at one cell: the restricted search cannot decide it; it ends unknown, not unsat.
    bad = PackingProblem("wang", 4, fixed=((0, 0, 1), (0, 0, 2)))
    s = search.solve_lift(bad, RunOptions(seed=1, deadline=Deadline(1.5)))
    assert s.status is Status.UNKNOWN and s.tiling is None


def test_lift_refuses_unequal_colour_counts():
    with pytest.raises(MethodNotApplicable, match="C_h = C_v"):
        facade.solve(PackingProblem("wang", 2, colors_v=4), method="lift")


@pytest.mark.parametrize("kind", ["corner", "wang"])
def test_published_packings_are_recursive(kind):
    """Figs. 5.11-5.12: the tiles over 3 colours fill the bottom-left 9x9 block, those over 2
    colours its bottom-left 4x4 block, and each block is a (toroidal) packing of its own."""
    _, g = known_packing(kind, 4)
    big = TileSet(kind, 4)
    for c, (r0, size) in ((3, (7, 9)), (2, (12, 4))):
        block = g[r0:r0 + size, :size]
        sub = TileSet(kind, c).index(*big.colors_of(block))
        assert is_packing(PackingProblem(kind, c), sub)
        pins = search.embedding_pins(sub, kind, c, 4)
        assert all(g[r, col] == t for r, col, t in pins)


@pytest.mark.slow
@pytest.mark.parametrize("kind", ["corner", "wang"])
def test_recursive_three_colours(kind):
    s = facade.solve(PackingProblem(kind, 3), method="recursive", seed=2, time_limit=120)
    assert s.status is Status.SAT and is_packing(PackingProblem(kind, 3), s.tiling)
    block = s.tiling[5:9, :4]
    assert is_packing(PackingProblem(kind, 2), TileSet(kind, 2).index(*TileSet(kind, 3).colors_of(block)))


def test_recursive_and_embedding_refusals():
    with pytest.raises(MethodNotApplicable, match="C must be >= 3"):
        facade.solve(PackingProblem("corner", 2), method="recursive")
    with pytest.raises(MethodNotApplicable, match="fewer colours"):
        search.embedding_pins(corner_packing_odd(3), "corner", 3, 3)
    with pytest.raises(MethodNotApplicable, match="does not fit"):
        search.embedding_pins(corner_packing_odd(3), "corner", 3, 4, at=(10, 0))


@pytest.mark.slow
def test_slow_first_run_escalates_to_a_portfolio(monkeypatch):
    """With QUICK_S = 0 a worker joins the in-process run at once; the seed that decided is
    named, and rerunning it alone (workers=1) gives the same packing."""
    monkeypatch.setattr(portfolio, "QUICK_S", 0.0)
    s = facade.solve(PackingProblem("wang", 3), method="sat", seed=10, workers=2)
    assert s.status is Status.SAT and is_packing(PackingProblem("wang", 3), s.tiling)
    assert any(n.startswith("portfolio: seed") for n in s.notes)
    rerun = facade.solve(PackingProblem("wang", 3), method="sat", seed=s.seed, workers=1)
    assert np.array_equal(rerun.tiling, s.tiling)


@pytest.mark.slow
def test_portfolio_on_a_dask_cluster():
    import distributed  # a test dependency (the "cluster" extra is part of the "test" extra)

    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True, dashboard_address=None) as lc:
        s = facade.solve(PackingProblem("corner", 4), method="lift", seed=1, cluster=lc.scheduler_address)
    assert s.status is Status.SAT and is_packing(PackingProblem("corner", 4), s.tiling)
    assert any("portfolio" in n for n in s.notes)


def test_lift_out_of_time_is_unknown_even_in_the_base_search():
    s = search.solve_lift(PackingProblem("corner", 8), RunOptions(seed=1, deadline=Deadline(0.01)))
    assert s.status is Status.UNKNOWN and s.tiling is None and "time limit" in s.reason


def test_lift_reports_each_level_and_its_attempts():
    from tilesolve.progress import Stream

    sent: list[dict] = []
    sol = search.solve_lift(PackingProblem("corner", 4), RunOptions(seed=1, progress=Stream(sent.append, every=0)))
    assert sol.status is Status.SAT
    assert {(m["label"], m["depth"]) for m in sent} == {("lift level 2: 4 colours", 0), ("lift level 1: 2 colours", 1)}
    assert {m["note"] for m in sent if m["depth"] == 0} >= {"attempt 1: drawing the restriction", "attempt 1: SAT search"}
    assert sent[-1]["label"] == "lift level 2: 4 colours" and sent[-1]["closed"]
