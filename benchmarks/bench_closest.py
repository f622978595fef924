"""Closest dappled tiling (dappled paper §6 item 3) proved optimal: RC2 vs lazy decomposition vs CP-SAT.

Instances: a uniformly random target tiling on an n x n grid, L = {H0^2, V1^2}, |T| = 2,
one instance per seed. Every (size, method, seed) runs in a fresh Python process so the
peak memory column (max RSS) belongs to that run alone; every answer is checked with the
independent verifier, and the optima of all methods that finished are compared.

Methods (``--methods``):

``rc2``          one RC2 run (oracle Glucose 3) on the whole weighted formula
``rc2:SOLVER``   the same with another oracle (``cd15``, ``mgh``, ``g4``...)
``rc2+aem``      RC2 with adapt, exhaust and minz
``rc2-strat``    RC2Stratified
``lazy``         :func:`tilesolve.engine.maxsat.solve_lazy` (exact lazy decomposition)
``auto``         :func:`tilesolve.engine.dappled.solve_maxsat` with its default choice
``cpsat``        CP-SAT, 2 workers (core-based + LP), target as solution hint

Usage::

    python benchmarks/bench_closest.py                       # sizes 32 64 128, 3 seeds
    python benchmarks/bench_closest.py --sizes 64 256 --methods rc2 lazy --seeds 1
"""

from __future__ import annotations

import argparse
import json
import resource
import statistics
import subprocess
import sys
import time

DEFAULT_METHODS = ["rc2", "lazy", "auto", "cpsat"]


def worker(size: int, seed: int, method: str, time_limit: float, conds: list[str]) -> dict:
    import numpy as np

    from tilesolve.deadline import Deadline
    from tilesolve.encodings import encode_wcnf
    from tilesolve.engine.dappled import solve_cpsat, solve_maxsat
    from tilesolve.engine.maxsat import RC2Options, solve_lazy, solve_wcnf
    from tilesolve.model import DappledProblem, Status
    from tilesolve.verify import hamming_distance, is_dappled

    rng = np.random.default_rng(seed)
    target = rng.integers(0, 2, (size, size))
    p = DappledProblem.from_strings(f"{size}x{size}", conds, closest_to=target)
    t0 = time.perf_counter()
    lb = None
    if method == "auto":
        sol = solve_maxsat(p, deadline=Deadline(time_limit))
        status, tiling, opt, lb = sol.status, sol.tiling, sol.objective, sol.stats.get("lower_bound")
        used = sol.solver
    elif method == "cpsat":
        sol = solve_cpsat(p, deadline=Deadline(time_limit))
        status, tiling, opt, lb = sol.status, sol.tiling, sol.objective, sol.stats.get("lower_bound")
        used = "cp-sat x2"
    else:
        enc = encode_wcnf(p)
        if method == "lazy":
            r = solve_lazy(enc.hard, enc.soft, enc.target_values(target), deadline=Deadline(time_limit))
        else:
            oracle = method.split(":", 1)[1] if ":" in method else "g3"
            opts = RC2Options(adapt="+aem" in method, exhaust="+aem" in method, minz="+aem" in method,
                              stratified=method.startswith("rc2-strat"))
            r = solve_wcnf(enc.hard, enc.soft, solver=oracle, deadline=Deadline(time_limit), options=opts)
        status, opt, lb, used = r.status, r.cost, r.stats.get("lower_bound"), r.solver
        tiling = enc.decode(r.model) if r.model is not None else None
    elapsed = time.perf_counter() - t0
    ok = tiling is not None and is_dappled(p, tiling) and hamming_distance(tiling, target) == opt
    return {
        "size": size, "seed": seed, "method": method, "solver": used, "status": Status(status).value,
        "optimum": opt if status is Status.OPTIMAL else None, "found": opt, "lower_bound": lb,
        "time_s": elapsed, "peak_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0,
        "verified": bool(ok),
    }


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[32, 64, 128])
    ap.add_argument("--seeds", type=int, default=3, help="instances per size (seeds 0..N-1)")
    ap.add_argument("--methods", nargs="+", default=DEFAULT_METHODS)
    ap.add_argument("--cond", default="H0=2,V1=2")
    ap.add_argument("--time-limit", type=float, default=60.0, help="per run, seconds")
    ap.add_argument("--json", help="also write the rows as JSON here")
    ap.add_argument("--worker", nargs=3, help=argparse.SUPPRESS)
    a = ap.parse_args(argv)
    conds = a.cond.split(",")
    if a.worker:
        size, seed, method = int(a.worker[0]), int(a.worker[1]), a.worker[2]
        print(json.dumps(worker(size, seed, method, a.time_limit, conds)))
        return 0
    rows = []
    for size in a.sizes:
        for seed in range(a.seeds):
            for method in a.methods:
                cmd = [sys.executable, __file__, "--worker", str(size), str(seed), method,
                       "--time-limit", str(a.time_limit), "--cond", a.cond]
                out = subprocess.run(cmd, capture_output=True, text=True)
                if out.returncode != 0:
                    print(out.stderr, file=sys.stderr)
                    raise SystemExit(f"worker failed: {' '.join(cmd)}")
                row = json.loads(out.stdout.strip().splitlines()[-1])
                rows.append(row)
                print(f"  {size:>4} seed {seed} {method:<10} {row['status']:<8} {row['found']!s:>6} "
                      f"{row['time_s']:8.2f} s", file=sys.stderr, flush=True)
    # agreement: every proved optimum of one instance must be the same number
    bad = []
    for size in a.sizes:
        for seed in range(a.seeds):
            opts = {r["optimum"] for r in rows if r["size"] == size and r["seed"] == seed and r["optimum"] is not None}
            if len(opts) > 1:
                bad.append((size, seed, opts))
    print(f"closest tiling, random targets, L = {{{a.cond}}}, time limit {a.time_limit:g} s per run")
    hdr = f"{'size':>9} {'method':<10} {'proved':>6} {'time s (median)':>15} {'time s (max)':>12} " \
          f"{'optimum (per seed)':<22} {'peak MB':>8} verified"
    print(hdr)
    print("-" * len(hdr))
    for size in a.sizes:
        for method in a.methods:
            rs = [r for r in rows if r["size"] == size and r["method"] == method]
            times = [r["time_s"] for r in rs]
            proved = sum(r["status"] == "optimal" for r in rs)
            optima = "/".join("-" if r["optimum"] is None else str(r["optimum"]) for r in rs)
            print(f"{size:>4}x{size:<4} {method:<10} {proved:>3}/{len(rs):<2} {statistics.median(times):>15.2f} "
                  f"{max(times):>12.2f} {optima:<22} {max(r['peak_mb'] for r in rs):>8.0f} "
                  f"{all(r['verified'] for r in rs if r['found'] is not None)}")
    print("optima agree across methods" if not bad else f"OPTIMA DISAGREE: {bad}")
    if a.json:
        from tilesolve.io.atomic import write_text_atomic

        write_text_atomic(a.json, json.dumps(rows, indent=2))
    return 1 if bad else 0


if __name__ == "__main__":
    raise SystemExit(main())
