"""Poisson tile-set and window files: round trips, exact floats, refusals."""

from __future__ import annotations

import json

import numpy as np
import pytest

from tilesolve.constructive.poisson import build_tiles, window_points
from tilesolve.errors import InvalidProblem
from tilesolve.io.poisson_json import (
    SeededWindow,
    dump,
    tiles_from_dict,
    tiles_to_dict,
    window_from_dict,
    window_to_dict,
    write_points,
)
from tilesolve.model.poisson import PoissonTilesProblem, PoissonWindowProblem
from tilesolve.model.solution import Solution, Status


@pytest.fixture(scope="module")
def built():
    p = PoissonTilesProblem(1, 24, 0.7)
    ts = build_tiles(p, seed=2)
    return p, Solution(Status.SAT, ts, method="dart", seed=2, stats=ts.stats)


def test_a_set_round_trips_exactly(built):
    p, sol = built
    q, back = tiles_from_dict(json.loads(dump(tiles_to_dict(p, sol))), "s.json")
    assert q == p and back.seed == 2
    for kind, arrays in sol.tiling.tiles.items():
        assert all(np.array_equal(a, b) for a, b in zip(arrays, back.tiling.tiles[kind]))


def test_a_window_round_trips_exactly(built, tmp_path):
    p, sol = built
    wp = PoissonWindowProblem(sol.tiling, (2**50, -3, 3, 2))
    w = window_points(sol.tiling, wp.window, seed=1)
    doc = json.loads(dump(window_to_dict(wp, Solution(Status.SAT, w, method="window", seed=1))))
    q, back = window_from_dict(doc, "w.json")
    assert doc["version"] == 2 and doc["tileset"]["format"] == "tilesolve/poisson-tiles"
    assert q.tileset.problem == p and (q.tiling, q.variant, q.hash, q.window) == ("direct", "complete", "long", wp.window)
    assert all(np.array_equal(a, b) for k in sol.tiling.tiles for a, b in zip(sol.tiling.tiles[k], q.tileset.tiles[k]))
    assert isinstance(back.tiling, SeededWindow) and back.tiling.seed == back.seed == 1
    assert back.tiling.window == wp.window and np.array_equal(back.tiling.local, w.local)
    assert dump(window_to_dict(q, back)) == dump(doc)
    with pytest.raises(InvalidProblem, match="beyond"):
        write_points(tmp_path / "w.csv", wp, Solution(Status.SAT, w, method="window", seed=1))
    assert not (tmp_path / "w.csv").exists()


def test_csv_and_npy_hold_plane_coordinates(built, tmp_path):
    _, sol = built
    wp = PoissonWindowProblem(sol.tiling, (-5, 7, 2, 2))
    w = window_points(sol.tiling, wp.window, seed=1)
    s = Solution(Status.SAT, w, method="window", seed=1)
    write_points(tmp_path / "w.csv", wp, s)
    write_points(tmp_path / "w.npy", wp, s)
    csv = np.loadtxt(tmp_path / "w.csv", delimiter=",", skiprows=1)
    assert np.array_equal(csv, w.absolute()) and np.array_equal(np.load(tmp_path / "w.npy"), w.absolute())
    assert (tmp_path / "w.csv").read_text().startswith("x,y\n")


@pytest.mark.parametrize("edit, words", [
    (lambda d: d.update(version=9), "version 9"),
    (lambda d: d.update(extra=1), "unknown field"),
    (lambda d: d.update(rho=2), "rho"),
    (lambda d: d["tiles"].pop("vedge"), "tiles"),
    (lambda d: d["tiles"]["corner"][0].append([1, "x"]), "corner"),
    (lambda d: d["tiles"]["interior"].append([]), "interior"),
    (lambda d: d.update(seed=-1), "seed"),
    (lambda d: d.update(distance=d["distance"] / 2), "'distance' is"),  # a weaker promise, forged
    (lambda d: d.update(distance="0.1"), "'distance' is"),
])
def test_bad_set_files_are_one_line_errors(built, edit, words):
    p, sol = built
    doc = json.loads(dump(tiles_to_dict(p, sol)))
    edit(doc)
    with pytest.raises(InvalidProblem, match=words):
        tiles_from_dict(doc, "s.json")


@pytest.fixture(scope="module")
def window_doc(built):
    wp = PoissonWindowProblem(built[1].tiling, (-4, 9, 2, 2))
    w = window_points(built[1].tiling, wp.window, seed=3)
    return json.loads(dump(window_to_dict(wp, Solution(Status.SAT, w, method="window", seed=3))))


def test_a_version_1_window_is_read_as_points_of_the_set_alone(built, window_doc):
    doc = {k: v for k, v in window_doc.items() if k != "tileset"}
    doc["version"] = 1
    q, back = window_from_dict(doc, "w1.json")
    assert q == built[0] and not isinstance(back.tiling, SeededWindow) and len(back.tiling.local) == len(doc["local"])


@pytest.mark.parametrize("edit, words", [
    (lambda d: d.pop("tileset"), "missing field 'tileset'"),
    (lambda d: d.update(seed=None), "seed"),
    (lambda d: d.update(version=1), "unknown field 'tileset'"),
    (lambda d: d["tileset"].update(rho=0.6, distance=None) or d["tileset"].pop("distance"), "but its tileset is"),
    (lambda d: d["tileset"]["tiles"].pop("hedge"), r"w.json \(tileset\): 'tiles'"),
    (lambda d: d["tileset"].update(format="tilesolve/poisson-window"), "tileset"),
    (lambda d: d.update(tiling="diagonal"), "corner tiling"),
    (lambda d: d.update(set="compact"), "compact"),
])
def test_bad_version_2_windows_are_one_line_errors(window_doc, edit, words):
    doc = json.loads(json.dumps(window_doc))
    edit(doc)
    with pytest.raises(InvalidProblem, match=words) as exc:
        window_from_dict(doc, "w.json")
    assert "\n" not in str(exc.value)
