"""The Wang tile census on 1, 2 and 4 Dask workers, beside local worker processes.

Issue 20 §4: ``tilesolve aperiodic census --tiles N --colors K`` classifies every set of N
tiles over at most K colours per axis (one per symmetry class). Each row runs the whole
command, as a user would, in a fresh folder::

    tilesolve aperiodic census --tiles N --colors K (--workers W | --cluster ADDR) -o c.jsonl

``local W``: W local worker processes (W = 1 classifies in the command's own process: the
baseline); ``dask W``: a ``distributed.LocalCluster`` of W single-threaded worker processes
started by this script before the command (its start-up is not counted; the command connects
to it). ``cpu s`` is the command's CPU with its local worker processes' (``os.wait4`` reports
a process with the children it reaped), and for Dask the CPU the cluster's workers spent
during the command (``Client.run`` of ``time.process_time`` before and after). ``ms/set`` is CPU per set; ``sets/s`` the throughput (wall); ``speed-up``
the wall time of ``local 1`` over the row's, in the same run. Every row's census must agree
set by set with the baseline's.

Usage::

    python benchmarks/bench_census.py                       # N = 3, K = 3 (461 sets)
    python benchmarks/bench_census.py --tiles 4 --colors 2 --workers 1 2 4
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

from _measure import child


def _tilesolve() -> str:
    here = Path(sys.executable).parent / "tilesolve"
    return str(here) if here.exists() else (shutil.which("tilesolve") or "tilesolve")


def _worker_cpu() -> float:
    return time.process_time()


def run(args: list[str], folder: Path, client=None) -> tuple[float, float, float, list]:
    """One census command in ``folder``: wall s, CPU s (command, its workers or the cluster's),
    peak RSS of the command (MiB), and its records as ``(set, class)``."""
    folder.mkdir(parents=True)
    before = sum(client.run(_worker_cpu).values()) if client is not None else 0.0
    r = child([_tilesolve(), "aperiodic", "census", *args, "-o", "c.jsonl"], cwd=folder)
    if r.returncode != 0:
        sys.exit(f"census exited {r.returncode}:\n{r.stdout[-2000:]}{r.stderr[-2000:]}")
    cpu = r.cpu
    if client is not None:
        cpu += sum(client.run(_worker_cpu).values()) - before
    lines = (folder / "c.jsonl").read_text().splitlines()[1:]
    records = sorted((tuple(rec["set"]), rec["class"]) for rec in map(json.loads, lines))
    return r.wall, cpu, r.rss_mib, records


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--tiles", type=int, default=3)
    ap.add_argument("--colors", type=int, default=3)
    ap.add_argument("--workers", type=int, nargs="+", default=[1, 2, 4])
    a = ap.parse_args()
    import logging

    import distributed

    logging.getLogger("distributed").setLevel(logging.ERROR)  # the nannies' shutdown notes

    size = ["--tiles", str(a.tiles), "--colors", str(a.colors)]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        base = run(size + ["--workers", "1"], tmp / "local-1")
        rows.append(("local", 1, *base))
        if 2 in a.workers:
            rows.append(("local", 2, *run(size + ["--workers", "2"], tmp / "local-2")))
        for w in a.workers:
            with distributed.LocalCluster(n_workers=w, threads_per_worker=1, processes=True,
                                          dashboard_address=":0") as lc, distributed.Client(lc) as client:
                rows.append(("dask", w, *run(size + ["--cluster", lc.scheduler_address], tmp / f"dask-{w}", client)))
    n = len(base[3])
    print(f"census of {n} sets of {a.tiles} tiles over at most {a.colors} colours per axis; "
          f"{os.cpu_count()} cores, load {os.getloadavg()[0]:.1f}")
    print(f"{'route':<7}{'workers':>8}{'wall s':>9}{'cpu s':>9}{'rss MiB':>9}{'sets/s':>9}{'ms/set':>9}"
          f"{'speed-up':>10}  agrees")
    for route, w, wall, cpu, rss, records in rows:
        print(f"{route:<7}{w:>8}{wall:>9.2f}{cpu:>9.2f}{rss:>9.0f}{n / wall:>9.1f}{1000 * cpu / n:>9.1f}"
              f"{base[0] / wall:>10.2f}  {records == base[3]}")


if __name__ == "__main__":
    main()
