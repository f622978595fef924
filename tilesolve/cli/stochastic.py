"""``tilesolve tiling``: a window of a stochastic Wang or corner tiling (class notes ch. 3).

::

    tilesolve tiling --kind wang|corner [--method auto|scanline|direct] [--set complete|compact|sums]
                     --colors C --region X0,Y0,WxH [--seed S] [-o T.json] [--png T.png] [--svg T.svg]
"""

from __future__ import annotations

import click

from tilesolve.cli import options as opt
from tilesolve.cli.common import progress_wanted
from tilesolve.cli.outputs import OutputFile, Outputs
from tilesolve.cli.window_outputs import check_svg_size, finish_window
from tilesolve.errors import InvalidProblem
from tilesolve.model.window import parse_region

__all__ = ["tiling"]


@click.command(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
               short_help="Stochastic Wang/corner tilings: a window of the plane, scanline or direct.")
@click.option("--kind", type=click.Choice(["wang", "corner"]), required=True,
              help="Wang tiles (coloured edges) or corner tiles (coloured corners).")
@click.option("--method", type=click.Choice(["auto", "scanline", "direct"]), default="auto", show_default=True,
              help="scanline: west to east, north to south, each tile a hashed choice among those that fit "
                   "(§3.2; complete or compact sets); direct: each tile from hashes of the lattice around it, "
                   "the same in every window (§3.3; complete or sums sets). auto: direct unless the set is compact.")
@click.option("--set", "variant", type=click.Choice(["complete", "compact", "sums"]), default="complete",
              show_default=True,
              help="Tile set: all C^4 tiles; the compact scanline sets (2C^2 Wang, 2C^3 corner tiles, §3.2); "
                   "the C^3 sums Wang tiles of the direct compact algorithm (§3.3.2.2).")
@click.option("--colors", type=int, required=True, metavar="C", help="Number of colours C.")
@click.option("--region", required=True, metavar="X0,Y0,WxH",
              help="The window: W columns by H rows whose SW tile is (X0, Y0); y points north, coordinates may "
                   "be negative.")
@click.option("--hash", "hash_", type=click.Choice(["long", "table"]), default="long", show_default=True,
              help="Lattice hash (§3.4): the long-period hash of §3.4.3 or one permutation table.")
@click.option("--algorithm", type=click.Choice(["edges", "two"]), default="edges", show_default=True,
              help="direct, complete Wang set: hashes at the edges (§3.3.2.3) or two hashes at the corners "
                   "(§3.3.2.1).")
@opt.seed_opt
@click.option("-o", "--output", type=OutputFile("json"), metavar="T.json",
              help="Write the tiling JSON here ('-' for stdout). Without outputs the grid is printed.")
@click.option("--png", type=OutputFile("png", allow_dash=False), metavar="T.png", help="Also draw the window as PNG.")
@click.option("--svg", type=OutputFile("svg"), metavar="T.svg",
              help="Also draw the window as SVG (at most 65,536 tiles; '-' for stdout).")
@click.option("--indices", is_flag=True, help="Write tile numbers on the SVG tiles (needs --svg).")
@click.pass_context
def tiling(ctx, kind, method, variant, colors, region, hash_, algorithm, seed, output, png, svg, indices) -> None:
    """Tile a window of the plane with a stochastic Wang or corner tiling.

    The same seed gives the same tiling; with the direct method (and scanline on a complete
    set) every window shows the same tiles where windows overlap. Every window is checked by
    the independent verifier before it is written.

    \b
    Examples:
      tilesolve tiling --kind wang --method scanline --set compact --colors 2 --region 0,0,32x16 --seed 1 -o t.json --svg t.svg
      tilesolve tiling --kind corner --method direct --colors 3 --region -20,-10,40x20 --seed 1 --png c.png
      tilesolve tiling --kind wang --method direct --set sums --colors 3 --region 1000000,0,8x4 --seed 2
      tilesolve verify t.json
    """
    from tilesolve.families import stochastic as facade
    from tilesolve.model.stochastic import StochasticProblem

    if indices and not svg:
        raise InvalidProblem("--indices labels the SVG tiles: add --svg FILE")
    outs = Outputs(output, png, svg)
    problem = StochasticProblem(kind, colors, parse_region(region), variant, hash_, algorithm)
    check_svg_size(problem, svg)
    progress = progress_wanted()
    sol = facade.solve(problem, method=method, seed=seed, progress=progress)
    finish_window(ctx, problem, sol, outs, progress, output, png, svg, indices=indices)
