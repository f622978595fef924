"""Aperiodicity checks on Jeandel-Rao: squares and tori, against the plain board encoding.

Jeandel-Rao (arXiv:1506.06492, Fig. 3; ``tilesolve/data/tilesets/jeandel-rao.json``) tiles
every square and no torus. Two tables, each measured side by side in the same run:

Squares (a witness for the n x n square)
    ``plain``: the board family's one-hot colour encoding
    (:func:`tilesolve.encodings.wang.encode_wang`) solved by CaDiCaL, capped at ``--cap`` s;
    ``aperiodic``: :func:`tilesolve.engine.aperiodic.square_scan` with ``max_n = n`` (the
    tile-selection CNF with support clauses, its default search: CaDiCaL's initial phase
    false), which ends at the first verified witness. Both include encoding and loading the solver; the witness is checked
    with the board verifier. CPU seconds are printed beside wall seconds: on a shared machine
    they are the better measure of the work.
Tori (every p x q, 1 <= p, q <= ``--max-period``)
    ``plain``: the one-hot encoding, no proofs, one process, capped; ``aperiodic``:
    :func:`tilesolve.engine.aperiodic.sweep` on ``--workers`` processes, every refutation's
    DRAT proof checked by tilesolve.verify.drat.

Usage::

    python benchmarks/bench_aperiodic.py                       # squares 20..100, tori up to 8
    python benchmarks/bench_aperiodic.py --sizes 100 200 --max-period 24 --cap 300
"""

from __future__ import annotations

import argparse
import resource
import time


from tilesolve.deadline import Deadline
from tilesolve.encodings.wang import encode_wang
from tilesolve.engine.aperiodic import square_scan, sweep
from tilesolve.engine.sat import solve_cnf
from tilesolve.io.builtin_tilesets import load
from tilesolve.model.aperiodic import leg_colours
from tilesolve.model.board import Board, BoardProblem
from tilesolve.model.run import RunOptions
from tilesolve.model.solution import Status
from tilesolve.verify.board import board_violations


def rss_mib() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def cpu() -> float:
    """CPU seconds of this process and its finished children (the sweep's workers)."""
    own, kids = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + kids.ru_utime + kids.ru_stime


def plain(ws, board: Board, cap: float):
    t, c = time.perf_counter(), cpu()
    enc = encode_wang(BoardProblem(board, ws))
    r = solve_cnf(enc.hard, deadline=Deadline(cap), seed=1)
    return r.status, time.perf_counter() - t, cpu() - c


def fmt(status, t: float, cap: float) -> str:
    return f">{cap:.0f} (cap)" if status is Status.UNKNOWN else f"{t:.2f}"


def squares(ws, sizes, cap: float) -> None:
    print(f"\nSquares: a Jeandel-Rao witness for n x n (plain capped at {cap:.0f} s)")
    print(f"{'n':>5} {'cells':>7} {'plain s':>12} {'plain cpu':>10} {'aperiodic s':>12} {'aperiodic cpu':>14} "
          f"{'cells/s':>9} {'max RSS MiB':>12} {'ratio':>7} {'route':>12}")
    for n in sizes:
        st, tp, cp = plain(ws, Board.rect(n, n), cap)
        t, c = time.perf_counter(), cpu()
        certs, largest = square_scan(ws, n, RunOptions(seed=1, deadline=Deadline(None)))
        ta, ca = time.perf_counter() - t, cpu() - c
        w = certs[-1]
        assert largest == n and w.status == "tiles"
        assert not board_violations(BoardProblem(Board.rect(n, n), ws), leg_colours(ws, w.tiling))
        ratio = f"{tp / ta:.1f}x" if st is not Status.UNKNOWN else f">{cap / ta:.1f}x"
        print(f"{n:>5} {n * n:>7} {fmt(st, tp, cap):>12} {cp:>10.2f} {ta:>12.2f} {ca:>14.2f} {n * n / ta:>9.0f} "
              f"{rss_mib():>12.0f} "
              f"{ratio:>7} {w.method:>12}", flush=True)


def tori(ws, max_p: int, workers: int, cap: float) -> None:
    names = [f"torus {p}x{q}" for p in range(1, max_p + 1) for q in range(1, max_p + 1)]
    print(f"\nTori p x q, 1 <= p, q <= {max_p} ({len(names)} tori)")
    t, c = time.perf_counter(), cpu()
    done = 0
    for p in range(1, max_p + 1):
        for q in range(1, max_p + 1):
            left = cap - (time.perf_counter() - t)
            if left <= 0:
                break
            st, _, _ = plain(ws, Board.torus(q, p), left)
            done += st is Status.UNSAT
    tp, cp = time.perf_counter() - t, cpu() - c
    t, c = time.perf_counter(), cpu()
    certs, _ = sweep(ws, names, RunOptions(seed=1, workers=workers))
    ta, ca = time.perf_counter() - t, cpu() - c
    refuted = sum(c.status == "refuted" for c in certs)
    check = sum(float(c.evidence.get("proof_check_s", 0.0)) for c in certs)
    solve = sum(c.time_s for c in certs) - check
    print(f"{'encoding':>26} {'tori refuted':>13} {'wall s':>9} {'cpu s':>8} {'proofs checked':>15} "
          f"{'check s / solve s':>18}")
    capped = Status.UNKNOWN if done < len(names) else Status.UNSAT
    print(f"{'plain, no proofs, 1 proc':>26} {done:>13} {fmt(capped, tp, cap):>9} {cp:>8.1f} {'-':>15} {'-':>18}")
    print(f"{f'aperiodic, {workers} workers':>26} {refuted:>13} {ta:>9.2f} {ca:>8.1f} {refuted:>15} "
          f"{f'{check:.1f} / {solve:.1f}':>18}")
    if done == len(names):
        print(f"ratio plain/aperiodic wall: {tp / ta:.2f}x")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="*", default=[20, 40, 60, 100])
    ap.add_argument("--max-period", type=int, default=8)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--cap", type=float, default=120.0, help="seconds for each plain baseline run")
    args = ap.parse_args()
    ws, _ = load("jeandel-rao")
    if args.sizes:
        squares(ws, args.sizes, args.cap)
    if args.max_period:
        tori(ws, args.max_period, args.workers, args.cap)


if __name__ == "__main__":
    main()
