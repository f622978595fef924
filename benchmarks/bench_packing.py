"""Benchmark of tile packings (class notes §5.5): constructions, solver searches, counting.

Prints one row per run: kind, C, method, seed, wall time, peak resident memory of the
process so far, status, and whether the result passed the independent verifier. The notes report 280 CPU-days (corner, C = 4) and about
23 CPU-years (Wang, C = 4) for their backtracking search; searches here are capped by
``--time-limit`` (status ``unknown`` when it runs out).

Run: ``python benchmarks/bench_packing.py [--time-limit S] [--max-colors C] [--big]``
(``--big`` adds the full C = 4 SAT and CP-SAT searches, the recursive C = 4 search, the
Wang C = 8 lift and the corner C = 10 and 12 lifts, each up to S seconds). Searches run with one worker (one seed: the times
are per seed); the last rows run the corner C = 8 lift as a two-process portfolio.
"""

from __future__ import annotations

import argparse
import resource
import time


def peak_mb() -> float:
    """Peak resident memory of this process so far (MiB; Linux reports KiB)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def row(kind, c, method, seed, t, status, ok, note=""):
    print(f"{kind:7s} {c:>2} {method:9s} {str(seed):>5s} {t:9.2f} {peak_mb():8.0f} {status:8s} {ok!s:9s} {note}",
          flush=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--time-limit", type=float, default=60.0, help="seconds per solver run")
    ap.add_argument("--max-colors", type=int, default=8, help="largest C for the constructions")
    ap.add_argument("--big", action="store_true", help="also run the C >= 4 searches")
    ap.add_argument("--seeds", type=int, default=3, help="seeds per small search")
    args = ap.parse_args()

    from tilesolve.families import packing as facade
    from tilesolve.model.packing import PackingProblem
    from tilesolve.verify.packing import is_packing

    print(f"{'kind':7s} {'C':>2} {'method':9s} {'seed':>5s} {'time_s':>9s} {'peak_MiB':>8s} {'status':8s} "
          f"{'verified':9s} note")

    def bench(kind, c, method, seed, workers=1):
        p = PackingProblem(kind, c)
        t0 = time.perf_counter()
        try:
            s = facade.solve(p, method=method, seed=seed, time_limit=args.time_limit, workers=workers)
        except Exception as exc:  # noqa: BLE001 - a benchmark reports, it does not stop
            row(kind, c, method, seed, time.perf_counter() - t0, "error", "-", f"{type(exc).__name__}: {exc}"[:80])
            return
        ok = is_packing(PackingProblem(kind, c), s.tiling) if s.tiling is not None else "-"
        note = s.reason or next((n for n in s.notes if n.startswith("portfolio")), "")
        row(kind, c, method, seed, time.perf_counter() - t0, s.status.value, ok, note[:90])

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
    # Lifted searches: corner packings for every even C <= 8 (odd C: the construction above),
    # random-looking Wang packings; recursive packings (Figs. 5.11-5.12).
    for kind, c in (("corner", 4), ("wang", 4), ("corner", 6), ("wang", 6), ("corner", 8)):
        for seed in range(1, args.seeds + 1):
            bench(kind, c, "lift", seed)
    for kind in ("corner", "wang"):
        for seed in range(1, args.seeds + 1):
            bench(kind, 3, "recursive", seed)
    if args.big:
        bench("wang", 5, "hybrid", 1)
        bench("wang", 8, "lift", 1)
        bench("corner", 10, "lift", 1)
        bench("corner", 12, "lift", 1)
        for kind in ("corner", "wang"):
            bench(kind, 4, "recursive", 1)
            for method in ("sat", "cpsat"):
                bench(kind, 4, method, 1)
    for seed in range(1, args.seeds + 1):
        bench("corner", 8, "lift", 100 + seed, workers=2)
    # Counting (C = 2).
    for kind in ("corner", "wang"):
        for sym in (False, True):
            t0 = time.perf_counter()
            res = facade.count(kind, 2, up_to_symmetry=sym)
            row(kind, 2, "count" + ("/sym" if sym else ""), None, time.perf_counter() - t0,
                "complete" if res.complete else "unknown", "-", f"{res.value:,} packings")


if __name__ == "__main__":
    main()
