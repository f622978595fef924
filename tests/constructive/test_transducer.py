"""The transducer route (Jeandel-Rao §2-3) against its certificates and against the SAT route.

Every verdict is checked by code that shares nothing with the transducer: a torus witness by
the board verifier on ``Board.torus``, an empty ``T_k`` by the SAT route refuting the
``k x w`` rectangle of :func:`strip_width` with a checked DRAT proof (and tiling ``k x (w-1)``).
The test sets are meyerphi/tiling's ``tilesets/*.tiles`` (``n s w e`` per line), in
``tests/data/transducer/``; the expected verdicts are those their names and comments state.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from tilesolve.constructive.transducer import (
    build_level, compose, decide, minimize, periodic_cycle, simplify, strip_width, tile_transducer,
    torus_tiling, transducer_report, unfold,
)
from tilesolve.deadline import Deadline, TimeLimitReached
from tilesolve.engine.aperiodic import decide as sat_decide
from tilesolve.model.aperiodic import AperiodicProblem
from tilesolve.model.board import Board, BoardProblem, WangTileSet
from tilesolve.model.run import RunOptions
from tilesolve.verify.board import board_violations

DATA = Path(__file__).resolve().parents[1] / "data" / "transducer"


def load_tiles(name: str) -> WangTileSet:
    """A meyerphi/tiling ``.tiles`` file: ``north south west east`` per line, ``#`` comments."""
    rows = []
    for line in (DATA / f"{name}.tiles").read_text(encoding="utf-8").splitlines():
        if line.strip() and not line.startswith("#"):
            n, s, w, e = map(int, line.split())
            rows.append((n, e, s, w))
    a = np.array(rows)
    return WangTileSet(a, int(a.max()) + 1)


def check_torus(ts: WangTileSet, torus: np.ndarray) -> None:
    k, p = torus.shape
    assert board_violations(BoardProblem(Board.torus(p, k), ts), torus_tiling(ts, torus)) == []


def sat(ts: WangTileSet, board: str) -> str:
    return sat_decide(ts, board, RunOptions(seed=1)).status


def check_empty(ts: WangTileSet, k: int) -> int:
    """SAT agrees with an empty ``T_k``: the ``k x w`` rectangle is refuted (checked proof), the
    ``k x (w-1)`` one is tiled."""
    w = strip_width(ts, k)
    assert w is not None and w >= 1
    cert = sat_decide(ts, f"square {k}x{w}", RunOptions(seed=1))
    assert cert.status == "refuted"
    assert cert.evidence["drat_sha256"] and cert.evidence["checker"] == "tilesolve.verify.drat"
    if w > 1:
        assert sat(ts, f"square {k}x{w - 1}") == "tiles"
    return w


#: meyerphi/tiling test sets decided quickly: (file, verdict, k, torus shape or strip width).
#: "periodic_N_P": N tiles, a periodic tiling (the transducer's torus need not be P x P);
#: "finite_14": tiles a 14 x 14 square, not a 15 x 15 one; "hard": no stated answer.
DECIDED = [
    ("all_colors", "periodic", 1, (1, 20)),
    ("hard", "periodic", 2, (2, 2)),
    ("finite_14", "empty", 8, 26),
    ("periodic_8_20", "periodic", 7, (7, 42)),
    ("periodic_8_28", "periodic", 28, (28, 28)),
    ("periodic_8_28_2", "periodic", 28, (28, 28)),
    ("periodic_8_30", "periodic", 30, (30, 30)),
    ("periodic_10_15_2", "periodic", 15, (15, 15)),
    ("periodic_7_30", "periodic", 30, (30, 30)),
]


@pytest.mark.fast_cases(1)
@pytest.mark.parametrize("name, verdict, k, detail", DECIDED)
def test_meyerphi_sets_decided(name, verdict, k, detail):
    ts = load_tiles(name)
    v = decide(ts, max_k=40)
    assert (v.verdict, v.k) == (verdict, k)
    if verdict == "periodic":
        assert v.torus.shape == detail
        check_torus(ts, v.torus)
        assert sat(ts, f"torus {detail[0]}x{detail[1]}") == "tiles"
    else:
        assert check_empty(ts, k) == detail


#: The other sets: aperiodic ones (the literature's proofs) and periodic / finite ones whose
#: transducers grow too large for a quick test. Up to k = 4 none is empty or periodic.
UNDECIDED = ["aperiodic_11_4", "aperiodic_11_5", "aperiodic_11_5_2", "aperiodic_13", "aperiodic_14",
             "aperiodic_16", "aperiodic_19", "finite_212", "finite_256", "periodic_10_101", "periodic_10_127",
             "periodic_10_127_2", "periodic_10_15", "periodic_10_30", "periodic_10_30_2", "periodic_10_30_3",
             "periodic_10_35", "periodic_9_22", "periodic_9_26", "periodic_9_73", "periodic_9_73_2"]


@pytest.mark.parametrize("name", UNDECIDED)
def test_meyerphi_sets_undecided_at_small_k(name):
    ts = load_tiles(name)
    v = decide(ts, max_k=4)
    assert (v.verdict, v.k, v.reason) == ("undecided", 4, "k limit 4 reached")
    assert [s[0] for s in v.sizes] == [1, 2, 3, 4] and all(s[2] > 0 for s in v.sizes)


def test_every_test_set_is_listed():
    assert sorted(p.stem for p in DATA.glob("*.tiles")) == sorted([d[0] for d in DECIDED] + UNDECIDED)


def test_jeandel_rao_undecided_agrees_with_sat():
    """No torus of height <= 3 (the transducer) and SAT refutes the small ones, each with a
    checked proof; SAT tiles a 3 x 12 strip piece (T_3 is not empty)."""
    ts = load_tiles("aperiodic_11_4")
    v = decide(ts, max_k=3)
    assert v.verdict == "undecided"
    for p in (1, 2, 3):
        for q in (1, 2):
            assert sat(ts, f"torus {p}x{q}") == "refuted"
    assert sat(ts, "square 3x12") == "tiles"


@pytest.mark.slow
def test_periodic_9_73_needs_k_73():
    """The transducer finds the 73-row torus of periodic_9_73 (SAT tiles the same torus)."""
    ts = load_tiles("periodic_9_73")
    v = decide(ts, max_k=80)
    assert (v.verdict, v.k, v.torus.shape) == ("periodic", 73, (73, 73))
    check_torus(ts, v.torus)


def test_minimisation_keeps_verdicts_and_witnesses():
    for name in ("hard", "finite_14", "periodic_8_20", "periodic_8_28"):
        ts = load_tiles(name)
        a, b = decide(ts, max_k=30), decide(ts, max_k=30, minimise=False)
        assert (a.verdict, a.k) == (b.verdict, b.k)
        for v in (a, b):
            if v.torus is not None:
                check_torus(ts, v.torus)
        # minimisation never grows a level
        assert all(x[1] <= y[1] for x, y in zip(a.sizes, b.sizes))


def test_minimize_is_a_bisimulation_and_merges():
    ts = load_tiles("aperiodic_11_4")
    level = build_level(ts, build_level(ts, None))
    full, cls = level.full, level.cls
    assert np.array_equal(minimize(full), cls)
    assert cls.max() + 1 < full.n_states  # something was merged
    # every state has exactly its class's (label, class of target) set
    sets = {}
    for a, n, s, b in zip(full.src.tolist(), full.north.tolist(), full.south.tolist(), cls[full.dst].tolist()):
        sets.setdefault(a, set()).add((n, s, b))
    by_class = {}
    for a in range(full.n_states):
        by_class.setdefault(int(cls[a]), []).append(frozenset(sets.get(a, ())))
    assert all(len(set(v)) == 1 for v in by_class.values())


def test_compose_is_stacking():
    """A transition of T∘T is a column of two tiles matching vertically (S of the top = N of the bottom)."""
    ts = load_tiles("hard")
    t = tile_transducer(ts)
    c, i, j = compose(t, t)
    assert np.array_equal(t.south[i], t.north[j])
    assert np.array_equal(c.north, t.north[i]) and np.array_equal(c.south, t.south[j])
    pairs = {(int(a), int(b)) for a, b in zip(i, j)}
    want = {(a, b) for a in range(len(ts)) for b in range(len(ts)) if ts.tiles[a][2] == ts.tiles[b][0]}
    # merged transitions keep one column each: every kept pair stacks, every stack is represented
    assert pairs <= want
    assert len({(int(c.src[e]), int(c.dst[e]), int(c.north[e]), int(c.south[e])) for e in range(c.n_transitions)}) \
        == c.n_transitions


def test_simplify_keeps_cycles_only():
    ts = WangTileSet([[0, 0, 0, 0], [0, 1, 0, 0], [0, 1, 0, 1]], 2)  # 0 -> 1 leaves for good
    t = tile_transducer(ts)
    kept = simplify(t)
    assert sorted(ts.tiles[kept].tolist()) == sorted(ts.tiles[[e for e in range(3) if t.src[e] == t.dst[e]]].tolist())


def random_graph(rng, n: int, m: int) -> tuple[np.ndarray, np.ndarray]:
    return rng.integers(0, n, m).astype(np.int64), rng.integers(0, n, m).astype(np.int64)


def nx_components(src, dst, n: int) -> set[frozenset]:
    import networkx as nx

    g = nx.DiGraph()
    g.add_nodes_from(range(n))
    g.add_edges_from(zip(src.tolist(), dst.tolist()))
    return {frozenset(c) for c in nx.strongly_connected_components(g)}


@pytest.mark.parametrize("mode", ["plain", "compiled"])
def test_components_agree_with_networkx(monkeypatch, mode):
    """Tarjan's kernel, interpreted and compiled, splits random graphs as networkx does."""
    from tilesolve.constructive import _transducer_kernels as K
    from tilesolve.constructive.transducer import _components

    monkeypatch.setattr(K.KERNELS, "mode", mode)
    rng = np.random.default_rng(5)
    for n, m in [(1, 0), (1, 1), (2, 2), (30, 25), (30, 45), (200, 260), (500, 2000)]:
        src, dst = random_graph(rng, n, m)
        label = _components(src, dst, n)
        got = {frozenset(np.flatnonzero(label == c).tolist()) for c in np.unique(label)}
        assert got == nx_components(src, dst, n), (n, m)


def shortest_cycle_through_least_state(t) -> int | None:
    """The length of periodic_cycle's answer by networkx: over the strongly connected parts of
    the transitions that write what they read, the shortest cycle through each part's least state."""
    import networkx as nx

    same = np.flatnonzero(t.north == t.south)
    if (t.src[same] == t.dst[same]).any():
        return 1
    g = nx.DiGraph()
    g.add_edges_from(zip(t.src[same].tolist(), t.dst[same].tolist()))
    best = None
    for comp in nx.strongly_connected_components(g):
        if len(comp) > 1:
            start = min(comp)
            dist = nx.single_source_shortest_path_length(g.subgraph(comp), start)
            length = min(dist[u] for u in g.predecessors(start) if u in comp) + 1
            best = length if best is None else min(best, length)
    return best


def test_periodic_cycle_is_a_shortest_cycle_that_writes_what_it_reads():
    from tilesolve.constructive.transducer import Transducer

    rng = np.random.default_rng(9)
    for trial in range(300):
        n, m = int(rng.integers(1, 12)), int(rng.integers(0, 30))
        src, dst = random_graph(rng, n, m)
        north, south = rng.integers(0, 2, m).astype(np.int64), rng.integers(0, 2, m).astype(np.int64)
        t = Transducer(n, src, dst, north, south)
        cyc = periodic_cycle(t)
        want = shortest_cycle_through_least_state(t)
        if want is None:
            assert cyc is None, trial
            continue
        assert cyc.size == want, trial
        assert np.array_equal(t.north[cyc], t.south[cyc]), trial
        assert np.array_equal(t.dst[cyc], np.roll(t.src[cyc], -1)), trial


class RecordingDeadline(Deadline):
    """A deadline that records what the search was doing at each look, and passes at look
    number ``passes_at`` (never when ``None``): no clock, so the tests do not depend on speed."""

    def __init__(self, passes_at: int | None = None):
        super().__init__(None)
        self.doing: list[str] = []
        self.passes_at = passes_at

    def check(self, doing: str) -> None:
        self.doing.append(doing)
        if self.passes_at is not None and len(self.doing) >= self.passes_at:
            raise TimeLimitReached(f"time limit reached while {doing}")


def test_every_step_of_a_level_looks_at_the_deadline():
    """Composing, simplifying and every round of minimising look at the deadline (so no step runs
    long unwatched), and wherever it passes the search ends undecided, never with an error."""
    ts = load_tiles("aperiodic_11_4")
    levels = [build_level(ts, None)]
    for _ in range(3):
        levels.append(build_level(ts, levels[-1]))
    d = RecordingDeadline()
    build_level(ts, levels[-1], deadline=d)
    kinds = [w.split()[0] for w in d.doing]
    assert {"composing", "simplifying", "minimising"} <= set(kinds)
    assert kinds.count("composing") >= 3 and kinds.count("simplifying") >= 2
    rounds = kinds.count("minimising") - 2  # the look before minimising, and the one before the exact check
    assert rounds >= 2  # refinement took rounds, each watched
    d = RecordingDeadline()
    assert decide(ts, max_k=5, deadline=d).verdict == "undecided"
    total = len(d.doing)
    for passes_at in range(1, total + 1):
        v = decide(ts, max_k=5, deadline=RecordingDeadline(passes_at))
        assert v.verdict == "undecided" and "time limit reached while" in v.reason, passes_at
        assert v.k == len(v.sizes) < 5


def test_strip_width_looks_at_the_deadline():
    ts = load_tiles("finite_14")
    with pytest.raises(TimeLimitReached):
        strip_width(ts, 8, deadline=Deadline(0))
    d = RecordingDeadline()
    assert strip_width(ts, 8, deadline=d) == 26
    assert sum(w.startswith("composing") for w in d.doing) >= 7


def test_periodic_cycle_and_unfold_by_hand():
    # 2 rows: A (N0 S1) on top of B (N1 S0); horizontally A-A and B-B (colour 0), a 2 x 1 torus
    ts = WangTileSet([[0, 0, 1, 0], [1, 0, 0, 0]], 2)
    l1 = build_level(ts, None)
    assert periodic_cycle(l1.quotient) is None
    l2 = build_level(ts, l1)
    cyc = periodic_cycle(l2.quotient)
    torus = unfold([l1, l2], cyc)
    assert torus.shape == (2, 1)
    check_torus(ts, torus)


def test_deadline_and_limits_give_undecided():
    ts = load_tiles("aperiodic_11_4")
    v = decide(ts, max_k=50, deadline=Deadline(0))
    assert (v.verdict, v.k) == ("undecided", 0) and "time limit" in v.reason
    v = decide(ts, max_k=50, max_transitions=200)
    assert v.verdict == "undecided" and "more than the limit of 200" in v.reason
    with pytest.raises(Exception, match="at least 1"):
        decide(ts, max_k=0)


def test_report_with_sat_certificates():
    refute = lambda name, run: sat_decide(ts, name, run)  # noqa: E731
    ts = load_tiles("finite_14")
    verdict, rep = transducer_report(AperiodicProblem(ts, 0, 10), RunOptions(seed=1, options={"max_k": 10}),
                                     refute=refute)
    (cert,) = rep.squares
    assert verdict == "empty" and cert.board == "rectangle 8x26" and cert.status == "refuted"
    assert cert.method == "sat+transducer" and cert.evidence["strip_width"] == 26
    assert cert.evidence["drat_sha256"] and "tiles no plane" in rep.conclusion
    ts = load_tiles("hard")
    verdict, rep = transducer_report(AperiodicProblem(ts, 0, 4), RunOptions(seed=1), refute=refute)
    (cert,) = rep.periods
    assert verdict == "periodic" and cert.board == "torus 2x2" and cert.status == "tiles"
    check_torus(ts, cert.tiling)
    verdict, rep = transducer_report(AperiodicProblem(load_tiles("aperiodic_11_4"), 0, 2), RunOptions(seed=1),
                                     refute=refute)
    assert verdict == "undecided" and rep.squares == rep.periods == () and "k = 2" in rep.conclusion


@pytest.mark.slow
def test_builtin_sets_agree_with_their_literature_verdicts_and_sat():
    """Up to k = 2: aperiodic sets undecided; periodic and finite sets never contradict their
    verdict (a torus only for a periodic set, emptiness only for a finite one). SAT agrees: an
    undecided T_2 means strips of height 2 (SAT tiles a 2 x 5 rectangle) and no torus of height
    at most 2 (SAT refutes the 2 x 2 torus, checked proof)."""
    from tilesolve.io.builtin_tilesets import load, names

    for name in names():
        ts, info = load(name)
        v = decide(ts, max_k=2)
        if info["verdict"] == "aperiodic":
            assert v.verdict == "undecided", name
        if v.verdict == "periodic":
            assert info["verdict"] == "periodic", name
            check_torus(ts, v.torus)
        elif v.verdict == "empty":
            assert info["verdict"] == "finite", name
            check_empty(ts, v.k)
        else:
            assert (sat(ts, "square 2x5"), sat(ts, "torus 2x2")) == ("tiles", "refuted"), name


@st.composite
def small_tile_sets(draw, max_colours=3, max_tiles=6):
    colours = draw(st.integers(1, max_colours))
    tiles = draw(st.lists(st.tuples(*[st.integers(0, colours - 1)] * 4), min_size=1, max_size=max_tiles,
                          unique=True))
    return WangTileSet(tiles, colours)


@settings(max_examples=12)
@given(small_tile_sets())
def test_random_sets_agree_with_sat(ts):
    """Periodic => SAT tiles that torus; empty at k => SAT refutes k x w (checked proof) and
    tiles k x (w-1); undecided up to 3 => SAT tiles a 3 x 4 rectangle and no torus of height
    at most 3 and width at most 2."""
    v = decide(ts, max_k=3)
    if v.verdict == "periodic":
        check_torus(ts, v.torus)
        k, p = v.torus.shape
        assert sat(ts, f"torus {k}x{p}") == "tiles"
        for j in range(1, k):  # no torus of a smaller height: T_j had no periodic cycle
            assert sat(ts, f"torus {j}x{p}") == "refuted"
    elif v.verdict == "empty":
        check_empty(ts, v.k)
    else:
        assert sat(ts, "square 3x4") == "tiles"
        for p in (1, 2, 3):
            for q in (1, 2):
                assert sat(ts, f"torus {p}x{q}") == "refuted"


@pytest.mark.slow
def test_reports_pass_the_family_verifier():
    from tilesolve.verify.aperiodic import aperiodic_violations

    for name, max_period in (("finite_14", 10), ("hard", 3), ("aperiodic_11_4", 2)):
        ts = load_tiles(name)
        problem = AperiodicProblem(ts, 0, max_period)
        _, rep = transducer_report(problem, RunOptions(seed=1), refute=lambda b, run: sat_decide(ts, b, run))
        assert aperiodic_violations(problem, rep) == []
    # a corrupted witness is caught
    ts = load_tiles("hard")
    problem = AperiodicProblem(ts, 0, 3)
    _, rep = transducer_report(problem, RunOptions(seed=1), refute=lambda b, run: sat_decide(ts, b, run))
    bad = rep.periods[0].tiling.copy()
    bad[0, 0] = (bad[0, 0] + 1) % len(ts)
    from dataclasses import replace

    rep = replace(rep, periods=(replace(rep.periods[0], tiling=bad),))
    assert aperiodic_violations(problem, rep) != []


@settings(max_examples=40)
@given(small_tile_sets(max_colours=4, max_tiles=10))
def test_random_sets_minimisation_changes_nothing_but_size(ts):
    a, b = decide(ts, max_k=6), decide(ts, max_k=6, minimise=False)
    assert (a.verdict, a.k) == (b.verdict, b.k)
    assert all(x[1] <= y[1] and x[2] <= y[2] for x, y in zip(a.sizes, b.sizes))
    for v in (a, b):
        if v.torus is not None:
            check_torus(ts, v.torus)


def test_report_without_a_rectangle_is_undecided(monkeypatch):
    import tilesolve.constructive.transducer as tr

    def too_large(*args, **kwargs):
        raise tr.InvalidProblem("a composition would have 9 candidate transitions, more than the limit of 1")

    monkeypatch.setattr(tr, "strip_width", too_large)
    ts = load_tiles("finite_14")
    verdict, rep = transducer_report(AperiodicProblem(ts, 0, 10), RunOptions(seed=1),
                                     refute=lambda b, run: sat_decide(ts, b, run))
    assert verdict == "undecided" and rep.squares == () and "could not be computed" in rep.conclusion

    def too_late(*args, **kwargs):
        raise TimeLimitReached("time limit of 1 s reached while composing (9 candidate transitions)")

    monkeypatch.setattr(tr, "strip_width", too_late)
    verdict, rep = transducer_report(AperiodicProblem(ts, 0, 10), RunOptions(seed=1),
                                     refute=lambda b, run: sat_decide(ts, b, run))
    assert verdict == "undecided" and rep.squares == () and "time limit of 1 s reached" in rep.conclusion
    assert rep.status.value == "unknown"


@pytest.mark.slow
def test_family_route_end_to_end():
    """``tilesolve.families.aperiodic.solve(..., method="transducer")``: the pipeline verifies the report."""
    from tilesolve.families.aperiodic import solve
    from tilesolve.io.builtin_tilesets import load

    ts, info = load("finite-jv7")
    s = solve(AperiodicProblem(ts, 0, 10, name="finite-jv7", info=info), method="transducer", seed=1)
    (cert,) = s.report.squares
    assert (s.status.value, s.method, cert.board, cert.status) == ("sat", "transducer", "rectangle 8x26", "refuted")
    ts, info = load("periodic-8-28")
    s = solve(AperiodicProblem(ts, 0, 30, name="periodic-8-28", info=info), method="transducer", seed=1)
    (cert,) = s.report.periods
    assert (cert.board, cert.status) == ("torus 28x28", "tiles")
    check_torus(ts, cert.tiling)
