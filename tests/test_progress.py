"""Progress on long work (tilesolve.progress, issue 19): bars on a terminal through the real
console script, silence without a terminal or with ``-q``, and the stream the studio reads."""

from __future__ import annotations

import fcntl
import os
import pickle
import pty
import struct
import subprocess
import termios
import threading
import time
from pathlib import Path

import pytest
from clitools import ENV, SCRIPT

from tilesolve.progress import DELAY_ENV, SILENT, Stream, Terminal, as_progress, terminal

#: Every bar at once: whether a bar shows must not depend on how fast the machine is.
NOW = dict(ENV, **{DELAY_ENV: "0"})
#: A count with known work: the transfer matrix builds 7 columns of row words, then 8 rows.
COUNT = ("wang", "count", "--builtin", "jeandel-rao", "--board", "rect:8x8")


def run_on_tty(*args: str, cwd: Path, env=NOW) -> tuple[int, str, str]:
    """``tilesolve ARGS`` with its stderr on a pseudo-terminal (120 x 24): (exit code, stdout,
    everything written to the terminal)."""
    leader, follower = pty.openpty()
    fcntl.ioctl(follower, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 120, 0, 0))
    proc = subprocess.Popen([SCRIPT, *args], cwd=cwd, env=env, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                            stderr=follower)
    os.close(follower)
    chunks: list[bytes] = []

    def drain() -> None:
        while True:
            try:
                data = os.read(leader, 65536)
            except OSError:  # the terminal closed: every writer is gone
                return
            if not data:
                return
            chunks.append(data)

    reader = threading.Thread(target=drain)
    reader.start()
    out = proc.stdout.read()
    proc.wait()
    reader.join()
    os.close(leader)
    return proc.returncode, out.decode(), b"".join(chunks).decode(errors="replace")


def test_count_shows_rows_on_a_terminal(tmp_path):
    code, out, tty = run_on_tty(*COUNT, cwd=tmp_path)
    assert code == 0 and out.strip() == "262019"
    # the work is known: a fraction of the total (how far each redraw got depends on the machine)
    assert "counting: building row words:" in tty and "/7 [" in tty and "column" in tty
    assert "counting: rows:" in tty and "/8 [" in tty and "row" in tty
    assert "count by transfer" in tty  # the summary still follows


def test_count_is_silent_without_a_terminal(tmp_path):
    proc = subprocess.run([SCRIPT, *COUNT], cwd=tmp_path, env=NOW, capture_output=True, text=True)
    assert proc.returncode == 0 and proc.stdout.strip() == "262019"
    assert "counting" not in proc.stderr and "\r" not in proc.stderr
    assert "count by transfer" in proc.stderr


@pytest.mark.parametrize("where", ["before", "after"])
@pytest.mark.parametrize("quiet", ["-q", "--quiet"])
def test_count_is_silent_with_q(tmp_path, quiet, where):
    """``-q`` before the command or after it: no bar and no summary."""
    args = (quiet, *COUNT) if where == "before" else (*COUNT, quiet)
    code, out, tty = run_on_tty(*args, cwd=tmp_path)
    assert code == 0 and out.strip() == "262019"
    assert tty.strip() == ""


def test_v_after_the_command_counts_with_q_before_it(tmp_path):
    code, _, tty = run_on_tty("-q", *COUNT, "-v", cwd=tmp_path)
    assert code == 0 and "counting: rows" in tty and "count by transfer" in tty


def test_quick_work_draws_nothing_by_default(tmp_path):
    """Without the environment's delay of 0, a bar shows only after DELAY_S: an instant
    command leaves the terminal alone. (Asserted one way only: nothing here may depend on
    the machine being slow.)"""
    env = {k: v for k, v in ENV.items() if k != DELAY_ENV}
    code, _, tty = run_on_tty("wang", "count", "--builtin", "jeandel-rao", "--board", "rect:2x2", cwd=tmp_path,
                              env=dict(env, **{DELAY_ENV: "3600"}))
    assert code == 0 and "counting" not in tty and "count by transfer" in tty


def test_sweep_shows_boards_decided_refuted_undecided_and_verify_the_claims(tmp_path):
    code, _, tty = run_on_tty("aperiodic", "check", "--builtin", "jeandel-rao", "--max-period", "2", "--workers", "1",
                              "--seed", "1", "-o", "jr.json", "--proof-dir", "proofs", cwd=tmp_path)
    assert code == 0, tty
    assert "periods:" in tty and "/4 [" in tty and "board" in tty  # 4 tori: 1x1, 1x2, 2x1, 2x2
    assert "tiled, " in tty and " refuted, " in tty and " undecided" in tty
    code, _, tty = run_on_tty("verify", "jr.json", "--proof-dir", "proofs", cwd=tmp_path)
    assert code == 0, tty
    assert "re-checking refutations:" in tty and "/4 [" in tty and "claim" in tty


def test_stream_snapshots():
    sent: list[dict] = []
    p = Stream(sent.append, every=0)
    with p.task("levels", total=2, unit="level") as levels:
        with p.task("seeds", unit=None) as seeds:
            seeds.note("seed 3")
        levels.advance(2)
    assert [(s["label"], s["depth"], s.get("closed", False)) for s in sent] == [
        ("levels", 0, False), ("seeds", 1, False), ("seeds", 1, False), ("seeds", 1, True),
        ("levels", 0, False), ("levels", 0, True)]
    assert sent[2]["note"] == "seed 3" and sent[-1]["done"] == 2 and sent[-1]["eta_s"] == 0
    p.announce("about 5 s")
    assert sent[-1] == {"announce": "about 5 s"}


def test_silent_and_pickling():
    assert not SILENT and Stream(print) and Terminal()
    assert as_progress(False) is SILENT and as_progress(None) is SILENT
    stream = Stream(print)
    assert as_progress(stream) is stream
    # a worker process gets silence: its parent reports for it
    assert pickle.loads(pickle.dumps(stream)) is SILENT and pickle.loads(pickle.dumps(Terminal())) is SILENT


def test_terminal_is_silent_off_a_tty(monkeypatch, capsys):
    assert terminal() is SILENT  # pytest captures stderr: not a terminal
    assert as_progress(True) is SILENT


def test_a_bar_drawn_after_its_delay_is_erased(monkeypatch):
    """A task shows once past its delay, and its line is erased when it ends (a bar tqdm itself
    never drew since the delay is still erased: the terminal keeps no stale line)."""
    import io
    import re
    import sys

    class Tty(io.StringIO):
        def isatty(self):
            return True

    fake = Tty()
    monkeypatch.setattr(sys, "stderr", fake)
    p = terminal()
    assert isinstance(p, Terminal)
    p.every, p.delay = 3600, 0.2  # no redraw from the helper thread: this test draws
    with p.task("solving", unit=None) as task:
        task.note("seed 1")
        assert fake.getvalue() == ""  # younger than its delay: nothing drawn
        time.sleep(0.3)  # past the delay (the sleep bounds nothing)
        task.note("seed 2")
    out = fake.getvalue()
    assert "solving: seed 2 [00:00]" in out and "seed 1" not in out
    assert re.search(r"solving: seed 2 \[00:00\]\r {23,}\r$", out), repr(out)
