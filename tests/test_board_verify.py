"""The independent board verifier catches every single corruption (DESIGN.md)."""

import numpy as np
import pytest

from tilesolve import board as wang
from tilesolve.model.board import E, W, Board, BoardProblem, WangTileSet, random_boundary
from tilesolve.verify.board import board_violations, is_valid_board_tiling


@pytest.fixture(scope="module")
def solved():
    b = Board.rect(6, 7)
    p = BoardProblem(b, WangTileSet.brick(3), random_boundary(b, 3, seed=5))
    s = wang.solve(p, method="sat", seed=1)
    assert s.status.value == "sat"
    return p, np.array(s.tiling)


def test_valid_tiling_passes(solved):
    p, t = solved
    assert board_violations(t, p) == [] and is_valid_board_tiling(t, p)


@pytest.mark.parametrize("cell", range(0, 42, 5))
@pytest.mark.parametrize("leg", range(4))
def test_single_leg_corruption_is_caught(solved, cell, leg):
    p, t = solved
    bad = t.copy()
    bad[cell, leg] = (bad[cell, leg] + 1) % 3
    v = board_violations(bad, p)
    assert v, "corruption not caught"
    near = {tuple(p.board.labels[cell])}
    if p.board.nbr_cell[cell, leg] >= 0:  # a broken join is reported at one of its two cells
        near.add(tuple(p.board.labels[p.board.nbr_cell[cell, leg]]))
    assert any((x.row, x.col) in near for x in v)
    kinds = {x.kind for x in v}
    assert kinds & {"edge", "boundary", "tile", "cross"}


def test_consistent_edge_recolouring_breaks_a_tile(solved):
    p, t = solved
    # change both sides of an inner edge: the joins agree but some tile leaves W_B
    b = p.board
    a = b.index_of()[(2, 3)]
    nb, nl = b.nbr_cell[a, E], b.nbr_leg[a, E]
    found = False
    for d in (1, 2):
        bad = t.copy()
        bad[a, E] = (bad[a, E] + d) % 3
        bad[nb, nl] = bad[a, E]
        v = board_violations(bad, p)
        assert not any(x.kind == "edge" for x in v)
        found |= any(x.kind in ("tile", "cross") for x in v)
    assert found


def test_shape_colour_and_generic_tiles():
    b = Board.rect(1, 2)
    p = BoardProblem(b, WangTileSet.brick(3))
    assert board_violations(np.zeros((3, 4), int), p)[0].kind == "shape"
    assert board_violations(np.full((2, 4), 7), p)[0].kind == "colour"
    q = BoardProblem(b, WangTileSet([[0, 1, 0, 1], [0, 0, 0, 0]], 2))
    assert board_violations([[0, 1, 0, 1], [0, 1, 0, 1]], q) == []
    v = board_violations([[0, 1, 0, 1], [0, 1, 1, 1]], q)
    assert [x.kind for x in v] == ["tile"] and (v[0].row, v[0].col) == (0, 1)


def test_line_limits_are_checked():
    b = Board.rect(1, 4)
    p = BoardProblem(b, WangTileSet.brick(3), max_h=2)
    # four horizontal tiles in a row: colours W=E=0 everywhere, N != S
    t = np.array([[0, 1, 0, 2]] * 4)
    v = board_violations(t, p)
    assert [x.kind for x in v] == ["line", "line"] and [x.col for x in v] == [2, 3]
    t2 = t.copy()
    t2[2] = [0, 1, 1, 1]
    t2[3, W] = 1
    t2[3] = [1, 1, 1, 2]
    assert not any(x.kind == "line" for x in board_violations(t2, p))
    # on a torus a full row is a run with no end
    tor = BoardProblem(Board.torus(2, 3), WangTileSet.brick(3), max_h=5)
    tt = np.tile([0, 1, 0, 2], (6, 1))
    assert any(x.kind == "line" for x in board_violations(tt, tor))
