"""Cross-checks of the procedural walls and stochastic tilings against the board CNF and the SAT
route on random windows (issue 10, item 5), and `tilesolve crosscheck wall | tiling`."""

from __future__ import annotations

import numpy as np
import pytest
from click.testing import CliRunner

from tilesolve.families import crosscheck_windows as cw
from tilesolve.cli.main import main_group
from tilesolve.constructive.walls import wall_window
from tilesolve.model.board import WangTileSet
from tilesolve.model.solution import CrosscheckReport, Status
from tilesolve.model.stochastic import StochasticProblem


def invoke(*args):
    return CliRunner().invoke(main_group, list(args), catch_exceptions=False)


@pytest.mark.parametrize("trial", range(4))
def test_random_wall_windows_agree_with_the_cnf_and_sat(trial):
    p = cw.random_wall_window(np.random.default_rng((11, trial)), max_side=6)
    rep = cw.crosscheck_wall_window(seed=trial, **p)
    assert rep.ok, rep.lines
    assert rep.verdicts == {"procedural": Status.SAT, "sat": Status.SAT}


def test_a_window_without_line_limits_agrees_too():
    rep = cw.crosscheck_wall_window((-(1 << 61), 1 << 40, 5, 4), colors=4, max_line=None, seed=2)
    assert rep.ok, rep.lines


@pytest.mark.parametrize("kind, variant, route", cw.TILING_ROUTES)
def test_every_tiling_route_agrees_with_the_grid_cnf_and_sat(kind, variant, route):
    problem = StochasticProblem(kind, 2, (-(1 << 33), 77, 4, 3), variant, "table" if route == "direct" else "long")
    rep = cw.crosscheck_tiling_window(problem, method=route, seed=3)
    assert rep.ok, rep.lines
    assert any("grid-tiling CNF" in line for line in rep.lines)


def test_the_cnf_check_catches_a_line_too_long_and_a_broken_tile():
    legs = wall_window(3, 3, 6, 6, colors=3, max_line=4, seed=1)
    n_clauses, bad = cw.cnf_falsified(cw.window_problem(legs, WangTileSet.brick(3), max_line=4), legs)
    assert n_clauses > 0 and bad == 0
    # the same window under a limit of 1: its lines of 2..4 bricks falsify line clauses
    assert cw.cnf_falsified(cw.window_problem(legs, WangTileSet.brick(3), max_line=1), legs)[1] > 0
    broken = legs.copy()
    broken[2, 2, 0] = (broken[2, 2, 0] + 1) % 3  # N leg no longer the S leg of the cell above
    problem = cw.window_problem(legs, WangTileSet.brick(3), max_line=4)
    assert cw.cnf_falsified(problem, broken)[1] > 0


def test_the_cnf_check_catches_a_tile_outside_the_set():
    problem = StochasticProblem("wang", 2, (0, 0, 3, 3), "compact")
    from tilesolve.families.stochastic import solve

    grid = solve(problem, method="scanline", seed=1).tiling
    legs, tiles = cw._wang_images(problem, grid)
    board_problem = cw.window_problem(legs, tiles)
    assert cw.cnf_falsified(board_problem, legs)[1] == 0
    outside = np.array([[t[0], t[1], t[2], t[3]] for t in np.ndindex(2, 2, 2, 2)
                        if not tiles.contains(np.array([t]))[0]])
    broken = legs.copy()
    broken[1, 1] = outside[0]
    assert cw.cnf_falsified(board_problem, broken)[1] > 0


def test_cli_sweeps_print_progress_and_agree():
    r = invoke("crosscheck", "wall", "--trials", "2", "--seed", "4", "--max-size", "4")
    assert r.exit_code == 0, r.output
    assert "trial 1/2 (seed 4, window" in r.output and "trial 2/2" in r.output
    assert "satisfies the board CNF" in r.output and "all 2 windows agree" in r.output
    t = invoke("crosscheck", "tiling", "--trials", "2", "--seed", "4", "--kind", "corner", "--max-size", "3")
    assert t.exit_code == 0, t.output
    assert "corner" in t.output and "grid-tiling CNF" in t.output


def test_cli_disagreement_exits_1(monkeypatch):
    def failing(*args, **kwargs):
        rep = CrosscheckReport()
        rep.add(False, "procedural window satisfies the board CNF (10 clauses, 1 falsified)")
        return rep

    monkeypatch.setattr(cw, "crosscheck_wall_window", failing)
    r = invoke("crosscheck", "wall", "--trials", "2", "--seed", "1")
    assert r.exit_code == 1
    assert "FAIL procedural window" in r.output and r.output.strip().endswith("crosscheck: FAILED (see the FAIL lines above)")


@pytest.mark.parametrize("args, msg", [
    (["wall", "--trials", "0"], "--trials"),
    (["wall", "--colors", "2"], "--colors"),
    (["tiling", "--kind", "hex"], "--kind"),
    (["tiling", "--max-size", "0"], "--max-size"),
])
def test_cli_bad_input(args, msg):
    r = invoke("crosscheck", *args)
    assert r.exit_code == 2 and msg in r.stderr
