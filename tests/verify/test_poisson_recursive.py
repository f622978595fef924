"""The independent recursive Wang verifier catches what it must (Kopf et al. 2006; class notes
Part V, §2.9, §4.3)."""

from __future__ import annotations

import numpy as np
import pytest

from tilesolve.constructive.poisson_recursive import build_recursive, sample_window
from tilesolve.model.poisson import PoissonTileSet
from tilesolve.model.poisson_recursive import (
    RecursiveTilesProblem,
    RecursiveTileSet,
    RecursiveWindow,
    RecursiveWindowProblem,
)
from tilesolve.verify.poisson_recursive import rule_violations, tileset_violations, window_violations


@pytest.fixture(scope="module")
def ts():
    return build_recursive(RecursiveTilesProblem(2, 16, 0.7, 3), seed=2)


@pytest.fixture(scope="module")
def win(ts):
    return sample_window(RecursiveWindowProblem(ts, (2**50, 3, 2, 2), level=2), seed=4)


def _with(w, local=None, level=None, rank=None):
    return RecursiveWindow(w.window, w.local if local is None else local, w.level if level is None else level,
                           w.rank if rank is None else rank, w.distance, w.subdivision)


def test_a_valid_window_has_no_violations(win):
    assert window_violations(win) == []


@pytest.mark.parametrize("level", [0, 1, 2])
def test_a_point_moved_too_close_at_any_level_is_caught_at_that_level(win, level):
    d = win.distance_at(level)
    i = int(np.flatnonzero(win.level == level)[0])
    j = int(np.flatnonzero(win.level <= level)[np.flatnonzero(win.level <= level) != i][0])
    local = win.local.copy()
    local[i] = local[j] + [0.9 * d / np.sqrt(2)] * 2
    local[i] = np.clip(local[i], 0, 2 - 1e-9)
    found = window_violations(_with(win, local=local))
    assert found and found[0].kind == "distance" and found[0].message.startswith(f"level {level}:")


def test_a_fine_point_claimed_coarse_is_caught(win):
    level = win.level.copy()
    level[win.level == 2] = 0  # level 0 would then hold points far closer than d_0
    assert [v.kind for v in window_violations(_with(win, level=level))][:1] == ["distance"]


def test_ranks_levels_and_the_window_are_checked(win):
    rank = win.rank.copy()
    rank[0] = 1.0
    assert [v.kind for v in window_violations(_with(win, rank=rank))] == ["rank"]
    level = win.level.copy()
    level[0] = 99
    assert [v.kind for v in window_violations(_with(win, level=level))] == ["level"]
    local = win.local.copy()
    local[0] = [2.5, 0.5]
    assert "window" in [v.kind for v in window_violations(_with(win, local=local))]


def test_rules_that_split_an_edge_two_ways_are_caught(ts):
    rules = ts.rules.copy()
    rules[5, 0, 1] = 1 - rules[5, 0, 1]  # the south edge of tile 5 alone
    found = rule_violations(rules, 2)
    assert found and "subdivides two ways" in found[0].message
    bad = RecursiveTileSet(ts.problem, ts.base, rules)
    assert tileset_violations(bad)


def test_rules_that_change_a_corner_colour_are_caught(ts):
    rules = ts.rules.copy()
    rules[3, 3, 3] = 1 - rules[3, 3, 3]
    assert any("corner colours" in v.message for v in rule_violations(rules, 2))


def test_corner_tiles_too_close_are_caught(ts):
    tiles = {k: [a.copy() for a in arrs] for k, arrs in ts.base.tiles.items()}
    pts = tiles["interior"][7]
    tiles["interior"][7] = np.vstack([pts, pts[:1] + [ts.problem.distance / 3, 0]])
    bad = RecursiveTileSet(ts.problem, PoissonTileSet(ts.problem.base, tiles), ts.rules)
    assert [v.kind for v in tileset_violations(bad)][:1] == ["distance"]
