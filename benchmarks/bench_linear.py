"""Speed of the linear brick Wang algorithm (brick paper §4) on boards with holes, with the
board build it needs.

Builds square boards with random rectangular holes (one hole of side 1..12 per 400
cells, about 10 % of the area), a random boundary colouring with 3 colours, and times
the board build (:meth:`Board.with_holes` + :class:`BoardProblem`), the previous board
build (a per-direction loop and the checked constructor, copied below as the baseline),
:func:`tilesolve.constructive.brick.solve_linear` (numba compile excluded) and the
independent verifier. The solve runs the numba-compiled kernels at every size
(``KERNELS.mode = "compiled"``), so the ratios compare compiled against compiled; the
automatic choice runs boards under the threshold of :mod:`tilesolve.constructive._jit` as
plain Python, shown in the column "plain s" for reference. Times are the best CPU time of
``--repeat`` runs (the machine is shared); the peak memory of the solve is tracemalloc's.
Prints the ratios time(10^6 cells) / time(10^4 cells) of the solve and of build + solve.

Usage::

    python benchmarks/bench_linear.py          # 100^2, 316^2, 1000^2
    python benchmarks/bench_linear.py --quick  # 100^2, 316^2

Goals (issue "Cost around the solver"): build + solve of 1000x1000 with holes <= 0.6 s on
one core, and the 10^6 / 10^4 ratio of build + solve <= 150 (linear).
"""

from __future__ import annotations

import argparse
import time
import tracemalloc

import numpy as np

import _measure


def old_grid_board(mask: np.ndarray):
    """The previous :meth:`Board.grid` for a planar mask: one pass per direction, then the
    checked constructor (symmetry of every join)."""
    from tilesolve.model.board import Board

    H, Wd = mask.shape
    index = np.full((H, Wd), -1, dtype=np.int64)
    rows, cols = np.nonzero(mask)
    n = rows.size
    index[rows, cols] = np.arange(n)
    nc = np.full((n, 4), -1, dtype=np.int64)
    nl = np.full((n, 4), -1, dtype=np.int64)
    for k, (dr, dc) in enumerate([(0, -1), (-1, 0), (0, 1), (1, 0)]):
        r2, c2 = rows + dr, cols + dc
        ok = (r2 >= 0) & (r2 < H) & (c2 >= 0) & (c2 < Wd)
        tgt = np.full(n, -1, dtype=np.int64)
        tgt[ok] = index[r2[ok], c2[ok]]
        nc[:, k] = tgt
        nl[:, k] = np.where(tgt >= 0, (k + 2) % 4, -1)
    wa, wl = np.nonzero(nc < 0)
    key = wa * 4 + (wl + 3) % 4  # boundary legs numbered by cell, then N, E, S, W
    nl[wa, wl] = np.argsort(np.argsort(key))
    return Board(np.stack([rows, cols], axis=1), nc, nl, kind="mask")


def holes_mask(s: int, seed: int) -> np.ndarray:
    """The mask :meth:`Board.with_holes` draws (same generator, same order)."""
    from tilesolve._random import rng_from_seed

    rng = rng_from_seed(seed)
    m = np.ones((s, s), bool)
    for _ in range(s * s // 400):
        h, w = rng.integers(1, 13, size=2)
        r, c = int(rng.integers(0, s)), int(rng.integers(0, s))
        m[r : r + h, c : c + w] = False
    return m


def best(fn, repeat: int):
    """Best CPU time of ``repeat`` runs, and the last output."""
    _, cpu, out = _measure.best(fn, repeat)
    return cpu, out


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    from tilesolve.constructive._brick_kernels import KERNELS
    from tilesolve.constructive.brick import solve_linear
    from tilesolve.model.board import Board, BoardProblem, WangTileSet, random_boundary
    from tilesolve.verify.board import board_violations

    sizes = [100, 316] if args.quick else [100, 316, 1000]
    warm = Board.random_holes(8, 8, 0.1, seed=0)
    t = time.perf_counter()
    KERNELS.mode = "compiled"
    solve_linear(BoardProblem(warm, WangTileSet.brick(3), random_boundary(warm, 3, seed=0)), seed=0)
    print(f"first call (numba compile or cache load): {time.perf_counter() - t:.2f} s")
    print(f"{'board':>10} {'cells':>9} {'old build':>9} {'build s':>8} {'speedup':>7} {'plain s':>8} {'solve s':>8} "
          f"{'b+s s':>7} {'Mcells/s':>8} {'solve MiB':>9} {'verify s':>8} {'status':>7}")
    times = {}
    for s in sizes:
        def build():
            b = Board.with_holes(s, s, s * s // 400, 12, seed=1)
            return BoardProblem(b, WangTileSet.brick(3), random_boundary(b, 3, seed=1))

        t_build, p = best(build, args.repeat)
        mask = holes_mask(s, 1)
        assert np.array_equal(p.board.mask_of(), mask)
        t_old, old = best(lambda: BoardProblem(old_grid_board(mask), WangTileSet.brick(3),
                                               random_boundary(p.board, 3, seed=1)), args.repeat)
        assert np.array_equal(old.board.nbr_cell, p.board.nbr_cell) and np.array_equal(old.board.nbr_leg,
                                                                                         p.board.nbr_leg)
        KERNELS.mode = "plain"
        t_plain = best(lambda: solve_linear(p, seed=0), 1)[0] if s * s <= KERNELS.threshold else np.nan
        KERNELS.mode = "compiled"
        t_solve, sol = best(lambda: solve_linear(p, seed=0), args.repeat)
        tracemalloc.start()
        solve_linear(p, seed=0)
        mib = tracemalloc.get_traced_memory()[1] / 2**20
        tracemalloc.stop()
        t_ver, v = best(lambda: board_violations(p, sol.tiling) if sol.status.value == "sat" else [], 1)
        times[s * s] = (t_solve, t_build + t_solve)
        n = p.board.n_cells
        print(f"{s:>5}x{s:<4} {n:>9} {t_old:>9.3f} {t_build:>8.3f} {t_old / t_build:>6.1f}x {t_plain:>8.3f} {t_solve:>8.3f} "
              f"{t_build + t_solve:>7.3f} {n / t_solve / 1e6:>8.2f} {mib:>9.1f} {t_ver:>8.3f} "
              f"{sol.status.value + ('' if not v else '!'):>7}")
    if 10**6 in times and 10**4 in times:
        big, small = times[10**6], times[10**4]
        print(f"ratio time(10^6) / time(10^4): solve {big[0] / small[0]:.1f}, build + solve {big[1] / small[1]:.1f}"
              "  (compiled at both sizes; goal <= 150)")


if __name__ == "__main__":
    main()
