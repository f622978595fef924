"""The SAT route's tori: refutations through a band (checked against the whole torus) and
witnesses read off a tall cylinder."""

from __future__ import annotations

import numpy as np
import pytest

from tilesolve.engine import aperiodic
from tilesolve.engine.aperiodic import _stacked, board_problem, decide, square_scan
from tilesolve.engine.certificates import recheck_unsat, writing_proofs
from tilesolve.errors import InvalidProblem
from tilesolve.io.builtin_tilesets import load
from tilesolve.model.aperiodic import board_of, leg_colours
from tilesolve.model.board import BoardProblem, WangTileSet
from tilesolve.model.run import RunOptions
from tilesolve.verify.board import board_violations

#: N = i, S = i + 1 (mod 3), E = W = 0: columns that repeat every 3 rows, so the torus p x q is
#: tiled exactly when 3 divides p.
STAIRS = WangTileSet([[i, 0, (i + 1) % 3, 0] for i in range(3)], 3)


@pytest.fixture
def small_bands(monkeypatch):
    """Bands and cylinders for tori of any size (small ones are solved whole by default)."""
    monkeypatch.setattr(aperiodic, "BAND_MIN_CELLS", 1)


def test_a_jeandel_rao_torus_is_refuted_through_a_band_with_a_proof_of_the_whole_torus(tmp_path, small_bands):
    ws, _ = load("jeandel-rao")
    name = "torus 3x6"
    with writing_proofs(tmp_path):
        cert = decide(ws, name, RunOptions(seed=1))
    assert cert.status == "refuted" and "the proof refutes its first" in cert.evidence["reason"]
    check = recheck_unsat(board_problem(ws, name), cert.evidence, tmp_path)
    assert check.ok, check.lines


def test_a_torus_witness_is_read_off_a_cylinder(small_bands):
    cert = decide(STAIRS, "torus 6x2", RunOptions(seed=1))
    assert cert.status == "tiles" and cert.method == "sat cylinder" and cert.tiling.shape == (6, 2)
    assert not board_violations(BoardProblem(board_of("torus 6x2"), STAIRS), leg_colours(STAIRS, cert.tiling))


def test_a_torus_no_cylinder_block_fits_is_decided_whole(small_bands):
    cert = decide(STAIRS, "torus 4x2", RunOptions(seed=1))
    assert cert.status == "refuted"


def test_stacked_takes_a_block_whose_height_divides_the_torus():
    legs = STAIRS.tiles
    grid = np.array([[0], [1], [2], [0], [1], [2], [0]])  # bottom colours 1, 2, 0, 1, 2, 0, 1
    assert _stacked(grid, legs, 4) is None
    block = _stacked(grid, legs, 6)
    assert block.tolist() == [[1], [2], [0], [1], [2], [0]]
    assert not board_violations(BoardProblem(board_of("torus 6x1"), STAIRS), leg_colours(STAIRS, block))


def test_small_tori_are_solved_whole():
    ws, _ = load("jeandel-rao")
    cert = decide(ws, "torus 3x6", RunOptions(seed=1))
    assert cert.status == "refuted" and "the proof refutes" not in cert.evidence["reason"]


def _square_witness_holds(ws, n, cert) -> bool:
    return cert.status == "tiles" and cert.tiling.shape == (n, n) and not board_violations(
        BoardProblem(board_of(f"square {n}x{n}"), ws), leg_colours(ws, cert.tiling))


def test_the_phase_search_tiles_a_jeandel_rao_square_above_the_portfolio_side_in_this_process():
    ws, _ = load("jeandel-rao")
    n = aperiodic.DIRECT_SIDE + 4  # the portfolio's side: "phase" still solves it here, on one process
    certs, largest = square_scan(ws, n, RunOptions(seed=1, workers=2), search="phase")
    assert largest == n and [c.board for c in certs] == [f"square {n}x{n}"]
    assert _square_witness_holds(ws, n, certs[0])


@pytest.mark.slow
def test_the_race_tiles_a_jeandel_rao_square_on_two_processes():
    ws, _ = load("jeandel-rao")
    n = aperiodic.DIRECT_SIDE + 4
    certs, largest = square_scan(ws, n, RunOptions(seed=1, workers=2), search="race")
    assert largest == n and _square_witness_holds(ws, n, certs[-1])


def test_the_phase_search_gives_the_same_witness_for_a_seed_and_for_any_seed():
    ws, _ = load("jeandel-rao")
    runs = [square_scan(ws, 24, RunOptions(seed=seed), search="phase")[0][-1].tiling for seed in (1, 1, 7)]
    assert np.array_equal(runs[0], runs[1]) and np.array_equal(runs[0], runs[2])


@pytest.mark.slow
def test_the_phase_search_refutes_a_square_only_with_a_checked_proof(tmp_path):
    ws, _ = load("finite-jv7")
    certs, largest = square_scan(ws, 20, RunOptions(seed=1), proof_dir=tmp_path, search="phase")
    refuted = [c for c in certs if c.status == "refuted"]
    assert largest is not None and largest < 20 and refuted[-1].board == f"square {largest + 1}x{largest + 1}"
    for c in refuted:
        assert c.evidence["checker"] == "tilesolve.verify.drat" and c.evidence["encoding"]
        check = recheck_unsat(board_problem(ws, c.board), c.evidence, tmp_path)
        assert check.ok, check.lines
    assert _square_witness_holds(ws, largest, next(c for c in certs if c.board == f"square {largest}x{largest}"))


def test_an_unknown_square_search_is_refused():
    with pytest.raises(InvalidProblem, match="unknown square search 'strips'"):
        square_scan(STAIRS, 3, RunOptions(seed=1), search="strips")
