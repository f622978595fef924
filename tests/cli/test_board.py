"""CLI contract of `tilesolve brick solve | wall`, `tilesolve wang solve` and `verify` on
board solutions: exit codes, one-line errors, and a JSON any tool can re-check."""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

import pytest
from click.testing import CliRunner

from tilesolve.cli.main import main_group
from clitools import SCRIPT


def invoke(*args, cwd=None):
    return CliRunner().invoke(main_group, list(args), catch_exceptions=False)


def recheck_without_tilesolve(doc: dict) -> bool:
    """Check a board solution from its plain fields only (tiles and edge legs in its leg order)."""
    tiles = doc["tiles"]
    ok = True
    for a, ka, b, kb in doc["edges"]:
        if b >= 0:
            ok &= tiles[a][ka] == tiles[b][kb]
        elif doc["boundary"][kb] is not None:
            ok &= tiles[a][ka] == doc["boundary"][kb]
    if doc["tileset"] == "brick":
        ok &= all((t[0] == t[2]) != (t[1] == t[3]) for t in tiles)
    else:
        allowed = {tuple(t) for t in doc["tileset"]}
        ok &= all(tuple(t) in allowed for t in tiles)
    return ok


@pytest.mark.parametrize("spec", ["rect:9x6", "torus:6x5", "cylinder:7x4", "mobius:8x5", "klein:5x5"])
def test_brick_solve_writes_checkable_json(tmp_path, monkeypatch, spec):
    monkeypatch.chdir(tmp_path)
    r = invoke("brick", "solve", "--board", spec, "--colors", "3", "--seed", "4", "-o", "out.json", "--svg", "out.svg")
    assert r.exit_code == 0, r.output
    doc = json.loads(Path("out.json").read_text())
    assert doc["format"] == "tilesolve/board-solution" and doc["colors"] == 3 and doc["tileset"] == "brick"
    assert doc["version"] == 3 and doc["leg_order"] == ["N", "E", "S", "W"]
    assert len(doc["tiles"]) == len(doc["cells"])
    assert recheck_without_tilesolve(doc)
    assert Path("out.svg").read_text().startswith("<svg") or "<svg" in Path("out.svg").read_text()[:300]
    v = invoke("verify", "out.json")
    assert v.exit_code == 0 and "ok:" in v.output


def test_verify_reports_corruption_exit_1(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert invoke("brick", "solve", "--board", "rect:5x5", "--seed", "1", "-o", "s.json").exit_code == 0
    doc = json.loads(Path("s.json").read_text())
    doc["tiles"][12][0] = (doc["tiles"][12][0] + 1) % 3
    Path("bad.json").write_text(json.dumps(doc))
    v = invoke("verify", "bad.json")
    assert v.exit_code == 1 and "violation" in v.output


def test_unsat_tree_exit_1_with_explanation(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    Path("m.txt").write_text("#\n")
    Path("b.json").write_text(json.dumps([0, 1, 0, 1]))  # W = E and N = S: a cross
    r = invoke("brick", "solve", "--board", "mask:m.txt", "--boundary", "b.json", "-o", "s.json")
    assert r.exit_code == 1
    assert "clash" in r.output
    assert json.loads(Path("s.json").read_text())["status"] == "unsat"


@pytest.mark.parametrize("args,msg", [
    (["brick", "solve", "--board", "rect:3x3", "--colors", "2", "-o", "x.json"], "#C >= 3"),
    (["brick", "solve", "--board", "hex:3x3", "-o", "x.json"], "cannot read board"),
    (["brick", "solve", "--board", "mask:nope.txt", "-o", "x.json"], "cannot read mask"),
    (["brick", "solve", "--board", "rect:2x2", "--boundary", "bnd.json", "-o", "x.json"], "boundary"),
    (["brick", "solve", "--board", "rect:2x2", "--boundary", "big.json", "-o", "x.json"], "not on the boundary"),
    (["wang", "solve", "--tiles", "empty.json", "--board", "rect:2x2", "-o", "x.json"], "empty"),
    (["wang", "solve", "--tiles", "outside.json", "--board", "rect:2x2", "-o", "x.json"], "outside C"),
    (["brick", "wall", "--size", "4x4", "--max-line", "2", "--colors", "2", "-o", "x.json"], "#C >= 3"),
])
def test_bad_input_exit_2_one_line(tmp_path, monkeypatch, args, msg):
    monkeypatch.chdir(tmp_path)
    Path("bnd.json").write_text(json.dumps([0, 9, 0, 0, 0, 0, 0, 0]))
    Path("big.json").write_text(json.dumps([0] * 9))
    Path("empty.json").write_text(json.dumps({"colors": 2, "tiles": []}))
    Path("outside.json").write_text(json.dumps({"colors": 2, "tiles": [[0, 1, 2, 0]]}))
    r = CliRunner().invoke(main_group, args)
    assert r.exit_code == 2, r.output
    assert msg in r.output and "Traceback" not in r.output
    assert not Path("x.json").exists()


def test_wang_solve_any_tileset(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    Path("t.json").write_text(json.dumps({"colors": 2, "order": "NESW",
                                          "tiles": [[n, e, s, w] for n in (0, 1) for e in (0, 1) for s in (0, 1)
                                                    for w in (0, 1) if w == e]}))
    r = invoke("wang", "solve", "--tiles", "t.json", "--board", "torus:4x3", "--boundary", "free",
               "-o", "w.json", "--svg", "w.svg")
    assert r.exit_code == 0, r.output
    doc = json.loads(Path("w.json").read_text())
    assert doc["tileset"] != "brick" and recheck_without_tilesolve(doc)
    assert invoke("verify", "w.json").exit_code == 0


def test_brick_wall_line_limits(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    r = invoke("brick", "wall", "--size", "30x20", "--max-line", "2", "--seed", "3", "-o", "w.json", "--svg", "w.svg")
    assert r.exit_code == 0, r.output
    doc = json.loads(Path("w.json").read_text())
    assert doc["max_h"] == 2 and doc["max_v"] == 2
    assert invoke("verify", "w.json").exit_code == 0


def test_console_script_contract(tmp_path):
    script = SCRIPT
    r = subprocess.run([script, "brick", "solve", "--board", "rect:12x8", "--colors", "3", "--boundary", "random",
                        "--seed", "5", "--method", "linear", "-o", "o.json"], cwd=tmp_path, capture_output=True,
                       text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    r = subprocess.run([script, "verify", "o.json"], cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert r.returncode == 0 and r.stdout.startswith("ok:")


def test_count_and_crosscheck_commands():
    r = invoke("brick", "count", "--board", "rect:2x1", "--boundary", "free")
    # 3 colours: each colour sits on the E leg of 12 brick tiles and on the W leg of 12
    assert r.exit_code == 0 and r.output.strip().splitlines()[-1] == str(3 * 12 * 12)
    r = invoke("brick", "crosscheck", "--board", "ring:5x4", "--trials", "2", "--seed", "1")
    assert r.exit_code == 0 and "all routes agree" in r.output


def test_malformed_board_solution_and_boundary_from_file(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert invoke("brick", "solve", "--board", "rect:4x3", "--seed", "2", "-o", "a.json").exit_code == 0
    doc = json.loads(Path("a.json").read_text())
    # the boundary of one solution file can be reused for another run
    r = invoke("brick", "solve", "--board", "rect:4x3", "--boundary", "a.json", "--method", "sat", "-o", "b.json")
    assert r.exit_code == 0
    assert json.loads(Path("b.json").read_text())["boundary"] == doc["boundary"]
    bad = dict(doc, edges=doc["edges"][:-1])
    Path("bad.json").write_text(json.dumps(bad))
    r = CliRunner().invoke(main_group, ["verify", "bad.json"])  # the listed edges are not the rect's
    assert r.exit_code == 1 and "does not list the edge where leg S of cell [2, 3] meets the wall" in r.output
    r = CliRunner().invoke(main_group, ["brick", "solve", "--board", "rect:600x600", "--svg", "x.svg"])
    assert r.exit_code == 2 and "too large" in r.output and not Path("x.svg").exists()
