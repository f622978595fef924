"""Bands shared by tori: one band refuted and checked once, its trimmed proof renamed into each
torus that holds it, and re-checked by ``verify`` against the CNF re-derived from the torus."""

from __future__ import annotations

import dataclasses

import pytest

from tilesolve.deadline import NO_LIMIT
from tilesolve.engine.aperiodic import board_problem, decide, sweep
from tilesolve.engine.aperiodic_bands import band_refutation, covers, refute_band, trim
from tilesolve.engine.certificates import recheck_unsat
from tilesolve.engine.sat import solve_cnf
from tilesolve.io.builtin_tilesets import load
from tilesolve.model.board import WangTileSet
from tilesolve.model.run import RunOptions
from tilesolve.verify.drat import check_drat, drat_bytes


@pytest.fixture(scope="module")
def jr():
    return load("jeandel-rao")[0]


@pytest.fixture(scope="module")
def column_band(jr):
    band = refute_band(jr, "cols", 4, 6, solver="cadical153", seed=1, deadline=NO_LIMIT)
    assert band is not None and band.axis == "cols" and band.length == 4 and 1 <= band.width <= 6
    return band


def test_covers_names_the_tori_that_hold_a_band(column_band):
    w = column_band.width
    assert covers(column_band, f"torus 4x{w + 1}") and covers(column_band, f"torus 4x{w + 5} shear 3")
    assert not covers(column_band, f"torus 4x{w}") and not covers(column_band, f"torus 5x{w + 3}")
    assert not covers(column_band, f"square 4x{w + 3}")
    rows = dataclasses.replace(column_band, axis="rows")
    assert covers(rows, f"torus {w + 1}x4") and not covers(rows, f"torus {w + 1}x4 shear 1")


@pytest.mark.parametrize("q, shear", [(None, 0), (9, 0), (9, 2), (12, 3)])
def test_a_band_refutation_is_rechecked_against_each_torus_cnf(tmp_path, jr, column_band, q, shear):
    q = q or column_band.width + 1
    name = f"torus 4x{q}" + (f" shear {shear}" if shear else "")
    cert = band_refutation(jr, name, column_band, deadline=NO_LIMIT, proof_dirs=((str(tmp_path), True),))
    assert cert.status == "refuted" and cert.evidence["band"] == column_band.what()
    assert f"the proof refutes {column_band.what()}" in cert.evidence["reason"]
    check = recheck_unsat(board_problem(jr, name), cert.evidence, tmp_path)  # the whole torus's CNF, re-derived
    assert check.ok, check.lines


def test_a_row_band_keeps_its_variables(tmp_path, jr):
    band = refute_band(jr, "rows", 2, 8, solver="cadical153", seed=1, deadline=NO_LIMIT)
    assert band is not None and band.width == 5  # no strip of 5 rows repeats every 2 columns
    name = "torus 7x2"
    cert = band_refutation(jr, name, band, deadline=NO_LIMIT, proof_dirs=((str(tmp_path), True),))
    assert recheck_unsat(board_problem(jr, name), cert.evidence, tmp_path).ok


def test_a_band_that_is_not_the_torus_own_is_refused(jr, column_band):
    # q = width: the band is the whole torus, whose clauses also join its last column to its first
    assert band_refutation(jr, f"torus 4x{column_band.width}", column_band, deadline=NO_LIMIT) is None


def test_verify_refuses_a_band_proof_given_to_the_wrong_torus(tmp_path, jr, column_band):
    forged = dataclasses.replace(column_band, length=5)  # the 4-row band's proof, claimed for 5 rows
    name = f"torus 5x{column_band.width + 2}"
    cert = band_refutation(jr, name, forged, deadline=NO_LIMIT, proof_dirs=((str(tmp_path), True),))
    assert not recheck_unsat(board_problem(jr, name), cert.evidence, tmp_path).ok


def test_a_tiled_band_refutes_nothing():
    stairs = WangTileSet([[i, 0, (i + 1) % 3, 0] for i in range(3)], 3)  # tori p x q tiled when 3 divides p
    assert refute_band(stairs, "cols", 6, 4, solver="cadical153", seed=1, deadline=NO_LIMIT) is None
    band = refute_band(stairs, "cols", 4, 4, solver="cadical153", seed=1, deadline=NO_LIMIT)
    assert band is not None and band.width == 1


def test_a_wide_band_past_its_budget_is_not_used(jr):
    # widths above 0 get no time: the band stage gives up (the tori stay for the sweep), refutes nothing
    assert refute_band(jr, "cols", 4, 6, solver="cadical153", seed=1, deadline=NO_LIMIT, budget=(0, 0.0)) is None
    band = refute_band(jr, "cols", 4, 6, solver="cadical153", seed=1, deadline=NO_LIMIT, budget=(6, 0.0))
    assert band is not None and band.length == 4


def test_trim_keeps_the_used_lemmas_and_a_proof_that_checks():
    # x1..x3 pigeons in 2 holes (variables p(i, h) = 2 * i + h + 1): unsat, with a real proof
    f = [[2 * i + 1, 2 * i + 2] for i in range(3)]
    f += [[-(2 * i + h + 1), -(2 * j + h + 1)] for h in range(2) for i in range(3) for j in range(i + 1, 3)]
    r = solve_cnf(f, with_proof=True)
    chk = check_drat(f, r.proof)
    lits, sizes, dels = trim(f, r.proof, chk.used)
    again = check_drat(f, drat_bytes(lits, sizes, dels))
    assert again.verified and again.lemmas == int((dels == 0).sum()) <= chk.lemmas
    assert sizes[-1] == 0  # the empty clause ends it


def test_a_sweep_refutes_jeandel_rao_tori_through_shared_bands(tmp_path, jr):
    names = [f"torus {p}x{q}" for p in (3, 4) for q in range(1, 9)] + ["torus 4x8 shear 2"]
    certs, interrupted = sweep(jr, names, RunOptions(seed=1, workers=1), proof_dir=tmp_path)
    assert not interrupted and all(c.status == "refuted" for c in certs)
    banded = [c for c in certs if "band" in c.evidence]
    assert any("shear" in c.board for c in banded) and len({c.evidence["band"] for c in banded}) < len(banded)
    for c in certs:
        assert recheck_unsat(board_problem(jr, c.board), c.evidence, tmp_path).ok, c.board


def test_a_torus_whose_cylinder_is_refuted_is_solved_whole():
    stairs = WangTileSet([[i, 0, (i + 1) % 3, 0] for i in range(3)], 3)  # tori p x q tiled when 3 divides p
    run = RunOptions(seed=1)
    assert decide(stairs, "torus 3x100", run, bands=False).method == "sat cylinder"
    cert = decide(stairs, "torus 3x100", run, bands=False, cylinder=False)
    assert cert.status == "tiles" and cert.method == "sat"
