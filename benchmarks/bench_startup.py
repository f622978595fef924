"""Start-up cost of whole commands, against plain-Python baselines measured in the same run.

Every row is one command run as a fresh process ``--repeat`` times (after one warm-up run,
which also fills a private bytecode cache: see ``ENV``): the median wall time,
the median CPU time of the process (user + sys, from ``os.wait4``; on a loaded machine this
is the steadier figure), its peak resident memory, and the ratio of the median CPU time to
the row's baseline. Goals (issue 9, "Start-up"):

* ``tilesolve --version`` <= 3x ``python -c pass``;
* ``tilesolve dappled solve --size 100x100 --cond H0=2,V1=2 -o out.json`` no slower than a
  plain script doing the same job: Algorithm 1 of the dappled paper (§2) for
  ``L = {H_0^2, V_1^2}`` on a random 100x100 tiling, in pure Python with numpy for the
  random start, written as JSON (the script is written to a temporary directory);
* compiled kernels loaded only when the problem is large enough: the second table runs the
  dappled kernels (Algorithm 1, the trivial algorithm) and the linear brick algorithm
  interpreted and compiled (numba, warm cache) in fresh processes around each module's
  ``THRESHOLD`` and prints the CPU time of each.

``tilesolve brick solve --board rect:100x100`` and ``tilesolve --help`` (which loads every family
and command) are listed against ``python -c "import numpy"``.

``--first-run`` measures instead the first run after install (issue 19: the README tour's
first run within 2x of a warm run): ``tilesolve demo`` (the quick start) and every command of
the README's tour, in order in a fresh folder holding a copy of ``examples/``, once with an
empty numba cache (a private ``NUMBA_CACHE_DIR``: the kernels compile) and once more with the
cache that run filled, bytecode compiled beforehand in both (as ``pip install`` does). It
prints the commands whose CPU time differs by more than half a second, and the totals. The
tour takes a few minutes a pass.

Usage::

    python benchmarks/bench_startup.py               # 9 runs a command
    python benchmarks/bench_startup.py --repeat 5 --no-crossover
    python benchmarks/bench_startup.py --first-run
"""

from __future__ import annotations

import argparse
import os
import re
import shlex
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

#: Algorithm 1 (dappled paper §2) for L = {H_0^2, V_1^2}, as a short stand-alone script.
PLAIN_SCRIPT = '''\
import json, sys
import numpy as np

R = C = 100
P, Q = {0: 2}, {1: 2}  # H_0^2: at most 2 zeros in a row; V_1^2: at most 2 ones in a column
g = np.random.default_rng().integers(0, 2, size=(R, C)).tolist()


def violate(r, c):
    t = g[r][c]
    p, q = P.get(t), Q.get(t)
    if p and c >= p and all(g[r][c - k] == t for k in range(1, p + 1)):
        return True
    return bool(q and r >= q and all(g[r - k][c] == t for k in range(1, q + 1)))


for d in range(R + C - 1):  # cells by weight i + j
    for r in range(max(0, d - C + 1), min(d, R - 1) + 1):
        c = d - r
        if violate(r, c):
            g[r][c] = 1 - g[r][c]  # step (I)
            if violate(r, c):  # step (II)
                t = g[r - 1][c - 1]
                g[r][c], g[r][c - 1], g[r - 1][c] = t, 1 - t, 1 - t
with open(sys.argv[1], "w") as f:
    json.dump({"rows": R, "cols": C, "conditions": ["H0=2", "V1=2"], "tiling": g}, f)
'''

#: Runs one dappled route on an n x n grid, interpreted or compiled (argv: mode, n, n_tiles):
#: Algorithm 1 for |T| = 2, the trivial algorithm for |T| = 3.
CROSSOVER_SCRIPT = '''\
import sys
from tilesolve.constructive import _dappled_kernels as K
from tilesolve.constructive.dappled import make_dappled
from tilesolve.model import DappledProblem

K.KERNELS.mode = sys.argv[1]
n, n_tiles = int(sys.argv[2]), int(sys.argv[3])
make_dappled(DappledProblem.from_strings(f"{n}x{n}", ["H0=2", "V1=2"], n_tiles=n_tiles), seed=1)
'''


#: The linear brick algorithm (brick paper §4) on an n x n rectangle, interpreted or compiled.
BRICK_SCRIPT = '''\
import sys
from tilesolve.constructive import _brick_kernels as K
from tilesolve.constructive.brick import solve_linear
from tilesolve.model.board import BoardProblem, WangTileSet, parse_board_spec, random_boundary

K.KERNELS.mode = sys.argv[1]
board = parse_board_spec(f"rect:{sys.argv[2]}x{sys.argv[2]}")
solve_linear(BoardProblem(board, WangTileSet.brick(3), random_boundary(board, 3, seed=1)), seed=1)
'''


#: Environment of the measured commands: bytecode is cached, as in any installed package, but
#: in a private directory (set in main) so that the working tree is left alone; a shell with
#: PYTHONDONTWRITEBYTECODE would otherwise recompile every tilesolve module on every run.
ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}

#: The repository (README.md, examples/).
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run_once(argv: list[str]) -> tuple[float, float, float]:
    """Wall seconds, CPU seconds (user + sys) and peak RSS (MiB) of one run of ``argv``."""
    t = time.perf_counter()
    proc = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=ENV)
    _, status, ru = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - t
    proc.returncode = os.waitstatus_to_exitcode(status)
    err = proc.stderr.read().decode(errors="replace")
    proc.stderr.close()
    if proc.returncode != 0:
        raise SystemExit(f"{' '.join(argv)} exited {proc.returncode}: {err.strip()}")
    return wall, ru.ru_utime + ru.ru_stime, ru.ru_maxrss / 1024


def measure(argv: list[str], repeat: int) -> tuple[float, float, float]:
    """Medians of wall and CPU time, and the largest peak RSS, over ``repeat`` runs (one warm-up)."""
    run_once(argv)
    runs = [run_once(argv) for _ in range(repeat)]
    return (statistics.median(r[0] for r in runs), statistics.median(r[1] for r in runs), max(r[2] for r in runs))


def tour() -> list[list[str]]:
    """The quick start's ``tilesolve demo``, then the README's tour commands (as tests/test_readme.py reads them)."""
    readme = open(os.path.join(ROOT, "README.md"), encoding="utf-8").read()
    lines = [line for kind, body in re.findall(r"```(bash|python)\n(.*?)```", readme, re.S) if kind == "bash"
             for line in body.splitlines() if line.startswith("tilesolve ") and line.split()[1] != "demo"]
    return [["demo"]] + [shlex.split(line.partition("#")[0])[1:] for line in lines]


def tour_pass(tilesolve: str, commands: list[list[str]], folder: str) -> list[tuple[float, float]]:
    """Wall and CPU seconds of each command, run in order in a fresh ``folder`` with ``examples/``."""
    shutil.copytree(os.path.join(ROOT, "examples"), os.path.join(folder, "examples"))
    out = []
    for argv in commands:
        t = time.perf_counter()
        proc = subprocess.Popen([tilesolve, *argv], cwd=folder, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                env=ENV)
        _, status, ru = os.wait4(proc.pid, 0)
        if os.waitstatus_to_exitcode(status) not in (0, 1):  # the tour has unsat examples (exit 1)
            raise SystemExit(f"tilesolve {' '.join(argv)} exited {os.waitstatus_to_exitcode(status)}")
        out.append((time.perf_counter() - t, ru.ru_utime + ru.ru_stime))
    return out


def first_run(tilesolve: str, tmp: str) -> None:
    """The README tour with an empty numba cache, then again with the cache it filled."""
    import tilesolve as package

    ENV["NUMBA_CACHE_DIR"] = os.path.join(tmp, "numba")
    subprocess.run([sys.executable, "-m", "compileall", "-q", os.path.dirname(package.__file__)], env=ENV, check=True)
    commands = tour()
    cold = tour_pass(tilesolve, commands, os.path.join(tmp, "cold"))
    warm = tour_pass(tilesolve, commands, os.path.join(tmp, "warm"))
    print(f"README tour, {len(commands)} commands: first run (empty numba cache) vs warm (cache filled by the first)")
    print(f"{'command':60s} {'cold wall':>9s} {'cold CPU':>9s} {'warm wall':>9s} {'warm CPU':>9s} {'CPU ratio':>9s}")
    for argv, (cw, cc), (ww, wc) in zip(commands, cold, warm):
        if abs(cc - wc) > 0.5:
            print(f"{' '.join(argv)[:60]:60s} {cw:9.2f} {cc:9.2f} {ww:9.2f} {wc:9.2f} {cc / wc:8.2f}x")
    total = [sum(r[i] for r in runs) for runs in (cold, warm) for i in (0, 1)]
    print(f"{'whole tour':60s} {total[0]:9.2f} {total[1]:9.2f} {total[2]:9.2f} {total[3]:9.2f} "
          f"{total[1] / total[3]:8.2f}x")
    print(f"(the other commands differ by at most 0.5 s CPU) goal: first run <= 2x warm; wall ratio "
          f"{total[0] / total[2]:.2f}x, CPU ratio {total[1] / total[3]:.2f}x")



def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=9)
    ap.add_argument("--no-crossover", action="store_true", help="skip the interpreted/compiled table")
    ap.add_argument("--first-run", action="store_true", help="the README tour with an empty numba cache, then warm")
    args = ap.parse_args()
    py = sys.executable
    tilesolve = shutil.which("tilesolve") or os.path.join(os.path.dirname(py), "tilesolve")
    with tempfile.TemporaryDirectory() as tmp:
        ENV["PYTHONPYCACHEPREFIX"] = os.path.join(tmp, "pycache")
        if args.first_run:
            first_run(tilesolve, tmp)
            return
        script = os.path.join(tmp, "dappled_alg1.py")
        with open(script, "w") as f:
            f.write(PLAIN_SCRIPT)
        cross = os.path.join(tmp, "crossover.py")
        with open(cross, "w") as f:
            f.write(CROSSOVER_SCRIPT)
        brick = os.path.join(tmp, "brick.py")
        with open(brick, "w") as f:
            f.write(BRICK_SCRIPT)
        out = os.path.join(tmp, "out.json")
        rows = [  # label, argv, baseline label
            ("python -c pass", [py, "-c", "pass"], None),
            ('python -c "import numpy"', [py, "-c", "import numpy"], None),
            ("tilesolve --version", [tilesolve, "--version"], "python -c pass"),
            ("tilesolve --help", [tilesolve, "--help"], 'python -c "import numpy"'),
            ("plain Algorithm 1 script 100x100", [py, script, out], None),
            ("tilesolve dappled solve 100x100", [tilesolve, "dappled", "solve", "--size", "100x100", "--cond",
                                                 "H0=2,V1=2", "-o", out], "plain Algorithm 1 script 100x100"),
            ("tilesolve brick solve rect:100x100", [tilesolve, "brick", "solve", "--board", "rect:100x100", "-o",
                                                    out], 'python -c "import numpy"'),
        ]
        res: dict[str, tuple[float, float, float]] = {}
        print(f"whole commands, {args.repeat} runs each (median; CPU = user + sys of the process)")
        print(f"{'command':36s} {'wall s':>8s} {'CPU s':>8s} {'peak RSS MiB':>13s} {'CPU ratio':>10s}  baseline")
        for label, argv, base in rows:
            res[label] = measure(argv, args.repeat)
            wall, cpu, rss = res[label]
            ratio = f"{cpu / res[base][1]:.2f}x" if base else ""
            print(f"{label:36s} {wall:8.3f} {cpu:8.3f} {rss:13.1f} {ratio:>10s}  {base or ''}", flush=True)
        print("goals: --version <= 3x python -c pass; dappled solve <= 1x the plain script")
        if args.no_crossover:
            return
        from tilesolve.constructive import _brick_kernels, _dappled_kernels

        print(f"\nkernels interpreted vs compiled (fresh process, warm numba cache; THRESHOLD = "
              f"{_dappled_kernels.THRESHOLD:,} cells dappled, {_brick_kernels.THRESHOLD:,} brick)")
        print(f"{'route':12s} {'side':>6s} {'cells':>9s} {'plain CPU s':>12s} {'compiled CPU s':>15s} "
              f"{'plain/compiled':>15s}")
        cases = [("algorithm1", [cross], ["2"], (250, 350, 450, 600), "tilesolve.constructive.dappled"),
                 ("trivial", [cross], ["3"], (250, 350, 450, 600), "tilesolve.constructive.dappled"),
                 ("brick", [brick], [], (100, 150, 200, 300), "tilesolve.constructive.brick")]
        reps = max(3, args.repeat // 3)
        for route, script_argv, extra, sides, module in cases:
            run_once([py, *script_argv, "compiled", "8", *extra])  # fill the cache
            base = measure([py, "-c", f"import {module}, tilesolve.model"], reps)[1]
            for n in sides:
                plain = measure([py, *script_argv, "plain", str(n), *extra], reps)[1] - base
                comp = measure([py, *script_argv, "compiled", str(n), *extra], reps)[1] - base
                print(f"{route:12s} {n:6d} {n * n:9,d} {plain:12.3f} {comp:15.3f} {plain / comp:14.2f}x", flush=True)
        print("(CPU beyond importing the route's module; a threshold belongs where the ratio crosses 1)")


if __name__ == "__main__":
    main()
