"""Decide a large cyclic dappled problem with the SAT route, and compare with a naive encoding.

Instance (default): the 1024x1024 torus with L = {H0^3, V1^3}, |T| = 2 (dappled paper
§3.2, §6 item 8). Each route runs in a fresh Python process so that its peak memory (max
RSS) is its own:

* ``vectorised``: :func:`tilesolve.engine.dappled.solve_sat` (numpy clause generation,
  CaDiCaL 1.5.3 with proof logging, decoding), then the independent verifier;
* ``naive``: :func:`tilesolve.encodings.dappled.naive_clauses` (one clause at a time in
  Python) handed to the same solver.

Usage::

    python benchmarks/bench_cyclic_sat.py                 # 1024x1024, both routes
    python benchmarks/bench_cyclic_sat.py --size 256 --no-naive --json out.json
"""

from __future__ import annotations

import argparse
import json
import resource
import subprocess
import sys
import time


def _peak_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def worker(route: str, size: int, conds: list[str], solver: str) -> dict:
    from tilesolve.model import DappledProblem
    from tilesolve.verify import is_dappled

    p = DappledProblem.from_strings(f"{size}x{size}", conds, cyclic=True)
    if route == "vectorised":
        from tilesolve.engine.dappled import solve_sat

        t0 = time.perf_counter()
        sol = solve_sat(p, solver=solver)
        total = time.perf_counter() - t0
        t1 = time.perf_counter()
        ok = bool(sol.tiling is not None and is_dappled(p, sol.tiling))
        verify_s = time.perf_counter() - t1
        return {
            "route": route, "status": sol.status.value, "encode_s": sol.stats["encode_s"],
            "solve_s": sol.stats["solve_s"], "total_s": total, "verify_s": verify_s, "verified": ok,
            "vars": sol.stats["variables"], "clauses": sol.stats["clauses"], "peak_mb": _peak_mb(),
        }
    from pysat.solvers import Solver

    from tilesolve.encodings.dappled import naive_clauses

    t0 = time.perf_counter()
    clauses = naive_clauses(p)
    t1 = time.perf_counter()
    with Solver(name=solver, bootstrap_with=clauses) as s:
        answer = s.solve()
        model = s.get_model() if answer else None
    t2 = time.perf_counter()
    import numpy as np

    tiling = None
    if model is not None:
        m = np.asarray(model, dtype=np.int64)[: p.size]
        tiling = (m > 0).astype(np.int8).reshape(p.rows, p.cols)
    return {
        "route": route, "status": "sat" if answer else "unsat", "encode_s": t1 - t0, "solve_s": t2 - t1,
        "total_s": t2 - t0, "verify_s": None, "verified": bool(tiling is not None and is_dappled(p, tiling)),
        "vars": p.size, "clauses": len(clauses), "peak_mb": _peak_mb(),
    }


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--size", type=int, default=1024, help="grid side (default 1024)")
    ap.add_argument("--cond", default="H0=3,V1=3", help="conditions, comma separated")
    ap.add_argument("--solver", default="cadical153")
    ap.add_argument("--no-naive", action="store_true", help="skip the naive baseline")
    ap.add_argument("--json", help="also write the rows as JSON here")
    ap.add_argument("--worker", help=argparse.SUPPRESS)
    a = ap.parse_args(argv)
    conds = a.cond.split(",")
    if a.worker:
        print(json.dumps(worker(a.worker, a.size, conds, a.solver)))
        return 0
    rows = []
    for route in ["vectorised"] + ([] if a.no_naive else ["naive"]):
        cmd = [sys.executable, __file__, "--worker", route, "--size", str(a.size), "--cond", a.cond,
               "--solver", a.solver]
        out = subprocess.run(cmd, capture_output=True, text=True, check=True)
        rows.append(json.loads(out.stdout.strip().splitlines()[-1]))
    print(f"cyclic {a.size}x{a.size}, L = {{{a.cond}}}, solver {a.solver}")
    hdr = f"{'route':<11} {'status':<7} {'vars':>9} {'clauses':>10} {'encode s':>9} {'solve s':>8} " \
          f"{'total s':>8} {'verify s':>9} {'peak MB':>8} verified"
    print(hdr)
    print("-" * len(hdr))
    for r in rows:
        vs = "-" if r["verify_s"] is None else f"{r['verify_s']:.2f}"
        print(f"{r['route']:<11} {r['status']:<7} {r['vars']:>9,} {r['clauses']:>10,} {r['encode_s']:>9.2f} "
              f"{r['solve_s']:>8.2f} {r['total_s']:>8.2f} {vs:>9} {r['peak_mb']:>8.0f} {r['verified']}")
    print("solve s includes loading the clauses into the solver; total = encode + solve (+ decode).")
    if a.json:
        from tilesolve.io.atomic import write_text_atomic

        write_text_atomic(a.json, json.dumps(rows, indent=2))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
