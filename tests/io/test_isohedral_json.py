"""The tilesolve/isohedral-tiling file (version 2, and version 1 read) and its pictures
(tilesolve.io.isohedral_json)."""

from __future__ import annotations

import json
import re

import numpy as np
import pytest

from tilesolve.errors import InvalidProblem
from tilesolve.families import isohedral as facade
from tilesolve.family import solution_text
from tilesolve.io.isohedral_json import png_bytes, svg_text, tiling_from_dict
from tilesolve.model.isohedral import MAX_OUTLINE


@pytest.fixture(scope="module")
def drawn():
    problem = facade.problem("IH21", edges=["bezier:0.3,0.1/0.7,-0.1", "bezier:0.2,0.2/0.6,-0.1",
                                                    "line:0.5,0.1"], region=(-1, -1, 6, 4))
    sol = facade.solve(problem)
    return problem, sol, json.loads(solution_text(problem, sol))


def test_round_trip(drawn):
    problem, sol, doc = drawn
    assert doc["format"] == "tilesolve/isohedral-tiling" and doc["version"] == 2 and doc["type"] == "IH21"
    assert "time_s" not in doc and doc["edge_kinds"] == ["S", "J", "J"]
    p2, s2 = tiling_from_dict(doc, "t.json")
    assert p2 == problem and s2.status == sol.status
    for name in ("outline", "aspects", "translations"):
        assert np.allclose(getattr(s2.tiling, name), getattr(sol.tiling, name), atol=1e-11)
    assert s2.tiling.corners == sol.tiling.corners
    assert np.array_equal(s2.tiling.placements, sol.tiling.placements)
    assert np.array_equal(s2.tiling.colours, sol.tiling.colours)
    assert facade.FAMILY.verify(p2, s2.tiling) == []


def test_same_problem_same_bytes(drawn):
    problem, sol, _ = drawn
    again = facade.solve(problem)
    assert solution_text(problem, again) == solution_text(problem, sol)
    assert svg_text(problem, again.tiling) == svg_text(problem, sol.tiling)
    assert png_bytes(problem, again.tiling) == png_bytes(problem, sol.tiling)


def forged(doc, **changes):
    out = dict(doc)
    for k, v in changes.items():
        if v is KeyError:
            del out[k]
        else:
            out[k] = v
    return out


@pytest.mark.parametrize("changes, message", [
    ({"version": 3}, "version 3 is not supported"),
    ({"marking": {"motif": []}}, "'marking' must be null or an object"),
    ({"colour": 1}, "unknown field 'colour'"),
    ({"type": KeyError}, "missing|'type'"),
    ({"type": "IH99"}, "unknown isohedral type"),
    ({"type": "IH20"}, "'edge_kinds' must be|edge classes"),
    ({"outline_of": "IH20"}, "'outline_of' must be None"),
    ({"edge_kinds": ["J", "J", "J"]}, "'edge_kinds' must be"),
    ({"edges": ["bezier:0.3,0.1/0.7,0.1", "line", "line"]}, "is an S edge"),
    ({"edges": "line"}, "'edges' must be a list"),
    ({"edges": [1, 2, 3]}, "'edges' must be a list of edge shapes"),
    ({"params": [0.1]}, "takes 2 parameters"),
    ({"params": [True, 0.5]}, "finite numbers"),
    ({"region": [0, 0, -1, 2]}, "positive sizes"),
    ({"scale": 0}, "scale"),
    ({"outline": [[0, 0], [1]]}, "'outline'"),
    ({"outline": [[0, 0, 1]]}, "'outline' must have shape"),
    ({"outline": [[0, 0]] * (MAX_OUTLINE + 1)}, "at most"),
    ({"outline": [[True, 0], [1, 0], [1, 1]]}, "booleans"),
    ({"aspects": [[[1, 0, 0], [0, 1, 0]]]}, "'aspects' must have shape"),
    ({"translations": [[1, 0]]}, "'translations' must have shape"),
    ({"corners": [0, "3"]}, "'corners' must be a list of integers"),
    ({"placements": [[0, 0]]}, "'placements' must be"),
    ({"colours": [0]}, "'placements' must be|'colours'"),
    ({"status": "maybe"}, "'status' must be one of"),
])
def test_forged_files_are_refused_in_one_line(drawn, changes, message):
    _, _, doc = drawn
    with pytest.raises(InvalidProblem, match=message) as info:
        tiling_from_dict(forged(doc, **changes), "t.json")
    assert str(info.value).startswith("t.json") and "\n" not in str(info.value)


def test_a_readable_but_wrong_tiling_is_the_verifiers(drawn):
    _, _, doc = drawn
    outline = [list(p) for p in doc["outline"]]
    outline[1][0] += 0.05
    p, s = tiling_from_dict(forged(doc, outline=outline), "t.json")
    assert {v.kind for v in facade.FAMILY.verify(p, s.tiling)} == {"template"}


def test_the_svg_shows_the_prototile_once_and_each_tile_by_its_motion(drawn):
    problem, sol, _ = drawn
    text = svg_text(problem, sol.tiling)
    assert text.count("<path ") == 1 and text.count("<use ") == sol.tiling.n_tiles
    w, h = (float(v) for v in re.search(r'<svg [^>]*width="([\d.]+)" height="([\d.]+)"', text).groups())
    assert w >= 240 and h > 160  # the 240x160 px drawing, its caption under it
    assert text.index("<rect ") < text.index("<use ")  # an opaque background first


def test_a_picture_too_large_is_refused():
    problem = facade.problem(41, region=(0, 0, 300, 2), scale=40)
    sol = facade.solve(problem)
    with pytest.raises(InvalidProblem, match="at most 8192 a side"):
        svg_text(problem, sol.tiling)


def test_a_marked_types_markings_round_trip_and_are_drawn():
    problem = facade.problem("IH89", region=(0, 0, 3, 2), scale=60)
    sol = facade.solve(problem)
    doc = json.loads(solution_text(problem, sol))
    p, s = tiling_from_dict(doc, "t.json")
    t = s.tiling
    assert np.array_equal(t.marks, sol.tiling.marks) and len(t.motif) == 3
    assert np.allclose(t.symmetries, sol.tiling.symmetries, atol=1e-12)
    assert facade.FAMILY.verify(p, t) == []
    svg = svg_text(p, t)
    assert svg.count('<path id="mark"') == 1 and svg.count('xlink:href="#mark"') == t.n_tiles
    plain = png_bytes(p, type(t)(*(getattr(t, f) for f in ("type", "outline", "corners", "aspects", "translations",
                                                           "placements", "colours"))))
    assert png_bytes(p, t) != plain  # the flags are drawn
    doc["marking"]["marks"][0] = len(doc["marking"]["symmetries"])
    with pytest.raises(InvalidProblem, match="one index into 'marking.symmetries' per placement"):
        tiling_from_dict(doc, "t.json")
    doc["marking"] = None
    assert tiling_from_dict(doc, "t.json")[1].tiling.marks is None  # read; the verifier's to refuse


def test_a_version_1_file_is_read():
    problem = facade.problem("IH41", region=(0, 0, 2, 2))
    doc = json.loads(solution_text(problem, facade.solve(problem)))
    doc["version"] = 1
    del doc["marking"]
    p, s = tiling_from_dict(doc, "t.json")
    assert facade.FAMILY.verify(p, s.tiling) == []
