"""`tilesolve draw FILE -o pic.svg|png`: every family's solution files drawn through the registry."""

import subprocess
from pathlib import Path

import pytest
from PIL import Image
from clitools import SCRIPT



def run(*args, cwd: Path):
    return subprocess.run([SCRIPT, *args], cwd=cwd, capture_output=True, text=True, timeout=300)


@pytest.mark.fast_cases(1)
@pytest.mark.parametrize("make", [
    ("dappled", "solve", "--size", "9x7", "--cond", "H0=2,V1=2", "--seed", "1", "-o", "s.json"),
    ("brick", "solve", "--board", "mobius:8x4", "--seed", "1", "-o", "s.json"),
    ("pack", "--kind", "corner", "--colors", "3", "--seed", "1", "-o", "s.json"),
])
def test_every_family_draws_svg_and_png(tmp_path, make):
    assert run(*make, cwd=tmp_path).returncode == 0
    for pic in ("s.svg", "s.png"):
        proc = run("draw", "s.json", "-o", pic, cwd=tmp_path)
        assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "s.svg").read_text().lstrip().startswith(("<?xml", "<svg"))
    with Image.open(tmp_path / "s.png") as img:
        assert img.size[0] > 0 and len(img.getcolors(maxcolors=1 << 16)) > 2  # not a blank picture


@pytest.mark.slow
def test_draw_refuses_what_it_cannot_draw(tmp_path):
    fixed = tmp_path / "fix.txt"
    fixed.write_text("1???\n?0??\n?011\n?0??\n")
    proc = run("dappled", "solve", "--size", "4x4", "--cond", "H0=2,V1=2", "--cyclic", "--fix", "fix.txt",
               "-o", "u.json", cwd=tmp_path)
    assert proc.returncode == 1  # Example 6.2: unsat
    proc = run("draw", "u.json", "-o", "u.svg", cwd=tmp_path)
    assert proc.returncode == 1 and "nothing to draw" in proc.stderr and not (tmp_path / "u.svg").exists()
    proc = run("draw", "u.json", "-o", "u.gif", cwd=tmp_path)
    assert proc.returncode == 2 and proc.stderr.startswith("tilesolve: error:") and "svg or .png" in proc.stderr


@pytest.mark.slow
def test_a_solution_draws_itself_in_a_notebook():
    from tilesolve.families import board, dappled
    from tilesolve.model import DappledProblem
    from tilesolve.model.board import Board, BoardProblem, WangTileSet

    s = dappled.solve(DappledProblem.from_strings("8x6", ["H0=2", "V1=2"]), seed=1)
    assert "<svg" in s._repr_svg_() and s._repr_png_().startswith(b"\x89PNG")
    big = dappled.solve(DappledProblem.from_strings("600x600", ["H0=2", "V1=2"]), seed=1)
    assert big._repr_svg_() is None and big._repr_png_().startswith(b"\x89PNG")  # SVG refused, PNG drawn
    b = board.solve(BoardProblem(Board.torus(6, 4), WangTileSet.brick(3)), seed=2)
    assert "<svg" in b._repr_svg_()
    import numpy as np

    unsat = dappled.solve(DappledProblem.from_strings("3x1", ["H0=1"], fixed=np.array([[0, 0, -1]])), seed=1)
    assert unsat.status.value == "unsat"
    assert unsat._repr_svg_() is None and unsat._repr_png_() is None


@pytest.mark.parametrize("grid, scale, repeat", [(True, 9, 2), (False, 1, 1), (None, 3, 3)])
def test_streamed_png_has_the_in_memory_pixels(tmp_path, grid, scale, repeat):
    import numpy as np

    from tilesolve.io.png import tiling_image, write_png

    t = np.random.default_rng(1).integers(-1, 4, (23, 17)).astype(np.int8)
    write_png(tmp_path / "t.png", t, scale=scale, repeat=repeat, grid=grid)
    with Image.open(tmp_path / "t.png") as img:
        streamed = np.asarray(img.convert("RGB"))
    assert np.array_equal(streamed, np.asarray(tiling_image(t, scale=scale, repeat=repeat, grid=grid).convert("RGB")))
