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

Large proofs against drat-trim (``--large``)
    The proofs ``tilesolve aperiodic check --proof-dir`` writes for the named Jeandel-Rao tori
    (the sweep's tile-selection encoding :func:`tilesolve.encodings.wang_tiles.encode_tiles`,
    CaDiCaL 1.5.3; written to ``--proof-dir``, or every ``.cnf``/``.drat`` pair already there
    with ``--large existing``), each checked from its files by tilesolve (reading included) and
    by drat-trim (``--drat-trim PATH``, or ``drat-trim`` on ``PATH``; build it with
    ``cc -O2 -o drat-trim drat-trim.c`` from github.com/marijnheule/drat-trim). Wall and CPU
    seconds are the best of ``--repeat`` runs; ``ratio`` is tilesolve's CPU time over
    drat-trim's (the goal: at most 1 on every proof tilesolve writes).

First run after an install (``--first-run``)
    ``tilesolve pack --kind wang --colors 3 --method sat --fix 0,0,5 --fix 0,1,7`` (unsat; unit
    propagation refutes it, and its DRAT proof of 2 lemmas is checked) with an empty numba
    cache (a fresh ``NUMBA_CACHE_DIR`` each run) against a cache holding the compiled DRAT
    kernels, in turns: wall and CPU time, peak RSS, and the ratio to warm (issue 19: the first
    run within 2x of a warm one; a tiny proof is checked by the interpreted kernels and
    compiles nothing, ``tilesolve.verify.drat.COLD_COMPILE_FROM``).

Usage::

    python benchmarks/bench_drat.py              # tori up to 12 x 12
    python benchmarks/bench_drat.py --max 6      # quick
    python benchmarks/bench_drat.py --large 13x13 16x16 15x16 14x16 --proof-dir /tmp/jr-proofs
    python benchmarks/bench_drat.py --first-run --repeat 5
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from _measure import best, child, peak_mib  # noqa: E402 - benchmarks/ is on sys.path

# The checker and the solvers are imported where they are used: --first-run measures whole
# commands from a small parent (a child's peak RSS starts from its parent's).

TILES = Path(__file__).resolve().parents[1] / "tilesolve" / "data" / "tilesets" / "jeandel-rao.json"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--max", type=int, default=12, help="largest torus side")
    ap.add_argument("--min", type=int, default=2, help="smallest torus side")
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--baseline-lines", type=int, default=3000)
    ap.add_argument("--large", nargs="+", metavar="PxQ", help="tori whose proofs to check against drat-trim, "
                    "or 'existing' for the pairs already in --proof-dir")
    ap.add_argument("--proof-dir", help="where the large proofs are written (default: a temporary folder)")
    ap.add_argument("--drat-trim", help="drat-trim binary (default: drat-trim on PATH)")
    ap.add_argument("--first-run", action="store_true", help="the unsat Wang packing whose tiny proof is checked: "
                    "empty numba cache against a filled one")
    args = ap.parse_args()
    if args.first_run:
        first_run(args)
        return
    if args.large:
        large(args)
        return
    import dratify
    from pysat.solvers import Solver

    from tilesolve.encodings.wang import encode_wang
    from tilesolve.model.board import Board, BoardProblem, WangTileSet
    from tilesolve.verify.drat import check_drat, dimacs_bytes

    doc = json.loads(TILES.read_text())
    tiles = WangTileSet(doc["tiles"], doc["colors"])
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
            enc = encode_wang(BoardProblem(Board.torus(q, p), tiles))
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


def write_proofs(tori: list[str], directory: Path) -> None:
    """CNF and DRAT proof of each torus, as ``aperiodic check --proof-dir`` makes them."""
    from pysat.solvers import Solver

    from tilesolve.encodings.wang_tiles import encode_tiles
    from tilesolve.io.builtin_tilesets import load
    from tilesolve.model.aperiodic import board_of
    from tilesolve.verify.drat import dimacs_bytes

    tiles = load("jeandel-rao")[0]
    for name in tori:
        p, q = (int(x) for x in name.split("x"))
        cnf = encode_tiles(board_of(f"torus {p}x{q}"), tiles).hard
        t = time.perf_counter()
        with Solver(name="cadical153", bootstrap_with=cnf.to_lists(), with_proof=True) as s:
            assert s.solve() is False, name
            proof = s.get_proof()
        print(f"torus {name}: solved in {time.perf_counter() - t:.1f} s, {len(proof)} proof lines", flush=True)
        (directory / f"torus-{name}.cnf").write_bytes(dimacs_bytes(cnf))
        (directory / f"torus-{name}.drat").write_text("".join(line + "\n" for line in proof))


def children_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def large(args) -> None:
    """tilesolve's checker against drat-trim on large proofs (see the module docstring)."""
    from tilesolve.verify.drat import check_drat, read_dimacs

    binary = args.drat_trim or shutil.which("drat-trim")
    directory = Path(args.proof_dir or tempfile.mkdtemp(prefix="jr-proofs-"))
    directory.mkdir(parents=True, exist_ok=True)
    if args.large != ["existing"]:
        write_proofs(args.large, directory)
    pairs = sorted((p for p in directory.glob("*.drat") if p.with_suffix(".cnf").is_file()),
                   key=lambda p: p.stat().st_size)
    check_drat([[1, 2], [1, -2], [-1, 2], [-1, -2]], ["1 0", "0"], kernels="compiled")  # load the kernels
    print(f"drat-trim: {binary or 'not found (give --drat-trim PATH)'}")
    print(f"{'proof':>28} {'MB':>6} {'lemmas':>8} {'checked':>8} {'ts wall':>8} {'ts cpu':>7} {'dt wall':>8} "
          f"{'dt cpu':>7} {'ratio':>6}")
    for drat in pairs:
        cnf = drat.with_suffix(".cnf")

        def ours():
            return check_drat(read_dimacs(cnf.read_bytes()), drat.read_bytes())

        t_ts, c_ts, r = best(ours, args.repeat)
        assert r.verified, (drat.name, r.reason)
        dt = dc = ratio = "-"
        if binary:
            t_dt = c_dt = float("inf")
            for _ in range(args.repeat):
                t, c = time.perf_counter(), children_cpu()
                out = subprocess.run([binary, os.fspath(cnf), os.fspath(drat)], capture_output=True, text=True).stdout
                t_dt, c_dt = min(t_dt, time.perf_counter() - t), min(c_dt, children_cpu() - c)
                assert "s VERIFIED" in out, (drat.name, out[-300:])
            dt, dc, ratio = f"{t_dt:.3f}", f"{c_dt:.3f}", f"{c_ts / c_dt:.2f}x"
        print(f"{drat.name:>28} {drat.stat().st_size / 1e6:>6.1f} {r.lemmas:>8} {r.checked:>8} {t_ts:>8.3f} "
              f"{c_ts:>7.3f} {dt:>8} {dc:>7} {ratio:>6}", flush=True)


#: The README's unsat Wang packing: unit propagation refutes it, its DRAT proof has 2 lemmas.
FIRST_RUN = ["pack", "--kind", "wang", "--colors", "3", "--method", "sat", "--fix", "0,0,5", "--fix", "0,1,7"]


def first_run(args) -> None:
    """The command a tiny proof is checked in, first after an install (an empty numba cache
    of its own: ``NUMBA_CACHE_DIR``) against warm (a cache holding the compiled DRAT kernels),
    in turns, ``--repeat`` times each (at least 3); medians."""
    script = Path(sys.executable).with_name("tilesolve")
    tilesolve = str(script) if script.exists() else shutil.which("tilesolve")
    repeat = max(3, args.repeat)
    with tempfile.TemporaryDirectory() as tmp:
        warm_cache = os.path.join(tmp, "warm")
        env = dict(os.environ, NUMBA_CACHE_DIR=warm_cache)
        subprocess.run([sys.executable, "-c", "from tilesolve.verify import drat; drat._kernels(0, 'compiled')"],
                       env=env, check=True)  # fills the warm cache
        argv = [tilesolve, *FIRST_RUN, "-o", os.path.join(tmp, "w.json")]
        runs: dict[str, list] = {"first run (empty cache)": [], "warm (kernels cached)": []}
        for i in range(repeat):
            cold_cache = os.path.join(tmp, f"cold{i}")
            for label, cache in zip(runs, (cold_cache, warm_cache)):
                r = child(argv, env=dict(os.environ, NUMBA_CACHE_DIR=cache))
                if r.returncode != 1:  # unsat
                    raise SystemExit(f"{' '.join(argv)} exited {r.returncode}: {r.stderr}")
                runs[label].append(r)
            compiled = [p.name for p in Path(cold_cache).rglob("_drat_kernels.*.nbi")]
    print(f"tilesolve {' '.join(FIRST_RUN)} -o w.json  (exit 1: unsat; {repeat} runs each, in turns; medians)")
    print(f"{'run':26s} {'wall_s':>7} {'cpu_s':>7} {'peak_MiB':>8} {'cpu/warm':>8} {'wall/warm':>9}")
    med = {label: {k: statistics.median(getattr(r, k) for r in rs) for k in ("wall", "cpu", "rss_mib")}
           for label, rs in runs.items()}
    warm = med["warm (kernels cached)"]
    for label, m in med.items():
        print(f"{label:26s} {m['wall']:7.2f} {m['cpu']:7.2f} {m['rss_mib']:8.0f} {m['cpu'] / warm['cpu']:8.2f} "
              f"{m['wall'] / warm['wall']:9.2f}")
    print(f"DRAT kernels compiled by the first run: {len(compiled)} (goal: first run <= 2x warm)")


if __name__ == "__main__":
    t0 = time.perf_counter()
    main()
    print(f"total {time.perf_counter() - t0:.1f} s")
