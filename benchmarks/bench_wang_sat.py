"""SAT and CP-SAT routes on brick Wang boards with a random boundary (brick paper Def. 2, 9).

For square rectangles (and a Möbius strip and a board with holes at the largest size)
with a random boundary colouring over 3 colours, times the CNF encoding
(:mod:`tilesolve.encodings.wang`) plus CaDiCaL, and CP-SAT's table constraints, and
prints one table. Every tiling is checked with the independent verifier.

Usage::

    python benchmarks/bench_wang_sat.py            # 50^2, 100^2, 200^2
    python benchmarks/bench_wang_sat.py --quick    # 50^2, 100^2
    python benchmarks/bench_wang_sat.py --no-cpsat

Goal (issue "Boards and brick Wang tilings"): a 200x200 brick Wang board with random
boundary decided by the SAT route in <= 10 s.
"""

from __future__ import annotations

import argparse
import time


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--no-cpsat", action="store_true")
    args = ap.parse_args()
    from tilesolve.families import board as wang
    from tilesolve.model.board import Board, BoardProblem, WangTileSet, random_boundary
    from tilesolve.verify.board import board_violations

    sizes = [50, 100] if args.quick else [50, 100, 200]
    boards = [(f"rect {s}x{s}", Board.rect(s, s)) for s in sizes]
    big = sizes[-1]
    boards += [(f"mobius {big}x{big}", Board.mobius(big, big)),
               (f"holes {big}x{big}", Board.with_holes(big, big, big * big // 400, 12, seed=1))]
    methods = ["sat"] + ([] if args.no_cpsat else ["cpsat"])
    print(f"{'board':>18} {'cells':>7} {'method':>6} {'vars':>9} {'clauses':>9} {'time s':>7} {'status':>7}")
    for name, b in boards:
        p = BoardProblem(b, WangTileSet.brick(3), random_boundary(b, 3, seed=1))
        for m in methods:
            if m == "cpsat" and b.n_cells > 50 * 50:
                continue  # CP-SAT is far slower here (see the table)
            t = time.perf_counter()
            s = wang.solve(p, method=m, seed=0, time_limit=120)
            dt = time.perf_counter() - t
            ok = not s.status.has_tiling or not board_violations(p, s.tiling)
            print(f"{name:>18} {b.n_cells:>7} {m:>6} {s.stats.get('variables', '-'):>9} "
                  f"{s.stats.get('clauses', '-'):>9} {dt:>7.2f} {s.status.value + ('' if ok else '!'):>7}")


if __name__ == "__main__":
    main()
