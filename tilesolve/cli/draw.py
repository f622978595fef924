"""``tilesolve draw FILE -o PICTURE``: draw an existing solution file of any family."""

from __future__ import annotations

import click

from tilesolve.cli import options as opt
from tilesolve.cli.common import check_writable, say
from tilesolve.cli.outputs import OutputFile, check_suffix

__all__ = ["draw"]


@click.command(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.READER_HELP)
@click.argument("file", type=click.Path(dir_okay=False))
@click.option("-o", "--output", required=True, type=OutputFile("svg", "png", allow_dash=False),
              metavar="OUT.svg|OUT.png",
              help="The picture; its suffix (.svg or .png) chooses the format.")
@opt.repeat_opt
@opt.grid_opt
@click.pass_context
def draw(ctx, file: str, output: str, repeat: int, grid) -> None:
    """Draw the tiling held in a solution FILE (any family) as SVG or PNG.

    \b
    Example:
      tilesolve dappled solve --size 64x48 --cond H0=2,V1=2 --cyclic -o t.json
      tilesolve draw t.json -o t.svg --repeat 2
      tilesolve draw t.json -o t.png

    A file that holds a window of the plane (a wall, a stochastic tiling) is drawn with its
    window's coordinates, read from the file's window.

    Exit 0 when the picture was written; 1 when the file holds no tiling (unsat/unknown);
    2 when the file is malformed, and so when a board file lists cells and edges that are not
    the board it describes, or holds tiles that are not 4 colours of C for each of its cells
    (tilesolve verify tells where).
    """
    from tilesolve.family import draw_solution, read_document

    fmt = check_suffix(output, ("svg", "png"))
    check_writable(output)
    fam, codec, doc = read_document(file)
    problem, sol = codec.read(doc, file)
    if sol is None or sol.answer is None:
        what = "no solution" if sol is None else f"status {sol.status.value}, no tiling"
        click.echo(f"tilesolve: {file} holds {what}: nothing to draw", err=True)
        ctx.exit(1)
    options = {}
    if repeat > 1:
        options["repeat"] = repeat
    if grid is not None:
        options["grid"] = grid
    draw_solution(output, problem, sol, fmt=fmt, **options)
    say(f"wrote {output}: {fam.name} solution of {problem.describe()}")
    if sol.window is not None:
        say(f"  {sol.window.caption()}")
