"""``tilesolve sample``: tile-based sampling (class notes ch. 4).

::

    tilesolve sample poisson-tiles build -C 2 -N 64 --rho 0.75 [--lloyd K] [--seed S] -o set.json
    tilesolve sample poisson-tiles window set.json --region X0,Y0,WxH [--tiling direct|scanline]
                     [--seed S] [-o pts.json|pts.csv|pts.npy] [--svg pts.svg] [--png pts.png]
    tilesolve sample poisson-tiles spectrum set.json [--size W] [--seed S] [--svg s.svg] [--png s.png]
    tilesolve sample recursive-wang build|window ...   (tilesolve.cli.sample_recursive)
    tilesolve sample stipple [IMAGE.png] [--method penrose|polyomino|rejection] [--points N] -o out.svg
    tilesolve sample importance-spectrum [IMAGE.png] [--points N] [--svg s.svg] [--periodogram p.png]
"""

from __future__ import annotations

import click

from tilesolve.cli import options as opt
from tilesolve.cli.common import say
from tilesolve.cli.outputs import OutputFile, Outputs
from tilesolve.cli.sample_common import (
    done,
    hash_option,
    point_outputs,
    read_image,
    set_and_region,
    write_set,
    write_window,
)
from tilesolve.cli.sample_recursive import recursive_wang
from tilesolve.errors import InvalidProblem

__all__ = ["sample"]


@click.group(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
             short_help="Tile-based sampling: Poisson disk tiles, importance sampling, stippling (ch. 4, Parts IV-V).")
def sample() -> None:
    """Tile-based sampling: point distributions of any size from a small precomputed tile set,
    and samples whose density follows an image (Penrose and polyomino sampling, stippling)."""


sample.add_command(recursive_wang)


@sample.group("poisson-tiles", context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
              short_help="Corner-based Poisson disk tiles: build a set, sample windows, spectra (§4.3).")
def poisson_tiles() -> None:
    """Corner-based Poisson disk tiles (class notes §4.3).

    A set of C + 2C^2 + C^4 tiles (corner, edge and interior regions) is built once; any
    window of the plane, tiled by the direct or scanline stochastic corner tiling, is then a
    Poisson disk distribution: no two points closer than 2 rho r_max(N), across tile seams too.

    \b
    Examples:
      tilesolve sample poisson-tiles build -C 2 -N 64 --rho 0.75 --seed 1 -o set.json
      tilesolve sample poisson-tiles window set.json --region 0,0,8x8 --seed 2 -o pts.csv --svg pts.svg
      tilesolve sample poisson-tiles spectrum set.json --seed 2 --svg spectrum.svg
      tilesolve sample poisson-tiles texture set.json --region 0,0,6x4 --px 48 --seed 2 --png texture.png
      tilesolve verify set.json
    """


def _load_set(path: str):
    from tilesolve.io.jsonio import load_document
    from tilesolve.io.poisson_json import TILES_FORMAT, VERSIONS, tiles_from_dict

    problem, sol = tiles_from_dict(load_document(path, {TILES_FORMAT: VERSIONS}), path)
    return problem, sol.tiling


@poisson_tiles.command(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
                       short_help="Build a tile set: C colours, N points a tile, relative radius rho.")
@click.option("-C", "--colors", type=int, required=True, metavar="C", help="Corner colours (1..8): C^4 interior tiles.")
@click.option("-N", "--points", type=int, required=True, metavar="N", help="Points a tile.")
@click.option("--rho", type=float, default=0.75, show_default=True,
              help="Relative radius (eq. 4.3): no two points closer than 2 rho r_max(N); 0.05..0.85.")
@click.option("--lloyd", type=int, default=0, show_default=True, metavar="K",
              help="Lloyd relaxation steps after dart throwing, per tile (§4.2.4.3).")
@opt.seed_opt
@click.option("-o", "--output", type=OutputFile("json"), required=True, metavar="SET.json",
              help="Write the tile set here ('-' for stdout).")
@click.pass_context
def build(ctx, colors, points, rho, lloyd, seed, output) -> None:
    """Build a set of corner-based Poisson disk tiles and verify it.

    The set is checked before it is written: every point in its region, and every 2 x 2
    block of cells of every tiling (all colourings for C <= 2, 4,096 random ones above) a
    Poisson disk distribution. The same seed gives the same file, byte for byte.

    \b
    Examples:
      tilesolve sample poisson-tiles build -C 2 -N 64 --rho 0.75 --seed 1 -o set.json
      tilesolve sample poisson-tiles build -C 3 -N 32 --rho 0.7 --lloyd 4 --seed 2 -o set3.json
    """
    from tilesolve.families.poisson import solve
    from tilesolve.io.poisson_json import dump, tiles_to_dict
    from tilesolve.model.poisson import PoissonTilesProblem

    problem = PoissonTilesProblem(colors, points, rho, lloyd)
    outs = Outputs(output)
    sol = solve(problem, method="dart", seed=seed)
    write_set(ctx, outs, output, problem, sol, lambda: dump(tiles_to_dict(problem, sol)))


@poisson_tiles.command(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
                       short_help="The points of a window of the plane tiled with a set.")
@set_and_region("tiles")
@click.option("--tiling", type=click.Choice(["direct", "scanline"]), default="direct", show_default=True,
              help="The stochastic corner tiling that colours the lattice (§3.3.1 direct, §3.2.2 scanline).")
@click.option("--set", "variant", type=click.Choice(["complete", "compact"]), default="complete", show_default=True,
              help="Corner tile set of the tiling (compact: scanline only).")
@hash_option
@opt.seed_opt
@point_outputs("the points")
@click.pass_context
def window(ctx, tileset, region, tiling, variant, hash_, seed, output, svg, png) -> None:
    """Sample a window: place the set's tiles on a stochastic corner tiling and keep the points
    inside the region. The window is verified before it is written: a search on a grid of
    cells finds every pair of points closer than the distance.

    \b
    Examples:
      tilesolve sample poisson-tiles build -C 2 -N 64 --rho 0.75 --seed 1 -o set.json
      tilesolve sample poisson-tiles window set.json --region 0,0,8x8 --seed 2 -o pts.csv --svg pts.svg --png pts.png
      tilesolve sample poisson-tiles window set.json --region 1000000000,-5,4x4 --tiling scanline --seed 3 -o far.json
      tilesolve verify far.json
    """
    from tilesolve.families.poisson import solve
    from tilesolve.io.poisson_json import check_point_output, write_points
    from tilesolve.model.poisson import PoissonWindowProblem
    from tilesolve.model.window import parse_region

    outs = Outputs(output, svg, png)
    _, ts = _load_set(tileset)
    problem = PoissonWindowProblem(ts, parse_region(region), tiling, variant, hash_)
    if output:
        check_point_output(output, problem.window)
    sol = solve(problem, method="window", seed=seed)
    w = sol.tiling
    caption = ""
    if svg or png:  # the achieved rho is a search of the points: made for a picture only
        caption = f"{w.n_points:,} points, {_rho_caption(w, ts.problem.rho)}, {w.window.caption()}"
    write_window(ctx, outs, (output, svg, png), problem, sol, write_points, w.distance, caption)


def _rho_caption(w, asked: float) -> str:
    """``rho = 0.746 achieved (0.75 asked)``: the relative radius (eq. 4.1-4.3, class notes §4.2)
    the window's points keep, measured on them, beside the set's parameter. The measure is a
    search of the points; a window too large to draw (the picture writer refuses it) is not
    measured."""
    from tilesolve.families.poisson import achieved_rho
    from tilesolve.io.poisson_plots import MAX_PICTURE_POINTS

    if w.n_points < 2 or w.n_points > MAX_PICTURE_POINTS:
        return f"rho {asked:g} asked"
    achieved = achieved_rho(w)
    return f"rho = {achieved:.3f} achieved ({asked:g} asked)"


@poisson_tiles.command(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
                       short_help="Relative radius, radial power spectrum and anisotropy against dart throwing.")
@click.argument("tileset", type=click.Path(dir_okay=False), metavar="SET.json")
@click.option("--size", type=click.IntRange(1, 64), default=8, show_default=True, metavar="W",
              help="The W x W window of tiles measured, at the origin.")
@click.option("--runs", type=click.IntRange(1, 64), default=4, show_default=True,
              help="Windows (and dart-throwing runs) whose periodograms are averaged.")
@opt.seed_opt
@click.option("--svg", type=OutputFile("svg", allow_dash=False), metavar="S.svg", help="Plot the spectra as SVG.")
@click.option("--png", type=OutputFile("png", allow_dash=False), metavar="S.png", help="Plot the spectra as PNG.")
@click.pass_context
def spectrum(ctx, tileset, size, runs, seed, svg, png) -> None:
    """Measure a set on windows: the achieved relative radius, and the radially averaged power
    spectrum and anisotropy (Ulichney 1987; §4.2.2) of its points, the periodograms of --runs
    windows averaged, against as many runs of plain dart throwing (Cook 1986) at the same
    distance on a torus of the same size. Prints a table.

    \b
    Examples:
      tilesolve sample poisson-tiles build -C 2 -N 64 --rho 0.75 --seed 1 -o set.json
      tilesolve sample poisson-tiles spectrum set.json --size 8 --seed 2 --svg spectrum.svg --png spectrum.png
    """
    from tilesolve.families.poisson import spectra
    from tilesolve.io.poisson_plots import write_spectrum_plot

    outs = Outputs(svg, png)
    problem, ts = _load_set(tileset)
    rows = spectra(ts, size, seed=seed, runs=runs)
    click.echo(f"{'distribution':<16} {'points':>8} {'rho':>6} {'mean anisotropy dB':>19}")
    for r in rows:
        click.echo(f"{r['name']:<16} {r['points']:>8,} {r['rho']:>6.3f} {r['anisotropy_db']:>19.2f}")
    series = [(r["name"], r["frequency"], r["power"], r["anisotropy"]) for r in rows]
    title = f"{problem.describe()}: {size}x{size} tiles, {runs} runs averaged"
    with outs.commit():
        for path, fmt in ((svg, "svg"), (png, "png")):
            if path:
                write_spectrum_plot(path, series, title, fmt)
    done(ctx, outs)


@poisson_tiles.command(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
                       short_help="Objects scattered without overlaps: the procedural object distribution (§6.6.2).")
@set_and_region("tiles")
@click.option("--px", type=click.IntRange(1, 512), default=32, show_default=True, help="Pixels a tile side.")
@click.option("--image", type=click.Path(dir_okay=False, exists=False), metavar="IMG.png",
              help="The object drawn in every Poisson disk (transparent pixels show the background); "
                   "default: shaded disks coloured by the point's id.")
@click.option("--background", type=click.Path(dir_okay=False, exists=False), metavar="BG.png",
              help="The picture the objects are scattered over, repeated from the top-left corner (a wall from "
                   "`tilesolve render wall`, a texture from `tilesolve render texture`); default: a shade by the "
                   "distance to the closest point.")
@opt.seed_opt
@click.option("--gpu", is_flag=True,
              help="Evaluate the function in a fragment shader (OpenGL 4.5 through EGL: the gpu extra; Mesa's "
                   "llvmpipe without a GPU): every pixel's point and id the CPU's, and on llvmpipe the same PNG, "
                   "byte for byte.")
@click.option("--png", type=OutputFile("png", allow_dash=False), required=True, metavar="T.png",
              help="Write the texture here.")
@click.pass_context
def texture(ctx, tileset, region, px, image, background, seed, gpu, png) -> None:
    """Scatter objects over a texture with the procedural object distribution function (class
    notes §6.6.2): each pixel is evaluated on its own (random access through the direct corner
    tiling), finds its closest point of the tiled Poisson disk distribution, and draws the
    object of that point's disk in the disk's own coordinates, or the background. Disks never
    overlap, so neither do the objects. --gpu evaluates the pixels in a fragment shader, each
    one equal to the CPU's.

    \b
    Examples:
      tilesolve sample poisson-tiles build -C 2 -N 16 --rho 0.75 --seed 1 -o set.json
      tilesolve sample poisson-tiles texture set.json --region 0,0,6x4 --px 48 --seed 2 --png texture.png
      tilesolve sample poisson-tiles texture set.json --region 0,0,3x2 --px 64 --image texture.png --png again.png
      tilesolve sample poisson-tiles texture set.json --region 1099511627776,-5,6x4 --px 48 --seed 2 --gpu --png far.png
      tilesolve render wall --size 288x192 --seed 4 -o wall.png
      tilesolve sample poisson-tiles texture set.json --region 0,0,6x4 --px 48 --seed 2 --image again.png --background wall.png --png on-wall.png
    """
    if gpu:
        from tilesolve.gpu.objects import objects
    else:
        from tilesolve.families.poisson import objects
    from tilesolve.io.poisson_plots import MAX_TEXTURE_PIXELS, write_texture_png
    from tilesolve.model.window import parse_region

    outs = Outputs(png)
    window = parse_region(region)
    if window.width * window.height * px * px > MAX_TEXTURE_PIXELS:
        raise InvalidProblem(f"a texture of {window.width * px:,} x {window.height * px:,} pixels is more than "
                             f"{MAX_TEXTURE_PIXELS:,}: ask for fewer tiles or pixels")
    picture = read_image(image) if image else None
    under = read_image(background) if background else None
    _, ts = _load_set(tileset)
    evaluation = objects(ts, window, px, seed=seed)
    with outs.commit():
        write_texture_png(png, evaluation, picture, under)
    say(f"ok: {int(evaluation['inside'].sum()):,} of {evaluation['inside'].size:,} pixels inside a Poisson disk, "
        f"{window.caption()}")
    done(ctx, outs)


@sample.group("poisson-spheres", context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
              short_help="Corner-based Poisson sphere tiles: build a 3-D set, sample boxes of space (§4.4).")
def poisson_spheres() -> None:
    """Corner-based Poisson sphere tiles (class notes §4.4).

    A set of C + 3C^2 + 3C^4 + C^8 tiles on corner cubes (corner, edge, face and interior
    regions) is built once; any box of space, tiled by the direct 3-D corner tiling with the
    long-period hash, is then a Poisson sphere distribution: no two points closer than
    2 rho r_max(N), across tile seams too.

    \b
    Examples:
      tilesolve sample poisson-spheres build -C 2 -N 100 --rho 0.6 --seed 1 -o spheres.json
      tilesolve sample poisson-spheres window spheres.json --region 0,0,0,4x4x4 --seed 2 -o pts.npy
      tilesolve verify spheres.json
    """


@poisson_spheres.command("build", context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
                         short_help="Build a 3-D tile set: C colours, N points a cell, relative radius rho.")
@click.option("-C", "--colors", type=int, required=True, metavar="C", help="Corner colours (1..4): C^8 interior tiles.")
@click.option("-N", "--points", type=int, required=True, metavar="N", help="Points a unit cell.")
@click.option("--rho", type=float, default=0.65, show_default=True,
              help="Relative radius (eq. 4.6): no two points closer than 2 rho r_max(N); 0.05..0.85.")
@opt.seed_opt
@click.option("-o", "--output", type=OutputFile("json"), required=True, metavar="SET.json",
              help="Write the tile set here ('-' for stdout).")
@click.pass_context
def spheres_build(ctx, colors, points, rho, seed, output) -> None:
    """Build a set of corner-based Poisson sphere tiles and verify it.

    The set is checked before it is written: every point in its region, and every pair of
    nearby tiles under every colouring of the lattice points they touch (C <= 2; 4,096
    random colourings a pair above). The same seed gives the same file, byte for byte.

    \b
    Examples:
      tilesolve sample poisson-spheres build -C 2 -N 100 --rho 0.6 --seed 1 -o spheres.json
      tilesolve sample poisson-spheres build -C 1 -N 100 --rho 0.6 -o one.json
    """
    from tilesolve.families.poisson_sphere import solve
    from tilesolve.io.poisson_sphere_json import dump, tiles_to_dict
    from tilesolve.model.poisson_sphere import PoissonSphereTilesProblem

    problem = PoissonSphereTilesProblem(colors, points, rho)
    outs = Outputs(output)
    sol = solve(problem, method="dart", seed=seed)
    write_set(ctx, outs, output, problem, sol, lambda: dump(tiles_to_dict(problem, sol)))


@poisson_spheres.command("window", context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
                         short_help="The points of a box of space tiled with a 3-D set.")
@click.argument("tileset", type=click.Path(dir_okay=False), metavar="SET.json")
@click.option("--region", required=True, metavar="X0,Y0,Z0,WxHxD",
              help="W x H x D cells whose least cell is (X0, Y0, Z0); coordinates may be negative.")
@hash_option
@opt.seed_opt
@click.option("-o", "--output", type=OutputFile("json", "csv", "npy", allow_dash=False), metavar="PTS.npy|csv|json",
              help="Write the points: JSON (relative to the box's least corner, any box), CSV or NPY (coordinates "
                   "of space).")
@click.pass_context
def spheres_window(ctx, tileset, region, hash_, seed, output) -> None:
    """Sample a box: colour its lattice points with the direct 3-D corner tiling, place the
    set's tiles and keep the points inside. The box is verified before it is written: a
    search on a grid of cells finds every pair of points closer than the distance.

    \b
    Examples:
      tilesolve sample poisson-spheres build -C 2 -N 100 --rho 0.6 --seed 1 -o spheres.json
      tilesolve sample poisson-spheres window spheres.json --region 0,0,0,8x8x8 --seed 2 -o pts.npy
      tilesolve sample poisson-spheres window spheres.json --region 1000000000000,-5,7,2x2x2 -o far.json
      tilesolve verify far.json
    """
    from tilesolve.families.poisson_sphere import solve
    from tilesolve.io.jsonio import load_document
    from tilesolve.io.poisson_sphere_json import (
        TILES_FORMAT,
        VERSIONS,
        check_point_output3,
        tiles_from_dict,
        write_points3,
    )
    from tilesolve.model.poisson_sphere import PoissonSphereWindowProblem, parse_box

    box = parse_box(region)
    outs = Outputs(output)
    if output:
        check_point_output3(output, box)
    _, set_sol = tiles_from_dict(load_document(tileset, {TILES_FORMAT: VERSIONS}), tileset)
    problem = PoissonSphereWindowProblem(set_sol.tiling, box, hash_)
    sol = solve(problem, method="window", seed=seed)
    with outs.commit(sol):
        if output:
            write_points3(output, problem, sol)
    say(f"{sol.status.value}: {sol.tiling.n_points:,} points, {problem.describe()}, seed {sol.seed}, "
        f"in {sol.time_s:.2f} s")
    done(ctx, outs)


def _density_options(lloyd: int, jitter: bool):
    """The IMAGE argument and the options shared by the importance-sampling commands (with the
    command's defaults of --lloyd and --jitter)."""
    return lambda command: _with_density_options(command, lloyd, jitter)


def _with_density_options(command, lloyd: int, jitter: bool):
    for option in reversed((
        click.argument("image", required=False, type=click.Path(dir_okay=False), metavar="[IMAGE.png]"),
        click.option("--test-image", type=click.Choice(["radial", "gradient", "flat"]), default=None,
                     help="A built-in 256 x 256 test image instead of IMAGE (radial when neither is given)."),
        click.option("-n", "--points", type=int, default=20_000, show_default=True, metavar="N",
                     help="About how many samples (1..2,000,000)."),
        click.option("--tile", type=click.Choice(["x-pentomino", "chair", "l-tetromino", "p-pentomino"]),
                     default="x-pentomino", show_default=True,
                     help="The polyomino method's self-similar tile: the X pentomino of base 2 + i (rep-5, each "
                          "level turned by atan(1/2)) or a rep-4 polyomino."),
        click.option("--lloyd", type=click.IntRange(0, 50), default=lloyd, show_default=True, metavar="K",
                     help="Density-weighted Lloyd steps after sampling."),
        click.option("--jitter/--no-jitter", default=jitter, show_default=True,
                     help="Each sample at a random point of its tile, not its centroid (penrose, polyomino)."),
    )):
        command = option(command)
    return command


@sample.command(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
                short_help="Stipple an image: samples whose density follows its darkness (Parts IV-V).")
@_density_options(lloyd=4, jitter=True)
@click.option("--method", type=click.Choice(["penrose", "polyomino", "rejection"]), default="penrose",
              show_default=True, help="The sampler.")
@click.option("--correction/--no-correction", default=True, show_default=True,
              help="The polyomino sampler without --jitter (X pentomino, chair): displace each sample by its "
                   "learnt correction table (Ostromoukhov 2007); --no-correction keeps the tiles' raw centroids, "
                   "whose lattice shows in the spectrum.")
@opt.seed_opt
@click.option("-o", "--output", type=OutputFile("svg", "json", allow_dash=False), required=True,
              metavar="OUT.svg|OUT.json", help="Write the stippled picture (.svg) or the stipple file (.json: the "
              "settings, the density, the seed and the samples, which `tilesolve verify` re-checks) here.")
@click.option("--svg", type=OutputFile("svg", allow_dash=False), metavar="OUT.svg", help="Also the picture as SVG.")
@click.option("--png", type=OutputFile("png", allow_dash=False), metavar="OUT.png", help="Also the picture as PNG.")
@click.option("--csv", "csv_", type=OutputFile("csv", allow_dash=False), metavar="PTS.csv",
              help="Also the samples: x, y (y up, the image's longer side 1).")
@click.pass_context
def stipple(ctx, image, test_image, points, tile, lloyd, jitter, method, correction, seed, output, svg, png,
            csv_) -> None:
    """Stipple an image (class notes Part V): about N samples whose density follows the image's
    darkness (1 - grey / 255), drawn as dots sized by it. The samplers are hierarchical: a
    Penrose tiling's Robinson triangles (Ostromoukhov, Donohue, Jodoin 2004) or a self-similar
    polyomino (Ostromoukhov 2007) subdivided where the image needs more than one sample a tile,
    each tile's sample kept by a threshold on its structural index; or plain rejection sampling.
    The polyomino sampler without --jitter (X pentomino, chair) takes its learnt correction table
    (Ostromoukhov 2007's offsets by structural index, rebuilt by this project; --no-correction
    leaves it out, the raw structure); --jitter and --lloyd are the other stand-ins (the
    defaults, Penrose with both, draw the picture without the tilings' patterns; `sample
    importance-spectrum` measures them). The samples are
    checked before anything is written: inside the image, and the counts of 2 x 2 and 4 x 4
    blocks near their share of the image's darkness (exit 1 if not). Without IMAGE, a built-in
    radial ramp. The same seed gives the same files, byte for byte. A stipple file (-o OUT.json,
    tilesolve/stipple) holds the settings, the density sampled, the seed and the samples:
    `tilesolve verify` re-checks the counts against that density and samples it again with the
    seed, and the samples must be the same (a point deleted, added or moved is found).

    \b
    Examples:
      tilesolve sample stipple --points 3000 --seed 1 -o radial.svg
      tilesolve sample stipple --test-image gradient --points 3000 --seed 1 -o g.svg --png g.png
      tilesolve sample stipple --method polyomino --no-jitter --lloyd 0 --points 3000 --seed 1 -o x.svg
      tilesolve sample stipple --method polyomino --no-correction --no-jitter --lloyd 0 -n 3000 -o raw.svg --csv raw.csv
      tilesolve sample stipple --test-image gradient --points 2000 --seed 1 -o g.json --svg g.svg
      tilesolve verify g.json
    """
    from tilesolve.families.importance import density_of
    from tilesolve.families.importance import stipple as run_stipple
    from tilesolve.family import draw_seed
    from tilesolve.io.atomic import write_text_atomic
    from tilesolve.io.stipple import MAX_STIPPLE_POINTS, Samples, dump, stipple_to_dict, write_stipple
    from tilesolve.model.importance import ImportanceProblem
    from tilesolve.model.solution import Solution, Status

    outs = Outputs(output, svg, png, csv_)
    if points > MAX_STIPPLE_POINTS:
        raise InvalidProblem(f"a stippled picture draws at most {MAX_STIPPLE_POINTS:,} points, not {points:,}")
    problem = ImportanceProblem(density_of(image, test_image), points, method, tile, lloyd, jitter, correction)
    seed = draw_seed() if seed is None else seed  # a stipple file records the seed it was sampled with
    r = run_stipple(problem, seed=seed)
    pts = r["points"]
    status = "violations" if r["violations"] else "ok"
    for v in r["violations"]:
        say(f"  {v.kind}: {v.message}")
    caption = f"{len(pts):,} points, {problem.describe().split(', ', 1)[1]}"
    with outs.commit():
        if output.lower().endswith(".json"):
            write_text_atomic(output, dump(stipple_to_dict(problem, Solution(Status.SAT, Samples(pts), seed=seed))))
        else:
            write_stipple(output, pts, problem.density, caption, "svg")
        if svg:
            write_stipple(svg, pts, problem.density, caption, "svg")
        if png:
            write_stipple(png, pts, problem.density, caption, "png")
        if csv_:
            import numpy as np

            rows = "".join(f"{x!r},{y!r}\n" for x, y in np.asarray(pts, dtype=float).tolist())
            write_text_atomic(csv_, "x,y\n" + rows)
    say(f"{status}: {len(pts):,} points ({problem.describe()}), discrepancy {r['discrepancy']:.4f}, "
        f"sampled in {r['time_s']:.2f} s")
    if r["violations"]:
        ctx.exit(1)
    done(ctx, outs)


@sample.command("importance-spectrum", context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
                short_help="Penrose and polyomino sampling against rejection: speed, discrepancy, spectra.")
@_density_options(lloyd=0, jitter=False)
@click.option("--runs", type=click.IntRange(1, 32), default=4, show_default=True,
              help="Seeds whose flat-image periodograms are averaged.")
@click.option("--spectrum-points", type=click.IntRange(64, 16384), default=4096, show_default=True, metavar="M",
              help="Samples of the flat image whose spectra are measured.")
@opt.seed_opt
@click.option("--svg", type=OutputFile("svg", allow_dash=False), metavar="S.svg",
              help="Plot the radial power and anisotropy as SVG.")
@click.option("--png", type=OutputFile("png", allow_dash=False), metavar="S.png",
              help="Plot the radial power and anisotropy as PNG.")
@click.option("--periodogram", type=OutputFile("png", allow_dash=False), metavar="P.png",
              help="Draw the 2-D periodograms side by side (PNG, log scale).")
@click.pass_context
def importance_spectrum(ctx, image, test_image, points, tile, lloyd, jitter, runs, spectrum_points, seed, svg, png,
                        periodogram) -> None:
    """Compare the Penrose and polyomino samplers with plain rejection sampling in one run: on the
    image, the samples a second and the density-weighted star discrepancy (anchored boxes on
    pixel edges: max |share of points - share of darkness|); on a flat image (the uniform case,
    as the papers show it), the radially averaged power spectrum and anisotropy (Ulichney 1987)
    of --runs seeds, and the peak factor: the largest power of the averaged 2-D periodogram
    over its annulus' mean (about 10 for white noise; spikes of a tiling's structure give
    hundreds). The polyomino sampler is shown with its learnt correction table and without it
    (X pentomino, chair, unjittered). Prints a table.

    \b
    Examples:
      tilesolve sample importance-spectrum --spectrum-points 1024 --runs 2 --seed 1 --svg s.svg --periodogram p.png
      tilesolve sample importance-spectrum --test-image gradient --spectrum-points 1024 --jitter --lloyd 3 --seed 1
    """
    from tilesolve.families.importance import compare, density_of
    from tilesolve.io.poisson_plots import write_spectrum_plot
    from tilesolve.io.stipple import write_periodograms_png
    from tilesolve.model.importance import ImportanceProblem

    outs = Outputs(svg, png, periodogram)
    problem = ImportanceProblem(density_of(image, test_image), points, "polyomino", tile, lloyd, jitter)
    rows = compare(problem, seed=seed, runs=runs, spectrum_points=spectrum_points)
    click.echo(f"{'method':<24} {'points':>9} {'points/s':>12} {'discrepancy':>12} {'peak factor':>12} "
               f"{'anisotropy dB':>14}")
    for r in rows:
        click.echo(f"{r['name']:<24} {r['points']:>9,} {r['rate']:>12,.0f} {r['discrepancy']:>12.4f} "
                   f"{r['peak']:>12.1f} {r['anisotropy_db']:>14.2f}")
    settings = (", jittered" if jitter else "") + (f", {lloyd} Lloyd steps" if lloyd else "")
    title = f"flat image, {spectrum_points:,} points{settings}, {runs} runs averaged"
    with outs.commit():
        series = [(r["name"], r["frequency"], r["power"], r["anisotropy"]) for r in rows]
        for path, fmt in ((svg, "svg"), (png, "png")):
            if path:
                write_spectrum_plot(path, series, title, fmt, xlabel="frequency (cycles per image side)")
        if periodogram:
            write_periodograms_png(periodogram, [(r["name"], r["periodogram"]) for r in rows], title)
    bad = [r["name"] for r in rows if r["violations"]]
    if bad:
        say(f"violations: the samples of {', '.join(bad)} do not follow the image's density")
        ctx.exit(1)
    done(ctx, outs)
