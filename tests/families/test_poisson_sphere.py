"""The poisson-sphere family (tilesolve.families.poisson_sphere): routes, the registry's verify
and codecs."""

from __future__ import annotations

import numpy as np
import pytest

from tilesolve.errors import MethodNotApplicable
from tilesolve.families.poisson_sphere import FAMILY, solve, sphere_violations
from tilesolve.family import get
from tilesolve.model.poisson_sphere import (
    PoissonSphereTilesProblem,
    PoissonSphereTileSet,
    PoissonSphereWindow,
    PoissonSphereWindowProblem,
)


@pytest.fixture(scope="module")
def built():
    return solve(PoissonSphereTilesProblem(1, 100, 0.6), seed=2)


def test_registered_under_its_entry_point():
    assert get("poisson-sphere") is FAMILY


def test_routes(built):
    assert built.status.value == "sat" and built.method == "dart"
    w = solve(PoissonSphereWindowProblem(built.tiling, (5, -2**45, 3, 2, 1, 1)), seed=1)
    assert w.method == "window" and w.tiling.n_points == 2 * (100 - built.tiling.stats["short"])
    with pytest.raises(MethodNotApplicable):
        solve(PoissonSphereTilesProblem(1, 100, 0.6), method="window")


def test_verify_refuses_another_set_or_box(built):
    ts = built.tiling
    other = PoissonSphereTilesProblem(1, 100, 0.5)
    assert sphere_violations(other, ts)[0].message == "the tile set is not the one the problem asks for"
    problem = PoissonSphereWindowProblem(ts, (0, 0, 0, 1, 1, 1))
    w = PoissonSphereWindow(problem.box, np.array([[0.5, 0.5, 0.5], [0.5, 0.5, 0.52]]), ts.problem.distance)
    assert [v.kind for v in sphere_violations(problem, w)] == ["distance"]
    moved = PoissonSphereWindowProblem(ts, (1, 0, 0, 1, 1, 1))
    assert sphere_violations(moved, w)[0].kind == "shape"
    assert sphere_violations(problem, "points")[0].kind == "shape"
    assert isinstance(ts, PoissonSphereTileSet)


def test_codecs_round_trip(built):
    from tilesolve.io.poisson_sphere_json import TILES_FORMAT

    codec = next(c for c in FAMILY.codecs if c.format == TILES_FORMAT)
    problem, sol = codec.read(codec.write(built.tiling.problem, built), "s.json")
    assert problem == built.tiling.problem and sphere_violations(problem, sol.tiling) == []
