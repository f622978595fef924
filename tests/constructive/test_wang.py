"""Theorem 7's strategy: tile outside a core leaves first, then solve the core."""

import itertools

import pytest

from tilesolve.families import board as wang
from tilesolve.constructive.wang import default_core
from tilesolve.errors import MethodNotApplicable
from tilesolve.model.board import Board, BoardProblem, WangTileSet, random_boundary
from tilesolve.verify.board import board_violations


@pytest.mark.parametrize("kind", ["rect", "cylinder", "mobius", "torus", "klein"])
def test_brick_boards_with_a_2x2_core(kind):
    b = getattr(Board, kind)(6, 5)
    for seed in range(4):
        p = BoardProblem(b, WangTileSet.brick(3), random_boundary(b, 3, seed=seed))
        s = wang.solve(p, method="theorem7", seed=seed)
        # a 2x2 block is a cycle with four corners: solvable for every boundary (Remark 11)
        assert s.status.value == "sat" and board_violations(p, s.tiling) == []
        assert s.stats["core_cells"] == 4


def test_generic_three_boundary_tileset():
    ts = WangTileSet([t for t in itertools.product(range(3), repeat=4) if sum(t) % 3 == 0], 3)
    assert ts.three_boundary()
    b = Board.rect(4, 4)
    for seed in range(6):
        p = BoardProblem(b, ts, random_boundary(b, 3, seed=seed))
        s = wang.solve(p, method="theorem7", seed=seed)
        sat = wang.solve(p, method="sat")
        if s.status.value == "sat":
            assert board_violations(p, s.tiling) == [] and sat.status.value == "sat"
        else:
            assert s.status.value == "unknown" and "Theorem 7" in s.reason  # never a false unsat


def test_core_choice_and_errors():
    p = BoardProblem(Board.with_holes(8, 8, 2, 3, seed=1), WangTileSet.brick(3))
    core = default_core(p)
    assert core.sum() >= 4
    with pytest.raises(MethodNotApplicable, match="three-boundary"):
        wang.solve(BoardProblem(Board.rect(2, 2), WangTileSet([[0, 0, 0, 0]], 2)), method="theorem7")
    s = wang.solve(BoardProblem(Board.rect(3, 3), WangTileSet.brick(3), [1] * 12), method="theorem7", seed=0)
    assert s.status.value == "sat" and s.method == "theorem7"
