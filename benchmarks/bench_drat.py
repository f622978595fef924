"""Proof checking against solving, on a sweep of real unsat instances: Jeandel-Rao tori.

The Jeandel-Rao set of 11 Wang tiles (Jeandel, Rao, arXiv:1506.06492, Fig. 3; shipped in
``tilesolve/data/tilesets``) is aperiodic, so every p x q torus is unsatisfiable and each
solve ends in a DRAT proof. For each torus (``p <= q <= --max``) the CNF is tilesolve's Wang
encoding (:func:`tilesolve.encodings.wang.encode_wang`), solved by CaDiCaL 1.5.3 with proof
logging (as ``sat_route`` does), and the proof is checked by

* ``new``: :func:`tilesolve.verify.drat.check_drat` (backward, core-first, compiled kernels),
* ``old``: the forward pure-Python engine (``engine="forward"``; the checker tilesolve had
  before, which also refused proofs over 5 M literals),
* ``dratify``: the independent checker from PyPI (its pure-Python engine; forward).

The baselines run only on proofs of at most ``--baseline-lines`` lines (they take minutes
beyond). Times are the best of ``--repeat`` runs; ``new/solve`` is the ratio the issue bounds
(proof checking at most 3x the solving time on the sweep, no proof skipped). The compiled
kernels are loaded before timing (numba's cache; the first build compiles them once).

Usage::

    python benchmarks/bench_drat.py              # tori up to 12 x 12
    python benchmarks/bench_drat.py --max 6      # quick
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import dratify
from _measure import best, peak_mib  # noqa: E402 - benchmarks/ is on sys.path
from pysat.solvers import Solver

from tilesolve.encodings.wang import encode_wang
from tilesolve.model.board import Board, BoardProblem, WangTileSet
from tilesolve.verify.drat import check_drat, dimacs_bytes

TILES = Path(__file__).resolve().parents[1] / "tilesolve" / "data" / "tilesets" / "jeandel-rao.json"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--max", type=int, default=12, help="largest torus side")
    ap.add_argument("--min", type=int, default=2, help="smallest torus side")
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--baseline-lines", type=int, default=3000)
    args = ap.parse_args()

    doc = json.loads(TILES.read_text())
    tiles = WangTileSet.from_nesw(doc["tiles"], doc["colors"])
    # load every compiled kernel once (numba loads each from its cache on first call)
    warm = encode_wang(BoardProblem(Board.torus(3, 3), tiles)).hard
    with Solver(name="cadical153", bootstrap_with=warm.to_lists(), with_proof=True) as s:
        s.solve()
        check_drat(warm, s.get_proof(), kernels="compiled", lemmas="all")
    print(f"Jeandel-Rao tori, CaDiCaL 1.5.3 with proofs; checkers: new (tilesolve backward), old (forward), "
          f"dratify {dratify.__version__} (python)")
    head = (f"{'torus':>7} {'clauses':>8} {'lines':>7} {'checked':>8} {'solve s':>8} {'new s':>7} {'klines/s':>8} {'new/solve':>9} "
            f"{'MiB':>6} {'old s':>7} {'old/new':>7} {'dratify s':>9} {'dr/new':>7}")
    print(head)
    tot = {"solve": 0.0, "new": 0.0}
    for p in range(args.min, args.max + 1):
        for q in range(p, args.max + 1):
            enc = encode_wang(BoardProblem(Board.torus(p, q), tiles))
            clauses = enc.hard.to_lists()

            def solve():
                with Solver(name="cadical153", bootstrap_with=clauses, with_proof=True) as s:
                    assert s.solve() is False, (p, q)
                    return s.get_proof()

            t_solve, _, proof = best(solve, args.repeat)
            t_new, _, r = best(lambda: check_drat(enc.hard, proof), args.repeat)
            assert r.verified, (p, q, r.reason)
            mib = peak_mib(lambda: check_drat(enc.hard, proof))
            tot["solve"] += t_solve
            tot["new"] += t_new
            old = dr = "-"
            ratio_old = ratio_dr = "-"
            if len(proof) <= args.baseline_lines:
                t_old, _, ro = best(lambda: check_drat(clauses, proof, engine="forward"), args.repeat)
                assert ro.verified, (p, q, ro.reason)
                cnf = dratify.parse_dimacs(dimacs_bytes(enc.hard).decode())
                text = "".join(line + "\n" for line in proof)
                t_dr, _, rd = best(lambda: dratify.check_proof(cnf, text, engine="python"), args.repeat)
                assert rd.ok, (p, q)
                old, ratio_old = f"{t_old:.3f}", f"{t_old / t_new:.1f}x"
                dr, ratio_dr = f"{t_dr:.3f}", f"{t_dr / t_new:.1f}x"
            print(f"{p:>3}x{q:<3} {len(clauses):>8} {len(proof):>7} {r.checked:>8} {t_solve:>8.3f} {t_new:>7.3f} "
                  f"{len(proof) / t_new / 1e3:>8.1f} {t_new / t_solve:>8.2f}x {mib:>6.1f} {old:>7} {ratio_old:>7} {dr:>9} {ratio_dr:>7}", flush=True)
    print(f"sweep: solving {tot['solve']:.2f} s, checking {tot['new']:.2f} s, check/solve = "
          f"{tot['new'] / tot['solve']:.2f}x (goal <= 3x, every proof checked)")


if __name__ == "__main__":
    t0 = time.perf_counter()
    main()
    print(f"total {time.perf_counter() - t0:.1f} s")
