"""Fuzzing finds of issue 17: what ``verify`` and ``draw`` take on trust, and work without bound.

Each test forges a file the way the fuzzer did, through the real console script:

- an aperiodicity report with a negative ``time_s`` or a colour count its tiles contradict;
- an unsat file whose stated problem is huge: its CNF is sized before it is re-derived;
- a packing file whose colour count does not fit its grid, handed to ``draw``;
- a board file with a line limit of 2^31 - 1 cells, whose encoding once looped that many times.
"""

from __future__ import annotations

import json

import pytest
from clitools import one_line_error, run


def _report(tmp_path) -> dict:
    proc = run("aperiodic", "check", "--builtin", "periodic-7-30", "--max-period", "1", "--workers", "1",
               "-o", "p.json", "--proof-dir", "proofs", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    return json.loads((tmp_path / "p.json").read_text())


def _forge(tmp_path, name: str, doc: dict) -> str:
    (tmp_path / name).write_text(json.dumps(doc))
    return name


@pytest.mark.slow
@pytest.mark.parametrize("time_s", [-5, 1e300, "-Infinity"])
def test_report_certificate_time_is_checked_like_every_time_s(tmp_path, time_s):
    doc = _report(tmp_path)
    doc["periods"][0]["time_s"] = time_s
    text = json.dumps(doc).replace('"-Infinity"', "-Infinity")
    (tmp_path / "t.json").write_text(text)
    line = one_line_error(run("verify", "t.json", cwd=tmp_path))
    assert "t.json" in line and ("periods[0].time_s" in line or "Infinity" in line), line


@pytest.mark.slow
def test_report_colour_count_must_be_the_one_its_tiles_use(tmp_path):
    doc = _report(tmp_path)
    assert run("verify", "p.json", cwd=tmp_path).returncode == 0
    doc["tileset"]["colours"] = 10**9
    line = one_line_error(run("verify", _forge(tmp_path, "c.json", doc), cwd=tmp_path))
    assert "'colours' is 1000000000, but its tiles use 4" in line, line
    doc = _report(tmp_path)
    doc["tileset"]["tiles"].append(doc["tileset"]["tiles"][0])
    line = one_line_error(run("aperiodic", "verify", _forge(tmp_path, "d.json", doc), cwd=tmp_path))
    assert "duplicate tile" in line, line


@pytest.mark.slow
def test_an_unsat_claim_is_sized_before_its_cnf_is_rederived(tmp_path):
    """A CNF too large to re-derive leaves the claim unconfirmed: exit 1, the README's code for
    "verify found ... a claim it cannot confirm" (the file is well-formed; it is its claim that
    cannot be checked here), not exit 2; --max-cnf raises the limit as it does for export."""
    proc = run("dappled", "solve", "--size", "3x3", "--cond", "H0=1", "--count", "1=0", "-o", "u.json",
               "--proof-dir", "proofs", cwd=tmp_path)
    assert proc.returncode == 1, proc.stderr
    doc = json.loads((tmp_path / "u.json").read_text())
    doc["size"]["rows"] = 3000001
    proc = run("verify", _forge(tmp_path, "big.json", doc), "--proof-dir", "proofs", cwd=tmp_path)
    assert proc.returncode == 1 and not proc.stdout.startswith("ok"), proc.stdout
    assert "NOT confirmed" in proc.stdout and "cannot be re-derived here" in proc.stdout, proc.stdout
    assert "GiB of DIMACS text" in proc.stdout and "--max-cnf 1.0 GiB" in proc.stdout, proc.stdout
    # the honest file under a limit below its CNF: refused the same way; with the default, ok
    proc = run("verify", "u.json", "--proof-dir", "proofs", "--max-cnf", "64", cwd=tmp_path)
    assert proc.returncode == 1 and "cannot be re-derived here" in proc.stdout, proc.stdout
    assert run("verify", "u.json", "--proof-dir", "proofs", cwd=tmp_path).returncode == 0
    assert "--max-cnf" in one_line_error(run("verify", "u.json", "--max-cnf", "lots", cwd=tmp_path))


@pytest.mark.slow
def test_a_report_refutation_is_sized_before_its_cnf_is_rederived(tmp_path):
    _report(tmp_path)
    proc = run("aperiodic", "verify", "p.json", "--proof-dir", "proofs", "--max-cnf", "64", cwd=tmp_path)
    last = proc.stdout.strip().splitlines()[-1]
    assert proc.returncode == 1 and "NOT confirmed" in last and not last.startswith("ok"), proc.stdout
    assert "torus 1x1: the certificate cannot be re-derived here" in proc.stdout, proc.stdout
    assert run("aperiodic", "verify", "p.json", "--proof-dir", "proofs", cwd=tmp_path).returncode == 0


@pytest.mark.fast_cases(1)
@pytest.mark.parametrize("colors", [3, 10**6])
def test_draw_refuses_a_packing_grid_that_is_not_its_torus(tmp_path, colors):
    assert run("pack", "--kind", "wang", "--colors", "2", "--seed", "1", "-o", "w.json", cwd=tmp_path).returncode == 0
    doc = json.loads((tmp_path / "w.json").read_text())
    doc["colors"] = colors
    _forge(tmp_path, "f.json", doc)
    line = one_line_error(run("draw", "f.json", "-o", "f.svg", cwd=tmp_path))
    assert "the grid is 4x4" in line and f"{colors**2}x{colors**2} torus" in line, line
    assert not (tmp_path / "f.svg").exists()
    proc = run("verify", "f.json", cwd=tmp_path)
    assert proc.returncode == 1 and "packing has shape (4, 4)" in proc.stdout, proc.stdout


@pytest.mark.slow
def test_a_huge_line_limit_encodes_as_the_board_allows(tmp_path):
    """A line limit beyond the board encodes in board-sized work: on a 5x4 torus, limits of
    2^31 - 1 give exactly the clauses of limits 5 and 4 (a line round the torus is forbidden
    either way)."""
    proc = run("brick", "solve", "--board", "torus:5x4", "--colors", "3", "--max-h", "3", "--method", "sat",
               "--seed", "1", "-o", "b.json", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    doc = json.loads((tmp_path / "b.json").read_text())
    clauses = {}
    for name, (h, v) in {"big": (2**31 - 1, 2**31 - 1), "side": (5, 4)}.items():
        doc["max_h"], doc["max_v"] = h, v
        proc = run("export", "dimacs", _forge(tmp_path, f"{name}.json", doc), "-o", f"{name}.cnf", cwd=tmp_path)
        assert proc.returncode == 0, proc.stderr
        clauses[name] = [ln for ln in (tmp_path / f"{name}.cnf").read_text().splitlines() if not ln.startswith("c")]
    assert clauses["big"] == clauses["side"] and len(clauses["big"]) > 400
