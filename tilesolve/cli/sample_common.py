"""What the sampling commands share (``sample poisson-tiles``, ``poisson-spheres`` and
``recursive-wang``): a window's set and region, its point files and pictures, a built set
written, a picture read."""

from __future__ import annotations

import click

from tilesolve.cli import options as opt
from tilesolve.cli.common import say
from tilesolve.cli.outputs import OutputFile, Outputs

__all__ = ["done", "write_set", "set_and_region", "hash_option", "point_outputs", "write_window", "read_image"]


def done(ctx, outs: Outputs) -> None:
    """Say which files were written and exit 0."""
    if outs.files:
        say(f"  wrote {', '.join(outs.files)}")
    ctx.exit(0)


def write_set(ctx, outs: Outputs, output: str, problem, sol, text) -> None:
    """Write a built tile set (``text()``, its JSON) to ``output`` (``-``: stdout) and say what was built."""
    from tilesolve.io.atomic import write_text_atomic

    with outs.commit(sol):
        if output == "-":
            click.echo(text(), nl=False)
        else:
            write_text_atomic(output, text())
    short = sol.stats.get("short", 0)
    say(f"{sol.status.value}: {problem.describe()}, {sol.stats['points']:,} points, seed {sol.seed}, "
        f"in {sol.time_s:.2f} s" + (f"; interior tiles lack {short} points in all" if short else ""))
    done(ctx, outs)


def set_and_region(cells: str):
    """The SET.json argument and the --region option of a command that lays out a window of
    ``cells`` (e.g. ``"tiles"``)."""
    return opt.compose(
        click.argument("tileset", type=click.Path(dir_okay=False), metavar="SET.json"),
        click.option("--region", required=True, metavar="X0,Y0,WxH",
                     help=f"W x H {cells} whose SW tile is (X0, Y0); y points north, coordinates may be negative."),
    )


#: The lattice hash of a window's corner tiling.
hash_option = click.option("--hash", "hash_", type=click.Choice(["long", "table"]), default="long", show_default=True,
                           help="Lattice hash of the corner tiling (§3.4).")


def point_outputs(what: str):
    """A window's -o (JSON, CSV or NPY of ``what``), --svg and --png options."""
    return opt.compose(
        click.option("-o", "--output", type=OutputFile("json", "csv", "npy", allow_dash=False),
                     metavar="PTS.csv|npy|json", help=f"Write {what}: JSON (relative to the window's corner, any "
                     "window, with all it is made from, which `tilesolve verify` re-derives), CSV or NPY (plane "
                     "coordinates)."),
        click.option("--svg", type=OutputFile("svg", allow_dash=False), metavar="PTS.svg",
                     help="Draw the points as SVG."),
        click.option("--png", type=OutputFile("png", allow_dash=False), metavar="PTS.png",
                     help="Draw the points as PNG."),
    )


def write_window(ctx, outs: Outputs, paths: tuple, problem, sol, write_points, distance: float, caption: str) -> None:
    """Write a sampled window's points (``write_points(output, problem, sol)``) and pictures (dots
    sized by ``distance``) to ``paths``, ``(output, svg, png)``; say what was sampled."""
    from tilesolve.io.poisson_plots import write_points_picture

    output, svg, png = paths
    w = sol.tiling
    with outs.commit(sol):
        if output:
            write_points(output, problem, sol)
        for path, fmt in ((svg, "svg"), (png, "png")):
            if path:
                write_points_picture(path, w.local, w.window, distance, caption, fmt)
    say(f"{sol.status.value}: {w.n_points:,} points, {problem.describe()}, seed {sol.seed}, in {sol.time_s:.2f} s")
    done(ctx, outs)


def read_image(path: str):
    """An RGBA array of a picture file of at most 2**22 pixels, or a one-line error
    (:func:`tilesolve.io.images.read_rgba`)."""
    from tilesolve.io.images import read_rgba

    return read_rgba(path, 1 << 22)
