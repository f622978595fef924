"""The CNF/WCNF/CP-SAT encodings of dappled problems against the independent verifier.

Reference: Kaji, Derouet-Jourdan, Ochiai, *Dappled tiling* (2016): Def. 1.1 (conditions),
§3.1 (per-cell limits), §3.2 (cyclic), §6 items 2, 3, 6, 7, 8.
"""

from __future__ import annotations

import itertools
import os

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from pysat.formula import CNF, WCNF
from pysat.solvers import Solver

from tilesolve.encodings import ClauseSet, encode_cnf, encode_wcnf
from tilesolve.encodings.dappled import PAIRWISE_AMO_MAX, naive_clauses
from tilesolve.io.dimacs import dimacs_text, write_dimacs
from tilesolve.model import Condition, DappledProblem, TileCount, parse_condition
from tilesolve.verify import is_dappled


# ---------------------------------------------------------------- strategies


@st.composite
def problems(draw, max_rows=4, max_cols=4, max_tiles=3, counts=True, per_cell=True):
    rows = draw(st.integers(1, max_rows))
    cols = draw(st.integers(1, max_cols))
    n_tiles = draw(st.integers(2, max_tiles))
    conds = []
    for _ in range(draw(st.integers(0, 3))):
        axis = draw(st.sampled_from("HV"))
        tiles = tuple(draw(st.sets(st.integers(0, n_tiles - 1), min_size=1, max_size=n_tiles)))
        if per_cell and draw(st.booleans()):
            limit = np.array(draw(st.lists(st.integers(0, 3), min_size=rows * cols, max_size=rows * cols)),
                             dtype=np.int32).reshape(rows, cols)
        else:
            limit = draw(st.integers(1, 5))
        conds.append(Condition(axis, tiles, limit))
    fixed = None
    if draw(st.booleans()):
        fixed = np.array(draw(st.lists(st.integers(-1, n_tiles - 1), min_size=rows * cols, max_size=rows * cols)),
                         dtype=np.int64).reshape(rows, cols)
        fixed[np.array(draw(st.lists(st.booleans(), min_size=rows * cols, max_size=rows * cols))).reshape(rows, cols)] = -1
    cnts = []
    if counts and draw(st.booleans()):
        t = draw(st.integers(0, n_tiles - 1))
        lo = draw(st.integers(0, rows * cols))
        hi = draw(st.one_of(st.none(), st.integers(lo, rows * cols)))
        cnts.append(TileCount(t, lo, hi))
    return DappledProblem(rows, cols, n_tiles=n_tiles, conditions=tuple(conds), cyclic=draw(st.booleans()),
                          fixed=fixed, counts=tuple(cnts))


def tiling_of(draw_list, p):
    return np.array(draw_list, dtype=np.int64).reshape(p.rows, p.cols)


# ---------------------------------------------------------------- semantics


@settings(max_examples=150)
@given(problems(counts=False), st.data())
def test_clauses_accept_exactly_the_dappled_tilings(p, data):
    """Without auxiliary variables, a tiling's assignment falsifies no clause iff it is dappled."""
    cells = data.draw(st.lists(st.integers(0, p.n_tiles - 1), min_size=p.size, max_size=p.size))
    t = tiling_of(cells, p)
    enc = encode_cnf(p)
    falsified = enc.hard.falsified(enc.target_values(t))
    assert (not falsified) == is_dappled(p, t)
    np.testing.assert_array_equal(enc.decode(enc.literals(t)), t)


@settings(max_examples=60)
@given(problems(max_rows=3, max_cols=3, counts=True), st.data())
def test_assumptions_check_a_tiling_against_the_encoding(p, data):
    """With counts (auxiliary variables), formula + tiling assumptions is SAT iff dappled."""
    cells = data.draw(st.lists(st.integers(0, p.n_tiles - 1), min_size=p.size, max_size=p.size))
    t = tiling_of(cells, p)
    enc = encode_cnf(p)
    clauses = enc.hard.to_lists()
    if any(len(c) == 0 for c in clauses):
        assert not is_dappled(p, t)
        return
    with Solver(name="cadical153", bootstrap_with=clauses) as s:
        assert s.solve(assumptions=enc.literals(t)) == is_dappled(p, t)


@settings(max_examples=80)
@given(
    st.integers(1, 6), st.integers(1, 6), st.booleans(),
    st.lists(st.tuples(st.sampled_from("HV"), st.sampled_from([(0,), (1,), (0, 1)]), st.integers(1, 7)), max_size=3),
)
def test_vectorised_clauses_equal_the_naive_loop(rows, cols, cyclic, spec):
    """numpy window generation gives the same clause set as the clause-by-clause reference."""
    p = DappledProblem(rows, cols, conditions=tuple(Condition(a, t, l) for a, t, l in spec), cyclic=cyclic)
    fast = {frozenset(c) for c in encode_cnf(p).hard}
    slow = {frozenset(c) for c in naive_clauses(p)}
    assert fast == slow


def test_cyclic_4x4_h0_v1_clause_count():
    # 16 horizontal and 16 vertical windows of three cells on the 4x4 torus (Example 6.2's L)
    enc = encode_cnf(DappledProblem.from_strings("4x4", ["H0=2", "V1=2"], cyclic=True))
    assert enc.n_vars == 16 and len(enc.hard) == 32
    assert all(len(c) == 3 for c in enc.hard)


def test_cyclic_window_longer_than_the_row_forbids_a_full_row():
    # H0=5 on a cyclic row of 3: violated only by a row of 0s (infinite run), as in the verifier
    p = DappledProblem.from_strings("3x1", ["H0=5"], cyclic=True)
    assert [sorted(c) for c in encode_cnf(p).hard] == [[1, 2, 3]]


def test_subset_equal_to_all_tiles_is_unsatisfiable():
    p = DappledProblem(1, 3, conditions=(Condition("H", (0, 1), 2),))
    assert [] in list(encode_cnf(p).hard)


def test_one_hot_with_many_tiles_uses_the_sequential_counter():
    n = PAIRWISE_AMO_MAX + 1
    p = DappledProblem(1, 2, n_tiles=n)
    enc = encode_cnf(p)
    assert enc.n_vars > enc.n_grid_vars  # auxiliary counter variables
    models = set()
    with Solver(name="cadical153", bootstrap_with=enc.hard.to_lists()) as s:
        for m in s.enum_models():
            models.add(tuple(enc.decode(m).ravel()))
            if len(models) > n * n:
                break
    assert len(models) == n * n


def test_counts_exact_and_bounds():
    p = DappledProblem(2, 3, counts=(TileCount(1, 2, 2),))
    enc = encode_cnf(p)
    for cells in itertools.product([0, 1], repeat=6):
        t = np.array(cells).reshape(2, 3)
        with Solver(name="cadical153", bootstrap_with=enc.hard.to_lists()) as s:
            assert s.solve(assumptions=enc.literals(t)) == (t.sum() == 2)


def test_wcnf_soft_literals_are_the_target():
    target = np.array([[0, 1, 1], [1, 0, 0]])
    p = DappledProblem.from_strings("3x2", ["H0=2"], closest_to=target)
    enc = encode_wcnf(p)
    assert enc.soft.tolist() == enc.literals(target)
    p3 = DappledProblem(2, 3, n_tiles=3, closest_to=np.array([[0, 1, 2], [2, 1, 0]]))
    enc3 = encode_wcnf(p3)
    assert len(enc3.soft) == 6 and (enc3.soft > 0).all()


def test_describe_var_names_cells():
    enc = encode_cnf(DappledProblem.from_strings("3x2", ["H0=2"]))
    assert enc.describe_var(5).startswith("x[1,1]")
    enc3 = encode_cnf(DappledProblem(2, 2, n_tiles=3, counts=(TileCount(2, 1, 2),)))
    assert enc3.describe_var(6).startswith("y[0,1,2]")
    assert "count" in enc3.describe_var(enc3.n_vars)


def test_clause_set_chunks_and_iteration_agree():
    cs = ClauseSet()
    cs.add_array(np.arange(1, 11).reshape(5, 2), "a")
    cs.add_lists([[1], [-2, 3, 4]], "b", grid_only=False)
    assert len(cs) == 7 and cs.max_var() == 10 and cs.n_literals == 14
    assert [c for ch in cs.chunks(2) for c in ch] == list(cs) == cs.to_lists()


# ---------------------------------------------------------------- DIMACS


def test_dimacs_cnf_round_trip(tmp_path):
    p = DappledProblem.from_strings("5x4", ["H0=2", "V{0,1}=3"], cyclic=True, counts=["1=6..9"])
    enc = encode_cnf(p)
    path = write_dimacs(enc, tmp_path / "p.cnf", comments=["made by a test"])
    text = path.read_text()
    assert "c problem: 5x4 grid" in text and "c made by a test" in text and "x[r,c]" in text
    cnf = CNF(from_file=str(path))
    assert cnf.clauses == enc.hard.to_lists()
    assert cnf.nv == enc.n_vars
    assert os.listdir(tmp_path) == ["p.cnf"]  # no temporary file left behind


@pytest.mark.parametrize("fmt", ["old", "new"])
def test_dimacs_wcnf_round_trip(tmp_path, fmt):
    target = np.array([[0, 0, 0], [1, 1, 0]])
    enc = encode_wcnf(DappledProblem.from_strings("3x2", ["H0=2", "V1=1"], closest_to=target))
    path = write_dimacs(enc, tmp_path / "p.wcnf", wcnf_format=fmt)
    w = WCNF(from_file=str(path))
    assert w.hard == enc.hard.to_lists()
    assert [c[0] for c in w.soft] == enc.soft.tolist() and set(w.wght) == {1}


def test_dimacs_write_is_atomic(tmp_path):
    target = tmp_path / "x.cnf"
    target.write_text("old contents\n")

    class Boom:
        hard = ClauseSet()

        def header(self):
            raise RuntimeError("interrupted while writing")

    with pytest.raises(RuntimeError):
        write_dimacs(Boom(), target)
    assert target.read_text() == "old contents\n"
    assert os.listdir(tmp_path) == ["x.cnf"]


def test_dimacs_text_of_plain_clauses_and_empty_clause():
    assert dimacs_text([[1, -2], []]) == "p cnf 2 2\n1 -2 0\n0\n"


def test_condition_strings_parse_into_the_same_encoding():
    a = encode_cnf(DappledProblem(3, 3, conditions=(parse_condition("H{0,1}=2"),), n_tiles=3))
    b = encode_cnf(DappledProblem(3, 3, conditions=(Condition("H", (1, 0), 2),), n_tiles=3))
    assert list(a.hard) == list(b.hard)
