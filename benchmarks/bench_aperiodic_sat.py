"""The SAT route's Jeandel-Rao tori and squares: bands and cylinders against the whole formula.

Jeandel-Rao (``tilesolve/data/tilesets/jeandel-rao.json``) tiles every square and no torus.
Measured side by side in the same run:

Tori (every p x q, 1 <= p, q <= ``--max-period``)
    ``plain``: the board family's one-hot colour encoding, no proofs, one process (from
    bench_aperiodic.py); ``whole``: each torus's tile-selection CNF solved whole with its DRAT
    proof checked, one process (the route before bands); ``bands``:
    :func:`tilesolve.engine.aperiodic.sweep` on ``--workers`` processes, each torus refuted
    through its smallest refuted band, the band's proof checked against the whole torus's CNF.
    The two baselines have ``--cap`` seconds each and say how far they got; they go from the
    smallest torus up, so a capped baseline's rate (tori per second) is that of the small tori
    and its ratio flatters it.
Squares (a witness for each n in ``--sizes``)
    ``plain`` (capped) beside :func:`tilesolve.engine.aperiodic.square_scan` (the route is
    unchanged by bands: a square has no band to refute it).

CPU seconds count this process and its finished children (the sweep's workers).

Usage::

    python benchmarks/bench_aperiodic_sat.py                        # tori up to 12, no squares
    python benchmarks/bench_aperiodic_sat.py --max-period 24 --cap 300 --sizes 100 200
"""

from __future__ import annotations

import argparse
import time

from bench_aperiodic import cpu, fmt, plain, rss_mib

from tilesolve.deadline import Deadline
from tilesolve.engine.aperiodic import board_encoding, square_scan, sweep
from tilesolve.engine.routes import sat_route
from tilesolve.io.builtin_tilesets import load
from tilesolve.model.aperiodic import board_of, leg_colours
from tilesolve.model.board import Board, BoardProblem
from tilesolve.model.run import RunOptions
from tilesolve.model.solution import Status
from tilesolve.verify.board import board_violations


def baseline(ws, names, cap: float, whole: bool) -> tuple[int, float, float]:
    """Tori refuted within ``cap`` s by the one-hot encoding (``whole`` False) or the whole
    tile-selection CNF with checked proofs; wall and CPU seconds."""
    t, c = time.perf_counter(), cpu()
    done = 0
    for name in names:
        left = cap - (time.perf_counter() - t)
        if left <= 0:
            break
        if whole:
            enc = board_encoding(ws, name)
            st = sat_route(enc, RunOptions(seed=1, deadline=Deadline(left)), solver="cadical153",
                           t0=time.perf_counter()).status
        else:
            st = plain(ws, board_of(name), left)[0]
        done += st is Status.UNSAT
    return done, time.perf_counter() - t, cpu() - c


def tori(ws, max_p: int, workers: int, cap: float) -> None:
    names = [f"torus {p}x{q}" for p in range(1, max_p + 1) for q in range(1, max_p + 1)]
    print(f"\nTori p x q, 1 <= p, q <= {max_p} ({len(names)} tori); baselines capped at {cap:.0f} s")
    t, c = time.perf_counter(), cpu()
    certs, _ = sweep(ws, names, RunOptions(seed=1, workers=workers))
    ta, ca = time.perf_counter() - t, cpu() - c
    refuted = sum(x.status == "refuted" for x in certs)
    banded = sum("the proof refutes" in str(x.evidence.get("reason", "")) for x in certs)
    check = sum(float(x.evidence.get("proof_check_s", 0.0)) for x in certs)
    rows = [("plain, no proofs, 1 proc", *baseline(ws, names, cap, False), "-"),
            ("whole CNF + proofs, 1 proc", *baseline(ws, names, cap, True), "-"),
            (f"bands + proofs, {workers} workers", refuted, ta, ca, f"{banded} / {check:.1f}")]
    print(f"{'route':>30} {'refuted':>8} {'wall s':>10} {'cpu s':>8} {'tori/s':>7} {'max RSS MiB':>12} "
          f"{'by band / check s':>18}")
    for label, done, wall, cp, extra in rows:
        st = Status.UNSAT if done == len(names) else Status.UNKNOWN
        print(f"{label:>30} {done:>8} {fmt(st, wall, cap):>10} {cp:>8.1f} {done / wall:>7.2f} {rss_mib():>12.0f} "
              f"{extra:>18}")
    for label, done, wall, _, _ in rows[:2]:
        base = label.split(",")[0]
        if done == len(names):
            print(f"ratio {base}/bands: {wall / ta:.1f}x wall")
        else:  # the baseline stopped at its cap: compare tori refuted per second
            print(f"ratio {base}/bands: >= {(refuted / ta) / max(done / wall, 1e-9):.1f}x in tori refuted per second "
                  f"({base} refuted {done} of {len(names)} within its cap)")


def squares(ws, sizes, cap: float) -> None:
    print(f"\nSquares: a Jeandel-Rao witness for n x n (plain capped at {cap:.0f} s)")
    print(f"{'n':>5} {'plain s':>12} {'plain cpu':>10} {'route s':>9} {'route cpu':>10} {'cells/s':>9} "
          f"{'max RSS MiB':>12} {'ratio':>7}")
    for n in sizes:
        st, tp, cp = plain(ws, Board.rect(n, n), cap)
        t, c = time.perf_counter(), cpu()
        certs, largest = square_scan(ws, n, RunOptions(seed=1, deadline=Deadline(cap)))
        ta, ca = time.perf_counter() - t, cpu() - c
        if largest != n:
            print(f"{n:>5} {fmt(st, tp, cap):>12} {cp:>10.2f} {f'>{cap:.0f} (cap)':>9}")
            continue
        assert not board_violations(BoardProblem(Board.rect(n, n), ws), leg_colours(ws, certs[-1].tiling))
        ratio = f"{tp / ta:.1f}x" if st is not Status.UNKNOWN else f">{cap / ta:.1f}x"
        print(f"{n:>5} {fmt(st, tp, cap):>12} {cp:>10.2f} {ta:>9.2f} {ca:>10.2f} {n * n / ta:>9.0f} "
              f"{rss_mib():>12.0f} {ratio:>7}", flush=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--max-period", type=int, default=12)
    ap.add_argument("--sizes", type=int, nargs="*", default=[])
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--cap", type=float, default=120.0, help="seconds for each baseline (and each square)")
    args = ap.parse_args()
    ws, _ = load("jeandel-rao")
    if args.max_period:
        tori(ws, args.max_period, args.workers, args.cap)
    if args.sizes:
        squares(ws, args.sizes, args.cap)


if __name__ == "__main__":
    main()
