"""The board family's answers (tilesolve.families.board): a tiling's legs are N, E, S, W."""

import numpy as np
import pytest

from tilesolve.families import board as wang
from tilesolve.model.board import E, N, S, W, Board, BoardProblem, WangTileSet


@pytest.mark.parametrize("method", ["sat", "cpsat", "auto"])
def test_a_tiling_holds_each_cells_tile_as_written_n_e_s_w(method):
    """One cell, one tile N=2 E=0 S=1 W=0: the tiling's row is the tile, its north colour in
    column 0 (``Solution.tiling`` of the board family is in the public order)."""
    p = BoardProblem(Board.rect(1, 1), WangTileSet([[2, 0, 1, 0]], 3))
    sol = wang.solve(p, method=method, seed=1)
    assert sol.status.value == "sat" and np.asarray(sol.tiling).tolist() == [[2, 0, 1, 0]]
    assert sol.tiling[0, N] == 2 and sol.tiling[0, S] == 1


def test_the_linear_algorithm_colours_the_legs_n_e_s_w():
    """Boundary colours given by boundary-leg number (cell, then N, E, S, W) come back at those
    legs: a horizontal brick tile W = E = 1 with N = 0, S = 2."""
    p = BoardProblem(Board.rect(1, 1), WangTileSet.brick(3), [0, 1, 2, 1])
    sol = wang.solve(p, method="linear", seed=3)
    assert sol.status.value == "sat" and np.asarray(sol.tiling).tolist() == [[0, 1, 2, 1]]
    assert sol.tiling[0, W] == sol.tiling[0, E] == 1 and wang.FAMILY.verify(p, sol.tiling) == []
