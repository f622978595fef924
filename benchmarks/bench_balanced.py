"""Speed of the balanced-sequence windows (Kari's 14 tiles, Culik's 13) over square windows.

Times :func:`tilesolve.constructive.balanced.balanced_window` in process (compiled kernels
loaded first) on squares of side 10^2, 10^3, 10^4 at rows near the seed's row (``y0 =
-side/2``), and at side 10^3 far from it (``y0 = -10^5``, where ``x(y)`` is a rational of
about 160,000 bits, and ``y0 = 2^61``, beyond exact arithmetic): the route holds each row's
``x`` as 256-bit bounds, so the cost should not depend on ``y0``. At side 10^4 the window is
built on one thread and on every core this process may use. In the same run, two baselines:

* ``np.zeros``: allocating and filling a uint8 array of the same size, the floor any window
  costs;
* ``exact``: :func:`~tilesolve.constructive.balanced.balanced_window_exact`, the cell-by-cell
  exact reference (the closed form per row, every floor an integer division), on sides 10^2
  and 10^3; its tiles are compared with the window's.

Columns: wall and CPU seconds of the best of ``--repeat`` calls, millions of tiles a second,
tracemalloc's peak over one call (the uint8 output plus the scratch of the running jobs), and
each baseline's wall time over the window's.

Run from the repository root: ``python benchmarks/bench_balanced.py`` (all sides) or with
``--quick`` (sides 100 and 1000 only). The goal of issue 20: a 10^4 x 10^4 window in at most
1 s in process.
"""

from __future__ import annotations

import argparse

import numpy as np

from _measure import best, peak_mib  # noqa: E402 - benchmarks/ is on sys.path

SEED = 1


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    from tilesolve.constructive import balanced
    from tilesolve.constructive._balanced_kernels import KERNELS
    from tilesolve.constructive.balanced import NAMES, balanced_window, balanced_window_exact
    from tilesolve.model.window import Window

    KERNELS.compiled()  # numba's compile or cache load, outside the timings
    for name in NAMES:
        balanced_window(name, Window(0, 0, 64, 64), SEED)
    cores = balanced._cores()
    cases = [(100, None), (1000, None), (1000, -100_000), (1000, 2**61)] + ([] if args.quick else [(10000, None)])
    print(f"balanced_window, seed {SEED}, {cores} core(s); best of {args.repeat}")
    print(f"{'set':<15}{'side':>6}{'y0':>20}{'tiles':>13}{'threads':>8}{'wall s':>8}{'cpu s':>7}{'Mtiles/s':>9}"
          f"{'peak MiB':>9}{'zeros s':>8}{'ratio':>6}{'exact s':>9}{'ratio':>7}{'same':>5}")
    for name in NAMES:
        for side, y0 in cases:
            x0, y0 = -side // 2, -side // 2 if y0 is None else y0
            window = Window(x0, y0, side, side)
            tz, _, _ = best(lambda: np.zeros((side, side), np.uint8) + 1, args.repeat)
            for threads in sorted({1, cores}) if side >= 10000 else [cores]:
                balanced._cores = lambda: threads
                t, cpu, grid = best(lambda: balanced_window(name, window, SEED), args.repeat)
                peak = peak_mib(lambda: balanced_window(name, window, SEED))
                exact = ""
                if side <= 1000 and y0 == -side // 2:
                    te, _, ref = best(lambda: balanced_window_exact(name, window, SEED), 1)
                    exact = f"{te:>9.3f}{te / t:>7.0f}{'yes' if np.array_equal(ref, grid) else 'NO':>5}"
                print(f"{name:<15}{side:>6}{y0:>20}{side * side:>13,}{threads:>8}{t:>8.3f}{cpu:>7.3f}"
                      f"{side * side / t / 1e6:>9.0f}{peak:>9.1f}{tz:>8.3f}{tz / t:>6.2f}{exact}")
    print("ratios: baseline wall / window wall (zeros: the floor, below 1; exact: the cell-by-cell reference)")


if __name__ == "__main__":
    main()
