"""Cost of writing and reading solution files, against the solve, old format vs new.

Boards: a linear-algorithm tiling (brick paper §4) of the ``s x s`` rectangle with a
random boundary, written and read back as ``tilesolve/board-solution`` version 3 with plain
lists (edge list and tiles as JSON lists, version 1's layout: the baseline) and with encoded
arrays (grid + mask + base64 arrays, version 2's layout).
Dappled: an Algorithm 1 tiling (dappled paper §2) for ``{H_0^2, V_1^2}``, written as
``tilesolve/dappled-solution`` version 1 (rows of digits) and version 2 (bit-packed).

Each row: write and read times (best of ``--repeat``), file size, tracemalloc peak of a
write and of a read, throughput of the new writer, and the old/new time ratio. Goals
(issue "Cost around the solver"): writing and reading cost at most the solve; a 10^6-cell
board solution <= 15 MB.

Usage::

    python benchmarks/bench_io.py            # boards 316^2, 1000^2; dappled 1024^2, 4096^2
    python benchmarks/bench_io.py --quick    # boards 316^2; dappled 1024^2
    python benchmarks/bench_io.py --big      # adds the 2000^2 board (version 1 takes minutes)
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time

import numpy as np
from _measure import peak_mib  # noqa: E402 - benchmarks/ is on sys.path


def timed(fn, repeat: int) -> float:
    t_best = np.inf
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        t_best = min(t_best, time.perf_counter() - t)
    return t_best


def measure(label, size, cells, t_solve, write, read, path, repeat, results):
    """Time, size and memory of one format; prints a row and returns the times."""
    tw = timed(write, repeat)
    mb = os.path.getsize(path) / 1e6
    tr = timed(read, repeat)
    mw, mr = peak_mib(write), peak_mib(read)
    results.append((label, size, cells, t_solve, tw, tr, mb, mw, mr))
    return tw, tr


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--big", action="store_true")
    ap.add_argument("--repeat", type=int, default=2)
    args = ap.parse_args()
    from tilesolve.constructive.brick import solve_linear
    from tilesolve.constructive.dappled import make_dappled
    from tilesolve.io.board_json import read_board_solution, write_board_solution
    from tilesolve.io.dappled_json import read_solution, write_solution
    from tilesolve.model.board import Board, BoardProblem, WangTileSet, random_boundary
    from tilesolve.model.dappled import DappledProblem
    from tilesolve.model.solution import Solution, Status

    board_sizes = [316] if args.quick else [316, 1000] + ([2000] if args.big else [])
    dappled_sizes = [1024] if args.quick else [1024, 4096]
    warm = Board.rect(4, 4)
    solve_linear(BoardProblem(warm, WangTileSet.brick(3)), seed=0)  # numba compile or cache load
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "s.json")
        for s in board_sizes:
            b = Board.rect(s, s)
            p = BoardProblem(b, WangTileSet.brick(3), random_boundary(b, 3, seed=1))
            t = time.perf_counter()
            sol = solve_linear(p, seed=1)
            t_solve = time.perf_counter() - t
            for version, compact in (("lists (old)", False), ("encoded", True)):
                measure(f"board {version}", f"{s}x{s}", b.n_cells, t_solve,
                        lambda: write_board_solution(path, p, sol, compact=compact),
                        lambda: read_board_solution(path), path, 1 if not compact else args.repeat, rows)
        for s in dappled_sizes:
            p = DappledProblem.from_strings(f"{s}x{s}", ["H0=2", "V1=2"])
            t = time.perf_counter()
            tiling = make_dappled(p, seed=1)
            t_solve = time.perf_counter() - t
            sol = Solution(Status.SAT, tiling, method="constructive", seed=1, time_s=t_solve)
            for version, compact in (("v1 (old)", False), ("v2", True)):
                measure(f"dappled {version}", f"{s}x{s}", s * s, t_solve,
                        lambda: write_solution(path, p, sol, compact=compact),
                        lambda: read_solution(path), path, 1 if not compact else args.repeat, rows)
    print(f"{'file':<16} {'size':>10} {'solve s':>8} {'write s':>8} {'read s':>8} {'MB':>8} "
          f"{'wr MiB':>8} {'rd MiB':>8} {'w Mc/s':>8} {'(w+r)/solve':>11} {'old/new w':>9} {'old/new r':>9}")
    for i, (label, size, cells, t_solve, tw, tr, mb, mw, mr) in enumerate(rows):
        ratio = ""
        if label.endswith("v2"):
            old = rows[i - 1]
            ratio = f"{old[4] / tw:>8.0f}x {old[5] / tr:>8.0f}x"
        print(f"{label:<16} {size:>10} {t_solve:>8.3f} {tw:>8.3f} {tr:>8.3f} {mb:>8.2f} {mw:>8.1f} {mr:>8.1f} "
              f"{cells / tw / 1e6:>8.1f} {(tw + tr) / t_solve:>11.2f} {ratio}")


if __name__ == "__main__":
    main()
