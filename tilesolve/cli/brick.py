"""``tilesolve brick solve | wall | count | crosscheck``: brick Wang tilings of boards, thin
layers over :mod:`tilesolve.families.board` and :mod:`tilesolve.families.walls`."""

from __future__ import annotations

import click

from tilesolve.cli import options as opt
from tilesolve.cli.board_common import (
    BOARD_HELP,
    board_opt,
    boundary_opt,
    check_brick_colors,
    check_svg_cells,
    colors_opt,
    finish,
    line_opts,
    method_opt,
    parse_boundary,
    solve_board,
    svg_opt,
)
from tilesolve.cli.common import say, sweep_trials
from tilesolve.cli.outputs import Outputs
from tilesolve.family import draw_seed, raise_if_interrupted

__all__ = ["brick"]


@click.group(context_settings=opt.CONTEXT_SETTINGS, short_help="Brick Wang tilings of boards; brick walls.")
def brick() -> None:
    """Brick Wang tiles on boards (Derouet-Jourdan, Kaji, Mizoguchi 2016).

    A brick Wang tile (Def. 9) has W = E or N = S, never both (the paper's c1 = c3 xor
    c2 = c4 on its legs l1..l4 = W, N, E, S): one straight mortar line crosses it, never two.
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
      tilesolve brick solve --board 'mask:################/####...#########/###.....####..##/####...#########/################' --colors 4 -o s.json

    Without -o or --svg the tiling is printed as text: each cell's colours N E S W.
    """
    from tilesolve.io.mask import read_board_spec
    from tilesolve.model.board import BoardProblem, WangTileSet

    outs = Outputs(output, svg)
    check_brick_colors(colors)
    tileset = WangTileSet.brick(colors)
    board = read_board_spec(board_spec)
    if seed is None:
        seed = draw_seed()
    problem = BoardProblem(board, tileset, parse_boundary(boundary, board, colors, seed),
                           max_h=max_h, max_v=max_v)
    solve_board(ctx, problem, method, seed, time_limit, outs, output, svg)


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

    Without -o or --svg the wall is printed as text: each cell's colours N E S W.
    """
    from tilesolve.families.walls import brick_wall
    from tilesolve.model.dappled import parse_size

    outs = Outputs(output, svg)
    rows, cols = parse_size(size)
    check_svg_cells(svg, rows * cols)
    check_brick_colors(colors)
    if seed is None:
        seed = draw_seed()
    problem, sol = brick_wall(cols, rows, max_line, max_v=max_v, n_colors=colors, seed=seed)
    finish(ctx, problem, sol, outs, output, svg)


def _brick_problem(board_spec, colors, boundary, seed):
    from tilesolve.io.mask import read_board_spec
    from tilesolve.model.board import BoardProblem, WangTileSet

    check_brick_colors(colors)
    tileset = WangTileSet.brick(colors)
    board = read_board_spec(board_spec)
    return BoardProblem(board, tileset, parse_boundary(boundary, board, colors, seed))


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
              help="N trials with seeds SEED, SEED+1, ... (with --boundary random, a new random boundary each time).")
@click.pass_context
def crosscheck(ctx, board_spec, colors, boundary, seed, time_limit, trials) -> None:
    """Run the linear algorithm, SAT and CP-SAT on one board and check that they agree.

    \b
    Example:
      tilesolve brick crosscheck --board 'mask:##########/###..#####/##....####/###..#####/##########' --trials 5
    """
    from tilesolve.families import board as facade

    base = draw_seed() if seed is None else seed

    def run_trial(i):
        problem = _brick_problem(board_spec, colors, boundary, base + i)
        return f"seed {base + i}", facade.crosscheck(problem, seed=base + i, time_limit=time_limit)

    sweep_trials(ctx, trials, run_trial, "crosscheck: all routes agree")

