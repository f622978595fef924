"""``tilesolve sample recursive-wang``: through the console script."""

from __future__ import annotations

import json
import shlex

import numpy as np
import pytest
from clitools import cut, one_line_error, run, snapshot, verify_forgery


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    """A folder with rset.json, written by the library (the build command has its own test)."""
    from tilesolve.families.poisson_recursive import solve
    from tilesolve.io.poisson_recursive_json import dump, set_to_dict
    from tilesolve.model.poisson_recursive import RecursiveTilesProblem

    d = tmp_path_factory.mktemp("recursive")
    p = RecursiveTilesProblem(2, 16, 0.7, 4)
    (d / "rset.json").write_text(dump(set_to_dict(p, solve(p, seed=1))))
    return d


@pytest.mark.slow
def test_build_is_deterministic_and_verifies(folder):
    for name in ("a.json", "b.json"):
        r = run("sample", "recursive-wang", "build", "-C", "2", "-N", "16", "--rho", "0.7", "-n", "4", "--seed", "1",
                "-o", name, cwd=folder)
        assert r.returncode == 0, r.stderr
    assert (folder / "a.json").read_bytes() == (folder / "b.json").read_bytes() == (folder / "rset.json").read_bytes()
    doc = json.loads((folder / "a.json").read_text())
    assert doc["format"] == "tilesolve/recursive-wang-tiles" and doc["version"] == 1
    v = run("verify", "a.json", cwd=folder)
    assert v.returncode == 0 and "ok" in v.stdout + v.stderr


def test_a_window_at_a_level_writes_points_and_pictures_and_verifies(folder):
    r = run("sample", "recursive-wang", "window", "rset.json", "--region", "-3,4,2x2", "--level", "2", "--seed", "2",
            "-o", "pts.csv", "--svg", "pts.svg", "--png", "pts.png", cwd=folder)
    assert r.returncode == 0, r.stderr
    table = np.loadtxt(folder / "pts.csv", delimiter=",", skiprows=1)
    assert ((table[:, 0] >= -3) & (table[:, 0] < -1) & (table[:, 1] >= 4) & (table[:, 1] < 6)).all()
    assert set(table[:, 2].tolist()) == {0.0, 1.0, 2.0} and (np.diff(table[:, 2]) >= 0).all()  # coarse first
    assert (folder / "pts.svg").read_text().startswith("<")
    assert (folder / "pts.png").read_bytes()[:4] == b"\x89PNG"


@pytest.mark.slow
def test_the_same_seed_gives_the_same_bytes_and_a_far_window_verifies(folder):
    for name in ("w1.json", "w2.json"):
        r = run("sample", "recursive-wang", "window", "rset.json", "--region", "4611686018427387000,-9,2x1",
                "--ramp", "16,3000", "--seed", "5", "-o", name, cwd=folder)
        assert r.returncode == 0, r.stderr
    assert (folder / "w1.json").read_bytes() == (folder / "w2.json").read_bytes()
    v = run("verify", "w1.json", cwd=folder)
    assert v.returncode == 0, v.stdout + v.stderr


def test_verify_finds_a_point_moved_too_close(folder):
    r = run("sample", "recursive-wang", "window", "rset.json", "--region", "0,0,1x1", "--level", "1", "--seed", "2",
            "-o", "w.json", cwd=folder)
    assert r.returncode == 0, r.stderr
    doc = json.loads((folder / "w.json").read_text())
    fine = next(row for row in doc["local"] if row[2] == 1)
    d1 = doc["distance"] / 4
    doc["local"].append([fine[0] + d1 / 3, fine[1], 1, 0.5])
    (folder / "bad.json").write_text(json.dumps(doc))
    r = run("verify", "bad.json", cwd=folder)
    assert r.returncode == 1 and "level 1" in r.stdout + r.stderr and "closer than" in r.stdout + r.stderr


@pytest.mark.slow
def test_an_image_sets_the_density(folder):
    from PIL import Image

    gradient = np.tile(np.linspace(0, 255, 64).astype(np.uint8), (16, 1))  # black west, white east
    Image.fromarray(gradient, "L").save(folder / "ramp.png")
    r = run("sample", "recursive-wang", "window", "rset.json", "--region", "0,0,4x1", "--image", "ramp.png",
            "--max-density", "800", "--seed", "1", "-o", "img.npy", cwd=folder)
    assert r.returncode == 0, r.stderr
    table = np.load(folder / "img.npy")
    assert table.shape[1] == 4
    assert (table[:, 0] < 1).sum() > 5 * (table[:, 0] >= 3).sum()


@pytest.mark.parametrize("args", [
    "build -N 4 --rho 0.75 -o x.json",
    "build -N 16 -n 1 -o x.json",
    "build -N 16 -n 9 -o x.json",
    "build -N 16 -o x.txt",
    "window missing.json --region 0,0,2x2 --level 1 -o x.csv",
    "window rset.json --region 0,0,2 --level 1 -o x.csv",
    "window rset.json --region 0,0,2x2 -o x.csv",
    "window rset.json --region 0,0,2x2 --level 1 --density 50 -o x.csv",
    "window rset.json --region 0,0,2x2 --level 13 -o x.csv",
    "window rset.json --region 0,0,2x2 --density -5 -o x.csv",
    "window rset.json --region 0,0,2x2 --ramp 5 -o x.csv",
    "window rset.json --region 0,0,2x2 --image rset.json --max-density 50 -o x.csv",
    "window rset.json --region 0,0,2x2 --image missing.png -o x.csv",
    "window rset.json --region 0,0,200x200 --level 6 -o x.csv",
    "window rset.json --region 3000000000,0,2x2 --level 1 -o x.csv",
    "window rset.json --region 0,0,2x2 --level 1 -o x.txt",
])
def test_bad_input_is_one_line_and_writes_nothing(folder, args):
    before = snapshot(folder)
    one_line_error(run("sample", "recursive-wang", *shlex.split(args), cwd=folder))
    assert snapshot(folder) == before


# --- window files bind their seed: forgeries `verify` finds (exit 1) or refuses (exit 2) ---

@pytest.fixture(scope="module")
def window_doc(folder):
    r = run("sample", "recursive-wang", "window", "rset.json", "--region", "5,-2,2x1", "--ramp", "16,600", "--seed", "3",
            "-o", "w2.json", cwd=folder)
    assert r.returncode == 0, r.stderr
    v = run("verify", "w2.json", cwd=folder)
    assert v.returncode == 0 and v.stdout.startswith("ok: "), v.stdout + v.stderr
    doc = json.loads((folder / "w2.json").read_text())
    assert doc["version"] == 2 and len(doc["local"]) > 60 and len(doc["density_grid"][0]) == 1024
    return doc


def _version_1(d):
    for key in ("tileset", "density_grid"):
        d.pop(key)
    d["version"] = 1


def _swap_rule_colour(d):
    rule = d["tileset"]["rules"][0]
    rule[0][1] = 1 - rule[0][1]


@pytest.mark.parametrize("forge, code, words", [
    (lambda d: d.update(local=d["local"][:-50]), 1, "50 point(s) the window of seed 3 gives are missing"),
    (lambda d: d["local"][-1].__setitem__(1, d["local"][-1][1] + 1e-9), 1, "1 point(s) of the file are not among"),
    (lambda d: d["local"][-1].__setitem__(3, 0.0), 1, "1 point(s) of the file are not among"),
    (lambda d: d["local"].append([1.999, 0.999, 1, 0.5]), 1, "1 point(s) of the file are not among"),
    (lambda d: d.update(seed=4), 1, "the window of seed 4 gives are missing"),
    (lambda d: d.update(density_grid=[[v / 2 for v in d["density_grid"][0]]]), 1, "of the file are not among"),
    (lambda d: d["tileset"]["base"]["tiles"]["corner"][0].append([0.0, 0.01]), 1, "the file's tile set: "),
    (_swap_rule_colour, 1, "the file's tile set: tile"),
    (_version_1, 1, "NOT confirmed"),
    (lambda d: d.update(density_grid=[[-1.0]]), 2, "'density_grid'"),
    (lambda d: d.update(density_grid=None), 1, "gives are missing from the file"),  # all of level 2
    (lambda d: d["tileset"].update(subdivision=2), 2, "(tileset): 'rules'"),
    (lambda d: d.pop("tileset"), 2, "missing field 'tileset'"),
    (cut, 2, "forged.json: malformed JSON"),
])
def test_verify_binds_a_window_to_its_set_density_and_seed(folder, window_doc, forge, code, words):
    verify_forgery(folder, window_doc, forge, code, words)
