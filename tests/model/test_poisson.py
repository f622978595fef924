"""Poisson tile problems: the notes' radius (eq. 4.2-4.3) and the checks on their values."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tilesolve.errors import InvalidProblem
from tilesolve.model.poisson import PoissonTilesProblem, PoissonWindowProblem, r_max


def test_radius_follows_the_notes():
    p = PoissonTilesProblem(3, 100, 0.8)
    assert p.r_max == pytest.approx(math.sqrt(1 / (2 * math.sqrt(3) * 100)))
    assert p.distance == pytest.approx(2 * 0.8 * r_max(100))
    assert p.n_tiles == 3 + 18 + 81
    # the strips of two edges meeting at a corner stay a distance apart (figure 4.3(b))
    a, d = p.corner_half, p.distance
    assert math.hypot(a - d, d - a) >= d


@pytest.mark.parametrize("args, words", [
    ((0, 64, 0.75), "colors"), ((9, 64, 0.75), "colors"), ((2, 0, 0.75), "points"),
    ((2, 64, 0.95), "rho"), ((2, 64, float("nan")), "rho"), ((2, 64, "x"), "rho"),
    ((2, 4, 0.75), "at least 13 points"), ((2, 64, 0.75, -1), "Lloyd"), ((True, 64, 0.7), "colors"),
])
def test_bad_values_are_one_line_errors(args, words):
    with pytest.raises(InvalidProblem, match=words):
        PoissonTilesProblem(*args)


def test_the_fewest_points_named_do_fit():
    PoissonTilesProblem(2, 13, 0.75)


def test_window_problems_check_their_tiling():
    from tilesolve.constructive.poisson import build_tiles

    ts = build_tiles(PoissonTilesProblem(1, 16, 0.6), seed=0)
    with pytest.raises(InvalidProblem, match="compact"):
        PoissonWindowProblem(ts, (0, 0, 2, 2), "direct", "compact")
    with pytest.raises(InvalidProblem, match="at most"):
        PoissonWindowProblem(ts, (0, 0, 2**14, 2**14))
    with pytest.raises(InvalidProblem, match="PoissonTileSet"):
        PoissonWindowProblem(np.zeros(3), (0, 0, 2, 2))
