"""``tilesolve shapes``: polyominoes, polyhexes and polyiamonds by SAT (class notes Part II §3).

::

    tilesolve shapes tile --grid omino --shape 'XX/XX/X.' --region 5x2 -o t.json --svg t.svg
    tilesolve shapes heesch --grid hex --shape 0,0/0,1/0,2/1,-1/1,2/2,-2 -o h.json --svg h.svg
    tilesolve shapes census --grid hex --size 6 -o census.json
    tilesolve shapes list --grid omino --size 5
"""

from __future__ import annotations

import click

from tilesolve.cli import options as opt
from tilesolve.cli.common import progress_wanted, say
from tilesolve.cli.outputs import OutputFile, Outputs
from tilesolve.errors import InvalidProblem

__all__ = ["shapes"]

_GRIDS = click.Choice(["omino", "hex", "iamond"])

SHAPE_HELP = """\b
Shapes (--shape, repeatable):
  'XX/X.'            ASCII art, rows top first, '/' between rows ('X', 'x', '#', '*' or 'o' a
                     cell, '.' none)
  '0,0 1,0 0,1'      cell coordinates x,y (spaces or ';' between cells)
Cells: omino (x, y) unit squares; hex axial (q, r) (each row drawn half a cell right of the
row below); iamond 3x the triangle's centroid in axial coordinates (up (3a+1, 3b+1), down
(3a+2, 3b+2)); in iamond ASCII art column c of row r is an up triangle when c + r is even."""


def _shape(text: str, grid_name: str):
    from tilesolve.model.shapes import parse_ascii, parse_cells

    if any(ch.isdigit() for ch in text):
        return parse_cells(text, grid_name)
    return parse_ascii(text.replace("/", "\n"), grid_name)


def _shapes(items, shape_file, grid_name):
    from tilesolve.inputs import read_input_text

    texts = list(items)
    if shape_file:
        texts += [block for block in read_input_text(shape_file, "shape file").split("\n\n") if block.strip()]
    if not texts:
        raise InvalidProblem("give at least one shape: --shape '##/#.' or --shape-file FILE")
    return tuple(_shape(t, grid_name) for t in texts)


def _size(text: str, what: str) -> tuple[int, int]:
    try:
        w, h = (int(v) for v in text.lower().split("x"))
    except ValueError:
        raise InvalidProblem(f"{what} takes WxH (e.g. 6x5), got {text!r}") from None
    if w < 1 or h < 1:
        raise InvalidProblem(f"{what} needs positive sides, got {text!r}")
    if w * h > 10**6:
        raise InvalidProblem(f"{what} {text} is too large: {w * h:,} translation cells (at most 1,000,000)")
    return w, h


def _rectangle(g, w: int, h: int) -> tuple:
    types = [(0, 0)] if g.period == 1 else [(1, 1), (2, 2)]
    return tuple((g.period * x + t[0], g.period * y + t[1]) for x in range(w) for y in range(h) for t in types)


#: The options of the commands that answer one question: copies, seed, limits and outputs.
_answer_options = opt.compose(
    click.option("--no-reflections", is_flag=True, help="Rotated copies only (no mirror images)."),
    opt.seed_opt,
    opt.time_limit_opt,
    opt.proof_dir_opt,
    click.option("-o", "--output", type=OutputFile("json"), metavar="OUT.json",
                 help="Write the answer JSON here."),
    click.option("--svg", type=OutputFile("svg"), metavar="OUT.svg",
                 help="Draw the tiling (a torus tiling over 3x3 periods) or the corona patch."),
    click.option("--png", type=OutputFile("png", allow_dash=False), metavar="OUT.png", help="The same picture as PNG."),
)


@click.group(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
             short_help="Polyforms by SAT: tilings, isohedral tilers, Heesch numbers, census.")
def shapes() -> None:
    """Polyominoes, polyhexes and polyiamonds by SAT: tile a region or a torus, classify a shape
    (isohedral or periodic tiler, or non-tiler with its Heesch number), a census of all free
    polyforms of a size. Every answer is verified by an independent checker; every refutation
    carries a checked DRAT proof.

    \b
    Examples:
      tilesolve shapes tile --grid omino --shape 'XX/XX/X.' --region 5x2 -o t.json --svg t.svg
      tilesolve shapes heesch --grid hex --shape '0,0 0,1 0,2 0,3 1,-1 1,3' -o h.json --svg h.svg
      tilesolve shapes list --grid omino --size 6   # prints 35
    """


@shapes.command("tile", context_settings=opt.CONTEXT_SETTINGS, epilog=SHAPE_HELP + "\n\n" + opt.READER_HELP)
@click.option("--grid", "grid_name", type=_GRIDS, default="omino", show_default=True, help="The grid of the cells.")
@click.option("--shape", "shape", multiple=True, metavar="SHAPE", help="A shape (see below); repeatable.")
@click.option("--shape-file", type=click.Path(dir_okay=False), metavar="FILE",
              help="Shapes as ASCII art, separated by blank lines.")
@click.option("--region", default=None, metavar="WxH",
              help="Tile the W x H parallelogram of translation cells (a rectangle of squares).")
@click.option("--mask", type=click.Path(dir_okay=False), default=None, metavar="FILE",
              help="Tile the region drawn as ASCII art in FILE (a cell 'X' or '#', none '.').")
@click.option("--torus", default=None, metavar="WxH", help="Tile the torus with periods (W, 0) and (0, H).")
@_answer_options
@click.pass_context
def tile(ctx, grid_name, shape, shape_file, region, mask, torus, no_reflections, seed, time_limit, output, svg,
         png) -> None:
    """Do copies of the shapes tile a region (rectangle or mask) or a torus?

    Exit 0 with a verified tiling, 1 when none exists (a checked DRAT proof), 3 unknown.

    \b
    Examples:
      tilesolve shapes tile --grid omino --shape 'XX/XX/X.' --region 5x2 -o t.json --svg t.svg
      tilesolve shapes tile --grid omino --shape 'XXX/.X.' --region 4x3 -o t4.json   # unsat
      tilesolve shapes tile --grid hex --shape 'XX' --torus 4x3 --png h.png
      tilesolve verify t.json
    """
    from tilesolve.families import shapes as facade
    from tilesolve.inputs import read_input_text
    from tilesolve.model.shapes import ShapesProblem, grid, parse_ascii

    given = [o for o, v in (("--region", region), ("--mask", mask), ("--torus", torus)) if v]
    if len(given) != 1:
        raise InvalidProblem("give exactly one of --region WxH, --mask FILE, --torus WxH"
                             + (f" (got {', '.join(given)})" if given else ""))
    outs = Outputs(output, svg, png)
    g = grid(grid_name)
    shapes_ = _shapes(shape, shape_file, grid_name)
    cells, lattice = None, None
    if region:
        cells = _rectangle(g, *_size(region, "--region"))
    elif mask:
        cells = parse_ascii(read_input_text(mask, "mask"), grid_name).cells
    else:
        w, h = _size(torus, "--torus")
        lattice = ((w, 0), (0, h))
    problem = ShapesProblem("tile", shapes_, region=cells, lattice=lattice, reflections=not no_reflections)
    sol = facade.solve(problem, seed=seed, time_limit=time_limit, progress=progress_wanted())
    _finish(ctx, facade, problem, sol, outs, output, svg, png)


def _finish(ctx, facade, problem, sol, outs, output, svg, png) -> None:
    written = []
    drawable = sol.status.has_tiling or sol.report is not None
    with outs.commit(sol):
        if output:
            from tilesolve.io.atomic import write_text_atomic
            from tilesolve.io.jsonio import dumps
            from tilesolve.io.shapes_json import shapes_to_dict

            write_text_atomic(output, dumps(shapes_to_dict(problem, sol)))
            written.append(output)
        for path, fmt in ((svg, "svg"), (png, "png")):
            if path and drawable:
                facade.FAMILY.draw(problem, sol, path, fmt)
                written.append(path)
    head = sol.report.conclusion if sol.report is not None else sol.status.value
    line = f"{head}: {problem.describe()} in {sol.time_s:.2f} s"
    if sol.reason:
        line += f" ({sol.reason})"
    say(line)
    for n in sol.notes:
        say(f"  note: {n}")
    if [w for w in written if w != "-"]:
        say(f"  wrote {', '.join(w for w in written if w != '-')}")
    ctx.exit(sol.status.exit_code)


@shapes.command("heesch", context_settings=opt.CONTEXT_SETTINGS, epilog=SHAPE_HELP + "\n\n" + opt.READER_HELP)
@click.option("--grid", "grid_name", type=_GRIDS, default="omino", show_default=True, help="The grid of the cells.")
@click.option("--shape", "shape", multiple=True, metavar="SHAPE", help="The shape (see below).")
@click.option("--shape-file", type=click.Path(dir_okay=False), metavar="FILE", help="The shape as ASCII art.")
@click.option("--max-level", type=click.IntRange(1, 8), default=3, show_default=True,
              help="The most coronas tried; a shape surrounded this often is inconclusive.")
@click.option("--max-copies", type=click.IntRange(1, 12), default=2, show_default=True,
              help="The most copies per period tried on tori.")
@click.option("--holes", is_flag=True, help="Allow holes in the outer corona (H_h instead of H_c).")
@_answer_options
@click.pass_context
def heesch(ctx, grid_name, shape, shape_file, max_level, max_copies, holes, no_reflections, seed, time_limit,
           output, svg, png) -> None:
    """Classify one polyform: isohedral tiler, periodic tiler (k copies per period), non-tiler
    with its Heesch number (coronas shown, the next level refuted by a checked DRAT proof), or
    inconclusive.

    Exit 0 when decided, 3 when inconclusive.

    \b
    Examples:
      tilesolve shapes heesch --grid hex --shape '0,0 0,1 0,2 0,3 1,-1 1,3' -o h.json --svg h.svg
      tilesolve shapes heesch --grid omino --shape 'XX/X.' --png l.png
      tilesolve verify h.json
    """
    from tilesolve.families import shapes as facade
    from tilesolve.model.shapes import ShapesProblem

    outs = Outputs(output, svg, png)
    shapes_ = _shapes(shape, shape_file, grid_name)
    if len(shapes_) != 1:
        raise InvalidProblem(f"heesch classifies one shape, got {len(shapes_)}")
    problem = ShapesProblem("classify", shapes_, reflections=not no_reflections, max_level=max_level,
                            max_copies=max_copies, holes=holes)
    sol = facade.solve(problem, seed=seed, time_limit=time_limit, progress=progress_wanted())
    _finish(ctx, facade, problem, sol, outs, output, svg, png)


@shapes.command("list", context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP)
@click.option("--grid", "grid_name", type=_GRIDS, default="omino", show_default=True, help="The grid of the cells.")
@click.option("--size", type=click.IntRange(1, 12), required=True, metavar="N", help="Cells per polyform (1..12).")
@click.option("--holes/--no-holes", default=True, show_default=True, help="Keep polyforms with holes.")
@click.option("--show", is_flag=True, help="Print each polyform's cells.")
def list_cmd(grid_name, size, holes, show) -> None:
    """List the free polyforms of a size (Redelmeier's algorithm, reduced by the grid's
    symmetries); the count on the last line.

    \b
    Examples:
      tilesolve shapes list --grid omino --size 6   # prints 35
      tilesolve shapes list --grid hex --size 6 --no-holes   # prints 81
    """
    from tilesolve.families.shapes import polyforms

    found = polyforms(grid_name, size, holes=holes)
    if show:
        for p in found:
            click.echo(" ".join(f"{x},{y}" for x, y in p.cells))
    click.echo(len(found))


@shapes.command("census", context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP)
@click.option("--grid", "grid_name", type=_GRIDS, default="omino", show_default=True, help="The grid of the cells.")
@click.option("--size", type=click.IntRange(1, 12), required=True, metavar="N", help="Cells per polyform.")
@click.option("--holes/--no-holes", default=False, show_default=True,
              help="Include polyforms with holes; with --holes the Heesch numbers are H_h (holes in the outer corona).")
@click.option("--max-level", type=click.IntRange(1, 8), default=3, show_default=True, help="The most coronas tried.")
@click.option("--max-copies", type=click.IntRange(1, 12), default=2, show_default=True,
              help="The most copies per period tried on tori.")
@click.option("--workers", type=click.IntRange(1, 256), default=None, metavar="N",
              help="Local worker processes [default: 2].")
@click.option("--cluster", default=None, metavar="ADDRESS", help="A Dask scheduler (tcp://host:8786) instead.")
@opt.time_limit_opt
@click.option("-o", "--output", type=OutputFile("json"), metavar="CENSUS.json",
              help="Write every shape's classification and time here (also when the time limit stops the census).")
@click.option("--resume", is_flag=True,
              help="Keep the shapes already classified in -o (a census with the same options) and classify the "
                   "others.")
@click.pass_context
def census_cmd(ctx, grid_name, size, holes, max_level, max_copies, workers, cluster, time_limit, output,
               resume) -> None:
    """Classify every free polyform of a size (each report verified); a summary table, the
    total on the last line. A census stopped by --time-limit (exit 3) continues with --resume.

    \b
    Examples:
      tilesolve shapes census --grid omino --size 4 -o census4.json   # prints 5 shapes
      tilesolve shapes census --grid omino --size 5 -o census5.json --resume   # prints 12 shapes
    """
    from collections import Counter

    from tilesolve.families import shapes as facade
    from tilesolve.io.atomic import write_text_atomic
    from tilesolve.io.jsonio import dumps

    outs = Outputs(output)
    options = {"grid": grid_name, "size": size, "holes": holes, "max_level": max_level, "max_copies": max_copies}
    done = _resumed(output, options) if resume else []
    rows, n_shapes = facade.census(grid_name, size, holes=holes, max_level=max_level, max_copies=max_copies,
                         workers=workers, cluster=cluster, time_limit=time_limit, progress=progress_wanted(),
                         done=done)
    if done:
        say(f"  {len(done)} shape(s) resumed from {output}")
    bad = [r for r in rows if r.problems]
    kinds = Counter((r.verdict, r.heesch if r.verdict in ("non-tiler", "inconclusive") else r.copies) for r in rows)
    for (verdict, k), n in sorted(kinds.items(), key=lambda kv: (kv[0][0], kv[0][1] or 0)):
        what = {"isohedral": "copies per period", "periodic": "copies per period"}.get(verdict, "Heesch number")
        click.echo(f"{n:6d}  {verdict} ({what} {k})")
    total = sum(r.time_s for r in rows)
    cpu = sum(r.cpu_s or 0.0 for r in rows)
    click.echo(f"        {total:.2f} s of classification, {total / max(len(rows), 1) * 1000:.1f} ms per shape "
               f"({cpu / max(len(rows), 1) * 1000:.1f} ms CPU)")
    if output:
        doc = {"format": "tilesolve/shapes-census", "version": 1, **options, "total": n_shapes,
               "shapes": [{"cells": [list(c) for c in r.cells], "verdict": r.verdict, "heesch": r.heesch,
                           "copies": r.copies, "time_s": round(r.time_s, 4),
                           "cpu_s": None if r.cpu_s is None else round(r.cpu_s, 4), "violations": list(r.problems)}
                          for r in rows]}
        with outs.commit():
            write_text_atomic(output, dumps(doc))
    click.echo(f"{len(rows)} shapes")
    if bad:
        say(f"{len(bad)} report(s) failed verification: {bad[0].problems[0]}")
        ctx.exit(70)
    ctx.exit(0 if len(rows) == n_shapes else 3)


def _resumed(output, options: dict) -> list:
    """The rows of an earlier census in ``output`` (none when it does not exist yet), refused
    when its options differ from ``options``."""
    import json
    import os

    from tilesolve.families.shapes import CensusRow
    from tilesolve.inputs import read_input_text

    if not output or output == "-":
        raise InvalidProblem("--resume continues the census in -o FILE: give -o")
    if not os.path.exists(output):
        return []
    try:
        doc = json.loads(read_input_text(output, "census "))
        if doc.get("format") != "tilesolve/shapes-census":
            raise ValueError("not a tilesolve/shapes-census file")
        differ = [k for k, v in options.items() if doc.get(k) != v]
        if differ:
            raise ValueError(f"its {differ[0]} is {doc.get(differ[0])!r}, this census has {options[differ[0]]!r}")
        return [CensusRow(tuple(tuple(c) for c in r["cells"]), r["verdict"], r["heesch"], r["copies"],
                          float(r["time_s"]), tuple(r["violations"]), r.get("cpu_s")) for r in doc["shapes"]]
    except (ValueError, KeyError, TypeError) as exc:
        raise InvalidProblem(f"cannot resume from {output}: {exc}") from None
