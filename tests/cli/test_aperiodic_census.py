"""``tilesolve aperiodic census`` through the console script: counts, the census file, resume,
bad input."""

from __future__ import annotations

import json

import pytest
from clitools import one_line_error, run


def test_census_counts_each_class_and_writes_its_file(tmp_path):
    p = run("aperiodic", "census", "--tiles", "2", "--colors", "2", "--workers", "1", "-o", "c.jsonl", cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    assert p.stdout.startswith("census of 13 sets of 2 tiles over at most 2 colours per axis (up to symmetry")
    assert p.stdout.strip().endswith("5 finite, 8 periodic, 0 undecided, 0 not reached"), p.stdout
    lines = (tmp_path / "c.jsonl").read_text().splitlines()
    header = json.loads(lines[0])
    assert (header["format"], header["tiles"], header["colours"], header["sets"]) == ("tilesolve/wang-census", 2, 2, 13)
    recs = [json.loads(line) for line in lines[1:]]
    assert sorted(r["class"] for r in recs) == ["finite"] * 5 + ["periodic"] * 8
    # stopped after four records: --resume keeps them and classifies the rest
    (tmp_path / "c.jsonl").write_text("\n".join(lines[:5]) + "\n")
    p = run("aperiodic", "census", "--tiles", "2", "--colors", "2", "--workers", "1", "-o", "c.jsonl", "--resume",
            cwd=tmp_path)
    assert p.returncode == 0 and "4 record(s) resumed" in p.stderr, p.stderr
    again = [json.loads(line) for line in (tmp_path / "c.jsonl").read_text().splitlines()[1:]]
    assert sorted((r["set"], r["class"]) for r in again) == sorted((r["set"], r["class"]) for r in recs)


def test_census_undecided_within_small_bounds_exits_3_and_lists_them(tmp_path):
    p = run("aperiodic", "census", "--tiles", "2", "--colors", "2", "--max-square", "1", "--max-period", "1",
            "--workers", "1", "-o", "c.jsonl", cwd=tmp_path)
    assert p.returncode == 3, p.stderr
    undecided = [line for line in p.stdout.splitlines() if line.startswith("undecided: ")]
    assert undecided and f"{len(undecided)} undecided" in p.stdout.splitlines()[0]


def test_census_bad_input(tmp_path):
    assert "give one of them" in one_line_error(run("aperiodic", "census", "--tiles", "2", "--colors", "2",
                                                    "--workers", "1", "--cluster", "tcp://127.0.0.1:1",
                                                    "-o", "c.jsonl", cwd=tmp_path))
    (tmp_path / "c.jsonl").write_text('{"format": "tilesolve/wang-census", "version": 1, "tiles": 3}\n')
    err = one_line_error(run("aperiodic", "census", "--tiles", "2", "--colors", "2", "-o", "c.jsonl", "--resume",
                             cwd=tmp_path))
    assert "is not a census of these sets and bounds" in err
    assert (tmp_path / "c.jsonl").read_text().startswith('{"format": "tilesolve/wang-census", "version": 1, "tiles": 3}')
    assert "more than" in one_line_error(run("aperiodic", "census", "--tiles", "8", "--colors", "4", "-o", "x.jsonl",
                                             cwd=tmp_path))
    assert not (tmp_path / "x.jsonl").exists()


@pytest.mark.slow
def test_census_stopped_by_its_time_limit_resumes_to_the_end(tmp_path):
    p = run("aperiodic", "census", "--tiles", "3", "--colors", "3", "--time-limit", "1", "-o", "c.jsonl", cwd=tmp_path)
    assert p.returncode == 3, p.stderr
    first = p.stdout.splitlines()[0]
    assert first.startswith("census of 461 sets") and not first.endswith("0 undecided, 0 not reached"), first
    p = run("aperiodic", "census", "--tiles", "3", "--colors", "3", "--resume", "-o", "c.jsonl", cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    resumed = int(p.stderr.split(" record(s) resumed")[0].split()[-1])
    assert resumed < 461
    assert p.stdout.splitlines()[0].endswith("263 finite, 198 periodic, 0 undecided, 0 not reached"), p.stdout


@pytest.mark.slow
def test_ctrl_c_keeps_the_records_and_says_so(tmp_path):
    import signal
    import subprocess
    import time

    from clitools import ENV, SCRIPT

    proc = subprocess.Popen([SCRIPT, "aperiodic", "census", "--tiles", "4", "--colors", "3", "-o", "c.jsonl"],
                            cwd=tmp_path, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, env=ENV)
    while not (tmp_path / "c.jsonl").exists() or not (tmp_path / "c.jsonl").read_text().count("\n"):
        assert proc.poll() is None, proc.stderr.read()
        time.sleep(0.05)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=300)
    assert proc.returncode == 130 and "Traceback" not in err
    assert err.strip().splitlines()[-1] == ("tilesolve: interrupted: the records decided so far are kept in c.jsonl; "
                                            "--resume continues")
    assert (tmp_path / "c.jsonl").read_text().count("\n") >= 1


def test_an_error_that_follows_ctrl_c_keeps_the_records_too(monkeypatch, tmp_path, capsys):
    """A Ctrl-C that surfaces as another exception (numpy turns one into a TypeError) still
    ends the census with its own message: the records are kept, --resume continues."""
    import os
    import signal
    import time

    from tilesolve.cli import group
    from tilesolve.families import aperiodic_census

    def census(*args, **kwargs):
        try:
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(60)
        except KeyboardInterrupt:
            raise TypeError("Cannot compare structured arrays unless they have a common dtype") from None

    monkeypatch.setattr(aperiodic_census, "census", census)
    monkeypatch.chdir(tmp_path)
    assert group.run(["aperiodic", "census", "--tiles", "2", "--colors", "2", "-o", "c.jsonl"]) == 130
    assert capsys.readouterr().err.strip().splitlines()[-1] == (
        "tilesolve: interrupted: the records decided so far are kept in c.jsonl; --resume continues")
    monkeypatch.setattr(aperiodic_census, "census", lambda *a, **k: 1 / 0)  # without a signal: a bug, exit 70
    assert group.run(["aperiodic", "census", "--tiles", "2", "--colors", "2", "-o", "c.jsonl"]) == 70
