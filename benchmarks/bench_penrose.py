"""Speed of Penrose windows: de Bruijn's pentagrid against the substitution route.

Times :func:`tilesolve.constructive.penrose.pentagrid` in process on square-ish windows of
about 10^4, 10^5 and 10^6 rhombs (seed 1), and in the same run two baselines:

* ``substitution``: :func:`~tilesolve.constructive.penrose.p3_substitution`, a sun deflated
  until it holds about the same number of rhombs (the other route to a patch that size);
* ``floor``: ``np.ceil`` over an array of ``5 x tiles`` floats, the five K-indices a rhomb
  needs: the floor any pentagrid costs.

Then the independent verifier on the pentagrid's window, and first the whole command
``tilesolve penrose --region ... -o t.json`` (generation, verification, writing the file) at
10^6 tiles (10^5 with ``--quick``), best of ``--repeat`` runs, beside its parts measured in
the same run: start-up (``tilesolve --version``), generation and verification in process; the
rest is importing the modules and writing the file.

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

from _measure import best, best_child, peak_mib  # noqa: E402 - benchmarks/ is on sys.path

SEED = 1
#: Mean rhomb area (thick:thin = phi:1): a window of ``n * AREA`` square units holds about n rhombs.
AREA = 0.8123


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    # the command runs first: a child's peak RSS starts from this process's at the fork
    n = 10**5 if args.quick else 10**6
    w = int(round((n * AREA * 1.25) ** 0.5))
    h = int(round(n * AREA / w))
    exe = os.path.join(os.path.dirname(sys.executable), "tilesolve")
    with tempfile.TemporaryDirectory() as d:
        argv = [exe, "penrose", "--region", f"{-w // 2},{-h // 2},{w}x{h}", "--seed", str(SEED), "-o",
                os.path.join(d, "t.json")]
        r = best_child(argv, args.repeat)
        size = os.path.getsize(os.path.join(d, "t.json")) / 2**20
    start = best_child([exe, "--version"], args.repeat)
    from tilesolve.constructive.penrose import p3_substitution, pentagrid
    from tilesolve.verify.substitution import penrose_violations

    window = (-w // 2, -h // 2, w, h)
    gw, gc, (types, verts) = best(lambda: pentagrid(window, seed=SEED), args.repeat)
    vw, vc, _ = best(lambda: penrose_violations("p3", types, verts), args.repeat)
    print(f"whole command at {len(types):,} tiles (generate, verify, write {size:.0f} MiB), best of {args.repeat}; "
          f"peak RSS {r.rss_mib:.0f} MiB")
    print(f"{'part':<28}{'wall s':>8}{'cpu s':>8}{'share of command cpu':>22}")
    for name, wall, cpu in (("whole command", r.wall, r.cpu), ("start-up (--version)", start.wall, start.cpu),
                            ("generation (pentagrid)", gw, gc), ("verification", vw, vc),
                            ("the rest (imports, writing)", r.wall - start.wall - gw - vw, r.cpu - start.cpu - gc - vc)):
        print(f"{name:<28}{wall:>8.2f}{cpu:>8.2f}{cpu / r.cpu:>22.2f}")
    print()

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
