"""A window of the plane as data (tilesolve.model.window) and the one ``--region X0,Y0,WxH``
parser that ``tiling`` and ``wall`` share: the same sizes (W columns, H rows) and the same
one-line errors, through the console script."""

from __future__ import annotations

import json

import pytest

from clitools import one_line_error, run
from tilesolve.errors import InvalidProblem
from tilesolve.model.window import Window, parse_region

COMMANDS = {
    "tiling": ["tiling", "--kind", "wang", "--colors", "2", "--seed", "1"],
    "wall": ["wall", "--max-line", "3", "--seed", "1"],
}


@pytest.mark.fast_cases(3)
@pytest.mark.parametrize("text,message", [
    ("1,2", "cannot read region '1,2': expected X0,Y0,WxH"),
    ("a,b,3x3", "cannot read region 'a,b,3x3'"),
    ("0,0,0x3", "window size must be positive, got 0x3 (WxH)"),
    (f"{2**62},0,3x3", "leaves the lattice tilesolve addresses"),
    ("0,0,3x", "cannot read region '0,0,3x'"),
    ("0,0,-3x3", "cannot read region '0,0,-3x3'"),
    ("0,0,3x0", "window size must be positive, got 3x0 (WxH)"),
])
def test_both_region_options_give_the_same_one_line_error(tmp_path, text, message):
    lines = set()
    for name, args in COMMANDS.items():
        line = one_line_error(run(*args, "--region", text, "-o", "x.json", cwd=tmp_path))
        assert message in line, (name, line)
        lines.add(line)
    assert len(lines) == 1  # one parser
    assert list(tmp_path.iterdir()) == []


@pytest.mark.slow
def test_both_region_options_read_width_then_height(tmp_path):
    for name, args in COMMANDS.items():
        r = run(*args, "--region", "-2,7,5x3", "-o", f"{name}.json", cwd=tmp_path)
        assert r.returncode == 0, r.stderr
        doc = json.loads((tmp_path / f"{name}.json").read_text())
        assert Window.from_dict(doc["window"]) == Window(-2, 7, 5, 3)
    tiles = json.loads((tmp_path / "tiling.json").read_text())["grid"]
    assert len(tiles) == 3 and len(tiles[0]) == 5
    wall = json.loads((tmp_path / "wall.json").read_text())["grid"]
    assert (wall["rows"], wall["cols"]) == (3, 5)


def test_cells_rows_from_the_top():
    w = Window(10, -4, 3, 2)
    assert [w.cell(r, c) for r in range(2) for c in range(3)] == [(10, -3), (11, -3), (12, -3),
                                                                  (10, -4), (11, -4), (12, -4)]
    down = Window(10, -4, 3, 2, y_up=False)
    assert down.cell(0, 0) == (10, -4) and down.cell(1, 2) == (12, -3)
    assert "y grows downwards" in down.describe() and down.caption().endswith("top-left cell x 10, y -4")


@pytest.mark.parametrize("doc,message", [
    ({"x0": 0, "y0": 0, "width": 2}, "window has no 'height'"),
    ({"x0": 0, "y0": 0, "width": 2, "height": 2, "z": 1}, "unknown window field 'z'"),
    ({"x0": True, "y0": 0, "width": 2, "height": 2}, "window x0 must be an integer"),
    ({"x0": 0, "y0": 0, "width": 2, "height": 2, "y_up": 1}, "y_up must be true or false"),
    ([0, 0, 2, 2], "a window is an object"),
])
def test_from_dict_refuses_in_one_line(doc, message):
    with pytest.raises(InvalidProblem, match=message) as exc:
        Window.from_dict(doc)
    assert "\n" not in str(exc.value)


def test_round_trip_and_parse():
    w = parse_region(" -40 , 12 , 64X40 ")
    assert w == Window(-40, 12, 64, 40) and Window.from_dict(json.loads(json.dumps(w.to_dict()))) == w
    assert Window.from_dict({"x0": 1, "y0": 2, "width": 3, "height": 4}).y_up is True
