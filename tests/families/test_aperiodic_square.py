"""The window that steers the aperiodic facade's square search ``"markov"``."""

from __future__ import annotations

import numpy as np
import pytest

from tilesolve.errors import InvalidProblem
from tilesolve.families.aperiodic_square import markov_set, steering
from tilesolve.io.builtin_tilesets import load
from tilesolve.model.aperiodic import leg_colours
from tilesolve.model.board import Board, BoardProblem, WangTileSet
from tilesolve.verify.board import board_violations


def test_only_the_sets_with_a_markov_partition_in_their_order_are_recognised():
    jr, _ = load("jeandel-rao")
    assert [markov_set(load(n)[0]) for n in ("jeandel-rao", "labbe-u19", "kari-14")] == \
        ["jeandel-rao", "labbe-u19", None]
    assert markov_set(WangTileSet(jr.tiles[::-1].copy(), jr.n_colors)) is None


@pytest.mark.parametrize("name", ["jeandel-rao", "labbe-u19"])
def test_the_window_is_a_tiling_of_the_square_and_the_seed_picks_it(name):
    ws, _ = load(name)
    grid = steering(ws, 5)(7)
    assert grid.shape == (7, 7)
    assert not board_violations(BoardProblem(Board.rect(7, 7), ws), leg_colours(ws, grid))
    assert np.array_equal(grid, steering(ws, 5)(7))


def test_a_set_without_a_partition_is_refused():
    with pytest.raises(InvalidProblem, match="Markov partition"):
        steering(load("kari-14")[0], 1)
