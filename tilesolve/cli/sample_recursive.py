"""``tilesolve sample recursive-wang``: recursive Wang tiles for multi-density blue noise
(Kopf et al. 2006; class notes Part V).

::

    tilesolve sample recursive-wang build -C 2 -N 16 --rho 0.7 -n 4 [--seed S] -o set.json
    tilesolve sample recursive-wang window set.json --region X0,Y0,WxH
                     (--level L | --density D | --ramp D0,D1 | --image IMG.png --max-density D)
                     [--seed S] [-o pts.json|pts.csv|pts.npy] [--svg pts.svg] [--png pts.png]
"""

from __future__ import annotations

import click

from tilesolve.cli import options as opt
from tilesolve.cli.outputs import OutputFile, Outputs
from tilesolve.cli.sample_common import hash_option, point_outputs, read_image, set_and_region, write_set, write_window
from tilesolve.errors import InvalidProblem

__all__ = ["recursive_wang"]

#: Columns of a density ramp's grid.
RAMP_STEPS = 1024


@click.group("recursive-wang", context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
             short_help="Recursive Wang tiles: blue noise at any density, every level verified (Kopf et al. 2006).")
def recursive_wang() -> None:
    """Recursive Wang tiles (Kopf, Cohen-Or, Deussen and Lischinski 2006; class notes Part V).

    The 16 Wang tiles equivalent to the complete corner set over 2 colours (§2.9; C^4 for C
    colours) carry corner-based Poisson disk points (§4.3) in progressive order and subdivide
    into n x n sub-tiles of the same set. Level l places the tiles n^l times smaller; its
    points are the level below's and the new points at least d / n^l from them, so every
    level is a Poisson disk distribution at its own distance d / n^l, across tile seams too.
    A density (a number, a ramp or an image) picks each point by its level and rank.

    \b
    Examples:
      tilesolve sample recursive-wang build -C 2 -N 16 --rho 0.7 -n 4 --seed 1 -o rset.json
      tilesolve sample recursive-wang window rset.json --region 0,0,8x4 --ramp 16,4096 --seed 2 --svg ramp.svg
      tilesolve sample recursive-wang window rset.json --region 0,0,4x4 --level 2 --seed 2 -o pts.json
      tilesolve verify pts.json
    """


def _load_set(path: str):
    from tilesolve.io.jsonio import load_document
    from tilesolve.io.poisson_recursive_json import TILES_FORMAT, VERSIONS, set_from_dict

    return set_from_dict(load_document(path, {TILES_FORMAT: VERSIONS}), path)[1].tiling


@recursive_wang.command(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
                        short_help="Build a set: C colours, N points a tile, rho, n x n subdivision.")
@click.option("-C", "--colors", type=int, default=2, show_default=True, metavar="C",
              help="Corner colours (1..8): C^4 Wang tiles.")
@click.option("-N", "--points", type=int, required=True, metavar="N", help="Points a tile at level 0.")
@click.option("--rho", type=float, default=0.7, show_default=True,
              help="Relative radius of every level: level l keeps 2 rho r_max(N) / n^l; 0.05..0.85.")
@click.option("-n", "--subdivision", type=int, default=4, show_default=True, metavar="n",
              help="Each tile splits into n x n sub-tiles (2..8): n^2 times the density a level.")
@click.option("--lloyd", type=int, default=0, show_default=True, metavar="K",
              help="Lloyd relaxation steps of the corner tiles (§4.2.4.3).")
@opt.seed_opt
@click.option("-o", "--output", type=OutputFile("json"), required=True, metavar="SET.json",
              help="Write the tile set here ('-' for stdout).")
@click.pass_context
def build(ctx, colors, points, rho, subdivision, lloyd, seed, output) -> None:
    """Build a set of recursive Wang tiles and verify it.

    The set is checked before it is written: every tiling of its corner tiles is a Poisson
    disk distribution (all 2 x 2 blocks for C <= 2), and its subdivision rules turn every
    tiling into a tiling (corner colours kept, one sub-colouring for each kind of edge).
    The same seed gives the same file, byte for byte.

    \b
    Examples:
      tilesolve sample recursive-wang build -C 2 -N 16 --rho 0.7 -n 4 --seed 1 -o rset.json
      tilesolve sample recursive-wang build -C 2 -N 32 --rho 0.75 -n 2 --seed 3 -o rset2.json
    """
    from tilesolve.families.poisson_recursive import solve
    from tilesolve.io.poisson_recursive_json import dump, set_to_dict
    from tilesolve.model.poisson_recursive import RecursiveTilesProblem

    problem = RecursiveTilesProblem(colors, points, rho, subdivision, lloyd)
    outs = Outputs(output)
    sol = solve(problem, method="build", seed=seed)
    write_set(ctx, outs, output, problem, sol, lambda: dump(set_to_dict(problem, sol)))


def _ramp(text: str):
    import numpy as np

    try:
        lo, hi = (float(v) for v in text.split(","))
    except ValueError:
        raise InvalidProblem(f"cannot read --ramp {text!r}: expected D0,D1 (points a unit area, west to east)") \
            from None
    return np.linspace(lo, hi, RAMP_STEPS)[None, :]


def _image_density(path: str, top: float):
    """Density ``top * (1 - luminance)`` of a picture (transparent pixels: no points)."""
    import numpy as np

    rgba = read_image(path).astype(np.float64) / 255.0
    lum = rgba[..., :3] @ np.array([0.299, 0.587, 0.114])
    return top * (1.0 - lum) * rgba[..., 3]


def _density(level, density, ramp, image, max_density):
    given = [name for name, v in (("--level", level), ("--density", density), ("--ramp", ramp), ("--image", image))
             if v is not None]
    if len(given) != 1:
        raise InvalidProblem("give exactly one of --level, --density, --ramp and --image"
                             + (f" (got {', '.join(given)})" if given else ""))
    if (image is None) != (max_density is None):
        raise InvalidProblem("--image and --max-density go together")
    if image is not None:
        return _image_density(image, max_density), f"image {click.format_filename(image)}, up to {max_density:g}"
    if ramp is not None:
        return _ramp(ramp), f"ramp {ramp}"
    if density is not None:
        return density, f"density {density:g}"
    return None, ""


@recursive_wang.command(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
                        short_help="The points of a window at a level, a density, a ramp or an image.")
@set_and_region("level-0 tiles")
@click.option("--level", type=int, default=None, metavar="L", help="Every point of level L.")
@click.option("--density", type=float, default=None, metavar="D", help="D points a unit area (a tile), uniform.")
@click.option("--ramp", default=None, metavar="D0,D1", help="A density growing from D0 (west) to D1 (east).")
@click.option("--image", type=click.Path(dir_okay=False), default=None, metavar="IMG.png",
              help="A density from a picture stretched over the window: dark is dense.")
@click.option("--max-density", type=float, default=None, metavar="D", help="With --image: the density of black.")
@hash_option
@opt.seed_opt
@point_outputs("the points with their level and rank")
@click.pass_context
def window(ctx, tileset, region, level, density, ramp, image, max_density, hash_, seed, output, svg, png) -> None:
    """Sample a window: subdivide the direct corner tiling of the region down to the level the
    density needs, keep each level's new points at least its distance from the points above
    it, and keep the points whose rank fits the density. The window is verified before it is
    written: every level is a Poisson disk distribution at its own distance (a grid search).

    \b
    Examples:
      tilesolve sample recursive-wang build -C 2 -N 16 --rho 0.7 -n 4 --seed 1 -o rset.json
      tilesolve sample recursive-wang window rset.json --region 0,0,4x4 --level 2 --seed 2 -o pts.csv --png pts.png
      tilesolve sample recursive-wang window rset.json --region 0,0,8x4 --ramp 16,4096 --seed 2 --svg ramp.svg
      tilesolve sample recursive-wang window rset.json --region 1000000000000,-7,2x2 --density 900 -o far.json
      tilesolve verify far.json
    """
    from tilesolve.families.poisson_recursive import picture_distance, solve
    from tilesolve.io.poisson_json import check_point_output
    from tilesolve.io.poisson_recursive_json import write_points
    from tilesolve.model.poisson_recursive import RecursiveWindowProblem
    from tilesolve.model.window import parse_region

    outs = Outputs(output, svg, png)
    win = parse_region(region)
    grid, label = _density(level, density, ramp, image, max_density)
    if output:
        check_point_output(output, win)
    ts = _load_set(tileset)
    problem = RecursiveWindowProblem(ts, win, level, grid, label, hash_)
    sol = solve(problem, method="window", seed=seed)
    w = sol.tiling
    caption = f"{w.n_points:,} points, {problem.label}, {w.window.caption()}"
    write_window(ctx, outs, (output, svg, png), problem, sol, write_points, picture_distance(w), caption)
