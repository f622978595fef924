"""Where a command's results go, and what an interruption leaves: the real console script.

The contract (README, "Exit codes"; DESIGN.md, "Files"): without an output option the
result is printed; ``-`` is standard output; every output is checked before any work and
all of them are written, or none; devices and FIFOs are written, never replaced; Ctrl-C
exits 130 and SIGTERM 143 leaving existing files as they were and no temporary behind; a
time limit writes its ``unknown`` record (exit 3).
"""

from __future__ import annotations

import json
import os
import select
import signal
import stat
import subprocess
import threading
import time
from pathlib import Path

import pytest
from clitools import ENV, SCRIPT, one_line_error, run, snapshot

posix_only = pytest.mark.skipif(os.name != "posix", reason="signals, FIFOs and ptys are POSIX")


# ----------------------------------------------------------------------------- printed results (defect 5)
@pytest.mark.fast_cases(1)
@pytest.mark.parametrize("args", [
    ["brick", "solve", "--board", "rect:5x3", "--seed", "2"],
    ["brick", "wall", "--size", "5x3", "--max-line", "2", "--seed", "2"],
    ["wang", "solve", "--tiles", "tiles.json", "--board", "rect:5x3", "--boundary", "free", "--seed", "2"],
])
def test_board_commands_print_the_tiling_without_outputs(tmp_path, args):
    (tmp_path / "tiles.json").write_text(json.dumps({"colors": 2, "tiles": [[0, 0, 0, 0], [1, 0, 1, 0]]}))
    printed = run(*args, cwd=tmp_path)
    assert printed.returncode == 0, printed.stderr
    saved = run(*args, "-o", "t.json", cwd=tmp_path)
    assert saved.returncode == 0 and saved.stdout == "", saved.stderr
    tiles = json.loads((tmp_path / "t.json").read_text())["tiles"]
    rows = [line.split() for line in printed.stdout.splitlines()]
    assert len(rows) == 3 and all(len(r) == 5 for r in rows)
    assert [[int(d) for d in cell] for row in rows for cell in row] == tiles  # N E S W per cell, row-major
    assert "N E S W" in printed.stderr


@pytest.mark.parametrize("command", [["brick", "solve"], ["brick", "wall"], ["wang", "solve"]])
def test_board_help_names_only_real_outputs(tmp_path, command):
    out = run(*command, "--help", cwd=tmp_path).stdout
    assert "--png" not in out and "printed as text" in out


# ----------------------------------------------------------------------------- '-' is stdout (defect 10)
@pytest.mark.fast_cases(1)
@pytest.mark.parametrize("args,start", [
    (["dappled", "solve", "--size", "4x3", "--cond", "H0=2", "--seed", "1", "-o", "-"], '"format"'),
    (["dappled", "solve", "--size", "4x3", "--cond", "H0=2", "--seed", "1", "--svg", "-"], "<svg"),
    (["dappled", "solve", "--size", "4x3", "--cond", "H0=2", "--seed", "1", "--png", "-"], "\ufffdPNG"),
    (["brick", "solve", "--board", "rect:3x2", "--seed", "1", "--svg", "-"], "<svg"),
    (["pack", "--kind", "corner", "--colors", "3", "--method", "euler", "-o", "-"], '"format"'),
    (["pack", "--kind", "corner", "--colors", "3", "--dimacs", "-"], "c "),
    (["tiles", "--kind", "wang", "--colors", "2", "--svg", "-"], "<svg"),
    (["export", "dimacs", "--size", "4x3", "--cond", "H0=2", "-o", "-"], "c "),
])
def test_dash_is_stdout(tmp_path, args, start):
    proc = subprocess.run([SCRIPT, *args], cwd=tmp_path, capture_output=True, timeout=300, env=ENV)
    assert proc.returncode == 0, proc.stderr
    assert start in proc.stdout.decode("utf-8", "replace")[:100]
    assert os.listdir(tmp_path) == []


def test_two_outputs_cannot_share_stdout_or_a_file(tmp_path):
    base = ["dappled", "solve", "--size", "4x3", "--cond", "H0=2"]
    assert "standard output" in one_line_error(run(*base, "-o", "-", "--svg", "-", cwd=tmp_path))
    os.symlink("a.svg", tmp_path / "a.png")  # one file by two names, each with its format's suffix
    assert "named twice" in one_line_error(run(*base, "--svg", "a.svg", "--png", "a.png", cwd=tmp_path))
    assert os.listdir(tmp_path) == ["a.png"]


# ----------------------------------------------------------------------------- all or nothing (defect 9)
def test_unwritable_second_output_is_refused_before_solving(tmp_path):
    msg = one_line_error(run("pack", "--kind", "corner", "--colors", "4", "-o", "out.json", "--svg", "/proc/x.svg",
                             cwd=tmp_path))
    assert "/proc/x.svg" in msg and ".part" not in msg
    assert os.listdir(tmp_path) == []


@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="needs /dev/full")
def test_a_failed_write_leaves_no_file_of_the_run(tmp_path):
    (tmp_path / "old.json").write_text("precious")
    before = snapshot(tmp_path)
    msg = one_line_error(run("dappled", "solve", "--size", "4x3", "--cond", "H0=2", "--seed", "1",
                             "-o", "old.json", "--svg", "new.svg", "--png", "/dev/full", cwd=tmp_path))
    assert "space" in msg and ".part" not in msg
    assert snapshot(tmp_path) == before
    assert stat.S_ISCHR(os.stat("/dev/full").st_mode)


# ----------------------------------------------------------------------------- devices and FIFOs (defect 11)
@posix_only
def test_fifo_output_is_written_not_replaced(tmp_path):
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    got = {}

    def reader():
        with open(fifo, "rb") as f:
            got["data"] = f.read()

    t = threading.Thread(target=reader)
    t.start()
    proc = run("dappled", "solve", "--size", "4x3", "--cond", "H0=2", "--seed", "1", "-o", str(fifo), cwd=tmp_path)
    t.join(timeout=60)
    assert proc.returncode == 0, proc.stderr
    assert stat.S_ISFIFO(os.stat(fifo).st_mode)
    assert json.loads(got["data"])["status"] == "sat"
    assert sorted(os.listdir(tmp_path)) == ["pipe"]


def test_devices_are_written_directly(tmp_path):
    from tilesolve.io import atomic

    # Checked without writing: a regression would replace the machine's /dev/null.
    assert atomic._is_direct(os.devnull) and atomic._is_direct("-")
    assert not atomic._is_direct(str(tmp_path / "new.json"))


# ----------------------------------------------------------------------------- interruptions (defects 7, 16)
def _interrupt(args: list[str], cwd: Path, sig: int) -> tuple[int, str]:
    """Start ``tilesolve ARGS`` with stderr on a terminal, send ``sig`` once its progress line
    shows that the solver runs, and return (exit code, stderr)."""
    import pty

    master, slave = pty.openpty()
    proc = subprocess.Popen([SCRIPT, *args], cwd=cwd, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                            stderr=slave, env=ENV)
    os.close(slave)
    out = b""
    try:
        while b"solving with" not in out:  # the progress line: "family: solving with 'route' [00:00]"
            ready, _, _ = select.select([master], [], [], 120)
            assert ready, f"no progress line: {out!r}"
            try:
                out += os.read(master, 4096)
            except OSError:  # the terminal closed: the process ended before its search
                raise AssertionError(f"exit {proc.wait()} before the search: {out!r}") from None
        proc.send_signal(sig)
        code = proc.wait(timeout=300)
        while True:
            try:
                chunk = os.read(master, 4096)
            except OSError:  # the terminal closed with the process
                break
            if not chunk:
                break
            out += chunk
    finally:
        if proc.poll() is None:
            proc.kill()
        os.close(master)
    return code, out.decode("utf-8", "replace")


#: Searches that run for minutes (a corner packing over 4 colours by plain SAT; a 10^6-cell grid).
HARD = {
    "pack": ["pack", "--kind", "corner", "--colors", "4", "--method", "sat", "--workers", "1", "--seed", "1"],
    "dappled": ["dappled", "solve", "--size", "1000x1000", "--cond", "H0=2,V1=2,V0=3,H1=3", "--method", "sat",
                "--seed", "1"],
}
PICTURE = {"pack": "--svg", "dappled": "--png"}


@pytest.mark.slow
@posix_only
@pytest.mark.parametrize("sig,code,word", [(signal.SIGINT, 130, "interrupted"), (signal.SIGTERM, 143, "terminated")])
@pytest.mark.parametrize("command", sorted(HARD))
def test_interruption_writes_nothing(tmp_path, command, sig, code, word):
    (tmp_path / "out.json").write_text("the result of an earlier run")
    before = snapshot(tmp_path)
    picture = "picture." + PICTURE[command].lstrip("-")
    got, err = _interrupt(HARD[command] + ["-o", "out.json", PICTURE[command], picture], tmp_path, sig)
    assert got == code, err
    assert f"tilesolve: {word} (no file was written)" in err and "Traceback" not in err
    assert snapshot(tmp_path) == before  # out.json untouched, no picture, no temporary


@pytest.mark.slow
def test_time_limit_writes_the_unknown_record(tmp_path):
    proc = run(*HARD["pack"], "--time-limit", "1", "-o", "out.json", cwd=tmp_path)
    assert proc.returncode == 3, proc.stderr
    assert json.loads((tmp_path / "out.json").read_text())["status"] == "unknown"
    assert sorted(os.listdir(tmp_path)) == ["out.json"]


def test_stale_temporaries_of_dead_writers_are_swept(tmp_path):
    from tilesolve.io import atomic

    dead = subprocess.Popen(["true"])
    dead.wait()
    old = time.time() - 2 * atomic.STALE_AFTER_S
    names = {"stale": f".out.json.{dead.pid}.abc123.part", "recent": f".out.json.{dead.pid}.def456.part",
             "alive": f".out.json.{os.getpid()}.ghi789.part", "other": f".other.json.{dead.pid}.jkl012.part"}
    for key, name in names.items():
        (tmp_path / name).write_text("x")
        if key != "recent":
            os.utime(tmp_path / name, (old, old))
    atomic.write_text_atomic(tmp_path / "out.json", "new")
    assert sorted(os.listdir(tmp_path)) == sorted(["out.json", names["recent"], names["alive"], names["other"]])


def test_temporary_names_carry_the_writer_pid(tmp_path):
    from tilesolve.io import atomic

    with atomic.atomic_write(tmp_path / "a.txt") as f:
        f.write("x")
        (part,) = [p for p in os.listdir(tmp_path) if p.endswith(".part")]
    assert part.startswith(f".a.txt.{os.getpid()}.")
    assert os.listdir(tmp_path) == ["a.txt"]


@posix_only
def test_a_symbolic_link_is_followed_not_replaced(tmp_path):
    from tilesolve.io import atomic

    (tmp_path / "real.txt").write_text("old")
    (tmp_path / "link.txt").symlink_to("real.txt")
    atomic.write_text_atomic(tmp_path / "link.txt", "new")
    assert (tmp_path / "link.txt").is_symlink() and (tmp_path / "real.txt").read_text() == "new"


# ----------------------------------------------------------------------------- suffixes (issue 22)
def _commands():
    """``(command words, click command)`` of every command, found by walking the command tree."""
    import click

    from tilesolve.cli.group import main_group

    def walk(cmd, path):
        if isinstance(cmd, click.Group):
            ctx = click.Context(cmd)
            for name in cmd.list_commands(ctx):
                yield from walk(cmd.get_command(ctx, name), [*path, name])
        else:
            yield " ".join(path), cmd

    return list(walk(main_group, []))


def _output_options() -> list[tuple[str, str, tuple[str, ...]]]:
    """``(command, option, formats)`` of every option whose type is an output file
    (:class:`tilesolve.cli.outputs.OutputFile`)."""
    from tilesolve.cli.outputs import OutputFile

    return [(path, p.opts[0], p.type.formats) for path, cmd in _commands() for p in cmd.params
            if isinstance(p.type, OutputFile)]


OUTPUT_OPTIONS = _output_options()
_WRITERS = {"-o", "--output", "--svg", "--png", "--dimacs", "--atlas"}


def test_every_output_option_is_an_output_file():
    """Each command's every option that names a written file checks its suffix."""
    import click

    checked = {(c, o) for c, o, _ in OUTPUT_OPTIONS}
    missing = [(path, p.opts) for path, cmd in _commands() for p in cmd.params
               if isinstance(p, click.Option) and _WRITERS & set(p.opts) and (path, p.opts[0]) not in checked]
    assert not missing
    assert len(OUTPUT_OPTIONS) >= 30 and {"draw", "tiles", "wall", "wall-lines", "render texture"} <= {
        c for c, _, _ in OUTPUT_OPTIONS}


@pytest.mark.fast_cases(3)
@pytest.mark.parametrize("command,option,formats", OUTPUT_OPTIONS, ids=[f"{c} {o}" for c, o, _ in OUTPUT_OPTIONS])
def test_every_output_option_refuses_another_format(tmp_path, command, option, formats):
    """``--svg c3.png``, ``--png x.svg``, ``-o x.txt``: one line, exit 2, no file, through the script."""
    wrong = next(s for s in ("png", "svg", "txt") if s not in formats)
    err = one_line_error(run(*command.split(), option, f"out.{wrong}", cwd=tmp_path))
    assert f"cannot write out.{wrong}: " in err and " or ".join(f".{f}" for f in formats) in err
    assert snapshot(tmp_path) == {}


@pytest.mark.parametrize("args,bad", [
    (["tiles", "--kind", "wang", "--colors", "3", "--svg", "c3.png"], "c3.png"),
    (["wall-lines", "--max-line", "2", "--size", "8x8", "--samples", "1", "--png", "lines.svg"], "lines.svg"),
    (["wall", "--region", "0,0,8x8", "--max-line", "2", "--png", "x.jpg"], "x.jpg"),
    (["wall-lines", "--max-line", "2", "--size", "8x8", "--samples", "1", "-o", "lines.txt"], "lines.txt"),
    (["draw", "t.json", "-o", "t.jpg"], "t.jpg"),
])
def test_whole_commands_refuse_a_suffix_of_another_format(tmp_path, args, bad):
    """The commands of issue 22, complete: refused as draw refuses them, before any work."""
    (tmp_path / "t.json").write_text("{}")
    before = snapshot(tmp_path)
    err = one_line_error(run(*args, cwd=tmp_path))
    assert err.startswith(f"tilesolve: error: cannot write {bad}: ") and "the name's suffix is the format" in err
    assert snapshot(tmp_path) == before


@pytest.mark.parametrize("args,name", [
    (["tiles", "--kind", "wang", "--colors", "2", "--svg", "T.SVG"], "T.SVG"),
    (["wall-lines", "--max-line", "2", "--size", "6x6", "--samples", "1", "-o", "t.csv"], "t.csv"),
])
def test_suffixes_of_the_format_are_written(tmp_path, args, name):
    assert run(*args, cwd=tmp_path).returncode == 0
    assert (tmp_path / name).stat().st_size > 0


@posix_only
def test_an_error_that_follows_ctrl_c_is_reported_as_the_interruption(monkeypatch, tmp_path, capsys):
    """A Ctrl-C can surface as another exception (numpy turns a KeyboardInterrupt raised inside
    a structured-array comparison into a TypeError, seen while a wall PNG was streamed): after
    a signal it is the interruption, exit 130, not an internal error."""
    from tilesolve.cli import group
    from tilesolve.families import dappled

    def solve(*args, **kwargs):
        try:
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(60)
        except KeyboardInterrupt:
            raise TypeError("Cannot compare structured arrays unless they have a common dtype") from None

    monkeypatch.setattr(dappled, "solve", solve)
    monkeypatch.chdir(tmp_path)
    assert group.run(["dappled", "solve", "--size", "4x4", "-o", "t.json"]) == 130
    assert "tilesolve: interrupted (no file was written)" in capsys.readouterr().err
    assert os.listdir(tmp_path) == []
    monkeypatch.setattr(dappled, "solve", lambda *a, **k: 1 / 0)  # without a signal: a bug, exit 70
    assert group.run(["dappled", "solve", "--size", "4x4", "-o", "t.json"]) == 70


@posix_only
def test_a_ctrl_c_is_remembered_for_its_own_run_only(monkeypatch, tmp_path, capsys):
    """After a run that Ctrl-C ended, a bug in a later command of the same process (the click
    runner, as the tests and the studio use it) is still a bug, exit 70: the signal is not
    carried over (the fast tier in one process once failed on this)."""
    from click.testing import CliRunner

    from tilesolve.cli import group
    from tilesolve.families import dappled

    def interrupted(*args, **kwargs):
        os.kill(os.getpid(), signal.SIGINT)
        time.sleep(60)

    monkeypatch.setattr(dappled, "solve", interrupted)
    monkeypatch.chdir(tmp_path)
    assert group.run(["dappled", "solve", "--size", "4x4", "-o", "t.json"]) == 130
    monkeypatch.setattr(dappled, "solve", lambda *a, **k: 1 / 0)
    result = CliRunner().invoke(group.main_group, ["dappled", "solve", "--size", "4x4", "-o", "t.json"])
    assert result.exit_code == 70 and "interrupted" not in result.output
