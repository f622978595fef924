"""The tilesolve/shapes file: round trips and strict reading."""

from __future__ import annotations

import json

import numpy as np
import pytest

from tilesolve.errors import InvalidProblem
from tilesolve.families.shapes import solve
from tilesolve.io.jsonio import dumps
from tilesolve.io.shapes_json import shapes_from_dict, shapes_to_dict
from tilesolve.model.shapes import ShapesProblem, parse_ascii, parse_cells


@pytest.mark.parametrize("problem", [
    ShapesProblem("tile", (parse_ascii("##", "hex"),), lattice=((4, 0), (0, 3))),
    ShapesProblem("tile", (parse_ascii("##", "omino"), parse_ascii("#", "omino")), region=((0, 0), (1, 0), (2, 0))),
    ShapesProblem("classify", (parse_cells("0,0 0,1 0,2 0,3 1,-1 1,3", "hex"),)),
])
def test_round_trip(problem):
    sol = solve(problem, seed=2)
    doc = json.loads(dumps(shapes_to_dict(problem, sol)))
    p2, s2 = shapes_from_dict(doc, "f.json")
    assert p2 == problem and s2.status is sol.status
    if sol.report is None:
        assert np.array_equal(s2.tiling, sol.tiling)
    else:
        assert s2.report.verdict == sol.report.verdict and np.array_equal(s2.report.patch, sol.report.patch)
        assert s2.report.refutation == sol.report.refutation


@pytest.mark.parametrize("change, message", [
    ({"frobnicate": 1}, "unknown field"),
    ({"grid": 3}, "'grid' must be a string"),
    ({"shapes": [[[0, 0], [2, 0]]]}, "edge-connected"),
    ({"region": [[0, "a"]]}, "'region' must be a list"),
    ({"status": "sat", "tiling": [[0, 0, 0]]}, "'tiling' must be"),
    ({"status": "sat", "report": {"verdict": "isohedral", "extra": 1}}, "unknown report field"),
    ({"holes": "no"}, "'holes' must be true or false"),
])
def test_malformed_fields_are_one_line_errors(change, message):
    doc = {"format": "tilesolve/shapes", "version": 1, "question": "tile", "grid": "omino",
           "shapes": [[[0, 0], [1, 0]]], "region": [[0, 0], [1, 0]]}
    doc.update(change)
    with pytest.raises(InvalidProblem, match=message):
        shapes_from_dict(doc, "f.json")
