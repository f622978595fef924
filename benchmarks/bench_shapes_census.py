"""The larger polyform census (issue 21): holeless free polyominoes up to size 10, polyhexes up
to 8, polyiamonds up to 10, each shape classified and its report verified, with its cost.

Each set runs as the whole command, ``tilesolve shapes census --resume --time-limit S`` (2 local
workers unless ``--workers``), writing ``benchmarks/results/shapes_census_<grid><size>.json``;
a set stopped by its time limit continues from that file on the next run, so the census grows
over several runs. Then one table over every file: shapes done of the total, isohedral,
periodic (k-isohedral, k <= ``max_copies``), non-tilers (their Heesch numbers), inconclusive,
and the cost per shape over the shapes done: the wall and the CPU seconds (the worker's own)
of each shape's classification and verification as the file records them (on a machine shared
by other jobs the CPU time is the measure), beside this run's wall time of the command.

Run from the repository root::

    python benchmarks/bench_shapes_census.py --time-limit 300          # every set, 300 s each
    python benchmarks/bench_shapes_census.py --set omino8 --table-only  # the table of the files
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import sys
import time
from collections import Counter

HERE = os.path.dirname(os.path.abspath(__file__))
RESULTS = os.path.join(HERE, "results")
#: The sets, in the order they run.
SETS = [("omino", 7), ("omino", 8), ("hex", 7), ("iamond", 8), ("iamond", 9), ("iamond", 10), ("omino", 9),
        ("hex", 8), ("omino", 10)]


def path_of(grid_name: str, size: int) -> str:
    return os.path.join(RESULTS, f"shapes_census_{grid_name}{size}.json")


def summary(doc: dict) -> dict:
    """Counts by class and the mean seconds a shape of one census file."""
    rows = doc["shapes"]
    kinds = Counter(r["verdict"] for r in rows)
    heesch = Counter(r["heesch"] for r in rows if r["verdict"] == "non-tiler")
    return {"done": len(rows), "total": doc.get("total"), "isohedral": kinds["isohedral"],
            "periodic": kinds["periodic"], "non-tiler": kinds["non-tiler"], "inconclusive": kinds["inconclusive"],
            "heesch": dict(sorted(heesch.items())), "ms": 1000 * sum(r["time_s"] for r in rows) / max(len(rows), 1),
            "cpu_ms": 1000 * sum(r.get("cpu_s") or 0 for r in rows) / max(len(rows), 1),
            "bad": sum(bool(r["violations"]) for r in rows)}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--set", dest="sets", action="append", metavar="GRIDSIZE",
                    help="e.g. omino8 (repeatable; default: every set)")
    ap.add_argument("--time-limit", type=float, default=300, help="seconds per set and run")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--table-only", action="store_true", help="print the table of the files, run nothing")
    args = ap.parse_args()
    chosen = [(g, n) for g, n in SETS if not args.sets or f"{g}{n}" in args.sets]
    script = shutil.which("tilesolve") or sys.exit("the tilesolve console script is not installed")
    os.makedirs(RESULTS, exist_ok=True)
    walls = {}
    if not args.table_only:
        import subprocess

        for g, n in chosen:
            t = time.perf_counter()
            p = subprocess.run([script, "shapes", "census", "--grid", g, "--size", str(n), "--workers",
                                str(args.workers), "--time-limit", str(args.time_limit), "--resume",
                                "-o", path_of(g, n)], capture_output=True, text=True)
            walls[(g, n)] = (time.perf_counter() - t, p.returncode)
            print(f"{g}{n}: exit {p.returncode} in {walls[(g, n)][0]:.0f} s", flush=True)
            if p.returncode not in (0, 3):
                print(p.stderr[-2000:])
    print("\n| set | done / total | isohedral | periodic | non-tilers (H: count) | inconclusive | ms a shape "
          "| CPU ms a shape | this run |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for g, n in chosen:
        if not os.path.exists(path_of(g, n)):
            continue
        with open(path_of(g, n)) as fh:
            s = summary(json.load(fh))
        hs = ", ".join(f"{h}: {c}" for h, c in s["heesch"].items())
        run = f"{walls[(g, n)][0]:.0f} s, exit {walls[(g, n)][1]}" if (g, n) in walls else "-"
        bad = f" ({s['bad']} failed verification)" if s["bad"] else ""
        print(f"| {n}-{g} | {s['done']} / {s['total']} | {s['isohedral']} | {s['periodic']} | {s['non-tiler']}"
              f"{f' ({hs})' if hs else ''} | {s['inconclusive']} | {s['ms']:,.0f} | {s['cpu_ms']:,.0f} | {run}{bad} |")


if __name__ == "__main__":
    main()
