"""The stochastic Wang/corner tiling family ("stochastic", class notes ch. 3) on the family contract:
the generic pipeline, reproducibility, random access of the direct route, the file format,
and the CLI promises through the console script (tiling, verify, draw, demo)."""

from __future__ import annotations

import json
import subprocess

import numpy as np
import pytest

from tilesolve import family
from tilesolve.errors import InvalidProblem, MethodNotApplicable
from tilesolve.family import solution_text
from tilesolve.family.files import identify
from tilesolve.io.jsonio import read_json
from tilesolve.model.solution import Status
from tilesolve.model.stochastic import StochasticProblem
from tilesolve.families.stochastic import FAMILY, stochastic_violations
from clitools import SCRIPT


CASES = [  # (kind, colors, variant, method)
    ("wang", 2, "complete", "direct"),
    ("wang", 3, "compact", "scanline"),
    ("wang", 3, "sums", "direct"),
    ("wang", 4, "complete", "scanline"),
    ("corner", 3, "complete", "direct"),
    ("corner", 3, "compact", "scanline"),
    ("corner", 2, "complete", "scanline"),
]


def run(args, cwd):
    return subprocess.run([SCRIPT, *args], cwd=cwd, capture_output=True, text=True, timeout=600)


def test_registered_under_its_entry_point():
    assert family.get("stochastic") is FAMILY
    assert family.family_of(StochasticProblem("wang", 2, (0, 0, 1, 1))) is FAMILY


@pytest.mark.parametrize("kind,colors,variant,method", CASES)
def test_generic_solve_verifies_and_repeats(kind, colors, variant, method):
    p = StochasticProblem(kind, colors, (-7, 3, 13, 9), variant)
    s = family.solve(p, method, seed=11)
    assert s.status is Status.SAT and s.method == method and s.seed == 11
    assert s.tiling.shape == (9, 13)
    assert stochastic_violations(p, s.tiling) == []
    assert set(np.unique(s.tiling)) <= set(p.tiles.indices.tolist())
    again = family.solve(p, method, seed=11)
    assert np.array_equal(again.tiling, s.tiling)
    assert not np.array_equal(family.solve(p, method, seed=12).tiling, s.tiling)


@pytest.mark.parametrize("kind,variant,hash_,algorithm", [("wang", "complete", "long", "edges"),
                                                          ("wang", "complete", "table", "two"),
                                                          ("wang", "sums", "long", "edges"),
                                                          ("corner", "complete", "table", "edges")])
def test_direct_windows_agree_on_their_overlap(kind, variant, hash_, algorithm):
    a = StochasticProblem(kind, 3, (-10, -6, 14, 9), variant, hash_, algorithm)   # x -10..3, y -6..2
    b = StochasticProblem(kind, 3, (-4, -2, 12, 10), variant, hash_, algorithm)   # x -4..7,  y -2..7
    ga = family.solve(a, "direct", seed=5).tiling
    gb = family.solve(b, "direct", seed=5).tiling
    # overlap x -4..3, y -2..2; row r of a window is y = y0 + h - 1 - r
    ov_a = ga[(2 - 2):(2 - (-2)) + 1, 6:14]        # a: y0 + h - 1 = 2
    ov_b = gb[(7 - 2):(7 - (-2)) + 1, 0:8]         # b: y0 + h - 1 = 7
    assert ov_a.shape == (5, 8) and np.array_equal(ov_a, ov_b)


def test_auto_takes_direct_unless_compact():
    assert family.solve(StochasticProblem("corner", 2, (0, 0, 3, 3)), seed=1).method == "direct"
    assert family.solve(StochasticProblem("corner", 3, (0, 0, 3, 3), "compact"), seed=1).method == "scanline"


def test_routes_that_do_not_apply_name_one_that_does():
    with pytest.raises(MethodNotApplicable, match="scanline"):
        family.solve(StochasticProblem("corner", 3, (0, 0, 3, 3), "compact"), "direct", seed=1)
    with pytest.raises(MethodNotApplicable, match="direct"):
        family.solve(StochasticProblem("wang", 3, (0, 0, 3, 3), "sums"), "scanline", seed=1)


@pytest.mark.parametrize("args,match", [
    (("wang", 2, (0, 0, 0, 4)), "size must be positive"),
    (("hex", 2, (0, 0, 2, 2)), "unknown tile kind"),
    (("corner", 2, (0, 0, 2, 2), "sums"), "only for Wang"),
    (("wang", 2, (0, 0, 2, 2), "complete", "md5"), "unknown hash"),
    (("wang", 2, (1 << 62, 0, 2, 2)), "leaves the lattice"),
    (("wang", 2, (-(1 << 70), 0, 2, 2)), "leaves the lattice"),
    (("wang", 2, (0, 0, 1 << 14, 1 << 14)), "GiB"),
    (("wang", 40, (0, 0, 2, 2)), "GiB"),
])
def test_bad_problems_are_one_line_errors(args, match):
    with pytest.raises(InvalidProblem, match=match) as exc:
        StochasticProblem(*args)
    assert "\n" not in str(exc.value)


def test_verifier_catches_a_single_changed_tile():
    p = StochasticProblem("wang", 3, (0, 0, 9, 7), "compact")
    g = family.solve(p, seed=2).tiling.copy()
    ts = p.tiles
    other = next(int(t) for t in ts.indices if t != g[3, 4])
    g[3, 4] = other
    bad = stochastic_violations(p, g)
    assert bad and all(v.kind == "match" for v in bad)
    g[3, 4] = 1  # not in the compact set (its tiles have E - N == S - W)
    assert any(v.kind == "tile" for v in stochastic_violations(p, g))
    assert stochastic_violations(p, g[:, :8])[0].kind == "shape"


def test_file_round_trip_and_large_grids_encoded():
    p = StochasticProblem("corner", 2, (-300, 40, 300, 300))
    s = family.solve(p, seed=4)
    doc = json.loads(solution_text(p, s))
    assert doc["format"] == "tilesolve/stochastic-tiling" and doc["version"] == 2
    assert doc["window"] == {"x0": -300, "y0": 40, "width": 300, "height": 300, "y_up": True}
    assert set(doc["grid"]) == {"dtype", "shape", "data"}  # 90,000 tiles: an encoded array
    fam, codec = identify(doc, "t.json")
    p2, s2 = codec.read(doc, "t.json")
    assert fam is FAMILY and p2 == p and np.array_equal(s2.tiling, s.tiling) and s2.seed == 4
    assert s.window == s2.window == p.window
    small = StochasticProblem("wang", 2, (0, 0, 3, 2), "compact")
    doc = json.loads(solution_text(small, family.solve(small, seed=1)))
    assert isinstance(doc["grid"], list) and doc["tile_set"]["numbers"] == [0, 3, 5, 6, 9, 10, 12, 15]
    # the colour table alone re-checks the grid (what another tool would do)
    table = dict(zip(doc["tile_set"]["numbers"], doc["tile_set"]["colours"]))
    g = doc["grid"]
    assert all(table[g[r][c]][1] == table[g[r][c + 1]][3] for r in range(2) for c in range(2))


@pytest.mark.parametrize("edit,field", [
    (lambda d: d.update(window={"x0": 0, "y0": 0, "width": 3}), "'window'"),
    (lambda d: d.update(colors="2"), "'colors'"),
    (lambda d: d.update(extra=1), "'extra'"),
    (lambda d: d["tile_set"]["colours"][0].__setitem__(0, 1), "tile_set.colours"),
    (lambda d: d.update(grid=[[0, "a"]]), "'grid'"),
    (lambda d: d.update(set="complete"), "tile_set.numbers"),
])
def test_reader_is_strict(edit, field):
    p = StochasticProblem("wang", 2, (0, 0, 3, 2), "compact")
    doc = json.loads(solution_text(p, family.solve(p, seed=1)))
    edit(doc)
    with pytest.raises(InvalidProblem, match=field) as exc:
        FAMILY.codecs[0].read(doc, "t.json")
    assert str(exc.value).startswith("t.json: ") and "\n" not in str(exc.value)


@pytest.mark.slow
def test_cli_tiling_verify_draw(tmp_path):
    args = ["tiling", "--kind", "corner", "--method", "scanline", "--set", "compact", "--colors", "3",
            "--region", "-6,-4,12x8", "--seed", "9"]
    r = run(args + ["-o", "t.json", "--png", "t.png", "--svg", "t.svg"], tmp_path)
    assert r.returncode == 0, r.stderr
    assert all((tmp_path / f).stat().st_size > 0 for f in ("t.json", "t.png", "t.svg"))
    r2 = run(args + ["-o", "u.json"], tmp_path)
    a, b = read_json(tmp_path / "t.json"), read_json(tmp_path / "u.json")
    assert a["grid"] == b["grid"] and a["seed"] == 9  # same seed, same tiling
    printed = run(args, tmp_path)
    assert printed.returncode == 0 and [list(map(int, row.split())) for row in printed.stdout.splitlines()] == a["grid"]
    v = run(["verify", "t.json"], tmp_path)
    assert v.returncode == 0 and v.stdout.startswith("ok:")
    for pic in ("d.svg", "d.png"):
        d = run(["draw", "t.json", "-o", pic], tmp_path)
        assert d.returncode == 0 and (tmp_path / pic).exists(), d.stderr
    assert r2.returncode == 0


@pytest.mark.slow
def test_cli_corrupted_file_fails_verify(tmp_path):
    assert run(["tiling", "--kind", "wang", "--colors", "2", "--region", "0,0,6x5", "--seed", "3", "-o", "t.json"],
               tmp_path).returncode == 0
    doc = read_json(tmp_path / "t.json")
    g = doc["grid"]
    g[2][3] = next(t for t in range(16) if t != g[2][3] and t % 2 != g[2][3] % 2)  # another W colour (eq. 2.1: W = t mod C)
    (tmp_path / "bad.json").write_text(json.dumps(doc))
    r = run(["verify", "bad.json"], tmp_path)
    assert r.returncode == 1 and "violation" in r.stdout + r.stderr


@pytest.mark.fast_cases(1)
@pytest.mark.parametrize("args", [
    ["--region", "0,0"],
    ["--region", "0,0,0x3"],
    ["--region", "0,0,4x4", "--set", "sums", "--method", "scanline"],
    ["--region", "0,0,70000x70000"],
    ["--region", "0,0,300x300", "--svg", "big.svg"],
    ["--region", "0,0,4x4", "--indices"],
    ["--region", "0,0,4x4", "-o", "nodir/t.json"],
])
def test_cli_bad_input_one_line_exit_2(tmp_path, args):
    r = run(["tiling", "--kind", "wang", "--colors", "2", *args], tmp_path)
    assert r.returncode == 2
    assert r.stderr.startswith("tilesolve: error: ") and len(r.stderr.strip().splitlines()) == 1
    assert list(tmp_path.iterdir()) == []


@pytest.mark.slow
def test_cli_demo(tmp_path):
    r = run(["demo", "--family", "stochastic", "--out", "pics"], tmp_path)
    assert r.returncode == 0, r.stderr
    for d in FAMILY.demos:
        assert (tmp_path / "pics" / f"{d.name}.svg").exists()
        assert run(["verify", f"pics/{d.name}.json"], tmp_path).returncode == 0


def test_png_streamed_in_bands_is_the_tile_by_tile_picture(tmp_path, monkeypatch):
    from PIL import Image

    from tilesolve.io import stochastic_png
    from tilesolve.io.png import write_packing_png

    for kind, colors in (("wang", 3), ("corner", 4)):
        g = family.solve(StochasticProblem(kind, colors, (-5, -5, 60, 40)), seed=3).tiling
        write_packing_png(tmp_path / "whole.png", g, kind, colors)
        monkeypatch.setattr(stochastic_png, "BAND_PIXELS", 1 << 12)  # many bands
        stochastic_png.write_window_png(tmp_path / "bands.png", g, kind, colors)
        a, b = (np.asarray(Image.open(tmp_path / f).convert("RGB")) for f in ("whole.png", "bands.png"))
        assert a.shape == b.shape and np.array_equal(a, b)
