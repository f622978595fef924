"""The ``tilesolve/stochastic-tiling`` file (tilesolve.io.stochastic_json): version 2 records the
window of the plane as data (origin, size, y direction); version 1 files still read, verify and
draw; a window that disagrees with the grid, or whose y grows downwards, is refused. Through the
console script."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from clitools import one_line_error, run

DATA = Path(__file__).resolve().parent.parent / "data" / "stochastic_tiling"
#: Written by ``tilesolve tiling --kind wang --method scanline --set compact --colors 2
#: --region -3,2,5x4 --seed 11`` before version 2 (the window without ``y_up``).
V1 = DATA / "v1-wang-compact.json"
REGION = ["tiling", "--kind", "wang", "--method", "scanline", "--set", "compact", "--colors", "2",
          "--region", "-3,2,5x4", "--seed", "11"]


@pytest.fixture(scope="module")
def tiling(tmp_path_factory) -> Path:
    """A version 2 file of the window the version 1 file holds."""
    d = tmp_path_factory.mktemp("tiling")
    r = run(*REGION, "-o", "t.json", cwd=d)
    assert r.returncode == 0, r.stderr
    return d / "t.json"


def edited(tiling: Path, tmp_path: Path, edit) -> str:
    doc = json.loads(tiling.read_text())
    edit(doc)
    (tmp_path / "f.json").write_text(json.dumps(doc))
    return "f.json"


def test_the_file_holds_the_window_as_data(tiling):
    doc = json.loads(tiling.read_text())
    assert doc["version"] == 2
    assert doc["window"] == {"x0": -3, "y0": 2, "width": 5, "height": 4, "y_up": True}
    assert len(doc["grid"]) == 4 and all(len(row) == 5 for row in doc["grid"])  # H rows of W tiles
    assert "window" not in " ".join(doc["notes"])


def test_version_1_still_reads_verifies_and_draws_with_its_window(tiling, tmp_path):
    shutil.copy(V1, tmp_path / "v1.json")
    v = run("verify", "v1.json", cwd=tmp_path)
    assert v.returncode == 0 and v.stdout.startswith("ok: ") and "window x -3..1, y 2..5 (y grows upwards)" in v.stdout
    d = run("draw", "v1.json", "-o", "v1.svg", cwd=tmp_path)
    assert d.returncode == 0, d.stderr
    assert "window x -3..1, y 2..5 (y grows upwards); top-left cell x -3, y 5" in d.stderr
    # the same window and tiles as version 2 writes today: y pointed north in version 1 too
    old, new = json.loads(V1.read_text()), json.loads(tiling.read_text())
    assert old["grid"] == new["grid"] and {**old["window"], "y_up": True} == new["window"]


@pytest.mark.slow
def test_verify_and_draw_show_the_window_from_the_data(tiling, tmp_path):
    name = edited(tiling, tmp_path, lambda d: d.update(notes=["window x 0..0, y 0..0"]))  # a note is not the data
    v = run("verify", name, cwd=tmp_path)
    assert v.returncode == 0 and "window x -3..1, y 2..5 (y grows upwards)" in v.stdout
    for pic in ("w.svg", "w.png"):
        d = run("draw", name, "-o", pic, cwd=tmp_path)
        assert d.returncode == 0, d.stderr
        assert "window x -3..1, y 2..5 (y grows upwards); top-left cell x -3, y 5" in d.stderr
    assert "window x -3..1, y 2..5 (y grows upwards)" in (tmp_path / "w.svg").read_text()
    moved = edited(tiling, tmp_path, lambda d: d["window"].update(x0=1000, y0=-7))
    assert run("verify", moved, cwd=tmp_path).returncode == 0  # any window of the plane: the tiles still match
    d = run("draw", moved, "-o", "m.svg", cwd=tmp_path)
    assert "window x 1000..1004, y -7..-4" in (tmp_path / "m.svg").read_text() and "x 1000, y -4" in d.stderr


@pytest.mark.parametrize("edit", [lambda d: d["window"].update(width=4), lambda d: d["window"].update(height=5)])
def test_a_window_whose_size_is_not_the_grids_is_refused(tiling, tmp_path, edit):
    name = edited(tiling, tmp_path, edit)
    v = run("verify", name, cwd=tmp_path)
    assert v.returncode == 1 and "1 violation" in v.stdout and "the grid has shape [4, 5], the window" in v.stdout
    line = one_line_error(run("draw", name, "-o", "f.svg", cwd=tmp_path))
    assert "nothing drawn: the grid has shape [4, 5]" in line and not (tmp_path / "f.svg").exists()


@pytest.mark.fast_cases(2)
@pytest.mark.parametrize("edit,message", [
    (lambda d: d["window"].update(y_up=False), "y growing upwards"),
    (lambda d: d["window"].pop("y_up"), "exactly the fields x0, y0, width, height, y_up in version 2"),
    (lambda d: d.update(version=1), "exactly the fields x0, y0, width, height in version 1"),
    (lambda d: d["window"].update(y_up="yes"), "y_up must be true or false"),
    (lambda d: d["window"].update(width=0), "size must be positive"),
    (lambda d: d["window"].update(x0=1.5), "x0 must be an integer"),
    (lambda d: d["window"].update(x0=2**62), "leaves the lattice"),
    (lambda d: d.update(window=[-3, 2, 5, 4]), "'window' must be an object"),
])
def test_a_malformed_window_is_one_line_exit_2(tiling, tmp_path, edit, message):
    name = edited(tiling, tmp_path, edit)
    line = one_line_error(run("verify", name, cwd=tmp_path))
    assert line.startswith(f"tilesolve: error: {name}: ") and message in line, line


def test_draw_refuses_a_malformed_window_too(tiling, tmp_path):
    name = edited(tiling, tmp_path, lambda d: d["window"].update(y_up=False))
    line = one_line_error(run("draw", name, "-o", "f.png", cwd=tmp_path))
    assert line.startswith(f"tilesolve: error: {name}: ") and "y growing upwards" in line
    assert not (tmp_path / "f.png").exists()
