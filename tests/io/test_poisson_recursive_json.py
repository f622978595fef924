"""Recursive Wang tile sets and windows as files: round trips, same bytes, one-line refusals."""

from __future__ import annotations

import json

import numpy as np
import pytest

from tilesolve.constructive.poisson_recursive import build_recursive, sample_window
from tilesolve.errors import InvalidProblem
from tilesolve.io.poisson_recursive_json import (
    SeededRecursiveWindow,
    dump,
    set_from_dict,
    set_to_dict,
    window_from_dict,
    window_to_dict,
    write_points,
)
from tilesolve.model.poisson_recursive import RecursiveTilesProblem, RecursiveWindowProblem
from tilesolve.model.solution import Solution, Status


@pytest.fixture(scope="module")
def built():
    p = RecursiveTilesProblem(2, 16, 0.7, 2)
    return p, Solution(Status.SAT, build_recursive(p, seed=3), method="build", seed=3)


@pytest.fixture(scope="module")
def window(built):
    problem = RecursiveWindowProblem(built[1].tiling, (-5, 2**40, 2, 1), density=np.array([[30.0, 60.0]]))
    return problem, Solution(Status.SAT, sample_window(problem, seed=1), method="window", seed=1)


def test_a_set_round_trips_to_the_same_bytes(built):
    text = dump(set_to_dict(*built))
    p, sol = set_from_dict(json.loads(text), "s.json")
    assert p == built[0] and (sol.tiling.rules == built[1].tiling.rules).all()
    assert dump(set_to_dict(p, sol)) == text
    assert json.loads(text)["base"]["format"] == "tilesolve/poisson-tiles"


def test_a_window_round_trips_to_the_same_bytes(window):
    problem, sol = window
    text = dump(window_to_dict(problem, sol))
    p, back = window_from_dict(json.loads(text), "w.json")
    w = back.tiling
    assert json.loads(text)["version"] == 2 and p.tileset.problem == problem.tileset.problem
    assert (p.tileset.rules == problem.tileset.rules).all() and np.array_equal(p.density, problem.density)
    assert (p.level, p.label, p.hash, p.window) == (problem.level, problem.label, problem.hash, problem.window)
    assert isinstance(w, SeededRecursiveWindow) and w.seed == 1 and w.window == problem.window
    assert (w.local == sol.tiling.local).all() and (w.level == sol.tiling.level).all()
    assert (w.rank == sol.tiling.rank).all()
    assert dump(window_to_dict(p, Solution(Status.SAT, w, method="window", seed=1))) == text


def test_a_version_1_window_is_read_as_points_of_the_set_alone(window):
    doc = json.loads(dump(window_to_dict(*window)))
    for key in ("tileset", "density_grid"):
        doc.pop(key)
    doc["version"] = 1
    p, back = window_from_dict(doc, "w1.json")
    assert p == window[0].tileset.problem and not isinstance(back.tiling, SeededRecursiveWindow)


def test_csv_and_npy_hold_plane_coordinates_level_and_rank(tmp_path, built):
    problem = RecursiveWindowProblem(built[1].tiling, (7, -3, 2, 2), level=1)
    sol = Solution(Status.SAT, sample_window(problem, seed=2), method="window", seed=2)
    write_points(tmp_path / "p.csv", problem, sol)
    write_points(tmp_path / "p.npy", problem, sol)
    table = np.loadtxt(tmp_path / "p.csv", delimiter=",", skiprows=1)
    assert (tmp_path / "p.csv").read_text().startswith("x,y,level,rank\n")
    assert np.array_equal(table, np.load(tmp_path / "p.npy"))
    assert np.allclose(table[:, :2], sol.tiling.local + [7, -3]) and set(table[:, 2]) == {0.0, 1.0}


@pytest.mark.parametrize("change, words", [
    (lambda d: d.update(subdivision=9), "subdivision"),
    (lambda d: d.update(subdivision=True), "subdivision"),
    (lambda d: d.update(rules=d["rules"][:3]), "'rules'"),
    (lambda d: d["rules"][0][0].__setitem__(0, True), "'rules'"),
    (lambda d: d["base"].update(distance=0.5), "distance"),
    (lambda d: d.update(extra=1), "extra"),
    (lambda d: d.update(rules=[[[0] * 3] * 3] * 15 + [[[0] * 3] * 2]), "'rules'"),
])
def test_bad_set_documents_are_refused_in_one_line(built, change, words):
    doc = json.loads(dump(set_to_dict(*built)))
    change(doc)
    with pytest.raises(InvalidProblem) as exc:
        set_from_dict(doc, "s.json")
    assert words in str(exc.value) and "\n" not in str(exc.value)


@pytest.mark.parametrize("change, words", [
    (lambda d: d["local"].append([0.5, 0.5, 3, 0.1]), "level"),
    (lambda d: d["local"].append([0.5, 0.5, 0.5, 0.1]), "level"),
    (lambda d: d["local"].append([0.5, 0.5, 0]), "[x, y, level, rank]"),
    (lambda d: d["local"].append([0.5, "x", 0, 0.1]), "[x, y, level, rank]"),
    (lambda d: d.update(level=13), "level"),
    (lambda d: d.update(distance=1.0), "distance"),
    (lambda d: d.pop("subdivision"), "subdivision"),
    (lambda d: d.pop("tileset"), "missing field 'tileset'"),
    (lambda d: d.update(seed=None), "seed"),
    (lambda d: d.update(density_grid=[[30.0], [1.0, 2.0]]), "density_grid"),
    (lambda d: d.update(density_grid=[[-1.0]]), "density_grid"),
    (lambda d: d.update(density_grid=[[True]]), "density_grid"),
    (lambda d: d.update(density_grid=[[30.0] * 8] * 8, level=2), "needs level 1"),
    (lambda d: d["tileset"]["base"].update(lloyd=1), "but its tileset is"),
    (lambda d: d["tileset"].update(subdivision=3), "(tileset): 'rules'"),
    (lambda d: d["tileset"].pop("rules"), "w.json (tileset): missing field 'rules'"),
    (lambda d: d.update(hash="short"), "hash"),
])
def test_bad_window_documents_are_refused_in_one_line(window, change, words):
    doc = json.loads(dump(window_to_dict(*window)))
    change(doc)
    with pytest.raises(InvalidProblem) as exc:
        window_from_dict(doc, "w.json")
    assert words in str(exc.value) and "\n" not in str(exc.value)
