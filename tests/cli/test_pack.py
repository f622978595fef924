"""The `tilesolve pack` contract (issue 4): files, exit codes, count on the last line, verify."""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

from tilesolve.io.packing_json import packing_from_dict, packing_to_dict, read_packing, write_packing
from tilesolve.errors import InvalidProblem
from tilesolve.model.packing import PackingProblem
from tilesolve.model.solution import Solution, Status
from tilesolve.verify.packing import is_packing
from clitools import SCRIPT


def run(*args: str, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run([SCRIPT, *args], cwd=cwd, capture_output=True, text=True, timeout=300,
                          env=dict(os.environ, COLUMNS="100"))


def one_line_error(proc) -> str:
    assert proc.returncode == 2, (proc.returncode, proc.stdout, proc.stderr)
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("tilesolve: error: "), proc.stderr
    return lines[0]


@pytest.mark.fast_cases(1)
@pytest.mark.parametrize("kind,c,method", [("wang", 4, "auto"), ("corner", 3, "euler"), ("wang", 2, "sat"),
                                           ("corner", 2, "cpsat"), ("corner", 4, "known"),
                                           ("wang", 4, "hybrid")])
def test_pack_writes_a_valid_file(tmp_path, kind, c, method):
    proc = run("pack", "--kind", kind, "--colors", str(c), "--method", method, "--seed", "3",
               "-o", "p.json", "--svg", "p.svg", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    doc = json.loads((tmp_path / "p.json").read_text())
    assert doc["format"] == "tilesolve/packing" and doc["kind"] == kind and doc["colors"] == c
    grid = np.array(doc["grid"])
    assert grid.shape == (c * c, c * c) and is_packing(PackingProblem(kind, c), grid)
    assert (tmp_path / "p.svg").read_text().startswith("<svg")
    proc = run("verify", "p.json", cwd=tmp_path)
    assert proc.returncode == 0 and proc.stdout.startswith("ok:")


def test_verify_lists_violations(tmp_path):
    run("pack", "--kind", "corner", "--colors", "3", "--seed", "1", "-o", "p.json", cwd=tmp_path)
    doc = json.loads((tmp_path / "p.json").read_text())
    doc["grid"][0][0], doc["grid"][4][4] = doc["grid"][4][4], doc["grid"][0][0]
    (tmp_path / "bad.json").write_text(json.dumps(doc))
    proc = run("verify", "bad.json", cwd=tmp_path)
    assert proc.returncode == 1
    assert "violation" in proc.stdout
    # each mismatch is reported at the western/northern cell of the pair
    near = ["row 0, col 0", "row 0, col 8", "row 8, col 0", "row 4, col 4", "row 4, col 3", "row 3, col 4"]
    assert any(w in proc.stdout for w in near)


@pytest.mark.fast_cases(1)
@pytest.mark.parametrize("kind,sym,expected", [("corner", False, 32), ("corner", True, 1), ("wang", False, 203520)])
def test_count_last_line(tmp_path, kind, sym, expected):
    args = ["pack", "count", "--kind", kind, "--colors", "2"] + (["--up-to-symmetry"] if sym else [])
    proc = run(*args, cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.strip().splitlines()[-1] == str(expected)


@pytest.mark.slow
def test_unsat_pins_and_unknown_exit_codes(tmp_path):
    proc = run("pack", "--kind", "corner", "--colors", "2", "--fix", "0,0,0", "--fix", "0,1,15", "-o", "u.json",
               cwd=tmp_path)
    assert proc.returncode == 1
    assert json.loads((tmp_path / "u.json").read_text())["status"] == "unsat"
    proc = run("verify", "u.json", cwd=tmp_path)
    assert proc.returncode == 1 and "no tiling" in proc.stdout
    proc = run("pack", "--kind", "corner", "--colors", "4", "--method", "sat", "--time-limit", "1", "-o", "t.json",
               cwd=tmp_path)
    assert proc.returncode == 3
    assert json.loads((tmp_path / "t.json").read_text())["status"] == "unknown"


@pytest.mark.slow
def test_bad_input_is_one_line(tmp_path):
    assert "at least 2" in one_line_error(run("pack", "--kind", "wang", "--colors", "1", cwd=tmp_path))
    line = one_line_error(run("pack", "--kind", "corner", "--colors", "20", "--method", "sat", "-o", "x.json",
                              cwd=tmp_path))
    assert "variables" in line and "clauses" in line
    line = one_line_error(run("pack", "--kind", "corner", "--colors", "1000", "-o", "x.json", cwd=tmp_path))
    assert "1,000,000,000,000 tiles" in line and "TiB" in line  # refused before the tile set is built
    assert not (tmp_path / "x.json").exists()
    assert "odd" in one_line_error(run("pack", "--kind", "corner", "--colors", "4", "--method", "euler", cwd=tmp_path))
    assert "--kind" in one_line_error(run("pack", "--colors", "2", cwd=tmp_path))
    assert "ROW,COL,TILE" in one_line_error(run("pack", "--kind", "wang", "--colors", "2", "--fix", "1,2", cwd=tmp_path))
    assert "C=2" in one_line_error(run("pack", "count", "--kind", "wang", "--colors", "3", cwd=tmp_path))
    proc = run("pack", "--kind", "hex", "--colors", "2", cwd=tmp_path)
    assert proc.returncode == 2 and "Traceback" not in proc.stderr


def test_dimacs_export(tmp_path):
    proc = run("pack", "--kind", "wang", "--colors", "3", "--dimacs", "w3.cnf", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    text = (tmp_path / "w3.cnf").read_text()
    assert "c tilesolve tile packing" in text and "\np cnf " in text


def test_json_round_trip_and_bad_files(tmp_path):
    p = PackingProblem("wang", 2, colors_v=3, fixed=((0, 0, 1),))
    grid = np.arange(36).reshape(4, 9)
    sol = Solution(Status.SAT, grid, method="outer", seed=4)
    write_packing(tmp_path / "a.json", p, sol)
    p2, s2 = read_packing(tmp_path / "a.json")
    assert p2 == p and np.array_equal(s2.tiling, grid) and s2.method == "outer"
    doc = packing_to_dict(p, sol)
    for bad, match in [({"grid": [[0, "x"]]}, "integer"), ({"kind": "hex"}, "kind"), ({"extra": 1}, "unknown field"),
                       ({"colors": "2"}, "integer"), ({"status": "maybe"}, "status")]:
        d = dict(doc, grid=grid.tolist())
        d.update(bad)
        with pytest.raises(InvalidProblem, match=match):
            packing_from_dict(d, "f.json")


@pytest.mark.slow
def test_demo_entry_writes_verified_pictures(tmp_path):
    p = run("demo", "--family", "packing", "--out", "pics", cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    for name in ("packing-wang3", "packing-corner4"):
        problem, sol = read_packing(tmp_path / "pics" / f"{name}.json")
        assert is_packing(problem, sol.tiling)
        assert (tmp_path / "pics" / f"{name}.svg").exists()


@pytest.mark.slow
def test_lift_and_recursive_from_the_command_line(tmp_path):
    p = run("pack", "--kind", "corner", "--colors", "4", "--method", "lift", "--seed", "2", "-o", "c4.json",
            cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    assert "base packing over 2 colours" in p.stderr
    assert run("verify", "c4.json", cwd=tmp_path).returncode == 0
    p = run("pack", "--kind", "wang", "--colors", "3", "--method", "recursive", "--seed", "1", "-o", "w3.json",
            cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    assert "embeds a packing over 2 colours" in p.stderr
    grid = np.array(read_packing(tmp_path / "w3.json")[1].tiling)
    assert is_packing(PackingProblem("wang", 3), grid)


@pytest.mark.slow
def test_unreachable_cluster_is_a_one_line_error(tmp_path):
    p = run("pack", "--kind", "corner", "--colors", "4", "--method", "lift", "--cluster", "tcp://127.0.0.1:9",
            "-o", "c.json", cwd=tmp_path)
    assert "cluster" in one_line_error(p).lower() or "connect" in p.stderr.lower()
    assert not (tmp_path / "c.json").exists()
