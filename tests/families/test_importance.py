"""The stipple family: registered, solved through the pipeline, its samples bound to their seed."""

from __future__ import annotations

import numpy as np

from tilesolve.families.importance import FAMILY, stipple_violations
from tilesolve.family import family_of, solve
from tilesolve.io.stipple import Samples
from tilesolve.model.importance import ImportanceProblem, builtin_density


def test_the_family_solves_and_binds_samples_to_their_seed():
    p = ImportanceProblem(builtin_density("gradient", 32), 400, "rejection")
    assert family_of(p) is FAMILY
    sol = solve(p, seed=2)
    assert sol.status.value == "sat" and sol.tiling.seed is None  # a fresh answer claims no seed
    pts = sol.tiling.points
    assert stipple_violations(p, Samples(pts, 2)) == []
    assert stipple_violations(p, Samples(pts, 3))[0].kind == "seed"
    assert stipple_violations(p, Samples(pts[1:], 2))[0].kind == "seed"
    assert stipple_violations(p, Samples(np.vstack([pts, [[2.0, 0.5]]]), 2))[0].kind == "bounds"
    assert stipple_violations(p, "points")[0].kind == "shape"
