"""`tilesolve isohedral draw|list` through the console script: the help's examples, files that
`tilesolve verify` re-checks, the same bytes for the same command, bad input in one line, and the
Escher-like pictures in examples/ redrawn by their commands."""

from __future__ import annotations

import json
import shlex
from pathlib import Path

import numpy as np
import pytest
from clitools import one_line_error, run
from PIL import Image

ROOT = Path(__file__).resolve().parents[2]
#: The example pictures in examples/ and the commands that draw them.
EXAMPLES = {
    "isohedral-ih41.png": "isohedral draw --type IH41 --edge 0=bezier:0.25,0.34/0.35,-0.37/0.5,0.05/0.65,0.39/0.8,-0.43 "
                          "--edge 1=bezier:0.25,0.43/0.35,-0.16/0.5,0.03/0.65,0.29/0.8,-0.43 --region 12x8 "
                          "--png isohedral-ih41.png",
    "isohedral-ih07.png": "isohedral draw --type IH7 --edge 0=bezier:0.25,0.44/0.35,-0.41/0.5,0.01/0.65,0.24/0.8,-0.44 "
                          "--edge 1=bezier:0.25,0.35/0.35,-0.21/0.5,0.09/0.65,0.43/0.8,-0.36 "
                          "--edge 2=bezier:0.25,0.42/0.35,-0.24/0.5,-0.07/0.65,0.26/0.8,-0.2 --region 12x8 "
                          "--png isohedral-ih07.png",
    "isohedral-ih55.png": "isohedral draw --type IH55 --edge 0=bezier:0.35,0.45/0.25,-0.3/0.55,-0.05/0.85,0.2/0.8,-0.3 "
                          "--edge 1=bezier:0.3,-0.3/0.6,0.35 --region 12x8 --png isohedral-ih55.png",
}


@pytest.mark.slow
@pytest.mark.parametrize("command", [["isohedral", "draw"], ["isohedral", "list"]])
def test_help_examples_run_in_an_empty_folder(tmp_path, command):
    text = run(*command, "--help", cwd=tmp_path).stdout
    shown = [line.strip() for line in text.splitlines() if line.strip().startswith("tilesolve ")]
    assert shown
    for line in shown:
        proc = run(*shlex.split(line)[1:], cwd=tmp_path)
        assert proc.returncode == 0, (line, proc.stderr[-2000:])
        assert "Traceback" not in proc.stderr


def test_list_shows_every_type(tmp_path):
    lines = run("isohedral", "list", cwd=tmp_path).stdout.splitlines()
    rows = {line.split()[0]: line for line in lines[1:]}
    assert list(rows) == [f"IH{n:02d}" for n in range(1, 94)]
    assert rows["IH41"].split()[1:4] == ["2", "1", "0:J"]
    assert "marked, p3m1: outline of IH20" in rows["IH19"]


def test_a_drawing_is_written_verified_and_the_same_twice(tmp_path):
    args = ["isohedral", "draw", "--type", "IH84", "--params", "0.5,0.2", "--edge", "1=bezier:0.3,0.15/0.7,-0.15",
            "--region", "-1,-1,6x4", "--scale", "30"]
    proc = run(*args, "-o", "t.json", "--svg", "t.svg", "--png", "t.png", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr.startswith("sat: IH84 in the region -1,-1,6x4: ") and "verified" in proc.stderr
    doc = json.loads((tmp_path / "t.json").read_text())
    assert doc["type"] == "IH84" and doc["params"] == [0.5, 0.2] and doc["edges"][1] == "bezier:0.3,0.15/0.7,-0.15"
    img = Image.open(tmp_path / "t.png").convert("L")
    assert img.width == 180 and img.height > 120  # the 6x4 region at 30 px, its caption under it
    assert min(img.crop((0, 120, 180, img.height)).getdata()) < 100  # dark caption text
    ok = run("verify", "t.json", cwd=tmp_path)
    assert ok.returncode == 0 and ok.stdout.startswith("ok: t.json is a valid tiling"), ok.stdout
    assert run(*args, "-o", "u.json", "--svg", "u.svg", "--png", "u.png", cwd=tmp_path).returncode == 0
    for ext in ("json", "svg", "png"):
        assert (tmp_path / f"t.{ext}").read_bytes() == (tmp_path / f"u.{ext}").read_bytes()


def test_a_region_in_pixels(tmp_path):
    proc = run("isohedral", "draw", "--type", "IH90", "--region", "-50,-25,300x200px", "--scale", "50", "--png", "p.png",
               cwd=tmp_path)
    assert proc.returncode == 0 and proc.stderr.startswith("sat: IH90 in the region -1,-0.5,6x4: "), proc.stderr
    w, h = Image.open(tmp_path / "p.png").size
    assert w == 300 and h > 200  # the 300x200 px picture, its caption under it


def test_verify_reports_a_forged_tiling(tmp_path):
    assert run("isohedral", "draw", "--type", "IH1", "-o", "t.json", cwd=tmp_path).returncode == 0
    doc = json.loads((tmp_path / "t.json").read_text())
    doc["translations"][0][0] += 0.25
    (tmp_path / "f.json").write_text(json.dumps(doc))
    proc = run("verify", "f.json", cwd=tmp_path)
    assert proc.returncode == 1 and "translation vectors are not IH01's" in proc.stdout + proc.stderr


def test_a_marked_type_draws_its_markings_and_a_flipped_marking_is_caught(tmp_path):
    proc = run("isohedral", "draw", "--type", "IH92", "-o", "t.json", "--svg", "t.svg", "--png", "t.png", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert "6 aspects, marked (p6m)" in proc.stderr + proc.stdout
    doc = json.loads((tmp_path / "t.json").read_text())
    assert doc["type"] == "IH92" and doc["outline_of"] == "IH93" and doc["version"] == 2
    marks = doc["marking"]["marks"]
    assert isinstance(marks, list) and len(marks) == len(doc["placements"]) and len(set(marks)) == 3
    svg = (tmp_path / "t.svg").read_text()
    assert svg.count('<path id="mark"') == 1 and svg.count('xlink:href="#mark"') == len(marks)
    assert run("verify", "t.json", cwd=tmp_path).returncode == 0
    # Flip one tile's marking: the prototile's symmetries are its rotations (0-2) then its reflections
    # (3-5); IH92's stabilizer is the identity and reflection 3 (vertex 0 fixed), so reflection 4
    # turns a tile's pair of flags over.
    k = next(k for k, m in enumerate(marks) if m == 0)
    marks[k] = 4
    (tmp_path / "f.json").write_text(json.dumps(doc))
    proc = run("verify", "f.json", cwd=tmp_path)
    assert proc.returncode == 1 and "markings are not mirror images" in proc.stdout + proc.stderr


def test_a_version_1_file_of_a_marked_type_reads_and_fails_verification(tmp_path):
    assert run("isohedral", "draw", "--type", "IH48", "--region", "3x2", "-o", "t.json", cwd=tmp_path).returncode == 0
    doc = json.loads((tmp_path / "t.json").read_text())
    del doc["marking"]
    doc["version"] = 1
    (tmp_path / "old.json").write_text(json.dumps(doc))
    proc = run("verify", "old.json", cwd=tmp_path)
    assert proc.returncode == 1 and "must carry markings" in proc.stdout + proc.stderr


@pytest.mark.parametrize("args, message", [
    ("--type IH94", "unknown isohedral type"),
    ("--type IH41 --params 0.2", "IH41 takes 2 parameters, got 1"),
    ("--type IH41 --params 0.2,x", "cannot read parameters"),
    ("--type IH41 --edge 2=line", "edge class 2 does not exist"),
    ("--type IH41 --edge 0=line --edge 0=line", "edge class 0 twice"),
    ("--type IH41 --edge zero=line", "expected CLASS=SHAPE"),
    ("--type IH41 --edge 0=spline:0,1", "cannot read edge shape"),
    ("--type IH16 --edge 0=line:0.5,0.1", "IH16's edge 0 is an I edge"),
    ("--type IH18 --edge 0=bezier:0.3,0.2/0.7,-0.2", "is a U edge"),
    ("--type IH11 --edge 0=bezier:0.3,0.2/0.7,0.2", "is an S edge"),
    ("--type IH41 --edge 0=line:0.5,1.5/0.6,-1.5 --edge 1=line:0.5,1.5/0.6,-1.5", "tile crosses itself"),
    ("--type IH41 --region 12", "cannot read region"),
    ("--type IH41 --region 0x5", "positive sizes"),
    ("--type IH41 --region 500x500", "at most"),
    ("--type IH41 --region 300x2", "at most 8192 a side"),
])
def test_bad_input_is_one_line_exit_2_and_no_file(tmp_path, args, message):
    proc = run("isohedral", "draw", *shlex.split(args), "-o", "x.json", "--png", "x.png", cwd=tmp_path)
    assert message in one_line_error(proc)
    assert not any(tmp_path.iterdir())


@pytest.mark.parametrize("name", sorted(EXAMPLES))
def test_the_example_pictures_are_drawn_by_their_commands(tmp_path, name):
    proc = run(*shlex.split(EXAMPLES[name]), cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    shipped = np.asarray(Image.open(ROOT / "examples" / name))
    assert np.array_equal(np.asarray(Image.open(tmp_path / name)), shipped)
