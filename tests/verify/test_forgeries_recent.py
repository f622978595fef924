"""Forged files of the recently added formats, through the console script: `tilesolve verify` must
refuse each (exit 1 with the reason, or one line ``tilesolve: error: ...`` and exit 2), never
answer "ok", never crash, and never allocate for an absurd size named by a small file.

The formats: isohedral drawings (``tilesolve/isohedral-tiling`` v2, with markings), the sampling
window files that embed their tile set (Poisson disk windows, Poisson sphere boxes, recursive
Wang windows, v2), stipple files (``tilesolve/stipple`` v1) and aperiodicity reports (square
witnesses; version 2 bodies relabelled version 1). Each case is a class of forgery
that `verify` once accepted or crashed on, or that guards the check that now catches it.
"""

from __future__ import annotations

import json

import pytest
from clitools import cut, run, verify_forgery


def _drawn(folder, *args) -> dict:
    proc = run(*args, cwd=folder)
    assert proc.returncode == 0, proc.stderr[-2000:]
    return json.loads((folder / args[args.index("-o") + 1]).read_text())


def _without(rows: list, k: int) -> list:
    return rows[:k] + rows[k + 1:]


def _drop_tile(k: int):
    """Delete placed tile ``k`` (with its colour and marking): the drawing is no longer the region's."""
    def forge(d):
        d["placements"], d["colours"] = _without(d["placements"], k), _without(d["colours"], k)
        d["counts"] = {f"colour {c}": d["colours"].count(c) for c in range(max(d["colours"]) + 1)}
        if d.get("marking"):
            d["marking"]["marks"] = _without(d["marking"]["marks"], k)
    return forge


def _grow_region(d):
    x0, y0, w, h = d["region"]
    d["region"] = [x0, y0, w + 1, h]


@pytest.fixture(scope="module")
def isohedral(tmp_path_factory):
    folder = tmp_path_factory.mktemp("isohedral")
    plain = _drawn(folder, "isohedral", "draw", "--type", "IH41", "--edge", "0=bezier:0.3,0.25/0.6,-0.2", "--edge",
                   "1=bezier:0.35,-0.2/0.7,0.2", "--region", "6x4", "-o", "iso.json")
    marked = _drawn(folder, "isohedral", "draw", "--type", "IH89", "--region", "5x4", "-o", "marked.json")
    return folder, {"plain": plain, "marked": marked}


ISOHEDRAL = [
    # every tile of the plane whose box meets the region must be drawn: the cover test of a grid of
    # 81 points let tiles that hold none of them be deleted, and a region be grown past the drawing
    ("plain", "a tile deleted that holds no cover point", _drop_tile(41), 1, "more tiles meet the region"),
    ("plain", "a tile in the middle deleted", _drop_tile(20), 1, "more tiles meet the region"),
    ("marked", "a marked tile deleted", _drop_tile(3), 1, "more tiles meet the region"),
    ("plain", "the region grown beyond the drawing", _grow_region, 1, "more tiles meet the region"),
    ("plain", "a region of 1000 x 1000 for a small drawing", lambda d: d.update(region=[0, 0, 1000, 1000]), 1,
     "cover at least its area"),
    ("plain", "a tile of lattice index 2**63 - 1", lambda d: d["placements"].__setitem__(0, [2**63 - 1, 0, 0]), 1,
     "lies outside the region"),
    # labels
    ("plain", "counts that are not the colours'", lambda d: d.update(counts={"colour 0": 47, "colour 1": 1}), 2,
     "'counts' does not match 'colours'"),
    ("plain", "the type as a number", lambda d: d.update(type=41), 2, "'type' must be a type name"),
    ("marked", "a version 1 file with a marking", lambda d: d.update(version=1), 2,
     "'marking' is a field of version 2"),
    ("plain", "a drawing's fields without its outline", lambda d: d.pop("outline"), 2, "without an 'outline'"),
    ("marked", "the marking dropped", lambda d: d.update(marking=None), 1, "must carry markings"),
    ("plain", "truncated", cut, 2, "malformed JSON"),
]


@pytest.mark.parametrize("which, name, forge, code, words", ISOHEDRAL, ids=[c[1] for c in ISOHEDRAL])
def test_forged_isohedral_drawings_are_refused(isohedral, which, name, forge, code, words):
    folder, docs = isohedral
    verify_forgery(folder, docs[which], forge, code, words)


def test_the_genuine_drawings_verify(isohedral):
    folder, _ = isohedral
    for name in ("iso.json", "marked.json"):
        r = run("verify", name, cwd=folder)
        assert r.returncode == 0 and r.stdout.startswith("ok:"), r.stdout + r.stderr


@pytest.fixture(scope="module")
def sampled(tmp_path_factory):
    folder = tmp_path_factory.mktemp("sampled")
    docs = {}
    _drawn(folder, "sample", "poisson-tiles", "build", "-C", "2", "-N", "16", "--rho", "0.75", "--seed", "1", "-o",
           "set.json")
    docs["poisson"] = _drawn(folder, "sample", "poisson-tiles", "window", "set.json", "--region", "3,-2,6x5", "--seed",
                             "2", "-o", "window.json")
    _drawn(folder, "sample", "poisson-spheres", "build", "-C", "1", "-N", "64", "--rho", "0.6", "--seed", "1", "-o",
           "spheres.json")
    docs["sphere"] = _drawn(folder, "sample", "poisson-spheres", "window", "spheres.json", "--region", "0,0,0,2x2x2",
                            "--seed", "2", "-o", "box.json")
    _drawn(folder, "sample", "recursive-wang", "build", "-C", "2", "-N", "16", "--rho", "0.7", "-n", "2", "--seed", "1",
           "-o", "rset.json")
    docs["recursive"] = _drawn(folder, "sample", "recursive-wang", "window", "rset.json", "--region", "0,0,4x3",
                               "--ramp", "16,256", "--seed", "2", "-o", "ramp.json")
    docs["stipple"] = _drawn(folder, "sample", "stipple", "--test-image", "radial", "--points", "2000", "--seed", "1",
                             "-o", "stipple.json")
    return folder, docs


def _empty_tiles(d):
    for kind, tiles in d["tileset"]["tiles"].items():
        d["tileset"]["tiles"][kind] = [[] for _ in tiles]


SAMPLED = [
    # no points at all: the exact comparison crashed on an empty array (internal error, exit 70); a
    # window's interior tiles now bound its points before anything is re-derived
    ("poisson", "every point deleted", lambda d: d.update(local=[]), 1, "hold at least 150 points"),
    ("sphere", "every point deleted", lambda d: d.update(local=[]), 1, "hold at least 176 points"),
    ("recursive", "every point deleted", lambda d: d.update(local=[]), 1, "are missing from the file"),
    ("stipple", "every sample deleted", lambda d: d.update(samples=[]), 1, "0 points where 2,000 were asked for"),
    # the set's stated shortfall is its tiles' own: emptied tiles cannot keep claiming N points a tile
    ("poisson", "every tile of the set emptied", _empty_tiles, 1, "but its tiles lack 256"),
    ("poisson", "the set's shortfall hidden", lambda d: d["tileset"].update(stats={"short": 0}), 1,
     "the set states its cells lack 0 points in all (N = 16 a cell), but its tiles lack"),
    ("sphere", "every tile of the set emptied", _empty_tiles, 1, "but its tiles lack 64"),
    ("sphere", "a point of the set deleted, its shortfall kept", lambda d: d["tileset"]["tiles"]["interior"][0].pop(),
     1, "the set states its cells lack 0 points in all (N = 64 a cell), but its tiles lack 1"),
    ("recursive", "the base set's shortfall hidden", lambda d: d["tileset"]["base"].update(stats={"short": 0}), 1,
     "the set states its cells lack 0 points"),
    # an absurd window named by a small file: refused before the lattice is coloured (it took 7.7 GB)
    ("poisson", "a 2048 x 2048 window of 3 points",
     lambda d: (d["window"].update(width=2048, height=2048), d.update(local=d["local"][:3])), 1, "hold at least"),
    ("poisson", "a 2048 x 2048 window of a set with empty tiles (its shortfall stated)",
     lambda d: (_empty_tiles(d), d["tileset"].update(stats={"short": 16 * 16}),
                d["window"].update(width=2048, height=2048), d.update(local=d["local"][:3])), 1,
     "NOT confirmed: the set has an empty interior tile"),
    ("sphere", "a 64^3 box of no points",
     lambda d: (d["box"].update(width=64, height=64, depth=64), d.update(local=[])), 1, "hold at least"),
    ("recursive", "a 1400 x 1400 window of 3 points",
     lambda d: (d["window"].update(width=1400, height=1400), d.update(local=d["local"][:3], density_grid=None, level=0,
                                                                      density="level 0")), 1,
     "NOT confirmed: sampling the window again builds about"),
    # labels shown in the verdict: the density's name, a recursive window's density label
    ("stipple", "the image's name a number", lambda d: d.update(image=3), 2, "'image' must be the density's name"),
    ("recursive", "the ramp's label changed", lambda d: d.update(density="ramp 16,999"), 1,
     "says a ramp from 16 to 999 west to east"),
    ("recursive", "a ramp's grid under a single density's label", lambda d: d.update(density="density 16"), 1,
     "says a density of 16 everywhere"),
    ("recursive", "the density's label a number", lambda d: d.update(density=5), 2, "'density' must be the density's"),
    # regressions: the seed binds the points
    ("poisson", "the seed changed", lambda d: d.update(seed=d["seed"] + 1), 1, "of seed 3 gives"),
    ("recursive", "a point's rank changed", lambda d: d["local"][0].__setitem__(3, d["local"][0][3] + 1e-9), 1,
     "missing from the file"),
]


@pytest.mark.slow
@pytest.mark.parametrize("which, name, forge, code, words", SAMPLED, ids=[f"{c[0]}: {c[1]}" for c in SAMPLED])
def test_forged_sampling_files_are_refused(sampled, which, name, forge, code, words):
    folder, docs = sampled
    verify_forgery(folder, docs[which], forge, code, words)


def test_points_compared_exactly_may_be_none():
    # the comparison of a file's points with the re-derived ones, either side empty
    import numpy as np

    from tilesolve.verify.poisson import match_violations

    assert match_violations([], np.zeros((0, 2)), "x") == []
    assert "3 point(s) x gives are missing" in match_violations([], np.ones((3, 2)), "x")[0].message
    assert "are not among those" in match_violations(np.ones((2, 4)), np.zeros((0, 4)), "x")[0].message


@pytest.fixture(scope="module")
def squares(tmp_path_factory):
    """A witness of the grams square search (Jeandel-Rao, squares up to 60)."""
    folder = tmp_path_factory.mktemp("squares")
    doc = _drawn(folder, "aperiodic", "check", "--builtin", "jeandel-rao", "--max-square", "60", "--square-search",
                 "grams", "--seed", "1", "-o", "grams.json")
    return folder, doc


def _last_square(d) -> dict:
    return d["squares"][-1]


SQUARES = [
    ("a tile of the witness changed",
     lambda d: _last_square(d)["tiling"][5].__setitem__(5, (_last_square(d)["tiling"][5][5] + 1) % 11), 1,
     "square 60x60: leg"),
    ("the witness's board named larger", lambda d: _last_square(d).update(board="square 61x61"), 1,
     "witness has shape (60, 60), expected (61, 61)"),
    ("a larger square claimed", lambda d: d.update(largest_square=61), 1, "claimed without its witness"),
    ("the verdict changed", lambda d: d.update(verdict="finite"), 1, "is not what the certificates give"),
    # one certificate a board, as for the periods: a second could contradict the first
    ("the witness listed twice", lambda d: d["squares"].append(json.loads(json.dumps(_last_square(d)))), 1,
     "square 60x60: certified twice"),
    # a built-in set's name (shown in the verdict) over another set
    ("another built-in set's name", lambda d: d.update(name="kari-14"), 2,
     "'name' is the built-in tile set 'kari-14', but 'tileset' is not that set"),
]


@pytest.mark.parametrize("name, forge, code, words", SQUARES, ids=[c[0] for c in SQUARES])
def test_forged_square_witnesses_are_refused(squares, name, forge, code, words):
    folder, doc = squares
    verify_forgery(folder, doc, forge, code, words)


# --- aperiodic reports: version 1 states no verdict, and its status is "sat" whatever the verdict ---

@pytest.fixture(scope="module")
def report12(tmp_path_factory):
    """A version 2 report: Jeandel-Rao's squares up to 12 (verdict open)."""
    folder = tmp_path_factory.mktemp("report12")
    doc = _drawn(folder, "aperiodic", "check", "--builtin", "jeandel-rao", "--max-square", "12", "--seed", "1", "-o",
                 "r.json")
    assert doc["version"] == 2 and doc["verdict"] == "open"
    return folder, doc


def _as_version_1(d, **changes):
    d.update(version=1, **changes)
    d.pop("verdict")


RELABELLED = [
    # a v2 body relabelled v1 kept its verdict word, which v1's reader ignored: 'periodic' was confirmed as valid
    ("a version 2 body labelled version 1", lambda d: d.update(version=1), 2,
     "'verdict' is not a field of a version 1 report"),
    ("labelled version 1, its verdict forged", lambda d: d.update(version=1, verdict="periodic"), 2,
     "'verdict' is not a field of a version 1 report"),
    # v1's status is "sat" (or "unknown" for a stopped run) whatever the verdict; any other is checked
    ("a version 1 report claiming unsat", lambda d: _as_version_1(d, status="unsat"), 1,
     "status 'unsat' NOT confirmed: the aperiodicity report's certificates give 'sat'"),
]


@pytest.mark.parametrize("name, forge, code, words", RELABELLED, ids=[c[0] for c in RELABELLED])
def test_reports_relabelled_version_1_are_refused(report12, name, forge, code, words):
    folder, doc = report12
    verify_forgery(folder, doc, forge, code, words)


def test_a_version_1_report_verifies_to_the_same_verdict(report12):
    # the body of a v2 report without its verdict is a v1 report: v1 and v2 differ only in that
    # field (and v1's status, "sat" whatever the verdict); the tile set, certificates and
    # conclusion mean the same, so verify's verdict, re-derived from the certificates, is the same
    folder, doc = report12
    v1 = json.loads(json.dumps(doc))
    _as_version_1(v1)
    (folder / "v1.json").write_text(json.dumps(v1))
    (folder / "v2.json").write_text(json.dumps(doc))
    r1, r2 = run("verify", "v1.json", cwd=folder), run("verify", "v2.json", cwd=folder)
    assert r1.returncode == r2.returncode == 0, r1.stdout + r1.stderr
    assert r1.stdout.startswith("ok: v1.json is a valid aperiodicity report") and "verdict open" in r1.stdout
    assert r1.stdout.replace("v1.json", "v2.json") == r2.stdout
