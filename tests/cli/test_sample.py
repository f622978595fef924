"""``tilesolve sample poisson-tiles``: through the console script."""

from __future__ import annotations

import json
import shlex

import numpy as np
import pytest
from clitools import cut, one_line_error, run, snapshot, verify_forgery


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    """A folder with set.json, written by the library (the build command has its own test)."""
    from tilesolve.families.poisson import solve
    from tilesolve.io.poisson_json import dump, tiles_to_dict
    from tilesolve.model.poisson import PoissonTilesProblem

    d = tmp_path_factory.mktemp("poisson")
    p = PoissonTilesProblem(2, 24, 0.7)
    (d / "set.json").write_text(dump(tiles_to_dict(p, solve(p, seed=1))))
    return d


@pytest.mark.slow
def test_build_is_deterministic_and_verifies(folder):
    for name in ("a.json", "b.json"):
        r = run("sample", "poisson-tiles", "build", "-C", "2", "-N", "24", "--rho", "0.7", "--seed", "1", "-o", name,
                cwd=folder)
        assert r.returncode == 0, r.stderr
    assert (folder / "a.json").read_bytes() == (folder / "b.json").read_bytes() == (folder / "set.json").read_bytes()
    doc = json.loads((folder / "set.json").read_text())
    assert doc["format"] == "tilesolve/poisson-tiles" and doc["version"] == 1
    v = run("verify", "set.json", cwd=folder)
    assert v.returncode == 0 and "ok" in v.stdout + v.stderr


@pytest.mark.slow
def test_window_writes_points_pictures_and_verifies(folder):
    r = run("sample", "poisson-tiles", "window", "set.json", "--region", "-3,4,5x4", "--seed", "2", "-o", "pts.csv",
            "--svg", "pts.svg", "--png", "pts.png", cwd=folder)
    assert r.returncode == 0, r.stderr
    pts = np.loadtxt(folder / "pts.csv", delimiter=",", skiprows=1)
    assert ((pts[:, 0] >= -3) & (pts[:, 0] < 2) & (pts[:, 1] >= 4) & (pts[:, 1] < 8)).all()
    assert (folder / "pts.svg").read_text().startswith("<")
    assert (folder / "pts.png").read_bytes()[:4] == b"\x89PNG"
    r = run("sample", "poisson-tiles", "window", "set.json", "--region", "4611686018427387000,-9,3x3", "--tiling",
            "scanline", "--seed", "5", "-o", "far.json", cwd=folder)
    assert r.returncode == 0, r.stderr
    assert run("verify", "far.json", cwd=folder).returncode == 0


@pytest.mark.slow
def test_verify_finds_points_too_close(folder):
    run("sample", "poisson-tiles", "window", "set.json", "--region", "0,0,2x2", "--seed", "2", "-o", "w.json",
        cwd=folder)
    doc = json.loads((folder / "w.json").read_text())
    x, y = doc["local"][0]
    doc["local"].append([x + 1e-4, y])
    (folder / "bad.json").write_text(json.dumps(doc))
    r = run("verify", "bad.json", cwd=folder)
    assert r.returncode == 1 and "closer than" in r.stdout + r.stderr


@pytest.mark.parametrize("args", [
    "build -C 2 -N 4 --rho 0.75 -o x.json",
    "build -C 9 -N 64 -o x.json",
    "build -C 2 -N 64 --rho 0.99 -o x.json",
    "build -C 2 -N 64 -o x.txt",
    "window missing.json --region 0,0,2x2 -o x.csv",
    "window set.json --region 0,0,2 -o x.csv",
    "window set.json --region 0,0,2x2 -o x.txt",
    "window set.json --region 3000000000,0,2x2 -o x.csv",
    "window set.json --region 0,0,2x2 --tiling direct --set compact -o x.csv",
    "window pts.svg --region 0,0,2x2 -o x.csv",
    "texture set.json --region 0,0,2x2 --png x.svg",
    "texture set.json --region 0,0,100x100 --px 512 --png x.png",
    "texture set.json --region 0,0,2x2 --image missing.png --png x.png",
    "texture set.json --region 0,0,2x2 --image set.json --png x.png",
])
def test_bad_input_is_one_line_and_writes_nothing(folder, args):
    (folder / "pts.svg").write_text("<svg/>") if not (folder / "pts.svg").exists() else None
    before = snapshot(folder)
    one_line_error(run("sample", "poisson-tiles", *shlex.split(args), cwd=folder))
    assert snapshot(folder) == before


@pytest.mark.slow
def test_spectrum_prints_the_table_and_plots(folder):
    r = run("sample", "poisson-tiles", "spectrum", "set.json", "--size", "4", "--seed", "1", "--svg", "s.svg", "--png",
            "s.png", cwd=folder)
    assert r.returncode == 0, r.stderr
    assert "corner tiles" in r.stdout and "dart throwing" in r.stdout
    assert (folder / "s.svg").read_text().count("<polyline") == 4


@pytest.mark.slow
def test_texture_scatters_objects_without_overlaps(folder):
    from PIL import Image

    r = run("sample", "poisson-tiles", "texture", "set.json", "--region", "-9,4,3x2", "--px", "20", "--seed", "3",
            "--png", "t.png", cwd=folder)
    assert r.returncode == 0, r.stderr
    with Image.open(folder / "t.png") as img:
        assert img.size == (60, 40)


@pytest.mark.slow
def test_help_examples_run_as_written_in_an_empty_folder(tmp_path):
    for sub in ((), ("build",), ("window",), ("spectrum",), ("texture",)):
        text = run("sample", "poisson-tiles", *sub, "--help", cwd=tmp_path).stdout
        lines = [ln.strip() for ln in text.splitlines() if ln.strip().startswith("tilesolve ")]
        assert lines
        folder = tmp_path / ("-".join(sub) or "group")
        folder.mkdir()
        for line in lines:
            r = run(*shlex.split(line)[1:], cwd=folder)
            assert r.returncode == 0, (line, r.stderr)


# --- sample stipple, sample importance-spectrum (Penrose and polyomino sampling, Part IV-V) ---

@pytest.mark.parametrize("method,more", [
    ("penrose", ["--lloyd", "0"]), ("polyomino", ["--no-jitter", "--lloyd", "0"]), ("rejection", ["--lloyd", "0"]),
    pytest.param("penrose", [], marks=pytest.mark.slow),  # the defaults: jitter and 4 Lloyd steps
])
def test_stipple_same_seed_same_bytes(tmp_path, method, more):
    for name in ("a", "b"):
        r = run("sample", "stipple", "--test-image", "gradient", "--method", method, *more, "--points", "1500",
                "--seed", "4", "-o", f"{name}.svg", "--png", f"{name}.png", "--csv", f"{name}.csv", cwd=tmp_path)
        assert r.returncode == 0, r.stderr
        assert r.stderr.startswith("ok: ")
    for ext in ("svg", "png", "csv"):
        assert (tmp_path / f"a.{ext}").read_bytes() == (tmp_path / f"b.{ext}").read_bytes()
    pts = np.loadtxt(tmp_path / "a.csv", delimiter=",", skiprows=1)
    assert (tmp_path / "a.svg").read_text().split(' d="', 1)[1].split('"', 1)[0].count("M") == len(pts)
    assert abs(len(pts) - 1500) <= 75
    assert (pts[:, 0] >= 0.5).mean() > 0.6  # the gradient is darker on the right


@pytest.mark.slow
def test_stipple_of_a_picture_follows_its_darkness(tmp_path):
    from PIL import Image

    a = np.full((40, 60), 255, np.uint8)
    a[:, :30] = 0  # the left half black, the right half white
    Image.fromarray(a, "L").save(tmp_path / "half.png")
    r = run("sample", "stipple", "half.png", "--points", "2000", "--seed", "1", "-o", "h.svg", "--csv", "h.csv",
            cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    pts = np.loadtxt(tmp_path / "h.csv", delimiter=",", skiprows=1)
    assert (pts[:, 0] < 0.5).all() and (pts[:, 1] <= 40 / 60).all()
    assert abs(len(pts) - 2000) <= 100  # the verifier allows 5%


@pytest.mark.parametrize("args,message", [
    (["missing.png"], "missing.png: no such file"),
    (["text.png"], "text.png: not a readable image"),
    (["white.png"], "zero everywhere"),
    (["--points", "0"], "points must be in"),
    (["--points", "1000000000"], "at most"),
    (["--points", "lots"], "--points"),
    (["text.png", "--test-image", "radial"], "not both"),
])
def test_stipple_bad_input_is_one_line_and_no_file(tmp_path, args, message):
    from PIL import Image

    (tmp_path / "text.png").write_text("this is no picture\n")
    Image.new("L", (4, 4), 255).save(tmp_path / "white.png")
    before = snapshot(tmp_path)
    line = one_line_error(run("sample", "stipple", *args, "--seed", "1", "-o", "out.svg", "--png", "out.png",
                              cwd=tmp_path))
    assert message in line, line
    assert snapshot(tmp_path) == before


def test_importance_spectrum_prints_the_table_and_draws(tmp_path):
    r = run("sample", "importance-spectrum", "--points", "1000", "--spectrum-points", "256", "--runs", "1", "--seed",
            "1", "--svg", "s.svg", "--png", "s.png", "--periodogram", "p.png", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    rows = [ln.split() for ln in r.stdout.splitlines()[1:]]
    assert [row[0] for row in rows] == ["penrose", "polyomino", "uncorrected", "rejection"]
    peak = {row[0]: float(row[-2]) for row in rows}
    assert peak["rejection"] < 30 < peak["uncorrected"]  # white noise has no spikes; a raw tiling's lattice has
    assert (tmp_path / "s.svg").read_text().count("<polyline") == 8
    for name in ("s.png", "p.png"):
        assert (tmp_path / name).read_bytes()[:4] == b"\x89PNG"


# --- window files bind their seed: forgeries `verify` finds (exit 1) or refuses (exit 2) ---

@pytest.fixture(scope="module")
def window_doc(folder):
    r = run("sample", "poisson-tiles", "window", "set.json", "--region", "-2,3,3x3", "--seed", "4", "-o", "w2.json",
            cwd=folder)
    assert r.returncode == 0, r.stderr
    v = run("verify", "w2.json", cwd=folder)
    assert v.returncode == 0 and v.stdout.startswith("ok: "), v.stdout + v.stderr
    return json.loads((folder / "w2.json").read_text())


def _version_1(d):
    d.pop("tileset")
    d["version"] = 1


@pytest.mark.parametrize("forge, code, words", [
    (lambda d: d.update(local=d["local"][:-5]), 1, "5 point(s) the direct corner tiling of seed 4 gives are missing"),
    (lambda d: d["local"][0].__setitem__(0, d["local"][0][0] + 1e-9), 1, "1 point(s) of the file are not among"),
    (lambda d: d["local"].append([2.999, 2.999]), 1, "1 point(s) of the file are not among"),
    (lambda d: d.update(seed=5), 1, "seed 5 gives are missing"),
    (lambda d: d.update(tiling="scanline"), 1, "the scanline corner tiling of seed 4"),
    (lambda d: d["tileset"]["tiles"]["corner"][0].append([0.0, 0.01]), 1, "the file's tile set: "),
    (lambda d: d["tileset"]["tiles"]["corner"][0].append([0.9, 0.0]), 1, "the file's tile set: corner tile 0"),
    (_version_1, 1, "NOT confirmed"),
    (lambda d: d["tileset"].update(points=32), 2, "'distance' is"),
    (lambda d: d["tileset"]["tiles"].pop("interior"), 2, "forged.json (tileset): 'tiles'"),
    (lambda d: d.pop("tileset"), 2, "missing field 'tileset'"),
    (cut, 2, "forged.json: malformed JSON"),
])
def test_verify_binds_a_window_to_its_set_and_seed(folder, window_doc, forge, code, words):
    verify_forgery(folder, window_doc, forge, code, words)


# --- stipple files: the density, the settings and the seed embedded; verify re-checks and re-samples ---

@pytest.fixture(scope="module")
def stipple_doc(tmp_path_factory):
    d = tmp_path_factory.mktemp("stipple")
    for name in ("s.json", "t.json"):
        r = run("sample", "stipple", "--test-image", "gradient", "--method", "polyomino", "--lloyd", "0", "--points",
                "800", "--seed", "6", "-o", name, "--svg", "s.svg", cwd=d)
        assert r.returncode == 0, r.stderr
    assert (d / "s.json").read_bytes() == (d / "t.json").read_bytes()
    v = run("verify", "s.json", cwd=d)
    assert v.returncode == 0 and v.stdout.startswith("ok: s.json is a valid point set of 800 points"), \
        v.stdout + v.stderr
    doc = json.loads((d / "s.json").read_text())
    assert (doc["format"], doc["version"], doc["seed"], len(doc["density"])) == ("tilesolve/stipple", 2, 6, 256)
    assert (d / "s.svg").read_text().split(' d="', 1)[1].split('"', 1)[0].count("M") == len(doc["samples"])
    return d, doc


@pytest.mark.parametrize("forge, code, words", [
    (lambda d: d.update(samples=d["samples"][:-5]), 1, "5 point(s) polyomino sampling with seed 6 gives are missing"),
    (lambda d: d["samples"][0].__setitem__(1, d["samples"][0][1] * (1 - 1e-12)), 1, "1 point(s) of the file are not"),
    (lambda d: d["samples"].append([0.5, 0.5]), 1, "1 point(s) of the file are not among"),
    (lambda d: d.update(seed=7), 1, "polyomino sampling with seed 7"),
    (lambda d: d.update(density=[r[::-1] for r in d["density"]]), 1, "its share of the density"),
    (lambda d: d.update(density=[r[::-1] for r in d["density"]]), 1, "not the built-in test image 'gradient'"),
    (lambda d: d["density"][5].__setitem__(7, d["density"][5][7] * 0.999), 1, "not the built-in test image"),
    (lambda d: d.update(image="flat"), 1, "not the built-in test image 'flat'"),
    (lambda d: d.update(method="rejection"), 1, "rejection sampling with seed 6"),
    (lambda d: d["samples"].append([1.5, 0.5]), 1, "outside the domain"),
    (lambda d: d.update(jitter="yes"), 2, "'jitter'"),
    (lambda d: d["density"][0].__setitem__(0, -1), 2, "'density'"),
    (lambda d: d.update(density=[[0.0]]), 2, "zero everywhere"),
    (lambda d: d.update(seed=None), 2, "seed"),
    (lambda d: d.pop("samples"), 2, "missing field 'samples'"),
    (cut, 2, "forged.json: malformed JSON"),
])
def test_verify_re_checks_a_stipple_file(stipple_doc, forge, code, words):
    verify_forgery(*stipple_doc, forge, code, words)


# --- the polyomino sampler's correction table (Ostromoukhov 2007): --no-correction, recorded in the file ---

@pytest.fixture(scope="module")
def corrected_docs(tmp_path_factory):
    """The same unjittered X-pentomino stipple with its correction table and with --no-correction."""
    d = tmp_path_factory.mktemp("corrected")
    docs = {}
    for name, more in (("on", []), ("off", ["--no-correction"])):
        r = run("sample", "stipple", "--test-image", "gradient", "--method", "polyomino", "--no-jitter", "--lloyd",
                "0", *more, "--points", "600", "--seed", "3", "-o", f"{name}.json", cwd=d)
        assert r.returncode == 0, r.stderr
        assert ("corrected" in r.stderr) is (name == "on"), r.stderr
        docs[name] = json.loads((d / f"{name}.json").read_text())
    return d, docs


def test_no_correction_is_recorded_and_verifies(corrected_docs):
    d, docs = corrected_docs
    assert (docs["on"]["version"], docs["on"]["correct"], docs["off"]["correct"]) == (2, True, False)
    assert docs["on"]["samples"] != docs["off"]["samples"]  # the table displaces the samples
    for name in ("on", "off"):
        v = run("verify", f"{name}.json", cwd=d)
        assert v.returncode == 0 and v.stdout.startswith("ok: "), v.stdout + v.stderr


def _as_version_1(doc):
    doc.pop("correct")
    doc["version"] = 1


def test_a_version_1_file_verifies_without_the_table(corrected_docs):
    """A version 1 file (written before the table) is sampled again without it: the
    uncorrected samples verify, the corrected ones do not."""
    d, docs = corrected_docs
    verify_forgery(d, docs["off"], _as_version_1, 0, "ok: ")
    verify_forgery(d, docs["on"], _as_version_1, 1, "polyomino sampling with seed 3")


@pytest.mark.parametrize("name", ["on", "off"])
def test_verify_finds_the_correction_flag_flipped(corrected_docs, name):
    d, docs = corrected_docs
    verify_forgery(d, docs[name], lambda doc: doc.update(correct=not doc["correct"]), 1,
                   "polyomino sampling with seed 3")


@pytest.mark.slow
def test_the_largest_stipple_asked_for_is_drawn_even_when_the_sampler_overshoots(tmp_path):
    # -n 200000 (the most a picture takes) gave 200,129 samples, which the picture writer refused
    p = run("sample", "stipple", "--method", "polyomino", "--no-jitter", "--lloyd", "0", "-n", "200000", "--seed", "1",
            "-o", "big.svg", cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    assert (tmp_path / "big.svg").stat().st_size > 0
