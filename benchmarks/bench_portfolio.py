"""Benchmark of the seed portfolio (:func:`tilesolve.engine.portfolio.escalate`): one seed
against the default portfolio, whole ``tilesolve pack`` commands.

For each seed, the same command runs three times in a row, so that a busy machine slows
all alike: ``--workers 1`` (the baseline: one seed, in one process), the default (this
process runs the seed; after ``QUICK_S`` = 5 s a worker process runs fresh seeds beside it,
if a core is idle) and ``--workers 2`` (the worker starts whatever the load). The problem
is a corner packing over C = 8 colours by ``lift`` (a 64 x 64 torus, 4,096 tiles; one seed
takes 10-20 s on an idle core). Each row gives the wall time of the whole command
(interpreter start, search, verification, writing the JSON), the CPU time of the command
and its workers, the peak resident memory of the command's own process, its throughput in
placed tiles per second, the status, the seed that decided and where, and the ratio of its
time to the baseline's (< 1: faster). The last rows sum the times over the seeds.

Run: ``python benchmarks/bench_portfolio.py [--seeds 1 2 3] [--colors 8] [--time-limit S]``
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

#: ``tilesolve pack`` exit codes (DESIGN.md): 0 sat, 3 unknown.
_STATUS = {0: "sat", 3: "unknown"}


def tilesolve_command() -> list[str]:
    """The console script next to this interpreter, else the CLI module."""
    script = Path(sys.executable).with_name("tilesolve")
    if script.exists():
        return [str(script)]
    found = shutil.which("tilesolve")
    return [found] if found else [sys.executable, "-c", "import sys; from tilesolve.cli.main import main; "
                                                       "sys.exit(main(sys.argv[1:]))"]


def run(args, seed: int, workers: int | None, out: Path) -> dict:
    """One whole command: wall time, peak RSS (of its own process), status, notes."""
    cmd = tilesolve_command() + ["pack", "--kind", "corner", "--colors", str(args.colors), "--method", "lift",
                                 "--seed", str(seed), "--time-limit", str(args.time_limit), "-o", str(out)]
    if workers is not None:
        cmd += ["--workers", str(workers)]
    if out.exists():
        out.unlink()
    log = out.with_suffix(".log")
    with open(log, "w") as err:
        t0 = time.perf_counter()
        proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=err)
        _, wait_status, usage = os.wait4(proc.pid, 0)  # rusage of the command and its workers
        wall = time.perf_counter() - t0
    proc.returncode = os.waitstatus_to_exitcode(wait_status)
    stderr = log.read_text()
    lines = [line.strip() for line in stderr.splitlines() if line.strip()]
    note = next((line[len("note: "):] for line in lines if line.startswith("note: portfolio")), "")
    status = _STATUS.get(proc.returncode, f"exit {proc.returncode}")
    if not note and status == "sat":
        note = f"seed {json.loads(out.read_text()).get('seed', seed)} alone"
    return {"wall": wall, "cpu": usage.ru_utime + usage.ru_stime, "rss": usage.ru_maxrss / 1024, "status": status,
            "note": note or (lines[0] if lines else "")}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3], help="seeds to compare")
    ap.add_argument("--colors", type=int, default=8, help="corner colours C (even: the lift searches)")
    ap.add_argument("--time-limit", type=float, default=120.0, help="--time-limit of each command (s)")
    args = ap.parse_args()
    tiles = args.colors**4
    print(f"corner packing C = {args.colors} by lift ({args.colors**2} x {args.colors**2}, {tiles:,} tiles), "
          f"--time-limit {args.time_limit:g}, {os.cpu_count()} cores, load average "
          f"{' '.join(f'{x:.1f}' for x in os.getloadavg())}")
    print(f"{'seed':>4} {'run':20s} {'time_s':>8} {'cpu_s':>7} {'peak_MiB':>8} {'tiles/s':>8} {'status':8s} "
          f"{'ratio':>6}  decided by")
    totals = {"single": 0.0, "portfolio": 0.0, "workers 2": 0.0}
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "pack.json"
        for seed in args.seeds:
            base = None
            for label, workers in (("single (--workers 1)", 1), ("portfolio (default)", None),
                                   ("--workers 2", 2)):
                r = run(args, seed, workers, out)
                key = {1: "single", None: "portfolio", 2: "workers 2"}[workers]
                totals[key] += r["wall"]
                ratio = "" if base is None else f"{r['wall'] / base:6.2f}"
                base = r["wall"] if base is None else base
                rate = tiles / r["wall"] if r["status"] == "sat" else 0.0
                print(f"{seed:>4} {label:20s} {r['wall']:8.2f} {r['cpu']:7.1f} {r['rss']:8.0f} {rate:8.0f} "
                      f"{r['status']:8s} {ratio:>6}  {r['note'][:110]}", flush=True)
    print(f"{'all':>4} {'single, total':20s} {totals['single']:8.2f}")
    for key in ("portfolio", "workers 2"):
        print(f"{'all':>4} {key + ', total':20s} {totals[key]:8.2f} {'':7} {'':8} {'':8} {'':8} "
              f"{totals[key] / totals['single']:6.2f}")

if __name__ == "__main__":
    main()
