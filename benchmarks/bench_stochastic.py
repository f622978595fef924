"""Speed of the stochastic tilings (class notes ch. 3) over large windows.

Times, on square windows of 10^5 .. 10^7 tiles over 3 colours (numba compile excluded, one
core): the direct stochastic corner tiling (§3.3.1), the direct Wang tiling with the edge hash
(§3.3.2.3), and the scanline Wang tiling (§3.2.1) with the complete and the compact set, each
with the one-table hash (§3.4.1, 258 entries) and the long-period hash (§3.4.3, period
5,930,659,848). The baseline, measured in the same run, is a straight per-tile Python
transcription of the same algorithm with the scalar hashes on 10^4 tiles (checked equal to
the window). Prints time, throughput, tracemalloc's peak and the per-tile ratio.

``--command`` measures the whole command instead (issue 19): ``tilesolve tiling --kind corner
--method direct --colors 3 --region 0,0,SxS --png t.png`` (the window tiled, verified, drawn
at the default 4 px a tile) beside two anchors, each a child process (CPU time user + sys and
peak RSS from ``os.wait4``; the run of least CPU of ``--repeat`` after one warm-up run of
each): ``direct_corner`` of the same window called in a fresh Python process (import, numba
cache load and the call), and the kernel alone, the CPU time of the call in that process
(best of 3 calls after one). The ratios are the command's CPU over each.

Usage::

    python benchmarks/bench_stochastic.py            # 10^5, 10^6, 10^7 tiles
    python benchmarks/bench_stochastic.py --quick    # 10^5, 10^6 tiles
    python benchmarks/bench_stochastic.py --command  # tiling --png at 3163^2 beside direct_corner

Goals (issue 10): direct corner tiling of 10^7 tiles <= 0.1 s; scanline Wang tiling of 10^7
tiles <= 0.5 s. Issue 19: the ``tiling --png`` command <= 5x the kernel, verification and PNG
included.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import tempfile
import time
import tracemalloc

import numpy as np

from _measure import best, best_child  # noqa: E402 - benchmarks/ is on sys.path

C, SEED, X0, Y0 = 3, 5, -1234, 777


def kernels():
    """:mod:`tilesolve.constructive.stochastic`, imported when first needed (``--command``
    measures children before: a child's peak RSS starts from its parent's)."""
    from tilesolve.constructive import stochastic

    return stochastic


def py_direct_corner(w, h, hash_name):
    """§3.3.1 tile by tile: four scalar hash evaluations and eq. 2.5."""
    hsh = kernels().make_hash(hash_name, C, SEED)
    out = []
    for y in range(Y0 + h - 1, Y0 - 1, -1):
        row = []
        for x in range(X0, X0 + w):
            ne, se = hsh.scalar(x + 1, y + 1) % C, hsh.scalar(x + 1, y) % C
            sw, nw = hsh.scalar(x, y) % C, hsh.scalar(x, y + 1) % C
            row.append(((ne * C + se) * C + sw) * C + nw)
        out.append(row)
    return np.array(out)


def py_direct_wang(w, h, hash_name):
    """§3.3.2.3 tile by tile: N, E, S, W = h(2x+1, 2y+2), h(2x+2, 2y+1), h(2x+1, 2y), h(2x, 2y+1)."""
    hsh = kernels().make_hash(hash_name, C, SEED)
    out = []
    for y in range(Y0 + h - 1, Y0 - 1, -1):
        row = []
        for x in range(X0, X0 + w):
            n, e = hsh.scalar(2 * x + 1, 2 * y + 2) % C, hsh.scalar(2 * x + 2, 2 * y + 1) % C
            s, wc = hsh.scalar(2 * x + 1, 2 * y) % C, hsh.scalar(2 * x, 2 * y + 1) % C
            row.append(((n * C + e) * C + s) * C + wc)
        out.append(row)
    return np.array(out)


def py_scanline_wang(w, h, hash_name, compact):
    """§3.2.1 tile by tile, west to east, north to south, choices from the scalar hash."""
    hsh = kernels().make_hash(hash_name, math.lcm(C, 2) if compact else C * C, SEED)
    top = Y0 + h
    south = [(hsh.scalar(x, top) % C) if compact else (hsh.scalar(x, top) // C) % C for x in range(X0, X0 + w)]
    out = []
    for y in range(top - 1, Y0 - 1, -1):
        east = hsh.scalar(X0 - 1, y) % C
        row = []
        for k, x in enumerate(range(X0, X0 + w)):
            n, wc, v = south[k], east, hsh.scalar(x, y)
            if compact:
                e, s = (n + (v & 1)) % C, (wc + (v & 1)) % C
            else:
                e, s = v % C, (v // C) % C
            row.append(((n * C + e) * C + s) * C + wc)
            south[k], east = s, e
        out.append(row)
    return np.array(out)


CASES = [
    ("direct corner", lambda w, h, hs: kernels().direct_corner(X0, Y0, w, h, colors=C, seed=SEED, hash=hs),
     py_direct_corner),
    ("direct wang edges", lambda w, h, hs: kernels().direct_wang(X0, Y0, w, h, colors=C, seed=SEED, hash=hs),
     py_direct_wang),
    ("scanline wang", lambda w, h, hs: kernels().scanline_wang(X0, Y0, w, h, colors=C, seed=SEED, hash=hs),
     lambda w, h, hs: py_scanline_wang(w, h, hs, False)),
    ("scanline wang compact",
     lambda w, h, hs: kernels().scanline_wang(X0, Y0, w, h, colors=C, seed=SEED, variant="compact", hash=hs),
     lambda w, h, hs: py_scanline_wang(w, h, hs, True)),
]


def kernel_child(side: int) -> None:
    """In a child: the CPU seconds of the best of 3 calls of direct_corner (after one), as JSON."""
    direct_corner = kernels().direct_corner
    direct_corner(0, 0, side, side, colors=C, seed=SEED)
    _, cpu, _ = best(lambda: direct_corner(0, 0, side, side, colors=C, seed=SEED), 3)
    print(json.dumps({"kernel_cpu": cpu}))


def command_rows(side: int, repeat: int) -> None:
    """``tilesolve tiling ... --png`` beside direct_corner (module docstring)."""
    exe = os.path.join(os.path.dirname(sys.executable), "tilesolve")
    anchor = [sys.executable, "-c", "from tilesolve.constructive.stochastic import direct_corner; "
              f"direct_corner(0, 0, {side}, {side}, colors={C}, seed={SEED})"]
    kernel = [sys.executable, os.path.abspath(__file__), "--kernel-child", str(side)]
    command = [exe, "tiling", "--kind", "corner", "--method", "direct", "--colors", str(C), "--region",
               f"0,0,{side}x{side}", "--seed", str(SEED), "--png", "t.png"]
    tiles = side * side
    print(f"tiling --png beside direct_corner, {side}x{side} = {tiles:,} tiles, C = {C}; best CPU of {repeat}")
    with tempfile.TemporaryDirectory() as d:
        for argv in (anchor, kernel, command):
            best_child(argv, 1, cwd=d)  # warm-up: bytecode and numba caches
        base = best_child(anchor, repeat, cwd=d)
        k_cpu = min(json.loads(best_child(kernel, 1, cwd=d).stdout.strip().splitlines()[-1])["kernel_cpu"]
                    for _ in range(repeat))
        run = best_child(command, repeat, cwd=d)
        size = os.path.getsize(os.path.join(d, "t.png")) / 2**20
    print(f"{'run':<36}{'wall s':>8}{'cpu s':>8}{'sys s':>8}{'RSS MiB':>9}{'Mtiles/cpu s':>13}{'file MiB':>9}"
          f"{'/ kernel':>9}{'/ process':>10}")
    print(f"{'direct_corner, the call alone':<36}{'':>8}{k_cpu:>8.3f}{'':>8}{'':>9}{tiles / k_cpu / 1e6:>13.1f}"
          f"{'':>9}{1:>9.2f}{'':>10}")
    for name, r, mib in (("direct_corner in a process", base, ""), ("tilesolve tiling ... --png t.png", run, size)):
        print(f"{name:<36}{r.wall:>8.2f}{r.cpu:>8.2f}{r.sys:>8.2f}{r.rss_mib:>9.0f}{tiles / r.cpu / 1e6:>13.1f}"
              f"{mib if mib == '' else f'{mib:.1f}':>9}{r.cpu / k_cpu:>9.1f}{r.cpu / base.cpu:>10.2f}")
    print("/ kernel: CPU over the call alone (goal, issue 19: <= 5); / process: over direct_corner in a process")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--command", action="store_true", help="the whole tiling --png command beside direct_corner")
    ap.add_argument("--side", type=int, default=3163, help="--command: the window's side in tiles")
    ap.add_argument("--kernel-child", type=int, metavar="SIDE", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.kernel_child:
        kernel_child(args.kernel_child)
        return
    if args.command:
        command_rows(args.side, args.repeat)
        return
    sides = [316, 1000] if args.quick else [316, 1000, 3163]
    print(f"{'algorithm':<23}{'hash':<6}{'tiles':>12}{'time s':>9}{'cpu s':>8}{'Mtiles/s':>10}{'peak MiB':>10}"
          f"{'python us/tile':>16}{'ratio':>8}")
    for name, fast, slow in CASES:
        for hs in ("table", "long"):
            fast(8, 8, hs)  # compile
            base = 100
            t0 = time.perf_counter()
            ref = slow(base, base, hs)
            py_per_tile = (time.perf_counter() - t0) / base**2
            assert np.array_equal(ref, fast(base, base, hs)), name
            for side in sides:
                tracemalloc.start()
                t, cpu, _ = best(lambda: fast(side, side, hs), args.repeat)
                _, peak = tracemalloc.get_traced_memory()
                tracemalloc.stop()
                tiles = side * side
                print(f"{name:<23}{hs:<6}{tiles:>12,}{t:>9.3f}{cpu:>8.3f}{tiles / t / 1e6:>10.1f}{peak / 2**20:>10.1f}"
                      f"{py_per_tile * 1e6:>16.1f}{py_per_tile / (t / tiles):>8.0f}")
    print("baseline: per-tile Python transcription with the scalar hashes on 10,000 tiles (equal to the window); "
          "goals: direct corner 10^7 <= 0.1 s, scanline Wang 10^7 <= 0.5 s")


if __name__ == "__main__":
    main()
