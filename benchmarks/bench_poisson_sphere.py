"""Speed of the corner-based Poisson sphere tiles (class notes §4.4; issue 23 §2).

Rows, each beside its anchor measured in the same run (numba compile excluded: one warm-up
build first; CPU time is this process's, the better measure on a shared machine):

* **build C = 2, N = 128, rho = 0.65** (``build_tiles``: 318 tiles), and its verification
  (``tileset_violations3``: every pair of nearby slots under all colourings of their corners),
  against scipy's ``PoissonDisk(d=3)`` (Bridson) drawing points at the same distance and density
  (compared by throughput: scipy's is in Python and slow, so it draws 3,000 points);
* **box of about 10^6 points** (``window_points`` on 20 x 20 x 20 cells, the direct 3-D corner
  tiling with the long-period hash) and its verification (the grid of
  ``point_violations3``), against plain 3-D dart throwing (Cook 1986; the project's compiled
  kernel, one distance, until 2,000 darts in a row miss) on 10^5 points, and scipy's
  ``PoissonDisk(d=3)`` at the same distance; compared by throughput, points a second;
* ``--command``: the whole ``tilesolve sample poisson-spheres build`` and ``window ... --region
  0,0,0,20x20x20 -o pts.npy`` as child processes (verification and writing included), run
  first, from a small parent.

Usage::

    python benchmarks/bench_poisson_sphere.py [--command]

Goal (issue 23 §2): a box of 10^6 points in <= 2 s.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile

from _measure import best, best_child, peak_mib  # noqa: E402 - benchmarks/ is on sys.path

C, N, RHO, SIDE = 2, 128, 0.65, 20


def row(name, size, t, cpu, mib, rate, anchor, ratio):
    print(f"| {name:<34} | {size:>16} | {t:>8.3f} | {cpu:>8.3f} | {mib:>8.1f} | {rate:>14} | {anchor:<28} | {ratio:>9} |")


def commands() -> list[tuple]:
    """The two console commands, each run twice (the first loads numba's cache), best CPU kept."""
    script = os.path.join(os.path.dirname(sys.executable), "tilesolve")
    out = []
    with tempfile.TemporaryDirectory() as d:
        build = [script, "sample", "poisson-spheres", "build", "-C", str(C), "-N", str(N), "--rho", str(RHO), "--seed",
                 "1", "-o", "set.json"]
        window = [script, "sample", "poisson-spheres", "window", "set.json", "--region", f"0,0,0,{SIDE}x{SIDE}x{SIDE}",
                  "--seed", "2", "-o", "pts.npy"]
        for name, argv in (("command: build -o set.json", build), ("command: window -o pts.npy", window)):
            best_child(argv, 1, cwd=d)
            out.append((name, best_child(argv, 2, cwd=d)))
        import numpy as np

        n = len(np.load(os.path.join(d, "pts.npy")))
    return [(name, r, n) for name, r in out]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--command", action="store_true", help="also time the whole build and window commands")
    args = ap.parse_args()
    ran = commands() if args.command else []

    from scipy.stats import qmc

    from tilesolve.constructive.poisson_sphere import build_tiles, dart_throwing3, window_points
    from tilesolve.model.poisson_sphere import PoissonSphereTilesProblem
    from tilesolve.verify.poisson_sphere import point_violations3, tileset_violations3

    def scipy_spheres(n_points: int, distance: float, seed: int):
        side = (n_points / N) ** (1 / 3)  # N points a unit cell
        eng = qmc.PoissonDisk(d=3, radius=distance / side, seed=seed)
        return eng.random(n_points) * side

    print(f"cores: {len(os.sched_getaffinity(0))}; CPU times of this process; compile excluded")
    print("| case                               |             size |   wall s |    CPU s | peak MiB |     throughput "
          "| anchor (same run)            |     ratio |")
    print("|---|---:|---:|---:|---:|---:|---|---:|")
    build_tiles(PoissonSphereTilesProblem(1, 100, 0.6), seed=0)  # warm-up: load the compiled kernel
    p = PoissonSphereTilesProblem(C, N, RHO)
    t, cpu, ts = best(lambda: build_tiles(p, seed=1), 1)
    mib = peak_mib(lambda: build_tiles(p, seed=1))
    n = ts.n_points
    row(f"build C={C} N={N} rho={RHO}", f"{p.n_tiles} tiles", t, cpu, mib, f"{n / cpu:,.0f} pt/s", "", "")
    vt, vcpu, v = best(lambda: tileset_violations3(ts), 1)
    assert v == [], v
    row("  verify the set (all colourings)", f"{n:,} points", vt, vcpu, float("nan"), "-", "", "")
    m = 3000
    st, scpu, spts = best(lambda: scipy_spheres(m, p.distance, 1), 1)
    row("  anchor: scipy PoissonDisk(d=3)", f"{len(spts):,} points", st, scpu, float("nan"),
        f"{len(spts) / scpu:,.0f} pt/s", "throughput build / scipy", f"{(n / cpu) / (len(spts) / scpu):.2f}x")
    print(f"|   (interior tiles short of N by {ts.stats['short']} points in all) | | | | | | | |")

    box = (0, 0, 0, SIDE, SIDE, SIDE)
    window_points(ts, (0, 0, 0, 2, 2, 2), seed=1)
    t, wcpu, w = best(lambda: window_points(ts, box, seed=2), 3)
    mib = peak_mib(lambda: window_points(ts, box, seed=2))
    n = w.n_points
    row(f"box {SIDE}^3 (direct 3-D corner)", f"{n:,} points", t, wcpu, mib, f"{n / wcpu / 1e6:,.2f} Mpt/s",
        "goal <= 2 s", f"{wcpu:.2f} s")
    vt, vcpu, v = best(lambda: point_violations3(w.local, p.distance, w.box.size), 1)
    assert v == [], v
    row("  verify the box (grid)", f"{n:,} points", vt, vcpu, float("nan"), f"{n / vcpu / 1e6:,.2f} Mpt/s", "", "")
    m = 100_000
    side = (m / N) ** (1 / 3)
    dt, dcpu, dpts = best(lambda: dart_throwing3(2 * m, p.distance / side, seed=3, patience=2000), 1)
    row("  anchor: plain 3-D dart throwing", f"{len(dpts):,} points", dt, dcpu, float("nan"),
        f"{len(dpts) / dcpu / 1e6:,.3f} Mpt/s", "throughput box / darts", f"{(n / wcpu) / (len(dpts) / dcpu):,.0f}x")
    st, scpu, spts = best(lambda: scipy_spheres(3000, p.distance, 3), 1)
    row("  anchor: scipy PoissonDisk(d=3)", f"{len(spts):,} points", st, scpu, float("nan"),
        f"{len(spts) / scpu / 1e6:,.4f} Mpt/s", "throughput box / scipy", f"{(n / wcpu) / (len(spts) / scpu):,.0f}x")
    for name, r, count in ran:
        kernel = wcpu if "window" in name else cpu
        row(name, f"{count:,} points" if "window" in name else f"{p.n_tiles} tiles", r.wall, r.cpu, r.rss_mib,
            f"{count / r.cpu / 1e6:,.2f} Mpt/s" if "window" in name else "-", "command CPU / kernel CPU",
            f"{r.cpu / kernel:.1f}x")


if __name__ == "__main__":
    main()
