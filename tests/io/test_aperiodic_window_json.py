"""The ``tilesolve/aperiodic-window`` file: written and read back, identified by ``tilesolve verify``,
and every forgery refused with one line (exit 2) or reported as violations (exit 1), never a
traceback. The windows here are tiled by the SAT route (engine.aperiodic.decide), so the file
format is tested apart from the constructive kernels."""

from __future__ import annotations

import json

import numpy as np
import pytest

from clitools import one_line_error, run
from tilesolve.engine.aperiodic import decide
from tilesolve.family import RunOptions, read_document, write_solution
from tilesolve.io.aperiodic_window_json import APERIODIC_WINDOW, window_from_dict, window_to_dict
from tilesolve.io.builtin_tilesets import load
from tilesolve.io.jsonio import dumps, parse_json
from tilesolve.model.aperiodic_window import AperiodicWindowProblem
from tilesolve.model.solution import Solution, Status
from tilesolve.model.window import Window


def _window(name: str, window: Window, seed: int = 4) -> tuple[AperiodicWindowProblem, Solution]:
    tileset, _ = load(name)
    cert = decide(tileset, f"square {window.height}x{window.width}", RunOptions(seed=seed))
    assert cert.status == "tiles"
    grid = np.asarray(cert.tiling).reshape(window.shape).astype(np.uint8)
    return AperiodicWindowProblem(name, tileset, window), Solution(Status.SAT, grid, method="markov", seed=seed,
                                                                   stats={"tiles": grid.size}, window=window)


@pytest.fixture(scope="module")
def good(tmp_path_factory) -> dict:
    """A valid Jeandel-Rao window file's document."""
    problem, sol = _window("jeandel-rao", Window(-3, 7, 9, 6))
    return json.loads(dumps(window_to_dict(problem, sol)))


def test_round_trip_records_the_window_tiles_route_and_seed(good):
    problem, sol = window_from_dict(good, "t.json")
    assert good["format"] == APERIODIC_WINDOW and good["version"] == 1
    assert good["window"] == {"x0": -3, "y0": 7, "width": 9, "height": 6, "y_up": True}
    assert good["tileset"]["name"] == "jeandel-rao" and good["tileset"]["order"] == ["N", "E", "S", "W"]
    assert good["tileset"]["tiles"] == load("jeandel-rao")[0].tiles.tolist()
    assert (good["method"], good["seed"]) == ("markov", 4) and "time_s" not in good
    assert problem.window == sol.window == Window(-3, 7, 9, 6)
    assert np.array_equal(sol.tiling, np.asarray(good["grid"]))
    assert json.loads(dumps(window_to_dict(problem, sol))) == good


def test_large_grids_are_encoded_arrays_and_read_back():
    """(The codec writes what it is given; the grid here is not a tiling.)"""
    tileset, _ = load("kari-culik-13")
    grid = np.random.default_rng(1).integers(0, len(tileset), size=(220, 300)).astype(np.uint8)
    problem = AperiodicWindowProblem("kari-culik-13", tileset, Window(0, 0, 300, 220))
    sol = Solution(Status.SAT, grid, method="balanced", seed=2)
    doc = window_to_dict(problem, sol)
    assert doc["grid"]["dtype"] == "uint8" and doc["grid"]["shape"] == [220, 300]
    back = window_from_dict(parse_json(dumps(doc), "k.json"), "k.json")[1]
    assert np.array_equal(back.tiling, sol.tiling)


def test_verify_identifies_the_file_and_accepts_it(good, tmp_path):
    path = tmp_path / "t.json"
    path.write_text(json.dumps(good))
    fam, codec, _ = read_document(path)
    assert fam.name == "aperiodic-window" and codec.format == APERIODIC_WINDOW
    proc = run("verify", "t.json", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.startswith("ok: t.json is a valid tiling of window x -3..5, y 7..12 (y grows upwards) of the "
                                  "jeandel-rao set (11 Wang tiles)")


def test_write_solution_is_the_codec(tmp_path):
    problem, sol = _window("labbe-u19", Window(5, 5, 4, 4))
    write_solution(tmp_path / "u.json", problem, sol)
    assert json.loads((tmp_path / "u.json").read_text())["tileset"]["name"] == "labbe-u19"


def _changed(doc: dict, path: str, value) -> dict:
    out = json.loads(json.dumps(doc))
    *keys, last = path.split(".")
    node = out
    for k in keys:
        node = node[int(k)] if isinstance(node, list) else node[k]
    if isinstance(node, list):
        node[int(last)] = value
    elif value is _DROP:
        del node[last]
    else:
        node[last] = value
    return out


_DROP = object()
JR = load("jeandel-rao")[0].tiles.tolist()
KARI = load("kari-14")[0].tiles.tolist()

#: (what, edit, the one-line error's tail): files refused before any check (exit 2).
REFUSED = [
    ("a changed tile", ("tileset.tiles.3", [4, 2, 1, 3]), "'tileset.tiles' are not the tiles of the built-in set "
                                                          "jeandel-rao (in its order)"),
    ("swapped tiles", ("tileset.tiles", JR[1:2] + JR[:1] + JR[2:]), "are not the tiles of the built-in set"),
    ("another set's tiles", ("tileset.tiles", KARI), "are not the tiles of the built-in set jeandel-rao"),
    ("another set's name", ("tileset.name", "kari-14"), "'tileset.colors' must be 8 for the built-in set kari-14"),
    ("a set that is not built in", ("tileset.name", "my-tiles"), "no built-in tile set 'my-tiles'"),
    ("colours as floats", ("tileset.tiles.0", [1.0, 1, 1, 3]), "are not the tiles of the built-in set"),
    ("a colour count as a float", ("tileset.colors", 5.0), "'tileset.colors' must be 5"),
    ("another edge order", ("tileset.order", ["W", "N", "E", "S"]), "'tileset.order' must be ['N', 'E', 'S', 'W']"),
    ("no tile set", ("tileset", _DROP), "missing field 'tileset'"),
    ("a window far away", ("window.x0", 10**30), "leaves the lattice tilesolve addresses"),
    ("a window of float size", ("window.width", 9.5), "window width must be an integer"),
    ("a huge window", ("window.width", 10**9), "window has 6,000,000,000 tiles and needs about"),
    ("a window field too many", ("window.z", 1), "'window' must be an object with exactly the fields"),
    ("a grid number too large for JSON integers", ("grid.0.0", 10**30), "'grid': must hold integers only"),
    ("a grid of floats", ("grid.0.0", 0.5), "'grid': must hold integers only"),
    ("an unknown field", ("colour", 3), "unknown field 'colour'"),
    ("a negative seed", ("seed", -1), "'seed' must be an integer from 0"),
    ("a bad status", ("status", "maybe"), "'status' must be one of"),
]


@pytest.mark.parametrize("what, edit, message", REFUSED, ids=[r[0] for r in REFUSED])
def test_forged_files_are_refused_with_one_line(good, tmp_path, what, edit, message):
    (tmp_path / "f.json").write_text(json.dumps(_changed(good, *edit)))
    line = one_line_error(run("verify", "f.json", cwd=tmp_path))
    assert message in line, line


@pytest.mark.parametrize("text, message", [
    (lambda t: t[: len(t) // 2], "malformed JSON"),
    (lambda t: t.replace('"seed": 4', '"seed": NaN'), "NaN is not a JSON number"),
    (lambda t: t.replace('"seed": 4', '"seed": 1e999'), "too large"),
    (lambda t: t.replace('"version": 1', '"version": 2'), "version 2"),
])
def test_broken_json_is_refused_with_one_line(good, tmp_path, text, message):
    (tmp_path / "f.json").write_text(text(json.dumps(good)))
    assert message in one_line_error(run("verify", "f.json", cwd=tmp_path))


#: (what, edit, a line the report must hold): files whose grid is checked and found wrong (exit 1).
VIOLATED = [
    ("a changed grid tile", ("grid.2.4", None), "meets"),
    ("a tile number out of range", ("grid.0.0", 11), "tile 11 is not in 0..10"),
    ("a negative tile number", ("grid.5.8", -1), "tile -1 is not in 0..10"),
    ("a window wider than the grid", ("window.width", 10), "the grid has shape [6, 9], the window x -3..6"),
    ("a window lower than the grid", ("window.height", 5), "has 5 rows of 9 tiles"),
]


@pytest.mark.parametrize("what, edit, message", VIOLATED, ids=[v[0] for v in VIOLATED])
def test_wrong_grids_are_reported_as_violations(good, tmp_path, what, edit, message):
    path, value = edit
    if value is None:  # another tile whose edges do not all match
        r, c = (int(v) for v in path.split(".")[1:])
        value = (good["grid"][r][c] + 5) % 11
    (tmp_path / "f.json").write_text(json.dumps(_changed(good, path, value)))
    proc = run("verify", "f.json", cwd=tmp_path)
    assert proc.returncode == 1 and "Traceback" not in proc.stderr, proc.stderr
    assert proc.stdout.startswith("f.json: ") and "violation" in proc.stdout.splitlines()[0]
    assert message in proc.stdout, proc.stdout
