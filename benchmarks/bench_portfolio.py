"""Benchmark of the seed portfolio (:func:`tilesolve.engine.portfolio.escalate`): one seed
against the default portfolio, whole ``tilesolve pack`` commands.

For each seed, the same command runs three times in a row, so that a busy machine slows
all alike: ``--workers 1`` (the baseline: one seed, in one process), the default (this
process runs the seed; after ``QUICK_S`` = 5 s a worker process runs fresh seeds beside it,
if a core is idle) and ``--workers 2`` (the worker starts whatever the load); the order of
the three turns with each seed, so that no configuration always runs first. Workers run at
the lowest priority (``WORKER_NICE``). The problem is a corner packing over C = 8 colours by
``lift`` (a 64 x 64 torus, 4,096 tiles; one seed takes 10-20 s on an idle core). Each row
gives the wall time of the whole command (interpreter start, search, verification, writing
the JSON), the CPU time of the command's own process (``main``, sampled from /proc every
0.05 s) and of its workers (the rest of what ``os.wait4`` reports), the peak resident memory
of the command's own process, its throughput in placed tiles per second, the status, the
seed that decided and where, and the ratio of its time to the baseline's (< 1: faster). The
last rows sum the times over the seeds. On a shared machine single runs are noisy: compare
the totals, and the main process's CPU (the same seed does the same work in both).

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
        main_cpu = 0.0
        while True:
            main_cpu = own_cpu(proc.pid, main_cpu)
            pid, wait_status, usage = os.wait4(proc.pid, os.WNOHANG)  # rusage of the command and its workers
            if pid:
                break
            time.sleep(0.05)
        wall = time.perf_counter() - t0
    proc.returncode = os.waitstatus_to_exitcode(wait_status)
    stderr = log.read_text()
    lines = [line.strip() for line in stderr.splitlines() if line.strip()]
    note = next((line[len("note: "):] for line in lines if line.startswith("note: portfolio")), "")
    status = _STATUS.get(proc.returncode, f"exit {proc.returncode}")
    if not note and status == "sat":
        note = f"seed {json.loads(out.read_text()).get('seed', seed)} alone"
    cpu = usage.ru_utime + usage.ru_stime
    return {"wall": wall, "cpu": cpu, "main": main_cpu, "workers": max(0.0, cpu - main_cpu),
            "rss": usage.ru_maxrss / 1024, "status": status, "note": note or (lines[0] if lines else "")}


def own_cpu(pid: int, last: float) -> float:
    """CPU seconds (user + sys) process ``pid`` has used itself, its children left out
    (/proc/PID/stat); ``last`` once it is gone."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            fields = f.read().rsplit(")", 1)[1].split()
    except OSError:
        return last
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")  # utime, stime


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
    print(f"{'seed':>4} {'run':20s} {'time_s':>8} {'cpu_s':>7} {'main_s':>7} {'workr_s':>7} {'peak_MiB':>8} "
          f"{'tiles/s':>8} {'status':8s} {'ratio':>6}  decided by")
    configs = [("single (--workers 1)", 1), ("portfolio (default)", None), ("--workers 2", 2)]
    totals = {workers: {"wall": 0.0, "main": 0.0} for _, workers in configs}
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "pack.json"
        for i, seed in enumerate(args.seeds):
            order = configs[i % 3:] + configs[:i % 3]  # who runs first turns with the seed
            rows = {workers: run(args, seed, workers, out) for _, workers in order}
            base = rows[1]["wall"]
            for label, workers in configs:
                r = rows[workers]
                totals[workers]["wall"] += r["wall"]
                totals[workers]["main"] += r["main"]
                ratio = "" if workers == 1 else f"{r['wall'] / base:6.2f}"
                rate = tiles / r["wall"] if r["status"] == "sat" else 0.0
                print(f"{seed:>4} {label:20s} {r['wall']:8.2f} {r['cpu']:7.1f} {r['main']:7.1f} {r['workers']:7.1f} "
                      f"{r['rss']:8.0f} {rate:8.0f} {r['status']:8s} {ratio:>6}  {r['note'][:100]}", flush=True)
    single = totals[1]
    for label, workers in configs:
        t = totals[workers]
        ratio = "" if workers == 1 else f"{t['wall'] / single['wall']:6.2f}"
        print(f"{'all':>4} {label.split(' (')[0] + ', total':20s} {t['wall']:8.2f} {'':7} {t['main']:7.1f} {'':7} "
              f"{'':8} {'':8} {'':8} {ratio:>6}")
    print(f"ratio of totals, default / --workers 1: {totals[None]['wall'] / single['wall']:.2f} "
          f"(goal: <= 1, never slower than one worker)")


if __name__ == "__main__":
    main()
