"""The poisson family through the registry: solve, verify, files."""

from __future__ import annotations

import numpy as np
import pytest

from tilesolve.errors import MethodNotApplicable
from tilesolve.families.poisson import poisson_violations, solve
from tilesolve.family import family_of
from tilesolve.model.poisson import PoissonTilesProblem, PoissonWindow, PoissonWindowProblem


@pytest.fixture(scope="module")
def built():
    return solve(PoissonTilesProblem(2, 20, 0.6), seed=7)


def test_the_family_is_registered_and_solves_both_questions(built):
    assert family_of(PoissonTilesProblem(1, 20, 0.6)).name == "poisson"
    assert built.status.value == "sat" and built.method == "dart"
    w = solve(PoissonWindowProblem(built.tiling, (-(2**61), 2**61 - 10, 4, 3), "scanline", "compact"), seed=1)
    assert w.method == "window" and w.tiling.n_points > 0


def test_routes_refuse_the_other_question(built):
    with pytest.raises(MethodNotApplicable):
        solve(PoissonTilesProblem(1, 20, 0.6), method="window")
    with pytest.raises(MethodNotApplicable):
        solve(PoissonWindowProblem(built.tiling, (0, 0, 1, 1)), method="dart")


def test_verify_checks_answers_against_the_stated_problem(built):
    assert poisson_violations(PoissonTilesProblem(2, 20, 0.55), built.tiling)[0].kind == "shape"
    w = solve(PoissonWindowProblem(built.tiling, (0, 0, 2, 2)), seed=1).tiling
    doubled = PoissonWindow(w.window, np.vstack([w.local, w.local[:1] + 1e-3]), w.distance)
    assert poisson_violations(built.tiling.problem, doubled)[0].kind == "distance"
    assert poisson_violations(built.tiling.problem, "points")[0].kind == "shape"
