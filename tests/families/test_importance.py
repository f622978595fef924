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


def test_a_density_naming_a_test_image_must_be_that_image():
    from tilesolve.families.importance import image_violations
    from tilesolve.model.importance import DensityMap

    d = builtin_density("radial", 16)
    assert image_violations(d) == []
    v = d.values.copy()
    v[3, 4] *= 1 + 1e-12  # one pixel off in its last bits
    for forged in (DensityMap(v, "radial"), DensityMap(d.values[:, :15], "radial"),
                   DensityMap(d.values, "gradient")):
        (found,) = image_violations(forged)
        assert found.kind == "image" and f"test image {forged.name!r}" in found.message
    assert image_violations(DensityMap(v, "radial.png")) == []  # a user's picture: only its counts are checked
    p = ImportanceProblem(DensityMap(v, "radial"), 300, "rejection")
    sol = solve(p, seed=1)  # a problem built in Python names its density as it likes
    assert stipple_violations(p, sol.tiling) == []
    assert [x.kind for x in stipple_violations(p, Samples(sol.tiling.points, 1))] == ["image"]  # a file's
