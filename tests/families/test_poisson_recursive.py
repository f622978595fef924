"""The recursive-wang family: routes, verification through the pipeline, pictures."""

from __future__ import annotations

import pytest

from tilesolve.families.poisson_recursive import recursive_violations, solve
from tilesolve.family import draw_solution
from tilesolve.model.poisson_recursive import RecursiveTilesProblem, RecursiveWindowProblem


@pytest.fixture(scope="module")
def built():
    return solve(RecursiveTilesProblem(2, 16, 0.7, 2), seed=5)


def test_a_set_and_a_window_are_solved_and_verified(built):
    assert built.status.value == "sat" and built.method == "build"
    w = solve(RecursiveWindowProblem(built.tiling, (3, 3, 2, 2), density=100.0), seed=1)
    assert w.method == "window" and w.stats["level"] == 2 and w.stats["points"] == w.tiling.n_points


def test_the_verifier_refuses_answers_to_other_problems(built):
    other = RecursiveTilesProblem(2, 16, 0.7, 3)
    assert recursive_violations(other, built.tiling)[0].kind == "shape"
    problem = RecursiveWindowProblem(built.tiling, (0, 0, 1, 1), level=1)
    w = solve(problem, seed=2).tiling
    assert recursive_violations(RecursiveWindowProblem(built.tiling, (1, 0, 1, 1), level=1), w)[0].kind == "window"
    assert recursive_violations(other, w)[0].kind == "shape"
    assert recursive_violations(problem, "points")[0].kind == "shape"


def test_a_set_is_drawn_as_a_window(built, tmp_path):
    draw_solution(tmp_path / "s.svg", RecursiveTilesProblem(2, 16, 0.7, 2), built)
    assert (tmp_path / "s.svg").read_text().count("<circle") > 4 * 4 * 16
