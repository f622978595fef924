"""The board commands' shared options agree with the Python API (issue 18, "Defaults"): sizes
are width first in both, and the boundary is free by default in both, for every tile set, as
``--help`` says."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pytest

from tilesolve.io.board_json import read_board_solution
from tilesolve.model.board import Board, BoardProblem, WangTileSet, parse_board_spec
from tilesolve.model.solution import Status

from clitools import run

PERIODIC = Path(__file__).parents[2] / "tilesolve" / "data" / "tilesets" / "periodic-7-30.json"


def _same_board(a: Board, b: Board) -> bool:
    return a.kind == b.kind and a.grid_spec == b.grid_spec and all(
        np.array_equal(getattr(a, name), getattr(b, name)) for name in ("labels", "nbr_cell", "nbr_leg"))


@pytest.mark.parametrize("kind", ["rect", "torus", "cylinder", "mobius", "klein", "ring"])
def test_every_builder_takes_width_then_height_as_the_spec_does(kind):
    board = getattr(Board, kind)(5, 3)
    assert (board.grid_spec.cols, board.grid_spec.rows) == (5, 3)
    assert board.describe().split(" in ")[1].startswith("5x3")
    assert _same_board(board, parse_board_spec(f"{kind}:5x3"))
    for holes in (Board.random_holes(5, 3, 0.2, seed=1), Board.with_holes(5, 3, 1, 2, seed=1)):
        assert holes.mask_of().shape == (3, 5)


def test_the_cli_board_is_the_api_board(tmp_path):
    proc = run("brick", "solve", "--board", "mobius:40x12", "--method", "sat", "--seed", "1", "-o", "m.json",
               cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    problem, _ = read_board_solution(tmp_path / "m.json")
    assert _same_board(problem.board, Board.mobius(40, 12))
    assert json.loads((tmp_path / "m.json").read_text())["grid"] == {"rows": 12, "cols": 40, "wrap_rows": None,
                                                                     "wrap_cols": "twist"}


@pytest.mark.fast_cases(1)
@pytest.mark.parametrize("command", [["wang", "solve"], ["brick", "solve"], ["brick", "count"]])
def test_help_states_the_free_default(tmp_path, command):
    out = " ".join(run(*command, "--help", cwd=tmp_path).stdout.split())
    assert "--boundary free|random|FILE" in out and "[default: free]" in out
    assert "the default for every tile set, as in the Python API" in out


@pytest.mark.slow
def test_a_general_tile_set_is_solved_under_the_same_free_boundary_as_the_api(tmp_path):
    """periodic-7-30 tiles a 3x3 square: with a random boundary (the old default) it was unsat."""
    from tilesolve.families.board import solve
    from tilesolve.io.tileset_json import read_tileset

    shutil.copy(PERIODIC, tmp_path / "p.json")
    proc = run("wang", "solve", "--tiles", "p.json", "--board", "rect:3x3", "--seed", "1", "-o", "s.json",
               cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    problem, sol = read_board_solution(tmp_path / "s.json")
    api = BoardProblem(Board.rect(3, 3), read_tileset(PERIODIC)[0])
    assert np.array_equal(problem.boundary, api.boundary) and (api.boundary == -1).all()
    assert solve(api, seed=1).status is Status.SAT and sol.status is Status.SAT
    # the brick tile set too: free unless asked
    brick = run("brick", "solve", "--board", "rect:3x3", "-o", "b.json", cwd=tmp_path)
    assert brick.returncode == 0 and (read_board_solution(tmp_path / "b.json")[0].boundary == -1).all()
    assert np.array_equal(BoardProblem(Board.rect(3, 3), WangTileSet.brick(3)).boundary, np.full(12, -1))
    randomly = run("brick", "solve", "--board", "rect:3x3", "--boundary", "random", "--seed", "4", "-o", "r.json",
                   cwd=tmp_path)
    assert randomly.returncode == 0 and (read_board_solution(tmp_path / "r.json")[0].boundary >= 0).all()


def test_boundary_legs_are_numbered_n_e_s_w_as_tiles_are_printed(tmp_path):
    """One cell, its four boundary legs given N=0 E=1 S=0 W=2: the printed cell reads the same
    four colours, and the API, given the same list, finds the same tile (its legs N, E, S, W)."""
    from tilesolve.families.board import solve

    (tmp_path / "b.json").write_text(json.dumps([0, 1, 0, 2]))
    proc = run("brick", "solve", "--board", "rect:1x1", "--boundary", "b.json", cwd=tmp_path)
    assert proc.returncode == 0 and proc.stdout.split() == ["0102"], proc.stdout + proc.stderr
    sol = solve(BoardProblem(Board.rect(1, 1), WangTileSet.brick(3), [0, 1, 0, 2]), seed=1)
    assert sol.tiling.tolist() == [[0, 1, 0, 2]]
