"""The board family's ``procedural`` route (procedural walls of 004 §3-4, App. B) and
``tilesolve wall``: every window verifies with its line limit, windows of one seed are parts
of one infinite wall, bad input is one line with exit 2 and no file."""

from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from clitools import SCRIPT, one_line_error, run

from tilesolve.cli.main import main_group
from tilesolve.errors import InvalidProblem, MethodNotApplicable
from tilesolve.family import solve
from tilesolve.model.board import Board, BoardProblem, WangTileSet
from tilesolve.verify.board import board_violations
from tilesolve.families.walls import wall_problem


def plane(tiling, x0, y0, rows, cols) -> dict:
    """``{(x, y): legs}`` of a window's board tiling (board row 0 is the top row, y grows upwards)."""
    t = np.asarray(tiling).reshape(rows, cols, 4)
    return {(x0 + c, y0 + rows - 1 - r): tuple(int(v) for v in t[r, c]) for r in range(rows) for c in range(cols)}


@pytest.mark.parametrize("n", range(1, 7))
def test_random_windows_verify_with_max_line(n):
    rng = np.random.default_rng(100 + n)
    for _ in range(4):
        rows, cols = (int(v) for v in rng.integers(1, 24, size=2))
        x0, y0 = (int(v) for v in rng.integers(-10**12, 10**12, size=2))
        colors = int(rng.integers(3, 6))
        p = wall_problem(cols, rows, n, n_colors=colors)
        s = solve(p, "procedural", seed=int(rng.integers(0, 2**31)), options={"origin": (x0, y0)})
        assert s.status.value == "sat" and s.method == "procedural"
        assert s.tiling.shape == (rows * cols, 4)
        assert board_violations(p, s.tiling) == []
        assert s.tiling.min() >= 0 and s.tiling.max() < colors


def test_line_limit_is_reached_and_kept():
    """A large window has lines of exactly n bricks somewhere (the limit is not trivially met)."""
    from tilesolve.constructive.walls import line_lengths

    for n in range(1, 7):
        p = wall_problem(60, 60, n)
        s = solve(p, "procedural", seed=11)
        hor, ver = line_lengths(s.tiling.reshape(60, 60, 4))
        assert max(hor.max(), ver.max()) == n


def test_overlapping_windows_agree():
    a = (-7, 3, 12, 15)  # x0, y0, rows, cols
    b = (0, 9, 20, 11)
    seen = {}
    for x0, y0, rows, cols in (a, b):
        s = solve(wall_problem(cols, rows, 4), "procedural", seed=21, options={"origin": (x0, y0)})
        seen[(x0, y0)] = plane(s.tiling, x0, y0, rows, cols)
    wa, wb = seen[(-7, 3)], seen[(0, 9)]
    shared = wa.keys() & wb.keys()
    assert len(shared) == 8 * 6  # x 0..7, y 9..14
    assert all(wa[k] == wb[k] for k in shared)


def test_same_seed_same_wall_other_seed_other_wall():
    p = wall_problem(10, 10, 3)
    one = solve(p, "procedural", seed=5, options={"origin": (4, -2)}).tiling
    assert np.array_equal(one, solve(p, "procedural", seed=5, options={"origin": (4, -2)}).tiling)
    assert not np.array_equal(one, solve(p, "procedural", seed=6, options={"origin": (4, -2)}).tiling)
    assert not np.array_equal(one, solve(p, "procedural", seed=5, options={"origin": (5, -2)}).tiling)


def test_route_preconditions():
    with pytest.raises(MethodNotApplicable, match="'wall' or 'sat'"):
        solve(wall_problem(4, 4, 2, max_v=3), "procedural", seed=1)
    fixed = BoardProblem(Board.rect(3, 3), WangTileSet.brick(3), [0] * 12, max_h=2, max_v=2)
    with pytest.raises(MethodNotApplicable, match="'sat'"):
        solve(fixed, "procedural", seed=1)
    with pytest.raises(MethodNotApplicable, match="'sat'"):
        solve(BoardProblem(Board.rect(3, 3), WangTileSet.brick(3), None), "procedural", seed=1)
    with pytest.raises(InvalidProblem, match="origin"):
        solve(wall_problem(3, 3, 2), "procedural", seed=1, options={"origin": (1.5, 0)})
    with pytest.raises(InvalidProblem, match="2\\*\\*62"):
        solve(wall_problem(3, 3, 2), "procedural", seed=1, options={"origin": (2**62, 0)})


def invoke(*args):
    return CliRunner().invoke(main_group, list(args), catch_exceptions=False)


@pytest.mark.slow
def test_cli_writes_verifiable_drawable_file(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    r = invoke("wall", "--region", "-40,12,30x20", "--max-line", "3", "--colors", "4", "--seed", "7",
               "-o", "w.json", "--svg", "w.svg", "--png", "w.png")
    assert r.exit_code == 0, r.output
    doc = json.loads(Path("w.json").read_text())
    assert doc["max_h"] == 3 and doc["max_v"] == 3 and doc["colors"] == 4 and doc["method"] == "procedural"
    assert "<svg" in Path("w.svg").read_text()[:300]
    assert Path("w.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    v = invoke("verify", "w.json")
    assert v.exit_code == 0 and "ok:" in v.output
    d = invoke("draw", "w.json", "-o", "again.svg")
    assert d.exit_code == 0 and "<svg" in Path("again.svg").read_text()[:300]


def test_cli_text_same_seed_and_shared_cells(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)

    def text(region, seed=3, method="procedural"):
        r = invoke("wall", "--region", region, "--max-line", "2", "--seed", str(seed), "--method", method)
        assert r.exit_code == 0, r.output
        return [line.split() for line in r.stdout.splitlines()]

    a = text("0,0,8x6")
    assert a == text("0,0,8x6")
    b = text("4,2,8x6")  # x 4..11, y 2..7: shares x 4..7, y 2..5 with a
    # board row r of a window at y0 with 6 rows is y = y0 + 5 - r
    for y in range(2, 6):
        assert a[5 - y][4:8] == b[7 - y][0:4]
    assert text("0,0,8x6", method="dappled") != a


def test_brick_wall_still_works(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    r = invoke("brick", "wall", "--size", "9x7", "--max-line", "2", "--seed", "3", "-o", "b.json")
    assert r.exit_code == 0, r.output
    assert json.loads(Path("b.json").read_text())["method"] == "wall"


@pytest.mark.fast_cases(1)
@pytest.mark.parametrize("args, msg", [
    (["--region", "0,0,6x4", "--max-line", "0"], "--max-line"),
    (["--region", "0,0,6x4", "--max-line", "2", "--colors", "2"], "#C >= 3"),
    (["--region", "0,0,0x4", "--max-line", "2"], "positive"),
    (["--region", "0,0,6", "--max-line", "2"], "X0,Y0,WxH"),
    (["--region", "0,0,100000x100000", "--max-line", "2"], "cells"),
    (["--region", "9000000000000000000,0,6x4", "--max-line", "2"], "2**62"),
])
def test_bad_input_one_line_exit_2_no_file(tmp_path, args, msg):
    r = subprocess.run([SCRIPT, "wall", *args, "-o", "x.json"], cwd=tmp_path, capture_output=True, text=True,
                       timeout=300)
    assert r.returncode == 2, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("tilesolve: error:") and msg in lines[0], r.stderr
    assert not (tmp_path / "x.json").exists()


def test_the_window_is_data_on_the_solution():
    from tilesolve.families.walls import npd_problem
    from tilesolve.model.window import Window

    def shape(problem):
        return problem.board.grid_spec.rows, problem.board.grid_spec.cols

    p = wall_problem(15, 12, 4)
    rows, cols = shape(p)
    s = solve(p, "procedural", seed=21, options={"origin": (-7, 3)})
    assert s.window == Window(-7, 3, cols, rows)
    cells, t = plane(s.tiling, -7, 3, rows, cols), s.tiling.reshape(rows, cols, 4)
    assert all(cells[s.window.cell(r, c)] == tuple(int(v) for v in t[r, c]) for r in range(rows) for c in range(cols))
    p = wall_problem(8, 6, 3)
    n = solve(p, "npd", seed=2, options={"origin": (5, -9), "period": (4, 6)})
    assert n.window == Window(5, -9, shape(p)[1], shape(p)[0])
    assert solve(npd_problem(6, 6, 3), "npd", seed=2).window == Window(0, 0, 6, 6)
    assert solve(wall_problem(8, 6, 3), "wall", seed=2).window is None  # a finite wall is no window of the plane


WALL_DATA = Path(__file__).resolve().parent.parent / "data" / "board_solution"


@pytest.mark.slow
def test_wall_file_window_verify_and_draw_read_the_data(tmp_path):
    r = run("wall", "--region", "-40,12,9x6", "--max-line", "3", "--seed", "7", "-o", "w.json", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    doc = json.loads((tmp_path / "w.json").read_text())
    assert doc["version"] == 3 and doc["window"] == {"x0": -40, "y0": 12, "width": 9, "height": 6, "y_up": True}
    doc["notes"] = []  # the coordinates come from the window, not from the note
    doc["window"].update(x0=1000, y0=-5)  # another window of the plane: still a valid wall tiling
    (tmp_path / "m.json").write_text(json.dumps(doc))
    assert run("verify", "m.json", cwd=tmp_path).returncode == 0
    for pic in ("m.svg", "m.png"):
        d = run("draw", "m.json", "-o", pic, cwd=tmp_path)
        assert d.returncode == 0, d.stderr
        assert "window x 1000..1008, y -5..0 (y grows upwards); top-left cell x 1000, y 0" in d.stderr
    assert "window x 1000..1008, y -5..0 (y grows upwards); top-left cell x 1000, y 0" in \
        (tmp_path / "m.svg").read_text()


@pytest.fixture(scope="module")
def wall_doc(tmp_path_factory):
    d = tmp_path_factory.mktemp("wall")
    assert run("wall", "--region", "0,0,9x6", "--max-line", "3", "--seed", "7", "-o", "w.json", cwd=d).returncode == 0
    return json.loads((d / "w.json").read_text())


@pytest.mark.slow
@pytest.mark.parametrize("edit", [lambda w: w.update(width=8), lambda w: w.update(height=9),
                                  lambda w: w.update(y_up=0)])
def test_a_forged_wall_window_is_refused(tmp_path, wall_doc, edit):
    doc = json.loads(json.dumps(wall_doc))
    edit(doc["window"])
    (tmp_path / "f.json").write_text(json.dumps(doc))
    for args in (["verify", "f.json"], ["draw", "f.json", "-o", "f.svg"]):
        assert one_line_error(run(*args, cwd=tmp_path)).startswith("tilesolve: error: f.json: 'window'")
    assert not (tmp_path / "f.svg").exists()


@pytest.mark.slow
def test_an_old_wall_file_reads_verifies_and_draws_its_window_unknown(tmp_path):
    """Written by ``tilesolve wall --region -4,3,6x4 --max-line 3 --seed 5`` as board-solution v1,
    its window only in a note: it still verifies and draws, with no window read from the note."""
    shutil.copy(WALL_DATA / "v1-wall-procedural.json", tmp_path / "old.json")
    v = run("verify", "old.json", cwd=tmp_path)
    assert v.returncode == 0 and v.stdout.startswith("ok: "), v.stdout + v.stderr
    d = run("draw", "old.json", "-o", "old.svg", cwd=tmp_path)
    assert d.returncode == 0 and "top-left cell" not in d.stderr + (tmp_path / "old.svg").read_text()


@pytest.mark.parametrize("region, n, band", [((-40, 12, 90, 70), 2, 1 << 16), ((3, -8, 101, 47), 3, 300)])
def test_the_streamed_wall_file_is_the_solved_one(tmp_path, monkeypatch, region, n, band):
    """``wall -o`` of a procedural wall (write_procedural_wall, checked in bands and written in
    pieces) writes the file that solve() and write_board_solution write, but for time_s."""
    from tilesolve.families import walls
    from tilesolve.io.board_json import write_board_solution

    monkeypatch.setattr(walls, "CHECK_CELLS", band)
    x0, y0, w, h = region
    sol = walls.write_procedural_wall(tmp_path / "s.json", region, colors=4, max_line=n, seed=9)
    problem = wall_problem(w, h, n, n_colors=4)
    held = solve(problem, "procedural", seed=9, options={"origin": (x0, y0)})
    assert np.array_equal(sol.tiling, held.tiling) and sol.window == held.window and sol.notes == held.notes
    write_board_solution(tmp_path / "h.json", problem, held)
    a, b = (json.loads((tmp_path / f).read_text()) for f in ("s.json", "h.json"))
    assert a.pop("time_s") >= 0 and b.pop("time_s") >= 0 and a == b


def test_a_streamed_wall_that_fails_the_verifier_is_not_written(tmp_path, monkeypatch):
    """A wall with horizontal lines of at most 2 bricks and longer vertical ones, checked against
    n = 2 in bands of 2 rows, each of which passes alone: the rows kept from the band above
    catch the lines that cross band borders, and no file is written."""
    from tilesolve.constructive import walls as constructive
    from tilesolve.constructive.walls import line_lengths
    from tilesolve.errors import InternalError
    from tilesolve.families import walls

    wall = walls.brick_wall(40, 40, 2, max_v=8, seed=3)[1].tiling.reshape(40, 40, 4)
    hor, ver = line_lengths(wall)
    assert hor.max() <= 2 and ver.max() > 2
    monkeypatch.setattr(constructive, "wall_window", lambda x0, y0, w, h, **kw: wall[:h, :w])
    monkeypatch.setattr(walls, "CHECK_CELLS", 2 * 40)
    with pytest.raises(InternalError, match="the procedural wall of seed 1 fails the board verifier in the band"):
        walls.write_procedural_wall(tmp_path / "w.json", (0, 0, 40, 40), colors=3, max_line=2, seed=1)
    assert list(tmp_path.iterdir()) == []


def test_cli_streams_a_procedural_wall_file_that_verifies(tmp_path):
    r = run("wall", "--region", "-5,7,80x60", "--max-line", "2", "--seed", "4", "-o", "w.json", "--png", "w.png",
            cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert "4,800 cells checked with the board verifier" in r.stderr and "wrote w.json, w.png" in r.stderr
    doc = json.loads((tmp_path / "w.json").read_text())
    assert doc["tiles"]["shape"] == [4800, 4] and doc["window"]["x0"] == -5 and doc["method"] == "procedural"
    v = run("verify", "w.json", cwd=tmp_path)
    assert v.returncode == 0 and v.stdout.startswith("ok: "), v.stdout + v.stderr
