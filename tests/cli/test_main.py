"""The command-line contract: the real ``tilesolve`` console script, run in a subprocess.

Other tools call these command forms, so the tests pin them: exit codes (0 sat, 1 unsat or
violations, 2 bad input, 3 unknown), one-line errors with no traceback and no output file,
the count as the last line of stdout, and the JSON file format.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from clitools import SCRIPT

from tilesolve.io import dappled_json
from tilesolve.model.dappled import DappledProblem
from tilesolve.model.solution import Solution, Status


def run(*args: str, cwd: Path, timeout: float = 120) -> subprocess.CompletedProcess:
    env = dict(os.environ, COLUMNS="100")
    return subprocess.run([SCRIPT, *args], cwd=cwd, capture_output=True, text=True, timeout=timeout, env=env)


def one_line_error(proc: subprocess.CompletedProcess) -> str:
    """Assert the process failed with exit 2 and exactly one `tilesolve: error:` line."""
    assert proc.returncode == 2, (proc.returncode, proc.stdout, proc.stderr)
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("tilesolve: error: "), proc.stderr
    assert "Traceback" not in proc.stderr
    return lines[0]


# A 4x3 tiling satisfying H0=2 and V1=2.
TILING = np.array([[0, 0, 1, 0], [1, 0, 0, 1], [0, 1, 1, 0]])


def _write_solution(path: Path, tiling=TILING) -> None:
    p = DappledProblem.from_strings("4x3", ["H0=2", "V1=2"])
    dappled_json.write_solution(path, p, Solution(Status.SAT, np.asarray(tiling), method="constructive", seed=1))


# ----------------------------------------------------------------------------- basics
@pytest.mark.slow
def test_version_and_help(tmp_path):
    proc = run("--version", cwd=tmp_path)
    assert proc.returncode == 0 and proc.stdout.startswith("tilesolve ")
    proc = run("--help", cwd=tmp_path)
    assert proc.returncode == 0
    for word in ("dappled", "verify", "export", "demo", "backends", "Exit codes"):
        assert word in proc.stdout


def _section(text: str, title: str) -> list[str]:
    """The command names of one section of a help text."""
    block = text.split(f"\n{title}:\n", 1)[1].split("\n\n", 1)[0]
    return [line.split()[0] for line in block.splitlines() if line.startswith("  ") and line[2] != " "]


@pytest.mark.slow
def test_help_lists_the_family_commands_then_the_tools(tmp_path):
    """The registry says which commands are a family's; they come first, in its order."""
    from tilesolve import family
    from tilesolve.cli.main import GENERIC

    out = run("--help", cwd=tmp_path).stdout
    assert out.index("Family commands:") < out.index("Tools:")
    # several families share a command group (``sample``): it is listed once, where it first comes
    want = list(dict.fromkeys(t.split(":")[1] for f in family.families() for t in f.commands))
    assert _section(out, "Family commands") == want
    assert _section(out, "Tools") == list(GENERIC)
    assert {"dappled", "brick", "pack", "tiling", "aperiodic"} <= set(_section(out, "Family commands"))


@pytest.mark.fast_cases(1)
@pytest.mark.parametrize(
    "command",
    [["dappled", "solve"], ["dappled", "count"], ["dappled", "crosscheck"], ["export", "dimacs"]],
)
def test_help_teaches(tmp_path, command):
    out = run(*command, "--help", cwd=tmp_path).stdout
    assert "Example:" in out and f"tilesolve {' '.join(command)} --size" in out
    assert "H0=2" in out and "H{0,2}=3" in out and "V1=inf" in out
    assert "Exit codes" in out and "bad input" in out


def test_verify_help(tmp_path):
    out = run("verify", "--help", cwd=tmp_path).stdout
    assert "Example:" in out and "tilesolve verify" in out and "Exit codes" in out


def test_backends(tmp_path):
    proc = run("backends", cwd=tmp_path)
    assert proc.returncode == 0, proc.stdout
    for name in ("cadical153", "rc2", "cp-sat"):
        assert name in proc.stdout
    assert "Exception" not in proc.stderr


# ----------------------------------------------------------------------------- verify
@pytest.mark.slow
def test_verify_valid_and_corrupted(tmp_path):
    good = tmp_path / "good.json"
    _write_solution(good)
    proc = run("verify", str(good), cwd=tmp_path)
    assert proc.returncode == 0 and proc.stdout.startswith("ok:"), proc.stdout + proc.stderr

    doc = json.loads(good.read_text())
    doc["tiling"][0][2] = 0  # row 0 becomes 0000: a horizontal run of 4 zeros
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(doc))
    proc = run("verify", str(bad), cwd=tmp_path)
    assert proc.returncode == 1
    assert "(row 0, col 2)" in proc.stdout and "(row 0, col 3)" in proc.stdout and "H0^2" in proc.stdout

    doc["tiling"][0][3] = 7  # a tile outside 0..1
    bad.write_text(json.dumps(doc))
    proc = run("verify", str(bad), cwd=tmp_path)
    assert proc.returncode == 1 and "tile 7 is not in 0..1" in proc.stdout


@pytest.mark.slow
def test_verify_bad_files(tmp_path):
    (tmp_path / "broken.json").write_text('{"format": "tilesolve/dappled-solution", ')
    assert "malformed JSON" in one_line_error(run("verify", "broken.json", cwd=tmp_path))
    (tmp_path / "other.json").write_text('{"format": "tilesolve/teapot", "version": 1}')
    assert "unknown format" in one_line_error(run("verify", "other.json", cwd=tmp_path))
    one_line_error(run("verify", "missing.json", cwd=tmp_path))
    dappled_json.write_problem(tmp_path / "problem.json", DappledProblem.from_strings("4x3", ["H0=2"]))
    assert "no solution" in one_line_error(run("verify", "problem.json", cwd=tmp_path))


# ----------------------------------------------------------------------------- bad input
BAD_INPUTS = {
    "zero size": ["--size", "0x5", "--cond", "H0=2"],
    "absurd size": ["--size", "100000x100000", "--cond", "H0=2"],
    "unreadable size": ["--size", "12", "--cond", "H0=2"],
    "unknown condition syntax": ["--size", "4x3", "--cond", "X0=2"],
    "condition on a missing tile": ["--size", "4x3", "--cond", "H5=2"],
    "one tile": ["--size", "4x3", "--cond", "H0=2", "--tiles", "1"],
    "bad count": ["--size", "4x3", "--cond", "H0=2", "--count", "1=many"],
    "partial tiling of wrong shape": ["--size", "4x3", "--cond", "H0=2", "--fix", "wrong-shape.txt"],
    "partial tiling with unknown tile": ["--size", "4x3", "--cond", "H0=2", "--fix", "unknown-tile.txt"],
    "partial tiling unreadable": ["--size", "4x3", "--cond", "H0=2", "--fix", "garbage.txt"],
    "malformed JSON problem": ["--problem", "broken.json"],
    "malformed JSON fix": ["--size", "4x3", "--cond", "H0=2", "--fix", "broken.json"],
    "missing file": ["--size", "4x3", "--cond", "H0=2", "--closest-to", "missing.txt"],
    "missing size": ["--cond", "H0=2"],
    "output directory missing": ["--size", "4x3", "--cond", "H0=2", "--svg", "nodir/x.svg"],
    "svg too large": ["--size", "1000x1000", "--cond", "H0=2", "--svg", "big.svg"],
    "png too large": ["--size", "10000x10000", "--cond", "H0=2", "--png", "big.png", "--repeat", "16"],
    "initial tiling of wrong shape": ["--size", "5x5", "--cond", "H0=2", "--initial", "wrong-shape.txt"],
}


@pytest.fixture
def inputs(tmp_path) -> Path:
    (tmp_path / "wrong-shape.txt").write_text("01?\n1.0\n")
    (tmp_path / "unknown-tile.txt").write_text("01?0\n1.02\n0000\n")
    (tmp_path / "garbage.txt").write_text("01?0\nhello\n")
    (tmp_path / "broken.json").write_text('{"format": "tilesolve/dappled-problem", "version": 1,')
    return tmp_path


@pytest.mark.fast_cases(1)
@pytest.mark.parametrize("case", sorted(BAD_INPUTS))
def test_bad_input_one_line_exit_2_no_file(inputs, case):
    before = sorted(os.listdir(inputs))
    proc = run("dappled", "solve", *BAD_INPUTS[case], "-o", "out.json", cwd=inputs)
    one_line_error(proc)
    assert sorted(os.listdir(inputs)) == before  # nothing written, not even a temp file


def test_bad_input_messages(inputs):
    msg = one_line_error(run("dappled", "solve", *BAD_INPUTS["partial tiling of wrong shape"], cwd=inputs))
    assert "wrong-shape.txt" in msg and "3x2" in msg and "4x3" in msg
    msg = one_line_error(run("dappled", "solve", *BAD_INPUTS["partial tiling with unknown tile"], cwd=inputs))
    assert "tile 2" in msg and "row 1, col 3" in msg
    msg = one_line_error(run("dappled", "solve", *BAD_INPUTS["unknown condition syntax"], cwd=inputs))
    assert "X0=2" in msg and "H0=2" in msg


@pytest.mark.parametrize("command", [["dappled", "count"], ["dappled", "crosscheck"]])
def test_other_commands_refuse_bad_input(tmp_path, command):
    one_line_error(run(*command, "--size", "0x5", "--cond", "H0=2", cwd=tmp_path))
    one_line_error(run(*command, "--size", "4x4", "--cond", "H0=two", cwd=tmp_path))


def test_export_refuses_bad_input(tmp_path):
    one_line_error(run("export", "dimacs", "--size", "4x4", "--cond", "H0=2", "-o", "nodir/t.cnf", cwd=tmp_path))
    one_line_error(run("export", "dimacs", "--size", "4x4", "--tiles", "1", "-o", "t.cnf", cwd=tmp_path))
    assert os.listdir(tmp_path) == []


@pytest.mark.slow
def test_usage_errors_exit_2(tmp_path):
    assert "--no-such-option" in one_line_error(run("dappled", "solve", "--size", "4x4", "--no-such-option",
                                                    cwd=tmp_path))
    msg = one_line_error(run("dappled", "solve", "--size", "4x4", "--method", "magic", cwd=tmp_path))
    assert "magic" in msg and "tilesolve dappled solve --help" in msg
    assert "--time-limit" in one_line_error(run("dappled", "count", "--size", "4x4", "--time-limit", "0", cwd=tmp_path))
    assert "FILE" in one_line_error(run("verify", cwd=tmp_path))


# ----------------------------------------------------------------------------- contract (uses the solvers)
@pytest.mark.slow
def test_solve_contract(tmp_path):
    proc = run("dappled", "solve", "--size", "12x8", "--cond", "H0=2", "--cond", "V1=3", "--seed", "3",
               "-o", "t.json", "--svg", "t.svg", "--png", "t.png", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert "sat" in proc.stderr and "t.json" in proc.stderr
    doc = json.loads((tmp_path / "t.json").read_text())
    assert doc["format"] == "tilesolve/dappled-solution" and doc["version"] == 1
    assert doc["status"] == "sat" and doc["seed"] == 3 and doc["cyclic"] is False
    assert doc["size"] == {"rows": 8, "cols": 12} and doc["conditions"] == ["H0=2", "V1=3"]
    assert np.asarray(doc["tiling"]).shape == (8, 12)
    assert (tmp_path / "t.svg").read_text().startswith("<?xml")
    assert (tmp_path / "t.png").read_bytes().startswith(b"\x89PNG")
    assert run("verify", "t.json", cwd=tmp_path).returncode == 0
    again = run("dappled", "solve", "--size", "12x8", "--cond", "H0=2", "--cond", "V1=3", "--seed", "3",
                "-o", "u.json", cwd=tmp_path)
    assert again.returncode == 0
    assert json.loads((tmp_path / "u.json").read_text())["tiling"] == doc["tiling"]  # same seed, same tiling


@pytest.mark.fast_cases(1)
@pytest.mark.parametrize("method", ["constructive", "sat", "maxsat", "cpsat"])
def test_solve_methods(tmp_path, method):
    args = ["--size", "6x5", "--cond", "H0=2,V1=2", "--cyclic", "--method", method, "-o", "t.json", "--seed", "1"]
    if method == "maxsat":
        (tmp_path / "target.txt").write_text("000000\n" * 5)
        args += ["--closest-to", "target.txt"]
    proc = run("dappled", "solve", *args, cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert json.loads((tmp_path / "t.json").read_text())["method"] == method
    assert run("verify", "t.json", cwd=tmp_path).returncode == 0


def test_solve_fix_count_and_text_output(tmp_path):
    (tmp_path / "fix.txt").write_text("1?????\n??????\n?????0\n")
    proc = run("dappled", "solve", "--size", "6x3", "--cond", "H0=2,V1=2", "--fix", "fix.txt",
               "--count", "1=8..10", "--seed", "2", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    grid = dappled_json.parse_text_grid(proc.stdout)
    assert grid.shape == (3, 6) and grid[0, 0] == 1 and grid[2, 5] == 0 and 8 <= grid.sum() <= 10


@pytest.mark.slow
def test_solve_unsat(tmp_path):
    proc = run("dappled", "solve", "--size", "3x1", "--cond", "H0=1,H1=1", "--count", "1=3", "-o", "u.json",
               cwd=tmp_path)
    assert proc.returncode == 1, proc.stderr
    assert "unsat" in proc.stderr and "why:" in proc.stderr
    doc = json.loads((tmp_path / "u.json").read_text())
    assert doc["status"] == "unsat" and doc["tiling"] is None
    assert run("verify", "u.json", cwd=tmp_path).returncode == 1


def test_solve_cyclic_repeat_svg(tmp_path):
    proc = run("dappled", "solve", "--size", "8x8", "--cond", "H0=3,V0=3,H1=3,V1=3", "--cyclic",
               "--svg", "c.svg", "--repeat", "2", "--no-grid", "--seed", "5", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "c.svg").read_text().count("<use") == 4


def test_solve_json_to_stdout_and_quiet(tmp_path):
    proc = run("-q", "dappled", "solve", "--size", "5x4", "--cond", "H0=2,V1=2", "-o", "-", cwd=tmp_path)
    assert proc.returncode == 0 and proc.stderr == ""
    assert json.loads(proc.stdout)["format"] == "tilesolve/dappled-solution"


@pytest.mark.slow
def test_solve_problem_file(tmp_path):
    dappled_json.write_problem(tmp_path / "p.json", DappledProblem.from_strings("7x5", ["H0=2", "V1=2"], n_tiles=3))
    proc = run("dappled", "solve", "--problem", "p.json", "-o", "t.json", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert json.loads((tmp_path / "t.json").read_text())["n_tiles"] == 3
    one_line_error(run("dappled", "solve", "--problem", "p.json", "--size", "3x3", cwd=tmp_path))


@pytest.mark.slow
def test_count_last_line(tmp_path):
    # Remark 1.4: T = {0, 1}, L = {H0=2, V1=2} on 3x3 has 174 tilings (OEIS A206994).
    proc = run("dappled", "count", "--size", "3x3", "--cond", "H0=2", "--cond", "V1=2", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.strip().splitlines()[-1] == "174"
    proc = run("dappled", "count", "--size", "3x3", "--cond", "H0=2,V1=2", "--method", "enumerate", cwd=tmp_path)
    assert proc.stdout.strip().splitlines()[-1] == "174"


@pytest.mark.slow
def test_crosscheck(tmp_path):
    proc = run("dappled", "crosscheck", "--size", "4x4", "--cond", "H0=2", "--cond", "V1=2", "--seed", "1",
               "--trials", "2", cwd=tmp_path)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "trial 2/2" in proc.stdout and "FAIL" not in proc.stdout


@pytest.mark.parametrize("suffix", ["cnf", "wcnf"])
def test_export_dimacs(tmp_path, suffix):
    args = ["export", "dimacs", "--size", "4x4", "--cond", "H0=2,V1=2", "--cyclic", "-o", f"t.{suffix}"]
    if suffix == "wcnf":
        (tmp_path / "target.txt").write_text("0000\n" * 4)
        args += ["--closest-to", "target.txt"]
    proc = run(*args, cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    text = (tmp_path / f"t.{suffix}").read_text()
    assert text.startswith("c ") and ("p cnf 16 32" in text if suffix == "cnf" else "p wcnf" in text or "h " in text)


@pytest.mark.slow
def test_export_needs_matching_suffix(tmp_path):
    (tmp_path / "target.txt").write_text("0000\n" * 4)
    one_line_error(run("export", "dimacs", "--size", "4x4", "--cond", "H0=2", "--closest-to", "target.txt",
                       "-o", "t.cnf", cwd=tmp_path))
    one_line_error(run("export", "dimacs", "--size", "4x4", "--cond", "H0=2", "-o", "t.wcnf", cwd=tmp_path))


@pytest.mark.slow
def test_demo(tmp_path):
    proc = run("demo", "--out", "pics", cwd=tmp_path, timeout=300)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    svgs = sorted(p.name for p in (tmp_path / "pics").glob("*.svg"))
    assert {"plain.svg", "cyclic.svg", "nonuniform.svg", "closest.svg", "three-tiles.svg"} <= set(svgs)
    for js in (tmp_path / "pics").glob("*.json"):
        assert run("verify", str(js), cwd=tmp_path).returncode == 0


def test_demo_of_one_family(tmp_path):
    """The fast tier's demo: one family's showcase (all of them: test_demo, slow)."""
    proc = run("demo", "--family", "aperiodic", "--out", "pics", cwd=tmp_path, timeout=300)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert sorted(p.suffix for p in (tmp_path / "pics").iterdir()) == [".json", ".svg"]
    assert run("verify", str(next((tmp_path / "pics").glob("*.json"))), cwd=tmp_path).returncode == 0


# ----------------------------------------------------------------------------- in-process (click runner)
def test_interrupt_exits_130_without_files(tmp_path, monkeypatch):
    from tilesolve.families import dappled
    from tilesolve.cli.main import main_group

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(dappled, "solve", interrupted)
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(main_group, ["dappled", "solve", "--size", "4x4", "--cond", "H0=2",
                                             "-o", "t.json", "--svg", "t.svg"])
    assert result.exit_code == 130
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("cause, code", [(KeyboardInterrupt(), 130), (ValueError("a bug"), 70)])
def test_ctrl_c_inside_a_compiled_kernel_exits_130(tmp_path, monkeypatch, cause, code):
    """Ctrl-C while a numba kernel runs comes back as a SystemError caused by KeyboardInterrupt:
    an interruption (130), where a SystemError of another cause is a bug (70)."""
    from tilesolve.families import dappled
    from tilesolve.cli.main import main_group

    def kernel(*args, **kwargs):
        raise SystemError("CPUDispatcher(<function kernel>) returned a result with an exception set") from cause

    monkeypatch.setattr(dappled, "solve", kernel)
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(main_group, ["dappled", "solve", "--size", "4x4", "--cond", "H0=2", "-o", "t.json"])
    assert result.exit_code == code
    assert ("interrupted" in result.output) == (code == 130) and "Traceback" not in result.output
    assert os.listdir(tmp_path) == []


def test_interrupted_solution_exits_130_and_keeps_old_files(tmp_path, monkeypatch):
    """The engine returns Ctrl-C inside a solver as an unknown solution; the CLI writes nothing."""
    from tilesolve.families import dappled
    from tilesolve.cli.main import main_group

    monkeypatch.setattr(dappled, "solve", lambda *a, **k: Solution(Status.UNKNOWN, None, method="sat",
                                                                   reason="interrupted (Ctrl-C)"))
    monkeypatch.chdir(tmp_path)
    Path("t.json").write_text("earlier result")
    result = CliRunner().invoke(main_group, ["dappled", "solve", "--size", "4x4", "--cond", "H0=2",
                                             "-o", "t.json", "--svg", "t.svg"])
    assert result.exit_code == 130
    assert "interrupted (no file was written)" in result.output
    assert os.listdir(tmp_path) == ["t.json"] and Path("t.json").read_text() == "earlier result"


def test_unknown_status_exit_3(tmp_path, monkeypatch):
    from tilesolve.families import dappled
    from tilesolve.cli.main import main_group

    monkeypatch.setattr(dappled, "solve", lambda *a, **k: Solution(Status.UNKNOWN, None, method="sat",
                                                                   reason="time limit 1 s reached"))
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(main_group, ["dappled", "solve", "--size", "4x4", "--cond", "H0=2",
                                             "--time-limit", "1", "-o", "t.json", "--svg", "t.svg"])
    assert result.exit_code == 3
    assert "time limit" in result.output
    assert os.listdir(tmp_path) == ["t.json"]  # the result is recorded; no picture without a tiling
    assert json.loads((tmp_path / "t.json").read_text())["status"] == "unknown"


def test_library_error_during_solve_is_one_line(tmp_path, monkeypatch):
    from tilesolve.families import dappled
    from tilesolve.cli.main import main_group
    from tilesolve.errors import MethodNotApplicable

    def refuse(*a, **k):
        raise MethodNotApplicable("the constructive route needs ...; use method 'sat'")

    monkeypatch.setattr(dappled, "solve", refuse)
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(main_group, ["dappled", "solve", "--size", "4x4", "--cond", "H0=2", "-o", "t.json"])
    assert result.exit_code == 2
    assert result.output.strip() == "tilesolve: error: the constructive route needs ...; use method 'sat'"
    assert os.listdir(tmp_path) == []


def test_split_conditions():
    from tilesolve.cli.common import split_conditions

    assert split_conditions(["H0=2, V{0, 1}=3 H1=2", "V1=inf"]) == ["H0=2", "V{0, 1}=3", "H1=2", "V1=inf"]
    assert split_conditions(["H{0,2}=3,V1=2"]) == ["H{0,2}=3", "V1=2"]


def test_time_limit_counts_from_the_start_of_the_command(tmp_path, monkeypatch):
    """A --time-limit covers the whole command: the run's clock starts where the command started
    (for the console script, the process's start), not where the run begins. A command said to
    have started 100 s ago is out of its 50 s at once; one that started now is not; and the next
    run in this process counts from its own beginning again."""
    import time

    from tilesolve.cli.group import run as run_in_process
    from tilesolve.deadline import run_start

    monkeypatch.chdir(tmp_path)
    args = ["dappled", "solve", "--size", "8x8", "--cond", "H0=2,V1=2", "--method", "sat", "--time-limit", "50",
            "-o", "t.json"]
    assert run_in_process(args, started=time.perf_counter() - 100) == 3
    doc = json.loads((tmp_path / "t.json").read_text())
    assert doc["status"] == "unknown" and "time limit of 50 s reached" in doc["reason"]
    assert doc["time_s"] >= 100
    assert run_in_process(args, started=time.perf_counter()) == 0
    assert json.loads((tmp_path / "t.json").read_text())["status"] == "sat"
    before = time.perf_counter()
    assert run_start() >= before  # the command's start is not left behind for a later run


def test_the_console_script_ends_as_the_interpreter_would(tmp_path):
    """The console script leaves its process without the interpreter's teardown, but only after
    what the interpreter does first at exit: threads that are not daemons finish, atexit
    handlers run, stdout is flushed, and the exit code is the command's."""
    code = ("import atexit, sys, threading, time\n"
            "atexit.register(lambda: print('atexit ran'))\n"
            "threading.Thread(target=lambda: (time.sleep(0.2), open('thread.txt', 'w').write('done'))).start()\n"
            "from tilesolve.cli.main import main\n"
            "sys.argv = ['tilesolve', 'dappled', 'count', '--size', '3x3', '--cond', 'H0=2', '--cond', 'V1=2']\n"
            "sys.exit(main())\n")
    proc = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.splitlines()[-2:] == ["174", "atexit ran"]
    assert (tmp_path / "thread.txt").read_text() == "done"
    proc = subprocess.run([sys.executable, "-c", code.replace("V1=2'", "V1=2', '--time-limit', 'x'")], cwd=tmp_path,
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 2 and proc.stdout.splitlines() == ["atexit ran"]
