"""Poisson sphere tile sets and boxes as files (tilesolve.io.poisson_sphere_json)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from tilesolve.errors import InvalidProblem
from tilesolve.io.poisson_sphere_json import (
    SeededBox,
    check_point_output3,
    dump,
    tiles_from_dict,
    tiles_to_dict,
    window_from_dict,
    window_to_dict,
    write_points3,
)
from tilesolve.model.poisson_sphere import (
    Box,
    PoissonSphereTilesProblem,
    PoissonSphereTileSet,
    PoissonSphereWindow,
    PoissonSphereWindowProblem,
)
from tilesolve.model.solution import Solution, Status


@pytest.fixture(scope="module")
def built():
    """A set of made-up points (the files do not care how a set was built)."""
    p = PoissonSphereTilesProblem(1, 100, 0.6)
    rng = np.random.default_rng(0)
    tiles = {k: [rng.random((3, 3)) * 0.01 for _ in range(n)] for k, n in p.counts().items()}
    ts = PoissonSphereTileSet(p, tiles, seed=4, stats={"short": 2})
    return p, Solution(Status.SAT, ts, method="dart", seed=4, stats={"short": 2})


def test_tiles_round_trip_exactly(built):
    p, sol = built
    text = dump(tiles_to_dict(p, sol))
    doc = json.loads(text)
    assert doc["format"] == "tilesolve/poisson-sphere-tiles" and doc["version"] == 1 and doc["stats"] == {"short": 2}
    q, back = tiles_from_dict(doc, "s.json")
    assert q == p and back.seed == 4
    for k in sol.tiling.tiles:
        assert all(np.array_equal(a, b) for a, b in zip(sol.tiling.tiles[k], back.tiling.tiles[k]))
    assert dump(tiles_to_dict(q, back)) == text  # same bytes again


@pytest.mark.parametrize("change, words", [
    ({"distance": 0.05}, "'distance' is 0.05, but its problem's"),
    ({"seed": -1}, "'seed' must be an integer"),
    ({"seed": True}, "'seed' must be an integer"),
    ({"colors": 9}, "colors must be within"),
    ({"version": 2}, "version 2 is not supported"),
    ({"extra": 1}, "unknown field 'extra'"),
])
def test_bad_tile_files(built, change, words):
    p, sol = built
    doc = {**json.loads(dump(tiles_to_dict(p, sol))), **change}
    with pytest.raises(InvalidProblem, match=words):
        tiles_from_dict(doc, "s.json")


def test_bad_tiles(built):
    p, sol = built
    doc = json.loads(dump(tiles_to_dict(p, sol)))
    doc["tiles"]["interior"] = []
    with pytest.raises(InvalidProblem, match="has 1 interior tiles"):
        tiles_from_dict(doc, "s.json")
    doc = json.loads(dump(tiles_to_dict(p, sol)))
    doc["tiles"]["corner"][0][0] = [0.1, 0.2]
    with pytest.raises(InvalidProblem, match="not an \\[x, y, z\\] triple"):
        tiles_from_dict(doc, "s.json")


def test_windows_round_trip_and_files(built, tmp_path):
    p, sol = built
    box = Box(2**50, -3, 7, 1, 1, 1)
    problem = PoissonSphereWindowProblem(sol.tiling, box)
    w = PoissonSphereWindow(box, np.array([[0.25, 0.5, 0.75], [0.1, 0.2, 0.3]]), p.distance)
    wsol = Solution(Status.SAT, w, method="window", seed=3)
    text = dump(window_to_dict(problem, wsol))
    doc = json.loads(text)
    assert doc["version"] == 2 and doc["tileset"] == json.loads(dump(tiles_to_dict(p, sol)))
    q, back = window_from_dict(doc, "w.json")
    assert q.tileset.problem == p and (q.box, q.hash) == (box, "long")
    assert all(np.array_equal(a, b) for k in sol.tiling.tiles for a, b in zip(sol.tiling.tiles[k], q.tileset.tiles[k]))
    assert isinstance(back.tiling, SeededBox) and back.tiling.seed == back.seed == 3
    assert back.tiling.box == box and np.array_equal(back.tiling.local, w.local)
    assert dump(window_to_dict(q, back)) == text  # same bytes again
    with pytest.raises(InvalidProblem, match="beyond"):
        check_point_output3(tmp_path / "w.npy", box)
    with pytest.raises(InvalidProblem, match="cannot tell the format"):
        check_point_output3(tmp_path / "w.txt", box)
    near = Box(-1, 2, 3, 1, 1, 1)
    problem = PoissonSphereWindowProblem(sol.tiling, near)
    wsol = Solution(Status.SAT, PoissonSphereWindow(near, w.local, p.distance), method="window", seed=3)
    write_points3(tmp_path / "w.npy", problem, wsol)
    write_points3(tmp_path / "w.csv", problem, wsol)
    assert np.array_equal(np.load(tmp_path / "w.npy"), w.local + [-1, 2, 3])
    assert np.allclose(np.loadtxt(tmp_path / "w.csv", delimiter=",", skiprows=1), w.local + [-1, 2, 3])
    assert (tmp_path / "w.csv").read_text().startswith("x,y,z\n")


@pytest.fixture(scope="module")
def box_doc(built):
    p, sol = built
    box = Box(-4, 9, 2**40, 1, 2, 1)
    w = PoissonSphereWindow(box, np.array([[0.25, 0.5, 0.75]]), p.distance)
    return json.loads(dump(window_to_dict(PoissonSphereWindowProblem(sol.tiling, box, "table"),
                                          Solution(Status.SAT, w, method="window", seed=6))))


def test_a_version_1_box_is_read_as_points_of_the_set_alone(built, box_doc):
    doc = {k: v for k, v in box_doc.items() if k != "tileset"}
    doc["version"] = 1
    q, back = window_from_dict(doc, "w1.json")
    assert q == built[0] and not isinstance(back.tiling, SeededBox) and back.seed == 6
    assert np.array_equal(back.tiling.local, [[0.25, 0.5, 0.75]])


@pytest.mark.parametrize("edit, words", [
    (lambda d: d.pop("tileset"), "missing field 'tileset'"),
    (lambda d: d.pop("seed"), "missing field 'seed'"),
    (lambda d: d.update(seed=None), "states the seed of its tiling, not null"),
    (lambda d: d.update(version=1), "unknown field 'tileset'"),
    (lambda d: d.update(rho=0.5, distance=None) or d.pop("distance"), "but its tileset is"),
    (lambda d: d["tileset"]["tiles"].pop("zface"), r"w.json \(tileset\): 'tiles'"),
    (lambda d: d["tileset"].update(format="tilesolve/poisson-sphere-window"), "tileset"),
    (lambda d: d.update(hash="md5"), "w.json: unknown hash 'md5'"),
    (lambda d: d["box"].update(width=10**6), "w.json: a 1000000x2x1 box holds about"),
])
def test_bad_version_2_boxes_are_one_line_errors(box_doc, edit, words):
    doc = json.loads(json.dumps(box_doc))
    edit(doc)
    with pytest.raises(InvalidProblem, match=words):  # one line: the console script's forgeries check it
        window_from_dict(doc, "w.json")
