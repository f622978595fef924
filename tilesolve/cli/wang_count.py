"""``tilesolve wang count``: count the Wang tilings of a small board exactly, and the tile-set
options every Wang command shares (``--tiles FILE [--format F]`` or ``--builtin NAME``).

::

    tilesolve wang count --tiles TILES | --builtin NAME --board rect:WxH|torus:WxH|... [--method M]
"""

from __future__ import annotations

import click

from tilesolve.cli import options as opt
from tilesolve.cli.common import progress_wanted, say
from tilesolve.errors import InvalidProblem
from tilesolve.family import raise_if_interrupted

__all__ = ["tileset_options", "load_tileset", "wang_count"]

TILESET_FORMATS = ("json", "nswe", "tilesat", "rtlb")

tileset_options = opt.compose(
    click.option("--tiles", "tiles_path", type=click.Path(dir_okay=False), metavar="TILES",
                 help="A tile-set file: tilesolve/wang-tileset JSON (tiles as [N, E, S, W]), 'n s w e' lines "
                      "(*.tiles), a TileSAT file, or (right, top, left, bottom) tuples; see --format."),
    click.option("--format", "tiles_format", type=click.Choice(TILESET_FORMATS), default=None,
                 help="The tile-set file's format: json, nswe (n s w e lines), tilesat (header + N E S W, "
                      "colours from 1), rtlb (right top left bottom). Default: by extension or content."),
    click.option("--builtin", metavar="NAME",
                 help="A built-in tile set instead of --tiles (`tilesolve tiles --builtin` lists them)."),
)


def load_tileset(tiles_path: str | None, tiles_format: str | None, builtin: str | None):
    """The tile set the options name, and the notes to print (dropped duplicates)."""
    if (tiles_path is None) == (builtin is None):
        raise InvalidProblem("give a tile set: --tiles FILE or --builtin NAME (one of them)")
    if builtin is not None:
        if tiles_format is not None:
            raise InvalidProblem("--format describes a --tiles file; a --builtin set has none")
        from tilesolve.io.builtin_tilesets import load

        return load(builtin)[0], []
    from tilesolve.io.tileset_formats import read_tileset_file

    return read_tileset_file(tiles_path, tiles_format)


@click.command(name="count", context_settings=opt.CONTEXT_SETTINGS, epilog=opt.READER_HELP,
               short_help="Count the tilings of a small board with any Wang tile set.")
@tileset_options
@click.option("--board", "board_spec", required=True, metavar="SPEC",
              help="rect:WxH, torus:WxH, cylinder:WxH (transfer method), or any board of `wang solve`.")
@click.option("--method", type=click.Choice(["auto", "transfer", "enumerate"]), default="auto", show_default=True,
              help="transfer: a transfer matrix over row words (free rectangles, cylinders, tori); enumerate: "
                   "SAT enumeration (any board); auto: transfer where it applies.")
@opt.time_limit_opt
@click.pass_context
def wang_count(ctx, tiles_path, tiles_format, builtin, board_spec, method, time_limit) -> None:
    """Count the tilings of a board with free boundary colours exactly; the count is the last
    line of stdout.

    Rectangles, cylinders and tori are counted by a transfer matrix whose states are the
    colour words of a row (exact big integers); other boards by SAT enumeration.

    \b
    Examples:
      tilesolve wang count --builtin jeandel-rao --board rect:6x6        # prints 50638
      tilesolve wang count --builtin jeandel-rao --board torus:4x4       # prints 0 (no 4x4 period)
      tilesolve tiles --kind wang --colors 3 --set sums -o tiles.json
      tilesolve wang count --tiles tiles.json --board cylinder:5x3       # prints 3486784401
      tilesolve wang count --builtin jeandel-rao --board mobius:3x2      # prints 16 (by enumeration)
    """
    from tilesolve.families import board as facade
    from tilesolve.io.mask import read_board_spec
    from tilesolve.model.board import BoardProblem

    ts, notes = load_tileset(tiles_path, tiles_format, builtin)
    for note in notes:
        say(f"note: {note}")
    problem = BoardProblem(read_board_spec(board_spec), ts)
    res = raise_if_interrupted(facade.count(problem, method=method, time_limit=time_limit, progress=progress_wanted()))
    say(f"{'count' if res.value is not None else 'unknown'} by {res.method}: {problem.describe()}  "
        f"({res.time_s:.3f} s)")
    if res.value is None:
        say(f"  stopped: {res.note}")
        ctx.exit(3)
    click.echo(str(res.value))
    ctx.exit(0)
