"""Build the polyomino sampler's correction tables (Ostromoukhov, "Sampling with polyominoes",
SIGGRAPH 2007: "the variety of structural indices and associated sampling point positions are
computed during the offline optimization process, and tabulated"; class notes Part IV).

The paper's own tables are not in the seeds; this script redoes its offline step
(:func:`tilesolve.constructive.importance.learn_corrections`): the sampler (children ranked in a
random order, samples at their tiles' centroids) at many constant densities on the unit square,
each point set relaxed by Lloyd steps (scipy's Voronoi cells), the displacement of every sample
away from the border recorded in its tile's frame under its structural index (which of 8
sectors around it hold a neighbour) and density bin; the table keeps each entry's mean and the
spread around it. Seeded: the same command writes the same file.

Usage::

    python scripts/build_importance_corrections.py                     # writes the shipped file
    python scripts/build_importance_corrections.py --runs 4 -o /tmp/t.json   # a quick, smaller table
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time

DEFAULT_OUT = os.path.join(os.path.dirname(__file__), "..", "tilesolve", "data", "importance",
                           "polyomino-corrections.json")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tiles", default="x-pentomino,chair", help="comma-separated tiles (default: %(default)s)")
    ap.add_argument("--runs", type=int, default=40, help="point sets per tile (default: %(default)s)")
    ap.add_argument("--n-min", type=float, default=5000, help="fewest samples of a set (default: %(default)s)")
    ap.add_argument("--n-max", type=float, default=25000, help="most samples of a set (default: %(default)s)")
    ap.add_argument("--steps", type=int, default=8, help="Lloyd steps per set (default: %(default)s)")
    ap.add_argument("--bins", type=int, default=4, help="density bins (default: %(default)s)")
    ap.add_argument("--seed", type=int, default=2007, help="seed (default: %(default)s)")
    ap.add_argument("-o", "--output", default=DEFAULT_OUT, help="the table file (default: the shipped one)")
    args = ap.parse_args(argv)

    from tilesolve.constructive.importance import CORRECTIONS_FORMAT, learn_corrections
    from tilesolve.io.atomic import write_text_atomic
    from tilesolve.model.importance import TILES

    tiles = args.tiles.split(",")
    bad = [t for t in tiles if t not in TILES]
    if bad or args.runs < 1 or args.steps < 1 or args.bins < 1 or not 0 < args.n_min <= args.n_max:
        print(f"build_importance_corrections: error: bad arguments ({', '.join(bad) or 'ranges'})", file=sys.stderr)
        return 2
    command = "python scripts/build_importance_corrections.py " + " ".join(
        f"--{k.replace('_', '-')} {v}" for k, v in (("tiles", args.tiles), ("runs", args.runs), ("n_min", args.n_min),
                                                    ("n_max", args.n_max), ("steps", args.steps),
                                                    ("bins", args.bins), ("seed", args.seed)))
    tables = []
    for i, tile in enumerate(tiles):
        t0 = time.perf_counter()
        table = learn_corrections(tile, runs=args.runs, n_min=args.n_min, n_max=args.n_max, steps=args.steps,
                                  bins=args.bins, seed=args.seed + i)
        table.provenance = {"seed": args.seed + i, "runs": args.runs, "n_min": args.n_min, "n_max": args.n_max,
                            "lloyd_steps": args.steps, "samples": int(table.count.sum()),
                            "entries_seen": int((table.count > 0).sum())}
        tables.append(table.to_dict())
        print(f"{tile}: {int(table.count.sum()):,} samples, {int((table.count > 0).sum())} of {table.count.size} "
              f"entries seen, {time.perf_counter() - t0:.0f} s", file=sys.stderr)
    doc = {"format": CORRECTIONS_FORMAT + "-file", "version": 1,
           "about": "Correction offsets of the polyomino importance sampler (Ostromoukhov 2007, 'Sampling with "
                    "polyominoes': sampling point positions by structural index, learnt offline). Rebuilt by this "
                    "project, not the paper's tables: the sampler at constant densities on the unit square, "
                    "Lloyd-relaxed (scipy Voronoi), the mean displacement of each sample in its tile's frame by "
                    "structural index (neighbours in 8 sectors) and density bin, and the spread around it.",
           "command": command, "tables": tables}
    write_text_atomic(args.output, json.dumps(doc, separators=(",", ":")) + "\n")
    print(f"wrote {args.output}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
