"""Benchmark of tile packings (class notes §5.5): constructions, solver searches, counting.

Prints one row per run: kind, C, method, seed, wall time, status, and whether the result
passed the independent verifier. The notes report 280 CPU-days (corner, C = 4) and about
23 CPU-years (Wang, C = 4) for their backtracking search; searches here are capped by
``--time-limit`` (status ``unknown`` when it runs out).

Run: ``python benchmarks/bench_packing.py [--time-limit S] [--max-colors C] [--big]``
(``--big`` adds the C = 4 SAT and CP-SAT searches, each up to S seconds).
"""

from __future__ import annotations

import argparse
import time


def row(kind, c, method, seed, t, status, ok, note=""):
    print(f"{kind:7s} {c:>2} {method:8s} {str(seed):>5s} {t:9.2f} {status:8s} {ok!s:9s} {note}", flush=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--time-limit", type=float, default=60.0, help="seconds per solver run")
    ap.add_argument("--max-colors", type=int, default=8, help="largest C for the constructions")
    ap.add_argument("--big", action="store_true", help="also run the C >= 4 searches")
    ap.add_argument("--seeds", type=int, default=3, help="seeds per small search")
    args = ap.parse_args()

    from tilesolve import packing as facade
    from tilesolve.model.packing import PackingProblem
    from tilesolve.verify.packing import is_packing

    print(f"{'kind':7s} {'C':>2} {'method':8s} {'seed':>5s} {'time_s':>9s} {'status':8s} {'verified':9s} note")

    def bench(kind, c, method, seed):
        p = PackingProblem(kind, c)
        t0 = time.perf_counter()
        try:
            s = facade.solve(p, method=method, seed=seed, time_limit=args.time_limit)
        except Exception as exc:  # noqa: BLE001 - a benchmark reports, it does not stop
            row(kind, c, method, seed, time.perf_counter() - t0, "error", "-", f"{type(exc).__name__}: {exc}"[:80])
            return
        ok = is_packing(s.tiling, kind, c) if s.tiling is not None else "-"
        row(kind, c, method, seed, time.perf_counter() - t0, s.status.value, ok, (s.reason or "")[:60])

    # Constructions, every C up to --max-colors.
    for c in range(2, args.max_colors + 1):
        bench("wang", c, "euler", None)
        bench("wang", c, "outer", 1)
        if c % 2:
            bench("corner", c, "outer", 1)
    bench("corner", 4, "known", 1)
    bench("wang", 4, "known", 1)
    # Solver searches, C = 2 and 3.
    for kind in ("wang", "corner"):
        for c in (2, 3):
            for method in ("sat", "cpsat"):
                for seed in range(1, args.seeds + 1):
                    bench(kind, c, method, seed)
    for seed in range(1, args.seeds + 1):
        bench("wang", 4, "hybrid", seed)
    if args.big:
        bench("wang", 5, "hybrid", 1)
        for kind in ("corner", "wang"):
            for method in ("sat", "cpsat"):
                bench(kind, 4, method, 1)
    # Counting (C = 2).
    for kind in ("corner", "wang"):
        for sym in (False, True):
            t0 = time.perf_counter()
            res = facade.count(kind, 2, up_to_symmetry=sym)
            row(kind, 2, "count" + ("/sym" if sym else ""), None, time.perf_counter() - t0,
                "complete" if res.complete else "unknown", "-", f"{res.value:,} packings")


if __name__ == "__main__":
    main()
