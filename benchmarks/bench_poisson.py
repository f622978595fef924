"""Speed of the corner-based Poisson disk tiles (class notes §4.3; issue 23 §1).

Rows, each beside its anchor measured in the same run (numba compile excluded: one warm-up
call first; CPU time is this process's, the better measure on a shared machine):

* **build C = 2, N = 64, rho = 0.75** (``build_tiles``, verification by
  ``tileset_violations`` over all 2^9 colourings of a 2 x 2 block reported apart) against the
  notes' figure for one set, "several minutes to several hours" (§4.3; 300 s is taken as the
  anchor, the low end), and against scipy's ``PoissonDisk`` (Bridson) drawing the same number
  of points (``N`` a tile times the ``C + 2C^2 + C^4`` tiles' share of the plane: one tile's
  worth per interior tile) at the same distance;
* **build C = 4** (256 interior tiles, 292 in all), the same anchors;
* **window of at least 10^6 points** (``window_points`` on 126 x 126 tiles, the direct corner
  tiling: 125 x 125 tiles hold 10^6 points less the interior tiles' shortfall), and its
  verification (the grid of ``point_violations``), against plain dart
  throwing (Cook 1986; the project's own compiled kernel, one distance, until 2,000 darts in a
  row miss) on 10^5 points, and scipy's ``PoissonDisk`` at the same distance on 2 x 10^4
  (Bridson in Python, far slower); compared by throughput, points a second;
* ``--command``: the whole ``tilesolve sample poisson-tiles window set.json --region
  0,0,126x126 -o pts.npy`` as a child process (verification and writing included), beside the
  kernel.

Usage::

    python benchmarks/bench_poisson.py            # everything
    python benchmarks/bench_poisson.py --quick    # without the C = 4 build

Goals (issue 23 §1): a C = 2, N = 64 set in <= 10 s; 10^6 points from a window in <= 1 s;
a C = 4 set within 2 minutes.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import tempfile

from _measure import best, best_child, peak_mib  # noqa: E402 - benchmarks/ is on sys.path

NOTES_S = 300.0  # §4.3: "several minutes to several hours", the low end


def row(name, size, t, cpu, mib, rate, anchor, ratio):
    print(f"| {name:<34} | {size:>16} | {t:>8.3f} | {cpu:>8.3f} | {mib:>8.1f} | {rate:>14} | {anchor:<30} | {ratio:>9} |")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="leave out the C = 4 build")
    ap.add_argument("--command", action="store_true", help="also time the whole window command")
    args = ap.parse_args()

    from scipy.stats import qmc

    from tilesolve.constructive.poisson import build_tiles, dart_throwing, window_points
    from tilesolve.model.poisson import PoissonTilesProblem
    from tilesolve.verify.poisson import point_violations, tileset_violations

    def scipy_disk(n_points: float, distance: float, seed: int):
        side = math.sqrt(n_points / 64)  # tiles of 64 points
        eng = qmc.PoissonDisk(d=2, radius=distance / side, seed=seed)
        return eng.fill_space() * side

    print(f"cores: {len(os.sched_getaffinity(0))}; CPU times of this process; compile excluded")
    print("| case                               |             size |   wall s |    CPU s | peak MiB |     throughput | anchor (same run)              |     ratio |")
    print("|---|---:|---:|---:|---:|---:|---|---:|")
    build_tiles(PoissonTilesProblem(1, 32, 0.7), seed=0)  # warm-up: compile / load the kernels
    sets = {}
    for c in (2,) if args.quick else (2, 4):
        p = PoissonTilesProblem(c, 64, 0.75)
        t, cpu, ts = best(lambda: build_tiles(p, seed=1), 1)
        mib = peak_mib(lambda: build_tiles(p, seed=1)) if c == 2 else float("nan")
        sets[c] = ts
        n = ts.n_points
        row(f"build C={c} N=64 rho=0.75", f"{p.n_tiles} tiles", t, cpu, mib, f"{n / cpu:,.0f} pt/s",
            f"notes §4.3: >= {NOTES_S:.0f} s", f"{NOTES_S / cpu:,.0f}x")
        ts_, tcpu, v = best(lambda: tileset_violations(ts), 1)
        assert v == [], v
        row(f"  verify the set C={c}", f"{min(c**9, 4096):,} blocks", ts_, tcpu, float("nan"), "-", "", "")
        st, scpu, spts = best(lambda: scipy_disk(n, p.distance, 1), 1)
        row("  anchor: scipy PoissonDisk", f"{len(spts):,} points", st, scpu, float("nan"),
            f"{len(spts) / scpu:,.0f} pt/s", "build / scipy CPU", f"{cpu / scpu:.2f}")
        short = ts.stats["short"]
        print(f"|   (interior tiles short of N by {short} points in all; {n:,} points in the set) | | | | | | | |")

    ts = sets[2]
    win = (0, 0, 126, 126)
    window_points(ts, (0, 0, 4, 4), seed=1)
    t, cpu, w = best(lambda: window_points(ts, win, seed=2), 3)
    mib = peak_mib(lambda: window_points(ts, win, seed=2))
    n = w.n_points
    row("window 126x126 (direct corner)", f"{n:,} points", t, cpu, mib, f"{n / cpu / 1e6:,.2f} Mpt/s", "goal <= 1 s",
        f"{cpu:.2f} s")
    vt, vcpu, v = best(lambda: point_violations(w.local, ts.problem.distance, 126, 126), 1)
    assert v == [], v
    row("  verify the window (grid)", f"{n:,} points", vt, vcpu, float("nan"), f"{n / vcpu / 1e6:,.2f} Mpt/s", "", "")
    m = 100_000
    side = math.sqrt(m / 64)
    dt, dcpu, dpts = best(lambda: dart_throwing(2 * m, ts.problem.distance / side, seed=3, patience=2000), 1)
    row("  anchor: plain dart throwing", f"{len(dpts):,} points", dt, dcpu, float("nan"),
        f"{len(dpts) / dcpu / 1e6:,.3f} Mpt/s", "throughput window / darts", f"{(n / cpu) / (len(dpts) / dcpu):,.0f}x")
    st, scpu, spts = best(lambda: scipy_disk(m // 5, ts.problem.distance, 3), 1)  # Bridson in Python: slow
    row("  anchor: scipy PoissonDisk", f"{len(spts):,} points", st, scpu, float("nan"),
        f"{len(spts) / scpu / 1e6:,.3f} Mpt/s", "throughput window / scipy", f"{(n / cpu) / (len(spts) / scpu):,.0f}x")

    if args.command:
        from tilesolve.io.poisson_json import dump, tiles_to_dict
        from tilesolve.model.solution import Solution, Status

        script = os.path.join(os.path.dirname(sys.executable), "tilesolve")
        with tempfile.TemporaryDirectory() as d:
            with open(os.path.join(d, "set.json"), "w") as f:
                f.write(dump(tiles_to_dict(ts.problem, Solution(Status.SAT, ts, method="dart", seed=1))))
            argv = [script, "sample", "poisson-tiles", "window", "set.json", "--region", "0,0,126x126", "--seed", "2",
                    "-o", "pts.npy"]
            best_child(argv, 1, cwd=d)
            r = best_child(argv, 3, cwd=d)
            row("command: window -o pts.npy", f"{n:,} points", r.wall, r.cpu, r.rss_mib, f"{n / r.cpu / 1e6:,.2f} Mpt/s",
                "command CPU / kernel CPU", f"{r.cpu / cpu:.1f}x")


if __name__ == "__main__":
    main()
