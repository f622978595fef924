"""tilesolve against Kaplan's heesch-sat, shape by shape, in the same run.

The same free polyforms (tilesolve's generator; ``--set``) go to both classifiers with the same
limits: heesch-sat's ``sat -isohedral -maxlevel L`` as a fresh process per shape (its wall and
CPU seconds from ``os.wait4``), and tilesolve's :func:`tilesolve.engine.shapes.classify` in this
process (lattice tilings, closed surrounds for isohedral tilings with any number of copies per
period, coronas up to ``L``, tori of up to ``--max-copies`` copies for periodic witnesses),
followed by the independent verification of its report
(:func:`tilesolve.verify.shapes.shapes_violations`; a non-tiler's refuted level carries a DRAT
proof checked inside ``classify``). Both columns are charged for everything their answer needs;
tilesolve's answer is certified, heesch-sat's is not. heesch-sat's start-up is paid by every
shape (a process each); tilesolve's, once per process (the refutation checker's modules and
its compiled DRAT kernels, under a second of CPU), is measured before the first shape and
printed apart: a set's row ``+ start-up`` charges all of it to that set's shapes, and ``all
sets + start-up`` charges it once (a census is one process for many shapes).

Answers agree when both say isohedral, both say non-tiler with the same Heesch number, or
heesch-sat says inconclusive and tilesolve says inconclusive or ``periodic`` (a k-isohedral
tiling that heesch-sat cannot see). When heesch-sat says isohedral and tilesolve ``periodic``,
both call it a tiler, but tilesolve found only non-isohedral torus tilings: counted apart as
``tiler``. Anything else is a disagreement, printed.

heesch-sat is not part of the project: build it from its sources (``src/sat``) and give the
binary with ``--heesch-sat PATH`` or ``HEESCH_SAT=PATH``. Without it the script says so and
prints tilesolve's column alone.

Cells are passed in heesch-sat's coordinates: ominoes and hexes (60-degree axial) are the same
as tilesolve's; heesch-sat's triangles are tilesolve's translated by ``(-1, -1)``.

Run from the repository root::

    HEESCH_SAT=/path/to/heesch-sat/src/sat python benchmarks/bench_heesch_sat.py --set hex6
    python benchmarks/bench_heesch_sat.py --set omino7 --set iamond8 --heesch-sat /path/to/sat
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys
import tempfile
import time
from collections import defaultdict

from _measure import child  # noqa: E402 - benchmarks/ is on sys.path

#: The shape sets: (grid, size), holeless free polyforms.
SETS = {"hex6": ("hex", 6), "hex5": ("hex", 5), "hex7": ("hex", 7), "omino6": ("omino", 6),
        "omino7": ("omino", 7), "iamond7": ("iamond", 7), "iamond8": ("iamond", 8)}
_FLAG = {"omino": "O", "hex": "H", "iamond": "I"}
_SHIFT = {"omino": 0, "hex": 0, "iamond": -1}


def heesch_sat_line(grid_name: str, cells) -> str:
    """One shape as a naked record of heesch-sat's text format."""
    d = _SHIFT[grid_name]
    return _FLAG[grid_name] + "? " + " ".join(f"{x + d} {y + d}" for x, y in cells) + "\n"


def parse_heesch_sat(out: str) -> tuple[str, int | None, int | None]:
    """``(verdict, hc, hh)`` from heesch-sat's output record (second line)."""
    lines = out.splitlines()
    if len(lines) < 2:
        return "no answer", None, None
    head = lines[1].split()
    kind = {"I": "isohedral", "~": "non-tiler", "!": "inconclusive", "#": "anisohedral", "O": "holes"}
    verdict = kind.get(head[0], "unknown")
    if verdict == "non-tiler":
        return verdict, int(head[1]), int(head[2])
    return verdict, None, None


def agree(ours, heesch) -> str:
    """``yes``, ``yes (periodic)``, ``tiler`` or ``NO`` (module docstring)."""
    verdict, hc = heesch[0], heesch[1]
    if ours.verdict == verdict == "isohedral":
        return "yes"
    if ours.verdict == verdict == "non-tiler":
        return "yes" if ours.heesch == hc else "NO"
    if verdict == "inconclusive" and ours.verdict == "inconclusive":
        return "yes"
    if verdict == "inconclusive" and ours.verdict == "periodic":
        return "yes (periodic)"
    if verdict == "isohedral" and ours.verdict == "periodic":
        return "tiler"
    return "NO"


def find_heesch_sat(given: str | None) -> str | None:
    """The heesch-sat ``sat`` binary from ``--heesch-sat`` or ``HEESCH_SAT``, if it runs."""
    path = given or os.environ.get("HEESCH_SAT")
    if path and os.path.isdir(path):
        path = os.path.join(path, "sat")
    return path if path and os.path.isfile(path) and os.access(path, os.X_OK) else None


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--set", dest="sets", action="append", choices=sorted(SETS),
                    help="shape set (repeatable; default hex6: the 81 holeless 6-hexes)")
    ap.add_argument("--heesch-sat", default=None, metavar="PATH", help="heesch-sat's sat binary (or $HEESCH_SAT)")
    ap.add_argument("--max-level", type=int, default=3)
    ap.add_argument("--max-copies", type=int, default=2)
    ap.add_argument("--limit", type=int, default=None, help="the first N shapes of each set")
    ap.add_argument("--per-shape", action="store_true", help="print every shape's row")
    args = ap.parse_args()
    binary = find_heesch_sat(args.heesch_sat)
    if binary is None:
        print("heesch-sat: ABSENT (give its sat binary with --heesch-sat PATH or HEESCH_SAT=PATH); "
              "tilesolve's column alone")
    else:
        print(f"heesch-sat: {binary} (-isohedral -maxlevel {args.max_level}, one process per shape)")
    from tilesolve.constructive.polyforms import free_polyforms
    from tilesolve.engine.shapes import classify
    from tilesolve.model.shapes import ShapesProblem
    from tilesolve.verify.shapes import shapes_violations

    print(f"tilesolve: classify (lattices, closed surrounds, coronas up to {args.max_level}, tori up to "
          f"{args.max_copies} copies) + verification, in process, one core")
    c = time.process_time()
    importlib.import_module("tilesolve.engine.certificates")  # the refutation path's modules
    from tilesolve.verify.drat import check_drat

    check_drat([[1], [-1]], ["0"], kernels="compiled")  # loads the compiled DRAT kernels
    startup = time.process_time() - c
    print(f"tilesolve start-up, once per process (the checker's modules, the compiled DRAT kernels): "
          f"{startup * 1000:.0f} ms of CPU; no shape pays it in the rows below; a set's '+ start-up' row "
          "charges all of it to that set's shapes ('all sets + start-up': once)")
    grand = defaultdict(float)
    for name in args.sets or ["hex6"]:
        grid_name, size = SETS[name]
        shapes = free_polyforms(grid_name, size, holes=False)[: args.limit]
        groups: dict = defaultdict(lambda: defaultdict(float))
        disagree = []
        if args.per_shape:
            print(f"{'#':>4} {'tilesolve':<18}{'wall s':>8}{'cpu s':>8}  {'heesch-sat':<18}{'wall s':>8}"
                  f"{'cpu s':>8}{'cpu ratio':>10}  agree")
        with tempfile.TemporaryDirectory() as d:
            for i, s in enumerate(shapes):
                p = ShapesProblem("classify", (s,), max_level=args.max_level, max_copies=args.max_copies)
                t, c = time.perf_counter(), time.process_time()
                r = classify(p, seed=0).report
                bad = shapes_violations(p, r)
                wall, cpu = time.perf_counter() - t, time.process_time() - c
                if bad:
                    sys.exit(f"tilesolve's report of shape {i} failed verification: {bad[0]}")
                ours = r.verdict + (f" H={r.heesch}" if r.heesch is not None and r.verdict != "isohedral" else "")
                g = groups[ours]
                g["n"] += 1
                g["ts_wall"] += wall
                g["ts_cpu"] += cpu
                hs, ok, hrow = None, "", ""
                if binary is not None:
                    f = os.path.join(d, "shape.txt")
                    with open(f, "w") as fh:
                        fh.write(heesch_sat_line(grid_name, s.cells))
                    run = child([binary, "-isohedral", "-maxlevel", str(args.max_level), f])
                    hs = parse_heesch_sat(run.stdout)
                    ok = agree(r, hs)
                    g["hs_wall"] += run.wall
                    g["hs_cpu"] += run.cpu
                    g["agree"] += ok.startswith("yes")
                    g["tiler"] += ok == "tiler"
                    if ok != "yes":
                        disagree.append((i, s.cells, ours, hs))
                    label = hs[0] + (f" H={hs[1]}" if hs[1] is not None else "")
                    hrow = f"{label:<18}{run.wall:>8.3f}{run.cpu:>8.3f}{run.cpu / max(cpu, 1e-9):>10.2f}  {ok}"
                if args.per_shape:
                    print(f"{i:>4} {ours:<18}{wall:>8.3f}{cpu:>8.3f}  {hrow}", flush=True)
        n = len(shapes)
        print(f"\n{name}: {n} holeless free {size}-{grid_name}es" if grid_name == "hex"
              else f"\n{name}: {n} holeless free {size}-{grid_name}s")
        print(f"{'tilesolve verdict':<22}{'shapes':>7}{'ts ms/shape':>13}{'hs ms/shape':>13}"
              f"{'ts cpu ms':>11}{'hs cpu ms':>11}{'hs/ts cpu':>11}{'agree':>7}{'tiler':>7}")
        tot = defaultdict(float)
        for key in sorted(groups):
            g = groups[key]
            for k, v in g.items():
                tot[k] += v
            _row(key, g, binary)
        _row("all", tot, binary)
        _row("all + start-up", {**tot, "ts_cpu": tot["ts_cpu"] + startup, "ts_wall": tot["ts_wall"] + startup},
             binary)
        for k, v in tot.items():
            grand[k] += v
        for i, cells, ours, hs in disagree:
            print(f"  shape {i} {list(cells)}: tilesolve {ours}, heesch-sat {hs[0]}"
                  + (f" H={hs[1]}" if hs[1] is not None else ""))
    if len(args.sets or []) > 1:
        print()
        _row("all sets", grand, binary)
        _row("all sets + start-up", {**grand, "ts_cpu": grand["ts_cpu"] + startup,
                                     "ts_wall": grand["ts_wall"] + startup}, binary)


def _row(label: str, g, binary) -> None:
    n = g["n"]
    ts, tc = g["ts_wall"] / n * 1000, g["ts_cpu"] / n * 1000
    if binary is None:
        print(f"{label:<22}{int(n):>7}{ts:>13.1f}{'-':>13}{tc:>11.1f}{'-':>11}{'-':>11}{'-':>7}")
        return
    hs, hc = g["hs_wall"] / n * 1000, g["hs_cpu"] / n * 1000
    print(f"{label:<22}{int(n):>7}{ts:>13.1f}{hs:>13.1f}{tc:>11.1f}{hc:>11.1f}{hc / max(tc, 1e-9):>11.2f}"
          f"{int(g['agree']):>7}{int(g['tiler']):>7}")


if __name__ == "__main__":
    main()
