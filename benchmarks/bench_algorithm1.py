"""Speed and memory of Algorithm 1 (dappled paper §2): numba kernel vs plain Python.

Prints one table: grid size, time, cells per second and peak memory (tracemalloc, numpy
buffers included) for ``L = {H_0^2, V_1^2}`` on uniform random tilings, then the
throughput ratio against a plain-Python Algorithm 1 written below as the paper boxes it.
The numba compile time (first call, with an empty cache) is reported on its own and
excluded from the timings, which are the best of a few warm runs.

Usage::

    python benchmarks/bench_algorithm1.py            # 256^2, 1024^2, 4096^2
    python benchmarks/bench_algorithm1.py --quick    # smaller sizes
    python benchmarks/bench_algorithm1.py --use-cache  # keep numba's on-disk cache

Goals: >= 25 million cells/s (a 4096^2 tiling in < 1 s) and >= 100x the plain Python.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
import tracemalloc


def python_algorithm1(f, p, q):
    """Algorithm 1 written plainly (lists, ``Violate`` scanning back), the baseline.

    ``f`` is a list of rows; ``p[t]``, ``q[t]`` are uniform limits (0 = unlimited).
    """
    g = [row[:] for row in f]
    rows, cols = len(g), len(g[0])

    def violate(r, c):
        t = g[r][c]
        pt, qt = p[t], q[t]
        if pt and c >= pt and all(g[r][c - k] == t for k in range(1, pt + 1)):
            return True
        return bool(qt and r >= qt and all(g[r - k][c] == t for k in range(1, qt + 1)))

    for w in range(rows + cols - 1):
        for r in range(max(0, w - cols + 1), min(w, rows - 1) + 1):
            c = w - r
            if violate(r, c):
                g[r][c] = 1 - g[r][c]
                if violate(r, c):
                    g[r][c] = g[r - 1][c - 1]
                    g[r][c - 1] = 1 - g[r][c]
                    g[r - 1][c] = 1 - g[r][c]
    return g


def _timed(fn, repeat):
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def _peak(fn):
    tracemalloc.start()
    tracemalloc.reset_peak()
    fn()
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return peak


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="small sizes only")
    ap.add_argument("--use-cache", action="store_true", help="keep numba's on-disk cache (compile time then = load)")
    args = ap.parse_args(argv)
    if not args.use_cache:  # measure a real compile: point numba at an empty cache
        os.environ["NUMBA_CACHE_DIR"] = tempfile.mkdtemp(prefix="tilesolve-bench-numba-")

    import numpy as np

    from tilesolve.constructive._dappled_kernels import KERNELS
    from tilesolve.constructive.dappled import algorithm1
    from tilesolve.model import DappledProblem
    from tilesolve.verify import is_dappled

    KERNELS.mode = "compiled"  # the numba kernel at every size (small grids would run interpreted)

    p, q = [2, 0], [0, 2]  # {H_0^2, V_1^2}
    rng = np.random.default_rng(0)

    t0 = time.perf_counter()
    algorithm1(rng.integers(0, 2, (8, 8), dtype=np.int8), p, q)
    compile_s = time.perf_counter() - t0

    sizes = [128, 256, 512] if args.quick else [256, 1024, 4096]
    py_sizes = [64, 128] if args.quick else [64, 128, 256]
    rows = []
    numba_rate = {}
    for n in sizes:
        f = rng.integers(0, 2, (n, n), dtype=np.int8)
        sec, g = _timed(lambda: algorithm1(f, p, q), 3 if n <= 1024 else 2)
        peak = _peak(lambda: algorithm1(f, p, q))
        if n <= 1024:
            assert is_dappled(DappledProblem.from_strings(f"{n}x{n}", ["H0=2", "V1=2"]), g)
        numba_rate[n] = n * n / sec
        rows.append(("numba", f"{n}x{n}", sec, n * n / sec, peak))
    py_rate = {}
    for n in py_sizes:
        f = rng.integers(0, 2, (n, n), dtype=np.int8)
        fl = f.tolist()
        sec, g = _timed(lambda: python_algorithm1(fl, p, q), 1)
        assert np.array_equal(np.array(g, dtype=np.int8), algorithm1(f, p, q)), "baseline and kernel disagree"
        peak = _peak(lambda: python_algorithm1(fl, p, q))
        py_rate[n] = n * n / sec
        rows.append(("python", f"{n}x{n}", sec, n * n / sec, peak))

    print("Algorithm 1, L = {H_0^2, V_1^2}, uniform random 0/1 input, int8 tilings")
    print(f"numba compile (first call, {'cache as found' if args.use_cache else 'empty cache'}): {compile_s:.2f} s")
    print()
    print(f"{'impl':<7} {'size':>10} {'time':>10} {'cells/s':>14} {'peak mem':>10}")
    for impl, size, sec, rate, peak in rows:
        print(f"{impl:<7} {size:>10} {sec:>9.4f}s {rate:>14,.0f} {peak / 2**20:>8.2f}MiB")
    print()
    common = sorted(set(numba_rate) & set(py_rate))
    if common:
        n = common[-1]
        ratio = numba_rate[n] / py_rate[n]
    else:
        n = max(py_rate)
        ratio = max(numba_rate.values()) / py_rate[n]
    print(f"throughput ratio numba / python at {n}x{n}: {ratio:,.0f}x (goal >= 100x)")
    big = max(numba_rate)
    print(f"numba at {big}x{big}: {numba_rate[big] / 1e6:.1f} M cells/s (goal >= 25 M cells/s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
