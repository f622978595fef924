"""Wall pictures written band by band (004 §3.2): the streamed PNG is the picture of the whole
window, every band is verified, and `tilesolve wall` keeps its promises about outputs."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from tilesolve.families import wall_render
from tilesolve.constructive.walls import wall_window
from tilesolve.errors import InternalError, InvalidProblem
from tilesolve.families.wall_render import wall_map_pixels, write_wall_png
from tilesolve.io.wall_png import DISTANCE_COLOURS, distance_legend

from clitools import one_line_error, run, snapshot


def pixels(path) -> np.ndarray:
    with Image.open(path) as img:
        return np.asarray(img)


@pytest.mark.parametrize("kind", ["id", "distance", "uv"])
def test_bands_make_the_picture_of_the_whole_window(tmp_path, monkeypatch, kind):
    region, ppc = (-31, 400, 23, 17), 5
    x0, y0, w, h = region
    legs = wall_window(x0 - 1, y0 - 1, w + 2, h + 2, colors=4, max_line=3, seed=9)
    whole = wall_map_pixels(legs, kind, colors=4, ppc=ppc, origin=(x0, y0))
    monkeypatch.setattr(wall_render, "BAND_CELLS", 3 * w)  # bands of 3 cell rows (the last one 2)
    rep = write_wall_png(tmp_path / "w.png", region, colors=4, max_line=3, seed=9, kind=kind, ppc=ppc)
    assert rep.bands == 6 and rep.size_px == (w * ppc, h * ppc) and rep.verified_cells == w * h
    got = pixels(tmp_path / "w.png")
    if kind == "distance":  # in colour, over its colour bar
        whole = DISTANCE_COLOURS[whole]
        assert np.array_equal(got[h * ppc:], distance_legend(w * ppc))
    assert np.array_equal(got[:h * ppc], whole)
    with Image.open(tmp_path / "w.png") as img:
        assert img.mode == {"id": "P", "distance": "RGB", "uv": "RGB"}[kind]


def test_npd_pictures_repeat_the_period(tmp_path):
    write_wall_png(tmp_path / "n.png", (0, 0, 24, 18), colors=3, max_line=3, seed=4, method="npd", period=(12, 9),
                   kind="distance", ppc=2)
    p = pixels(tmp_path / "n.png")
    assert np.array_equal(p[:, :24], p[:, 24:]) and np.array_equal(p[:18], p[18:])


def test_a_band_that_fails_the_verifier_leaves_no_file(tmp_path, monkeypatch):
    real = wall_render.wall_source

    def corrupted(*args, **kwargs):
        window = real(*args, **kwargs)

        def legs(x0, y0, w, h):
            t = window(x0, y0, w, h).copy()
            if y0 < 5:  # the second band down: a leg no neighbour agrees with
                t[h // 2, w // 2, 1] = (t[h // 2, w // 2, 1] + 1) % 3
            return t
        return legs

    monkeypatch.setattr(wall_render, "wall_source", corrupted)
    monkeypatch.setattr(wall_render, "BAND_CELLS", 40)
    with pytest.raises(InternalError, match="board verifier"):
        write_wall_png(tmp_path / "w.png", (0, 0, 10, 10), colors=3, max_line=2, seed=1)
    assert list(tmp_path.iterdir()) == []
    # without the verifier the same picture is written
    write_wall_png(tmp_path / "w.png", (0, 0, 10, 10), colors=3, max_line=2, seed=1, verify=False)
    assert (tmp_path / "w.png").exists()


def test_lines_crossing_band_borders_are_checked_whole(tmp_path, monkeypatch):
    """A wall with horizontal lines of at most 2 bricks and longer vertical ones, checked
    against n = 2 in bands of 2 rows: every band alone passes the verifier, the rows kept
    from the band above catch the vertical lines that cross band borders."""
    from tilesolve.constructive.npd import periodic_window
    from tilesolve.constructive.walls import line_lengths
    from tilesolve.model.board import Board, BoardProblem, WangTileSet
    from tilesolve.verify.board import board_violations
    from tilesolve.families.walls import brick_wall

    problem, sol = brick_wall(44, 44, 2, max_v=8, seed=3)
    wall = sol.tiling.reshape(44, 44, 4)
    hor, ver = line_lengths(wall[:40, :40])
    assert hor.max() <= 2 and ver.max() > 2
    band = BoardProblem(Board.rect(40, 2), WangTileSet.brick(3), None, max_h=2, max_v=2)
    assert all(not board_violations(band, wall[r:r + 2, :40].reshape(-1, 4)) for r in range(0, 40, 2))
    monkeypatch.setattr(wall_render, "BAND_CELLS", 2 * 40)
    monkeypatch.setattr(wall_render, "wall_source",
                        lambda method, **kw: lambda x0, y0, w, h: periodic_window(wall, x0, y0 + 4, w, h))
    with pytest.raises(InternalError, match="board verifier"):
        write_wall_png(tmp_path / "w.png", (0, 0, 40, 40), colors=3, max_line=2, seed=3)
    assert not (tmp_path / "w.png").exists()


def test_bad_input_to_the_library():
    with pytest.raises(InvalidProblem, match="px limit"):
        write_wall_png("never.png", (0, 0, 70_000, 70_000), colors=3, max_line=2, ppc=1)
    with pytest.raises(InvalidProblem, match="unknown wall map"):
        write_wall_png("never.png", (0, 0, 4, 4), colors=3, max_line=2, kind="phase")
    with pytest.raises(InvalidProblem, match="2\\*\\*62"):
        write_wall_png("never.png", ((1 << 62) - 3, 0, 4, 4), colors=3, max_line=2)
    assert not Path("never.png").exists()


# ----------------------------------------------------------------------------- the command
def invoke(*args):
    from click.testing import CliRunner

    from tilesolve.cli.main import main_group

    return CliRunner().invoke(main_group, list(args), catch_exceptions=False)


def test_cli_png_maps_json_verify_and_draw(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    r = invoke("wall", "--region", "-12,30,20x15", "--max-line", "3", "--seed", "5", "-o", "w.json", "--png", "w.png",
               "--map", "uv", "--ppc", "6")
    assert r.exit_code == 0, r.output
    p = pixels("w.png")
    assert p.shape[0] > 90 and p.shape[1:] == (120, 3)  # the picture, then its caption
    assert (p[90:] == 255).all(axis=2).mean() > 0.8 and (p[90:] < 100).all(axis=2).any()
    assert json.loads(Path("w.json").read_text())["method"] == "procedural"
    v = invoke("verify", "w.json")
    assert v.exit_code == 0 and "ok:" in v.output
    d = invoke("draw", "w.json", "-o", "again.png")
    assert d.exit_code == 0 and Path("again.png").read_bytes()[:4] == b"\x89PNG"
    alone = invoke("wall", "--region", "-12,30,20x15", "--max-line", "3", "--seed", "5", "--png", "alone.png",
                   "--map", "uv", "--ppc", "6")
    assert alone.exit_code == 0 and "300 cells checked with the board verifier" in alone.stderr
    assert Path("alone.png").read_bytes() == Path("w.png").read_bytes()
    fast = invoke("wall", "--region", "-12,30,20x15", "--max-line", "3", "--seed", "5", "--png", "fast.png",
                  "--map", "uv", "--ppc", "6", "--no-verify")
    assert fast.exit_code == 0 and "not verified" in fast.stderr
    assert Path("fast.png").read_bytes() == Path("w.png").read_bytes()


def test_cli_npd_outputs_are_readable(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    r = invoke("wall", "--region", "5,5,30x20", "--max-line", "3", "--method", "npd", "--period", "12x9", "--seed",
               "7", "-o", "n.json", "--png", "n.png")
    assert r.exit_code == 0, r.output
    assert json.loads(Path("n.json").read_text())["method"] == "npd"
    assert invoke("verify", "n.json").exit_code == 0
    assert invoke("draw", "n.json", "-o", "n.svg").exit_code == 0


@pytest.mark.parametrize("args, msg", [
    (["--region", "0,0,20000x20000", "-o", "keep.json"], "--png alone"),
    (["--region", "0,0,2000x2000", "--svg", "x.svg"], "--png alone"),
    (["--region", "0,0,70000x70000", "--png", "x.png", "--ppc", "1"], "px limit"),
    (["--region", "0,0,20x20", "--map", "uv"], "add --png"),
    (["--region", "0,0,20x20", "--period", "5x5", "--png", "x.png"], "--method npd"),
    (["--region", "0,0,20x20", "--method", "dappled", "--png", "x.png", "--map", "id"], "finite"),
    (["--region", "0,0,20x20", "--method", "npd", "--period", "2x8", "--png", "x.png"], "3x3"),
])
def test_cli_refusals_one_line_no_file(tmp_path, monkeypatch, args, msg):
    monkeypatch.chdir(tmp_path)
    Path("keep.json").write_text("{}\n")
    before = snapshot(tmp_path)
    r = invoke("wall", "--max-line", "2", "--seed", "1", *args)
    lines = r.stderr.strip().splitlines()
    assert r.exit_code == 2 and len(lines) == 1 and lines[0].startswith("tilesolve: error: ") and msg in lines[0], \
        r.stderr
    assert snapshot(tmp_path) == before


def test_console_script_refuses_a_held_region_in_one_line(tmp_path):
    r = run("wall", "--region", "0,0,20000x20000", "--max-line", "2", "--method", "npd", "-o", "w.json", cwd=tmp_path)
    assert "about 83.4 GiB" in one_line_error(r) and not (tmp_path / "w.json").exists()
    # -o of a procedural wall is streamed: the file format's limit, not memory, refuses it
    r = run("wall", "--region", "0,0,20000x20000", "--max-line", "2", "-o", "w.json", cwd=tmp_path)
    assert "a board-solution file (-o) holds at most 67,108,864 cells" in one_line_error(r)
    assert not (tmp_path / "w.json").exists()


@pytest.mark.slow
def test_ctrl_c_during_a_streamed_picture_leaves_no_file(tmp_path):
    import signal
    import subprocess
    import time

    from clitools import SCRIPT

    # 400 M cells take many seconds however fast the machine: the signal comes once the picture's
    # temporary file is there, while bands are being written
    proc = subprocess.Popen([SCRIPT, "wall", "--region", "0,0,20000x20000", "--max-line", "2", "--seed", "1",
                             "--png", "big.png"], cwd=tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)
    while proc.poll() is None and not any(tmp_path.iterdir()):
        time.sleep(0.05)
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=120)
    assert proc.returncode == 130, err
    assert "interrupted" in err and "Traceback" not in err
    assert list(tmp_path.iterdir()) == []


@pytest.mark.slow
# ----------------------------------------------------------------------------- legible maps (issue 22)
def test_a_distance_map_reads_at_full_size(tmp_path):
    """A distance map of a large region: 8 px a cell by default (not 2: noise), in colour from
    dark edges to light centres, over its colour bar and caption."""
    err = run("wall", "--region", "0,0,200x150", "--max-line", "2", "--seed", "7", "--png", "d.png",
              "--map", "distance", cwd=tmp_path)
    assert err.returncode == 0, err.stderr
    p = pixels(tmp_path / "d.png")
    pic, below = p[:150 * 8], p[150 * 8:]
    assert p.shape[1] == 200 * 8 and 30 < len(below) < 120
    colours, counts = np.unique(pic.reshape(-1, 3), axis=0, return_counts=True)
    assert len(colours) >= 4 and counts.max() < 0.5 * pic.shape[0] * pic.shape[1]  # no one colour dominates
    luma = pic @ np.array([0.299, 0.587, 0.114])
    assert luma.min() < 70 and luma.max() > 180  # dark by the mortar, light inside the bricks
    bar = below[4:14, 4:-4]
    assert np.array_equal(bar[0, 0], DISTANCE_COLOURS[0]) and np.array_equal(bar[0, -1], DISTANCE_COLOURS[255])
    ink = (below[14:] < 100).all(axis=2)
    assert ink.any() and ink.mean() < 0.3  # the lines that read the bar and name the wall


@pytest.mark.slow
def test_a_histogram_of_one_seed_says_seed(tmp_path):
    proc = run("wall-lines", "--method", "procedural", "--max-line", "2", "--size", "8x8", "--samples", "1",
               "--seed", "4", "--svg", "h.svg", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    text = (tmp_path / "h.svg").read_text()
    assert "1 per generator, seed 4<" in text and "seeds" not in text
    two = run("wall-lines", "--method", "procedural", "--max-line", "2", "--size", "8x8", "--samples", "2",
              "--svg", "-", cwd=tmp_path)
    assert "seeds 0..1<" in two.stdout


@pytest.mark.parametrize("columns", [1, 2])
def test_a_charts_legend_stays_inside_its_width(columns):
    """wall-lines' one-column chart (the default) put its three names in one row and cut the
    last, 'wall (Kaji dappling)', at the picture's edge: the legend wraps instead."""
    from tilesolve.io.histogram import Panel, chart_shapes
    from tilesolve.io.svg import text_width

    names = ["PD (procedural)", "NPD (Kaji cyclic dappling)", "wall (Kaji dappling)"]
    panels = [Panel("vertical lines", ["1", "2"], [(n, [0.5, 0.5]) for n in names])] * 2
    width, height, shapes = chart_shapes(panels, columns=columns, title="line lengths")
    texts = {s[3]: s for s in shapes if s[0] == "text"}
    for name in names:
        _, x, y, _, anchor = texts[name]
        assert anchor == "start" and x + text_width(name, 12) <= width - 8, (name, x, width)
    legend_bottom = max(texts[n][2] for n in names)
    plots = [s for s in shapes if s[0] == "rect" and s[2] > legend_bottom]
    assert plots and min(s[2] for s in shapes if s[0] == "line") > legend_bottom  # the panels start below it
    assert max(s[2] + s[4] for s in plots) <= height
