"""One Wang vocabulary: N, E, S, W at the public boundary, converters, the tile-set file."""

import json

import numpy as np
import pytest

from tilesolve.errors import InvalidProblem
from tilesolve.io.tileset_json import read_tileset, tileset_to_dict, write_tileset
from tilesolve.model.board import WangTileSet
from tilesolve.model.tiles import TileSet
from tilesolve.verify.grid import grid_violations
from clitools import SCRIPT


def test_tileset_round_trip_in_nesw_order(tmp_path):
    ts = WangTileSet.brick(3)
    write_tileset(tmp_path / "b.json", ts, name="brick")
    doc = json.loads((tmp_path / "b.json").read_text())
    assert doc["format"] == "tilesolve/wang-tileset" and doc["order"] == ["N", "E", "S", "W"]
    assert doc["tiles"] == ts.tiles.tolist()
    back, notes = read_tileset(tmp_path / "b.json")
    assert notes == [] and np.array_equal(back.tiles, ts.tiles)


def test_legacy_files_are_still_read(tmp_path):
    (tmp_path / "old.json").write_text(json.dumps({"colors": 2, "tiles": [[0, 1, 0, 1], [1, 0, 1, 0]]}))
    ts, _ = read_tileset(tmp_path / "old.json")  # no order: legs W, N, E, S (the paper's l1..l4)
    assert ts.tiles.tolist() == [[1, 0, 1, 0], [0, 1, 0, 1]]
    (tmp_path / "nesw.json").write_text(json.dumps({"order": "NESW", "tiles": [[1, 2, 3, 0]]}))
    ts, _ = read_tileset(tmp_path / "nesw.json")
    assert ts.tiles.tolist() == [[1, 2, 3, 0]]


def test_duplicates_are_dropped_with_a_note_and_bad_files_refused(tmp_path):
    doc = tileset_to_dict(WangTileSet([[0, 0, 0, 0]], 1))
    doc["tiles"] = doc["tiles"] * 3
    (tmp_path / "dup.json").write_text(json.dumps(doc))
    ts, notes = read_tileset(tmp_path / "dup.json")
    assert len(ts) == 1 and "2 duplicate tile(s) dropped" in notes[0]
    for bad, message in ((dict(doc, tiles=[[0, 0, 0]]), "tile 0 must be a list of 4"),
                         (dict(doc, tiles=[]), "non-empty"),
                         (dict(doc, version=9), "version 9"),
                         (dict(doc, colors=1, tiles=[[0, 0, 0, 5]]), "outside C"),
                         (dict(doc, extra=1), "unknown field")):
        (tmp_path / "bad.json").write_text(json.dumps(bad))
        with pytest.raises(InvalidProblem, match=message):
            read_tileset(tmp_path / "bad.json")


@pytest.mark.parametrize("colors, colors_v, variant", [(2, None, "complete"), (3, None, "compact"), (2, 3, "complete")])
def test_tileset_converter_keeps_the_edges(colors, colors_v, variant):
    ts = TileSet("wang", colors, colors_v, variant=variant)
    w = WangTileSet.from_tileset(ts)
    assert len(w) == ts.n_tiles
    assert sorted(map(tuple, w.tiles.tolist())) == sorted(map(tuple, ts.table().tolist()))
    # a 1x2 tiling that matches in TileSet terms matches in board terms too
    table = ts.table()
    a, b = next((i, j) for i in range(len(table)) for j in range(len(table)) if table[i, 1] == table[j, 3])
    assert grid_violations(table, [[a, b]]) == []
    with pytest.raises(InvalidProblem, match="corner tiles are not Wang tiles"):
        WangTileSet.from_tileset(TileSet("corner", 2))


@pytest.mark.slow
def test_cli_writes_a_tileset_file_that_wang_solve_reads(tmp_path):
    import subprocess

    def run(*args):
        return subprocess.run([SCRIPT, *args], cwd=tmp_path, capture_output=True, text=True,
                              timeout=300)

    p = run("tiles", "--kind", "wang", "--colors", "3", "--set", "compact", "-o", "c3.json", "--png", "c3.png")
    assert p.returncode == 0, p.stderr
    ts, _ = read_tileset(tmp_path / "c3.json")
    assert len(ts) == 18 and (tmp_path / "c3.png").stat().st_size > 0
    p = run("wang", "solve", "--tiles", "c3.json", "--board", "torus:4x4", "--boundary", "free", "-o", "w.json")
    assert p.returncode == 0, p.stderr
    assert run("verify", "w.json").returncode == 0
    p = run("tiles", "--kind", "corner", "--colors", "2", "-o", "x.json")
    assert p.returncode == 2 and "corner tiles have no such file" in p.stderr and not (tmp_path / "x.json").exists()
