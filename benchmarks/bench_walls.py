"""Speed of the procedural wall (walls paper 004 §4.2-4.3) over large windows.

Times :func:`tilesolve.constructive.walls.wall_window` (compiled, one core; numba compile
excluded) on square windows of 10^5 .. 10^7 cells, with procedural dappling n = 2 (PD, the
paper's Table 2 row) and without (P), and, in the same run, a straight per-cell Python
transcription of the same algorithm (``_ScalarWall.tile``, one cell at a time, the form a
shader follows) on 10^4 cells. Both produce the same tiles (checked on the baseline cells).
Prints time, throughput, peak memory and the per-cell ratio baseline / compiled.

Memory: "peak MiB" is tracemalloc's peak during the call (the output, 4 bytes a cell, and the
kernel's scratch arrays); "RSS MiB" is the process's peak resident size so far.

Usage::

    python benchmarks/bench_walls.py          # 10^5, 10^6, 10^7 cells
    python benchmarks/bench_walls.py --quick  # 10^5, 10^6 cells

Goals (issue 10): PD n = 2 over 10^7 cells <= 0.2 s on one core, and >= 100x the per-cell
Python transcription. For reference, the paper's Table 2: 3726 ms for 10^7 PD look-ups (CPU).
"""

from __future__ import annotations

import argparse
import resource
import time
import tracemalloc

import numpy as np

from tilesolve.constructive.walls import _ScalarWall, dappling_period, wall_window
from _measure import best  # noqa: E402 - benchmarks/ is on sys.path

COLORS, SEED = 3, 7


def peak_rss_mib() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def python_baseline(side: int, n):
    """Per-cell Python transcription over a side x side window at the origin; (seconds, tiles)."""
    scalar = _ScalarWall(COLORS, dappling_period(n), n is not None and n % 2 == 1, SEED)
    t = time.perf_counter()
    tiles = [[scalar.tile(i, j) for i in range(side)] for j in range(side - 1, -1, -1)]
    return time.perf_counter() - t, np.array(tiles, dtype=np.int8)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
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
