"""The substitution family (tilesolve.families.substitution): routes, auto, verification through
the pipeline, and the family record's files."""

import pytest

from tilesolve import family
from tilesolve.errors import MethodNotApplicable
from tilesolve.families.substitution import FAMILY, patch_violations, solve
from tilesolve.model.substitution import Patch, SubstitutionProblem


def test_registered_with_its_commands():
    assert family.get("substitution") is FAMILY
    assert FAMILY.methods == ("auto", "substitution", "pentagrid")


@pytest.mark.parametrize("problem,method", [(SubstitutionProblem("p3", region=(-4, -4, 8, 8)), "pentagrid"),
                                            (SubstitutionProblem("p2", steps=3), "substitution"),
                                            (SubstitutionProblem("l-tetromino", steps=2), "substitution")])
def test_auto_route_and_verification(problem, method):
    s = solve(problem, seed=2)
    assert s.status.value == "sat" and s.method == method and patch_violations(problem, s.tiling) == []
    assert s.stats["tiles"] == s.tiling.n_tiles


def test_substitution_on_a_region_keeps_the_tiles_inside():
    p = SubstitutionProblem("p2", region=(3, -2, 9, 7))
    s = solve(p, method="substitution", seed=1)
    assert s.tiling.n_tiles > 10 and patch_violations(p, s.tiling) == []


def test_pentagrid_needs_a_region():
    with pytest.raises(MethodNotApplicable, match="give a region"):
        solve(SubstitutionProblem("p3", steps=3), method="pentagrid")


def test_a_patch_of_another_window_or_kind_fails():
    s = solve(SubstitutionProblem("p3", region=(0, 0, 10, 10)), seed=1)
    assert patch_violations(SubstitutionProblem("p3", region=(0, 0, 5, 5)), s.tiling)[0].kind == "window"
    assert patch_violations(SubstitutionProblem("p2", region=(0, 0, 10, 10)), s.tiling)[0].kind == "shape"
    other = Patch("chair", s.tiling.types, s.tiling.vertices)
    assert patch_violations(SubstitutionProblem("chair", steps=1), other)


def test_the_same_seed_gives_the_same_window():
    p = SubstitutionProblem("p3", region=(-5, 0, 10, 10))
    a, b = solve(p, seed=9).tiling, solve(p, seed=9).tiling
    assert (a.vertices == b.vertices).all()


def test_demos_build():
    for demo in FAMILY.demos:
        assert solve(demo.make(), method=demo.method, seed=1).status.value == "sat"
