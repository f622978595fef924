"""The independent board verifier catches every single corruption (DESIGN.md)."""

import numpy as np
import pytest

from tilesolve.families import board as wang
from tilesolve.model.board import E, W, Board, BoardProblem, WangTileSet, random_boundary
from tilesolve.verify.board import MAX_LISTED, board_violations, is_valid_board_tiling, listing_violations


@pytest.fixture(scope="module")
def solved():
    b = Board.rect(7, 6)
    p = BoardProblem(b, WangTileSet.brick(3), random_boundary(b, 3, seed=5))
    s = wang.solve(p, method="sat", seed=1)
    assert s.status.value == "sat"
    return p, np.array(s.tiling)


def test_valid_tiling_passes(solved):
    p, t = solved
    assert board_violations(p, t) == [] and is_valid_board_tiling(p, t)


@pytest.mark.parametrize("cell", range(0, 42, 5))
@pytest.mark.parametrize("leg", range(4))
def test_single_leg_corruption_is_caught(solved, cell, leg):
    p, t = solved
    bad = t.copy()
    bad[cell, leg] = (bad[cell, leg] + 1) % 3
    v = board_violations(p, bad)
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
        v = board_violations(p, bad)
        assert not any(x.kind == "edge" for x in v)
        found |= any(x.kind in ("tile", "cross") for x in v)
    assert found


def test_shape_colour_and_generic_tiles():
    b = Board.rect(2, 1)
    p = BoardProblem(b, WangTileSet.brick(3))
    assert board_violations(p, np.zeros((3, 4), int))[0].kind == "shape"
    assert board_violations(p, np.full((2, 4), 7))[0].kind == "colour"
    q = BoardProblem(b, WangTileSet([[1, 0, 1, 0], [0, 0, 0, 0]], 2))  # N, E, S, W
    assert board_violations(q, [[1, 0, 1, 0], [1, 0, 1, 0]]) == []  # rows are tiles: legs N, E, S, W
    v = board_violations(q, [[1, 0, 1, 0], [1, 1, 1, 0]])
    assert [x.kind for x in v] == ["tile"] and (v[0].row, v[0].col) == (0, 1)


def test_line_limits_are_checked():
    b = Board.rect(4, 1)
    p = BoardProblem(b, WangTileSet.brick(3), max_h=2)
    # four horizontal tiles in a row: colours W=E=0 everywhere, N != S
    t = np.array([[1, 0, 2, 0]] * 4)
    v = board_violations(p, t)
    assert [x.kind for x in v] == ["line", "line"] and [x.col for x in v] == [2, 3]
    t2 = t.copy()
    t2[2] = [1, 1, 1, 0]
    t2[3] = [1, 1, 2, 1]
    assert t2[3, W] == t2[2, E] == 1
    assert not any(x.kind == "line" for x in board_violations(p, t2))
    # on a torus a full row is a run with no end
    tor = BoardProblem(Board.torus(3, 2), WangTileSet.brick(3), max_h=5)
    tt = np.tile([1, 0, 2, 0], (6, 1))
    assert any(x.kind == "line" for x in board_violations(tor, tt))


def _listing(board):
    return board.labels.copy(), board.edge_array().copy()


@pytest.mark.parametrize("board", [Board.rect(4, 3), Board.mobius(5, 4), Board.klein(3, 3),
                                   Board.ring(4, 4).restrict(np.arange(12) != 3)])
def test_a_board_listed_as_written_or_reordered_has_no_listing_violations(board):
    cells, edges = _listing(board)
    assert listing_violations(board, cells, edges) == []
    inner = edges[:, 2] >= 0
    turned = edges.copy()
    turned[inner] = edges[inner][:, [2, 3, 0, 1]]  # joins listed from their other end, in reverse order
    assert listing_violations(board, cells, turned[::-1]) == []


def test_every_listing_difference_is_a_violation_at_its_cell():
    board = Board.rect(4, 3)  # cell 5 is [1, 1]
    cells, edges = _listing(board)
    moved = cells.copy()
    moved[5] = [9, 9]
    v = listing_violations(board, moved, edges)
    assert [(x.kind, x.row, x.col) for x in v] == [("board", 1, 1)] and "[9, 9]" in v[0].message
    v = listing_violations(board, cells[:-1], edges)
    assert [str(x) for x in v] == ["the file lists 11 cells; the board has 12"]
    j = int(np.flatnonzero((edges[:, 0] == 5) & (edges[:, 1] == E))[0])  # [5, E, 6, W]
    for forged, expected in ((np.delete(edges, j, axis=0), "does not list the edge where leg E of cell [1, 1] meets "
                                                           "leg W of cell [1, 2]"),
                             (np.vstack([edges, edges[j]]), "is listed twice"),
                             (np.where(np.arange(len(edges))[:, None] == j, [5, E, 7, W], edges), "not an edge"),
                             (np.where(np.arange(len(edges))[:, None] == j, [5, 9, 6, W], edges), "does not have")):
        v = listing_violations(board, cells, forged)
        assert any(expected in x.message and (x.row, x.col) == (1, 1) for x in v), [str(x) for x in v]


def test_a_listing_that_differs_everywhere_is_reported_within_bounds():
    board = Board.rect(60, 60)
    cells, edges = _listing(board)
    v = listing_violations(board, cells[::-1], edges)
    assert len(v) == MAX_LISTED + 1 and v[-1].message == f"... and {3600 - MAX_LISTED} more cells listed at other places"


def test_tiles_of_sets_with_very_many_colours_are_matched_exactly():
    k = 1 << 20  # (N, E, S, W) keys would overflow int64: rows are matched another way
    ts = WangTileSet([[k - 1, 0, 5, 0], [8, 9, k - 1, 7]], k)  # N, E, S, W
    p = BoardProblem(Board.rect(1, 1), ts)
    assert board_violations(p, [[k - 1, 0, 5, 0]]) == []
    v = board_violations(p, [[k - 1, 0, 6, 0]])
    assert [x.kind for x in v] == ["tile"]


def test_a_line_limit_beyond_the_board_is_cheap_and_still_catches_endless_lines():
    tor = BoardProblem(Board.torus(3, 2), WangTileSet.brick(3), max_h=10**12)
    tt = np.tile([1, 0, 2, 0], (6, 1))  # every row one horizontal line round the torus
    assert sum(x.kind == "line" for x in board_violations(tor, tt)) == 6
    rect = BoardProblem(Board.rect(4, 1), WangTileSet.brick(3), max_h=10**12)
    assert board_violations(rect, np.array([[1, 0, 2, 0]] * 4)) == []
