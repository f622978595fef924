"""``tilesolve render`` and ``tilesolve gpu`` through the console script, and what happens without GL."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from clitools import ENV, SCRIPT, one_line_error, run, snapshot
from PIL import Image

from tilesolve.gpu.texture import Atlas, TextureMapper, read_example
from tilesolve.gpu.wall import WallRenderer
from tilesolve.gpu.wang_texture import WangAtlas, WangTexture
from tilesolve.io.builtin_tilesets import load

#: Points libglvnd at no EGL vendor: what a machine without Mesa's EGL looks like.
NO_GL = dict(ENV, __EGL_VENDOR_LIBRARY_FILENAMES=os.devnull)


@pytest.mark.slow
def test_gpu_info_names_the_renderer(tmp_path):
    proc = run("gpu", "info", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert re.search(r"^renderer: +\S", proc.stdout, re.M) and "OpenGL:" in proc.stdout
    assert re.search(r"^samples: +1\b", proc.stdout, re.M)


def test_render_wall_writes_a_small_picture(tmp_path):
    """The fast tier's render: a small wall, pixel for pixel the library's (wall and texture: below, slow)."""
    proc = run("render", "wall", "--size", "64x32", "--max-line", "3", "--seed", "3", "-o", "w.png", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert np.array_equal(np.asarray(Image.open(tmp_path / "w.png")), WallRenderer(max_line=3, seed=3).image(64, 32))


@pytest.mark.slow
def test_render_wall_and_texture_write_the_library_pictures(tmp_path):
    proc = run("render", "wall", "--size", "200x120", "--max-line", "3", "--cell", "16", "--seed", "4",
               "--origin", "-50,7", "-o", "w.png", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    wall = np.asarray(Image.open(tmp_path / "w.png"))
    assert np.array_equal(wall, WallRenderer(max_line=3, cell_px=16, seed=4, origin=(-50, 7)).image(200, 120))
    proc = run("render", "texture", "--example", "w.png", "--colors", "2", "--tile", "16", "--scale", "8",
               "--size", "150x90", "--seed", "2", "--origin", "3,-4", "-o", "t.png", "--atlas", "a.png", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    at = Atlas.from_example(read_example(tmp_path / "w.png"), 2, tile=16, seed=2)
    want = TextureMapper(at, seed=2, origin=(3, -4), tile_px=8).image(150, 90)
    assert np.array_equal(np.asarray(Image.open(tmp_path / "t.png")), want)
    assert np.array_equal(np.asarray(Image.open(tmp_path / "a.png")), at.image)


@pytest.mark.slow
def test_benchmark_prints_frames_per_second(tmp_path):
    proc = run("render", "wall", "--size", "320x200", "--benchmark", "3", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert re.search(r"^3 frames of 320x200 in [\d.]+ s: [\d.]+ fps \(", proc.stdout, re.M)
    assert not list(tmp_path.iterdir())


@pytest.mark.slow
def test_without_gl_one_line_naming_the_packages_and_the_cpu_routes_still_work(tmp_path):
    (tmp_path / "keep.png").write_bytes(b"earlier")
    before = snapshot(tmp_path)
    for args in (["render", "wall", "--size", "64x64", "-o", "keep.png"], ["gpu", "info"]):
        proc = subprocess.run([SCRIPT, *args], cwd=tmp_path, capture_output=True, text=True, env=NO_GL, timeout=300)
        line = one_line_error(proc)
        assert "libegl1 libegl-mesa0 libgl1 libgl1-mesa-dri" in line
    assert snapshot(tmp_path) == before
    proc = subprocess.run([SCRIPT, "tiling", "--kind", "corner", "--method", "direct", "--colors", "2",
                           "--region", "0,0,4x3", "--seed", "1"], cwd=tmp_path, capture_output=True, text=True,
                          env=NO_GL, timeout=300)
    assert proc.returncode == 0 and len(proc.stdout.split()) == 12, proc.stderr


def test_version_and_cpu_modules_do_not_import_moderngl():
    code = ("import contextlib, io, sys\nfrom tilesolve.cli.main import main\n"
            "with contextlib.redirect_stdout(io.StringIO()):\n    assert main(['--version']) == 0\n"
            "import tilesolve.families.stochastic, tilesolve.families.walls, tilesolve.families.packing\n"
            "print('moderngl' in sys.modules, 'glcontext' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300, check=True)
    assert out.stdout.split() == ["False", "False"]


# ------------------------------------------------------------------------------------ aperiodic textures
def _example(folder):
    img = np.random.default_rng(3).integers(0, 256, (48, 56, 3), dtype=np.uint8)
    Image.fromarray(img).save(folder / "ex.png")
    return img


def test_render_texture_aperiodic_gpu_and_cpu_write_the_same_picture(tmp_path):
    """The fast tier's aperiodic texture: GPU and CPU files identical, and the library's picture."""
    ex = _example(tmp_path)
    args = ["render", "texture", "--example", "ex.png", "--aperiodic", "jeandel-rao", "--tile", "16", "--scale", "6",
            "--size", "90x50", "--seed", "4", "--origin", "-30,8"]
    gpu = run(*args, "-o", "gpu.png", "--atlas", "atlas.png", cwd=tmp_path)
    assert gpu.returncode == 0, gpu.stderr
    assert re.search(r"^  cells coded by the shader: 135; left to the CPU route .*: 0$", gpu.stderr, re.M)
    cpu = run(*args, "--cpu", "-o", "cpu.png", cwd=tmp_path)
    assert cpu.returncode == 0, cpu.stderr
    assert "(CPU)" in cpu.stderr
    picture = np.asarray(Image.open(tmp_path / "gpu.png"))
    assert np.array_equal(np.asarray(Image.open(tmp_path / "cpu.png")), picture)
    at = WangAtlas.from_example(ex, load("jeandel-rao")[0].tiles, tile=16, seed=4)
    assert np.array_equal(np.asarray(Image.open(tmp_path / "atlas.png")), at.image)
    assert np.array_equal(picture, WangTexture("jeandel-rao", at, seed=4, origin=(-30, 8), tile_px=6).image(90, 50))


@pytest.mark.slow
def test_render_texture_aperiodic_on_the_cpu_needs_no_gl(tmp_path):
    _example(tmp_path)
    args = ["render", "texture", "--example", "ex.png", "--aperiodic", "kari-culik-13", "--tile", "16",
            "--size", "64x48", "--seed", "2"]
    proc = subprocess.run([SCRIPT, *args, "--cpu", "-o", "cpu.png"], cwd=tmp_path, capture_output=True, text=True,
                          env=NO_GL, timeout=300)
    assert proc.returncode == 0, proc.stderr
    one_line_error(subprocess.run([SCRIPT, *args, "-o", "gpu.png"], cwd=tmp_path, capture_output=True, text=True,
                                  env=NO_GL, timeout=300))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cpu.png", "ex.png"]


@pytest.mark.slow
@pytest.mark.parametrize("args,says", [
    (["--aperiodic", "periodic-7-30"], "no constructive route"),
    (["--aperiodic", "nope"], "no constructive route"),
    (["--cpu"], "--cpu draws aperiodic textures"),
    (["--aperiodic", "jeandel-rao", "--colors", "2"], "--colors: options of corner-tile textures"),
    (["--aperiodic", "jeandel-rao", "--per-fragment", "--hash", "table"], "--hash, --per-fragment"),
    (["--aperiodic", "jeandel-rao", "--tile", "18", "--cpu", "--benchmark", "2"], "--benchmark times the GPU"),
    (["--aperiodic", "labbe-u19", "--tile", "9"], "even"),
    (["--aperiodic", "kari-14", "--tile", "8", "--origin", "0,-4611686018427387904"], "lattice"),
    (["--aperiodic", "kari-14", "--tile", "64"], "smaller than a diamond"),
])
def test_render_texture_aperiodic_bad_input_one_line_exit_2(tmp_path, args, says):
    _example(tmp_path)
    (tmp_path / "keep.png").write_bytes(b"earlier")
    before = snapshot(tmp_path)
    for where in ([], ["--cpu"]) if "--cpu" not in args and "--benchmark" not in args else ([],):
        proc = run("render", "texture", "--example", "ex.png", "--size", "40x30", *args, *where, "-o", "keep.png",
                   cwd=tmp_path)
        assert says in one_line_error(proc)
    assert snapshot(tmp_path) == before


#: The commands that make the README's picture of a texture that never repeats.
README_TEXTURE = ("render wall --size 384x384 --max-line 4 --seed 3 --cell 12 -o wall.png".split(),
                  ("render texture --example wall.png --aperiodic jeandel-rao --seed 1 --tile 64 --size 576x288 "
                   "-o aperiodic-texture.png").split())


@pytest.mark.slow
def test_the_readme_texture_is_what_its_commands_draw(tmp_path):
    for args in README_TEXTURE:
        proc = run(*args, cwd=tmp_path)
        assert proc.returncode == 0, proc.stderr
    shipped = Path(__file__).resolve().parents[2] / "examples" / "aperiodic-texture.png"
    assert np.array_equal(np.asarray(Image.open(tmp_path / "aperiodic-texture.png")), np.asarray(Image.open(shipped)))
