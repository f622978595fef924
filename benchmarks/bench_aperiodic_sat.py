"""The SAT route's Jeandel-Rao tori and squares: shared bands against the whole formula and per-torus bands.

Jeandel-Rao (``tilesolve/data/tilesets/jeandel-rao.json``) tiles every square and no torus.
Measured side by side in the same run:

Tori (every p x q, 1 <= p, q <= ``--max-period``)
    ``shared bands``: :func:`tilesolve.engine.aperiodic.sweep` on ``--workers`` processes: one
    band per torus height (and per width for the tori left) solved and its proof checked once,
    the trimmed proof renamed into every torus that holds the band
    (:mod:`tilesolve.engine.aperiodic_bands`); then 8 sampled refutations re-checked as
    ``verify`` does, against their re-derived CNF. Baselines, one process each, capped at
    ``--cap`` s, the tori in a seeded random order (a capped baseline's rate is the mix's):
    ``plain`` the board family's one-hot colour encoding, no proofs (from bench_aperiodic.py);
    ``whole`` each torus's tile-selection CNF with its DRAT proof checked; ``per-torus bands``
    each torus through its own bands (:func:`tilesolve.engine.aperiodic.decide`: the route
    before shared bands). A capped baseline is compared in tori refuted per CPU second.
Squares (a witness for each n in ``--sizes``, each seed of ``--seeds``)
    :func:`tilesolve.engine.aperiodic.square_scan` with its search ``phase`` (the default: the
    full formula, CaDiCaL's initial phase false and its saved phases; the seed changes nothing)
    beside its search ``portfolio`` (the route before: full and guided formulas on two
    processes, the seed's random phases), ``race`` (that portfolio, its full formula searched
    as ``phase``), ``markov`` (the race with the guided run replaced by the full formula phased
    by the constructive route's window: steered, not unguided; its ``won by`` column says which
    run found each witness), ``grams`` (the race with the guided run restricted to the short runs
    of a 100x100 witness of ``phase``: unguided by any outside tiling) and ``plain`` (the one-hot
    colour encoding, one run),
    every run capped at ``--cap`` s; median and max CPU by route, and each route's CPU over
    ``phase``'s on the same seed.

CPU seconds count this process and its finished children (the sweep's workers).

Usage::

    python benchmarks/bench_aperiodic_sat.py                        # tori up to 12, no squares
    python benchmarks/bench_aperiodic_sat.py --max-period 24 --cap 300 --sizes 100 200
    python benchmarks/bench_aperiodic_sat.py --max-period 24 --cap 300 --baselines plain
    python benchmarks/bench_aperiodic_sat.py --max-period 0 --sizes 100 200 400 --cap 600
    python benchmarks/bench_aperiodic_sat.py --max-period 0 --sizes 200 400 --cap 150 --seeds 1 \
        --routes phase race grams markov plain
"""

from __future__ import annotations

import argparse
import random
import tempfile
import time

from bench_aperiodic import cpu, fmt, plain, rss_mib

from tilesolve.deadline import Deadline
from tilesolve.engine.aperiodic import board_encoding, board_problem, decide, square_scan, sweep
from tilesolve.engine.certificates import recheck_unsat
from tilesolve.engine.routes import sat_route
from tilesolve.families.aperiodic_square import steering
from tilesolve.io.builtin_tilesets import load
from tilesolve.model.aperiodic import board_of, leg_colours
from tilesolve.model.board import Board, BoardProblem
from tilesolve.model.run import RunOptions
from tilesolve.model.solution import Status
from tilesolve.verify.board import board_violations


#: The tori's baselines (each one process, capped).
BASELINES = ("plain", "whole", "per-torus bands")


def baseline(ws, names, cap: float, how: str) -> tuple[int, float, float]:
    """Tori refuted within ``cap`` s, one process, in a seeded random order (so that the rate of a
    capped run is that of the whole mix): ``plain`` the one-hot encoding, no proofs; ``whole``
    each torus's tile-selection CNF with its proof checked; ``per-torus bands`` each torus by
    :func:`tilesolve.engine.aperiodic.decide` (its own bands, the route before shared bands).
    Returns the count, wall and CPU seconds."""
    order = list(names)
    random.Random(1).shuffle(order)
    t, c = time.perf_counter(), cpu()
    done = 0
    for name in order:
        left = cap - (time.perf_counter() - t)
        if left <= 0:
            break
        if how == "whole":
            enc = board_encoding(ws, name)
            st = sat_route(enc, RunOptions(seed=1, deadline=Deadline(left)), solver="cadical153",
                           t0=time.perf_counter()).status
        elif how == "per-torus bands":
            st = Status.UNSAT if decide(ws, name, RunOptions(seed=1, deadline=Deadline(left))).status == "refuted" \
                else Status.UNKNOWN
        else:
            st = plain(ws, board_of(name), left)[0]
        done += st is Status.UNSAT
    return done, time.perf_counter() - t, cpu() - c


def tori(ws, max_p: int, workers: int, cap: float, proof_dir: str, baselines=BASELINES) -> None:
    names = [f"torus {p}x{q}" for p in range(1, max_p + 1) for q in range(1, max_p + 1)]
    print(f"\nTori p x q, 1 <= p, q <= {max_p} ({len(names)} tori); baselines capped at {cap:.0f} s")
    t, c = time.perf_counter(), cpu()
    certs, _ = sweep(ws, names, RunOptions(seed=1, workers=workers), proof_dir=proof_dir)
    ta, ca = time.perf_counter() - t, cpu() - c
    refuted = sum(x.status == "refuted" for x in certs)
    shared = [x for x in certs if "band" in x.evidence]
    bands = {(x.evidence["band"], x.board.split()[1].split("x")[0 if "column" in x.evidence["band"] else 1]): x
             for x in shared}
    check = sum(float(x.evidence.get("proof_check_s", 0.0)) for x in bands.values()) + \
        sum(float(x.evidence.get("proof_check_s", 0.0)) for x in certs if "band" not in x.evidence)
    lines = sorted(int(x.evidence.get("proof_lines", 0)) for x in bands.values())
    kept = sorted(int(x.evidence.get("proof_lemmas", 0)) for x in bands.values())
    rows = [(f"shared bands + proofs, {workers} workers", refuted, ta, ca,
             f"{len(shared)} by {len(bands)} / {check:.1f}")]
    rows += [(f"{how}, 1 proc", *baseline(ws, names, cap, how), "-") for how in baselines]
    print(f"{'route':>36} {'refuted':>8} {'wall s':>10} {'cpu s':>8} {'tori/s':>7} {'max RSS MiB':>12} "
          f"{'tori by bands / check s':>24}")
    for label, done, wall, cp, extra in rows:
        st = Status.UNSAT if done == len(names) else Status.UNKNOWN
        print(f"{label:>36} {done:>8} {fmt(st, wall, cap):>10} {cp:>8.1f} {done / wall:>7.2f} {rss_mib():>12.0f} "
              f"{extra:>24}")
    if bands:
        print(f"band proofs: median {lines[len(lines) // 2]} lines as solved, largest {lines[-1]}; trimmed to median "
              f"{kept[len(kept) // 2]}, largest {kept[-1]} lemmas")
    for label, done, wall, cp, _ in rows[1:]:
        base = label.split(",")[0]
        if done == len(names):
            print(f"ratio {base}/shared bands: {wall / ta:.1f}x wall, {cp / ca:.1f}x CPU")
        else:  # the baseline stopped at its cap: compare tori refuted per CPU second
            print(f"ratio {base}/shared bands: >= {(refuted / ca) / max(done / cp, 1e-9):.1f}x in tori refuted per CPU "
                  f"second ({base} refuted {done} of {len(names)} within its cap)")
    sample = random.Random(2).sample([x for x in certs if x.status == "refuted"], min(8, refuted))
    t = time.perf_counter()
    ok = sum(recheck_unsat(board_problem(ws, x.board), x.evidence, proof_dir).ok for x in sample)
    print(f"verify: {ok} of {len(sample)} sampled refutations re-checked against their re-derived CNF "
          f"({time.perf_counter() - t:.1f} s)")


def square_run(ws, n: int, seed: int, cap: float, route: str) -> tuple[float, float, str]:
    """One capped witness search for the ``n x n`` square: wall and CPU seconds (wall ``inf``
    when capped) and the method of the witness. ``route``: ``plain`` the one-hot colour
    encoding (seed 1's random phases), else :func:`tilesolve.engine.aperiodic.square_scan` with
    that search (``markov`` steered by the seed's window); a witness is checked by the board
    verifier."""
    t, c = time.perf_counter(), cpu()
    method = "-"
    if route == "plain":
        st = plain(ws, Board.rect(n, n), cap)[0]
        ok = st is Status.SAT
    else:
        window = steering(ws, seed) if route == "markov" else None
        certs, largest = square_scan(ws, n, RunOptions(seed=seed, deadline=Deadline(cap)), search=route,
                                     window=window)
        ok = largest == n
        if ok:
            assert not board_violations(BoardProblem(Board.rect(n, n), ws), leg_colours(ws, certs[-1].tiling))
            method = certs[-1].method
    return (time.perf_counter() - t if ok else float("inf")), cpu() - c, method


def _cell(xs: list[float], cap: float) -> str:
    return " ".join(f"{x:.1f}" if x != float("inf") else f">{cap:.0f}" for x in xs)


def squares(ws, sizes, cap: float, seeds, routes) -> None:
    """Every route of ``routes`` on every size and seed (``plain`` once per size: its seed is
    fixed), capped at ``cap`` s; the paired ratio is a route's CPU over ``phase``'s on the same
    seed (a capped run's CPU is a lower bound: ``>``)."""
    print(f"\nSquares: a Jeandel-Rao witness for n x n, seeds {list(seeds)}, each run capped at {cap:.0f} s "
          "(CPU: this process and its finished workers)")
    print(f"{'n':>5} {'route':>10} {'wall s by seed':>28} {'cpu s by seed':>28} {'median cpu':>11} {'max cpu':>9} "
          f"{'max wall':>9} {'cpu / phase':>12} {'max RSS MiB':>12}  won by")
    for n in sizes:
        base: list[tuple[float, float, str]] = []
        for route in routes:
            runs = [square_run(ws, n, seed, cap, route) for seed in (seeds if route != "plain" else seeds[:1])]
            walls, cpus = [w for w, _, _ in runs], [c for _, c, _ in runs]
            if route == "phase":
                base = runs
            ratio = "-"
            if base and route != "phase":
                r = sorted(c / b[1] for (_, c, _), b in zip(runs, base))
                capped = any(w == float("inf") for w in walls)
                ratio = f"{'>' if capped else ''}{r[len(r) // 2]:.1f}x"
            mw = max(walls)
            print(f"{n:>5} {route:>10} {_cell(walls, cap):>28} {_cell(cpus, 1e9):>28} "
                  f"{sorted(cpus)[len(cpus) // 2]:>11.1f} {max(cpus):>9.1f} "
                  f"{(f'{mw:.1f}' if mw != float('inf') else f'>{cap:.0f}'):>9} {ratio:>12} {rss_mib():>12.0f}  "
                  f"{', '.join(m for _, _, m in runs)}",
                  flush=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--max-period", type=int, default=12)
    ap.add_argument("--sizes", type=int, nargs="*", default=[])
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--cap", type=float, default=120.0, help="seconds for each baseline (and each square)")
    ap.add_argument("--seeds", type=int, nargs="*", default=[1, 2, 3], help="the squares' seeds")
    ap.add_argument("--baselines", nargs="*", default=list(BASELINES), choices=BASELINES,
                    help="the tori's baselines, each capped at --cap s")
    ap.add_argument("--routes", nargs="*", default=["phase", "portfolio", "plain"],
                    choices=["phase", "portfolio", "race", "markov", "grams", "plain"], help="the squares' routes, phase first (the ratios' base)")
    args = ap.parse_args()
    ws, _ = load("jeandel-rao")
    if args.max_period:
        with tempfile.TemporaryDirectory() as proof_dir:
            tori(ws, args.max_period, args.workers, args.cap, proof_dir, args.baselines)
    if args.sizes:
        squares(ws, args.sizes, args.cap, args.seeds, args.routes)


if __name__ == "__main__":
    main()
