"""Board names of aperiodicity certificates (:mod:`tilesolve.model.aperiodic`)."""

from __future__ import annotations

import pytest

from tilesolve.errors import InvalidProblem
from tilesolve.model.aperiodic import board_of, parse_board_name, rectangle_name
from tilesolve.model.board import Board


def test_a_rectangle_is_named_a_square_only_when_its_sides_are_equal():
    assert rectangle_name(8, 26) == "rectangle 8x26" and rectangle_name(7, 7) == "square 7x7"
    for rows, cols in ((8, 26), (26, 8), (7, 7), (1, 3)):
        name = rectangle_name(rows, cols)
        assert parse_board_name(name) == (rows, cols, -1)
        board = board_of(name)
        assert board.n_cells == rows * cols and board.describe() == Board.rect(cols, rows).describe()


def test_old_reports_rectangles_named_squares_still_read():
    assert parse_board_name("square 8x26") == (8, 26, -1)
    with pytest.raises(InvalidProblem, match="'rectangle RxC'"):
        parse_board_name("rectangle 8x26 shear 1")
