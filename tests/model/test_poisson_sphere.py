"""The Poisson sphere problems, boxes and tile sets (tilesolve.model.poisson_sphere)."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from tilesolve.errors import InvalidProblem
from tilesolve.model.poisson_sphere import (
    Box,
    PoissonSphereTilesProblem,
    PoissonSphereTileSet,
    PoissonSphereWindowProblem,
    cube_index,
    parse_box,
    r_max3,
)


def test_counts_and_geometry():
    p = PoissonSphereTilesProblem(2, 128, 0.7)
    assert p.n_tiles == 2 + 12 + 48 + 256 == sum(p.counts().values())
    assert PoissonSphereTilesProblem(3, 128, 0.6).counts()["interior"] == 6561  # §4.4.2
    d, a, b = p.distance, p.corner_half, p.edge_half
    assert math.isclose(d, 2 * 0.7 * (1 / (4 * math.sqrt(2) * 128)) ** (1 / 3))
    assert math.sqrt(2) * (a - b) >= d and math.sqrt(2) * (b - d) >= d and 1 - 2 * a >= d


def test_r_max3_is_the_densest_packing():
    # N spheres of radius r_max fill pi / (3 sqrt 2) of the unit cube (eq. 4.4-4.5)
    for n in (1, 10, 1000):
        assert math.isclose(n * 4 / 3 * math.pi * r_max3(n) ** 3, math.pi / (3 * math.sqrt(2)))


@pytest.mark.parametrize("args, words", [
    ((0, 128, 0.7), "colors must be within 1..4"),
    ((5, 128, 0.7), "colors must be within 1..4"),
    ((2, 128, 0.9), "rho must be within"),
    ((2, 128, float("nan")), "rho must be a number"),
    ((2, True, 0.7), "points a tile must be an integer"),
    ((2, 96, 0.7), "use at least 97 points a tile"),
])
def test_bad_problems(args, words):
    with pytest.raises(InvalidProblem, match=words):
        PoissonSphereTilesProblem(*args)


def test_cube_index_reads_the_corners_as_digits():
    assert cube_index([1, 0, 1], 2) == 5
    seen = {cube_index(c, 3) for c in itertools.product(range(3), repeat=8)}
    assert seen == set(range(3**8))


def test_box_parse_and_round_trip():
    b = parse_box(" -4, 2, 9 , 3x4X5")
    assert (b.origin, b.size, b.n_cells) == ((-4, 2, 9), (3, 4, 5), 60)
    assert Box.from_dict(b.to_dict()) == b
    for text in ("1,2,3x4", "1,2,3,4x5", "a,b,c,1x1x1", "0,0,0,0x1x1"):
        with pytest.raises(InvalidProblem):
            parse_box(text)
    with pytest.raises(InvalidProblem, match="2\\*\\*62"):
        Box(2**62, 0, 0, 1, 1, 1)
    with pytest.raises(InvalidProblem, match="exactly the fields"):
        Box.from_dict({"x0": 0})


def test_tile_set_shapes_are_checked():
    p = PoissonSphereTilesProblem(1, 100, 0.6)
    tiles = {k: [np.zeros((0, 3))] for k in p.counts()}
    assert PoissonSphereTileSet(p, tiles).n_points == 0
    with pytest.raises(InvalidProblem, match="float64"):
        PoissonSphereTileSet(p, {**tiles, "corner": [np.zeros((1, 2))]})
    with pytest.raises(InvalidProblem, match="1 interior tiles"):
        PoissonSphereTileSet(p, {**tiles, "interior": []})
    ts = PoissonSphereTileSet(p, tiles)
    with pytest.raises(InvalidProblem, match="unknown hash"):
        PoissonSphereWindowProblem(ts, (0, 0, 0, 1, 1, 1), "sha")
    with pytest.raises(InvalidProblem, match="at most"):
        PoissonSphereWindowProblem(ts, (0, 0, 0, 1000, 1000, 1000))
