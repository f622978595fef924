"""``tilesolve aperiodic tiling``: a window of a tiling of the plane by a built-in aperiodic set.

::

    tilesolve aperiodic tiling --builtin jeandel-rao|labbe-u19|kari-14|kari-culik-13 --region X0,Y0,WxH
                               [--seed S] [-o T.json] [--png T.png] [--svg T.svg]
"""

from __future__ import annotations

import click

from tilesolve.cli import options as opt
from tilesolve.cli.common import progress_wanted
from tilesolve.cli.outputs import OutputFile, Outputs
from tilesolve.cli.window_outputs import check_svg_size, finish_window
from tilesolve.errors import InvalidProblem
from tilesolve.io.units import big

__all__ = ["tiling", "MAX_PRINTED_TILES"]

#: Most tiles printed as text when no output is given.
MAX_PRINTED_TILES = 1 << 16


@click.command(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
               short_help="A window of a tiling of the plane by an aperiodic set, by its constructive route.")
@click.option("--builtin", required=True, metavar="NAME",
              help="The tile set: jeandel-rao or labbe-u19 (coded by a Markov partition of the torus, Labbé 2021), "
                   "kari-14 or kari-culik-13 (rows of balanced sequences, Kari and Culik 1996).")
@click.option("--region", required=True, metavar="X0,Y0,WxH",
              help="The window: W columns by H rows whose bottom-left cell is (X0, Y0); y points up, coordinates "
                   "may be negative.")
@opt.seed_opt
@click.option("-o", "--output", type=OutputFile("json"), metavar="T.json",
              help="Write the window JSON here ('-' for stdout). Without outputs the grid is printed.")
@click.option("--png", type=OutputFile("png", allow_dash=False), metavar="T.png",
              help="Also draw the window as PNG (written band by band, any size).")
@click.option("--svg", type=OutputFile("svg"), metavar="T.svg",
              help="Also draw the window as SVG (at most 65,536 tiles; '-' for stdout).")
@click.pass_context
def tiling(ctx, builtin, region, seed, output, png, svg) -> None:
    """Tile a window of the plane with a built-in aperiodic Wang tile set, by its constructive route.

    The seed chooses the tiling of the plane: the same seed gives the same file, byte for
    byte, and windows of one seed agree where they overlap. Every window is checked by the
    independent grid verifier before it is written; the file records the tile set, the
    window's origin and size, the route and the seed (tilesolve verify re-checks it against
    the built-in set). Entries of the grid are tile indices in the set's order (tilesolve
    tiles --builtin NAME), row 0 the top row.

    \b
    Examples:
      tilesolve aperiodic tiling --builtin jeandel-rao --region -20,-10,40x24 --seed 1 -o jr.json --png jr.png
      tilesolve aperiodic tiling --builtin kari-culik-13 --region 0,0,24x12 --seed 2 --svg kc.svg
      tilesolve aperiodic tiling --builtin labbe-u19 --region 1000,-1000,8x4 --seed 3
      tilesolve verify jr.json
    """
    from tilesolve.families import aperiodic_window as facade
    from tilesolve.model.window import parse_region

    outs = Outputs(output, png, svg)
    problem = facade.window_problem(builtin, parse_region(region))
    rows, cols = problem.shape
    if not outs and problem.n_cells > MAX_PRINTED_TILES:
        raise InvalidProblem(f"a {cols}x{rows} window has {big(problem.n_cells)} tiles, too many to print (at most "
                             f"{MAX_PRINTED_TILES:,}): write it with -o T.json or --png T.png")
    check_svg_size(problem, svg)
    progress = progress_wanted()
    sol = facade.solve(problem, seed=seed, progress=progress)
    finish_window(ctx, problem, sol, outs, progress, output, png, svg)
