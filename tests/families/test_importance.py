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


def test_compare_shows_the_polyomino_sampler_with_and_without_its_table():
    from tilesolve.families.importance import compare

    d = builtin_density("gradient", 32)
    rows = compare(ImportanceProblem(d, 500, "polyomino", "x-pentomino"), seed=1, runs=1, spectrum_points=256)
    assert [r["name"] for r in rows] == ["penrose", "polyomino (x-pentomino)", "uncorrected polyomino", "rejection"]
    for r in rows:
        assert r["violations"] == [] and r["peak"] >= r["off_ring_peak"] > 0 and 2 <= r["ring"] <= 48
    jittered = compare(ImportanceProblem(d, 500, "polyomino", "x-pentomino", jitter=True), seed=1, runs=1,
                       spectrum_points=256)
    assert [r["name"] for r in jittered] == ["penrose", "polyomino (x-pentomino)", "rejection"]  # no table applies
