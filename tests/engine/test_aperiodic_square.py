"""The square searches' steered runs: phased by a window of a known tiling (search ``"markov"``),
restricted to a smaller witness's short runs (search ``"grams"``)."""

from __future__ import annotations

import functools

import numpy as np
import pytest

from tilesolve.deadline import Deadline
from tilesolve.engine import aperiodic
from tilesolve.engine.aperiodic import _square_task, board_encoding, square_scan
from tilesolve.engine import aperiodic_square
from tilesolve.engine.aperiodic_square import GRAMS_METHOD, METHOD, gram_encoding, grams, window_phases
from tilesolve.errors import InvalidProblem
from tilesolve.families.aperiodic_square import square_window
from tilesolve.io.builtin_tilesets import load
from tilesolve.model.aperiodic import leg_colours
from tilesolve.model.board import Board, BoardProblem, WangTileSet
from tilesolve.model.run import RunOptions
from tilesolve.model.solution import Status
from tilesolve.verify.board import board_violations


def _holds(ws: WangTileSet, n: int, tiling) -> bool:
    grid = np.asarray(tiling)
    return grid.shape == (n, n) and not board_violations(BoardProblem(Board.rect(n, n), ws), leg_colours(ws, grid))


def test_the_phases_set_every_variable_and_read_back_as_the_window():
    ws, _ = load("jeandel-rao")
    enc = board_encoding(ws, "square 6x6")
    grid = square_window("jeandel-rao", 4, 6)
    lits = window_phases(enc, grid)
    assert sorted(map(abs, lits)) == list(range(1, enc.n_vars + 1))
    assert np.array_equal(enc.decode([v for v in lits if v > 0]), grid)


def test_the_phased_run_is_the_full_formula_and_says_so():
    ws, _ = load("jeandel-rao")
    n = aperiodic.DIRECT_SIDE + 4
    window = functools.partial(square_window, "jeandel-rao", 1)
    sol = _square_task(ws.tiles.tolist(), int(ws.n_colors), n, Deadline(None), None, None, 1, "markov", window,
                       seed=1)
    assert sol.status is Status.SAT and sol.method == METHOD and _holds(ws, n, sol.tiling)
    assert sol.stats["clauses"] == len(board_encoding(ws, f"square {n}x{n}").hard)


def test_the_markov_race_tiles_a_square_and_names_the_run_that_did():
    ws, _ = load("jeandel-rao")
    n = aperiodic.DIRECT_SIDE + 4
    window = functools.partial(square_window, "jeandel-rao", 2)
    certs, largest = square_scan(ws, n, RunOptions(seed=2, workers=2), search="markov", window=window)
    assert largest == n and certs[-1].method in ("sat", METHOD) and _holds(ws, n, certs[-1].tiling)


def test_the_markov_search_needs_a_window():
    with pytest.raises(InvalidProblem, match="needs a window"):
        square_scan(load("jeandel-rao")[0], 3, RunOptions(seed=1), search="markov")


def test_a_tiling_keeps_to_its_own_runs_and_a_grid_that_breaks_them_does_not():
    ws, _ = load("jeandel-rao")
    grid = square_window("jeandel-rao", 3, 12)
    enc = board_encoding(ws, "square 12x12")
    restricted = gram_encoding(enc, grams(grid))
    assert restricted.restricted and len(restricted.hard) > len(enc.hard)

    def broken(g) -> int:
        values = np.zeros(enc.n_vars + 1, dtype=bool)
        values[enc.literals(g)] = True
        return sum(len(rows) for _, rows in restricted.hard.falsified(values))

    assert broken(grid) == 0
    assert broken(grid[::-1, ::-1]) > 0  # the same tiles turned round: its runs are not the window's


@pytest.mark.slow
def test_the_gram_guided_run_tiles_a_square_from_a_smaller_witness(monkeypatch):
    ws, _ = load("jeandel-rao")
    monkeypatch.setattr(aperiodic_square, "GRAM_SIDE", 60)
    n = 64
    sol = _square_task(ws.tiles.tolist(), int(ws.n_colors), n, Deadline(None), None, None, 1, "grams", seed=1)
    assert sol.status is Status.SAT and sol.method == GRAMS_METHOD and _holds(ws, n, sol.tiling)
