"""Pins that contradict each other are decided on the full formula and explained in words
(issue: `pack --method lift --fix 0,0,11 --fix 1,1,11` ran forever)."""

import itertools
import subprocess

import numpy as np
import pytest

from tilesolve.families import packing
from tilesolve.model.packing import PackingProblem
from tilesolve.verify.grid import grid_violations
from clitools import SCRIPT


@pytest.mark.parametrize("kind, colors", [("wang", 2), ("corner", 2), ("wang", 3)])
def test_side_by_side_clashes_agree_with_the_grid_verifier(kind, colors):
    table = PackingProblem(kind, colors).tiles.table()
    rng = np.random.default_rng(0)
    for t, u in rng.integers(0, len(table), size=(200, 2)).tolist():
        if t == u:
            continue
        for (dr, dc), grid in (((0, 1), [[t, u]]), ((1, 0), [[t], [u]])):
            p = PackingProblem(kind, colors, fixed=((0, 0, t), (dr, dc, u)))
            assert bool(p.pin_clashes()) == bool(grid_violations(table, grid, kind=kind)), (t, u, dr, dc)


def test_pins_from_a_packing_never_clash():
    s = packing.solve(PackingProblem("corner", 3), method="euler", seed=1)
    pins = tuple((r, c, int(s.tiling[r, c])) for r, c in itertools.product(range(3), range(3)))
    assert PackingProblem("corner", 3, fixed=pins).pin_clashes() == []


@pytest.mark.parametrize("method", ["lift", "recursive", "hybrid"])
def test_restricted_routes_refute_clashing_pins_with_a_checked_proof(method):
    p = PackingProblem("wang", 2, fixed=((0, 0, 11), (1, 1, 11)))
    s = packing.solve(p, method=method, seed=1)
    assert s.status.value == "unsat" and "checked" in s.reason and "pinned at (0, 0) and at (1, 1)" in s.reason


@pytest.mark.slow
def test_cli_clashing_pins(tmp_path):
    proc = subprocess.run([SCRIPT, "pack", "--kind", "wang", "--colors", "3", "--method", "sat",
                           "--fix", "0,0,5", "--fix", "0,1,7"], cwd=tmp_path, capture_output=True, text=True,
                          timeout=300)
    assert proc.returncode == 1 and "tile 7 cannot sit east of tile 5" in proc.stderr
