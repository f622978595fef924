"""The object distribution function (class notes §6.6.2) in a shader against the CPU, pixel for pixel.

Nothing here is skipped (Mesa's llvmpipe through EGL in CI, as tests/gpu/test_gpu.py). The
reference is :func:`tilesolve.families.poisson.objects` (the CPU's
:func:`~tilesolve.constructive.poisson.object_distribution` at the pixel centres): the id
(cell and rank of the closest point) and ``inside`` must be identical at every pixel; the
distance, the closest point and the local coordinates within 1e-12 (:data:`TOLERANCE`; they
are computed with the CPU's double operations in its order, and equal on llvmpipe).
"""

from __future__ import annotations

import os

import numpy as np
import pytest
from clitools import ENV, one_line_error, run

from tilesolve.constructive.poisson import build_tiles, window_points
from tilesolve.families.poisson import objects as cpu_objects
from tilesolve.gpu.objects import ObjectMapper, cell_points
from tilesolve.gpu.objects import objects as gpu_objects
from tilesolve.model.poisson import PoissonTilesProblem
from tilesolve.model.window import Window

#: Largest difference allowed in the float arrays (tile units; local: disk radii).
TOLERANCE = 1e-12
HUGE = 2**61 + 12345


@pytest.fixture(scope="module")
def sets():
    return {c: build_tiles(PoissonTilesProblem(c, n, 0.7), seed=11) for c, n in ((1, 16), (2, 32), (3, 16))}


def _same(gpu: dict, cpu: dict) -> None:
    assert set(gpu) == set(cpu)
    assert np.array_equal(gpu["id"], cpu["id"])
    assert np.array_equal(gpu["inside"], cpu["inside"])
    for key in ("closest", "distance", "local"):
        assert gpu[key].shape == cpu[key].shape
        assert np.abs(gpu[key] - cpu[key]).max() <= TOLERANCE, key


@pytest.mark.fast_cases(4)
@pytest.mark.parametrize("colors,origin,size,px,seed", [
    (2, (0, 0), (6, 4), 24, 2),
    (2, (-7, 2**40), (5, 3), 17, 5),           # far north
    (2, (HUGE, -HUGE), (3, 3), 31, 9),          # near the end of the 63-bit lattice
    (1, (-(2**40) - 3, 5), (4, 2), 12, 0),
    (3, (123456789, -987654321), (4, 3), 9, 4),
    (2, (-1, -1), (40, 30), 1, 7),               # a pixel a tile: every pixel next to a seam
    (3, (2**33, 2**33), (2, 2), 256, 1),        # pixels within 1/512 of the seams
])
def test_every_pixel_equals_the_cpu(sets, colors, origin, size, px, seed):
    window = Window(origin[0], origin[1], *size)
    _same(gpu_objects(sets[colors], window, px, seed=seed), cpu_objects(sets[colors], window, px, seed=seed))


def test_passes_give_the_pixels_of_one_pass(sets):
    m = ObjectMapper(sets[2], px=13, seed=3, origin=(-50, 2**40))
    whole = m.evaluate(130, 91)
    m.max_pass = 40  # as if the context's viewport were 40 px: 4 x 3 passes, cut inside cells
    cut = m.evaluate(130, 91)
    assert all(np.array_equal(whole[k], cut[k]) for k in whole)
    _same(whole, cpu_objects(sets[2], Window(-50, 2**40, 10, 7), 13, seed=3))


def test_cells_hold_the_points_of_every_window(sets):
    """What the shader searches: a cell's points, in the CPU's order, by its corner tile."""
    from tilesolve.constructive.stochastic import direct_corner

    ts = sets[3]
    counts, origin, frame = cell_points(ts)
    x0, y0, w, h = -3, 2**40, 5, 4
    pts = window_points(ts, (x0, y0, w, h), seed=6).local
    grid = direct_corner(x0, y0, w, h, colors=3, seed=6)[::-1]  # row j: y0 + j
    cell = np.floor(pts).astype(np.int64)
    for (j, i), t in np.ndenumerate(grid):
        mine = pts[(cell[:, 0] == i) & (cell[:, 1] == j)] - [i, j]
        mine = mine[np.lexsort((mine[:, 1], mine[:, 0]))]
        n = counts[t]
        assert len(mine) == n
        assert np.abs(origin[t, :n] + frame[t, :n] - mine).max() < 1e-12


def test_the_objects_do_not_overlap(sets):
    """§6.6.2: an object is drawn in the disk of radius d/2 of its point; two disks' points are at
    least d apart, so no pixel is in two objects."""
    ts = sets[2]
    out = ObjectMapper(ts, px=20, seed=8, origin=(2**40, -3)).evaluate(200, 160)
    inside = out["inside"]
    assert inside.any() and (np.hypot(*out["local"][inside].T) < 1).all()
    ids, first = np.unique(out["id"][inside], axis=0, return_index=True)
    centres = out["closest"][inside][first]
    gaps = np.hypot(*(centres[:, None] - centres[None]).transpose(2, 0, 1)) + np.eye(len(ids)) * 9
    assert gaps.min() >= ts.problem.distance
    same_id = (out["id"][inside][:, None] == ids[None]).all(axis=2).argmax(axis=1)
    assert np.array_equal(out["closest"][inside], centres[same_id])  # one point per id


@pytest.fixture(scope="module")
def folder(tmp_path_factory, sets):
    from PIL import Image

    from tilesolve.io.poisson_json import dump, tiles_to_dict
    from tilesolve.model.solution import Solution, Status

    d = tmp_path_factory.mktemp("objects")
    ts = sets[2]
    (d / "set.json").write_text(dump(tiles_to_dict(ts.problem, Solution(Status.SAT, ts, method="dart", seed=11))))
    yy, xx = np.mgrid[0:24, 0:24]
    star = np.zeros((24, 24, 4), np.uint8)
    star[..., 0], star[..., 2] = xx * 10, yy * 10
    star[..., 3] = np.where(np.abs(xx - 11.5) + np.abs(yy - 11.5) < 12, 255, 0)
    Image.fromarray(star, "RGBA").save(d / "star.png")
    return d


@pytest.mark.fast_cases(1)
@pytest.mark.parametrize("region,more", [("-9,4,3x2", ["--image", "star.png"]), ("-9,4,3x2", []),
                                         ("1099511627776,-1099511627777,2x2", ["--image", "star.png"])])
def test_gpu_flag_writes_the_cpu_png(folder, more, region):
    """The example image scattered over the shaded background (or the default disks): the same file."""
    args = ["sample", "poisson-tiles", "texture", "set.json", "--region", region, "--px", "20", "--seed", "3", *more]
    cpu = run(*args, "--png", "cpu.png", cwd=folder)
    gpu = run(*args, "--gpu", "--png", "gpu.png", cwd=folder)
    assert cpu.returncode == 0 and gpu.returncode == 0, (cpu.stderr, gpu.stderr)
    assert (folder / "gpu.png").read_bytes() == (folder / "cpu.png").read_bytes()
    assert gpu.stderr.splitlines()[0] == cpu.stderr.splitlines()[0]  # "ok: ... pixels inside a Poisson disk"


@pytest.mark.slow
def test_objects_scattered_over_a_wall(folder, sets):
    """--background: the wall shows where no object is, the object where it is opaque; the GPU's file is the CPU's."""
    from PIL import Image

    assert run("render", "wall", "--size", "50x30", "--seed", "4", "-o", "wall.png", cwd=folder).returncode == 0
    args = ["sample", "poisson-tiles", "texture", "set.json", "--region", "-9,4,3x2", "--px", "20", "--seed", "3",
            "--image", "star.png", "--background", "wall.png"]
    assert run(*args, "--png", "cpu.png", cwd=folder).returncode == 0
    assert run(*args, "--gpu", "--png", "gpu.png", cwd=folder).returncode == 0
    assert (folder / "gpu.png").read_bytes() == (folder / "cpu.png").read_bytes()
    picture = np.asarray(Image.open(folder / "cpu.png"))
    wall = np.asarray(Image.open(folder / "wall.png"))[..., :3]
    ev = cpu_objects(sets[2], Window(-9, 4, 3, 2), 20, seed=3)
    under = wall[np.arange(40) % 30][:, np.arange(60) % 50]  # repeated from the top-left corner
    assert np.array_equal(picture[~ev["inside"]], under[~ev["inside"]])
    star = np.asarray(Image.open(folder / "star.png"))
    col = np.clip(((ev["local"][..., 0] + 1) / 2 * 24).astype(int), 0, 23)
    row = np.clip(((1 - ev["local"][..., 1]) / 2 * 24).astype(int), 0, 23)
    opaque = ev["inside"] & (star[row, col, 3] == 255)
    assert opaque.any() and np.array_equal(picture[opaque], star[row, col, :3][opaque])


def test_gpu_flag_without_opengl_is_one_line_and_no_file(folder, monkeypatch):
    import clitools

    monkeypatch.setattr(clitools, "ENV", dict(ENV, __EGL_VENDOR_LIBRARY_FILENAMES=os.devnull))
    r = run("sample", "poisson-tiles", "texture", "set.json", "--region", "0,0,2x2", "--px", "8", "--gpu",
            "--png", "none.png", cwd=folder)
    assert "OpenGL" in one_line_error(r, 2)
    assert not (folder / "none.png").exists()


@pytest.mark.parametrize("background", ["missing.png", "set.json"])
def test_an_unreadable_background_is_one_line_and_no_file(folder, background):
    r = run("sample", "poisson-tiles", "texture", "set.json", "--region", "0,0,2x2", "--px", "8", "--gpu",
            "--background", background, "--png", "none.png", cwd=folder)
    assert background in one_line_error(r, 2)
    assert not (folder / "none.png").exists()
