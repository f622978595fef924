"""`tilesolve penrose` and `tilesolve reptile` through the console script: the help's examples,
files that `tilesolve verify` re-checks, pictures, and bad input in one line."""

from __future__ import annotations

import json
import shlex
from pathlib import Path

import numpy as np
import pytest
from clitools import one_line_error, run
from PIL import Image

ROOT = Path(__file__).resolve().parents[2]
#: The example picture in examples/ and the command that draws it.
EXAMPLE = "penrose --kind p3 --region -16,-9,32x18 --seed 1 --png penrose.png"


@pytest.mark.slow
@pytest.mark.parametrize("command", ["penrose", "reptile"])
def test_help_examples_run(tmp_path, command):
    text = run(command, "--help", cwd=tmp_path).stdout
    shown = [line.strip() for line in text.splitlines() if line.strip().startswith("tilesolve ")]
    assert len(shown) >= 3
    for line in shown:
        proc = run(*shlex.split(line)[1:], cwd=tmp_path)
        assert proc.returncode == 0, (line, proc.stderr[-2000:])
        assert "Traceback" not in proc.stderr


def test_a_window_is_written_verified_and_drawn(tmp_path):
    proc = run("penrose", "--kind", "p2", "--region", "-10,-5,20x10", "--seed", "3", "-o", "t.json", "--svg", "t.svg",
               "--png", "t.png", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert "by pentagrid, seed 3" in proc.stderr and "kite" in proc.stderr
    doc = json.loads((tmp_path / "t.json").read_text())
    assert doc["format"] == "tilesolve/substitution-patch" and doc["version"] == 1 and doc["kind"] == "p2"
    assert len(doc["stats"]["offsets"]) == 5 and abs(sum(doc["stats"]["offsets"])) < 1e-9
    ok = run("verify", "t.json", cwd=tmp_path)
    assert ok.returncode == 0 and ok.stdout.startswith("ok: t.json is a valid tiling"), ok.stdout
    assert "<polygon" in (tmp_path / "t.svg").read_text()
    with Image.open(tmp_path / "t.png") as img:
        assert len(img.getcolors(maxcolors=1 << 16)) > 2


def test_verify_finds_a_broken_arrow_in_a_file(tmp_path):
    assert run("penrose", "--steps", "5", "--method", "substitution", "-o", "t.json", cwd=tmp_path).returncode == 0
    doc = json.loads((tmp_path / "t.json").read_text())
    v = np.array(doc["vertices"])
    centre = np.argmin(np.abs(v[:, :, :]).sum(axis=(1, 2)))
    v[centre] = np.roll(v[centre], 2, axis=0)
    doc["vertices"] = v.tolist()
    (tmp_path / "bad.json").write_text(json.dumps(doc))
    proc = run("verify", "bad.json", cwd=tmp_path)
    assert proc.returncode == 1 and "matching rule" in proc.stdout + proc.stderr


def test_reptile_files_verify(tmp_path):
    assert run("reptile", "--tile", "p-pentomino", "--steps", "3", "-o", "p.json", cwd=tmp_path).returncode == 0
    assert run("verify", "p.json", cwd=tmp_path).returncode == 0
    doc = json.loads((tmp_path / "p.json").read_text())
    doc["vertices"] = doc["vertices"][1:]
    doc["types"] = doc["types"][1:]
    (tmp_path / "gap.json").write_text(json.dumps(doc))
    assert run("verify", "gap.json", cwd=tmp_path).returncode == 1


@pytest.mark.parametrize("args,message", [
    ("penrose --steps 60", "would have about"),
    ("penrose --region 0,0,100000x100000", "would have about"),
    ("penrose --region 0,0,10x10 --steps 2", "either --region"),
    ("penrose", "either --region"),
    ("penrose --method pentagrid --steps 3", "give a region"),
    ("penrose --steps -1", "steps must be >= 0"),
    ("penrose --region 1000000000,0,4x4", "coordinates"),
    ("penrose --region 0,0,4", "region"),
    ("penrose --steps 14 --svg big.svg", "too large for SVG"),
    ("reptile --steps 20", "would have about"),
    ("reptile --tile hat --steps 2", "hat"),
])
def test_bad_input_is_one_line_exit_2(tmp_path, args, message):
    proc = run(*shlex.split(args), "-o", "x.json", cwd=tmp_path)
    assert message in one_line_error(proc)
    assert not any(tmp_path.iterdir())


def test_the_example_picture_is_drawn_by_its_command(tmp_path):
    assert run(*shlex.split(EXAMPLE), cwd=tmp_path).returncode == 0
    shipped = np.asarray(Image.open(ROOT / "examples" / "penrose.png"))
    assert np.array_equal(np.asarray(Image.open(tmp_path / "penrose.png")), shipped)


def test_verify_finds_a_second_sheet_in_a_file(tmp_path):
    """A forged file: a disk of a window with a ring of the same tiling moved by 5 over it. No edge or
    vertex in common, every vertex locally flat, V - E + F = 1 + 0: the verifier's local checks
    passed it; the one-sheet check (verify/substitution.py, check 6) finds the overlap."""
    assert run("penrose", "--region", "-25,-20,50x40", "--seed", "1", "-o", "t.json", cwd=tmp_path).returncode == 0
    doc = json.loads((tmp_path / "t.json").read_text())
    types, v = np.array(doc["types"]), np.array(doc["vertices"])
    angles = 2 * np.pi * np.arange(4) / 5
    c = (v @ np.stack([np.cos(angles), np.sin(angles)], axis=1)).mean(axis=1)
    disk, ring = np.hypot(c[:, 0], c[:, 1]) < 10, np.abs(np.hypot(c[:, 0] + 5, c[:, 1]) - 9.5) < 4.5
    doc["types"] = np.concatenate([types[disk], types[ring]]).tolist()
    doc["vertices"] = np.concatenate([v[disk], v[ring] + [5, 0, 0, 0]]).tolist()
    doc["counts"] = {name: doc["types"].count(i) for i, name in enumerate(("thin", "thick"))}
    doc["stats"].update(tiles=len(doc["types"]), **doc["counts"])
    (tmp_path / "two.json").write_text(json.dumps(doc))
    proc = run("verify", "two.json", cwd=tmp_path)
    assert proc.returncode == 1 and "lie over one point" in proc.stdout + proc.stderr, (proc.stdout, proc.stderr)
