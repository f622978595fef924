"""``tilesolve sample poisson-spheres`` (tilesolve/cli/sample.py) through the console script."""

from __future__ import annotations

import json

import numpy as np
import pytest
from clitools import cut, one_line_error, run, snapshot, verify_forgery


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    """A folder with set.json, written by the build command."""
    d = tmp_path_factory.mktemp("spheres")
    r = run("sample", "poisson-spheres", "build", "-C", "1", "-N", "100", "--rho", "0.6", "--seed", "1", "-o",
            "set.json", cwd=d)
    assert r.returncode == 0, r.stderr
    return d


@pytest.mark.slow
def test_build_is_deterministic_and_verifies(folder):
    r = run("sample", "poisson-spheres", "build", "-C", "1", "-N", "100", "--rho", "0.6", "--seed", "1", "-o",
            "again.json", cwd=folder)
    assert r.returncode == 0, r.stderr
    assert (folder / "again.json").read_bytes() == (folder / "set.json").read_bytes()
    doc = json.loads((folder / "set.json").read_text())
    assert doc["format"] == "tilesolve/poisson-sphere-tiles" and doc["version"] == 1
    v = run("verify", "set.json", cwd=folder)
    assert v.returncode == 0 and "ok" in v.stdout + v.stderr


@pytest.mark.slow
def test_window_writes_points_and_far_boxes_verify(folder):
    r = run("sample", "poisson-spheres", "window", "set.json", "--region", "-3,4,-1,3x2x2", "--seed", "2", "-o",
            "pts.npy", cwd=folder)
    assert r.returncode == 0, r.stderr
    pts = np.load(folder / "pts.npy")
    assert pts.shape[1] == 3 and ((pts >= [-3, 4, -1]) & (pts < [0, 6, 1])).all()
    r = run("sample", "poisson-spheres", "window", "set.json", "--region", "-3,4,-1,3x2x2", "--seed", "2", "-o",
            "pts.csv", cwd=folder)
    assert np.allclose(np.loadtxt(folder / "pts.csv", delimiter=",", skiprows=1), pts)
    r = run("sample", "poisson-spheres", "window", "set.json", "--region", "4611686018427387000,-9,77,2x2x2",
            "--hash", "table", "--seed", "5", "-o", "far.json", cwd=folder)
    assert r.returncode == 0, r.stderr
    assert run("verify", "far.json", cwd=folder).returncode == 0


@pytest.mark.slow
def test_verify_catches_a_forged_set_and_a_forged_box(folder):
    doc = json.loads((folder / "set.json").read_text())
    x, y, z = doc["tiles"]["interior"][0][0]
    doc["tiles"]["interior"][0].append([x + 1e-3, y, z])
    (folder / "forged.json").write_text(json.dumps(doc))
    v = run("verify", "forged.json", cwd=folder)
    assert v.returncode == 1, (v.stdout, v.stderr)
    run("sample", "poisson-spheres", "window", "set.json", "--region", "0,0,0,2x1x1", "--seed", "2", "-o", "w.json",
        cwd=folder)
    doc = json.loads((folder / "w.json").read_text())
    x, y, z = doc["local"][0]
    doc["local"].append([x, y + 1e-4, z])
    (folder / "wf.json").write_text(json.dumps(doc))
    assert run("verify", "wf.json", cwd=folder).returncode == 1


@pytest.mark.parametrize("args, words", [
    (["build", "-C", "9", "-N", "100", "-o", "x.json"], "colors must be within 1..4"),
    (["build", "-C", "2", "-N", "20", "--rho", "0.7", "-o", "x.json"], "use at least 97 points"),
    (["build", "-C", "2", "-N", "100", "--rho", "2", "-o", "x.json"], "rho must be within"),
    (["window", "set.json", "--region", "0,0,4x4", "-o", "x.npy"], "expected X0,Y0,Z0,WxHxD"),
    (["window", "set.json", "--region", "0,0,0,0x1x1", "-o", "x.npy"], "box size must be positive"),
    (["window", "set.json", "--region", "3000000000,0,0,1x1x1", "-o", "x.npy"], "beyond +-2**31"),
    (["window", "set.json", "--region", "0,0,0,1000x1000x1000", "-o", "x.npy"], "at most"),
    (["window", "missing.json", "--region", "0,0,0,1x1x1", "-o", "x.npy"], "missing.json"),
    (["window", "set.json", "--region", "0,0,0,1x1x1", "-o", "x.txt"], "x.txt"),
])
def test_bad_input_is_one_line_and_writes_nothing(folder, args, words):
    before = snapshot(folder)
    line = one_line_error(run("sample", "poisson-spheres", *args, cwd=folder))
    assert words in line, line
    assert snapshot(folder) == before


def test_a_window_of_another_format_is_refused(folder):
    (folder / "bad.json").write_text(json.dumps({"format": "tilesolve/poisson-tiles", "version": 1}))
    before = snapshot(folder)
    line = one_line_error(run("sample", "poisson-spheres", "window", "bad.json", "--region", "0,0,0,1x1x1", "-o",
                              "x.npy", cwd=folder))
    assert "poisson-sphere-tiles" in line
    assert snapshot(folder) == before


# --- box files bind their seed: forgeries `verify` finds (exit 1) or refuses (exit 2) ---
# (a verdict of exit 1 checks the embedded set, about a second of CPU: most are in the slow tier)

@pytest.fixture(scope="module")
def box_doc(tmp_path_factory):
    """A box of a small valid C = 2 set, written and verified by the console script. The set
    (written here: building one takes seconds) has one point a tile, at its slot's middle
    moved along x by its index, so that tiles of other colours differ and every tiling keeps
    its points 0.4 apart. It states its true shortfall: a unit cell holds the points of its
    corner tile at its least corner, the three edge and three face tiles through that corner and
    its interior tile, 8 of N = 100, under each of its 2^8 colourings."""
    from tilesolve.io.poisson_sphere_json import dump, tiles_to_dict
    from tilesolve.model.poisson_sphere import PoissonSphereTilesProblem, PoissonSphereTileSet
    from tilesolve.model.solution import Solution, Status

    d = tmp_path_factory.mktemp("bound")
    p = PoissonSphereTilesProblem(2, 100, 0.6)
    middle = {"corner": (0, 0, 0), "xedge": (.5, 0, 0), "yedge": (0, .5, 0), "zedge": (0, 0, .5),
              "xface": (0, .5, .5), "yface": (.5, 0, .5), "zface": (.5, .5, 0), "interior": (.5, .5, .5)}
    ts = PoissonSphereTileSet(p, {k: [np.array([middle[k]]) + [0.05 * i / n, 0, 0] for i in range(n)]
                                  for k, n in p.counts().items()}, seed=0, stats={"short": 2**8 * (100 - 8)})
    (d / "set.json").write_text(dump(tiles_to_dict(p, Solution(Status.SAT, ts, method="dart", seed=0))))
    r = run("sample", "poisson-spheres", "window", "set.json", "--region", "-2,5,1000000,3x2x2", "--seed", "4", "-o",
            "box.json", cwd=d)
    assert r.returncode == 0, r.stderr
    v = run("verify", "box.json", cwd=d)
    assert v.returncode == 0 and v.stdout.startswith("ok: "), v.stdout + v.stderr
    doc = json.loads((d / "box.json").read_text())
    assert doc["version"] == 2 and doc["tileset"] == json.loads((d / "set.json").read_text())
    return d, doc


def _version_1(d):
    d.pop("tileset")
    d["version"] = 1


def _moved(d):
    d["local"][0][2] += 1e-9


@pytest.mark.parametrize("forge, code, words", [
    (lambda d: d.update(local=d["local"][:-3]), 1, "3 point(s) the direct corner tiling of seed 4 gives are missing"),
    pytest.param(_moved, 1, "1 point(s) of the file are not among those the direct corner tiling of seed 4 gives",
                 marks=pytest.mark.slow),
    pytest.param(lambda d: d["local"].append([0.25, 0.25, 0.25]), 1, "1 point(s) of the file are not among",
                 marks=pytest.mark.slow),
    (lambda d: d.update(seed=5), 1, "seed 5 gives are missing"),
    pytest.param(lambda d: d.update(hash="table"), 1, "seed 4 gives are missing", marks=pytest.mark.slow),
    pytest.param(lambda d: d["tileset"]["tiles"]["corner"][1].__setitem__(0, [0.45, 0.0, 0.0]), 1,
                 "the file's tile set: corner tile 1: 1 points outside its region", marks=pytest.mark.slow),
    pytest.param(lambda d: d["tileset"]["tiles"]["interior"][7].append([0.5, 0.5, 0.55]), 1,
                 "the file's tile set: interior", marks=pytest.mark.slow),
    # the set's stated shortfall is its tiles' own: 8 of N = 100 a cell is not N points a cell
    pytest.param(lambda d: d["tileset"]["stats"].update(short=0), 1,
                 "the file's tile set: the set states its cells lack 0 points in all (N = 100 a cell), but its tiles "
                 "lack 23,552", marks=pytest.mark.slow),
    (_version_1, 1, "NOT confirmed"),
    (lambda d: d["tileset"].update(points=120), 2, "forged.json (tileset): 'distance' is"),
    (lambda d: d.update(rho=0.5, distance=None) or d.pop("distance"), 2, "but its tileset is"),
    (lambda d: d.pop("tileset"), 2, "missing field 'tileset'"),
    (lambda d: d.update(seed=None), 2, "states the seed of its tiling, not null"),
    (cut, 2, "forged.json: malformed JSON"),
])
def test_verify_binds_a_box_to_its_set_and_seed(box_doc, forge, code, words):
    verify_forgery(*box_doc, forge, code, words)
