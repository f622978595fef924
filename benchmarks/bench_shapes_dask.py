"""Census throughput on a real local Dask cluster against local worker processes, same run.

The whole command ``tilesolve shapes census --grid G --size N`` (default: the 81 holeless
6-hexes) runs four times as a fresh process: ``--workers 1``, ``--workers 2``, then against a
``distributed.LocalCluster`` of 1 and of 2 single-threaded worker processes (started here; the
command connects to its scheduler address with ``--cluster``). Printed: wall seconds, shapes a
second, and the ratio to ``--workers 1``. The answers of every run are compared shape by shape.

Run from the repository root: ``python benchmarks/bench_shapes_dask.py [--grid hex --size 6]``.
"""

from __future__ import annotations

import argparse
import json
import shutil
import sys
import tempfile

from _measure import child  # noqa: E402 - benchmarks/ is on sys.path


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--grid", default="hex")
    ap.add_argument("--size", type=int, default=6)
    args = ap.parse_args()
    script = shutil.which("tilesolve") or sys.exit("the tilesolve console script is not installed")
    base = [script, "shapes", "census", "--grid", args.grid, "--size", str(args.size)]
    runs = []
    with tempfile.TemporaryDirectory() as d:
        for w in (1, 2):
            runs.append((f"local --workers {w}", child(base + ["--workers", str(w), "-o", f"{d}/l{w}.json"]),
                         f"{d}/l{w}.json"))
        import distributed

        for w in (1, 2):
            with distributed.LocalCluster(n_workers=w, threads_per_worker=1, processes=True,
                                          dashboard_address=None) as lc:
                runs.append((f"dask LocalCluster, {w} worker(s)",
                             child(base + ["--cluster", lc.scheduler_address, "-o", f"{d}/d{w}.json"]),
                             f"{d}/d{w}.json"))
        answers = []
        for _, r, path in runs:
            with open(path) as fh:
                answers.append([(s["cells"], s["verdict"], s["heesch"], s["copies"]) for s in json.load(fh)["shapes"]])
    n = len(answers[0])
    print(f"census of {args.size}-{args.grid} holeless: {n} shapes; the whole command as a fresh process")
    print(f"{'run':<32}{'wall s':>8}{'cpu s':>8}{'shapes/s':>10}{'vs 1 local':>12}  exit")
    w1 = runs[0][1].wall
    for name, r, _ in runs:
        print(f"{name:<32}{r.wall:>8.1f}{r.cpu:>8.1f}{n / r.wall:>10.2f}{w1 / r.wall:>12.2f}  {r.returncode}")
    print("answers identical in every run:", all(a == answers[0] for a in answers))
    print("(cpu s is the command's own process; Dask workers' CPU is not counted there)")


if __name__ == "__main__":
    main()
