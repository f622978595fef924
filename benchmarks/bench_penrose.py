"""Speed of Penrose windows: de Bruijn's pentagrid against the substitution route.

Times :func:`tilesolve.constructive.penrose.pentagrid` in process on square-ish windows of
about 10^4, 10^5 and 10^6 rhombs (seed 1), and in the same run two baselines:

* ``substitution``: :func:`~tilesolve.constructive.penrose.p3_substitution`, a sun deflated
  until it holds about the same number of rhombs (the other route to a patch that size);
* ``floor``: ``np.ceil`` over an array of ``5 x tiles`` floats, the five K-indices a rhomb
  needs: the floor any pentagrid costs.

Then the independent verifier on the pentagrid's window, and the whole command
``tilesolve penrose --region ... -o t.json`` (generation, verification, writing the file) at
10^5 tiles.

Prints tiles, wall and CPU seconds (best of ``--repeat``), peak traced memory of one call,
tiles per second, and the ratios baseline wall / pentagrid wall.

Usage::

    python benchmarks/bench_penrose.py            # 10^4, 10^5, 10^6 rhombs
    python benchmarks/bench_penrose.py --quick    # 10^4, 10^5

Goal (issue 21): a window of 10^6 tiles in <= 2 s.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile

import numpy as np

from _measure import best, child, peak_mib  # noqa: E402 - benchmarks/ is on sys.path

SEED = 1
#: Mean rhomb area (thick:thin = phi:1): a window of ``n * AREA`` square units holds about n rhombs.
AREA = 0.8123


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    # the command runs first: a child's peak RSS starts from this process's at the fork
    with tempfile.TemporaryDirectory() as d:
        w = int(round((10**5 * AREA * 1.25) ** 0.5))
        h = int(round(10**5 * AREA / w))
        exe = os.path.join(os.path.dirname(sys.executable), "tilesolve")
        argv = [exe, "penrose", "--region", f"{-w // 2},{-h // 2},{w}x{h}", "--seed", str(SEED), "-o",
                os.path.join(d, "t.json")]
        r = child(argv)
        print(f"whole command at 10^5 tiles (generate, verify, write {os.path.getsize(os.path.join(d, 't.json')) / 2**20:.1f} "
              f"MiB): wall {r.wall:.2f} s, CPU {r.cpu:.2f} s, peak RSS {r.rss_mib:.0f} MiB, exit {r.returncode}")
    from tilesolve.constructive.penrose import p3_substitution, pentagrid
    from tilesolve.verify.substitution import penrose_violations

    sizes = [10**4, 10**5] + ([] if args.quick else [10**6])
    print(f"pentagrid windows, seed {SEED}; best of {args.repeat}; wall and CPU seconds")
    print(f"{'target':>9}{'tiles':>10}{'wall s':>8}{'cpu s':>7}{'peak MiB':>9}{'Mtiles/s':>9}"
          f"{'subst tiles':>12}{'subst s':>8}{'ratio':>7}{'floor s':>8}{'ratio':>7}{'verify s':>9}")
    for n in sizes:
        w = int(round((n * AREA * 1.25) ** 0.5))
        h = int(round(n * AREA / w))
        window = (-w // 2, -h // 2, w, h)
        t, cpu, (types, verts) = best(lambda: pentagrid(window, seed=SEED), args.repeat)
        peak = peak_mib(lambda: pentagrid(window, seed=SEED))
        steps = int(round(np.log(n / 3.6) / np.log(2.618)))
        ts, _, (st, _) = best(lambda: p3_substitution(steps), args.repeat)
        x = np.random.default_rng(0).random((len(types), 5)) * 1000
        tf, _, _ = best(lambda: np.ceil(x).astype(np.int64), args.repeat)
        tv, _, bad = best(lambda: penrose_violations("p3", types, verts), 1)
        assert bad == [], bad[:3]
        print(f"{n:>9,}{len(types):>10,}{t:>8.3f}{cpu:>7.3f}{peak:>9.1f}{len(types) / t / 1e6:>9.2f}"
              f"{len(st):>12,}{ts:>8.3f}{ts / t:>7.2f}{tf:>8.3f}{tf / t:>7.2f}{tv:>9.2f}")
    print("ratios: baseline wall / pentagrid wall (substitution: the other route, about the same tile count; "
          "floor: np.ceil over 5 values a tile)")

if __name__ == "__main__":
    main()
