"""Ctrl-C stops a cross-check sweep (issue: five SIGINTs were ignored and all trials ran)."""

import signal
import subprocess
import time

import pytest
from clitools import SCRIPT


@pytest.mark.slow
@pytest.mark.parametrize("args", [
    ("dappled", "crosscheck", "--size", "12x12", "--cond", "H0=2,V1=2", "--trials", "1000"),
    ("brick", "crosscheck", "--board", "rect:12x12", "--trials", "1000"),
    ("crosscheck", "wall", "--trials", "1000", "--seed", "1"),
    ("crosscheck", "tiling", "--trials", "1000", "--seed", "1"),
])
def test_sigint_ends_a_crosscheck_with_130(tmp_path, args):
    proc = subprocess.Popen([SCRIPT, *args], cwd=tmp_path, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    seen = 0
    for line in proc.stdout:  # wait until the sweep is under way
        seen += line.startswith("trial ")
        if seen >= 2:
            break
    proc.send_signal(signal.SIGINT)
    t0 = time.monotonic()
    try:
        out, err = proc.communicate(timeout=120)
    except subprocess.TimeoutExpired:
        proc.kill()
        pytest.fail("the cross-check kept running after Ctrl-C")
    assert proc.returncode == 130, (out[-500:], err[-500:])
    assert "interrupted" in err and "Traceback" not in err
    assert "trial 1000/1000" not in out and time.monotonic() - t0 < 120
