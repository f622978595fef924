"""The transducer route (Jeandel-Rao §2-3) against the SAT route, in the same run.

Part 1, the test sets: meyerphi/tiling's ``tilesets/*.tiles`` (``tests/data/transducer/``). For
each set the transducer searches ``k = 1 ..`` within ``--budget`` seconds; its verdict's
certificate is then decided by the SAT route (:func:`tilesolve.engine.aperiodic.decide`,
CaDiCaL with a checked DRAT proof for a refutation): the ``k x p`` torus it found, or the
``k x w`` rectangle an empty ``T_k`` refutes. ``sat/tr`` is the SAT time over the transducer's.
SAT is given the answer's size here; finding that size by a sweep costs far more.

Part 2, Jeandel-Rao (the 11 tiles, ``tilesolve/data/tilesets/jeandel-rao.json``): the largest
``k`` whose ``T_k`` the transducer builds within ``--budget`` seconds (no torus of height at most
``k``, whatever its width), against the largest ``m`` such that the SAT route refutes every
``p x q`` torus with ``p, q <= m`` in the same budget (checked proofs).

Times are wall-clock on this machine (best of ``--repeat``); MiB is the transducer search's
peak traced memory (numpy buffers included), measured by a second run for searches that took at
most ``--memory-below`` seconds (``nan`` otherwise).

Usage::

    python benchmarks/bench_transducer.py                 # budget 20 s a set
    python benchmarks/bench_transducer.py --budget 5 --quick
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np
from _measure import best, peak_mib  # noqa: E402 - benchmarks/ is on sys.path

from tilesolve.constructive.transducer import decide, strip_width
from tilesolve.deadline import Deadline
from tilesolve.engine.aperiodic import decide as sat_decide
from tilesolve.io.builtin_tilesets import load
from tilesolve.model.board import WangTileSet
from tilesolve.model.run import RunOptions

DATA = Path(__file__).resolve().parents[1] / "tests" / "data" / "transducer"
QUICK = ["all_colors", "hard", "finite_14", "periodic_8_20", "periodic_8_28", "periodic_7_30", "aperiodic_11_4"]


def load_tiles(path: Path) -> WangTileSet:
    rows = []
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.strip() and not line.startswith("#"):
            n, s, w, e = map(int, line.split())
            rows.append((n, e, s, w))
    a = np.array(rows)
    return WangTileSet(a, int(a.max()) + 1)


def test_sets(args) -> None:
    print(f"Part 1: meyerphi/tiling test sets, transducer budget {args.budget:g} s a set; SAT decides the "
          f"transducer's certificate")
    head = (f"{'set':>18} {'tiles':>5} {'verdict':>9} {'k':>4} {'certificate':>18} {'T_k st/tr':>13} "
            f"{'tr s':>7} {'MiB':>6} {'sat':>8} {'sat s':>7} {'sat/tr':>7}")
    print(head)
    paths = sorted(DATA.glob("*.tiles"))
    if args.quick:
        paths = [p for p in paths if p.stem in QUICK]
    for path in paths:
        ts = load_tiles(path)
        run = lambda: decide(ts, max_k=args.max_k, deadline=Deadline(args.budget))  # noqa: E731
        t_tr, _, v = best(run, args.repeat)
        mib = peak_mib(run) if t_tr <= args.memory_below else float("nan")
        st, tr = v.sizes[-1][1:] if v.sizes else (0, 0)
        board, sat_status, t_sat = "-", "-", float("nan")
        if v.verdict == "periodic":
            board = f"torus {v.torus.shape[0]}x{v.torus.shape[1]}"
        elif v.verdict == "empty":
            t0 = time.perf_counter()
            w = strip_width(ts, v.k)
            t_tr += time.perf_counter() - t0
            board = f"square {v.k}x{w}"
        if board != "-":
            t_sat, _, cert = best(lambda: sat_decide(ts, board, RunOptions(seed=1)), args.repeat)
            sat_status = cert.status
        ratio = t_sat / t_tr if board != "-" else float("nan")
        print(f"{path.stem:>18} {len(ts):>5} {v.verdict:>9} {v.k:>4} {board:>18} {f'{st}/{tr}':>13} "
              f"{t_tr:>7.2f} {mib:>6.1f} {sat_status:>8} {t_sat:>7.2f} {ratio:>7.2f}", flush=True)


def jeandel_rao(args) -> None:
    ts, _ = load("jeandel-rao")
    print(f"\nPart 2: Jeandel-Rao ({len(ts)} tiles), budget {args.budget:g} s each")
    t0 = time.perf_counter()
    v = decide(ts, max_k=10_000, deadline=Deadline(args.budget))
    t_tr = time.perf_counter() - t0
    print(f"  transducer: {v.verdict} up to k = {v.k} in {t_tr:.1f} s ({v.reason}); "
          f"T_k states/transitions by k: " + ", ".join(f"{k}:{s}/{t}" for k, s, t in v.sizes))
    deadline = Deadline(args.budget)
    m, t0 = 0, time.perf_counter()
    done = True
    while done:
        side = m + 1
        for p, q in sorted({(p, side) for p in range(1, side + 1)} | {(side, q) for q in range(1, side + 1)}):
            if deadline.expired():
                done = False
                break
            cert = sat_decide(ts, f"torus {p}x{q}", RunOptions(seed=1, deadline=deadline))
            if cert.status != "refuted":
                done = False
                break
        if done:
            m = side
    t_sat = time.perf_counter() - t0
    print(f"  SAT route : every torus p x q with p, q <= {m} refuted (checked proofs) in {t_sat:.1f} s")
    print(f"  {'route':>10} {'reach':>34} {'time s':>7}")
    print(f"  {'transducer':>10} {f'no torus of height <= {v.k} (any width)':>34} {t_tr:>7.1f}")
    print(f"  {'sat':>10} {f'no torus p x q, p, q <= {m}':>34} {t_sat:>7.1f}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--budget", type=float, default=20.0, help="seconds for the transducer search of one set")
    ap.add_argument("--max-k", type=int, default=200)
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--quick", action="store_true", help=f"only {', '.join(QUICK)}")
    ap.add_argument("--memory-below", type=float, default=5.0,
                    help="measure the peak memory (a second run) of searches that took at most this many seconds")
    args = ap.parse_args()
    decide(WangTileSet([[0, 0, 0, 0]], 1), max_k=2)  # load networkx before timing
    test_sets(args)
    jeandel_rao(args)


if __name__ == "__main__":
    main()
