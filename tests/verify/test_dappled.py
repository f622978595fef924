"""The independent dappled verifier: definitions from the paper, and it catches corruption."""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from tilesolve.model import Condition, DappledProblem, TileCount, parse_condition
from tilesolve.verify import dappled_violations, hamming_distance, is_dappled


def brute_violates(tiling, cond, cyclic):
    """Definition 1.1 / §3.2 read literally: a violation at (r, c) is a run of limit+1 cells
    in ``tau`` ending at (r, c), going left (H) or up (V), wrapping when cyclic."""
    rows, cols = tiling.shape
    bad = set()
    for r in range(rows):
        for c in range(cols):
            lim = cond.limit if cond.is_uniform else int(cond.limit[r, c]) or None
            if lim is None:
                continue
            ok = True
            for k in range(lim + 1):
                rr, cc = (r, c - k) if cond.axis == "H" else (r - k, c)
                if cyclic:
                    rr, cc = rr % rows, cc % cols
                elif rr < 0 or cc < 0:
                    ok = False
                    break
                if tiling[rr, cc] not in cond.tiles:
                    ok = False
                    break
            if ok:
                bad.add((r, c))
    return bad


conditions = st.builds(
    Condition,
    axis=st.sampled_from("HV"),
    tiles=st.sets(st.integers(0, 2), min_size=1, max_size=2).map(tuple),
    limit=st.one_of(st.none(), st.integers(1, 4)),
)


@pytest.mark.slow
@settings(max_examples=300, deadline=None)
@given(
    rows=st.integers(1, 6),
    cols=st.integers(1, 6),
    conds=st.lists(conditions, min_size=1, max_size=3),
    cyclic=st.booleans(),
    data=st.data(),
)
def test_matches_literal_definition(rows, cols, conds, cyclic, data):
    tiling = np.array(
        data.draw(st.lists(st.lists(st.integers(0, 2), min_size=cols, max_size=cols), min_size=rows, max_size=rows))
    )
    problem = DappledProblem(rows, cols, n_tiles=3, conditions=conds, cyclic=cyclic)
    got = {(v.row, v.col) for v in dappled_violations(problem, tiling) if v.kind == "condition"}
    want = set()
    for cond in conds:
        want |= brute_violates(tiling, cond, cyclic)
    assert got == want


def test_per_cell_limits_follow_the_cell_where_the_run_ends():
    limits = np.array([[0, 0, 2, 0]])  # only cell (0, 2) carries a limit
    p = DappledProblem(1, 4, conditions=[Condition("H", (0,), limits)])
    assert [(v.row, v.col) for v in dappled_violations(p, [[0, 0, 0, 0]])] == [(0, 2)]
    assert is_dappled(p, [[0, 0, 1, 0]])


def test_cyclic_full_line_violates_any_finite_limit():
    p = DappledProblem(1, 3, conditions=[parse_condition("H0=7")], cyclic=True)
    assert len(dappled_violations(p, [[0, 0, 0]])) == 3
    assert is_dappled(DappledProblem(1, 3, conditions=[parse_condition("H0=7")]), [[0, 0, 0]])


def test_draughtboard_example_1_5_is_dappled_for_strict_conditions():
    tiling = np.indices((6, 8)).sum(axis=0) % 2
    conds = [parse_condition(s) for s in ("H0=1", "H1=1", "V0=1", "V1=1")]
    assert is_dappled(DappledProblem(6, 8, conditions=conds, cyclic=True), tiling)


@settings(max_examples=100, deadline=None)
@given(seed=st.integers(0, 10**6), cyclic=st.booleans())
def test_catches_every_single_cell_corruption(seed, cyclic):
    """Flip one cell of a valid tiling so that it joins a run: the verifier must report it."""
    rng = np.random.default_rng(seed)
    rows, cols = rng.integers(2, 8, size=2) * 2
    tiling = np.indices((rows, cols)).sum(axis=0) % 2  # draughtboard: dappled for H0=1, V1=1
    p = DappledProblem(rows, cols, conditions=[parse_condition("H0=1"), parse_condition("V1=1")], cyclic=cyclic)
    assert is_dappled(p, tiling)
    r, c = int(rng.integers(rows)), int(rng.integers(cols))
    bad = tiling.copy()
    bad[r, c] = 1 - bad[r, c]
    found = {(v.row, v.col) for v in dappled_violations(p, bad)}
    assert found, "a flipped draughtboard cell always creates a run of two"
    neighbours = {(r, (c + 1) % cols), (r, c), ((r + 1) % rows, c)}
    assert found <= neighbours | {(r, c)}


def test_fixed_cells_counts_shape_and_range():
    fixed = np.full((2, 2), -1)
    fixed[0, 1] = 1
    p = DappledProblem(2, 2, fixed=fixed, counts=[TileCount(1, 3, 3)])
    kinds = [v.kind for v in dappled_violations(p, [[0, 0], [1, 1]])]
    assert kinds == ["fixed", "count"]
    assert is_dappled(p, [[1, 1], [1, 0]])
    assert [v.kind for v in dappled_violations(p, [[0, 0]])] == ["shape"]
    assert [v.kind for v in dappled_violations(p, [[0, 5], [1, 1]])] == ["tile"]


def test_hamming_distance():
    assert hamming_distance([[0, 1], [1, 1]], [[1, 1], [1, 0]]) == 2


@pytest.mark.parametrize("text", ["X0=2", "H0", "H=2", "H0=-1", "H0=0", "Hq=2"])
def test_condition_syntax_errors(text):
    from tilesolve.errors import InvalidProblem

    with pytest.raises(InvalidProblem):
        parse_condition(text)
