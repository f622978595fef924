"""Re-verifying a whole aperiodicity report against what the sweep spent, on Jeandel-Rao tori.

Issue 17 (part 6): re-checking a report (``tilesolve aperiodic verify --proof-dir``: every
witness verified, every refuted board's CNF re-derived from the report's tile set and board
name with its named encoding, and every DRAT proof checked against that re-derived formula)
must cost no more than the sweep spent checking its proofs.

The Jeandel-Rao set is aperiodic, so every torus ``p x q`` (``p, q <= --max-period``) is
refuted with a proof. The script runs, as a user would, through the console script:

1. ``tilesolve aperiodic check --builtin jeandel-rao --max-period N --workers K --proof-dir D -o r.json``
   (whole command, wall clock), and reads from the report each board's time (solving and
   checking, ``time_s``) and the checker's share (``evidence.proof_check_s``);
2. ``tilesolve aperiodic verify r.json --proof-dir D`` (whole command, wall clock: start-up,
   reading, re-deriving every CNF, checking every proof, best of ``--repeat``).

It prints the solve time (boards' time less their checking), the sweep's checking time, the
re-verification time (wall clock, and CPU time of the command with its worker processes) and
their ratios; the goal is ``re-verify / sweep checking <= 1``. The
numba kernels are compiled (cached on disk) before timing by one small check, so neither side
pays a first compile.

Usage::

    python benchmarks/bench_reverify.py                  # tori up to 8 x 8, one worker
    python benchmarks/bench_reverify.py --max-period 10 --workers 2
"""

from __future__ import annotations

import argparse
import json
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


def _timed(args: list[str], cwd: Path) -> tuple[float, float]:
    """Wall-clock and CPU seconds (the command and its worker processes) of ``tilesolve ARGS``."""
    cpu0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    proc = subprocess.run([_tilesolve(), *args], cwd=cwd, capture_output=True, text=True)
    took = time.perf_counter() - t
    cpu1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode != 0:
        sys.exit(f"tilesolve {' '.join(args)} exited {proc.returncode}:\n{proc.stdout[-2000:]}{proc.stderr[-2000:]}")
    return took, (cpu1.ru_utime + cpu1.ru_stime) - (cpu0.ru_utime + cpu0.ru_stime)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--max-period", type=int, default=8, help="tori p x q with p, q <= this")
    ap.add_argument("--workers", type=int, default=1, help="sweep worker processes")
    ap.add_argument("--repeat", type=int, default=1, help="runs of the re-verification (best is shown)")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as d:
        cwd = Path(d)
        # compile (or load from numba's cache) the checker's kernels before anything is timed
        subprocess.run([sys.executable, "-c", "from tilesolve.verify.drat import check_drat; "
                        "check_drat([[1, 2], [-1, 2], [1, -2], [-1, -2]], ['1 0', '0'], kernels='compiled')"],
                       check=True)
        check_wall, check_cpu = _timed(["aperiodic", "check", "--builtin", "jeandel-rao", "--max-period",
                                        str(args.max_period), "--workers", str(args.workers), "--proof-dir", "proofs",
                                        "-o", "r.json"], cwd)
        doc = json.loads((cwd / "r.json").read_text())
        refuted = [c for c in doc["periods"] if c["status"] == "refuted"]
        boards_s = sum(c["time_s"] for c in doc["periods"])
        checking_s = sum(c["evidence"]["proof_check_s"] for c in refuted)
        solving_s = boards_s - checking_s
        proof_mb = sum(p.stat().st_size for p in (cwd / "proofs").glob("*.drat")) / 1e6
        runs = [_timed(["aperiodic", "verify", "r.json", "--proof-dir", "proofs", "--workers", str(args.workers)],
                       cwd) for _ in range(args.repeat)]
        verify_s, verify_cpu = min(r[0] for r in runs), min(r[1] for r in runs)
    rows = [
        ("sweep, whole command: wall / CPU", check_wall, check_cpu),
        ("  boards: solving (sum over boards)", solving_s, None),
        ("  boards: checking proofs (sum over boards)", checking_s, None),
        ("aperiodic verify --proof-dir, whole command: wall / CPU", verify_s, verify_cpu),
    ]
    print(f"Jeandel-Rao, {len(refuted)} tori p, q <= {args.max_period} refuted, {args.workers} worker(s), "
          f"{proof_mb:.1f} MB of proofs")
    print(f"{'what':56s} {'seconds':>9s} {'CPU s':>8s} {'/ checking':>11s}")
    for what, s, cpu in rows:
        print(f"{what:56s} {s:9.2f} {'' if cpu is None else f'{cpu:8.2f}':>8s} {s / checking_s:11.2f}")
    print(f"re-verify / solving: {verify_s / solving_s:.2f} wall, {verify_cpu / solving_s:.2f} CPU; goal re-verify / "
          f"sweep checking <= 1: {'met' if verify_s <= checking_s else 'missed'} (wall {verify_s / checking_s:.2f}, "
          f"CPU {verify_cpu / checking_s:.2f})")


if __name__ == "__main__":
    main()
