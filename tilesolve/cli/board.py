"""The board family's commands: ``tilesolve brick solve | wall | count | crosscheck``,
``tilesolve wang solve`` and ``tilesolve wall``, thin layers over :mod:`tilesolve.families.board` and
:mod:`tilesolve.families.walls`."""

from __future__ import annotations

import click

from tilesolve.cli import options as opt
from tilesolve.cli.common import big, human_bytes, progress_wanted, say
from tilesolve.cli.outputs import Outputs
from tilesolve.cli.wang_count import load_tileset, tileset_options, wang_count
from tilesolve.errors import InvalidProblem
from tilesolve.family import draw_seed, raise_if_interrupted
from tilesolve.model.board import MAX_BRICK_COLORS

__all__ = ["brick", "wang", "wall", "BOARD_HELP", "parse_region"]

BOARD_HELP = (
    "\b\nBoards (SPEC): rect:WxH, torus:WxH, cylinder:WxH, mobius:WxH (Example 5: columns "
    "wrap with a twist), klein:WxH, ring:WxH, or mask:FILE (text: '#' = cell, '.' = hole; or "
    "a PNG whose opaque pixels are cells).\n\b\nLegs l1..l4 = W, N, E, S; boundary legs are "
    "numbered by cell (row-major) then leg."
)


def _method_choices():
    from tilesolve.families.board import METHODS

    return METHODS


board_opt = click.option("--board", "board_spec", required=True, metavar="SPEC", help="The board (see below).")
boundary_opt = click.option(
    "--boundary", default="random", show_default=True, metavar="random|free|FILE",
    help="Boundary colours: random, free, or a JSON file with a list (one colour or null per boundary leg).",
)
method_opt = click.option("--method", type=click.Choice(_method_choices()), default="auto", show_default=True,
                          help="auto: the linear algorithm (§4) where it applies, SAT otherwise.")
svg_opt = click.option("--svg", type=click.Path(dir_okay=False, allow_dash=True), metavar="OUT.svg",
                       help="Also draw the tiling as SVG ('-' for stdout).")
colors_opt = click.option("--colors", type=int, default=3, show_default=True, metavar="K",
                          help="Number of colours #C (edge positions), at least 3.")
line_opts = opt.compose(
    click.option("--max-h", type=opt.positive_int, default=None, metavar="N",
                 help="No horizontal line through more than N cells (brick tiles; SAT route)."),
    click.option("--max-v", type=opt.positive_int, default=None, metavar="N",
                 help="No vertical line through more than N cells (brick tiles; SAT route)."),
)


def _boundary(spec: str, board, n_colors: int, seed: int):
    """``--boundary``: random (seeded), free, or a boundary file (:func:`tilesolve.io.board_json.read_boundary`)."""
    from tilesolve.model.board import random_boundary

    if spec == "random":
        return random_boundary(board, n_colors, seed=seed)
    if spec == "free":
        return None
    from tilesolve.io.board_json import read_boundary

    return read_boundary(spec)


def _svg_ok(svg, n_cells: int) -> None:
    from tilesolve.io.svg import MAX_SVG_CELLS

    if svg and n_cells > MAX_SVG_CELLS:
        raise InvalidProblem(f"a board of {n_cells:,} cells is too large for an SVG (limit {MAX_SVG_CELLS:,})")


def _brick_colors(colors: int) -> None:
    """Refuse a brick colour count that cannot be built, saying what it would need."""
    if colors < 3:
        raise InvalidProblem(f"brick Wang tiles need #C >= 3 colours (Def. 9), got {colors}")
    if colors > MAX_BRICK_COLORS:
        tiles = 2 * colors * colors * (colors - 1)
        raise InvalidProblem(
            f"--colors {big(colors)}: the brick tile set would have {big(tiles)} tiles and need "
            f"{human_bytes(64 * colors**4)} to build; tilesolve builds up to {MAX_BRICK_COLORS} colours"
        )


def board_text(problem, tiling) -> str:
    """The tiling as text, one line per board row (labels, row 0 first).

    Each cell shows its leg colours W N E S: four digits (``0121``) up to 10 colours, else
    comma-separated; ``.`` fills a hole.

    >>> from tilesolve.model.board import Board, BoardProblem, WangTileSet
    >>> p = BoardProblem(Board.rect(1, 2), WangTileSet.brick(3), None)
    >>> print(board_text(p, [[0, 1, 0, 2], [0, 1, 2, 1]]), end="")
    0102 0121
    """
    import numpy as np

    t = np.asarray(tiling, dtype=np.int64).reshape(-1, 4)
    lab = problem.board.labels
    if problem.n_colors <= 10:
        cells = np.char.add(np.char.add(t[:, 0].astype(str), t[:, 1].astype(str)),
                            np.char.add(t[:, 2].astype(str), t[:, 3].astype(str)))
    else:
        cells = np.array([",".join(map(str, row)) for row in t.tolist()])
    width = max((len(c) for c in cells.tolist()), default=1)
    rows, cols = (int(lab[:, 0].max()) + 1, int(lab[:, 1].max()) + 1) if len(lab) else (0, 0)
    grid = np.full((rows, cols), "." * width, dtype=f"<U{width}")
    grid[lab[:, 0], lab[:, 1]] = np.char.rjust(cells, width)
    return "".join(" ".join(row) + "\n" for row in grid.tolist())


def _run(ctx, problem, method, seed, time_limit, outs, output, svg) -> None:
    from tilesolve.families import board as facade

    _svg_ok(svg, problem.board.n_cells)
    sol = facade.solve(problem, method=method, seed=seed, time_limit=time_limit)
    _finish(ctx, problem, sol, outs, output, svg)


def _finish(ctx, problem, sol, outs, output, svg, png=None, draw_png=None) -> None:
    from tilesolve.io.board_json import write_board_solution

    written = []
    with outs.commit(sol):
        if output:
            write_board_solution(output, problem, sol)
            written.append(output)
        if svg and sol.status.has_tiling:
            from tilesolve.io.svg_board import write_board_svg

            write_board_svg(svg, problem, sol.tiling, title=problem.board.describe(),
                            notes=[f"{sol.status.value} by {sol.method}, seed {sol.seed}"])
            written.append(svg)
        if png and sol.status.has_tiling:
            if draw_png is not None:
                draw_png(png)
            else:
                from tilesolve.io.png import write_board_png

                write_board_png(png, problem, sol.tiling)
            written.append(png)
    if not outs and sol.status.has_tiling:
        click.echo(board_text(problem, sol.tiling), nl=False)
    say(f"{sol.status.value}: {problem.describe()}")
    say(f"  method {sol.method}" + (f", solver {sol.solver}" if sol.solver else "")
        + (f", seed {sol.seed}" if sol.seed is not None else "") + f", {sol.time_s:.3f} s")
    if sol.reason:
        say(f"  {'why' if sol.status.value == 'unsat' else 'stopped'}: {sol.reason}")
    for note in sol.notes:
        say(f"  note: {note}")
    if not outs and sol.status.has_tiling:
        say("  printed: each cell's leg colours W N E S ('.' = hole); -o FILE writes the JSON, --svg FILE draws it")
    written = [w for w in written if w != "-"]
    if written:
        say("  wrote " + ", ".join(written))
    ctx.exit(sol.status.exit_code)


@click.group(context_settings=opt.CONTEXT_SETTINGS, short_help="Brick Wang tilings of boards; brick walls.")
def brick() -> None:
    """Brick Wang tiles on boards (Derouet-Jourdan, Kaji, Mizoguchi 2016).

    A brick Wang tile (Def. 9) has colours (c1, c2, c3, c4) on its legs W, N, E, S with
    c1 = c3 xor c2 = c4: one straight mortar line crosses it, never two (no crosses).
    """


@brick.command(context_settings=opt.CONTEXT_SETTINGS, epilog=BOARD_HELP + "\n\n" + opt.READER_HELP)
@board_opt
@colors_opt
@boundary_opt
@opt.seed_opt
@method_opt
@opt.time_limit_opt
@opt.proof_dir_opt
@line_opts
@opt.output_opt
@svg_opt
@click.pass_context
def solve(ctx, board_spec, colors, boundary, seed, method, time_limit, max_h, max_v, output, svg) -> None:
    """Tile a board with brick Wang tiles, or prove it impossible.

    \b
    Example:
      tilesolve brick solve --board rect:40x30 --colors 3 --seed 1 -o wall.json --svg wall.svg
      tilesolve brick solve --board mobius:30x12 --boundary free --method sat -o m.json
      tilesolve brick solve --board mask:shape.png --colors 4 -o s.json

    Without -o or --svg the tiling is printed as text: each cell's leg colours W N E S.
    """
    from tilesolve.io.mask import read_board_spec
    from tilesolve.model.board import BoardProblem, WangTileSet

    outs = Outputs(output, svg)
    _brick_colors(colors)
    tileset = WangTileSet.brick(colors)
    board = read_board_spec(board_spec)
    if seed is None:
        seed = draw_seed()
    problem = BoardProblem(board, tileset, _boundary(boundary, board, colors, seed),
                           max_h=max_h, max_v=max_v)
    _run(ctx, problem, method, seed, time_limit, outs, output, svg)


@brick.command(name="wall", context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP)
@click.option("--size", required=True, metavar="WxH", help="Wall size: W columns by H rows.")
@click.option("--max-line", type=opt.positive_int, required=True, metavar="N",
              help="No horizontal line through more than N cells (and no vertical one, unless --max-v).")
@click.option("--max-v", type=opt.positive_int, default=None, metavar="N", help="Vertical limit, if different.")
@colors_opt
@opt.seed_opt
@opt.output_opt
@svg_opt
@click.pass_context
def brick_wall_cmd(ctx, size, max_line, max_v, colors, seed, output, svg) -> None:
    """A brick wall without long lines, from a dappled tiling (dappled paper §4).

    \b
    Example:
      tilesolve brick wall --size 40x25 --max-line 3 --seed 2 -o wall.json --svg wall.svg

    Without -o or --svg the wall is printed as text: each cell's leg colours W N E S.
    """
    from tilesolve.families.walls import brick_wall
    from tilesolve.model.dappled import parse_size

    outs = Outputs(output, svg)
    rows, cols = parse_size(size)
    _svg_ok(svg, rows * cols)
    _brick_colors(colors)
    if seed is None:
        seed = draw_seed()
    problem, sol = brick_wall(rows, cols, max_line, max_v=max_v, n_colors=colors, seed=seed)
    _finish(ctx, problem, sol, outs, output, svg)


def _brick_problem(board_spec, colors, boundary, seed):
    from tilesolve.io.mask import read_board_spec
    from tilesolve.model.board import BoardProblem, WangTileSet

    _brick_colors(colors)
    tileset = WangTileSet.brick(colors)
    board = read_board_spec(board_spec)
    return BoardProblem(board, tileset, _boundary(boundary, board, colors, seed))


@brick.command(context_settings=opt.CONTEXT_SETTINGS, epilog=BOARD_HELP + "\n\n" + opt.READER_HELP)
@board_opt
@colors_opt
@boundary_opt
@opt.seed_opt
@opt.time_limit_opt
@click.pass_context
def count(ctx, board_spec, colors, boundary, seed, time_limit) -> None:
    """Count the brick Wang tilings of a small board exactly (SAT enumeration); the count is
    the last line of stdout.

    \b
    Example:
      tilesolve brick count --board rect:2x1 --boundary free      # prints 432
    """
    from tilesolve.families import board as facade

    problem = _brick_problem(board_spec, colors, boundary, 0 if seed is None else seed)
    res = facade.count(problem, time_limit=time_limit)
    raise_if_interrupted(res)
    say(f"{'count' if res.value is not None else 'unknown'}: {problem.describe()}  ({res.time_s:.3f} s)")
    if res.value is None:
        say(f"  stopped: {res.note}")
        ctx.exit(3)
    click.echo(str(res.value))
    ctx.exit(0)


@brick.command(context_settings=opt.CONTEXT_SETTINGS, epilog=BOARD_HELP + "\n\n" + opt.READER_HELP)
@board_opt
@colors_opt
@boundary_opt
@opt.seed_opt
@opt.time_limit_opt
@click.option("--trials", type=click.IntRange(1, 1000), default=1, show_default=True,
              help="N trials with seeds SEED, SEED+1, ... (a new random boundary each time).")
@click.pass_context
def crosscheck(ctx, board_spec, colors, boundary, seed, time_limit, trials) -> None:
    """Run the linear algorithm, SAT and CP-SAT on one board and check that they agree.

    \b
    Example:
      tilesolve brick crosscheck --board mask:shape.txt --trials 5
    """
    from tilesolve.families import board as facade

    base = draw_seed() if seed is None else seed
    ok = True
    for i in range(trials):
        problem = _brick_problem(board_spec, colors, boundary, base + i)
        rep = facade.crosscheck(problem, seed=base + i, time_limit=time_limit)
        ok &= rep.ok
        click.echo(f"trial {i + 1}/{trials} (seed {base + i}): {'ok' if rep.ok else 'FAILED'}")
        for line in rep.lines:
            click.echo(f"  {line}")
    click.echo("crosscheck: all routes agree" if ok else "crosscheck: FAILED (see the FAIL lines above)")
    ctx.exit(0 if ok else 1)


@click.group(context_settings=opt.CONTEXT_SETTINGS, short_help="Any Wang tile set on any board.")
def wang() -> None:
    """Wang tilings of boards with any tile set W ⊂ C^4 (Def. 2 of the brick paper)."""


wang.add_command(wang_count)


@wang.command(name="solve", context_settings=opt.CONTEXT_SETTINGS, epilog=BOARD_HELP + "\n\n" + opt.READER_HELP)
@tileset_options
@board_opt
@boundary_opt
@opt.seed_opt
@method_opt
@opt.time_limit_opt
@opt.proof_dir_opt
@opt.output_opt
@svg_opt
@click.pass_context
def wang_solve(ctx, tiles_path, tiles_format, builtin, board_spec, boundary, seed, method, time_limit, output,
               svg) -> None:
    """Tile a board with any Wang tile set, or prove it impossible.

    \b
    Example:
      tilesolve wang solve --tiles tiles.json --board torus:8x8 --boundary free -o t.json --svg t.svg
      tilesolve wang solve --builtin jeandel-rao --board rect:12x12 --boundary free --svg jr.svg

    Without -o or --svg the tiling is printed as text: each cell's leg colours W N E S.
    """
    from tilesolve.io.mask import read_board_spec
    from tilesolve.model.board import BoardProblem

    outs = Outputs(output, svg)
    ts, tile_notes = load_tileset(tiles_path, tiles_format, builtin)
    for note in tile_notes:
        say(f"note: {note}")
    board = read_board_spec(board_spec)
    if seed is None:
        seed = draw_seed()
    problem = BoardProblem(board, ts, _boundary(boundary, board, ts.n_colors, seed))
    _run(ctx, problem, method, seed, time_limit, outs, output, svg)


def parse_region(text: str) -> tuple[int, int, int, int]:
    """``--region X0,Y0,WxH``: ``(x0, y0, rows, cols)``; ``(x0, y0)`` is the bottom-left cell.

    >>> parse_region("-40,12,64x40")
    (-40, 12, 40, 64)
    """
    import re

    m = re.match(r"^\s*([+-]?\d+)\s*,\s*([+-]?\d+)\s*,\s*(\d+)\s*[xX×]\s*(\d+)\s*$", str(text))
    if not m:
        raise InvalidProblem(f"cannot read region {text!r}: expected X0,Y0,WxH, e.g. -40,12,64x40 "
                             "(bottom-left cell x -40, y 12; 64 columns, 40 rows)")
    x0, y0, w, h = (int(g) for g in m.groups())
    if w < 1 or h < 1:
        raise InvalidProblem(f"region size must be positive, got {w}x{h} (WxH)")
    return x0, y0, h, w


#: Memory a wall held whole takes per cell (-o, --svg, printed text): measured peak RSS of
#: ``tilesolve wall --region 0,0,2000x2000 -o w.json``, 1.0 GiB for 4 M cells.
HELD_BYTES_PER_CELL = 224


def _check_held(rows: int, cols: int, svg) -> None:
    """Refuse a region that -o, --svg or the printed text would have to hold whole."""
    from tilesolve.io.svg import MAX_SVG_CELLS
    from tilesolve.model.board import MAX_BOARD_CELLS

    cells = rows * cols
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
                   "edges (grey); uv, the brick's Cartesian UV coordinates (red u, green v) (004 §3.2).")
@click.option("--ppc", type=click.IntRange(1, 256), default=None, metavar="N",
              help="--png pixels per cell  [default: about 1024 px on the longer side, 1 to 32]")
@click.option("--verify/--no-verify", "check", default=True, show_default=True,
              help="Check every --png band with the board verifier (line limits included); the check takes "
                   "most of the time of a large picture.")
@click.pass_context
def wall(ctx, region, max_line, colors, seed, method, period, output, svg, png, map_kind, ppc, check) -> None:
    """A brick wall in which no line runs through more than N bricks, cut from an infinite wall.

    The procedural wall (Derouet-Jourdan, Salvati, Jonchier, 004 §3-4, App. B) gives every
    cell of the plane its tile from the cell's coordinates and the seed alone: the same seed
    gives the same wall, and windows at different origins are parts of one wall that agree
    where they overlap. The answer is checked with the board verifier (line limits included).

    --png draws the bricks of the procedural and npd walls (merged from the edge structure) as a
    map, computed and written band by band: a region of any size (20,000 x 20,000 cells and more)
    takes the memory of one band (a dappled wall is drawn by its tiles' legs). -o, --svg and the
    printed text hold the whole wall, so they take smaller regions.

    \b
    Example:
      tilesolve wall --region -40,12,64x40 --max-line 4 --seed 7 -o wall.json --png wall.png
      tilesolve wall --region 0,0,30x20 --max-line 3 --colors 4 --seed 7 --svg wall.svg
      tilesolve wall --region 0,0,400x300 --max-line 2 --seed 7 --png d.png --map distance --ppc 4
      tilesolve wall --region 5,5,60x40 --max-line 3 --method npd --period 12x9 --seed 7 --png n.png
      tilesolve wall --region 0,0,30x20 --max-line 2 --method dappled --seed 1 -o d.json

    Without -o, --svg or --png the wall is printed as text: each cell's leg colours W N E S.
    """
    import time

    from tilesolve import family
    from tilesolve.model.dappled import parse_size

    outs = Outputs(output, svg, png)
    x0, y0, rows, cols = parse_region(region)
    held = bool(output or svg or not outs) or method == "dappled"  # a dappled wall is built whole
    if held:
        _check_held(rows, cols, svg)
    _brick_colors(colors)
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

        def draw(path):
            last = [0.0]

            def show(line: str) -> None:  # a line every 2 s at most, on a terminal
                now = time.monotonic()
                if now - last[0] >= 2:
                    last[0] = now
                    say(line)

            return write_wall_png(path, (x0, y0, cols, rows), colors=colors, max_line=max_line, seed=seed,
                                  method=method, period=(pw, ph), kind=map_kind or "id", ppc=ppc, verify=check,
                                  progress=show if progress_wanted() else None)
    if held:
        from tilesolve.families.walls import wall_problem

        problem = wall_problem(rows, cols, max_line, n_colors=colors)
        options = {"origin": (x0, y0)} | ({"period": (pw, ph)} if method == "npd" else {})
        sol = raise_if_interrupted(family.solve(problem, route, seed=seed, options=options))
        _finish(ctx, problem, sol, outs, output, svg, png, draw_png=draw)
        return
    with outs.commit():
        rep = draw(png)
    say(f"sat: {method} brick wall, window x {x0}..{x0 + cols - 1}, y {y0}..{y0 + rows - 1} (y grows upwards), "
        f"lines <= {max_line}, {colors} colours")
    say(f"  method {method}, seed {seed}" + (f", period {pw}x{ph}" if method == "npd" else "")
        + f", {rep.time_s:.3f} s")
    bands = f"{rep.bands} band{'s' if rep.bands > 1 else ''}"
    checked = f"{big(rep.verified_cells)} cells checked with the board verifier" if check else "not verified"
    say(f"  {map_kind or 'id'} map {rep.size_px[0]}x{rep.size_px[1]} px, drawn in {bands}; {checked}")
    if png != "-":
        say(f"  wrote {png}")
    ctx.exit(0)
