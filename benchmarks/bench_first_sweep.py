"""Proof checking against solving in the first Jeandel-Rao sweep after an install, then warm.

Issue 17 (part 6): in a fresh install's first sweep, checking the DRAT proofs must cost at most
3x the solving, as it does once numba's cache holds the checker's compiled kernels. The first
run compiles them (several seconds of CPU), and a sweep runs in several worker processes that
may all want them at once (:func:`tilesolve.verify.drat._kernels` compiles them once, in one
process, under a file lock; the others wait, or check small proofs interpreted meanwhile).

"First run after install" is measured by pointing ``NUMBA_CACHE_DIR`` at a fresh empty folder:
numba then reads and writes every cache there (a cache in ``__pycache__`` next to the sources
is not used), as a fresh install with no cache at all would. Each row runs, as a user would::

    tilesolve aperiodic check --builtin jeandel-rao --max-period N --workers K -o r.json

in a new folder (so no results cache is reused), first with the fresh numba cache, then again
with the cache the first run left (warm). From the report: ``solve s`` is the boards' time
less the checker's share (``time_s - evidence.proof_check_s``, summed over boards), ``check s``
the checker's share (compiling or waiting for the kernels included, since they happen inside
the check), ``check/solve`` their ratio (the goal: at most 3), and the slowest single check.
``wall s`` and ``cpu s`` are the whole command's (workers included).

Usage::

    python benchmarks/bench_first_sweep.py                    # tori up to 12 x 12, 2 workers
    python benchmarks/bench_first_sweep.py --max-period 8 --workers 1
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def _tilesolve() -> str:
    here = Path(sys.executable).parent / "tilesolve"
    return str(here) if here.exists() else (shutil.which("tilesolve") or "tilesolve")


def sweep(max_period: int, workers: int, cache: Path, folder: Path) -> dict:
    """Run one sweep in ``folder`` with numba's cache in ``cache``; its times from the report."""
    folder.mkdir(parents=True)
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache))
    cpu0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    proc = subprocess.run([_tilesolve(), "aperiodic", "check", "--builtin", "jeandel-rao", "--max-period",
                           str(max_period), "--workers", str(workers), "-o", "r.json"],
                          cwd=folder, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - t
    cpu1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode != 0:
        sys.exit(f"aperiodic check exited {proc.returncode}:\n{proc.stdout[-2000:]}{proc.stderr[-2000:]}")
    boards = json.loads((folder / "r.json").read_text())["periods"]
    checks = [float(b.get("evidence", {}).get("proof_check_s", 0.0)) for b in boards]
    total = sum(float(b["time_s"]) for b in boards)
    return {"boards": len(boards), "solve": total - sum(checks), "check": sum(checks), "slowest": max(checks),
            "wall": wall, "cpu": (cpu1.ru_utime + cpu1.ru_stime) - (cpu0.ru_utime + cpu0.ru_stime)}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--max-period", type=int, default=12, help="tori p x q with p, q <= this")
    ap.add_argument("--workers", type=int, default=2)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory(prefix="first-sweep-") as tmp:
        cache = Path(tmp) / "numba-cache"
        cache.mkdir()
        print(f"Jeandel-Rao tori p, q <= {args.max_period}, {args.workers} worker(s); numba cache {cache}")
        print(f"{'run':>6} {'boards':>6} {'solve s':>8} {'check s':>8} {'check/solve':>11} {'slowest':>8} "
              f"{'wall s':>7} {'cpu s':>7}")
        for run in ("first", "warm"):
            r = sweep(args.max_period, args.workers, cache, Path(tmp) / run)
            print(f"{run:>6} {r['boards']:>6} {r['solve']:>8.2f} {r['check']:>8.2f} "
                  f"{r['check'] / r['solve']:>10.2f}x {r['slowest']:>8.2f} {r['wall']:>7.1f} {r['cpu']:>7.1f}",
                  flush=True)
    print("goal: check/solve <= 3 on the first run too")


if __name__ == "__main__":
    main()
