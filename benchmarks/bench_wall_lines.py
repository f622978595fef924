"""Line-length histograms of PD, NPD and Kaji's finite wall (004 §5, Fig. 22), and their cost.

Part 1 reproduces Fig. 22: the share of vertical (and horizontal) lines of each length for the
procedural wall (PD, 004 §4.3), the repeatable wall on Kaji's cyclic dappling (NPD, App. A) and
the finite wall on Kaji's dappling (the ``wall`` route, dappled paper §4), at n = 4 and n = 10,
and measures 004's claim that Kaji's algorithm clamps lines at n: the count of lines of
length n against n - 1 (``n/(n-1)``; a row of fair independent choices gives about 1/2).
Every wall's longest line is checked against n (:func:`tilesolve.families.walls.line_statistics`).

Part 2 times the generators on the same walls (one period / window of W x H cells, solved and
verified through the family pipeline for NPD and the wall route; PD is a bare window), as
004's Table 2 compares NP/NPD with P/PD: time, peak memory and cells per second, with the ratio
to PD measured in the same run.

Usage::

    python benchmarks/bench_wall_lines.py            # 256x256 walls, 8 seeds each
    python benchmarks/bench_wall_lines.py --quick    # 128x128 walls, 2 seeds each
"""

from __future__ import annotations

import argparse

from tilesolve.constructive.wall_stats import clamp_numbers
from tilesolve.families.walls import LINE_METHODS, line_statistics
from _measure import best, peak_mib  # noqa: E402 - benchmarks/ is on sys.path


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    side, samples = (128, 2) if args.quick else (256, 8)
    print(f"Line lengths (004 Fig. 22): {side}x{side} walls, seeds 0..{samples - 1}, 3 colours; "
          "shares of lines by length; n/(n-1) = count at n / count at n-1")
    print(f"{'method':<11}{'n':>3} {'dir':<11}{'lines':>8}{'max':>5}{'at n':>8}{'at n-1':>8}{'n/(n-1)':>9}"
          "  shares 1..n")
    for n in (4, 10):
        for m in LINE_METHODS:
            h = line_statistics(m, n, width=side, height=side, samples=samples, seed=0)
            for d in ("vertical", "horizontal"):
                c = clamp_numbers(h.counts(d))
                print(f"{m:<11}{n:>3} {d:<11}{c['lines']:>8}{h.longest[d == 'vertical']:>5}{c['at_n']:>8.4f}"
                      f"{c['at_n_minus_1']:>8.4f}{c['ratio']:>9.3f}  "
                      + " ".join(f"{v:.3f}" for v in h.shares(d)))
    print()
    print(f"Cost of one {side}x{side} wall, generated (and verified, for npd and wall) and its lines counted "
          "(best of 3; PD is the baseline)")
    print(f"{'method':<11}{'n':>3}{'time s':>10}{'peak MiB':>10}{'Mcells/s':>10}{'x PD time':>11}")
    for n in (4, 10):
        base = None
        for m in LINE_METHODS:
            def one(m=m, n=n):
                return line_statistics(m, n, width=side, height=side, samples=1, seed=1)
            t, _, _ = best(one, 3)
            mem = peak_mib(one)
            base = t if base is None else base
            print(f"{m:<11}{n:>3}{t:>10.4f}{mem:>10.1f}{side * side / t / 1e6:>10.2f}{t / base:>11.1f}")


if __name__ == "__main__":
    main()
