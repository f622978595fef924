"""Cost per shape of the polyform census (``tilesolve shapes census``): the 81 holeless free
6-hexes of heesch-sat's README table (``--quick``: the 22 free 5-hexes).

In process, on one core: the generator (Redelmeier's algorithm and the reduction to free
forms), then every shape's classification (:func:`tilesolve.engine.shapes.classify`: tori with
up to 2 copies per period, else coronas up to level 3 with the refuted level's DRAT proof
checked) and its independent verification, grouped by verdict: shapes, mean and worst wall
seconds per shape, CPU seconds, tracemalloc's peak over the worst shape. In the same run, the
whole command as a fresh process (``tilesolve shapes census --workers 1``: start-up,
generation, classification, verification, output), and its wall time over the in-process sum.

heesch-sat (Kaplan's C++ program) side by side, shape by shape: ``bench_heesch_sat.py``.

Run from the repository root: ``python benchmarks/bench_shapes.py`` (or ``--quick``).
"""

from __future__ import annotations

import argparse
import shutil
import sys
import tempfile
import time
from collections import defaultdict

from _measure import child, peak_mib  # noqa: E402 - benchmarks/ is on sys.path


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    size = 5 if args.quick else 6
    # the whole command first, from a small parent (peak RSS is counted from the fork)
    script = shutil.which("tilesolve") or sys.exit("the tilesolve console script is not installed")
    with tempfile.TemporaryDirectory() as d:
        whole = child([script, "shapes", "census", "--grid", "hex", "--size", str(size), "--workers", "1",
                       "-o", f"{d}/census.json"])
    from tilesolve.constructive.polyforms import free_polyforms
    from tilesolve.engine.shapes import classify
    from tilesolve.model.shapes import ShapesProblem
    from tilesolve.verify.shapes import shapes_violations

    t = time.perf_counter()
    shapes = free_polyforms("hex", size, holes=False)
    gen_s = time.perf_counter() - t
    groups: dict = defaultdict(list)
    worst: dict = {}
    for s in shapes:
        p = ShapesProblem("classify", (s,), max_level=3, max_copies=2)
        t, c = time.perf_counter(), time.process_time()
        r = classify(p, seed=0).report
        bad = shapes_violations(p, r)
        wall, cpu = time.perf_counter() - t, time.process_time() - c
        assert not bad, bad
        key = r.verdict + (f" H={r.heesch}" if r.verdict == "non-tiler" else f" k={r.copies}")
        groups[key].append((wall, cpu))
        if wall > worst.get(key, (0, None))[0]:
            worst[key] = (wall, p)
    print(f"census of the holeless free {size}-hexes ({len(shapes)} shapes), one core; generator {gen_s:.3f} s")
    print(f"{'verdict':<18}{'shapes':>7}{'mean s':>9}{'worst s':>9}{'cpu s':>9}{'peak MiB':>10}")
    total = 0.0
    for key in sorted(groups):
        walls = [w for w, _ in groups[key]]
        cpu = sum(c for _, c in groups[key])
        total += sum(walls)
        peak = peak_mib(lambda: classify(worst[key][1], seed=0))
        print(f"{key:<18}{len(walls):>7}{sum(walls) / len(walls):>9.3f}{max(walls):>9.3f}{cpu:>9.2f}{peak:>10.1f}")
    print(f"{'all':<18}{len(shapes):>7}{total / len(shapes):>9.3f}{'':>9}{'':>9}{'':>10}")
    print(f"whole command (fresh process, --workers 1): wall {whole.wall:.2f} s, cpu {whole.cpu:.2f} s, "
          f"peak RSS {whole.rss_mib:.0f} MiB, exit {whole.returncode}; "
          f"ratio whole / in-process classification {whole.wall / (total + gen_s):.2f}")


if __name__ == "__main__":
    main()
