"""Pictures of board tilings: bricks merged from edge positions, Wang triangles, seams."""

import numpy as np

from tilesolve.families.walls import brick_wall
from tilesolve.io.svg_board import board_drawing, brick_ids
from tilesolve.model.board import Board, BoardProblem, WangTileSet


def test_one_cell_has_four_brick_corners():
    p = BoardProblem(Board.rect(1, 1), WangTileSet.brick(3))
    ids = brick_ids(p, [[0, 1, 0, 2]])
    assert sorted(ids.ravel().tolist()) == [0, 1, 2, 3]


def test_corners_merge_across_joins():
    p = BoardProblem(Board.rect(2, 1), WangTileSet.brick(3))
    # two W_H cells sharing the horizontal line: TR~TL and BR~BL merge -> 6 bricks
    ids = brick_ids(p, [[1, 0, 1, 2], [1, 2, 1, 0]])
    assert np.unique(ids).size == 6
    assert ids[0, 1] == ids[1, 0] and ids[0, 3] == ids[1, 2]


def test_wall_svg_and_seam_arrows():
    p, s = brick_wall(10, 6, 2, seed=1)
    svg = board_drawing(p, s.tiling, title="wall").tostring()
    assert svg.startswith("<svg") and "<rect" in svg and "<line" in svg
    m = BoardProblem(Board.mobius(6, 4), WangTileSet.brick(3))
    from tilesolve.families import board as wang

    sol = wang.solve(m, seed=0)
    svg = board_drawing(m, sol.tiling).tostring()
    assert svg.count("<polygon") >= 2  # the two arrows of the twisted seam
    ts = WangTileSet([[a, b, a, b] for a in range(2) for b in range(2)], 2)
    q = BoardProblem(Board.rect(3, 2), ts)
    svg = board_drawing(q, wang.solve(q).tiling).tostring()
    assert svg.count("<polygon") == 4 * 6  # four triangles per cell
