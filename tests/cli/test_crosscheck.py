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


def test_ctrl_c_in_the_linear_tilings_cnf_check_is_the_interruption(monkeypatch):
    """The brick cross-check's check that the linear tiling satisfies the CNF is a SAT call that
    catches Ctrl-C and answers unknown: that is the interruption, not a failed check (a sweep
    once printed FAIL and ran on after a Ctrl-C landed there)."""
    from tilesolve.engine import sat
    from tilesolve.engine.result import Result
    from tilesolve.families import board
    from tilesolve.model.board import Board, BoardProblem, WangTileSet
    from tilesolve.model.solution import Status

    monkeypatch.setattr(sat, "solve_cnf", lambda *a, **k: Result(Status.UNKNOWN, reason="interrupted (Ctrl-C)"))
    problem = BoardProblem(Board.rect(4, 4), WangTileSet.brick(3))  # a free boundary: tiled
    with pytest.raises(KeyboardInterrupt):
        board.crosscheck(problem, seed=1, methods=("linear",))


@pytest.mark.parametrize("argv", [
    ["brick", "crosscheck", "--board", "rect:4x4", "--trials", "3"],
    ["dappled", "crosscheck", "--size", "4x4", "--trials", "3"],
])
def test_a_trial_that_swallowed_a_ctrl_c_ends_the_sweep_with_130(monkeypatch, capsys, argv):
    """Whatever a route made of a Ctrl-C (an unknown, a failed check), the sweep stops after
    that trial with exit 130 and reports nothing of it."""
    import os

    from tilesolve.cli import group
    from tilesolve.families import board, dappled
    from tilesolve.model.solution import CrosscheckReport

    def crosscheck(*args, **kwargs):
        try:
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(60)
        except KeyboardInterrupt:
            pass  # swallowed, as a solver does
        rep = CrosscheckReport()
        rep.add(False, "a check the interruption cut short")
        return rep

    monkeypatch.setattr(board if argv[0] == "brick" else dappled, "crosscheck", crosscheck)
    assert group.run(argv) == 130
    out = capsys.readouterr().out
    assert "trial" not in out and "FAIL" not in out, out
