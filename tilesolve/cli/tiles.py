"""``tilesolve tiles``: list (and draw) a complete or compact Wang or corner tile set.

::

    tilesolve tiles --kind wang|corner --colors C [--set complete|compact|sums] [--svg FILE]

The tile indices (eq. 2.1 for Wang tiles, eq. 2.5 for corner tiles) are the last line of
standard output, space-separated (unless ``--svg -`` puts the picture there); a one-line
summary goes to stderr (hidden by ``-q``).
"""

from __future__ import annotations

import click

from tilesolve.cli import options as opt
from tilesolve.cli.common import check_colors, say
from tilesolve.cli.outputs import Outputs

__all__ = ["tiles"]


@click.command(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
               short_help="List or draw a complete or compact Wang or corner tile set.")
@click.option("--kind", type=click.Choice(["wang", "corner"]), required=True,
              help="Wang tiles (coloured edges, N E S W) or corner tiles (coloured corners, NE SE SW NW).")
@click.option("--colors", type=int, required=True, metavar="C", help="Number of colours C (>= 2).")
@click.option("--set", "variant", type=click.Choice(["complete", "compact", "sums"]), default="complete",
              show_default=True,
              help="complete: all C^4 tiles (notes §2.7); compact: two tiles per (N, W) edge colours, 2C^2 "
                   "Wang tiles (§3.2.1), or per (NE, NW, SW) corner colours, 2C^3 corner tiles (§3.2.2); "
                   "sums: the C^3 Wang tiles whose edges are sums of corner colours (§3.3.2.2).")
@click.option("--svg", type=click.Path(dir_okay=False, allow_dash=True), metavar="OUT.svg",
              help="Also draw the set: one tile per index, in index order, labelled ('-' for stdout).")
@click.option("--png", type=click.Path(dir_okay=False), metavar="OUT.png",
              help="Also draw the set as PNG (large sets), tiles in index order.")
@click.option("-o", "--output", type=click.Path(dir_okay=False, allow_dash=True), metavar="OUT.json",
              help="Write a Wang set as a tilesolve/wang-tileset file (tiles as [N, E, S, W]) for wang solve --tiles.")
def tiles(kind: str, colors: int, variant: str, svg: str | None, png: str | None, output: str | None) -> None:
    """Print the indices of the tiles of a Wang or corner tile set (class notes §2.7, §3.2-3.3).

    Wang tile N E S W over C colours has index ((N*C + E)*C + S)*C + W (eq. 2.1); corner
    tile NE SE SW NW has index ((NE*C + SE)*C + SW)*C + NW (eq. 2.5). The notes give the
    compact sets only for C = 2; for larger C tilesolve picks one (see the TileSet docs).

    \b
    Examples:
      tilesolve tiles --kind wang --colors 2 --set compact        # 0 3 5 6 9 10 12 15 (notes Fig. 3.2)
      tilesolve tiles --kind corner --colors 3 --set compact --svg c3.svg
      tilesolve tiles --kind wang --colors 3 --set sums
      tilesolve tiles --kind wang --colors 3 --set compact -o compact3.json --png compact3.png
    """
    from tilesolve.errors import InvalidProblem
    from tilesolve.model.tiles import TileSet

    outs = Outputs(output, svg, png)
    check_colors(kind, colors)
    if output and kind != "wang":
        raise InvalidProblem("-o writes Wang tile-set files; corner tiles have no such file (draw them with --svg/--png)")
    ts = TileSet(kind, colors, variant=variant)
    with outs.commit():
        if svg:
            from tilesolve.io.svg_tileset import write_tileset_svg

            write_tileset_svg(svg, ts)
        if png:
            from tilesolve.io.png import write_tileset_png

            write_tileset_png(png, ts)
        if output:
            from tilesolve.io.tileset_json import write_tileset
            from tilesolve.model.board import WangTileSet

            write_tileset(output, WangTileSet.from_tileset(ts), name=ts.describe())
    say(ts.describe() + (f"; wrote {', '.join(outs.files)}" if outs.files else ""))
    if "-" not in (svg, output):
        click.echo(" ".join(map(str, ts.indices.tolist())))
