"""The repeatable non-procedural wall NPD (004 App. A): cyclic dappling with the border
constraint, Algorithm 1 on top, verified on the torus by the board verifier."""

from __future__ import annotations

import numpy as np
import pytest

from tilesolve.constructive.npd import cyclic_limits, npd_legs, periodic_window
from tilesolve.constructive.walls import line_lengths
from tilesolve.errors import InvalidProblem, MethodNotApplicable
from tilesolve.family import solve
from tilesolve.model.board import Board, BoardProblem, WangTileSet
from tilesolve.model.solution import Status
from tilesolve.verify.board import board_violations
from tilesolve.families.walls import npd_problem, wall_problem


def period_legs(sol, rows: int, cols: int) -> np.ndarray:
    """``(rows, cols, 4)`` legs of a torus solution (cells in label order)."""
    lab = Board.torus(cols, rows).labels
    out = np.empty((rows, cols, 4), np.int64)
    out[lab[:, 0], lab[:, 1]] = sol.tiling
    return out


@pytest.mark.parametrize(("rows", "cols", "n", "nc", "seed"), [
    (4, 4, 1, 3, 0), (6, 10, 1, 3, 1), (5, 7, 2, 3, 2), (8, 8, 2, 4, 3), (3, 6, 3, 3, 4), (12, 16, 4, 3, 5),
    (9, 13, 5, 5, 6), (20, 20, 10, 3, 7), (11, 4, 10, 6, 8), (40, 30, 4, 3, 9),
])
def test_npd_tiles_the_torus(rows, cols, n, nc, seed):
    p = npd_problem(cols, rows, n, n_colors=nc)
    assert p.board.kind == "torus" and p.board.n_boundary == 0
    sol = solve(p, "npd", seed=seed)
    assert sol.status is Status.SAT and sol.method == "npd"
    assert board_violations(p, sol.tiling) == []
    # the lines stay within n across the seams: repeat the period 3x3 times and measure the runs
    big = periodic_window(period_legs(sol, rows, cols), -cols, -rows, 3 * cols, 3 * rows)
    hor, ver = line_lengths(big)
    assert hor.max() <= min(n, cols - 2) and ver.max() <= min(n, rows - 2)


def test_different_limits_across_and_down():
    p = npd_problem(14, 10, 2, max_v=6)
    sol = solve(p, "npd", seed=11)
    assert board_violations(p, sol.tiling) == []
    hor, ver = line_lengths(periodic_window(period_legs(sol, 10, 14), 0, 0, 28, 20))
    assert hor.max() <= 2 < ver.max() <= 6


def test_same_seed_same_wall():
    p = npd_problem(16, 12, 4)
    a, b, c = (solve(p, "npd", seed=s).tiling for s in (21, 21, 22))
    assert np.array_equal(a, b) and not np.array_equal(a, c)


def test_a_window_of_the_repeating_wall_is_cut_from_the_period():
    torus = solve(npd_problem(12, 8, 3), "npd", seed=5)
    q = wall_problem(30, 10, 3)
    win = solve(q, "npd", seed=5, options={"period": (12, 8), "origin": (-5, 3)})
    assert board_violations(q, win.tiling) == []
    expect = periodic_window(period_legs(torus, 8, 12), -5, 3, 30, 10)
    assert np.array_equal(win.tiling.reshape(10, 30, 4), expect)
    # the default period is the rectangle itself, which then tiles the plane
    r = solve(wall_problem(9, 6, 2), "npd", seed=1).tiling.reshape(6, 9, 4)
    assert (r[:, -1, 1] == r[:, 0, 3]).all() and (r[-1, :, 2] == r[0, :, 0]).all()  # E = W, S = N


@pytest.mark.parametrize(("rows", "cols", "n"), [(3, 3, 1), (3, 3, 2), (5, 5, 1), (4, 5, 1)])
def test_unsat_tori_agree_with_the_sat_route(rows, cols, n):
    p = npd_problem(cols, rows, n)
    assert solve(p, "npd", seed=0).status is Status.UNSAT
    assert solve(p, "sat", seed=0).status is Status.UNSAT


def test_sat_route_agrees_where_npd_builds_one():
    p = npd_problem(6, 4, 1)
    assert solve(p, "npd", seed=0).status is Status.SAT
    assert solve(p, "sat", seed=0).status is Status.SAT


def test_algorithm_1_on_random_dapplings():
    rng = np.random.default_rng(0)
    done = 0
    while done < 30:
        rows, cols = (int(v) for v in rng.integers(3, 9, size=2))
        d = rng.integers(0, 2, size=(rows, cols))
        if (d.sum(axis=1) < 2).any() or ((1 - d).sum(axis=0) < 2).any():
            continue
        nc = int(rng.integers(3, 6))
        t = npd_legs(d, nc, seed=done)
        assert np.array_equal(t[..., 3] == t[..., 1], d == 0)  # W_H exactly where the dappling says so
        p = BoardProblem(Board.torus(cols, rows), WangTileSet.brick(nc))
        assert board_violations(p, t.reshape(-1, 4)) == []
        done += 1


def test_cyclic_limits_fold_in_the_border_constraint():
    assert cyclic_limits(12, 16, 4, 4) == (4, 4)
    assert cyclic_limits(5, 4, 10, 10) == (2, 3)


@pytest.mark.parametrize(("make", "options", "error", "words"), [
    (lambda: npd_problem(8, 2, 2), {}, InvalidProblem, "at least 3x3"),
    (lambda: npd_problem(1, 8, 2), {}, InvalidProblem, "at least 3x3"),
    (lambda: wall_problem(5, 5, 2), {"period": (2, 6)}, InvalidProblem, "at least 3x3"),
    (lambda: npd_problem(6, 6, 2), {"period": (4, 4)}, InvalidProblem, "the period is the board"),
    (lambda: wall_problem(5, 5, 2), {"period": (4, "x")}, InvalidProblem, "period"),
    (lambda: wall_problem(5, 5, 2), {"origin": 3}, InvalidProblem, "origin"),
    (lambda: wall_problem(5, 5, 1), {"period": (9, 9)}, MethodNotApplicable, "repeats with period 9x9"),
    (lambda: BoardProblem(Board.cylinder(6, 6), WangTileSet.brick(3), max_h=2, max_v=2), {}, MethodNotApplicable,
     "torus or a rectangle"),
    (lambda: BoardProblem(Board.torus(6, 6), WangTileSet.brick(3), max_h=2), {}, MethodNotApplicable,
     "both line limits"),
    (lambda: npd_problem(6, 6, 0), {}, InvalidProblem, "max_h must be >= 1"),
    (lambda: npd_problem(6, 6, 2, n_colors=2), {}, InvalidProblem, "3"),
])
def test_bad_input_is_one_line(make, options, error, words):
    with pytest.raises(error) as exc:
        solve(make(), "npd", seed=0, options=options)
    assert words in str(exc.value) and "\n" not in str(exc.value)


def test_npd_legs_refuses_what_it_cannot_close():
    with pytest.raises(InvalidProblem, match="two vertical tiles"):
        npd_legs([[0, 1, 0], [1, 0, 1], [0, 1, 1]], 3)
    with pytest.raises(InvalidProblem, match="at least 3 colours"):
        npd_legs([[0, 1, 0, 1], [1, 0, 1, 0], [0, 1, 0, 1], [1, 0, 1, 0]], 2)
