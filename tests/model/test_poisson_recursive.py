"""Recursive Wang problems refuse what they cannot hold, in one line."""

from __future__ import annotations

import numpy as np
import pytest

from tilesolve.errors import InvalidProblem
from tilesolve.model.poisson_recursive import MAX_LEVEL, RecursiveTilesProblem


def test_levels_and_densities():
    p = RecursiveTilesProblem(2, 16, 0.7, 3)
    assert p.distance_at(2) == pytest.approx(p.distance / 9)
    assert [p.level_for(d) for d in (0, 16, 17, 144, 145)] == [0, 0, 1, 1, 2]
    assert p.level_for(1e300) == MAX_LEVEL
    assert p.base.n_tiles == 2 + 2 * 4 + 16


@pytest.mark.parametrize("args, words", [
    ((2, 16, 0.7, 1), "subdivision"),
    ((2, 16, 0.7, 9), "subdivision"),
    ((2, 16, 0.7, True), "subdivision"),
    ((2, 4, 0.75, 4), "points a tile"),
    ((9, 16, 0.7, 4), "colors"),
    ((2, 16, 0.95, 4), "rho"),
])
def test_bad_problems_are_refused(args, words):
    with pytest.raises(InvalidProblem) as exc:
        RecursiveTilesProblem(*args)
    assert words in str(exc.value)


def test_a_window_takes_a_level_or_a_density_and_bounds_its_work():
    from tilesolve.constructive.poisson_recursive import build_recursive
    from tilesolve.model.poisson_recursive import RecursiveWindowProblem

    ts = build_recursive(RecursiveTilesProblem(1, 16, 0.7, 2), seed=1)
    assert RecursiveWindowProblem(ts, (0, 0, 2, 2), density=np.array([[10.0, 65.0]])).level == 2
    for kw, words in (({}, "either"), ({"level": 1, "density": 3.0}, "either"), ({"level": -1}, "level"),
                      ({"density": np.array([[np.nan]])}, "density"), ({"level": 12}, "candidate points")):
        with pytest.raises(InvalidProblem) as exc:
            RecursiveWindowProblem(ts, (0, 0, 2, 2), **kw)
        assert words in str(exc.value)
