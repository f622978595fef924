"""``tilesolve dappled count`` through the console script: refusals with the planner's estimate,
and progress on a terminal (issue 19)."""

from __future__ import annotations

import pytest
from clitools import one_line_error, run
from test_progress import run_on_tty


def test_count_beyond_the_memory_limit_is_refused_with_the_estimate(tmp_path):
    # 3^18 profiles need ~6 GiB (the halves met in the middle); enumeration would never end:
    # one line, exit 2, before anything large is allocated.
    msg = one_line_error(run("dappled", "count", "--size", "18x18", "--cond", "H0=2,V1=2", cwd=tmp_path))
    assert "3^18 = 387,420,489 states" in msg and "GiB, limit 2.00 GiB" in msg and "min of work" in msg
    assert "only enumeration can count this problem" in msg and "--time-limit" in msg and "--force" in msg


def test_count_shows_row_sweeps_on_a_terminal(tmp_path):
    code, out, tty = run_on_tty("dappled", "count", "--size", "12x12", "--cond", "H0=2,V1=2", cwd=tmp_path)
    assert code == 0 and out.strip().splitlines()[-1] == "145816870651378340099973452074"  # A206994: T(12, 12)
    # 2 primes x (6 rows of one half + the join of the halves)
    assert "counting: row sweeps:" in tty and "/14 [" in tty
    assert "counting: about" not in tty  # a quick count is not announced


@pytest.mark.slow
def test_a_long_count_is_announced_with_its_estimate(tmp_path):
    code, out, tty = run_on_tty("dappled", "count", "--size", "15x15", "--cond", "H0=2,V1=2", cwd=tmp_path)
    assert code == 0 and len(out.strip().splitlines()[-1]) == 45
    assert "counting: about" in tty and "by the planner's estimate (3^15 = 14,348,907 states x 8 of 15 rows" in tty
