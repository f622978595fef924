"""Speed of Penrose and polyomino importance sampling (class notes Part IV; issue 23 §3) against
plain rejection sampling in the same run.

Rows, each beside its anchor measured in the same run (CPU time is this process's, the better
measure on a shared machine; each kernel called once before it is timed):

* **penrose / polyomino (x-pentomino, chair) / rejection** on the built-in radial test image
  (256 x 256) at N samples (``sample`` of :mod:`tilesolve.constructive.importance`, the count
  calibration included), compared by throughput, points a second; the ratio is the sampler's
  throughput over rejection sampling's at the same N. The polyomino rows are unjittered and
  take their learnt correction table (Ostromoukhov 2007; ``ImportanceProblem.correct``, on by
  default for the X pentomino and the chair), its look-ups included;
* **+ Lloyd 4**: the corrected X-pentomino sampler with four density-weighted Lloyd steps;
* ``--command``: the whole ``tilesolve sample stipple --points 10000 -o out.svg --png
  out.png`` as a child process (imports, verification, the SVG and the PNG included), beside
  the kernel with the same settings: the raw polyomino sampler (``--no-correction --no-jitter
  --lloyd 0``: the tiles' centroids), and the command's defaults (Penrose, jitter, 4 Lloyd
  steps).

Usage::

    python benchmarks/bench_importance.py              # N = 10^4 and 10^5
    python benchmarks/bench_importance.py --quick      # N = 10^4 only
    python benchmarks/bench_importance.py --command    # also the whole stipple command
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile

from _measure import best, best_child, peak_mib  # noqa: E402 - benchmarks/ is on sys.path


def row(name, size, t, cpu, mib, rate, anchor, ratio):
    print(f"| {name:<30} | {size:>14} | {t:>8.3f} | {cpu:>8.3f} | {mib:>8.1f} | {rate:>14} | {anchor:<26} | {ratio:>8} |")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="N = 10^4 only")
    ap.add_argument("--command", action="store_true", help="also time the whole stipple command")
    args = ap.parse_args()

    from tilesolve.constructive.importance import sample
    from tilesolve.model.importance import ImportanceProblem, builtin_density

    d = builtin_density("radial", 256)
    print(f"cores: {len(os.sched_getaffinity(0))}; CPU times of this process; image: radial 256x256")
    print("| case                           |           size |   wall s |    CPU s | peak MiB |     throughput | "
          "anchor (same run)          |    ratio |")
    print("|---|---:|---:|---:|---:|---:|---|---:|")
    cases = [("penrose", "chair", 0), ("polyomino", "x-pentomino", 0), ("polyomino", "chair", 0),
             ("polyomino", "x-pentomino", 4)]
    for n in (10_000,) if args.quick else (10_000, 100_000):
        rej = ImportanceProblem(d, n, "rejection")
        sample(rej, seed=0)
        rt, rcpu, rpts = best(lambda: sample(rej, seed=1), 3)
        rate_rej = len(rpts) / rcpu
        row("rejection (anchor)", f"{len(rpts):,} points", rt, rcpu, peak_mib(lambda: sample(rej, seed=1)),
            f"{rate_rej / 1e6:,.2f} Mpt/s", "", "")
        for method, tile, lloyd in cases:
            if lloyd and n > 10_000:
                continue  # Lloyd on a grid of 16 positions a point: minutes at 10^5 on a shared core
            p = ImportanceProblem(d, n, method, tile, lloyd)
            sample(ImportanceProblem(d, 1000, method, tile), seed=0)
            t, cpu, pts = best(lambda: sample(p, seed=1), 1 if lloyd else 3)
            mib = peak_mib(lambda: sample(p, seed=1))
            name = method if method == "penrose" else f"polyomino ({tile})"
            name += f" + Lloyd {lloyd}" if lloyd else ""
            rate = len(pts) / cpu
            row(name, f"{len(pts):,} points", t, cpu, mib, f"{rate / 1e6:,.3f} Mpt/s", "throughput / rejection's",
                f"{rate / rate_rej:.3f}")

    if args.command:
        script = os.path.join(os.path.dirname(sys.executable), "tilesolve")
        n = 10_000
        for label, p, flags in (
                ("raw polyomino", ImportanceProblem(d, n, "polyomino", "x-pentomino", correct=False),
                 ["--method", "polyomino", "--no-correction", "--no-jitter", "--lloyd", "0"]),
                ("defaults", ImportanceProblem(d, n, "penrose", lloyd=4, jitter=True), [])):
            kt, kcpu, _ = best(lambda: sample(p, seed=1), 1)
            with tempfile.TemporaryDirectory() as folder:
                argv = [script, "sample", "stipple", "--points", str(n), *flags, "--seed", "1", "-o", "out.svg",
                        "--png", "out.png"]
                best_child(argv, 1, cwd=folder)
                r = best_child(argv, 2, cwd=folder)
            row(f"command: stipple, {label}", f"{n:,} points", r.wall, r.cpu, r.rss_mib,
                f"{n / r.cpu / 1e6:,.3f} Mpt/s", "command CPU / kernel CPU", f"{r.cpu / kcpu:.1f}x")


if __name__ == "__main__":
    main()
