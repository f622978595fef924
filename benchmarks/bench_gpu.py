"""Frames per second of the GPU path at 1920x1080 (004 Table 1; class notes §5.4), against the CPU.

GPU rows (moderngl through EGL; on a machine without a GPU, Mesa's llvmpipe on the CPU cores):

* ``wall``: :class:`tilesolve.gpu.wall.WallRenderer`, 32 px cells, lines of at most 4 bricks,
  1 sample and every other sample count of 004 Table 1 the context allows; two passes (cells,
  then pixels) and ``per-fragment`` (the whole wall procedure in every fragment, as 004 §5.2);
* ``texture``: :class:`tilesolve.gpu.texture.TextureMapper`, C = 3, 64 px tiles at one pixel
  per texel; two passes (tiles, then pixels) and ``per-fragment`` (the tiling hash per fragment).

A frame is one draw of the full 1920x1080 picture; the clock stops after reading the last
frame back (the GPU has then finished every frame). Baselines in the same run, same picture:

* ``cpu numpy``: the CPU implementations of the same pictures: the wall's cells by
  :func:`~tilesolve.constructive.walls.wall_window` (compiled) and its pixels (brick id
  colours, 004 §3.2) by :func:`tilesolve.families.wall_render.wall_map_pixels` in its numpy form, and
  ``cpu compiled`` its numba form; the texture's tiles by
  :func:`~tilesolve.constructive.stochastic.direct_corner` and its pixels by one numpy gather
  from the atlas.

The ratio is fps / CPU numpy fps. The load average is printed before and after: the machine
may be shared, and llvmpipe uses every core. So the table also gives the CPU seconds each frame
took (this process, llvmpipe's threads included) and the frame rate they would give on idle
cores (all cores for llvmpipe, one for numpy). A ``bare`` row renders a shader that only
writes its coordinates: the floor of a 1920x1080 frame on this renderer.

Usage::

    python benchmarks/bench_gpu.py              # 1920x1080, about 2 s per row
    python benchmarks/bench_gpu.py --seconds 5

Goals (issue 12): wall shader at 1920x1080, 1 sample, >= 200 fps on llvmpipe (004 Table 1's
figure for a Quadro K620); texture mapping at 1920x1080 >= 300 fps on llvmpipe; on a real GPU
the wall >= 10,000 fps.
"""

from __future__ import annotations

import argparse
import os
import resource
import time

import numpy as np

from tilesolve.constructive.stochastic import direct_corner
from tilesolve.constructive.walls import wall_window
from tilesolve.gpu.context import gpu_info
from tilesolve.gpu.texture import Atlas, TextureMapper
from tilesolve.gpu.wall import WallRenderer, allowed_samples
from tilesolve.families.wall_render import wall_map_pixels

W, H = 1920, 1080
CELL, MAX_LINE, SEED = 32, 4, 1
COLORS, TILE = 3, 64


def rss_mib() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def fps(draw, finish, seconds: float) -> tuple[int, float, float]:
    """Frames drawn in about ``seconds`` (at least 3), the rate, and the CPU seconds per frame of
    this process (llvmpipe's rendering threads included)."""
    draw()
    finish()
    n, t, c = 0, time.perf_counter(), time.process_time()
    while n < 3 or time.perf_counter() - t < seconds:
        for _ in range(max(1, n)):  # double the batch: few clock reads, few pipeline stalls
            draw()
        n += max(1, n)
        finish()
    return n, n / (time.perf_counter() - t), (time.process_time() - c) / n


def gpu_row(renderer, seconds: float) -> tuple[int, float, float]:
    fbo, draw = renderer.frame(W, H)
    return fps(draw, lambda: fbo.read(components=4), seconds)


def cpu_wall(compiled: bool):
    cols, rows = W // CELL + 1, H // CELL + 1

    def draw():
        legs = wall_window(-1, -1, cols + 2, rows + 2, colors=3, max_line=MAX_LINE, seed=SEED)
        return wall_map_pixels(legs, "id", colors=3, ppc=CELL, origin=(0, 0), compiled=compiled)

    return draw


def cpu_texture(atlas: Atlas):
    t, rows = atlas.tile, atlas.grid.shape[0]
    where = atlas.where().astype(np.int64)
    nx, ny = -(-W // t), -(-H // t)
    full_y, full_x = np.arange(ny * t)[-H:], np.arange(W)  # the picture grows from the SW corner
    tr, ty, tc, tx = full_y // t, full_y % t, full_x // t, full_x % t

    def draw():
        g = direct_corner(0, 0, nx, ny, colors=COLORS, seed=SEED)
        ar, ac = rows - 1 - where[g, 1], where[g, 0]  # each tile's place in the atlas (row from the top)
        y = ar[tr][:, tc] * t + ty[:, None]
        x = ac[tr][:, tc] * t + tx[None, :]
        return atlas.image[y, x]

    return draw


def bare_row(seconds: float) -> tuple[int, float, float]:
    """The floor: a shader that only writes its coordinates, through the same full-screen quad."""
    import moderngl

    from tilesolve.gpu.context import gpu_context

    ctx = gpu_context()
    prog = ctx.program(vertex_shader="#version 450\nin vec2 in_pos; void main() { gl_Position = vec4(in_pos, 0, 1); }",
                       fragment_shader="#version 450\nout vec4 f; void main() { f = vec4(gl_FragCoord.xy / 2048.0, 0, 1); }")
    quad = ctx.buffer(np.array([-1, -1, 1, -1, -1, 1, 1, 1], dtype="f4").tobytes())
    vao = ctx.vertex_array(prog, [(quad, "2f", "in_pos")])
    fbo = ctx.simple_framebuffer((W, H), components=4)

    def draw():
        fbo.use()
        vao.render(mode=moderngl.TRIANGLE_STRIP)

    return fps(draw, lambda: fbo.read(components=4), seconds)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--seconds", type=float, default=2.0, help="time per row (default 2)")
    args = ap.parse_args()
    info = gpu_info()
    load0 = os.getloadavg()
    print(f"renderer: {info['renderer']}, OpenGL {info['version']}; {os.cpu_count()} CPU cores; "
          f"load average {load0[0]:.2f} {load0[1]:.2f} {load0[2]:.2f}")
    rows = []
    for per_fragment in (False, True):
        for s in allowed_samples():
            r = WallRenderer(colors=3, max_line=MAX_LINE, seed=SEED, cell_px=CELL, samples=s,
                             per_fragment=per_fragment)
            rows.append(("wall", f"gpu{' per-fragment' if per_fragment else ''}", s, *gpu_row(r, args.seconds)))
            if per_fragment:
                break  # the per-fragment wall at one sample shows its cost; more samples multiply it
    for compiled in (False, True):
        rows.append(("wall", "cpu compiled" if compiled else "cpu numpy", 1,
                     *fps(cpu_wall(compiled), lambda: None, args.seconds)))
    example = np.random.default_rng(0).integers(0, 256, (256, 256, 3), dtype=np.uint8)
    atlas = Atlas.from_example(example, COLORS, tile=TILE, seed=SEED)
    for two_pass in (True, False):
        m = TextureMapper(atlas, seed=SEED, two_pass=two_pass)
        rows.append(("texture", f"gpu{'' if two_pass else ' per-fragment'}", 1, *gpu_row(m, args.seconds)))
    rows.append(("texture", "cpu numpy", 1, *fps(cpu_texture(atlas), lambda: None, args.seconds)))
    rows.append(("bare", "gpu", 1, *bare_row(args.seconds)))
    same = np.array_equal(cpu_texture(atlas)(), TextureMapper(atlas, seed=SEED).image(W, H))

    base = {what: f for what, how, _, _, f, _ in rows if how == "cpu numpy"}
    cores = os.cpu_count()
    print(f"{'picture':<9}{'implementation':<18}{'size':>11}{'samples':>8}{'frames':>8}{'s/frame':>9}"
          f"{'fps':>8}{'Mpixel/s':>9}{'vs numpy':>9}{'cpu s/frame':>12}{f'fps/{cores} idle cores':>18}")
    for what, how, s, n, f, cpu in rows:
        ratio = f"{f / base[what]:.1f}x" if what in base else "-"
        idle = cores / cpu if how.startswith("gpu") else 1 / cpu  # llvmpipe uses every core, numpy one
        print(f"{what:<9}{how:<18}{f'{W}x{H}':>11}{s:>8}{n:>8}{1 / f:>9.4f}{f:>8.1f}{W * H * f / 1e6:>9.1f}"
              f"{ratio:>9}{cpu:>12.4f}{idle:>18.1f}")
    load1 = os.getloadavg()
    print(f"texture: GPU and CPU pictures {'identical' if same else 'DIFFER'}; peak RSS {rss_mib():.0f} MiB; load average after {load1[0]:.2f} {load1[1]:.2f} {load1[2]:.2f}")


if __name__ == "__main__":
    main()
