"""Board specs with masks (tilesolve.io.mask.read_board_spec): a file, or the rows inline."""

import numpy as np
import pytest

from tilesolve.errors import InvalidProblem
from tilesolve.io.mask import read_board_spec


def test_an_inline_mask_is_the_text_with_slashes_between_rows():
    board = read_board_spec("mask:####/#..#/####")
    assert board.mask_of().tolist() == [[True] * 4, [True, False, False, True], [True] * 4]
    with pytest.raises(InvalidProblem, match="no '#' cells"):
        read_board_spec("mask:..../....")


def test_a_file_of_that_name_is_read_first(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "##").write_text("#.\n##\n")
    assert np.array_equal(read_board_spec("mask:##").mask_of(), [[True, False], [True, True]])
    with pytest.raises(InvalidProblem, match="cannot read mask"):
        read_board_spec("mask:#x#")  # not only '#', '.' and '/': a file name
