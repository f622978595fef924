"""Benchmark of the exact dappled-tiling counter (tilesolve.constructive.dappled_count).

Counts the ``{H_0^2, V_1^2}``-dappled tilings with ``T = {0, 1}`` (dappled paper, Remark 1.4;
OEIS A206994) on square grids, plus a few other problems, and prints a table of wall time,
number of digits, primes used and peak Python-heap memory (tracemalloc, which sees numpy
buffers). The one-time numba compilation is measured separately, in a subprocess with an empty
numba cache.

Run: ``python benchmarks/bench_count.py [--max N] [--repeat R]``.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
import tracemalloc

import numpy as np

_COMPILE_SNIPPET = """
import time
t0 = time.perf_counter()
from tilesolve.constructive.dappled_count import count_dappled
from tilesolve.model.dappled import DappledProblem
t1 = time.perf_counter()
count_dappled(DappledProblem.from_strings("3x3", ["H0=2", "V1=2"]))
t2 = time.perf_counter()
print(f"{t1 - t0:.3f} {t2 - t1:.3f}")
"""


def compile_time() -> tuple[float, float, float]:
    """(import s, first call with an empty numba cache s, first call with a warm cache s)."""
    with tempfile.TemporaryDirectory() as tmp:
        env = dict(os.environ, NUMBA_CACHE_DIR=tmp)
        cold = subprocess.run([sys.executable, "-c", _COMPILE_SNIPPET], env=env, capture_output=True, text=True)
        warm = subprocess.run([sys.executable, "-c", _COMPILE_SNIPPET], env=env, capture_output=True, text=True)
    imp, first = map(float, cold.stdout.split())
    _, cached = map(float, warm.stdout.split())
    return imp, first, cached


def measure(problem, repeat: int):
    from tilesolve.constructive.dappled_count import count_dappled

    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        n = count_dappled(problem)
        best = min(best, time.perf_counter() - t0)
    seen = []
    tracemalloc.start()
    count_dappled(problem, progress=lambda done, total: seen.append(total))
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    return n, best, peak, (seen[-1] if seen else 0)


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--max", type=int, default=14, help="largest square side (default 14)")
    ap.add_argument("--repeat", type=int, default=3, help="timing repeats, best kept (default 3)")
    args = ap.parse_args(argv)

    imp, cold, cached = compile_time()
    print(f"import {imp:.2f} s; first call: {cold:.2f} s with an empty numba cache (compile), "
          f"{cached:.2f} s with the on-disk cache")

    from tilesolve.constructive.dappled_count import count_dappled, plan_count
    from tilesolve.model.dappled import DappledProblem

    count_dappled(DappledProblem.from_strings("3x3", ["H0=2", "V1=2"]))  # load compiled code
    cases = [(f"{n}x{n}", ["H0=2", "V1=2"], {}) for n in range(4, args.max + 1, 2)]
    fixed = np.full((10, 10), -1, dtype=np.int8)
    fixed[::3, ::4] = 1
    cases += [
        ("10x10", ["H{0,1}=2", "V0=1", "V2=2"], {"n_tiles": 3}),
        ("10x10", ["H0=2", "V1=2"], {"fixed": fixed}),
        ("9x9", ["H0=3", "V1=3", "H1=2", "V0=2"], {}),
        ("8x8", ["H0=1", "V{1,2}=2"], {"n_tiles": 6}),
    ]
    print()
    print(f"{'grid':>6} {'conditions':<26} {'|T|':>3} {'extra':<6} {'s^W':>12} {'primes':>6} "
          f"{'time s':>8} {'digits':>6} {'peak MiB':>9}")
    for size, conds, kw in cases:
        p = DappledProblem.from_strings(size, conds, **kw)
        plan = plan_count(p)
        n, t, peak, steps = measure(p, args.repeat)
        primes = steps // plan.rows if plan.route == "transfer" else "-"  # progress total = primes * rows
        extra = "fixed" if "fixed" in kw else ""
        states = f"{plan.column_states}^{plan.cols}" if plan.route == "transfer" else plan.route
        print(f"{size:>6} {','.join(conds):<26} {p.n_tiles:>3} {extra:<6} {states:>12} {primes:>6} "
              f"{t:>8.3f} {len(str(n)):>6} {peak / 2**20:>9.1f}")


if __name__ == "__main__":
    main()
