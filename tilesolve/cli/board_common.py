"""What the board commands share (``tilesolve brick``, ``wang solve``, ``wall``): the board,
boundary, method, colour and SVG options, their checks, and the output of a board solution
(files, the tiling as text, the summary on stderr)."""

from __future__ import annotations

import click

from tilesolve.cli import options as opt
from tilesolve.cli.common import big, human_bytes, progress_wanted, say
from tilesolve.cli.outputs import OutputFile
from tilesolve.errors import InvalidProblem
from tilesolve.model.board import MAX_BRICK_COLORS

__all__ = ["BOARD_HELP", "board_opt", "boundary_opt", "method_opt", "svg_opt", "colors_opt", "line_opts",
           "parse_boundary", "check_svg_cells", "check_brick_colors", "board_text", "solve_board", "finish"]

BOARD_HELP = (
    "\b\nBoards (SPEC): rect:WxH, torus:WxH, cylinder:WxH, mobius:WxH (Example 5: columns "
    "wrap with a twist), klein:WxH, ring:WxH, or mask:FILE (text: '#' = cell, '.' = hole; or "
    "a PNG whose opaque pixels are cells), or mask:ROWS (the text itself, '/' between rows)."
    "\n\b\nTiles and printed cells: colours N, E, S, W. Boundary "
    "legs are numbered by cell (row-major), then by leg N, E, S, W."
)


def _method_choices():
    from tilesolve.families.board import METHODS

    return METHODS


board_opt = click.option("--board", "board_spec", required=True, metavar="SPEC", help="The board (see below).")
boundary_opt = click.option(
    "--boundary", default="free", show_default=True, metavar="free|random|FILE",
    help="Boundary colours: free (any colours; the default for every tile set, as in the Python API), random "
         "(seeded by --seed: the brick paper's given boundary, which brick tiles always meet on planar boards), "
         "or a JSON file with a list (one colour or null per boundary leg).",
)
method_opt = click.option("--method", type=click.Choice(_method_choices()), default="auto", show_default=True,
                          help="auto: the linear algorithm (§4) where it applies, SAT otherwise.")
svg_opt = click.option("--svg", type=OutputFile("svg"), metavar="OUT.svg",
                       help="Also draw the tiling as SVG ('-' for stdout).")
colors_opt = click.option("--colors", type=int, default=3, show_default=True, metavar="K",
                          help="Number of colours #C (edge positions), at least 3.")
line_opts = opt.compose(
    click.option("--max-h", type=opt.positive_int, default=None, metavar="N",
                 help="No horizontal line through more than N cells (brick tiles; SAT route)."),
    click.option("--max-v", type=opt.positive_int, default=None, metavar="N",
                 help="No vertical line through more than N cells (brick tiles; SAT route)."),
)


def parse_boundary(spec: str, board, n_colors: int, seed: int):
    """``--boundary``: random (seeded), free, or a boundary file (:func:`tilesolve.io.board_json.read_boundary`)."""
    from tilesolve.model.board import random_boundary

    if spec == "random":
        return random_boundary(board, n_colors, seed=seed)
    if spec == "free":
        return None
    from tilesolve.io.board_json import read_boundary

    return read_boundary(spec)


def check_svg_cells(svg, n_cells: int) -> None:
    from tilesolve.io.svg import MAX_SVG_CELLS

    if svg and n_cells > MAX_SVG_CELLS:
        raise InvalidProblem(f"a board of {n_cells:,} cells is too large for an SVG (limit {MAX_SVG_CELLS:,})")


def check_brick_colors(colors: int) -> None:
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

    Each cell shows its colours N E S W, as tiles are written everywhere: four digits
    (``1020``) up to 10 colours, else comma-separated; ``.`` fills a hole.

    >>> from tilesolve.model.board import Board, BoardProblem, WangTileSet
    >>> p = BoardProblem(Board.rect(2, 1), WangTileSet.brick(3), None)
    >>> print(board_text(p, [[1, 0, 2, 0], [1, 2, 1, 0]]), end="")
    1020 1210
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


def solve_board(ctx, problem, method, seed, time_limit, outs, output, svg) -> None:
    from tilesolve.families import board as facade

    check_svg_cells(svg, problem.board.n_cells)
    sol = facade.solve(problem, method=method, seed=seed, time_limit=time_limit, progress=progress_wanted())
    finish(ctx, problem, sol, outs, output, svg)


def finish(ctx, problem, sol, outs, output, svg, png=None, draw_png=None) -> None:
    from tilesolve.io.board_json import write_board_solution

    written = []
    with outs.commit(sol):
        if output:
            write_board_solution(output, problem, sol)
            written.append(output)
        if svg and sol.status.has_tiling:
            from tilesolve.io.svg_board import write_board_svg

            write_board_svg(svg, problem, sol.tiling, title=problem.board.describe(), window=sol.window,
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
        say("  printed: each cell's colours N E S W ('.' = hole); -o FILE writes the JSON, --svg FILE draws it")
    written = [w for w in written if w != "-"]
    if written:
        say("  wrote " + ", ".join(written))
    ctx.exit(sol.status.exit_code)

