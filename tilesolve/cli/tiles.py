"""``tilesolve tiles``: list (and draw) a complete or compact Wang or corner tile set, or list
and print the built-in Wang tile sets.

::

    tilesolve tiles --kind wang|corner --colors C [--set complete|compact|sums] [--svg FILE]
    tilesolve tiles --builtin [NAME] [-o OUT.json]

The tile indices (eq. 2.1 for Wang tiles, eq. 2.5 for corner tiles) are the last line of
standard output, space-separated (unless ``--svg -`` puts the picture there); a one-line
summary goes to stderr (hidden by ``-q``).
"""

from __future__ import annotations

import click

from tilesolve.cli import options as opt
from tilesolve.cli.common import check_colors, say
from tilesolve.cli.outputs import OutputFile, Outputs

__all__ = ["tiles"]


@click.command(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
               short_help="List or draw a complete or compact Wang or corner tile set.")
@click.option("--kind", type=click.Choice(["wang", "corner"]),
              help="Wang tiles (coloured edges, N E S W) or corner tiles (coloured corners, NE SE SW NW).")
@click.option("--colors", type=int, metavar="C", help="Number of colours C (>= 2).")
@click.option("--set", "variant", type=click.Choice(["complete", "compact", "sums"]), default="complete",
              show_default=True,
              help="complete: all C^4 tiles (notes §2.7); compact: two tiles per (N, W) edge colours, 2C^2 "
                   "Wang tiles (§3.2.1), or per (NE, NW, SW) corner colours, 2C^3 corner tiles (§3.2.2); "
                   "sums: the C^3 Wang tiles whose edges are sums of corner colours (§3.3.2.2).")
@click.option("--svg", type=OutputFile("svg"), metavar="OUT.svg",
              help="Also draw the set: one tile per index, in index order, labelled ('-' for stdout).")
@click.option("--png", type=OutputFile("png", allow_dash=False), metavar="OUT.png",
              help="Also draw the set as PNG (large sets), tiles in index order.")
@click.option("-o", "--output", type=OutputFile("json"), metavar="OUT.json",
              help="Write a Wang set as a tilesolve/wang-tileset file (tiles as [N, E, S, W]) for wang solve --tiles.")
@click.option("--builtin", is_flag=False, flag_value="", default=None, metavar="[NAME]",
              help="Alone: list the built-in Wang tile sets (name, tiles, colours, literature verdict). With "
                   "NAME: print that set's tiles, one 'N E S W' line each (and -o writes it).")
def tiles(kind: str | None, colors: int | None, variant: str, svg: str | None, png: str | None, output: str | None,
          builtin: str | None) -> None:
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
      tilesolve tiles --builtin
      tilesolve tiles --builtin jeandel-rao -o jr.json
    """
    from tilesolve.errors import InvalidProblem
    from tilesolve.model.tiles import TileSet

    if builtin is not None:
        if kind or colors is not None or svg or png:
            raise InvalidProblem("--builtin lists or prints a built-in set; drop --kind, --colors, --svg and --png")
        _builtin(builtin, output)
        return
    if kind is None or colors is None:
        raise InvalidProblem("give --kind and --colors (or --builtin to list the built-in tile sets)")
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


def _verdict(info: dict) -> str:
    extra = {"periodic": "period", "finite": "max_square"}.get(info["verdict"])
    return info["verdict"] + (f" ({extra.replace('_', ' ')} {info[extra]})" if extra in info else "")


def _builtin(name: str, output: str | None) -> None:
    """``--builtin``: the table of built-in sets, or one set's tiles (and its file with -o)."""
    from tilesolve.io.builtin_tilesets import load, names

    if not name:
        if output:
            from tilesolve.errors import InvalidProblem

            raise InvalidProblem("-o writes one set: give its name, --builtin NAME")
        rows = [load(n)[1] for n in names()]
        width = max(len(r["name"]) for r in rows)
        click.echo(f"{'name':<{width}}  tiles  colours  verdict (literature)")
        for r in rows:
            click.echo(f"{r['name']:<{width}}  {r['n_tiles']:>5}  {r['n_colors']:>7}  {_verdict(r)}")
        say(f"{len(rows)} built-in tile sets; `tilesolve tiles --builtin NAME` prints one")
        return
    ts, info = load(name)
    outs = Outputs(output)
    with outs.commit():
        if output:
            from tilesolve.io.tileset_json import write_tileset

            write_tileset(output, ts, name=name, about={k: info[k] for k in info
                                                         if k not in ("name", "n_tiles", "n_colors")})
    say(f"{name}: {info['title']}; {len(ts)} tiles, {ts.n_colors} colours; {_verdict(info)} ({info['reference']})"
        + (f"; wrote {output}" if output and output != "-" else ""))
    if output != "-":
        for t in ts.tiles.tolist():
            click.echo(" ".join(map(str, t)))
