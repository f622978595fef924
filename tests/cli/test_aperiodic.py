"""``tilesolve aperiodic check`` and ``verify`` of its reports, through the console script: a
report is an answer of its own (``Solution.report``), with its own verdict and words, not a
tiling with status ``sat``."""

from __future__ import annotations

import json

import pytest
from clitools import one_line_error, run

#: Three Wang tiles [N, E, S, W] = [i, i+1, i+1, i] (mod 3): they tile diagonals, so every 3x3
#: torus is tiled (a periodic tiling).
DIAGONAL = {"format": "tilesolve/wang-tileset", "version": 1, "order": ["N", "E", "S", "W"], "colors": 3,
            "tiles": [[i, (i + 1) % 3, (i + 1) % 3, i] for i in range(3)]}

CASES = {
    "periodic": (["diagonal.json", "--max-square", "4", "--max-period", "3"], 0, "sat"),
    "finite": (["--builtin", "finite-jv7", "--max-square", "20"], 0, "sat"),
    "undecided": (["--builtin", "jeandel-rao", "--method", "transducer", "--max-period", "1"], 3, "unknown"),
}


def check(tmp_path, verdict: str):
    """Run ``aperiodic check`` for the case whose report has ``verdict``; the report's JSON."""
    args, code, status = CASES[verdict]
    (tmp_path / "diagonal.json").write_text(json.dumps(DIAGONAL))
    p = run("aperiodic", "check", *args, "--workers", "1", "--seed", "1", "-o", "r.json", cwd=tmp_path)
    assert p.returncode == code, p.stderr
    assert f"verdict {verdict};" in p.stderr, p.stderr
    doc = json.loads((tmp_path / "r.json").read_text())
    assert (doc["version"], doc["verdict"], doc["status"]) == (2, verdict, status)
    return doc


@pytest.mark.slow
@pytest.mark.parametrize("verdict", sorted(CASES))
def test_verify_names_a_report_and_its_verdict_not_a_tiling(tmp_path, verdict):
    check(tmp_path, verdict)
    p = run("verify", "r.json", cwd=tmp_path)
    assert p.returncode == 0, p.stdout + p.stderr  # every claim holds, whatever the verdict
    head = p.stdout.splitlines()[0]
    assert head.startswith("ok: r.json is a valid aperiodicity report (aperiodicity check of ")
    assert f"): verdict {verdict}" in head and "tiling" not in head, head
    assert p.stdout.splitlines()[1].startswith("  conclusion: ")
    p = run("aperiodic", "verify", "r.json", cwd=tmp_path)  # the details first, the verdict last
    assert p.returncode == 0 and p.stdout.splitlines()[-1] == head, p.stdout


@pytest.mark.slow
@pytest.mark.parametrize("verdict", ["periodic", "undecided"])
def test_a_version_1_report_still_reads_and_verifies(tmp_path, verdict):
    doc = check(tmp_path, verdict)
    del doc["verdict"]
    doc.update(version=1, status="sat")  # version 1 wrote "sat" whatever the certificates gave
    (tmp_path / "v1.json").write_text(json.dumps(doc))
    p = run("verify", "v1.json", cwd=tmp_path)
    assert p.returncode == 0, p.stdout + p.stderr
    assert p.stdout.startswith("ok: v1.json is a valid aperiodicity report (")
    assert f"verdict {verdict}" in p.stdout.splitlines()[0]


@pytest.mark.slow
def test_a_report_whose_words_are_not_its_certificates_is_false(tmp_path):
    doc = check(tmp_path, "periodic")
    for key, value, said in (("verdict", "open", "the verdict 'open' is not what the certificates give: 'periodic'"),
                             ("status", "unknown", "status 'unknown' NOT confirmed: the aperiodicity report's "
                                                   "certificates give 'sat'")):
        (tmp_path / "bad.json").write_text(json.dumps(dict(doc, **{key: value})))
        p = run("verify", "bad.json", cwd=tmp_path)
        assert p.returncode == 1 and said in p.stdout and not p.stdout.startswith("ok:"), p.stdout
    for verdict in ("aperiodic", [], {"a": 1}, 3):  # not a word a report says
        (tmp_path / "bad.json").write_text(json.dumps(dict(doc, verdict=verdict)))
        assert "'verdict' must be one of periodic, finite, open, undecided" in one_line_error(
            run("verify", "bad.json", cwd=tmp_path))


@pytest.mark.slow
def test_a_report_draws_its_witness(tmp_path):
    check(tmp_path, "periodic")
    p = run("draw", "r.json", "-o", "w.svg", cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    assert (tmp_path / "w.svg").read_text().startswith("<svg")


def test_the_transducer_stops_at_the_time_limit_and_writes_an_undecided_report(tmp_path):
    """periodic-10-35's transducers grow past a million transitions before k = 35: a 2 s limit
    stops the search (every step of a level looks at the deadline), exit 3, and the report
    says where it stopped and claims nothing."""
    p = run("aperiodic", "check", "--builtin", "periodic-10-35", "--method", "transducer", "--max-period", "35",
            "--time-limit", "2", "-o", "r.json", cwd=tmp_path)
    assert p.returncode == 3, p.stderr
    assert "verdict undecided;" in p.stderr and "Traceback" not in p.stderr
    doc = json.loads((tmp_path / "r.json").read_text())
    assert (doc["verdict"], doc["status"], doc["squares"], doc["periods"]) == ("undecided", "unknown", [], [])
    assert "time limit of 2 s reached while " in doc["conclusion"], doc["conclusion"]
    assert run("verify", "r.json", cwd=tmp_path).returncode == 0


@pytest.mark.slow
def test_a_transducer_refutation_of_a_rectangle_is_named_a_rectangle(tmp_path):
    p = run("aperiodic", "check", "--builtin", "finite-jv7", "--method", "transducer", "--max-square", "12",
            "-o", "t.json", "--proof-dir", "proofs", cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    (cert,) = json.loads((tmp_path / "t.json").read_text())["squares"]
    assert (cert["board"], cert["status"]) == ("rectangle 8x26", "refuted")
    p = run("aperiodic", "verify", "t.json", "--proof-dir", "proofs", cwd=tmp_path)
    assert p.returncode == 0 and "rectangle 8x26: " in p.stdout and p.stdout.splitlines()[-1].startswith("ok: ")


def _diagonal_in(fmt: str) -> tuple[str, str]:
    """The DIAGONAL set written in a text format of ``wang count``: ``(file name, text)``."""
    tiles = DIAGONAL["tiles"]
    if fmt == "nswe":
        return "d.tiles", "".join(f"{n} {s} {w} {e}\n" for n, e, s, w in tiles)
    if fmt == "tilesat":
        return "d.txt", "3 3 5 5\n" + "".join(f"{n + 1} {e + 1} {s + 1} {w + 1}\n" for n, e, s, w in tiles)
    return "d.py", "tiles = [" + ", ".join(f"({e}, {n}, {w}, {s})" for n, e, s, w in tiles) + "]\n"


@pytest.mark.parametrize("how", ["json", "--tiles json", "nswe", "tilesat", "rtlb", "--tiles --format rtlb"])
def test_check_reads_every_tile_set_format_wang_count_reads(tmp_path, how):
    fmt = how.split()[-1]
    name, text = ("d.json", json.dumps(DIAGONAL)) if fmt == "json" else _diagonal_in(fmt)
    (tmp_path / name).write_text(text)
    args = [name] if how == fmt else ["--tiles", name] + (["--format", fmt] if "--format" in how else [])
    p = run("aperiodic", "check", *args, "--max-square", "2", "--workers", "1", "--seed", "1", "-o", "r.json",
            cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    doc = json.loads((tmp_path / "r.json").read_text())
    assert doc["tileset"]["tiles"] == DIAGONAL["tiles"] and doc["largest_square"] == 2


@pytest.mark.parametrize("args, msg", [
    (["d.tiles", "--tiles", "d.tiles"], "give the tile-set file once: TILES or --tiles FILE"),
    (["--builtin", "jeandel-rao", "--format", "nswe"], "--format describes a --tiles file"),
    ([], "give a tile set: --tiles FILE or --builtin NAME"),
    (["d.tiles", "--builtin", "jeandel-rao"], "give a tile set: --tiles FILE or --builtin NAME"),
    (["d.tiles", "--format", "tilesat"], "d.tiles"),
])
def test_check_refuses_a_tile_set_given_twice_or_misdescribed(tmp_path, args, msg):
    (tmp_path / "d.tiles").write_text(_diagonal_in("nswe")[1])
    err = one_line_error(run("aperiodic", "check", *args, "--max-square", "2", "-o", "r.json", cwd=tmp_path))
    assert msg in err and not (tmp_path / "r.json").exists(), err


@pytest.mark.parametrize("search", ["phase", "portfolio", "race", "markov", "grams"])
def test_check_searches_squares_every_way_and_its_witness_verifies(tmp_path, search):
    p = run("aperiodic", "check", "--builtin", "jeandel-rao", "--max-square", "12", "--square-search", search,
            "--seed", "1", "-o", "r.json", cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    assert json.loads((tmp_path / "r.json").read_text())["largest_square"] == 12
    p = run("verify", "r.json", cwd=tmp_path)
    assert p.returncode == 0 and p.stdout.startswith("ok: r.json is a valid aperiodicity report"), p.stdout


@pytest.mark.slow
def test_check_says_which_run_of_the_markov_race_found_the_witness(tmp_path):
    p = run("aperiodic", "check", "--builtin", "jeandel-rao", "--max-square", "44", "--square-search", "markov",
            "--seed", "1", "-o", "r.json", cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    doc = json.loads((tmp_path / "r.json").read_text())
    method = doc["squares"][-1]["method"]
    assert method in ("sat", "sat markov-phased")
    assert ("phased by the constructive route's window" in p.stdout) == (method == "sat markov-phased"), p.stdout
    assert run("verify", "r.json", cwd=tmp_path).returncode == 0


def test_check_refuses_the_markov_search_for_a_set_without_a_partition(tmp_path):
    err = one_line_error(run("aperiodic", "check", "--builtin", "kari-14", "--max-square", "2",
                             "--square-search", "markov", "-o", "r.json", cwd=tmp_path))
    assert "Markov partition" in err and not (tmp_path / "r.json").exists(), err


def test_check_refuses_an_unknown_square_search(tmp_path):
    err = one_line_error(run("aperiodic", "check", "--builtin", "jeandel-rao", "--max-square", "2",
                             "--square-search", "strips", "-o", "r.json", cwd=tmp_path))
    assert "--square-search" in err and not (tmp_path / "r.json").exists(), err


def test_periodic_10_35_gets_its_35x35_torus_from_the_lattice_route(tmp_path):
    """Its rows repeat shifted by 13 columns: one row of 35 tiles is a whole period (the sheared
    torus 35x1, shear 8), found among the lattices of index <= 35; the witness is the 35x35
    torus it repeats to, checked by ``verify``."""
    p = run("aperiodic", "check", "--builtin", "periodic-10-35", "--method", "lattice", "--max-period", "35",
            "-o", "r.json", cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    assert "verdict periodic;" in p.stderr and "the torus 35x1 shear 8 is tiled" in p.stderr
    doc = json.loads((tmp_path / "r.json").read_text())
    (cert,) = doc["periods"]
    assert (doc["verdict"], cert["board"], cert["status"], cert["method"]) == ("periodic", "torus 35x35", "tiles",
                                                                               "lattice")
    v = run("verify", "r.json", cwd=tmp_path)
    assert v.returncode == 0 and v.stdout.startswith("ok: "), v.stdout


@pytest.mark.slow
def test_every_built_in_periodic_set_gets_a_verified_torus_witness(tmp_path):
    """Every built-in set that the literature calls periodic, checked up to the period its source
    names (the lattice route; periodic-10-127 takes longest, about 30 s CPU)."""
    from tilesolve.io.builtin_tilesets import load, names

    periodic = [n for n in names() if load(n)[1]["verdict"] == "periodic"]
    assert len(periodic) >= 12
    for name in periodic:
        period = str(load(name)[1]["period"])
        p = run("aperiodic", "check", "--builtin", name, "--method", "lattice", "--max-period", period,
                "-o", f"{name}.json", cwd=tmp_path, timeout=None)
        assert p.returncode == 0 and "verdict periodic;" in p.stderr, (name, p.stderr)
        (cert,) = json.loads((tmp_path / f"{name}.json").read_text())["periods"]
        assert cert["status"] == "tiles" and cert["evidence"]["index"] == int(period), (name, cert["evidence"])
        assert run("verify", f"{name}.json", cwd=tmp_path).returncode == 0, name
