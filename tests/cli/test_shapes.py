"""``tilesolve shapes`` through the console script: answers, files, verify, pictures, bad input."""

from __future__ import annotations

import json

import pytest
from clitools import one_line_error, run


def test_list_counts_free_polyforms(tmp_path):
    assert run("shapes", "list", "--grid", "omino", "--size", "6", cwd=tmp_path).stdout.split() == ["35"]
    assert run("shapes", "list", "--grid", "hex", "--size", "6", "--no-holes", cwd=tmp_path).stdout.split() == ["81"]
    assert run("shapes", "list", "--grid", "iamond", "--size", "6", cwd=tmp_path).stdout.split() == ["12"]


def test_tile_writes_a_verified_tiling_and_pictures(tmp_path):
    p = run("shapes", "tile", "--grid", "omino", "--shape", "##/##/#.", "--region", "5x2", "-o", "t.json",
            "--svg", "t.svg", "--png", "t.png", "--seed", "1", cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    assert (tmp_path / "t.svg").read_text().startswith("<svg") and (tmp_path / "t.png").read_bytes()[:4] == b"\x89PNG"
    v = run("verify", "t.json", cwd=tmp_path)
    assert v.returncode == 0 and "valid tiling" in v.stdout


def test_an_unsat_tiling_is_re_checked_by_verify(tmp_path):
    p = run("shapes", "tile", "--shape", "###/.#.", "--region", "4x3", "-o", "t.json", "--proof-dir", "pd",
            cwd=tmp_path)
    assert p.returncode == 1
    v = run("verify", "t.json", "--proof-dir", "pd", cwd=tmp_path)
    assert v.returncode == 0 and "unsat re-checked" in v.stdout


def test_heesch_report_and_its_refutation_are_re_checked(tmp_path):
    p = run("shapes", "heesch", "--grid", "hex", "--shape", "0,0 0,1 0,2 0,3 1,-1 1,3", "-o", "h.json", "--svg",
            "h.svg", "--proof-dir", "pd", cwd=tmp_path)
    assert p.returncode == 0 and "Heesch number H_c = 1" in p.stderr
    doc = json.loads((tmp_path / "h.json").read_text())
    assert doc["report"]["verdict"] == "non-tiler" and doc["report"]["heesch"] == 1
    v = run("verify", "h.json", "--proof-dir", "pd", cwd=tmp_path)
    assert v.returncode == 0 and "1 refutation(s) re-checked" in v.stdout
    doc["report"]["heesch"] = 2
    (tmp_path / "bad.json").write_text(json.dumps(doc))
    assert run("verify", "bad.json", cwd=tmp_path).returncode == 1


@pytest.mark.slow
def test_heesch_with_holes_in_the_outer_corona(tmp_path):
    # a 7-omino with H_c = 0 and H_h = 1 (heesch-sat's -hh reports the same pair)
    shape = "1,-2 1,-1 0,0 1,0 2,0 3,0 1,1"
    hc = run("shapes", "heesch", "--shape", shape, "-o", "hc.json", cwd=tmp_path)
    assert hc.returncode == 0 and "Heesch number H_c = 0" in hc.stderr, hc.stderr
    hh = run("shapes", "heesch", "--shape", shape, "--holes", "-o", "hh.json", "--proof-dir", "pd", cwd=tmp_path)
    assert hh.returncode == 0 and "Heesch number H_h = 1" in hh.stderr, hh.stderr
    doc = json.loads((tmp_path / "hh.json").read_text())
    assert doc["report"]["heesch"] == 1 and doc["report"]["holes"] is True
    v = run("verify", "hh.json", "--proof-dir", "pd", cwd=tmp_path)
    assert v.returncode == 0 and "1 refutation(s) re-checked" in v.stdout, v.stdout
    doc["report"]["holes"] = False  # the H_h patch has a hole: as an H_c patch it is refused
    (tmp_path / "bad.json").write_text(json.dumps(doc))
    bad = run("verify", "bad.json", cwd=tmp_path)
    assert bad.returncode == 1 and "hole" in bad.stdout + bad.stderr


def test_census_resumes_from_its_file(tmp_path):
    full = run("shapes", "census", "--grid", "omino", "--size", "5", "--workers", "1", "-o", "c.json", cwd=tmp_path)
    assert full.returncode == 0
    doc = json.loads((tmp_path / "c.json").read_text())
    assert doc["total"] == 12 and len(doc["shapes"]) == 12
    kept = doc["shapes"][:4] + doc["shapes"][9:]
    doc["shapes"] = kept
    (tmp_path / "c.json").write_text(json.dumps(doc))
    again = run("shapes", "census", "--grid", "omino", "--size", "5", "--workers", "1", "-o", "c.json", "--resume",
                cwd=tmp_path)
    assert again.returncode == 0 and "7 shape(s) resumed from c.json" in again.stderr
    assert again.stdout.splitlines()[:2] == full.stdout.splitlines()[:2]
    resumed = json.loads((tmp_path / "c.json").read_text())["shapes"]
    assert len(resumed) == 12 and resumed[:4] == kept[:4] and resumed[9:] == kept[4:]  # kept rows as they were
    other = run("shapes", "census", "--grid", "omino", "--size", "5", "--max-level", "2", "-o", "c.json", "--resume",
                cwd=tmp_path)
    assert "its max_level is 3, this census has 2" in one_line_error(other)
    (tmp_path / "stray.json").write_text(json.dumps({**doc, "shapes": [{**kept[0], "cells": [[0, 0]]}]}))
    stray = run("shapes", "census", "--grid", "omino", "--size", "5", "-o", "stray.json", "--resume", cwd=tmp_path)
    assert "are not a free omino polyform of size 5" in one_line_error(stray)


def test_census_prints_its_table_and_total(tmp_path):
    p = run("shapes", "census", "--grid", "omino", "--size", "4", "--workers", "1", "-o", "c.json", cwd=tmp_path)
    assert p.returncode == 0 and p.stdout.strip().splitlines()[-1] == "5 shapes"
    assert len(json.loads((tmp_path / "c.json").read_text())["shapes"]) == 5


@pytest.mark.parametrize("args, message", [
    (["tile", "--shape", "##"], "exactly one of --region"),
    (["tile", "--shape", "#.#", "--region", "3x3"], "edge-connected"),
    (["tile", "--shape", "##", "--region", "3by3"], "WxH"),
    (["tile", "--shape", "#" * 19 + "/#", "--torus", "140x140"], "about .* literals"),
    (["tile", "--region", "2x2"], "at least one shape"),
    (["tile", "--shape", "X-/XX", "--region", "2x2"], "one of '#', 'X', 'x', '\\*', 'o' .* got '-' in row 1"),
    (["heesch", "--shape", "##", "--shape", "#"], "one shape"),
    (["list", "--grid", "omino", "--size", "12"], "sizes 1..11"),
])
def test_bad_input_is_one_line_exit_2(tmp_path, args, message):
    import re

    line = one_line_error(run("shapes", *args, "-o", "x.json", cwd=tmp_path) if args[0] != "list"
                          else run("shapes", *args, cwd=tmp_path))
    assert re.search(message, line), line
    assert not (tmp_path / "x.json").exists()


@pytest.mark.slow
@pytest.mark.parametrize("command", [("shapes",), ("shapes", "tile"), ("shapes", "heesch"), ("shapes", "list"),
                                     ("shapes", "census")])
def test_help_examples_run(tmp_path, command):
    import re
    import shlex

    shown = [ln.strip() for ln in run(*command, "--help", cwd=tmp_path).stdout.splitlines()
             if ln.strip().startswith("tilesolve ")]
    assert shown
    for line in shown:
        cmd, _, comment = line.partition("#")
        proc = run(*shlex.split(cmd)[1:], cwd=tmp_path)
        assert proc.returncode == (1 if "unsat" in comment else 0), (line, proc.stderr[-800:])
        promised = re.match(r"\s*prints\s+(.+)$", comment)
        if promised:
            assert proc.stdout.strip().splitlines()[-1] == promised.group(1).strip(), line


@pytest.mark.slow
def test_ctrl_c_stops_a_census_with_exit_130_and_no_file(tmp_path):
    import signal
    import subprocess
    import time

    from clitools import ENV, SCRIPT

    # The 363 holeless 8-ominoes take minutes: the signal lands while shapes are classified.
    proc = subprocess.Popen([SCRIPT, "shapes", "census", "--grid", "omino", "--size", "8", "-o", "c.json"],
                            cwd=tmp_path, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, env=ENV)
    time.sleep(3)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=300)
    assert proc.returncode == 130 and "Traceback" not in err
    assert err.strip().splitlines()[-1] == "tilesolve: interrupted (no file was written)"
    assert not (tmp_path / "c.json").exists()


@pytest.mark.slow
def test_census_on_a_dask_cluster_matches_local_workers(tmp_path):
    import distributed

    args = ("shapes", "census", "--grid", "hex", "--size", "5")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0") as lc:
        dask = run(*args, "--cluster", lc.scheduler_address, "-o", "d.json", cwd=tmp_path)
    local = run(*args, "--workers", "1", "-o", "l.json", cwd=tmp_path)
    assert dask.returncode == local.returncode == 0, dask.stderr
    assert dask.stdout.splitlines()[-1] == "22 shapes"
    rows = [json.loads((tmp_path / f).read_text())["shapes"] for f in ("d.json", "l.json")]
    assert [(r["cells"], r["verdict"], r["copies"]) for r in rows[0]] == \
        [(r["cells"], r["verdict"], r["copies"]) for r in rows[1]]
