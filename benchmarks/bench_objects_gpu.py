"""The procedural object distribution function (class notes §6.6.2): the shader against the CPU.

Rows, GPU (Mesa's llvmpipe where there is no GPU) beside the CPU path of the same picture,
measured in the same run:

* ``command``: the whole ``tilesolve sample poisson-tiles texture set.json --region
  X0,Y0,WxH --px P --seed 1 --png t.png``, with and without ``--gpu``, as a fresh process
  (best wall of ``--repeat``); wall and CPU seconds of the process (llvmpipe's threads
  included) and its peak RSS; the two PNG files compared byte for byte.
* ``kernel``: the function at every pixel in process: :meth:`tilesolve.gpu.objects.ObjectMapper.evaluate`
  (the mapper made once: shaders compiled, the cells' points uploaded) against
  :func:`tilesolve.families.poisson.objects` (the CPU's ``object_distribution``), best of
  ``--repeat``; peak memory traced by tracemalloc (numpy buffers; llvmpipe's own memory is not
  traced); every array compared.
* ``setup``: making the mapper (compiling both shaders, the cells' points), once.

The set is the demo's (C = 2, N = 64, rho = 0.75, seed 1), the picture far from the origin
(x0 = 2**40). The ratio is CPU wall / GPU wall (> 1: the GPU path is faster), the cpu ratio
the same of CPU seconds (llvmpipe's threads included), the steadier one on a shared machine.

Usage::

    python benchmarks/bench_objects_gpu.py                     # 20 x 15 tiles at 32 px: 640 x 480
    python benchmarks/bench_objects_gpu.py --tiles 40x30 --px 32 --repeat 3
"""

from __future__ import annotations

import argparse
import filecmp
import os
import sys
import tempfile
import time
from pathlib import Path

from _measure import best, child, peak_mib  # noqa: E402 - benchmarks/ is on sys.path

SEED = 1
X0, Y0 = 2**40, -7


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--tiles", default="20x15", help="window in tiles WxH (default 20x15)")
    ap.add_argument("--px", type=int, default=32, help="pixels a tile side (default 32)")
    ap.add_argument("--repeat", type=int, default=2, help="runs per row (best is kept)")
    args = ap.parse_args()
    tw, th = (int(v) for v in args.tiles.lower().split("x"))
    w, h = tw * args.px, th * args.px
    script = str(Path(sys.executable).parent / "tilesolve")
    region = f"{X0},{Y0},{tw}x{th}"
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        build = child([script, "sample", "poisson-tiles", "build", "-C", "2", "-N", "64", "--rho", "0.75", "--seed",
                       str(SEED), "-o", str(folder / "set.json")])
        if build.returncode:
            raise SystemExit(f"build exited {build.returncode}: {build.stderr}")
        load0 = os.getloadavg()
        runs = {}
        for how in ("gpu", "cpu"):  # whole commands first, from a small parent (no heavy imports yet)
            argv = [script, "sample", "poisson-tiles", "texture", str(folder / "set.json"), "--region", region,
                    "--px", str(args.px), "--seed", str(SEED), "--png", str(folder / f"{how}.png")]
            r = min((child(argv + (["--gpu"] if how == "gpu" else [])) for _ in range(args.repeat)),
                    key=lambda r: r.wall)
            if r.returncode:
                raise SystemExit(f"{' '.join(argv)} exited {r.returncode}: {r.stderr}")
            runs[how] = r
        same = "same PNG" if filecmp.cmp(folder / "gpu.png", folder / "cpu.png", shallow=False) else "PNG DIFFER"
        for how, r in runs.items():
            rows.append(("command", how, r.wall, r.cpu, f"{r.rss_mib:.0f} RSS", runs["cpu"].wall / r.wall,
                         runs["cpu"].cpu / r.cpu, same))

        import numpy as np

        from tilesolve.families.poisson import objects
        from tilesolve.gpu.context import gpu_info
        from tilesolve.gpu.objects import ObjectMapper
        from tilesolve.io.jsonio import load_document
        from tilesolve.io.poisson_json import TILES_FORMAT, VERSIONS, tiles_from_dict
        from tilesolve.model.window import Window

        ts = tiles_from_dict(load_document(str(folder / "set.json"), {TILES_FORMAT: VERSIONS}), "set.json")[1].tiling
        window = Window(X0, Y0, tw, th)
        t, c = time.perf_counter(), time.process_time()
        mapper = ObjectMapper(ts, px=args.px, seed=SEED, origin=(X0, Y0))
        setup = (time.perf_counter() - t, time.process_time() - c)
        mapper.evaluate(w, h)  # warm
        tg, cg, g = best(lambda: mapper.evaluate(w, h), args.repeat)
        tc, cc, cpu = best(lambda: objects(ts, window, args.px, seed=SEED), args.repeat)
        exact = all(np.array_equal(g[k], cpu[k]) for k in cpu)
        agree = "arrays equal" if exact else ("ids equal" if np.array_equal(g["id"], cpu["id"]) else "IDS DIFFER")
        mg = peak_mib(lambda: mapper.evaluate(w, h))
        mc = peak_mib(lambda: objects(ts, window, args.px, seed=SEED))
        rows.append(("kernel", "gpu", tg, cg, f"{mg:.0f} traced", tc / tg, cc / cg, agree))
        rows.append(("kernel", "cpu", tc, cc, f"{mc:.0f} traced", 1.0, 1.0, agree))
        rows.append(("setup", "gpu mapper", setup[0], setup[1], "-", float("nan"), float("nan"), "-"))
    load1 = os.getloadavg()
    print(f"renderer: {gpu_info()['renderer']}; {os.cpu_count()} CPU cores; set C = 2, N = 64, rho = 0.75; "
          f"window {region} at {args.px} px a tile = {w}x{h} px; load average {load0[0]:.2f} before, "
          f"{load1[0]:.2f} after")
    print("throughput: pixels a second; cpu s: the process's CPU time, llvmpipe's threads included; "
          "ratio: CPU wall / this row's wall; cpu ratio: the same of CPU times (the better measure on a busy machine)")
    print(f"{'what':<9}{'implementation':<16}{'pixels':>10}{'wall s':>9}{'cpu s':>9}{'peak MiB':>14}{'Mpx/s':>8}"
          f"{'ratio':>9}{'cpu ratio':>10}  result")
    for what, how, wall, cpu_s, mem, ratio, cpu_ratio, note in rows:
        tput = "-" if what == "setup" else f"{w * h / wall / 1e6:.2f}"
        rat, crat = ("-", "-") if what == "setup" else (f"{ratio:.2f}x", f"{cpu_ratio:.2f}x")
        print(f"{what:<9}{how:<16}{w * h:>10,}{wall:>9.3f}{cpu_s:>9.3f}{mem:>14}{tput:>8}{rat:>9}{crat:>10}  {note}")


if __name__ == "__main__":
    main()
