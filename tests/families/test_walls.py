"""Brick walls without long lines (dappled paper §4) and the direct SAT route with limits."""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from tilesolve.families import board as wang
from tilesolve.constructive.brick import wall_from_dappled
from tilesolve.families.walls import brick_wall
from tilesolve.errors import InvalidProblem
from tilesolve.model.board import Board, BoardProblem, WangTileSet, random_boundary
from tilesolve.verify.board import board_violations, line_runs


@pytest.mark.slow
@settings(max_examples=40)
@given(st.integers(1, 12), st.integers(1, 12), st.integers(1, 4), st.integers(1, 4), st.integers(3, 5),
       st.integers(0, 10**6))
def test_walls_from_dappling_verify(rows, cols, p, q, k, seed):
    prob, sol = brick_wall(cols, rows, p, max_v=q, n_colors=k, seed=seed)
    assert sol.status.value == "sat"
    assert board_violations(prob, sol.tiling) == []
    t = sol.tiling
    h = t[:, 3] == t[:, 1]  # W = E
    assert line_runs(prob.board.nbr_cell, prob.board.nbr_leg, h, "H", p + 2).max(initial=0) <= p
    assert line_runs(prob.board.nbr_cell, prob.board.nbr_leg, ~h, "V", q + 2).max(initial=0) <= q


def test_wall_keeps_the_dappled_classes():
    g = np.array([[0, 0, 1], [1, 0, 1], [0, 1, 1]])
    t = wall_from_dappled(g, 3, seed=2)
    assert np.array_equal((t[:, 3] != t[:, 1]).reshape(3, 3).astype(int), g)  # W != E: vertical
    with pytest.raises(InvalidProblem):
        wall_from_dappled(g, 2)
    with pytest.raises(InvalidProblem):
        wall_from_dappled([[0, 2]], 3)


def test_long_line_is_caught_in_a_wall():
    prob, sol = brick_wall(8, 4, 2, seed=0)
    t = np.array(sol.tiling)
    # make the whole first row horizontal: W = E everywhere (joins stay consistent)
    row = np.arange(8)
    t[row, 3] = t[row, 1] = 0  # W = E (legs N, E, S, W)
    t[row, 0] = 1
    t[row, 2] = 2
    kinds = {v.kind for v in board_violations(prob, t)}
    assert "line" in kinds


@pytest.mark.parametrize("board", [Board.rect(7, 7), Board.with_holes(9, 9, 3, 3, seed=2), Board.mobius(6, 6)])
def test_direct_sat_with_limits_and_fixed_boundary(board):
    for seed in range(3):
        p = BoardProblem(board, WangTileSet.brick(3), random_boundary(board, 3, seed=seed), max_h=2, max_v=2)
        s = wang.solve(p, seed=seed)
        assert s.method == "sat" and s.status.value in ("sat", "unsat")
        if s.status.has_tiling:
            assert board_violations(p, s.tiling) == []


def test_line_limit_can_make_a_board_unsolvable():
    # a 1x3 strip: the middle cell's W and E are joined to cells, N/S fixed equal -> must be W_H
    b = Board.rect(3, 1)
    base = BoardProblem(b, WangTileSet.brick(3), [1, 1, 0, 0, 1, 0, 1, 0])
    assert wang.solve(base, method="sat").status.value == "sat"
    lim = BoardProblem(b, WangTileSet.brick(3), [1, 1, 0, 0, 1, 0, 1, 0], max_h=1, max_v=1)
    s = wang.solve(lim, method="sat")
    assert s.status.value in ("sat", "unsat")
    if s.status.value == "sat":
        assert board_violations(lim, s.tiling) == []
