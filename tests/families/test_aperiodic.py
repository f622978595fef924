"""The aperiodicity family: lattices, the tile-selection CNF, squares, sweeps, reports, CLI."""

from __future__ import annotations

import itertools
import json

import numpy as np
import pytest
from clitools import one_line_error, run, snapshot
from hypothesis import given, settings
from hypothesis import strategies as st

from tilesolve.families.aperiodic import AperiodicProblem, solve
from tilesolve.deadline import Deadline
from tilesolve.encodings.wang_tiles import encode_tiles
from tilesolve.engine.aperiodic import sweep
from tilesolve.engine.sat import solve_cnf
from tilesolve.errors import InvalidProblem
from tilesolve.family import solution_text, verify_document
from tilesolve.model.aperiodic import Certificate, Lattice, board_of, leg_colours
from tilesolve.model.board import Board, BoardProblem, WangTileSet
from tilesolve.model.run import RunOptions
from tilesolve.model.solution import Status
from tilesolve.verify.aperiodic import aperiodic_violations, witness_violations
from tilesolve.verify.board import board_violations

#: (R + C) mod 3 colours both ways: tile i has N = i, S = i + 1, W = i, E = i + 1 (mod 3), so
#: crossing east shifts the row counter: it tiles the torus 3x1 only with shear 1.
DIAGONAL = WangTileSet([[i, (i + 1) % 3, (i + 1) % 3, i] for i in range(3)], 3)
#: One tile whose E and W differ: it tiles a single column only (no 1x2 rectangle).
LONELY = WangTileSet([[0, 1, 0, 0]], 2)


def _brute_tiles(board: Board, ws: WangTileSet) -> bool:
    n = board.n_cells
    for choice in itertools.product(range(len(ws)), repeat=n):
        if not board_violations(BoardProblem(board, ws), ws.tiles[list(choice)]):
            return True
    return False


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(*[st.integers(0, 1)] * 4), min_size=1, max_size=4),
       st.sampled_from([(1, 2, -1), (2, 2, -1), (2, 2, 0), (2, 1, 1), (1, 3, 0), (2, 3, 1), (3, 1, 2)]))
def test_tile_cnf_agrees_with_brute_force(tiles, shape):
    ws = WangTileSet(np.array(tiles), 2)
    rows, cols, shear = shape
    board = Board.rect(cols, rows) if shear < 0 else Lattice(rows, cols, shear).board()
    enc = encode_tiles(board, ws)
    r = solve_cnf(enc.hard)
    assert (r.status is Status.SAT) == _brute_tiles(board, ws)
    if r.status is Status.SAT:
        grid = enc.decode(r.model)
        assert not board_violations(BoardProblem(board, ws), leg_colours(ws, grid))


def test_sheared_torus_unfolds_to_a_periodic_patch():
    """A tiling of torus (p, q, s) repeated with periods (q, s), (0, p) tiles the plane."""
    lat = Lattice(3, 1, 1)
    enc = encode_tiles(lat.board(), DIAGONAL)
    r = solve_cnf(enc.hard)
    assert r.status is Status.SAT
    t = enc.decode(r.model)
    R, C = np.meshgrid(np.arange(7), np.arange(8), indexing="ij")
    patch = t[(R + (C // lat.cols) * lat.shear) % lat.rows, C % lat.cols]
    assert not board_violations(BoardProblem(Board.rect(8, 7), DIAGONAL), leg_colours(DIAGONAL, patch))
    assert solve_cnf(encode_tiles(Lattice(3, 1, 0).board(), DIAGONAL).hard).status is Status.UNSAT


def test_lattices_and_names():
    p = AperiodicProblem(DIAGONAL, 0, 3, shears=True)
    assert len(p.lattices()) == 3 * (1 + 2 + 3)
    assert board_of("torus 3x1 shear 1").n_cells == 3
    with pytest.raises(InvalidProblem, match="not a board name"):
        board_of("torus 3 by 1")
    with pytest.raises(InvalidProblem, match="too large"):
        AperiodicProblem(DIAGONAL, 10**6, 0)
    with pytest.raises(InvalidProblem, match="nothing to check"):
        AperiodicProblem(DIAGONAL, 0, 0)


def test_periodic_set_gives_a_verified_torus_witness():
    s = solve(AperiodicProblem(DIAGONAL, 4, 3, shears=True), seed=1, workers=1)
    rep = s.report
    assert s.verdict == "periodic" and s.tiling is None and s.status.value == "sat"
    # the sweep stops at its first tiled torus: the rest are undecided and say why
    tiled = [c for c in rep.periods if c.status == "tiles"]
    assert len(tiled) == 1 and tiled[0].tiling is not None
    stopped = [c for c in rep.periods if c.status == "undecided"]
    assert stopped and all(f"stopped at the first tiled board, the {tiled[0].board}" in c.evidence["why"]
                           for c in stopped)
    refuted = [c for c in rep.periods if c.status == "refuted"]
    assert refuted and all(c.evidence["cnf_sha256"] and c.evidence["drat_sha256"] for c in refuted)
    assert rep.largest_square == 4 and "not aperiodic" in rep.conclusion
    assert not rep.complete and not aperiodic_violations(AperiodicProblem(DIAGONAL, 4, 3, True), rep)


def test_a_sweep_told_not_to_stop_decides_every_torus():
    names = [lat.name() for lat in AperiodicProblem(DIAGONAL, 0, 3, shears=True).lattices()]
    certs, interrupted = sweep(DIAGONAL, names, RunOptions(seed=1, workers=1), stop_at_witness=False)
    by = {c.board: c for c in certs}
    assert not interrupted and all(c.status != "undecided" for c in certs)
    assert by["torus 3x1"].status == "refuted" and by["torus 3x1 shear 1"].status == "tiles"
    assert by["torus 3x3"].status == "tiles"


def test_finite_set_stops_with_a_checked_refutation():
    s = solve(AperiodicProblem(LONELY, 5, 0), seed=1)
    rep = s.report
    assert s.verdict == "finite" and s.status.value == "sat"
    assert rep.largest_square == 1
    refuted = [c for c in rep.squares if c.status == "refuted"]
    assert {c.board for c in refuted} >= {"square 2x2"}
    assert "tiles no plane" in rep.conclusion and "aperiodic" not in rep.conclusion.replace("not aperiodic", "")


def test_report_round_trip_and_tampering_caught():
    problem = AperiodicProblem(DIAGONAL, 3, 2, shears=True)
    s = solve(problem, seed=2, workers=1)
    doc = json.loads(solution_text(problem, s))
    assert verify_document(doc).ok
    bad = json.loads(json.dumps(doc))
    sq = next(c for c in bad["squares"] if c["status"] == "tiles")
    sq["tiling"][0][0] = (sq["tiling"][0][0] + 1) % 3
    rep = verify_document(bad)
    assert rep.exit_code == 1 and "square 3x3" in rep.lines[1]
    bad = json.loads(json.dumps(doc))
    ref = next(c for c in bad["periods"] if c["status"] == "refuted")
    del ref["evidence"]["drat_sha256"]
    assert "without the digests" in verify_document(bad).lines[1]
    bad = json.loads(json.dumps(doc))
    bad["largest_square"] = 2
    assert verify_document(bad).exit_code == 1


def _names(n):
    return [lat.name() for lat in AperiodicProblem(DIAGONAL, 0, n, shears=True).lattices()]


@pytest.mark.slow
def test_sweep_workers_and_cache(tmp_path):
    names = _names(3)  # every board decided (a stop at the first witness depends on which worker ends first)
    one, _ = sweep(DIAGONAL, names, RunOptions(seed=1, workers=1), stop_at_witness=False)
    cache = tmp_path / "c.jsonl"
    two, intr = sweep(DIAGONAL, names, RunOptions(seed=1, workers=2), cache=cache, stop_at_witness=False)
    assert not intr and [c.status for c in one] == [c.status for c in two]
    assert len(cache.read_text().splitlines()) == len(names)
    problem = AperiodicProblem(DIAGONAL, 0, 3, shears=True)

    def holds(cert):
        return not witness_violations(problem, cert)

    again, _ = sweep(DIAGONAL, names, RunOptions(seed=1, workers=2), cache=cache, check_witness=holds,
                     stop_at_witness=False)
    assert all(c.evidence.get("cached") for c in again)
    assert [c.status for c in again] == [c.status for c in one]
    assert {c.evidence["cache_check"] for c in again} == {"witness re-verified",
                                                           "proof re-checked against the re-derived CNF"}


def test_time_limit_leaves_boards_undecided_never_refuted():
    jr = WangTileSet([(t, r, b, l) for r, t, l, b in [
        (2, 4, 2, 1), (2, 2, 2, 0), (1, 1, 3, 1), (1, 2, 3, 2), (3, 1, 3, 3), (0, 1, 3, 1), (0, 0, 0, 1),
        (3, 1, 0, 2), (0, 2, 1, 2), (1, 2, 1, 4), (3, 3, 1, 2)]], 5)
    certs, _ = sweep(jr, ["torus 20x20", "torus 21x21"], RunOptions(seed=1, workers=1, deadline=Deadline(0.05)))
    assert [c.status for c in certs] == ["undecided", "undecided"]
    assert all("time limit" in c.evidence["why"] for c in certs)


@pytest.mark.slow
def test_sweep_on_a_dask_cluster():
    import distributed

    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True, dashboard_address=":0") as lc:
        certs, intr = sweep(DIAGONAL, _names(2), RunOptions(seed=1, cluster=lc.scheduler_address),
                            stop_at_witness=False)
    local, _ = sweep(DIAGONAL, _names(2), RunOptions(seed=1, workers=1), stop_at_witness=False)
    assert not intr and [c.status for c in certs] == [c.status for c in local]


def test_certificate_shape_checked():
    with pytest.raises(InvalidProblem, match="needs tiling"):
        Certificate("torus 1x1", "tiles")


# ------------------------------------------------------------------------------------ CLI
@pytest.mark.slow
def test_cli_check_verify_and_duplicates(tmp_path):
    (tmp_path / "t.json").write_text(json.dumps({"order": "NESW", "colors": 3, "tiles": [
        [0, 1, 1, 0], [1, 2, 2, 1], [2, 0, 0, 2], [2, 0, 0, 2]]}))
    proc = run("aperiodic", "check", "t.json", "--max-square", "3", "--max-period", "3", "--shears",
               "--workers", "1", "--proof-dir", "proofs", "-o", "r.json", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert "duplicate" in proc.stderr and "not aperiodic" in proc.stdout
    assert (tmp_path / "r.json.cache.jsonl").exists()
    assert any(p.suffix == ".drat" for p in (tmp_path / "proofs").iterdir())
    assert run("verify", "r.json", cwd=tmp_path).returncode == 0


@pytest.mark.fast_cases(1)
@pytest.mark.parametrize("tiles,msg", [
    ([[0, 1, 0]], "4 integer colours"),
    ([[0, 1, 0, 7]], "outside C"),
    ([], "non-empty"),
])
def test_cli_bad_tile_sets(tmp_path, tiles, msg):
    (tmp_path / "t.json").write_text(json.dumps({"colors": 2, "tiles": tiles}))
    before = snapshot(tmp_path)
    proc = run("aperiodic", "check", "t.json", "--max-square", "3", "-o", "r.json", cwd=tmp_path)
    assert msg in one_line_error(proc)
    assert snapshot(tmp_path) == before


def test_transducer_route_gives_a_verified_torus_witness():
    problem = AperiodicProblem(DIAGONAL, 0, 3)
    s = solve(problem, method="transducer", seed=1)
    assert s.stats["transducer_verdict"] == "periodic" and s.verdict == "periodic"
    (cert,) = s.report.periods
    assert cert.status == "tiles" and cert.method == "transducer"
    assert not aperiodic_violations(problem, s.report)
    assert verify_document(json.loads(solution_text(problem, s))).ok


@pytest.mark.slow
def test_cli_ctrl_c_writes_no_report_and_the_cache_resumes(tmp_path):
    import signal
    import subprocess
    import time

    from clitools import ENV, SCRIPT

    args = [SCRIPT, "aperiodic", "check", "--builtin", "jeandel-rao", "--max-period", "14", "--workers", "2",
            "-o", "r.json"]
    proc = subprocess.Popen(args, cwd=tmp_path, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    cache = tmp_path / "r.json.cache.jsonl"
    t = time.monotonic()
    while not (cache.exists() and cache.read_text().count("\n") >= 3) and time.monotonic() - t < 240:
        time.sleep(0.2)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 130 and "Traceback" not in err, err
    assert not (tmp_path / "r.json").exists()
    decided = [json.loads(line) for line in cache.read_text().splitlines()]
    assert len(decided) >= 3 and all(d["status"] == "refuted" for d in decided)
    again = run("aperiodic", "check", "--builtin", "jeandel-rao", "--max-period", "2", "--workers", "1",
                "-o", "r2.json", "--cache", "r.json.cache.jsonl", cwd=tmp_path)
    assert again.returncode == 0, again.stderr
    periods = json.loads((tmp_path / "r2.json").read_text())["periods"]
    names = {d["board"] for d in decided}
    assert all(p["evidence"].get("cached", False) == (p["board"] in names) for p in periods)


def test_proof_files_listed_and_rechecked(tmp_path):
    problem = AperiodicProblem(DIAGONAL, 0, 2)
    s = solve(problem, seed=1, workers=1, options={"proof_dir": tmp_path})
    doc = json.loads(solution_text(problem, s))
    rep = verify_document(doc, "r.json", tmp_path)
    assert rep.ok and "4 refutation(s) re-checked" in rep.lines[0]
    assert sum("verified against the re-derived CNF" in ln for ln in rep.lines) == 4
    drat = sorted(tmp_path.glob("*.drat"))[0]
    drat.write_text(drat.read_text() + "1 0\n")
    rep = verify_document(doc, "r.json", tmp_path)
    assert not rep.ok and any("differs from the recorded" in ln for ln in rep.lines)


def test_draw_shows_the_torus_witness_else_the_largest_square(tmp_path):
    from tilesolve.families.aperiodic import witness
    from tilesolve.family import draw_solution

    p = AperiodicProblem(DIAGONAL, 4, 3, shears=True)
    s = solve(p, seed=1, workers=1)
    board = witness(s.report).board
    assert board.startswith("torus")  # a period beats the larger square
    draw_solution(tmp_path / "t.svg", p, s)
    draw_solution(tmp_path / "t.png", p, s)
    assert f": {board}</text>" in (tmp_path / "t.svg").read_text()
    assert (tmp_path / "t.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    squares = AperiodicProblem(LONELY, 3, 0)
    s = solve(squares, seed=1, workers=1)
    assert witness(s.report).board == "square 1x1" and s.report.largest_square == 1
    draw_solution(tmp_path / "s.svg", squares, s, title="one column")
    svg = (tmp_path / "s.svg").read_text()
    assert "one column</text>" in svg and "witness: the square 1x1 tiled (sat, seed 1)" in svg


def test_a_report_without_a_witness_has_nothing_to_draw(tmp_path):
    from tilesolve.family import draw_solution

    p = AperiodicProblem(LONELY, 0, 1)  # the 1x1 torus joins the tile's E and W legs: refuted
    s = solve(p, seed=1, workers=1)
    assert [c.status for c in s.report.periods] == ["refuted"]
    for fmt in ("svg", "png"):
        with pytest.raises(InvalidProblem, match="^this report has no witness tiling to draw$"):
            draw_solution(tmp_path / f"r.{fmt}", p, s)
        assert not (tmp_path / f"r.{fmt}").exists()


@pytest.mark.slow
def test_demo_and_cli_draw(tmp_path):
    from tilesolve.families.aperiodic import FAMILY

    proc = run("demo", "--family", "aperiodic", "--seed", "1", "--out", "d", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    (demo,) = FAMILY.demos
    doc = json.loads((tmp_path / "d" / f"{demo.name}.json").read_text())
    assert verify_document(doc).ok
    assert f">{demo.caption}</text>" in (tmp_path / "d" / f"{demo.name}.svg").read_text()  # the caption is the title
    proc = run("draw", f"d/{demo.name}.json", "-o", "r.svg", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert "jeandel-rao: square 12x12</text>" in (tmp_path / "r.svg").read_text()
    run("aperiodic", "check", "--builtin", "periodic-7-30", "--max-period", "1", "--workers", "1", "-o", "p.json",
        cwd=tmp_path)
    proc = run("draw", "p.json", "-o", "p.png", cwd=tmp_path)
    assert one_line_error(proc) == "tilesolve: error: this report has no witness tiling to draw"
    assert not (tmp_path / "p.png").exists()


def test_studio_form_poses_the_cli_check():
    from tilesolve.families.aperiodic import FAMILY

    form = FAMILY.form
    values = form.values({"tileset": "periodic-7-30", "max_square": 5, "max_period": 3, "shears": True, "seed": 2})
    problem, options = form.build(values)
    assert (problem.name, problem.max_square, problem.max_period, problem.shears, options) == (
        "periodic-7-30", 5, 3, True, {})
    assert problem.info["verdict"] == "periodic"
    assert form.command(values) == (["aperiodic", "check", "--builtin", "periodic-7-30", "--max-square", "5",
                                     "--max-period", "3", "--shears"], {})
    defaults = form.values({})
    assert form.command(defaults)[0][2:] == ["--builtin", "jeandel-rao", "--max-square", "12", "--max-period", "2"]
    with pytest.raises(InvalidProblem, match="max square"):
        form.values({"max_square": 41})
    with pytest.raises(InvalidProblem, match="tile set"):
        form.values({"tileset": "nope"})


def test_lattice_route_reports_the_plain_torus_of_the_first_lattice_tiled():
    from tilesolve.families.aperiodic import FAMILY

    problem = AperiodicProblem(DIAGONAL, 0, 3)
    s = solve(problem, method="lattice", seed=1)
    assert (s.verdict, s.status, s.method) == ("periodic", Status.SAT, "lattice")
    (cert,) = s.report.periods
    assert (cert.board, cert.status, cert.method) == ("torus 3x3", "tiles", "lattice")
    assert cert.evidence["lattice"] == "torus 3x1 shear 1" and cert.evidence["index"] == 3
    assert not witness_violations(problem, cert) and not FAMILY.verify(problem, s.report)
    assert "torus 3x1 shear 1 is tiled, which repeats to the torus 3x3" in s.notes[0]


def test_lattice_route_without_a_witness_leaves_every_lattice_undecided():
    from tilesolve.families.aperiodic import FAMILY

    problem = AperiodicProblem(DIAGONAL, 0, 2, shears=True)  # its lattices of index <= 2 are not tiled
    s = solve(problem, method="lattice", seed=1)
    assert (s.verdict, s.status) == ("undecided", Status.UNKNOWN)
    assert [c.board for c in s.report.periods] == [lat.name() for lat in problem.lattices()]
    assert all(c.status == "undecided" and "finds witnesses only" in c.evidence["why"] for c in s.report.periods)
    assert not FAMILY.verify(problem, s.report)
    with pytest.raises(InvalidProblem, match="periods only"):
        solve(AperiodicProblem(DIAGONAL, 3, 3), method="lattice")
