"""Tile indices in every output refer to the user's input order (issue 18, "Tile order").

``periodic-7-30.json`` lists its tiles in an order tilesolve used to sort away (by the board
legs W, N, E, S): the reports, board files and witnesses then spoke of another numbering than
the file's. Through the console script, the outputs list the tiles as the input does, and a
witness read with the *input's* tiles is a valid tiling.
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from clitools import run

TILES = Path(__file__).parents[1] / "tilesolve" / "data" / "tilesets" / "periodic-7-30.json"


@pytest.fixture()
def tiles(tmp_path):
    doc = json.loads(TILES.read_text())
    legs_order = sorted(range(len(doc["tiles"])), key=lambda i: [doc["tiles"][i][k] for k in (3, 0, 1, 2)])
    assert legs_order != list(range(len(doc["tiles"])))  # the order a sort by W, N, E, S would change
    (tmp_path / "p.json").write_text(json.dumps(doc))
    return doc["tiles"]


def _matches(tiles, grid):
    """Every pair of neighbours in ``grid`` (tile indices, row 0 on top) meets colour to colour,
    read with ``tiles`` (N, E, S, W)."""
    rows, cols = len(grid), len(grid[0])
    east = all(tiles[grid[r][c]][1] == tiles[grid[r][c + 1]][3] for r in range(rows) for c in range(cols - 1))
    south = all(tiles[grid[r][c]][2] == tiles[grid[r + 1][c]][0] for r in range(rows - 1) for c in range(cols))
    return east and south


@pytest.mark.slow
def test_aperiodic_report_and_witness_use_the_input_order(tmp_path, tiles):
    proc = run("aperiodic", "check", "p.json", "--max-square", "4", "--workers", "1", "--seed", "1", "-o", "r.json",
               cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    report = json.loads((tmp_path / "r.json").read_text())
    assert report["tileset"]["tiles"] == tiles
    witness = report["squares"][-1]["tiling"]
    assert len(witness) == 4 and _matches(tiles, witness)
    assert run("verify", "r.json", cwd=tmp_path).returncode == 0


@pytest.mark.slow
def test_wang_solve_lists_the_tiles_in_the_input_order(tmp_path, tiles):
    proc = run("wang", "solve", "--tiles", "p.json", "--board", "rect:4x4", "--boundary", "free", "--seed", "1",
               "-o", "s.json", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    doc = json.loads((tmp_path / "s.json").read_text())
    assert doc["leg_order"] == ["N", "E", "S", "W"] and doc["tileset"] == tiles
    assert all(cell in tiles for cell in doc["tiles"])
    assert run("verify", "s.json", cwd=tmp_path).returncode == 0


def test_a_report_written_before_keeps_its_own_order_and_verifies(tmp_path):
    """A report written while tilesolve sorted the tiles (by W, N, E, S): its indices refer to
    the list it holds, which the verifier reads in the order written, proofs included."""
    old = Path(__file__).parent / "data" / "aperiodic_report"
    shutil.copytree(old, tmp_path / "old")
    report = json.loads((old / "v1-periodic-7-30.json").read_text())
    listed = report["tileset"]["tiles"]
    assert listed == sorted(listed, key=lambda t: [t[3], t[0], t[1], t[2]]) != json.loads(TILES.read_text())["tiles"]
    assert _matches(listed, report["squares"][-1]["tiling"])
    proc = run("verify", "v1-periodic-7-30.json", "--proof-dir", "proofs", cwd=tmp_path / "old")
    assert proc.returncode == 0 and proc.stdout.startswith("ok:"), proc.stdout + proc.stderr
    assert proc.stdout.count("verified against the re-derived CNF") == 4
