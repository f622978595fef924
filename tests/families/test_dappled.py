"""The dappled facade: method choice, independent verification, fallback, cross-checks."""

import itertools
import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import tilesolve.families.dappled as facade
from tilesolve.families.dappled import count, crosscheck, solve
from tilesolve.errors import MethodNotApplicable
from tilesolve.model import Condition, DappledProblem, Solution, Status, parse_condition
from tilesolve.verify import is_dappled


def brute_force_solvable(problem):
    for cells in itertools.product(range(problem.n_tiles), repeat=problem.size):
        if is_dappled(problem, np.array(cells).reshape(problem.shape)):
            return True
    return False


@st.composite
def small_problems(draw, max_cells=9):
    rows = draw(st.integers(1, 3))
    cols = draw(st.integers(1, max_cells // rows))
    n_tiles = draw(st.integers(2, 3))
    conds = draw(
        st.lists(
            st.builds(
                Condition,
                axis=st.sampled_from("HV"),
                tiles=st.sets(st.integers(0, n_tiles - 1), min_size=1, max_size=2).map(tuple),
                limit=st.integers(1, 3),
            ),
            min_size=1,
            max_size=4,
        )
    )
    fixed = None
    if draw(st.booleans()):
        fixed = np.array(draw(st.lists(st.integers(-1, n_tiles - 1), min_size=rows * cols, max_size=rows * cols)))
        fixed = fixed.reshape(rows, cols)
    return DappledProblem(rows, cols, n_tiles=n_tiles, conditions=conds, cyclic=draw(st.booleans()), fixed=fixed)


@pytest.mark.slow
@settings(max_examples=60, deadline=None)
@given(problem=small_problems(), seed=st.integers(0, 1000))
def test_auto_agrees_with_brute_force_and_every_route(problem, seed):
    truth = brute_force_solvable(problem)
    for method in ("auto", "sat", "cpsat"):
        sol = solve(problem, method=method, seed=seed)
        assert sol.status in (Status.SAT, Status.UNSAT)
        assert sol.status.has_tiling == truth, (method, sol)
        if truth:
            assert is_dappled(problem, sol.tiling)


@pytest.mark.parametrize("cyclic", [False, True])
def test_crosscheck_agrees_on_a_small_grid(cyclic):
    """The fast tier's crosscheck: one small grid, plain and cyclic (random grids: below, slow)."""
    problem = DappledProblem(4, 5, conditions=[Condition("H", (0,), 2), Condition("V", (1,), 3)], cyclic=cyclic)
    report = crosscheck(problem, seed=1)
    assert report.ok, "\n".join(report.lines)


@pytest.mark.slow
@settings(max_examples=25, deadline=None)
@given(
    rows=st.integers(2, 12),
    cols=st.integers(2, 12),
    p=st.integers(2, 4),
    q=st.integers(2, 4),
    cyclic=st.booleans(),
    seed=st.integers(0, 10**6),
)
def test_crosscheck_agrees_on_random_grids(rows, cols, p, q, cyclic, seed):
    problem = DappledProblem(rows, cols, conditions=[Condition("H", (0,), p), Condition("V", (1,), q)], cyclic=cyclic)
    report = crosscheck(problem, seed=seed)
    assert report.ok, "\n".join(report.lines)


def test_auto_picks_the_route_the_problem_needs():
    plain = DappledProblem.from_strings("20x10", ["H0=2", "V1=2"])
    assert solve(plain, seed=1).method == "constructive"
    fixed = np.full((10, 20), -1)
    fixed[0, 0] = 1
    assert solve(DappledProblem(10, 20, conditions=plain.conditions, fixed=fixed), seed=1).method == "sat"
    target = np.zeros((10, 20), dtype=int)
    closest = solve(DappledProblem(10, 20, conditions=plain.conditions, closest_to=target), seed=1)
    assert closest.method == "maxsat" and closest.status == Status.OPTIMAL
    # Each row of 20 zeros holds 6 disjoint windows of three, each needing a 1: at least 60.
    assert closest.objective >= 10 * (20 // 3)
    cp = solve(DappledProblem(10, 20, conditions=plain.conditions, closest_to=target), method="cpsat")
    assert cp.status == Status.OPTIMAL and cp.objective == closest.objective


def test_limit_one_routes_to_sat_with_a_note():
    problem = DappledProblem.from_strings("6x6", ["H0=1", "V1=2"])
    sol = solve(problem, seed=3)
    assert sol.method == "sat" and sol.status == Status.SAT
    assert any("Remark 2.2" in n for n in sol.notes)
    with pytest.raises(MethodNotApplicable, match="sat"):
        solve(problem, method="constructive")


def test_invalid_constructive_output_falls_back_to_sat(monkeypatch):
    def broken(problem, run):
        return Solution(Status.SAT, np.zeros(problem.shape, dtype=np.int8), method="constructive")

    monkeypatch.setitem(facade.SOLVERS, "constructive", broken)
    sol = solve(DappledProblem.from_strings("9x9", ["H0=2", "V1=2"]), seed=2)
    assert sol.method == "sat" and sol.status == Status.SAT
    assert any("failed verification" in n and "fell back" in n for n in sol.notes)


def test_example_6_2_is_unsat_with_a_checked_proof():
    fixed = np.array([[1, -1, -1, -1], [-1, 0, -1, -1], [-1, 0, 1, 1], [-1, 0, -1, -1]])
    conds = [parse_condition("H0=2"), parse_condition("V1=2")]
    sol = solve(DappledProblem(4, 4, conditions=conds, cyclic=True, fixed=fixed))
    assert sol.status == Status.UNSAT
    assert "checked by tilesolve.verify.drat" in sol.reason
    # Without the wrap-around the same partial tiling extends.
    assert solve(DappledProblem(4, 4, conditions=conds, fixed=fixed)).status == Status.SAT


@pytest.mark.parametrize("rows,cols,n_tiles", [(3, 3, 2), (4, 4, 2), (4, 5, 2), (3, 4, 3), (4, 4, 3)])
def test_proposition_1_3_lower_bounds(rows, cols, n_tiles):
    """Prop. 1.3: at least |T|^N dappled tilings, N = ceil(m/2) ceil(n/2), for *any* L
    (with p, q >= 2); and the sharper (|T|(|T|-1)^2 + |T|(|T|-1)(|T|-2)^2)^N' below it."""
    T = n_tiles
    conds = [parse_condition(f"{a}{t}=2") for a in "HV" for t in range(T)]
    exact = count(DappledProblem(rows, cols, n_tiles=T, conditions=conds)).value
    n = math.ceil(rows / 2) * math.ceil(cols / 2)
    n2 = (rows // 2) * (cols // 2)
    assert exact >= T**n
    assert exact >= (T * (T - 1) ** 2 + T * (T - 1) * (T - 2) ** 2) ** n2


def test_count_routes_agree_and_time_limit_gives_unknown():
    p = DappledProblem.from_strings("4x3", ["H0=2", "V1=2", "H{0,1}=3"])
    assert count(p, method="transfer").value == count(p, method="enumerate").value
    cyclic = DappledProblem.from_strings("10x10", ["H0=2", "V1=2"], cyclic=True)  # about 20 s
    res = count(cyclic, time_limit=0.2)
    assert res.status == Status.UNKNOWN and res.value is None


def test_progress_shows_route_and_time_on_a_terminal_only(monkeypatch, capsys):
    import io
    import sys

    from tilesolve.progress import Terminal

    class Tty(io.StringIO):
        def isatty(self):
            return True

    fake = Tty()
    monkeypatch.setattr(sys, "stderr", fake)
    with Terminal(every=0.01, delay=0).task("solving with 'sat'", unit=None):
        import time

        time.sleep(0.1)
    assert "solving with 'sat' [00:00]" in fake.getvalue()
    assert fake.getvalue().rstrip(" ").endswith("\r")  # the line is erased when the call returns
    monkeypatch.undo()
    solve(DappledProblem.from_strings("6x6", ["H0=1", "V1=2"]), progress=True)
    assert capsys.readouterr().err == ""  # not a terminal: nothing drawn
