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

Before the sweep, a first table (issue 19, "``tilesolve verify FILE`` vs ``json.load``"): the whole
command ``tilesolve verify FILE`` on solution files a user writes (``brick solve --board
rect:SxS``, the same on a board with 10% of its cells holes (``mask:``), ``dappled
solve --size SxS``, ``wall --region 0,0,SxS --max-line 2``), each run as a fresh process
beside ``python -c "json.load(open(FILE))"`` of the same file, paired in the same run:
median wall and CPU time (user + sys) and peak RSS of ``--repeat`` runs after a warm-up,
bytecode cached as in an installed package (:mod:`bench_startup`). The ratio is of CPU
times; the goal is ``<= 3x``. ``python -c "import numpy, json; json.load(...)"`` is listed
too: what any numpy program reading the file pays.

Usage::

    python benchmarks/bench_reverify.py                  # files 1000^2, then tori up to 8 x 8, one worker
    python benchmarks/bench_reverify.py --max-period 10 --workers 2
    python benchmarks/bench_reverify.py --only files --side 2000 --repeat 5
    python benchmarks/bench_reverify.py --only files --before f399833   # and as that revision ran it
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

from bench_startup import ENV, measure  # noqa: E402 - benchmarks/ is on sys.path


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


#: A numpy program that reads a JSON file: the floor of any command that checks it with numpy.
NUMPY_LOAD = "import json, sys, numpy; json.load(open(sys.argv[1]))"


#: ``tilesolve verify`` run from a package folder given by PYTHONPATH (an earlier revision's).
VERIFY_FROM_PATH = "import sys; from tilesolve.cli.main import main; sys.argv[0] = 'tilesolve'; main()"


def _before(rev: str, into: Path) -> Path:
    """The ``tilesolve`` package of git revision ``rev`` of this repository, extracted under ``into``."""
    repo = Path(__file__).resolve().parent.parent
    archive = subprocess.run(["git", "archive", rev, "tilesolve"], cwd=repo, capture_output=True, check=True).stdout
    subprocess.run(["tar", "-x", "-C", str(into)], input=archive, check=True)
    return into


def files_table(side: int, repeat: int, before: str | None = None) -> None:
    """``tilesolve verify FILE`` against ``json.load`` of FILE, whole processes (module docstring);
    with ``before``, also ``tilesolve verify FILE`` as revision ``before`` runs it."""
    import random  # not numpy: a child's peak RSS starts from this process's (see _measure.child)

    with tempfile.TemporaryDirectory() as d:
        cwd = Path(d)
        ENV["PYTHONPYCACHEPREFIX"] = str(cwd / "pycache")
        old = _before(before, Path(tempfile.mkdtemp(dir=d))) if before else None
        rng = random.Random(1)
        (cwd / "holes.txt").write_text("\n".join("".join("#" if rng.random() >= 0.1 else "." for _ in range(side))
                                                 for _ in range(side)))
        made = [
            ("brick rect", "b.json", ["brick", "solve", "--board", f"rect:{side}x{side}", "--seed", "1"]),
            ("brick mask (10% holes)", "m.json", ["brick", "solve", "--board", "mask:holes.txt", "--seed", "1"]),
            ("dappled H0=2,V1=2", "d.json", ["dappled", "solve", "--size", f"{side}x{side}", "--cond", "H0=2,V1=2",
                                             "--seed", "1"]),
            ("wall, lines <= 2", "w.json", ["wall", "--region", f"0,0,{side}x{side}", "--max-line", "2", "--seed",
                                            "7"]),
        ]
        py = sys.executable
        print(f"tilesolve verify FILE vs json.load of FILE, {side}x{side} cells, {repeat} runs each (median; CPU = "
              "user + sys of the process)")
        print(f"{'file':30s} {'MB':>6s} {'verify wall':>11s} {'CPU s':>7s} {'RSS MiB':>8s} {'json.load CPU':>13s} "
              f"{'ratio':>6s} {'numpy+json CPU':>14s} {'ratio':>6s}" + (f" {before + ' CPU':>12s} {'RSS MiB':>8s} "
                                                                      f"{'ratio':>6s}" if before else ""))
        for what, name, argv in made:
            _timed([*argv, "-o", name], cwd)
            path = str(cwd / name)
            v_wall, v_cpu, v_rss = measure([_tilesolve(), "verify", path], repeat)
            _, j_cpu, _ = measure([py, "-c", "import json, sys; json.load(open(sys.argv[1]))", path], repeat)
            _, n_cpu, _ = measure([py, "-c", NUMPY_LOAD, path], repeat)
            mb = os.path.getsize(path) / 1e6
            line = (f"{what:30s} {mb:6.1f} {v_wall:11.3f} {v_cpu:7.3f} {v_rss:8.1f} {j_cpu:13.3f} {v_cpu / j_cpu:5.1f}x "
                    f"{n_cpu:14.3f} {v_cpu / n_cpu:5.1f}x")
            if old is not None:
                ENV["PYTHONPATH"] = str(old)
                try:
                    _, b_cpu, b_rss = measure([py, "-c", VERIFY_FROM_PATH, "verify", path], repeat)
                finally:
                    del ENV["PYTHONPATH"]
                line += f" {b_cpu:12.3f} {b_rss:8.1f} {b_cpu / j_cpu:5.1f}x"
            print(line, flush=True)
        print("goal: tilesolve verify <= 3x json.load (CPU)")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--max-period", type=int, default=8, help="tori p x q with p, q <= this")
    ap.add_argument("--workers", type=int, default=1, help="sweep worker processes")
    ap.add_argument("--repeat", type=int, default=1, help="runs of the re-verification (best is shown)")
    ap.add_argument("--only", choices=("files", "sweep"), default=None, help="run one of the two tables")
    ap.add_argument("--side", type=int, default=1000, help="files table: boards of side x side cells")
    ap.add_argument("--before", metavar="REV", default=None,
                    help="files table: also tilesolve verify as git revision REV runs it (its package extracted)")
    args = ap.parse_args()
    if args.only != "sweep":
        files_table(args.side, max(args.repeat, 3), args.before)
        if args.only == "files":
            return
        print()
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
