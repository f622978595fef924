"""``tilesolve wall``: a window of an infinite brick wall without long lines, a thin layer over
:mod:`tilesolve.families.walls` and :mod:`tilesolve.families.wall_render`."""

from __future__ import annotations

import click

from tilesolve.cli import options as opt
from tilesolve.cli.board_common import check_brick_colors, colors_opt, finish, svg_opt
from tilesolve.cli.common import big, human_bytes, progress_wanted, say
from tilesolve.cli.outputs import Outputs
from tilesolve.errors import InvalidProblem
from tilesolve.family import draw_seed, raise_if_interrupted
from tilesolve.model.window import parse_region

__all__ = ["wall"]


#: Memory a wall held whole takes per cell (--svg, printed text, --method npd or dappled with -o):
#: measured peak RSS of ``tilesolve wall --region 0,0,2000x2000 --method npd -o w.json``, 1.0 GiB for 4 M cells.
HELD_BYTES_PER_CELL = 224


def _check_held(rows: int, cols: int, svg, streamed: bool) -> None:
    """Refuse a region that -o, --svg or the printed text would have to hold whole (``streamed``:
    -o alone of a procedural wall, which holds 4 bytes a cell and writes the file as it goes)."""
    from tilesolve.io.svg import MAX_SVG_CELLS
    from tilesolve.model.board import MAX_BOARD_CELLS

    cells = rows * cols
    if streamed:
        if cells > MAX_BOARD_CELLS:
            raise InvalidProblem(
                f"region {cols}x{rows} has {big(cells)} cells: a board-solution file (-o) holds at most "
                f"{big(MAX_BOARD_CELLS)} cells; draw it with --png alone, which streams the picture band by band")
        return
    limit, what = (MAX_SVG_CELLS, "an SVG holds") if svg else (MAX_BOARD_CELLS, "-o and the printed text hold")
    if cells > limit:
        raise InvalidProblem(
            f"region {cols}x{rows} has {big(cells)} cells: {what} the whole wall (about "
            f"{human_bytes(cells * HELD_BYTES_PER_CELL)}), tilesolve holds at most {big(limit)} cells that way; "
            "draw it with --png alone, which streams the picture band by band")


@click.command(name="wall", context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
               short_help="A window of an infinite brick wall without long lines.")
@click.option("--region", required=True, metavar="X0,Y0,WxH",
              help="The window: bottom-left cell (X0, Y0) of the infinite wall (y grows upwards), "
                   "W columns by H rows.")
@click.option("--max-line", type=opt.positive_int, required=True, metavar="N",
              help="No line (horizontal or vertical) through more than N bricks.")
@colors_opt
@opt.seed_opt
@click.option("--method", type=click.Choice(("procedural", "npd", "dappled")), default="procedural",
              show_default=True,
              help="procedural: the window of the infinite procedural wall (004 §4); npd: the repeatable wall "
                   "of 004 App. A (one period repeated, see --period); dappled: a finite wall from a dappled "
                   "tiling (dappled paper §4; the origin is not used).")
@click.option("--period", metavar="WxH", default=None,
              help="npd: the repeating period, W columns by H rows (at least 3x3)  [default: the region's size]")
@opt.output_opt
@svg_opt
@opt.png_opt
@click.option("--map", "map_kind", type=click.Choice(("id", "distance", "uv")), default=None,
              help="What --png shows: id, a colour per brick (default); distance, the distance to the brick's "
                   "edges (a colour map, with its colour bar); uv, the brick's Cartesian UV coordinates (red u, "
                   "green v) (004 §3.2).")
@click.option("--ppc", type=click.IntRange(1, 256), default=None, metavar="N",
              help="--png pixels per cell  [default: about 1024 px on the longer side, 1 to 32; at least 8 for "
                   "the distance and uv maps]")
@click.option("--verify/--no-verify", "check", default=True, show_default=True,
              help="Check every --png band with the board verifier (line limits included); -o is always "
                   "checked.")
@click.pass_context
def wall(ctx, region, max_line, colors, seed, method, period, output, svg, png, map_kind, ppc, check) -> None:
    """A brick wall in which no line runs through more than N bricks, cut from an infinite wall.

    The procedural wall (Derouet-Jourdan, Salvati, Jonchier, 004 §3-4, App. B) gives every
    cell of the plane its tile from the cell's coordinates and the seed alone: the same seed
    gives the same wall, and windows at different origins are parts of one wall that agree
    where they overlap. The answer is checked with the board verifier (line limits included).

    --png draws the bricks of the procedural and npd walls (merged from the edge structure) as a
    map, computed and written band by band: a region of any size (20,000 x 20,000 cells and more)
    takes the memory of one band (a dappled wall is drawn by its tiles' legs). -o of a procedural
    wall is checked band by band and written as it goes (4 bytes a cell); --svg, the printed
    text and -o of the other methods hold the whole wall as a board, so they take smaller regions.

    \b
    Example:
      tilesolve wall --region -40,12,64x40 --max-line 4 --seed 7 -o wall.json --png wall.png
      tilesolve wall --region 0,0,30x20 --max-line 3 --colors 4 --seed 7 --svg wall.svg
      tilesolve wall --region 0,0,400x300 --max-line 2 --seed 7 --png d.png --map distance --ppc 4
      tilesolve wall --region 5,5,60x40 --max-line 3 --method npd --period 12x9 --seed 7 --png n.png
      tilesolve wall --region 0,0,30x20 --max-line 2 --method dappled --seed 1 -o d.json

    Without -o, --svg or --png the wall is printed as text: each cell's colours N E S W.
    """
    from tilesolve import family
    from tilesolve.model.dappled import parse_size

    outs = Outputs(output, svg, png)
    window = parse_region(region)
    x0, y0, (rows, cols) = window.x0, window.y0, window.shape
    streamed = method == "procedural" and not svg  # -o written as it goes, --png band by band
    # a dappled wall is built whole
    held = bool(svg or not outs) or method == "dappled" or (bool(output) and not streamed)
    if held or output:
        _check_held(rows, cols, svg, not held)
    check_brick_colors(colors)
    if (map_kind or ppc) and not png:
        raise InvalidProblem("--map and --ppc choose what --png draws; add --png FILE")
    if period and method != "npd":
        raise InvalidProblem("--period is the repeating period of --method npd")
    if method == "dappled" and (map_kind or ppc):
        raise InvalidProblem("--map and --ppc need the wall around the region (--method procedural or npd); "
                             "a dappled wall is finite")
    pw, ph = (cols, rows) if period is None else parse_size(period)[::-1]
    if seed is None:
        seed = draw_seed()
    route = {"procedural": "procedural", "npd": "npd", "dappled": "wall"}[method]
    draw = None
    if method != "dappled":
        from tilesolve.families.wall_render import write_wall_png

        def draw_streamed(path):
            return write_wall_png(path, (x0, y0, cols, rows), colors=colors, max_line=max_line, seed=seed,
                                  method=method, period=(pw, ph), kind=map_kind or "id", ppc=ppc, verify=check,
                                  progress=progress_wanted(),
                                  caption=[f"{method} brick wall, lines <= {max_line}, seed {seed}"
                                           + (f", period {pw}x{ph}" if method == "npd" else ""), window.caption()])

        draw = draw_streamed
    if held:
        from tilesolve.families.walls import wall_problem

        problem = wall_problem(cols, rows, max_line, n_colors=colors)
        options = {"origin": (x0, y0)} | ({"period": (pw, ph)} if method == "npd" else {})
        sol = raise_if_interrupted(family.solve(problem, route, seed=seed, options=options, progress=progress_wanted()))
        finish(ctx, problem, sol, outs, output, svg, png, draw_png=draw)
        return
    sol = rep = None
    with outs.commit():
        if output:
            from tilesolve.families.walls import write_procedural_wall

            with progress_wanted().task(f"wall: {big(rows * cols)} cells built, checked and written", unit=None):
                sol = write_procedural_wall(output, (x0, y0, cols, rows), colors=colors, max_line=max_line, seed=seed)
        if png:
            rep = draw(png)
    say(f"sat: {method} brick wall, window {window.describe()}, lines <= {max_line}, {colors} colours")
    say(f"  method {method}, seed {seed}" + (f", period {pw}x{ph}" if method == "npd" else "")
        + f", {sum(r.time_s for r in (sol, rep) if r is not None):.3f} s")
    if sol is not None:
        say(f"  {big(rows * cols)} cells checked with the board verifier")
    if rep is not None:
        bands = f"{rep.bands} band{'s' if rep.bands > 1 else ''}"
        checked = f"{big(rep.verified_cells)} cells checked with the board verifier" if check else "not verified"
        say(f"  {map_kind or 'id'} map {rep.size_px[0]}x{rep.size_px[1]} px, drawn in {bands}; {checked}")
    if outs.files:
        say(f"  wrote {', '.join(outs.files)}")
    ctx.exit(0)
