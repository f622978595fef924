"""``tilesolve wang solve | count``: any Wang tile set on any board, a thin layer over
:mod:`tilesolve.families.board`."""

from __future__ import annotations

import click

from tilesolve.cli import options as opt
from tilesolve.cli.board_common import (
    BOARD_HELP,
    board_opt,
    boundary_opt,
    method_opt,
    parse_boundary,
    solve_board,
    svg_opt,
)
from tilesolve.cli.common import say
from tilesolve.cli.outputs import Outputs
from tilesolve.cli.wang_count import load_tileset, tileset_options, wang_count
from tilesolve.family import draw_seed

__all__ = ["wang"]


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
      tilesolve tiles --kind wang --colors 3 --set sums -o tiles.json
      tilesolve wang solve --tiles tiles.json --board torus:8x8 --boundary free -o t.json --svg t.svg
      tilesolve wang solve --builtin jeandel-rao --board rect:12x12 --boundary free --svg jr.svg

    Without -o or --svg the tiling is printed as text: each cell's colours N E S W.
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
    problem = BoardProblem(board, ts, parse_boundary(boundary, board, ts.n_colors, seed))
    solve_board(ctx, problem, method, seed, time_limit, outs, output, svg)
