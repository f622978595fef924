"""Textures that never repeat (``render texture --aperiodic``): the GPU path against the CPU path.

Rows, each beside the CPU path of the same picture measured in the same run:

* ``command``: the whole ``tilesolve render texture --example ex.png --aperiodic NAME --seed 1
  --tile 32 --size WxH -o t.png`` as a fresh process, GPU (llvmpipe without a GPU) and
  ``--cpu``; wall and CPU seconds of the process (llvmpipe's rendering threads included) and
  its peak RSS; the two PNG files are compared byte for byte.
* ``picture``: :meth:`WangTextureMapper.image` against :meth:`WangTexture.image` in process
  (the atlas built once), best of ``--repeat``: the tiles of the picture's cells (the shader's
  Markov coding, or the route's window uploaded) and every pixel read back.
* ``frames``: :data:`FRAMES` frames of the picture drawn by the GPU path, each frame the whole
  pass (the Markov cells coded or the window uploaded, then every pixel), against the same
  frames of the corner-tile texture (:class:`~tilesolve.gpu.texture.TextureMapper`, C = 3, the
  same tile size; ratio corner time / Wang time).
* ``cells``: the Markov coding of the picture's cells alone: the shader
  (:class:`~tilesolve.gpu.wang_texture._MarkovCells`, read back) against
  :func:`tilesolve.constructive.markov.markov_window`.

Peak memory: the command's peak RSS; in process, the peak traced by tracemalloc of one picture
(numpy buffers; llvmpipe's own memory is not traced).

Two scales: 32 px a tile (the README command: 25 x 19 cells) and 1 px a tile (one cell a
pixel: 480,000 cells, where coding the cells is the work). The ratio is CPU time / GPU time of
the wall clock (> 1: the GPU path is faster), except on the frame rows.

Usage::

    python benchmarks/bench_wang_texture.py                 # 800x600, jeandel-rao and kari-culik-13
    python benchmarks/bench_wang_texture.py --size 1920x1080 --repeat 5
"""

from __future__ import annotations

import argparse
import filecmp
import os
import sys
import tempfile
from pathlib import Path

import numpy as np

from _measure import best, child, peak_mib  # noqa: E402 - benchmarks/ is on sys.path

SEED = 1
TILE = 32
FRAMES = 10


def example(folder: Path) -> Path:
    from PIL import Image

    rng = np.random.default_rng(0)
    img = rng.integers(0, 256, (32, 32, 3)).astype(np.uint8)
    path = folder / "ex.png"
    Image.fromarray(img).resize((256, 256), Image.BICUBIC).save(path)
    return path


def frames(fbo, draw) -> None:
    """Draw :data:`FRAMES` frames and read the last back (every frame is then finished)."""
    for _ in range(FRAMES):
        draw()
    fbo.read(components=4)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--size", default="800x600", help="picture size WxH (default 800x600)")
    ap.add_argument("--repeat", type=int, default=3, help="runs per in-process row (best is kept)")
    ap.add_argument("--sets", default="jeandel-rao,kari-culik-13", help="comma-separated aperiodic sets")
    args = ap.parse_args()
    w, h = (int(v) for v in args.size.lower().split("x"))
    script = str(Path(sys.executable).parent / "tilesolve")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        ex = example(folder)
        load0 = os.getloadavg()
        # whole commands first, from a small parent (no heavy imports yet)
        for name in args.sets.split(","):
            for scale in (TILE, 1):
                runs = {}
                for how in ("gpu", "cpu"):
                    argv = [script, "render", "texture", "--example", str(ex), "--aperiodic", name, "--seed", str(SEED),
                            "--tile", str(TILE), "--scale", str(scale), "--size", f"{w}x{h}",
                            "-o", str(folder / f"{how}.png")]
                    r = min((child(argv + (["--cpu"] if how == "cpu" else [])) for _ in range(args.repeat)),
                            key=lambda r: r.wall)
                    if r.returncode:
                        raise SystemExit(f"{' '.join(argv)} exited {r.returncode}: {r.stderr}")
                    runs[how] = r
                same = filecmp.cmp(folder / "gpu.png", folder / "cpu.png", shallow=False)
                for how, r in runs.items():
                    rows.append((name, scale, "command", how, r.wall, r.cpu, f"{r.rss_mib:.0f} RSS", w * h,
                                 runs["cpu"].wall / r.wall, "same" if same else "DIFFER"))

        from tilesolve.constructive.markov import NAMES, markov_window
        from tilesolve.gpu.texture import read_example
        from tilesolve.gpu.wang_texture import WangAtlas, WangTexture, WangTextureMapper
        from tilesolve.io.builtin_tilesets import load
        from tilesolve.model.window import Window

        image = read_example(ex)
        # baseline of the frame rows: the corner-tile texture (class notes §5.4) of the same size and tile
        from tilesolve.gpu.texture import Atlas, TextureMapper

        mapper = TextureMapper(Atlas.from_example(image, 3, tile=TILE, seed=SEED), seed=SEED)
        fbo, draw = mapper.frame(w, h)
        corner, cpu_s, _ = best(lambda: frames(fbo, draw), args.repeat)
        rows.append(("corner C=3", TILE, "frames", f"gpu, {FRAMES} frames", corner, cpu_s, "-", FRAMES * w * h, 1.0, "-"))
        for name in args.sets.split(","):
            at = WangAtlas.from_example(image, load(name)[0].tiles, tile=TILE, seed=SEED)
            for scale in (TILE, 1):
                gpu = WangTextureMapper(name, at, seed=SEED, tile_px=scale)
                cpu = WangTexture(name, at, seed=SEED, tile_px=scale)
                gpu.image(w, h)  # warm: shaders compiled, route kernels loaded
                tg, cg, pg = best(lambda: gpu.image(w, h), args.repeat)
                tc, cc, pc = best(lambda: cpu.image(w, h), args.repeat)
                same = "same" if np.array_equal(pg, pc) else "DIFFER"
                mg, mc = (f"{peak_mib(lambda: p.image(w, h)):.0f} traced" for p in (gpu, cpu))
                rows.append((name, scale, "picture", "gpu", tg, cg, mg, w * h, tc / tg, same))
                rows.append((name, scale, "picture", "cpu", tc, cc, mc, w * h, 1.0, same))
                fbo, draw = gpu.frame(w, h)
                tg, cg, _ = best(lambda: frames(fbo, draw), args.repeat)
                rows.append((name, scale, "frames", f"gpu, {FRAMES} frames", tg, cg, "-", FRAMES * w * h, corner / tg,
                             "-"))
                if name in NAMES:
                    cols, nrows = -(-w // scale), -(-h // scale)
                    tg, cg, g = best(lambda: gpu._markov.code(0, 0, cols, nrows), args.repeat)
                    tc, cc, c = best(lambda: markov_window(name, Window(0, 0, cols, nrows), SEED), args.repeat)
                    decided = g != 255
                    agree = np.array_equal(g[decided], c[decided])
                    same = f"same ({(~decided).sum()} undecided)" if agree else "DIFFER"
                    rows.append((name, scale, "cells", "gpu shader", tg, cg, "-", cols * nrows, tc / tg, same))
                    rows.append((name, scale, "cells", "cpu markov_window", tc, cc, "-", cols * nrows, 1.0, same))
    load1 = os.getloadavg()
    from tilesolve.gpu.context import gpu_info

    print(f"renderer: {gpu_info()['renderer']}; {os.cpu_count()} CPU cores; picture {w}x{h}, tiles of {TILE} texels; "
          f"load average {load0[0]:.2f} before, {load1[0]:.2f} after")
    print("throughput: pixels a second (command, picture) or cells a second (cells); cpu s: the process's CPU time, "
          "llvmpipe's threads included")
    print(f"{'set':<15}{'px/tile':>8}  {'what':<9}{'implementation':<19}{'wall s':>8}{'cpu s':>8}{'peak MiB':>14}"
          f"{'M/s':>8}{'ratio':>9}  pictures")
    for name, scale, what, how, wall, cpu_s, mem, items, ratio, same in rows:
        print(f"{name:<15}{scale:>8}  {what:<9}{how:<19}{wall:>8.3f}{cpu_s:>8.3f}{mem:>14}{items / wall / 1e6:>8.2f}"
              f"{ratio:>8.2f}x  {same}")


if __name__ == "__main__":
    main()
