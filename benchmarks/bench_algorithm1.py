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

First the whole command (issue 19): ``tilesolve dappled solve --size 100x100 --cond H0=2,V1=2
-o t.json`` beside a plain numpy script doing Algorithm 1 and writing the same JSON
(``bench_startup.PLAIN_SCRIPT``), both as fresh processes, alternated ``--runs`` times: medians
of wall and CPU time, peak RSS, and the ratio (goal: the command no slower than the script).
``--command-only`` skips the kernel table.
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


def whole_command(runs: int) -> None:
    """The command against the plain script (module doc), as fresh processes, alternated."""
    import shutil
    import statistics

    from _measure import command
    from bench_startup import PLAIN_SCRIPT

    exe = shutil.which("tilesolve") or os.path.join(os.path.dirname(sys.executable), "tilesolve")
    with tempfile.TemporaryDirectory() as tmp:
        env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}  # bytecode cached, as installed
        env["PYTHONPYCACHEPREFIX"] = os.path.join(tmp, "pycache")
        script = os.path.join(tmp, "alg1.py")
        with open(script, "w") as f:
            f.write(PLAIN_SCRIPT)
        rows = {
            "plain numpy Algorithm 1 script": [sys.executable, script, os.path.join(tmp, "p.json")],
            "tilesolve dappled solve": [exe, "dappled", "solve", "--size", "100x100", "--cond", "H0=2,V1=2", "-o",
                                        os.path.join(tmp, "t.json")],
        }
        got: dict[str, list] = {k: [] for k in rows}
        for argv in rows.values():
            command(argv, env)  # warm-up (fills the bytecode cache)
        for _ in range(runs):
            for label, argv in rows.items():
                wall, cpu, rss, rc, err = command(argv, env)
                assert rc == 0, (label, err)
                got[label].append((wall, cpu, rss))
    print(f"whole command, 100x100, L = {{H_0^2, V_1^2}}, -o JSON; {runs} alternated runs each (medians)")
    print(f"{'':32} {'wall s':>7} {'CPU s':>7} {'RSS MiB':>8}")
    med = {}
    for label, rs in got.items():
        med[label] = [statistics.median(r[i] for r in rs) for i in range(2)] + [max(r[2] for r in rs)]
        print(f"{label:32} {med[label][0]:7.3f} {med[label][1]:7.3f} {med[label][2]:8.1f}")
    cmd, plain = med["tilesolve dappled solve"], med["plain numpy Algorithm 1 script"]
    print(f"command / script: {cmd[1] / plain[1]:.2f}x CPU, {cmd[0] / plain[0]:.2f}x wall "
          "(goal: <= 1x, no slower than the script)")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="small sizes only")
    ap.add_argument("--use-cache", action="store_true", help="keep numba's on-disk cache (compile time then = load)")
    ap.add_argument("--runs", type=int, default=7, help="runs of the whole command and of the script (default 7)")
    ap.add_argument("--command-only", action="store_true", help="only the whole command against the script")
    args = ap.parse_args(argv)
    whole_command(args.runs)  # first, while this process is small (a child's peak RSS starts from it)
    if args.command_only:
        return 0
    print()
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
