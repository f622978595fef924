"""Benchmark of exact Wang-tiling counts by the transfer method (tilesolve.constructive.wang_count)
against SAT enumeration (the board family's 'enumerate' count) in the same run.

Counts the tilings of free rectangles and tori by built-in tile sets (Jeandel-Rao 11 tiles,
Jeandel-Vanier's 7 tiles that tile finite squares only, a periodic test set) and prints size, count, wall and CPU
time, peak Python-heap memory (tracemalloc, numpy buffers included) and the ratio to
enumeration where enumeration is run (it costs one SAT call per tiling, so only small counts).

Run: ``python benchmarks/bench_wang_count.py [--repeat R] [--max-enumerate N]``.
"""

from __future__ import annotations

import argparse

from _measure import best, peak_mib

from tilesolve.families import board as facade
from tilesolve.io.builtin_tilesets import load
from tilesolve.io.mask import read_board_spec
from tilesolve.model.board import BoardProblem

CASES = [("jeandel-rao", "rect:3x3"), ("jeandel-rao", "rect:4x4"), ("jeandel-rao", "rect:6x6"),
         ("jeandel-rao", "rect:8x8"), ("jeandel-rao", "torus:4x4"), ("jeandel-rao", "torus:6x6"),
         ("finite-jv7", "rect:4x4"), ("finite-jv7", "rect:10x10"), ("finite-jv7", "rect:14x14"),
         ("finite-jv7", "torus:5x5"), ("periodic-8-20", "torus:20x10")]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--max-enumerate", type=int, default=3000,
                    help="run the enumeration baseline only where the count is at most this")
    args = ap.parse_args()
    print(f"{'tile set':<14} {'board':<11} {'count':>10} {'transfer s':>10} {'cpu s':>7} {'MiB':>7} "
          f"{'enumerate s':>11} {'ratio':>7}")
    for name, spec in CASES:
        problem = BoardProblem(read_board_spec(spec), load(name)[0])
        t, cpu, res = best(lambda: facade.count(problem, method="transfer"), args.repeat)
        mib = peak_mib(lambda: facade.count(problem, method="transfer"))
        base, ratio = "-", "-"
        if res.value <= args.max_enumerate:
            tb, _, ref = best(lambda: facade.count(problem, method="enumerate"), 1)
            assert ref.value == res.value, (name, spec, ref.value, res.value)
            base, ratio = f"{tb:.3f}", f"{tb / t:.0f}x"
        print(f"{name:<14} {spec:<11} {res.value:>10} {t:>10.3f} {cpu:>7.3f} {mib:>7.1f} {base:>11} {ratio:>7}")


if __name__ == "__main__":
    main()
