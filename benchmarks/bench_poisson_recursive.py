"""Speed of the recursive Wang tiles (Kopf et al. 2006; class notes Part V; issue 23 §3).

Rows, each beside its anchor measured in the same run (numba compile excluded: one warm-up
call first; CPU time is this process's, the better measure on a shared machine):

* **build C = 2, N = 16, rho = 0.7, 4 x 4 subdivision** (corner tiles, progressive order,
  rules; the verification apart) against the slides' figure for Kopf et al.'s tile
  construction, "approx. 10 mins" (Part V);
* **window of about 10^6 points at level 2** (16 x 16 tiles, every point of level 2) and its
  verification (every level by the grid), against **plain dart throwing** (Cook 1986;
  the project's compiled kernel, one distance ``d_2`` on a torus of the same area, until
  1,000 darts in a row miss) asked for as many points, and against the slides' "6,000,000+
  points/s" (Part V); compared by throughput, points a CPU second;
* **a density ramp** of about 5 x 10^5 points (16 to 8,000 a unit area, west to east, on
  16 x 8 tiles: levels 0 to 3 in one window; each level computed only where it is needed);
* ``--command``: the whole ``tilesolve sample recursive-wang window ... --level 2 -o pts.npy``
  as a child process (verification and writing included; the set built by the build command
  in a child too), beside the kernel.

Usage::

    python benchmarks/bench_poisson_recursive.py [--command]
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile

import numpy as np
from _measure import best, best_child, peak_mib  # noqa: E402 - benchmarks/ is on sys.path

SLIDES_BUILD_S = 600.0  # Part V slides: "Tile construction: approx. 10 mins"
SLIDES_RATE = 6e6  # Part V slides: "Extremely fast (6,000,000+ points/s)"


def row(name, size, t, cpu, mib, rate, anchor, ratio):
    print(f"| {name:<34} | {size:>16} | {t:>8.3f} | {cpu:>8.3f} | {mib:>8.1f} | {rate:>14} | {anchor:<30} | {ratio:>9} |")


def command() -> tuple[float, float, float]:
    """Wall s, CPU s and peak RSS MiB of the window command (after one warm-up run), the set
    built by the build command: both children of this still small process."""
    script = os.path.join(os.path.dirname(sys.executable), "tilesolve")
    with tempfile.TemporaryDirectory() as d:
        best_child([script, "sample", "recursive-wang", "build", "-N", "16", "--rho", "0.7", "-n", "4", "--seed", "1",
                    "-o", "rset.json"], 1, cwd=d)
        argv = [script, "sample", "recursive-wang", "window", "rset.json", "--region", "0,0,16x16", "--level", "2",
                "--seed", "2", "-o", "pts.npy"]
        best_child(argv, 1, cwd=d)
        r = best_child(argv, 2, cwd=d)
        return r.wall, r.cpu, r.rss_mib


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--command", action="store_true", help="also time the whole window command")
    args = ap.parse_args()

    command_run = command() if args.command else None  # first: a child's peak RSS starts from its parent's
    from tilesolve.constructive.poisson import dart_throwing
    from tilesolve.constructive.poisson_recursive import build_recursive, sample_window
    from tilesolve.model.poisson_recursive import RecursiveTilesProblem, RecursiveWindowProblem
    from tilesolve.verify.poisson_recursive import tileset_violations, window_violations

    print(f"cores: {len(os.sched_getaffinity(0))}; CPU times of this process; compile excluded")
    print("| case                               |             size |   wall s |    CPU s | peak MiB |     throughput "
          "| anchor (same run)              |     ratio |")
    print("|---|---:|---:|---:|---:|---:|---|---:|")
    p = RecursiveTilesProblem(2, 16, 0.7, 4)
    warm = build_recursive(RecursiveTilesProblem(1, 16, 0.7, 2), seed=0)  # compile / load the kernels
    sample_window(RecursiveWindowProblem(warm, (0, 0, 8, 8), level=2), seed=0)
    dart_throwing(20_000, 0.005, seed=0)
    t, cpu, ts = best(lambda: build_recursive(p, seed=1), 1)
    row("build C=2 N=16 rho=0.7 n=4", f"{p.n_tiles} tiles", t, cpu, float("nan"), f"{ts.n_points:,} points",
        f"slides: ~{SLIDES_BUILD_S:.0f} s", f"{SLIDES_BUILD_S / cpu:,.0f}x")
    vt, vcpu, v = best(lambda: tileset_violations(ts), 1)
    assert v == [], v
    row("  verify the set", "512 blocks", vt, vcpu, float("nan"), "-", "", "")

    problem = RecursiveWindowProblem(ts, (0, 0, 16, 16), level=2)
    t, window_cpu, w = best(lambda: sample_window(problem, seed=2), 3)
    mib = peak_mib(lambda: sample_window(problem, seed=2))
    n = w.n_points
    row("window 16x16, level 2", f"{n:,} points", t, window_cpu, mib, f"{n / window_cpu / 1e6:,.2f} Mpt/s",
        "slides: 6 Mpt/s", f"{n / window_cpu / SLIDES_RATE:.2f}")
    vt, vcpu, v = best(lambda: window_violations(w), 1)
    assert v == [], v
    row("  verify every level (grid)", f"{n:,} points", vt, vcpu, float("nan"), f"{n / vcpu / 1e6:,.2f} Mpt/s",
        "", "")
    side = 16.0
    dt, dcpu, dpts = best(lambda: dart_throwing(n, p.distance_at(2) / side, seed=3, patience=1000), 1)
    row("  anchor: plain dart throwing", f"{len(dpts):,} points", dt, dcpu, float("nan"),
        f"{len(dpts) / dcpu / 1e6:,.3f} Mpt/s", "CPU darts / window", f"{dcpu / window_cpu:,.1f}x")

    ramp = RecursiveWindowProblem(ts, (0, 0, 16, 8), density=np.linspace(16, 8000, 1024)[None, :])
    t, cpu, rw = best(lambda: sample_window(ramp, seed=2), 1)
    row("ramp 16..8000 /unit, 16x8", f"{rw.n_points:,} points", t, cpu, float("nan"),
        f"{rw.n_points / cpu / 1e6:,.2f} Mpt/s", f"levels 0..{int(rw.level.max())}", "")

    if args.command:
        row("command: window -o pts.npy", f"{n:,} points", *command_run, f"{n / command_run[1] / 1e6:,.2f} Mpt/s",
            "command CPU / kernel CPU", f"{command_run[1] / window_cpu:.1f}x")

if __name__ == "__main__":
    main()
