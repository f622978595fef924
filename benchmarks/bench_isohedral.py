"""Speed of isohedral drawings: the whole command, and its parts beside tactile's own fill.

The design is the IH41 example of examples/ (two J edges, two cubics each: 128 outline points
a tile). For regions of about 10^3, 10^4 and 10^5 tiles it times, in process (best of
``--repeat``):

* ``layout``: :func:`tilesolve.constructive.isohedral.layout` (template, prototile, the tiles
  meeting the region, colours);
* the baseline ``tactile``: the PyPI package's own ``fill_region_bounds`` over the same region
  plus each tile's outline moved by its motion (numpy), the route tilesolve would take by
  using the library whole (its fill is approximate: its tile count is printed);
* ``verify``: :func:`tilesolve.verify.isohedral.tiling_violations` (the torus check and the
  drawing's cover and colours);
* ``svg`` and ``png``: the pictures' bytes (the PNG at 4 pixels a unit, under 8192 a side).

Then the whole command as a fresh process at about 10^3 tiles: ``tilesolve isohedral draw ...
-o t.json --svg t.svg`` (and with ``--png``), beside ``tilesolve --version`` (the start-up floor),
with wall and CPU seconds, peak RSS, and the ratio command / floor.

Usage::

    python benchmarks/bench_isohedral.py            # 10^3, 10^4, 10^5 tiles
    python benchmarks/bench_isohedral.py --quick    # 10^3, 10^4
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile

import numpy as np

from _measure import best, best_child, peak_mib  # noqa: E402 - benchmarks/ is on sys.path

EDGES = ["bezier:0.25,0.34/0.35,-0.37/0.5,0.05/0.65,0.39/0.8,-0.43",
         "bezier:0.25,0.43/0.35,-0.16/0.5,0.03/0.65,0.29/0.8,-0.43"]


def command_table(repeat: int) -> None:
    exe = os.path.join(os.path.dirname(sys.executable), "tilesolve")
    floor = best_child([exe, "--version"], repeat)
    print(f"whole command, about 10^3 tiles (region 40x24 at 20 px a unit); best CPU of {repeat}")
    print(f"{'command':<44}{'wall s':>8}{'cpu s':>7}{'RSS MiB':>9}{'ratio':>7}")
    print(f"{'tilesolve --version (floor)':<44}{floor.wall:>8.2f}{floor.cpu:>7.2f}{floor.rss_mib:>9.0f}{1:>7.1f}")
    with tempfile.TemporaryDirectory() as d:
        base = [exe, "isohedral", "draw", "--type", "IH41", *[a for k, e in enumerate(EDGES) for a in ("--edge", f"{k}={e}")],
                "--region", "40x24", "--scale", "20", "-o", "t.json", "--svg", "t.svg"]
        for name, argv in (("draw -o t.json --svg t.svg", base), ("draw -o t.json --svg t.svg --png t.png", base + ["--png", "t.png"])):
            r = best_child(argv, repeat, cwd=d)
            print(f"{name:<44}{r.wall:>8.2f}{r.cpu:>7.2f}{r.rss_mib:>9.0f}{r.cpu / floor.cpu:>7.1f}")
        print(f"  ({r.stderr.strip().splitlines()[0]}; SVG {os.path.getsize(os.path.join(d, 't.svg')) / 1024:.0f} KiB)")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    command_table(args.repeat)  # first: a child's peak RSS starts from this process's at the fork

    import tactile

    from tilesolve.constructive.isohedral import layout
    from tilesolve.families import isohedral as facade
    from tilesolve.io.isohedral_json import png_bytes, svg_text
    from tilesolve.verify.isohedral import tiling_violations

    def tactile_fill(problem, outline):
        tl = tactile.IsohedralTiling(41)
        tl.parameters = list(problem.params)
        x0, y0, w, h = problem.region
        out = []
        for shape in tl.fill_region_bounds(x0, y0, x0 + w, y0 + h):
            m = np.array(shape.T).reshape(2, 3)
            out.append(outline @ m[:, :2].T + m[:, 2])
        return out

    sizes = [10**3, 10**4] + ([] if args.quick else [10**5])
    print(f"\nin process, best of {args.repeat}; seconds (wall)")
    print(f"{'target':>8}{'tiles':>8}{'layout':>8}{'MiB':>6}{'tactile':>9}{'tiles':>8}{'ratio':>7}{'verify':>8}"
          f"{'svg':>7}{'png':>7}{'ktiles/s':>9}")
    for n in sizes:
        side = (n * 0.6) ** 0.5
        problem = facade.problem(41, edges=EDGES, region=(0, 0, round(side / 0.6), round(side)), scale=4)
        t, _, tiling = best(lambda: layout(problem), args.repeat)
        peak = peak_mib(lambda: layout(problem))
        tb, _, polys = best(lambda: tactile_fill(problem, tiling.outline), args.repeat)
        tv, _, bad = best(lambda: tiling_violations(problem, tiling), 1)
        assert bad == [], bad[:3]
        ts, _, _ = best(lambda: svg_text(problem, tiling), 1)
        tp, _, _ = best(lambda: png_bytes(problem, tiling), 1)
        print(f"{n:>8,}{tiling.n_tiles:>8,}{t:>8.3f}{peak:>6.1f}{tb:>9.3f}{len(polys):>8,}{tb / t:>7.1f}{tv:>8.2f}"
              f"{ts:>7.2f}{tp:>7.2f}{tiling.n_tiles / t / 1e3:>9.0f}")
    print("ratio: tactile's fill (with the outlines moved) / layout, wall")


if __name__ == "__main__":
    main()
