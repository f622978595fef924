"""Benchmark of the exact dappled-tiling counter (tilesolve.constructive.dappled_count).

Two tables.

*Whole commands* (issue 19), each a fresh process measured beside its anchor in the same run
(wall, CPU = user + sys of the process, peak RSS):

* ``tilesolve dappled count --size 16x16 --cond H0=2,V1=2`` (goal <= 5 s CPU) beside the same
  count in this process, and beside the full sweep down the grid (``_MEET_IN_MIDDLE`` off: the
  previous algorithm, which also gives the count to cross-check);
* ``tilesolve dappled count --size 18x18 --cond H0=2,V1=2``: refused at once with the estimate
  (exit 2, one line; goal: refused or counted);
* the cyclic example of ``tilesolve dappled count --help`` (goal <= 3 s), beside its count in
  this process.

*In process*: the ``{H_0^2, V_1^2}``-dappled tilings with ``T = {0, 1}`` (dappled paper,
Remark 1.4; OEIS A206994) on square grids, plus a few other problems: wall time, number of
digits, primes used and peak Python-heap memory (tracemalloc, which sees numpy buffers). The
one-time numba compilation is measured separately, in a subprocess with an empty numba cache.

Run: ``python benchmarks/bench_count.py [--max N] [--repeat R] [--side S] [--no-commands]``.
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
from _measure import command

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


#: One count in a fresh process (argv: size, cyclic 0/1, meet in the middle 0/1): the CPU
#: seconds of the call alone (compiled code loaded first) and the count.
_ANCHOR = """
import sys, time
import tilesolve.constructive.dappled_count as dc
from tilesolve.model.dappled import DappledProblem
dc.count_dappled(DappledProblem.from_strings("3x3", ["H0=2", "V1=2"]))
dc._MEET_IN_MIDDLE = sys.argv[3] == "1"
p = DappledProblem.from_strings(sys.argv[1], ["H0=2", "V1=2"], cyclic=sys.argv[2] == "1")
c = time.process_time()
n = dc.count_dappled(p)
print(time.process_time() - c, n)
"""


def _anchor(size: str, cyclic: bool = False, meet: bool = True) -> tuple[float, int]:
    """(CPU s, count) of :data:`_ANCHOR` (a fresh process, so this one stays small: a child's
    peak RSS as ``wait4`` reports it starts from its parent's)."""
    out = subprocess.run([sys.executable, "-c", _ANCHOR, size, str(int(cyclic)), str(int(meet))],
                         capture_output=True, text=True, check=True).stdout.split()
    return float(out[0]), int(out[1])


def commands(side: int) -> None:
    """The whole-command table (module doc); every process is a fresh one."""
    import shutil

    exe = shutil.which("tilesolve") or os.path.join(os.path.dirname(sys.executable), "tilesolve")
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}  # cache bytecode as installed
    command([exe, "dappled", "count", "--size", "3x3", "--cond", "H0=2,V1=2"], env)  # warm the caches
    help_text = subprocess.run([exe, "dappled", "count", "--help"], capture_output=True, text=True, env=env).stdout
    example = next(line.split("#")[0].split() for line in help_text.splitlines() if "--cyclic" in line)
    size = example[example.index("--size") + 1]

    rows = []
    wall, cpu, rss, rc, _ = command([exe, "dappled", "count", "--size", f"{side}x{side}", "--cond", "H0=2,V1=2"], env)
    k_cpu, value = _anchor(f"{side}x{side}")
    f_cpu, full = _anchor(f"{side}x{side}", meet=False)
    assert value == full, "the count met in the middle differs from the full sweep"
    rows.append((f"count {side}x{side}", wall, cpu, rss, rc, f"count_dappled {k_cpu:.2f} s (command {cpu / k_cpu:.2f}x "
                 f"it); the full sweep {f_cpu:.2f} s ({f_cpu / k_cpu:.2f}x the meeting in the middle)"))
    wall, cpu, rss, rc, err = command([exe, "dappled", "count", "--size", "18x18", "--cond", "H0=2,V1=2"], env)
    rows.append(("count 18x18", wall, cpu, rss, rc, err[:150] + ("..." if len(err) > 150 else "")))
    wall, cpu, rss, rc, _ = command(example, env)
    k_cpu, _ = _anchor(size, cyclic=True)
    rows.append((f"help: count {size} --cyclic", wall, cpu, rss, rc,
                 f"count_dappled {k_cpu:.2f} s (command {cpu / k_cpu:.2f}x it)"))

    print("whole commands (fresh processes; CPU = user + sys), {H0^2, V1^2}")
    print(f"{'command':<26} {'wall s':>7} {'CPU s':>7} {'RSS MiB':>8} {'exit':>4}  anchor in a process of its own (CPU)")
    for label, wall, cpu, rss, rc, anchor in rows:
        print(f"{label:<26} {wall:7.2f} {cpu:7.2f} {rss:8.0f} {rc:4d}  {anchor}")
    print("goals: count 16x16 <= 5 s CPU; 18x18 refused with the estimate (exit 2) or counted; "
          "the cyclic help example <= 3 s")
    print()


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--max", type=int, default=14, help="largest square side (default 14)")
    ap.add_argument("--repeat", type=int, default=3, help="timing repeats, best kept (default 3)")
    ap.add_argument("--side", type=int, default=16, help="grid side of the whole count command (default 16)")
    ap.add_argument("--no-commands", action="store_true", help="skip the whole-command table")
    args = ap.parse_args(argv)
    if not args.no_commands:
        commands(args.side)

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
        sweeps = plan.rows - plan.rows // 2 + 1 if plan.halves else plan.rows  # per prime
        primes = steps // sweeps if plan.route == "transfer" else "-"  # progress total = primes * sweeps
        extra = "fixed" if "fixed" in kw else ""
        states = f"{plan.column_states}^{plan.cols}" if plan.route == "transfer" else plan.route
        print(f"{size:>6} {','.join(conds):<26} {p.n_tiles:>3} {extra:<6} {states:>12} {primes:>6} "
              f"{t:>8.3f} {len(str(n)):>6} {peak / 2**20:>9.1f}")


if __name__ == "__main__":
    main()
