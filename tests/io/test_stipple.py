"""Reading a picture as a density; the stippled pictures."""

from __future__ import annotations

import numpy as np
import pytest
from PIL import Image

from tilesolve.errors import InvalidProblem
from tilesolve.io.stipple import dot_radii, read_density, stipple_svg, write_periodograms_png, write_stipple
from tilesolve.model.importance import builtin_density


def test_darkness_of_a_picture(tmp_path):
    a = np.full((4, 6), 255, np.uint8)
    a[0, 0] = 0
    Image.fromarray(a, "L").save(tmp_path / "g.png")
    d = read_density(tmp_path / "g.png")
    assert d.values.shape == (4, 6) and d.values[0, 0] == 1.0 and d.values[1:, 1:].max() == 0.0
    assert (d.width, d.height) == (1.0, pytest.approx(4 / 6))


def test_a_picture_named_like_a_built_in_image_keeps_its_own_name(tmp_path):
    # verify holds a density named "radial" to the built-in radial image: a user's file that
    # happens to be called radial must not take that name (its genuine stipple file would fail)
    Image.fromarray(np.zeros((4, 4), np.uint8), "L").save(tmp_path / "radial", format="PNG")
    assert read_density(tmp_path / "radial").name == "./radial"
    Image.fromarray(np.zeros((4, 4), np.uint8), "L").save(tmp_path / "ramp.png")
    assert read_density(tmp_path / "ramp.png").name == "ramp.png"


def test_transparent_pixels_are_white_paper(tmp_path):
    a = np.zeros((2, 2, 4), np.uint8)
    a[0, 0] = (0, 0, 0, 255)  # one opaque black pixel; the others transparent black
    Image.fromarray(a, "RGBA").save(tmp_path / "t.png")
    assert read_density(tmp_path / "t.png").values.tolist() == [[1.0, 0.0], [0.0, 0.0]]


def test_bad_pictures_are_one_line_errors(tmp_path):
    (tmp_path / "x.png").write_text("not a picture")
    with pytest.raises(InvalidProblem, match="not a readable image"):
        read_density(tmp_path / "x.png")
    with pytest.raises(InvalidProblem, match="no such file"):
        read_density(tmp_path / "missing.png")
    Image.new("L", (3, 3), 255).save(tmp_path / "white.png")
    with pytest.raises(InvalidProblem, match="zero everywhere"):
        read_density(tmp_path / "white.png")


def test_dots_are_larger_where_it_is_dark():
    d = builtin_density("gradient", 16)
    r = dot_radii(np.array([[0.01, 0.5], [0.99, 0.5]]), d)
    assert r[1] > 1.5 * r[0]


def test_pictures(tmp_path):
    d = builtin_density("radial", 16)
    pts = np.array([[0.5, 0.5], [0.1, 0.9]])
    text = stipple_svg(pts, d, "two")
    assert text.count("<path") == 1 and text.split(' d="', 1)[1].split('"', 1)[0].count("M") == 2
    write_stipple(tmp_path / "s.png", pts, d, "two", "png")
    with Image.open(tmp_path / "s.png") as img:
        assert img.size == (800, 820)
        assert np.asarray(img).min() == 0  # a black dot
    write_periodograms_png(tmp_path / "p.png", [("a", np.ones((9, 9))), ("b", np.ones((9, 9)))], "t")
    assert (tmp_path / "p.png").read_bytes()[:4] == b"\x89PNG"


def test_a_stipple_file_round_trips_to_the_same_bytes():
    import json

    from tilesolve.io.stipple import Samples, dump, stipple_from_dict, stipple_to_dict
    from tilesolve.model.importance import ImportanceProblem
    from tilesolve.model.solution import Solution, Status

    p = ImportanceProblem(builtin_density("radial", 8), 30, "penrose", "chair", 2, True)
    pts = np.array([[0.1, 0.2], [1 / 3, 0.9]])
    text = dump(stipple_to_dict(p, Solution(Status.SAT, Samples(pts), seed=5)))
    q, sol = stipple_from_dict(json.loads(text), "s.json")
    assert (q.method, q.points, q.tile, q.lloyd, q.jitter, q.density.name) == ("penrose", 30, "chair", 2, True, "radial")
    assert np.array_equal(q.density.values, p.density.values) and np.array_equal(sol.tiling.points, pts)
    assert sol.tiling.seed == sol.seed == 5
    assert dump(stipple_to_dict(q, sol)) == text
    doc = json.loads(text)
    doc["density"] = [[1.0, 2.0], [3.0]]
    with pytest.raises(InvalidProblem, match="'density' must be equal rows"):
        stipple_from_dict(doc, "s.json")


@pytest.mark.parametrize("correct", [True, False])
def test_version_2_records_the_correction_table(correct):
    import json

    from tilesolve.io.stipple import Samples, dump, stipple_from_dict, stipple_to_dict
    from tilesolve.model.importance import ImportanceProblem
    from tilesolve.model.solution import Solution, Status

    p = ImportanceProblem(builtin_density("radial", 8), 30, "polyomino", "x-pentomino", 0, False, correct)
    assert p.corrected is correct
    text = dump(stipple_to_dict(p, Solution(Status.SAT, Samples(np.array([[0.5, 0.5]])), seed=2)))
    doc = json.loads(text)
    assert (doc["version"], doc["correct"]) == (2, correct)
    q, sol = stipple_from_dict(doc, "s.json")
    assert (q.correct, q.corrected) == (correct, correct)
    assert dump(stipple_to_dict(q, sol)) == text
    doc.pop("correct")
    with pytest.raises(InvalidProblem, match="missing field 'correct'"):
        stipple_from_dict(doc, "s.json")
    doc["correct"] = "yes"
    with pytest.raises(InvalidProblem, match="'correct' must be true or false"):
        stipple_from_dict(doc, "s.json")


def test_version_1_is_read_without_the_correction_table():
    """A version 1 file was written before the table: read as ``correct=False``; it has no
    ``correct`` field to state."""
    from tilesolve.io.stipple import stipple_from_dict

    doc = {"format": "tilesolve/stipple", "version": 1, "method": "polyomino", "points": 30, "tile": "x-pentomino",
           "lloyd": 0, "jitter": False, "seed": 2, "image": "flat", "density": [[1.0, 1.0], [1.0, 1.0]],
           "samples": [[0.5, 0.5]]}
    q, _ = stipple_from_dict(doc, "s.json")
    assert (q.correct, q.corrected) == (False, False)
    doc["correct"] = True
    with pytest.raises(InvalidProblem, match="unknown field 'correct'"):
        stipple_from_dict(doc, "s.json")
