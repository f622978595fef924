"""``tilesolve wall-lines``: line-length histograms of brick walls (004 §5, Fig. 22).

::

    tilesolve wall-lines [--method procedural|npd|wall ...] [--max-line N ...] [--size WxH] [--samples K]
                         [--seed S] [--colors C] [-o TABLE.json|TABLE.csv] [--svg H.svg] [--png H.png]
"""

from __future__ import annotations

import csv
import io
import json
import math

import click

from tilesolve.cli import options as opt
from tilesolve.cli.common import say
from tilesolve.cli.outputs import OutputFile, Outputs
from tilesolve.errors import InvalidProblem

__all__ = ["wall_lines"]

_NAMES = {"procedural": "PD (procedural)", "npd": "NPD (Kaji cyclic dappling)", "wall": "wall (Kaji dappling)"}
_DIRECTIONS = ("vertical", "horizontal")


def _rows(hists) -> list[dict]:
    """One table row per generator, limit and direction."""
    out = []
    for h in hists:
        for d in _DIRECTIONS:
            counts = h.counts(d)
            c = h.clamp(d)
            out.append({"method": h.method, "n": h.n, "direction": d, "lines": c["lines"],
                        "longest": h.longest[0 if d == "horizontal" else 1], "at_n": c["at_n"],
                        "at_n_minus_1": c["at_n_minus_1"], "ratio": c["ratio"],
                        "counts": [int(v) for v in counts]})
    return out


def _num(v: float) -> float | None:
    return None if math.isnan(v) else round(v, 6)


def _table_text(rows: list[dict]) -> str:
    lines = [f"{'method':<11}{'n':>3} {'dir':<11}{'lines':>7}{'max':>5}{'at n':>8}{'at n-1':>8}{'n/(n-1)':>9}"
             "  counts of lengths 1..n"]
    for r in rows:
        ratio = "-" if math.isnan(r["ratio"]) else f"{r['ratio']:.3f}"
        before = "-" if math.isnan(r["at_n_minus_1"]) else f"{r['at_n_minus_1']:.4f}"
        lines.append(f"{r['method']:<11}{r['n']:>3} {r['direction']:<11}{r['lines']:>7}{r['longest']:>5}"
                     f"{r['at_n']:>8.4f}{before:>8}{ratio:>9}  {' '.join(str(v) for v in r['counts'])}")
    return "\n".join(lines)


def _table_csv(rows: list[dict]) -> str:
    top = max(r["n"] for r in rows)
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["method", "n", "direction", "lines", "longest", "at_n", "at_n_minus_1", "ratio"]
               + [f"length_{k}" for k in range(1, top + 1)])
    for r in rows:
        w.writerow([r["method"], r["n"], r["direction"], r["lines"], r["longest"],
                    *("" if math.isnan(r[k]) else f"{r[k]:.6f}" for k in ("at_n", "at_n_minus_1", "ratio")),
                    *(r["counts"] + [""] * (top - r["n"]))])
    return buf.getvalue()


def _panels(hists, methods, limits):
    from tilesolve.io.histogram import Panel

    by = {(h.method, h.n): h for h in hists}
    return [Panel(f"{d} lines, n = {n} (share of lines by length)", [str(k) for k in range(1, n + 1)],
                  [(_NAMES[m], [float(v) for v in by[m, n].shares(d)]) for m in methods])
            for d in _DIRECTIONS for n in limits]


@click.command("wall-lines", context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
               short_help="Line-length histograms of brick walls: PD vs NPD vs Kaji (004 Fig. 22).")
@click.option("--method", "methods", type=click.Choice(["procedural", "npd", "wall"]), multiple=True,
              help="Generators to measure (repeatable; default all three): procedural = PD, windows of the "
                   "infinite wall (004 §4.3); npd = one period of the repeatable wall on Kaji's cyclic dappling "
                   "(App. A), lines wrap; wall = the finite wall on Kaji's dappling (dappled §4).")
@click.option("--max-line", "limits", type=int, multiple=True, metavar="N",
              help="Line limits n (repeatable; default 4 and 10, as in Fig. 22).")
@click.option("--size", default="128x128", show_default=True, metavar="WxH", help="Size of each measured wall.")
@click.option("--samples", type=int, default=4, show_default=True, metavar="K",
              help="Walls per generator and limit (seeds S, S+1, ...).")
@click.option("--seed", type=click.IntRange(0, opt.MAX_SEED), default=0, show_default=True, metavar="S",
              help="First seed; the same seed gives the same table.")
@click.option("--colors", type=int, default=3, show_default=True, metavar="C", help="Edge colours (>= 3).")
@click.option("-o", "--output", type=OutputFile("json", "csv"), metavar="TABLE.json|.csv",
              help="Write the table as JSON, or CSV when the name ends in .csv ('-': JSON on stdout).")
@click.option("--svg", type=OutputFile("svg"), metavar="H.svg",
              help="Draw the histograms as SVG ('-' for stdout).")
@click.option("--png", type=OutputFile("png", allow_dash=False), metavar="H.png", help="Draw the histograms as PNG.")
@click.pass_context
def wall_lines(ctx, methods, limits, size, samples, seed, colors, output, svg, png) -> None:
    """Histograms of the line lengths of brick walls (004 §5, Fig. 22).

    A line is a run of horizontal bricks along a row or of vertical bricks up a column. Each
    line is counted once and whole: every line of a finite wall, the lines of a torus period
    wrapping its seams, the lines of a window of the infinite wall that start in it. Every
    wall's longest line is checked against n. The table gives, per generator, n and
    direction, the number of lines, the longest, the shares at n and n-1 and their ratio:
    the clamp of Kaji's algorithm that 004 §5 reports (as many lines at n as at n-1) shows as
    a ratio near 1, against about 1/2 for the procedural wall.

    \b
    Examples:
      tilesolve wall-lines --max-line 4 --size 64x64 --samples 2 --svg fig22.svg -o fig22.json
      tilesolve wall-lines --method procedural --method npd --max-line 4 --max-line 10 --size 48x48 --samples 1 --png lines.png -o lines.csv
    """
    from tilesolve.io.atomic import write_text_atomic
    from tilesolve.model.dappled import parse_size
    from tilesolve.families.walls import LINE_METHODS, line_statistics

    outs = Outputs(output, svg, png)
    rows_, cols = parse_size(size)
    methods = tuple(dict.fromkeys(methods)) or LINE_METHODS
    limits = tuple(dict.fromkeys(limits)) or (4, 10)
    for n in limits:
        if n < 1:
            raise InvalidProblem(f"--max-line must be >= 1 brick, got {n}")
    hists = [line_statistics(m, n, width=cols, height=rows_, samples=samples, seed=seed, colors=colors)
             for n in limits for m in methods]
    rows = _rows(hists)
    seeds = f"seed {seed}" if samples == 1 else f"seeds {seed}..{seed + samples - 1}"
    title = f"line lengths of {cols}x{rows_} walls, {samples} per generator, {seeds}"
    with outs.commit():
        if output:
            if output.lower().endswith(".csv"):
                write_text_atomic(output, _table_csv(rows))
            else:
                doc = {"format": "tilesolve-wall-lines", "version": 1, "size": [cols, rows_], "samples": samples,
                       "seed": seed, "colors": colors,
                       "rows": [{**r, **{k: _num(r[k]) for k in ("at_n", "at_n_minus_1", "ratio")}} for r in rows]}
                write_text_atomic(output, json.dumps(doc, indent=1) + "\n")
        if svg or png:
            from tilesolve.io.histogram import write_chart_png, write_chart_svg

            panels = _panels(hists, methods, limits)
            if svg:
                write_chart_svg(svg, panels, columns=len(limits), title=title)
            if png:
                write_chart_png(png, panels, columns=len(limits), title=title)
    if "-" not in (output, svg):
        click.echo(_table_text(rows))
    say(f"{title}; every line <= n")
    if outs.files:
        say(f"  wrote {', '.join(outs.files)}")
    ctx.exit(0)
