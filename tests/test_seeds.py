"""Same seed, one worker: the same output on every route; other seeds: other solutions (issue 9,
defect 8).

Each route is run through the one pipeline (:func:`tilesolve.family.solve`) with ``workers=1``.
The problems have many solutions, so the seed has room to matter: SAT draws the solver's
initial phases from it, CP-SAT a solution hint (presolve off, one worker), MaxSAT the oracle's phases
(the optimum distance is unique, the optimal tiling is not), and the packing searches their
random domains, phases and symmetries.
"""

from __future__ import annotations

import numpy as np
import pytest

from tilesolve import family
from tilesolve.model.board import Board, BoardProblem, WangTileSet
from tilesolve.model.dappled import DappledProblem
from tilesolve.model.packing import PackingProblem
from clitools import SCRIPT


def _dappled():
    return DappledProblem.from_strings("16x16", ["H0=2", "V1=2"], cyclic=True)


def _closest():
    # Target all zeros under H0=2: every row needs tiles 1 somewhere in each run of three, at
    # many equally good places.
    return DappledProblem.from_strings("9x9", ["H0=2"], closest_to=np.zeros((9, 9), dtype=np.int8))


CASES = {
    "dappled sat": (_dappled, "sat"),
    "dappled cpsat": (_dappled, "cpsat"),
    "dappled maxsat": (_closest, "maxsat"),
    "board sat": (lambda: BoardProblem(Board.rect(8, 8), WangTileSet.brick(3)), "sat"),
    "packing lift": (lambda: PackingProblem("corner", 4), "lift"),
}


def _tiling(make, method, seed, workers=1):
    sol = family.solve(make(), method, seed=seed, workers=workers)
    assert sol.status.has_tiling, (method, sol.status, sol.reason)
    return np.asarray(sol.tiling), sol


@pytest.mark.parametrize("case", sorted(CASES))
def test_same_seed_same_output_other_seeds_other_solutions(case):
    make, method = CASES[case]
    first, sol = _tiling(make, method, 11)
    again, _ = _tiling(make, method, 11)
    assert np.array_equal(first, again), f"{case}: seed 11 gave two different answers"
    others = [_tiling(make, method, s)[0] for s in (12, 13, 14)]
    assert any(not np.array_equal(first, o) for o in others), f"{case}: seeds 11..14 all gave one answer"
    if method == "maxsat":  # the freedom is among optima: every seed reaches the same distance
        dist = {int((t != make().closest_to).sum()) for t in [first] + others}
        assert dist == {sol.objective}


def test_cpsat_seeded_satisfaction_repeats_with_two_workers():
    # A seeded satisfaction run uses one CP-SAT worker: deterministic whatever the workers asked for.
    first, _ = _tiling(_dappled, "cpsat", 5, workers=2)
    assert all(np.array_equal(first, _tiling(_dappled, "cpsat", 5, workers=2)[0]) for _ in range(3))
    assert np.array_equal(first, _tiling(_dappled, "cpsat", 5, workers=1)[0])


@pytest.mark.slow
@pytest.mark.parametrize("method", ["sat", "cpsat"])
def test_console_script_seed_repeats_across_processes(method):
    import subprocess

    cmd = [SCRIPT,
        "dappled", "solve", "--size", "12x12", "--cond", "H0=2,V1=2", "--method", method, "--seed"]
    out = [subprocess.run(cmd + [str(s)], capture_output=True, text=True, timeout=300) for s in (1, 1, 2)]
    assert all(o.returncode == 0 for o in out), [o.stderr for o in out]
    assert out[0].stdout == out[1].stdout != out[2].stdout
