"""Speed of the procedural wall (walls paper 004 §4.2-4.3) over large windows.

Times :func:`tilesolve.constructive.walls.wall_window` (compiled, one core; numba compile
excluded) on square windows of 10^5 .. 10^7 cells, with procedural dappling n = 2 (PD, the
paper's Table 2 row) and without (P), and, in the same run, a straight per-cell Python
transcription of the same algorithm (``_ScalarWall.tile``, one cell at a time, the form a
shader follows) on 10^4 cells. Both produce the same tiles (checked on the baseline cells).
Prints time, throughput, peak memory and the per-cell ratio baseline / compiled.

Memory: "peak MiB" is tracemalloc's peak during the call (the output, 4 bytes a cell, and the
kernel's scratch arrays); "RSS MiB" is the process's peak resident size so far.

``--command`` measures the whole command instead (issue 19): ``tilesolve wall --region
0,0,SxS --max-line 2 -o w.json`` (the wall generated, checked by the board verifier, written
as a board-solution file) beside its anchor, ``wall_window`` of the same window called in a
fresh Python process, each run as a child process (its own CPU time, user + sys, and peak
RSS from ``os.wait4``; the run of least CPU of ``--repeat``, after one warm-up run of each),
and prints the ratios command / anchor.

Usage::

    python benchmarks/bench_walls.py            # 10^5, 10^6, 10^7 cells
    python benchmarks/bench_walls.py --quick    # 10^5, 10^6 cells
    python benchmarks/bench_walls.py --command  # wall -o at 3163^2 (10^7 cells) beside wall_window

Goals (issue 10): PD n = 2 over 10^7 cells <= 0.2 s on one core, and >= 100x the per-cell
Python transcription. For reference, the paper's Table 2: 3726 ms for 10^7 PD look-ups (CPU).
Issue 19: ``wall -o`` <= 2x the CPU time and <= 2x the peak memory of ``wall_window`` in a
process, the file streamed.
"""

from __future__ import annotations

import argparse
import os
import resource
import sys
import tempfile
import time
import tracemalloc

import numpy as np

from _measure import best, best_child  # noqa: E402 - benchmarks/ is on sys.path

COLORS, SEED = 3, 7


def peak_rss_mib() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def python_baseline(side: int, n):
    """Per-cell Python transcription over a side x side window at the origin; (seconds, tiles)."""
    from tilesolve.constructive.walls import _ScalarWall, dappling_period

    scalar = _ScalarWall(COLORS, dappling_period(n), n is not None and n % 2 == 1, SEED)
    t = time.perf_counter()
    tiles = [[scalar.tile(i, j) for i in range(side)] for j in range(side - 1, -1, -1)]
    return time.perf_counter() - t, np.array(tiles, dtype=np.int8)


def command_rows(side: int, repeat: int) -> None:
    """``tilesolve wall ... -o w.json`` beside ``wall_window`` in a process (module docstring)."""
    exe = os.path.join(os.path.dirname(sys.executable), "tilesolve")
    anchor = [sys.executable, "-c", "from tilesolve.constructive.walls import wall_window; "
              f"wall_window(0, 0, {side}, {side}, colors={COLORS}, max_line=2, seed={SEED})"]
    command = [exe, "wall", "--region", f"0,0,{side}x{side}", "--max-line", "2", "--seed", str(SEED), "-o", "w.json"]
    cells = side * side
    print(f"wall -o beside wall_window in a process, {side}x{side} = {cells:,} cells, n = 2; best CPU of {repeat}")
    print(f"{'run':<34}{'wall s':>8}{'cpu s':>8}{'sys s':>8}{'RSS MiB':>9}{'Mcells/cpu s':>13}{'file MiB':>9}"
          f"{'cpu ratio':>10}{'RSS ratio':>10}")
    with tempfile.TemporaryDirectory() as d:
        for argv in (anchor, command):
            best_child(argv, 1, cwd=d)  # warm-up: bytecode and numba caches
        base = best_child(anchor, repeat, cwd=d)
        run = best_child(command, repeat, cwd=d)
        size = os.path.getsize(os.path.join(d, "w.json")) / 2**20
    for name, r, mib in (("wall_window in a process", base, ""), ("tilesolve wall ... -o w.json", run, size)):
        ratio = f"{r.cpu / base.cpu:>10.2f}{r.rss_mib / base.rss_mib:>10.2f}"
        print(f"{name:<34}{r.wall:>8.2f}{r.cpu:>8.2f}{r.sys:>8.2f}{r.rss_mib:>9.0f}{cells / r.cpu / 1e6:>13.1f}"
              f"{mib if mib == '' else f'{mib:.1f}':>9}{ratio}")
    print("ratios: the command over the anchor (CPU = user + sys of the process; peak RSS); "
          "goal (issue 19): both <= 2")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--command", action="store_true", help="the whole wall -o command beside wall_window")
    ap.add_argument("--side", type=int, default=3163, help="--command: the window's side in cells")
    args = ap.parse_args()
    if args.command:  # before the kernels are imported: a child's peak RSS starts from this process's
        command_rows(args.side, args.repeat)
        return
    from tilesolve.constructive.walls import wall_window

    sides = [316, 1000] if args.quick else [316, 1000, 3163]
    wall_window(0, 0, 8, 8, colors=COLORS, max_line=2, seed=SEED)  # compile
    wall_window(0, 0, 8, 8, colors=COLORS, max_line=None, seed=SEED)

    print(f"{'method':<8}{'cells':>12}{'time s':>10}{'cpu s':>8}{'Mcells/s':>10}{'peak MiB':>9}{'RSS MiB':>9}"
          f"{'us/cell':>10}{'python us/cell':>16}{'ratio':>9}")
    for label, n in (("PD n=2", 2), ("P", None)):
        base_side = 100
        t_py, tiles_py = python_baseline(base_side, n)
        assert np.array_equal(tiles_py, wall_window(0, 0, base_side, base_side, colors=COLORS, max_line=n, seed=SEED))
        py_per_cell = t_py / base_side**2
        for side in sides:
            cells = side * side
            tracemalloc.start()
            t, cpu, out = best(lambda: wall_window(-side // 2, 12345, side, side, colors=COLORS, max_line=n, seed=SEED),
                          args.repeat)
            _, peak = tracemalloc.get_traced_memory()
            tracemalloc.stop()
            per_cell = t / cells
            print(f"{label:<8}{cells:>12,}{t:>10.3f}{cpu:>8.3f}{cells / t / 1e6:>10.1f}{peak / 2**20:>9.1f}"
                  f"{peak_rss_mib():>9.0f}"
                  f"{per_cell * 1e6:>10.4f}{py_per_cell * 1e6:>16.1f}{py_per_cell / per_cell:>9.0f}")
            del out
    print(f"baseline: per-cell Python transcription on {100 * 100:,} cells (same tiles as the compiled window); "
          "goal: PD n=2, 10^7 cells <= 0.2 s and ratio >= 100")


if __name__ == "__main__":
    main()
