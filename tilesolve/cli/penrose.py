"""``tilesolve penrose`` and ``tilesolve reptile``: substitution tilings (class notes Part II §8.1, §8.3).

::

    tilesolve penrose --kind p3|p2 [--method auto|substitution|pentagrid] (--region X0,Y0,WxH | --steps N)
                      [--seed S] [-o T.json] [--svg T.svg] [--png T.png]
    tilesolve reptile --tile chair|sphinx|l-tetromino|p-pentomino --steps N [--seed S] [-o T.json] [--svg T.svg]
                      [--png T.png]
"""

from __future__ import annotations

import click

from tilesolve.cli import options as opt
from tilesolve.cli.common import say
from tilesolve.cli.outputs import OutputFile, Outputs
from tilesolve.errors import InvalidProblem
from tilesolve.model.window import parse_region

__all__ = ["penrose", "reptile"]

_OUTPUTS = (
    click.option("-o", "--output", type=OutputFile("json"), metavar="T.json",
                 help="Write the patch JSON here ('-' for stdout); `tilesolve verify T.json` re-checks it."),
    click.option("--svg", type=OutputFile("svg"), metavar="T.svg",
                 help="Draw the patch as SVG (at most 200,000 tiles)."),
    click.option("--png", type=OutputFile("png", allow_dash=False), metavar="T.png", help="Draw the patch as PNG."),
)


def _outputs(f):
    for o in reversed(_OUTPUTS):
        f = o(f)
    return f


def _run(ctx, problem, method: str, seed, output, svg, png) -> None:
    from tilesolve.families import substitution as facade
    from tilesolve.family import draw_solution, write_solution
    from tilesolve.io.substitution_json import MAX_SVG_TILES

    if svg and problem.estimate > 2 * MAX_SVG_TILES:
        raise InvalidProblem(f"a patch of about {problem.estimate:,} tiles is too large for SVG "
                             f"(at most {MAX_SVG_TILES:,}); use --png")
    outs = Outputs(output, png, svg)
    sol = facade.solve(problem, method=method, seed=seed)
    with outs.commit(sol):
        if output:
            write_solution(output, problem, sol)
        if png:
            draw_solution(png, problem, sol, fmt="png")
        if svg:
            draw_solution(svg, problem, sol, fmt="svg")
    counts = ", ".join(f"{v:,} {k}" for k, v in sol.tiling.counts().items())
    say(f"{sol.status.value}: {problem.describe()} by {sol.method}, seed {sol.seed}: {sol.tiling.n_tiles:,} tiles "
        f"({counts}), verified, in {sol.time_s:.2f} s")
    if outs.files:
        say(f"  wrote {', '.join(outs.files)}")
    ctx.exit(sol.status.exit_code)


@click.command(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
               short_help="Penrose rhombs (P3) or kites and darts (P2): substitution or de Bruijn's pentagrid.")
@click.option("--kind", type=click.Choice(["p3", "p2"]), default="p3", show_default=True,
              help="p3: thin and thick rhombs; p2: kites and darts (from P3 by the Robinson-triangle correspondence).")
@click.option("--method", type=click.Choice(["auto", "substitution", "pentagrid"]), default="auto",
              show_default=True,
              help="substitution: deflate a sun of Robinson triangles (--steps N, or until it covers --region); "
                   "pentagrid: de Bruijn's five grids, any window anywhere (--region). auto: pentagrid with a region.")
@click.option("--region", metavar="X0,Y0,WxH",
              help="The window: W by H units (the rhomb edge is 1) from (X0, Y0); the tiles whose centre lies in it.")
@click.option("--steps", type=int, metavar="N", help="Substitution steps from the sun (about 3.6 x 2.618^N rhombs).")
@opt.seed_opt
@_outputs
@click.pass_context
def penrose(ctx, kind, method, region, steps, seed, output, svg, png) -> None:
    """Penrose tilings with their matching rules: a window of the plane or a deflated sun.

    Every patch is checked by the independent verifier (tile shapes, every shared edge's
    arrows, the angles around each vertex, one piece without holes) before it is written.
    The pentagrid's offsets come from the seed: the same seed gives the same tiles in every
    window.

    \b
    Examples:
      tilesolve penrose --kind p3 --region -20,-10,40x20 --seed 1 -o t.json --svg t.svg
      tilesolve penrose --kind p2 --method substitution --steps 6 --png kd.png
      tilesolve penrose --kind p3 --region 100000,-5000,30x20 --seed 7 -o far.json
      tilesolve verify t.json
    """
    from tilesolve.model.substitution import SubstitutionProblem

    if (region is None) == (steps is None):
        raise InvalidProblem("give either --region X0,Y0,WxH or --steps N")
    if region is not None:
        w = parse_region(region)
        problem = SubstitutionProblem(kind, region=(w.x0, w.y0, w.width, w.height))
    else:
        problem = SubstitutionProblem(kind, steps=steps)
    _run(ctx, problem, method, seed, output, svg, png)


@click.command(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
               short_help="Rep-tile substitution tilings: the chair, the sphinx, polyomino rep-tiles.")
@click.option("--tile", type=click.Choice(["chair", "sphinx", "l-tetromino", "p-pentomino"]), default="chair",
              show_default=True, help="The rep-tile (each is the union of four half-size copies of itself).")
@click.option("--steps", type=int, required=True, metavar="N", help="Substitution steps (4^N tiles).")
@click.option("--method", type=click.Choice(["auto", "substitution"]), default="auto", show_default=True,
              help="The one route: the rep-tile's rule applied N times.")
@click.option("--seed", type=click.IntRange(0, opt.MAX_SEED), default=None, metavar="N",
              help="Recorded in the file; a rep-tile patch does not depend on it.")
@_outputs
@click.pass_context
def reptile(ctx, tile, steps, method, seed, output, svg, png) -> None:
    """Substitution tilings by rep-tiles, with exact integer coordinates.

    The rule (four copies of the tile that make the doubled tile) is found by an exact cover,
    then applied N times; the patch is checked to cover the tile scaled by 2^N exactly.

    \b
    Examples:
      tilesolve reptile --tile chair --steps 4 -o chair.json --svg chair.svg
      tilesolve reptile --tile sphinx --steps 5 --png sphinx.png
      tilesolve verify chair.json
    """
    from tilesolve.model.substitution import SubstitutionProblem

    _run(ctx, SubstitutionProblem(tile, steps=steps), method, seed, output, svg, png)
