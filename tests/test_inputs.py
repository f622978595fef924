"""Readers read within a limit, refuse files that contradict their format, relabel colours
compactly, size a CNF before encoding it, and turn a bug into one line (issue 17, part 4).
Every promise runs through the console script."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from clitools import ENV, SCRIPT, one_line_error, run

from tilesolve.inputs import DEFAULT_MAX_INPUT


def test_endless_inputs_stop_at_the_input_limit(tmp_path):
    env = dict(ENV, TILESOLVE_MAX_INPUT="1M")
    zero = subprocess.run([SCRIPT, "verify", "/dev/zero"], capture_output=True, text=True, env=env, timeout=300)
    assert "larger than the input limit of 1 MiB" in one_line_error(zero)
    yes = subprocess.Popen(["yes"], stdout=subprocess.PIPE)
    try:
        piped = subprocess.run([SCRIPT, "verify", "/dev/stdin"], stdin=yes.stdout, capture_output=True, text=True,
                               env=env, timeout=300)
    finally:
        yes.kill()
        yes.wait()
    assert "TILESOLVE_MAX_INPUT" in one_line_error(piped)


@pytest.mark.slow
def test_the_limit_is_documented_and_can_be_raised(tmp_path):
    run("-q", "dappled", "solve", "--size", "6x4", "--cond", "H0=2", "--seed", "1", "-o", "t.json", cwd=tmp_path)
    size = (tmp_path / "t.json").stat().st_size
    assert size > 256
    assert "--max-input" in one_line_error(run("--max-input", "256", "verify", "t.json", cwd=tmp_path))
    assert run("--max-input", "1M", "verify", "t.json", cwd=tmp_path).returncode == 0
    assert "--max-input" in one_line_error(run("--max-input", "lots", "verify", "t.json", cwd=tmp_path))
    assert DEFAULT_MAX_INPUT == 256 << 20  # the help's figure
    for command in (["verify"], ["aperiodic", "verify"], ["wang", "count"], ["export", "dimacs"], ["draw"],
                    ["dappled", "solve"], ["wang", "solve"]):
        text = " ".join(run(*command, "--help", cwd=tmp_path).stdout.split())
        assert "read up to 256 MiB" in text and "TILESOLVE_MAX_INPUT" in text, command
    assert "--max-input" in run("--help", cwd=tmp_path).stdout


@pytest.mark.slow
def test_a_file_that_contradicts_its_format_is_refused(tmp_path):
    (tmp_path / "short.txt").write_text("3 4 2 2\n1 1 2 1\n2 4 3 1\n")  # header: 3 tiles; 2 follow
    line = one_line_error(run("wang", "count", "--tiles", "short.txt", "--board", "rect:2x2", cwd=tmp_path))
    assert "announcing 3 tiles" in line and "--format" in line
    line = one_line_error(run("wang", "count", "--tiles", "short.txt", "--format", "tilesat", "--board", "rect:2x2",
                              cwd=tmp_path))
    assert "announces 3 tiles, the file has 2" in line
    said = run("wang", "count", "--tiles", "short.txt", "--format", "nswe", "--board", "rect:1x1", cwd=tmp_path)
    assert said.returncode == 0 and said.stdout.split()[-1] == "3"  # the user said nswe: three tiles
    (tmp_path / "cut.rtlb").write_text("[(0, 0, 1, 0), (1, 3, 2, 0), (2, 0")
    assert "truncated" in one_line_error(run("wang", "count", "--tiles", "cut.rtlb", "--board", "rect:2x2",
                                             cwd=tmp_path))
    (tmp_path / "open.rtlb").write_text("[(0, 0, 1, 0), (1, 3, 2, 0)")
    assert "do not close" in one_line_error(run("wang", "count", "--tiles", "open.rtlb", "--board", "rect:2x2",
                                                cwd=tmp_path))


@pytest.mark.slow
def test_colours_are_relabelled_compactly(tmp_path):
    (tmp_path / "big.tiles").write_text("0 0 1 0\n1 3 2 0\n2 0 2 99999992\n")
    proc = run("wang", "count", "--tiles", "big.tiles", "--board", "rect:2x2", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert "99999992 -> 4" in proc.stderr and "5 colours" in proc.stderr
    (tmp_path / "small.tiles").write_text("0 0 1 0\n1 3 2 0\n2 0 2 4\n")
    same = run("wang", "count", "--tiles", "small.tiles", "--board", "rect:2x2", cwd=tmp_path)
    assert same.stdout.split()[-1] == proc.stdout.split()[-1] and "relabelled" not in same.stderr
    doc = {"format": "tilesolve/wang-tileset", "version": 1, "colors": 10**9, "tiles": [[0, 1, 0, 1], [1, 0, 1, 0]]}
    (tmp_path / "wide.json").write_text(json.dumps(doc))
    proc = run("wang", "count", "--tiles", "wide.json", "--board", "rect:2x2", cwd=tmp_path)
    assert proc.returncode == 0 and "2 colours" in proc.stderr


@pytest.mark.slow
def test_export_sizes_the_cnf_before_encoding(tmp_path):
    line = one_line_error(run("export", "dimacs", "--size", "2048x2048", "--tiles", "10", "--cond", "H0=2",
                              "-o", "big.cnf", cwd=tmp_path))
    assert "GiB of DIMACS text" in line and "--max-cnf" in line
    assert not (tmp_path / "big.cnf").exists()
    args = ("export", "dimacs", "--size", "8x8", "--tiles", "3", "--cond", "H0=2", "-o", "s.cnf")
    assert "--max-cnf 1.0 KiB" in one_line_error(run(*args, "--max-cnf", "1K", cwd=tmp_path))
    assert run(*args, cwd=tmp_path).returncode == 0 and (tmp_path / "s.cnf").exists()


def test_a_bug_is_one_internal_error_line_exit_70(tmp_path):
    """An unexpected exception (here forced into verify) is exit 70 with one line, no traceback."""
    code = ("import sys, tilesolve.family as f\n"
            "def broken(*args, **kwargs): raise ZeroDivisionError('forced')\n"
            "f.verify_file = broken\n"
            "from tilesolve.cli.main import main\n"
            "sys.exit(main(['verify', 'x.json']))\n")
    proc = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True, timeout=300)
    line = one_line_error(proc, 70)
    assert line == "tilesolve: error: internal error: ZeroDivisionError: forced; please report this"
    assert "70" in run("verify", "--help", cwd=tmp_path).stdout


@pytest.mark.slow
def test_proof_files_and_sweep_caches_are_read_through_the_limit(tmp_path):
    """A DRAT proof past the input limit is not read (the unsat claim is not confirmed, exit 1);
    a sweep cache past it is one error line (exit 2), as any other input."""
    assert run("-q", "dappled", "solve", "--size", "3x3", "--cond", "H0=1", "--count", "1=0", "-o", "u.json",
               "--proof-dir", "proofs", cwd=tmp_path).returncode == 1
    assert run("verify", "u.json", "--proof-dir", "proofs", cwd=tmp_path).returncode == 0
    (proof,) = (tmp_path / "proofs").glob("*.drat")
    with open(proof, "ab") as fh:
        fh.write(b"c padding\n" * 200_000)  # 2 MB: over a 1 MiB limit
    big = run("--max-input", "1M", "verify", "u.json", "--proof-dir", "proofs", cwd=tmp_path)
    assert big.returncode == 1 and "Traceback" not in big.stderr
    assert "NOT confirmed" in big.stdout and "larger than the input limit of 1 MiB" in big.stdout
    (tmp_path / "c.jsonl").write_text("[" * 100_000 + "\n")  # a forged line nested past the parser
    assert run("aperiodic", "check", "--builtin", "finite-jv7", "--max-period", "2", "--workers", "1", "--cache",
               "c.jsonl", "-o", "r.json", cwd=tmp_path).returncode == 0
    (tmp_path / "r.json").unlink()
    (tmp_path / "c.jsonl").write_text("x" * (2 << 20))
    cached = run("--max-input", "1M", "aperiodic", "check", "--builtin", "finite-jv7", "--max-period", "2",
                 "--workers", "1", "--cache", "c.jsonl", "-o", "r.json", cwd=tmp_path)
    assert "larger than the input limit of 1 MiB" in one_line_error(cached)
    assert not (tmp_path / "r.json").exists()
