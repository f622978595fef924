"""Speed of the linear brick Wang algorithm (brick paper §4) on boards with holes.

Builds square boards with random rectangular holes (one hole of side 1..12 per 400
cells, about 10 % of the area), a random boundary colouring with 3 colours,
and times :func:`tilesolve.constructive.brick.solve_linear` (best of a few runs, numba
compile excluded; board building and verification are timed separately). Prints a table
and the ratio time(10^6 cells) / time(10^4 cells).

Usage::

    python benchmarks/bench_linear.py          # 100^2, 316^2, 1000^2
    python benchmarks/bench_linear.py --quick  # 100^2, 316^2

Goals (issue "Boards and brick Wang tilings"): 1000x1000 with holes in <= 2 s, and the
10^6 / 10^4 time ratio <= 150 (linear).
"""

from __future__ import annotations

import argparse
import time

import numpy as np


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    from tilesolve.constructive.brick import solve_linear
    from tilesolve.model.board import Board, BoardProblem, WangTileSet, random_boundary
    from tilesolve.verify.board import board_violations

    sizes = [100, 316] if args.quick else [100, 316, 1000]
    warm = Board.random_holes(8, 8, 0.1, seed=0)
    t = time.perf_counter()
    solve_linear(BoardProblem(warm, WangTileSet.brick(3), random_boundary(warm, 3, seed=0)), seed=0)
    print(f"first call (numba compile or cache load): {time.perf_counter() - t:.2f} s")
    print(f"{'board':>10} {'cells':>9} {'build s':>8} {'solve s':>8} {'Mcells/s':>9} {'verify s':>9} {'status':>7}")
    times = {}
    for s in sizes:
        t = time.perf_counter()
        b = Board.with_holes(s, s, s * s // 400, 12, seed=1)
        p = BoardProblem(b, WangTileSet.brick(3), random_boundary(b, 3, seed=1))
        build = time.perf_counter() - t
        best = np.inf
        sol = None
        for r in range(args.repeat):
            t = time.perf_counter()
            sol = solve_linear(p, seed=r)
            best = min(best, time.perf_counter() - t)
        t = time.perf_counter()
        ok = sol.status.value != "sat" or not board_violations(sol.tiling, p)
        ver = time.perf_counter() - t
        times[s * s] = best
        print(f"{s:>5}x{s:<4} {b.n_cells:>9} {build:>8.3f} {best:>8.3f} {b.n_cells / best / 1e6:>9.2f} {ver:>9.3f} "
              f"{sol.status.value + ('' if ok else '!'):>7}")
    if 10**6 in times and 10**4 in times:
        print(f"ratio time(10^6) / time(10^4) = {times[10**6] / times[10**4]:.1f}  (goal <= 150)")


if __name__ == "__main__":
    main()
