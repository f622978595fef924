"""Windows of aperiodic tilings ("aperiodic-window", issue 20 §1) through the public API: every
window verified, each cross-checked clause by clause against the SAT encoding of its rectangle,
windows of one seed agreeing where they overlap, and the refusals."""

from __future__ import annotations

import numpy as np
import pytest

from tilesolve import family
from tilesolve.encodings.registry import encode
from tilesolve.errors import InvalidProblem, MethodNotApplicable
from tilesolve.families import aperiodic, aperiodic_window
from tilesolve.families.aperiodic_window import FAMILY, route_of, window_problem, window_violations
from tilesolve.model.aperiodic_window import AperiodicWindowProblem
from tilesolve.model.board import Board, BoardProblem
from tilesolve.model.solution import Status
from tilesolve.model.window import Window

#: Every built-in set with a constructive route, and its route.
SETS = {"jeandel-rao": "markov", "labbe-u19": "markov", "kari-14": "balanced", "kari-culik-13": "balanced"}
#: Small windows anywhere in the plane: (x0, y0, width, height).
WINDOWS = [(0, 0, 7, 5), (-13, 21, 5, 8), (1000, -77, 6, 6), (2**61 - 3, -(2**61), 5, 4)]


def clause_violations(problem: AperiodicWindowProblem, grid) -> list[list[int]]:
    """The clauses of the named encoding ``wang-tiles-cnf`` of the window's rectangle (free
    boundary) that the grid, read as the encoding's assignment (tile ``t`` at cell ``a``: the
    variable ``1 + a * n_tiles + t`` true, every other false), leaves unsatisfied."""
    rows, cols = problem.shape
    enc = encode("wang-tiles-cnf", BoardProblem(Board.rect(cols, rows), problem.tileset))
    value = np.zeros(enc.n_vars + 1, dtype=bool)
    value[enc.literals(grid)] = True
    return [c for c in enc.clauses if not any(value[v] if v > 0 else not value[-v] for v in c)]


def overlap(win_a: Window, grid_a, win_b: Window, grid_b) -> tuple[np.ndarray, np.ndarray]:
    """The tiles of two windows on the cells they share, in the same order (plane coordinates)."""
    x_lo, x_hi = max(win_a.x0, win_b.x0), min(win_a.x0 + win_a.width, win_b.x0 + win_b.width)
    y_lo, y_hi = max(win_a.y0, win_b.y0), min(win_a.y0 + win_a.height, win_b.y0 + win_b.height)
    assert x_lo < x_hi and y_lo < y_hi, "the windows do not overlap"

    def part(win, grid):
        top = win.y0 + win.height - 1  # row 0
        return np.asarray(grid)[top - (y_hi - 1): top - y_lo + 1, x_lo - win.x0: x_hi - win.x0]

    return part(win_a, grid_a), part(win_b, grid_b)


def test_registered_under_its_entry_point():
    p = window_problem("jeandel-rao", (0, 0, 2, 2))
    assert family.get("aperiodic-window") is FAMILY
    assert family.family_of(p) is FAMILY
    assert aperiodic.tiling is aperiodic_window.tiling


def test_every_constructive_set_has_its_route():
    assert {name: route_of(name) for name in SETS} == SETS


@pytest.mark.parametrize("name", SETS)
@pytest.mark.parametrize("window", WINDOWS, ids=str)
def test_windows_are_verified_and_satisfy_every_clause_of_the_sat_encoding(name, window):
    problem, s = aperiodic.tiling(name, window, seed=5)
    assert s.status is Status.SAT and s.method == SETS[name] and s.seed == 5
    assert s.window == problem.window == Window(*window)
    assert s.tiling.shape == (window[3], window[2])
    assert window_violations(problem, s.tiling) == []
    assert clause_violations(problem, s.tiling) == []


@pytest.mark.parametrize("name", SETS)
def test_the_clause_check_catches_a_wrong_tile(name):
    """The cross-check can fail: one tile changed breaks a clause (and the verifier sees it)."""
    problem, s = aperiodic.tiling(name, (2, 3, 6, 5), seed=1)
    bad = s.tiling.astype(np.int64)
    bad[2, 3] = (bad[2, 3] + 1) % len(problem.tileset)
    assert clause_violations(problem, bad)
    assert window_violations(problem, bad)


@pytest.mark.parametrize("name", SETS)
def test_windows_of_one_seed_agree_where_they_overlap(name):
    a_win, b_win, c_win = Window(-9, 4, 23, 17), Window(3, -5, 19, 14), Window(-40, 18, 45, 6)
    _, a = aperiodic.tiling(name, a_win, seed=9)
    _, b = aperiodic.tiling(name, b_win, seed=9)
    _, c = aperiodic.tiling(name, c_win, seed=9)
    for (wx, gx), (wy, gy) in [((a_win, a.tiling), (b_win, b.tiling)), ((a_win, a.tiling), (c_win, c.tiling))]:
        left, right = overlap(wx, gx, wy, gy)
        assert left.size and np.array_equal(left, right)


@pytest.mark.parametrize("name", SETS)
def test_the_same_seed_gives_the_same_window(name):
    _, a = aperiodic.tiling(name, "-4,-4,12x9", seed=3)
    _, b = aperiodic.tiling(name, (-4, -4, 12, 9), seed=3)
    assert np.array_equal(a.tiling, b.tiling)


@pytest.mark.parametrize("name", ["jeandel-rao", "labbe-u19"])
def test_another_seed_gives_another_window(name):
    _, a = aperiodic.tiling(name, "0,0,16x16", seed=3)
    _, b = aperiodic.tiling(name, "0,0,16x16", seed=4)
    assert not np.array_equal(a.tiling, b.tiling)


def test_a_seed_is_drawn_and_recorded_when_none_is_given():
    problem, s = aperiodic.tiling("kari-culik-13", "0,0,5x4")
    assert isinstance(s.seed, int)
    assert np.array_equal(aperiodic.tiling("kari-culik-13", "0,0,5x4", seed=s.seed)[1].tiling, s.tiling)


def test_a_route_takes_only_its_own_sets():
    problem = window_problem("kari-14", (0, 0, 3, 3))
    with pytest.raises(MethodNotApplicable, match="'balanced'"):
        aperiodic_window.solve(problem, method="markov", seed=1)


@pytest.mark.parametrize("name, message", [
    ("ammann-16", "has no constructive route; windows are built for jeandel-rao, kari-14, kari-culik-13, labbe-u19"),
    ("no-such-set", "no built-in tile set 'no-such-set'"),
])
def test_sets_without_a_route_are_refused(name, message):
    with pytest.raises(InvalidProblem, match=message):
        aperiodic.tiling(name, "0,0,4x4", seed=1)


@pytest.mark.parametrize("window, message", [
    ("0,0,20000x20000", r"a 20000x20000 window has 400,000,000 tiles and needs about 3.0 GiB"),
    ("0,0,0x3", "window size must be positive"),
    ("0,0;3x3", "cannot read region"),
    (Window(0, 0, 3, 3, y_up=False), "y growing upwards"),
])
def test_bad_windows_are_refused_before_any_work(window, message):
    with pytest.raises(InvalidProblem, match=message):
        aperiodic.tiling("jeandel-rao", window, seed=1)


def test_a_wrong_shape_is_a_violation_and_is_not_drawn(tmp_path):
    problem, s = aperiodic.tiling("jeandel-rao", "0,0,4x3", seed=1)
    (v,) = window_violations(problem, s.tiling[:2])
    assert v.kind == "shape"
    with pytest.raises(InvalidProblem, match="nothing drawn"):
        family.draw_solution(tmp_path / "x.png", problem, s.replace(tiling=s.tiling[:2]), fmt="png")
