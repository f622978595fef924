"""``tilesolve aperiodic tiling`` through the console script: verified files and pictures, windows
of one seed that agree where they overlap, the same bytes for the same seed, and bad input
refused with one line (exit 2) and no file written."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from clitools import one_line_error, run, snapshot
from tilesolve.io.jsonio import decode_array

SETS = ("jeandel-rao", "labbe-u19", "kari-14", "kari-culik-13")


def _tiles_by_cell(path) -> dict[tuple[int, int], int]:
    """``{(x, y): tile}`` of a window file, from its recorded window."""
    doc = json.loads(path.read_text())
    w = doc["window"]
    grid = decode_array(doc["grid"], "grid", path)
    assert grid.shape == (w["height"], w["width"]) and w["y_up"]
    return {(w["x0"] + c, w["y0"] + w["height"] - 1 - r): int(grid[r, c])
            for r in range(w["height"]) for c in range(w["width"])}


@pytest.mark.parametrize("name", SETS)
def test_files_of_one_seed_agree_where_their_windows_overlap(tmp_path, name):
    for out, region in (("a.json", "-12,-3,20x11"), ("b.json", "-2,4,15x9")):
        proc = run("aperiodic", "tiling", "--builtin", name, "--region", region, "--seed", "8", "-o", out,
                   cwd=tmp_path)
        assert proc.returncode == 0, proc.stderr
        assert run("verify", out, cwd=tmp_path).returncode == 0
    a, b = _tiles_by_cell(tmp_path / "a.json"), _tiles_by_cell(tmp_path / "b.json")
    shared = a.keys() & b.keys()
    assert len(shared) == 10 * 4 and all(a[k] == b[k] for k in shared)


def test_the_same_seed_writes_the_same_bytes_and_the_file_verifies(tmp_path):
    args = ["aperiodic", "tiling", "--builtin", "jeandel-rao", "--region", "-30,17,60x40", "--seed", "5"]
    for d in ("one", "two"):
        (tmp_path / d).mkdir()
        proc = run(*args, "-o", "t.json", "--png", "t.png", "--svg", "t.svg", cwd=tmp_path / d)
        assert proc.returncode == 0, proc.stderr
        assert "sat: window x -30..29, y 17..56 (y grows upwards) of the jeandel-rao set (11 Wang tiles) by markov, " \
               "seed 5" in proc.stderr
    assert snapshot(tmp_path / "one") == snapshot(tmp_path / "two")
    doc = json.loads((tmp_path / "one" / "t.json").read_text())
    assert doc["window"] == {"x0": -30, "y0": 17, "width": 60, "height": 40, "y_up": True}
    assert (doc["method"], doc["seed"], doc["tileset"]["name"]) == ("markov", 5, "jeandel-rao")
    proc = run("verify", "t.json", cwd=tmp_path / "one")
    assert proc.returncode == 0 and proc.stdout.startswith("ok: t.json is a valid tiling of window x -30..29")
    from PIL import Image

    with Image.open(tmp_path / "one" / "t.png") as img:
        assert img.width == 60 * 17 and 40 * 17 < img.height < 40 * 17 + 60  # about 1024 px wide; the caption


def test_another_seed_writes_another_window(tmp_path):
    grids = []
    for seed in ("1", "2"):
        proc = run("aperiodic", "tiling", "--builtin", "kari-14", "--region", "0,0,30x12", "--seed", seed, "-o",
                   f"{seed}.json", cwd=tmp_path)
        assert proc.returncode == 0, proc.stderr
        grids.append(json.loads((tmp_path / f"{seed}.json").read_text())["grid"])
    assert grids[0] != grids[1]


def test_without_outputs_the_grid_is_printed(tmp_path):
    proc = run("aperiodic", "tiling", "--builtin", "kari-culik-13", "--region", "3,-2,7x4", "--seed", "1",
               cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    rows = [[int(v) for v in line.split()] for line in proc.stdout.splitlines()]
    assert np.array(rows).shape == (4, 7) and all(0 <= v < 13 for row in rows for v in row)
    assert snapshot(tmp_path) == {}


BAD = [
    (["--builtin", "jeandel-rao", "--region", "0,0;8x8", "-o", "t.json"], "cannot read region '0,0;8x8'"),
    (["--builtin", "jeandel-rao", "--region", "0,0,0x8", "-o", "t.json"], "window size must be positive"),
    (["--builtin", "no-such-set", "--region", "0,0,8x8", "-o", "t.json"], "no built-in tile set 'no-such-set'"),
    (["--builtin", "ammann-16", "--region", "0,0,8x8", "-o", "t.json"],
     "the built-in set 'ammann-16' has no constructive route; windows are built for jeandel-rao, kari-14, "
     "kari-culik-13, labbe-u19"),
    (["--builtin", "kari-14", "--region", "0,0,100000x100000", "--png", "t.png"],
     "a 100000x100000 window has 10,000,000,000 tiles and needs about"),
    (["--builtin", "kari-14", "--region", "5,5,300x300", "-o", "t.json", "--svg", "t.svg"],
     "a 300x300 window is too large for SVG (at most 65,536 tiles); use --png"),
    (["--builtin", "kari-14", "--region", "5,5,300x300"], "too many to print (at most 65,536): write it with -o"),
    (["--builtin", "labbe-u19", "--region", "0,0,8x8", "-o", "missing/t.json", "--png", "t.png"],
     "cannot write missing/t.json: directory missing does not exist"),
    (["--builtin", "labbe-u19", "--region", "0,0,8x8", "-o", "t.json", "--png", "t.json"], "--png writes .png files"),
    (["--builtin", "labbe-u19", "--region", "0,0,8x8", "--seed", "-3", "-o", "t.json"], "--seed"),
]


@pytest.mark.parametrize("args, message", BAD, ids=[" ".join(a) for a, _ in BAD])
def test_bad_input_is_one_line_and_writes_nothing(tmp_path, args, message):
    line = one_line_error(run("aperiodic", "tiling", *args, cwd=tmp_path))
    assert message in line, line
    assert snapshot(tmp_path) == {}


def test_the_readme_window_is_what_its_command_draws(tmp_path):
    proc = run("aperiodic", "tiling", "--builtin", "jeandel-rao", "--region", "-20,-10,40x24", "--seed", "1",
               "-o", "jr-window.json", "--png", "jr-window.png", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    shipped = Path(__file__).resolve().parents[2] / "examples" / "jr-window.png"
    assert np.array_equal(np.asarray(Image.open(tmp_path / "jr-window.png")), np.asarray(Image.open(shipped)))
