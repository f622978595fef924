"""``tilesolve render`` and ``tilesolve gpu``: the GPU path (moderngl through EGL, headless).

::

    tilesolve render texture --example IMG --colors C --size WxH -o out.png [--benchmark N]
    tilesolve render texture --example IMG --aperiodic NAME --size WxH -o out.png [--cpu]
    tilesolve render wall --size WxH [--max-line N] [--samples S] -o out.png [--benchmark N]
    tilesolve gpu info
"""

from __future__ import annotations

import time

import click

from tilesolve.cli import options as opt
from tilesolve.cli.common import progress_wanted, say
from tilesolve.cli.outputs import OutputFile, Outputs
from tilesolve.errors import InvalidProblem

__all__ = ["render", "gpu"]

_ORIGIN = click.option("--origin", default="0,0", show_default=True, metavar="X0,Y0",
                       help="The lattice cell at the picture's SW corner (y points north; may be negative, "
                            "|X0|, |Y0| < 2^62).")
_SEED = click.option("--seed", type=click.IntRange(0, opt.MAX_SEED), default=0, show_default=True, metavar="N",
                     help="Seed of the hashes; the same seed gives the same picture.")
_BENCH = click.option("--benchmark", type=click.IntRange(1, 100_000), default=None, metavar="FRAMES",
                      help="Also render FRAMES frames of the picture (its lower-left 4096x4096 px at most, one pass) "
                           "and print the frames per second.")
_PER_FRAGMENT = click.option("--per-fragment", is_flag=True,
                             help="Evaluate the tiling hash in every fragment (one pass) instead of once per "
                                  "tile in a first pass; the same picture.")
_OUTPUT = click.option("-o", "--output", type=OutputFile("png", allow_dash=False), metavar="OUT.png",
                       help="Write the picture here (PNG; rendered in passes when larger than the viewport).")


#: Largest side of a benchmark frame (a 4096 x 4096 RGBA frame is 64 MiB, 256 MiB with 4 samples).
BENCH_SIDE = 4096


def _benchmark(renderer, width: int, height: int, frames: int) -> None:
    """Render ``frames`` frames of one pass and print the rate (the GPU finishes before the clock stops)."""
    side = min(renderer.max_pass, BENCH_SIDE)
    w, h = min(width, side), min(height, side)
    fbo, draw = renderer.frame(w, h)
    draw()
    renderer.ctx.finish()
    t = time.perf_counter()
    for _ in range(frames):
        draw()
    fbo.read(components=4)  # waits for every frame
    dt = time.perf_counter() - t
    click.echo(f"{frames} frames of {w}x{h} in {dt:.3f} s: {frames / dt:.1f} fps "
               f"({renderer.ctx.info['GL_RENDERER']})")


def _need_output(output, benchmark) -> None:
    if not output and benchmark is None:
        raise InvalidProblem("nothing to do: give -o OUT.png and/or --benchmark FRAMES")


@click.group(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
             short_help="GPU pictures: tile-based texture mapping and the procedural wall shader.")
def render() -> None:
    """Render pictures on the GPU (moderngl, OpenGL 4.5 through EGL; Mesa's llvmpipe without a GPU).

    \b
    Examples:
      tilesolve render wall --size 640x360 --max-line 4 --seed 3 -o wall.png
      tilesolve render texture --example wall.png --colors 3 --tile 32 --size 800x600 -o texture.png
      tilesolve render texture --example wall.png --aperiodic jeandel-rao --seed 1 --tile 32 --size 800x600 -o t.png
    """


@render.command("texture", context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
                short_help="Tile-based texture mapping: corner tiles (class notes §5.3-5.4) or aperiodic Wang sets.")
@click.option("--example", required=True, type=click.Path(dir_okay=True), metavar="IMG",
              help="The example texture (any image Pillow reads), at least one tile in each direction.")
@click.option("--colors", type=click.IntRange(2, 8), default=3, show_default=True, metavar="C",
              help="Corner colours: the atlas packs the C^4 corner tiles in a C^2 x C^2 tile packing.")
@click.option("--aperiodic", default=None, metavar="NAME",
              help="Instead of corner tiles, the Wang tiles of this aperiodic set, placed by its constructive route: "
                   "jeandel-rao or labbe-u19 (Markov partitions, coded in the shader), kari-14 or kari-culik-13 "
                   "(balanced rows): a texture that never repeats.")
@click.option("--cpu", is_flag=True,
              help="With --aperiodic: draw on the CPU (no OpenGL needed); the same pixels as the GPU.")
@click.option("--size", required=True, metavar="WxH", help="Picture size in pixels (any size: rendered in passes).")
@click.option("--tile", type=click.IntRange(8, 1024), default=64, show_default=True, metavar="PX",
              help="Side of an atlas tile in texels (even; the atlas, C^2 tiles a side or the square root of the "
                   "aperiodic set's tiles, at most 16384 px).")
@click.option("--scale", type=click.IntRange(1, 4096), default=None, metavar="PX",
              help="Pixels per tile side in the picture (default: --tile); smaller values use the atlas's mipmaps "
                   "(--aperiodic: the nearest texel).")
@_ORIGIN
@_SEED
@click.option("--hash", "hash_", type=click.Choice(["long", "table"]), default="long", show_default=True,
              help="Lattice hash of the direct stochastic tiling (§3.4): long period or one permutation table.")
@_PER_FRAGMENT
@click.option("--atlas", type=OutputFile("png", allow_dash=False), metavar="ATLAS.png",
              help="Also write the packed atlas.")
@_OUTPUT
@_BENCH
@click.pass_context
def texture(ctx, example, colors, aperiodic, cpu, size, tile, scale, origin, seed, hash_, per_fragment, atlas, output,
            benchmark) -> None:
    """An arbitrarily large non-periodic texture from an example image (Wei 2004; Lagae §5.4).

    The example is synthesised over the complete corner tile set by the corner-patch
    construction of §5.3; the tiles are packed into one atlas as a corner tile packing
    (§5.5.3), so filtering across tile borders is seamless; a fragment shader picks each
    pixel's tile by the direct stochastic corner tiling (§3.3.1), the same tiles as
    `tilesolve tiling --kind corner --method direct` with the same seed.

    With --aperiodic NAME the tiles are instead the Wang tiles of an aperiodic set, each
    edge colour a diamond of the example (Cohen et al. 2003), and the tile at each cell is
    the one of `tilesolve aperiodic tiling --builtin NAME` with the same seed and origin:
    the texture never repeats. Pixels sample the nearest texel (an aperiodic set has no
    tile packing to filter across); --cpu draws the same pixels without OpenGL.

    \b
    Examples:
      tilesolve render wall --size 256x256 --seed 5 -o bricks.png
      tilesolve render texture --example bricks.png --colors 3 --tile 32 --size 800x600 -o texture.png
      tilesolve render texture --example bricks.png --colors 2 --tile 32 --scale 16 --size 640x480 --origin -1000,20 -o small.png --atlas atlas.png
      tilesolve render texture --example bricks.png --colors 3 --tile 32 --size 1920x1080 --benchmark 5
      tilesolve render texture --example bricks.png --aperiodic jeandel-rao --seed 1 --tile 32 --size 800x600 -o jr.png
      tilesolve render texture --example bricks.png --aperiodic kari-culik-13 --tile 32 --scale 16 --size 640x480 --origin 5,-20 --cpu -o kc.png --atlas kc-atlas.png
    """
    from tilesolve.gpu.texture import Atlas, TextureMapper, check_atlas, read_example

    if aperiodic is not None or cpu:
        _aperiodic_texture(ctx, example, aperiodic, cpu, size, tile, scale, origin, seed, atlas, output, benchmark)
        return
    outs, w, h, x0, y0 = _texture_setup(output, atlas, benchmark, size, origin)
    check_atlas(colors, tile)
    image = read_example(example)
    t = time.perf_counter()
    at = Atlas.from_example(image, colors, tile=tile, seed=seed)
    mapper = TextureMapper(at, seed=seed, origin=(x0, y0), tile_px=scale, hash=hash_, two_pass=not per_fragment)
    _texture_finish(outs, output, atlas, mapper, at.image, w, h, benchmark, t,
                    f"texture {w}x{h} from {example}: {colors}^4 = {colors**4} corner tiles of {tile} px, seed {seed}")


def _texture_setup(output, atlas, benchmark, size, origin):
    """``(outputs, width, height, x0, y0)`` of a texture, checked before any work."""
    from tilesolve.gpu.picture import parse_origin, parse_size

    _need_output(output, benchmark)
    outs = Outputs(output, atlas)
    w, h = parse_size(size)
    return (outs, w, h, *parse_origin(origin))


def _texture_finish(outs, output, atlas, picture, atlas_image, w: int, h: int, benchmark, t: float, summary: str,
                    notes=list) -> None:
    """Write the picture (``output``, streamed) and the atlas image (``atlas``) together, say what
    was drawn and on what (then the lines ``notes()``), and run the benchmark."""
    from tilesolve.gpu.picture import write_png

    with outs.commit():
        if output:
            write_png(output, w, h, picture.bands(w, h), progress_wanted())
        if atlas:
            write_png(atlas, atlas_image.shape[1], atlas_image.shape[0], [atlas_image])
    renderer = picture.ctx.info["GL_RENDERER"] if hasattr(picture, "ctx") else "CPU"
    say(f"{summary}, in {time.perf_counter() - t:.2f} s ({renderer})")
    for note in notes():
        say(f"  {note}")
    if outs.files:
        say(f"  wrote {', '.join(outs.files)}")
    if benchmark:
        _benchmark(picture, w, h, benchmark)


def _aperiodic_texture(ctx, example, name, cpu, size, tile, scale, origin, seed, atlas, output, benchmark) -> None:
    """``render texture --aperiodic NAME``: Wang tiles of an aperiodic set placed by its constructive route."""
    from click.core import ParameterSource

    from tilesolve.gpu.texture import read_example
    from tilesolve.gpu.wang_texture import WangAtlas, check_aperiodic

    if name is None:
        raise InvalidProblem("--cpu draws aperiodic textures (--aperiodic NAME); corner textures are drawn on the GPU")
    given = [opt_ for p, opt_ in (("colors", "--colors"), ("hash_", "--hash"), ("per_fragment", "--per-fragment"))
             if ctx.get_parameter_source(p) is not ParameterSource.DEFAULT]
    if given:
        raise InvalidProblem(f"{', '.join(given)}: options of corner-tile textures, not of --aperiodic ones")
    if cpu and benchmark is not None:
        raise InvalidProblem("--benchmark times the GPU: leave out --cpu")
    outs, w, h, x0, y0 = _texture_setup(output, atlas, benchmark, size, origin)
    tileset, route = check_aperiodic(name, tile)
    image = read_example(example)
    t = time.perf_counter()
    at = WangAtlas.from_example(image, tileset.tiles, tile=tile, seed=seed)
    if cpu:
        from tilesolve.gpu.wang_texture import WangTexture as Picture
    else:
        from tilesolve.gpu.wang_texture import WangTextureMapper as Picture
    picture = Picture(name, at, seed=seed, origin=(x0, y0), tile_px=scale)
    summary = (f"texture {w}x{h} from {example}: the {len(tileset)} Wang tiles of {name} ({route} route) "
               f"of {tile} px, seed {seed}")

    def notes() -> list[str]:
        if not getattr(picture, "codes_in_shader", False) or not picture.decided + picture.undecided:
            return []  # the CPU route's windows, or no picture drawn (--benchmark alone)
        return [f"cells coded by the shader: {picture.decided:,}; left to the CPU route (near a polygon edge): "
                f"{picture.undecided:,}"]

    _texture_finish(outs, output, atlas, picture, at.image, w, h, benchmark, t, summary, notes)


@render.command("wall", context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
                short_help="The procedural brick wall shader (004 §4-5).")
@click.option("--size", required=True, metavar="WxH", help="Picture size in pixels (any size: rendered in passes).")
@click.option("--max-line", type=click.IntRange(1, 1 << 20), default=None, metavar="N",
              help="No line longer than N bricks (procedural dappling, 004 §4.3); default: no limit (§4.2).")
@click.option("--colors", type=click.IntRange(3, 127), default=3, show_default=True, metavar="NC",
              help="Edge colours (brick edge positions per cell side).")
@click.option("--cell", type=click.IntRange(1, 4096), default=32, show_default=True, metavar="PX",
              help="Pixels per cell side.")
@click.option("--samples", type=int, default=1, show_default=True, metavar="S",
              help="Samples per pixel (004 Table 1: 1, 2, 8, 16, 32); as many as the context allows "
                   "(`tilesolve gpu info`; llvmpipe: 1, 2, 4).")
@_ORIGIN
@_SEED
@_PER_FRAGMENT
@_OUTPUT
@_BENCH
def wall(size, max_line, colors, cell, samples, origin, seed, per_fragment, output, benchmark) -> None:
    """The procedural wall of 004 drawn by a shader: bricks, mortar and a colour per brick.

    Each cell's edges are those of `tilesolve wall` (the procedural route) for the same
    seed, computed by the same integer hashes on the GPU (004 §4.2-4.3, App. B); each pixel
    finds its brick, the distance to the brick's edge and its UV (004 §3.3, Fig. 10).

    \b
    Examples:
      tilesolve render wall --size 1280x720 --max-line 4 --seed 1 -o wall.png
      tilesolve render wall --size 640x480 --cell 24 --samples 4 --origin -100000,5 -o aa.png
      tilesolve render wall --size 1920x1080 --max-line 4 --benchmark 5
    """
    from tilesolve.gpu.picture import parse_origin, parse_size, write_png
    from tilesolve.gpu.wall import WallRenderer

    _need_output(output, benchmark)
    outs = Outputs(output)
    w, h = parse_size(size)
    x0, y0 = parse_origin(origin)
    t = time.perf_counter()
    renderer = WallRenderer(colors=colors, max_line=max_line, seed=seed, origin=(x0, y0), cell_px=cell,
                            samples=samples, per_fragment=per_fragment)
    with outs.commit():
        if output:
            write_png(output, w, h, renderer.bands(w, h), progress_wanted())
    limit = f"lines of at most {max_line} bricks" if max_line else "no line limit"
    say(f"wall {w}x{h}, {limit}, {samples} sample(s), seed {seed}, in {time.perf_counter() - t:.2f} s "
        f"({renderer.ctx.info['GL_RENDERER']})")
    if outs.files:
        say(f"  wrote {', '.join(outs.files)}")
    if benchmark:
        _benchmark(renderer, w, h, benchmark)


@click.group(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
             short_help="The OpenGL context of the GPU path.")
def gpu() -> None:
    """The headless OpenGL context that `tilesolve render` uses (moderngl, EGL).

    \b
    Examples:
      tilesolve gpu info
    """


@gpu.command("info", context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
             short_help="Renderer, OpenGL version and limits.")
def info() -> None:
    """Print the renderer, the OpenGL version and the limits the renderers use.

    \b
    Examples:
      tilesolve gpu info
    """
    from tilesolve.gpu.context import gpu_info
    from tilesolve.gpu.wall import allowed_samples

    i = gpu_info()
    click.echo(f"renderer:         {i['renderer']}")
    click.echo(f"vendor:           {i['vendor']}")
    click.echo(f"OpenGL:           {i['version']}")
    click.echo(f"max texture size: {i['max_texture_size']}")
    click.echo(f"max viewport:     {i['max_viewport'][0]}x{i['max_viewport'][1]}")
    click.echo(f"samples:          {', '.join(map(str, allowed_samples()))} (of 1, 2, 4, 8, 16, 32)")
    click.echo(f"64-bit integers:  {'yes' if i['extensions_int64'] else 'no'}")
