"""Decide a large cyclic dappled problem with the SAT route, and compare with a naive encoding.

Instance (default): the 1024x1024 torus with L = {H0^3, V1^3}, |T| = 2 (dappled paper
§3.2, §6 item 8). Each route runs in a fresh Python process so that its peak memory (max
RSS) is its own:

* ``command``: the whole command ``tilesolve dappled solve --size NxN --cond H0=3,V1=3
  --cyclic --method sat -o out.json`` (issue 19: at 4096x4096, goal <= 60 s and <= 4 GB);
* ``vectorised``: :func:`tilesolve.engine.dappled.solve_sat` (numpy clause generation,
  CaDiCaL 1.5.3 with proof logging, decoding), then the independent verifier;
* ``append``: the same clauses loaded the previous way, PySAT's ``append_formula`` (a Python
  loop over the clauses) with the garbage collector running, then solved: the anchor of the
  loading path;
* ``naive``: :func:`tilesolve.encodings.dappled.naive_clauses` (one clause at a time in
  Python) handed to the same solver.

Usage::

    python benchmarks/bench_cyclic_sat.py                 # 1024x1024, every route
    python benchmarks/bench_cyclic_sat.py --size 4096 --no-naive --no-vectorised  # the issue's size (~10 GB)
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


def _cpu_s() -> float:
    """CPU seconds (user + sys) of this whole process so far, start-up included."""
    ru = resource.getrusage(resource.RUSAGE_SELF)
    return ru.ru_utime + ru.ru_stime


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
            "vars": sol.stats["variables"], "clauses": sol.stats["clauses"], "peak_mb": _peak_mb(), "cpu_s": _cpu_s(),
        }
    from pysat.solvers import Solver

    if route == "append":
        from tilesolve.encodings.dappled import encode_cnf

        t0 = time.perf_counter()
        enc = encode_cnf(p)
        t1 = time.perf_counter()
        with Solver(name=solver, with_proof=True) as s:
            for chunk in enc.hard.chunks(1 << 14):
                s.append_formula(chunk)
            answer = s.solve()
            tiling = enc.decode(s.get_model()) if answer else None
        t2 = time.perf_counter()
        return {
            "route": route, "status": "sat" if answer else "unsat", "encode_s": t1 - t0, "solve_s": t2 - t1,
            "total_s": t2 - t0, "verify_s": None, "verified": bool(tiling is not None and is_dappled(p, tiling)),
            "vars": enc.n_vars, "clauses": len(enc.hard), "peak_mb": _peak_mb(), "cpu_s": _cpu_s(),
        }
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
        "vars": p.size, "clauses": len(clauses), "peak_mb": _peak_mb(), "cpu_s": _cpu_s(),
    }


def whole_command(size: int, cond: str) -> dict:
    """The ``command`` route (module doc): one fresh ``tilesolve`` process, its JSON checked."""
    import os
    import shutil
    import tempfile

    from _measure import command

    exe = shutil.which("tilesolve") or os.path.join(os.path.dirname(sys.executable), "tilesolve")
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "t.json")
        wall, cpu, rss, rc, err = command([exe, "dappled", "solve", "--size", f"{size}x{size}", "--cond", cond,
                                           "--cyclic", "--method", "sat", "-o", out])
        assert rc == 0, err
        ok = command([exe, "verify", out])[3] == 0
    return {"route": "command", "status": "sat", "encode_s": None, "solve_s": None, "total_s": wall,
            "cpu_s": cpu, "verify_s": None, "verified": ok, "vars": size * size, "clauses": 0,
            "peak_mb": rss}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--size", type=int, default=1024, help="grid side (default 1024)")
    ap.add_argument("--cond", default="H0=3,V1=3", help="conditions, comma separated")
    ap.add_argument("--solver", default="cadical153")
    ap.add_argument("--no-naive", action="store_true", help="skip the naive baseline")
    ap.add_argument("--no-vectorised", action="store_true", help="skip the in-process vectorised route")
    ap.add_argument("--json", help="also write the rows as JSON here")
    ap.add_argument("--worker", help=argparse.SUPPRESS)
    a = ap.parse_args(argv)
    conds = a.cond.split(",")
    if a.worker:
        print(json.dumps(worker(a.worker, a.size, conds, a.solver)))
        return 0
    if a.solver != "cadical153":
        ap.error("the command runs the default solver, cadical153: compare routes with that one")
    rows = [whole_command(a.size, a.cond)]
    for route in ([] if a.no_vectorised else ["vectorised"]) + ["append"] + ([] if a.no_naive else ["naive"]):
        cmd = [sys.executable, __file__, "--worker", route, "--size", str(a.size), "--cond", a.cond,
               "--solver", a.solver]
        out = subprocess.run(cmd, capture_output=True, text=True, check=True)
        rows.append(json.loads(out.stdout.strip().splitlines()[-1]))
    rows[0]["clauses"] = rows[1]["clauses"]  # the command's formula is the other routes' (not naive's)
    print(f"cyclic {a.size}x{a.size}, L = {{{a.cond}}}, solver {a.solver}")
    hdr = f"{'route':<11} {'status':<7} {'vars':>9} {'clauses':>10} {'encode s':>9} {'solve s':>8} " \
          f"{'total s':>8} {'verify s':>9} {'CPU s':>7} {'peak MB':>8} {'B/cell':>6} verified"
    print(hdr)
    print("-" * len(hdr))
    for r in rows:
        es, ss, vs = ("-" if r[k] is None else f"{r[k]:.2f}" for k in ("encode_s", "solve_s", "verify_s"))
        print(f"{r['route']:<11} {r['status']:<7} {r['vars']:>9,} {r['clauses']:>10,} {es:>9} "
              f"{ss:>8} {r['total_s']:>8.2f} {vs:>9} {r['cpu_s']:>7.2f} {r['peak_mb']:>8.0f} "
              f"{r['peak_mb'] * 2**20 / (a.size * a.size):>6.0f} {r['verified']}")
    print("solve s includes loading the clauses into the solver; total = encode + solve (+ decode); the command's")
    print("total is its wall time (start-up, encoding, solving, verification, JSON); CPU s is user + sys of each")
    print("whole process (start-up included).")
    base = {r["route"]: r for r in rows}
    cmd, old = base["command"], base["append"]
    print(f"command / append route: {cmd['cpu_s'] / old['cpu_s']:.2f}x CPU, {cmd['peak_mb'] / old['peak_mb']:.2f}x "
          "peak memory (goal at 4096x4096: <= 60 s, <= 4 GB)")
    if a.json:
        from tilesolve.io.atomic import write_text_atomic

        write_text_atomic(a.json, json.dumps(rows, indent=2))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
