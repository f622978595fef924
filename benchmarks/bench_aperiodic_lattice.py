"""The lattice route against the transducer route on the built-in periodic sets, in the same run.

For each set, the whole command ``tilesolve aperiodic check --builtin SET --max-period P``
(``P``: the period the set's source names) with ``--method lattice`` and then with
``--method transducer`` (the baseline, ``--time-limit`` seconds), each a fresh process: its
verdict and witness board, wall and CPU seconds (user + sys), peak RSS, and the lattices
searched per CPU second. ``tr/lat`` is the transducer's CPU time over the lattice route's
(the transducer's time-limit when it stopped undecided: a lower bound).

Usage::

    python benchmarks/bench_aperiodic_lattice.py                       # periodic-10-35 9-73 10-101
    python benchmarks/bench_aperiodic_lattice.py --sets all --time-limit 120
"""

from __future__ import annotations

import argparse
import json
import shutil
import sys
import tempfile
from pathlib import Path

from _measure import child  # noqa: E402 - benchmarks/ is on sys.path

DEFAULT = "periodic-10-35,periodic-9-73,periodic-10-101"


def tilesolve() -> str:
    here = Path(sys.executable).parent / "tilesolve"
    return str(here) if here.exists() else shutil.which("tilesolve")


def periodic_sets() -> list[str]:
    from tilesolve.io.builtin_tilesets import load, names

    return [n for n in names() if load(n)[1]["verdict"] == "periodic"]


def measure(name: str, period: int, method: str, time_limit: float, folder: Path) -> tuple:
    """One run: (verdict, board, wall, cpu, MiB, lattices searched)."""
    report = folder / f"{name}-{method}.json"
    argv = [tilesolve(), "aperiodic", "check", "--builtin", name, "--method", method, "--max-period", str(period),
            "-o", str(report)]
    if method == "transducer":
        argv += ["--time-limit", str(time_limit)]
    r = child(argv)
    if r.returncode not in (0, 3):
        raise SystemExit(f"{' '.join(argv)} exited {r.returncode}: {r.stderr}")
    doc = json.loads(report.read_text())
    tiled = [c for c in doc["periods"] if c["status"] == "tiles"]
    board = tiled[0]["board"] if tiled else "-"
    return doc["verdict"], board, r.wall, r.cpu, r.rss_mib, doc.get("stats", {}).get("lattices_searched")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sets", default=DEFAULT, help=f"comma-separated built-in sets, or 'all' [{DEFAULT}]")
    ap.add_argument("--time-limit", type=float, default=180.0, help="the transducer's time limit, seconds [180]")
    args = ap.parse_args()
    from tilesolve.io.builtin_tilesets import load

    sets = periodic_sets() if args.sets == "all" else args.sets.split(",")
    print(f"{'set':>16} {'P':>4} {'route':>10} {'verdict':>9} {'witness':>13} {'wall s':>7} {'CPU s':>7} "
          f"{'MiB':>6} {'lat/CPU s':>9} {'tr/lat':>7}")
    with tempfile.TemporaryDirectory() as tmp:
        for name in sets:
            period = int(load(name)[1]["period"])
            rows = {m: measure(name, period, m, args.time_limit, Path(tmp)) for m in ("lattice", "transducer")}
            for method, (verdict, board, wall, cpu, mib, lat) in rows.items():
                rate = f"{lat / cpu:9.0f}" if lat else f"{'-':>9}"
                ratio = f"{rows['transducer'][3] / rows['lattice'][3]:7.1f}" if method == "transducer" else f"{'':>7}"
                print(f"{name:>16} {period:4d} {method:>10} {verdict:>9} {board:>13} {wall:7.1f} {cpu:7.1f} "
                      f"{mib:6.0f} {rate} {ratio}", flush=True)


if __name__ == "__main__":
    main()
