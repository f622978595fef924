"""``tilesolve isohedral draw`` and ``tilesolve isohedral list``: isohedral tilings for design
(class notes Part II §7).

::

    tilesolve isohedral draw --type IH41 [--params P,P,...] [--edge CLASS=SHAPE ...] [--region [X0,Y0,]WxH]
                             [--scale PX] [-o T.json] [--svg T.svg] [--png T.png]
    tilesolve isohedral list
"""

from __future__ import annotations

import re

import click

from tilesolve.cli import options as opt
from tilesolve.cli.common import say
from tilesolve.cli.outputs import OutputFile, Outputs
from tilesolve.errors import InvalidProblem

__all__ = ["isohedral"]

_NUMBER = r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?"


def _region(text: str, scale: float) -> tuple[float, float, float, float]:
    """``X0,Y0,WxH`` or ``WxH`` (from 0,0), in the tiling's units, or in pixels with a ``px`` suffix
    (divided by ``scale``); numbers may have decimals."""
    m = re.fullmatch(rf"\s*(?:({_NUMBER})\s*,\s*({_NUMBER})\s*,\s*)?({_NUMBER})\s*[xX×]\s*({_NUMBER})\s*(px)?\s*", text)
    if m is None:
        raise InvalidProblem(f"cannot read region {text!r}: expected WxH or X0,Y0,WxH in tile units, e.g. 12x8 "
                             "or -2,-2,12x8, or in pixels, e.g. 800x600px")
    unit = scale if m.group(5) else 1.0
    x0, y0, w, h = (float(g) / unit if g is not None else 0.0 for g in m.groups()[:4])
    return x0, y0, w, h


def _params(text: str | None) -> tuple[float, ...] | None:
    if text is None:
        return None
    parts = [p.strip() for p in text.split(",")] if text.strip() else []
    if not all(re.fullmatch(_NUMBER, p) for p in parts):
        raise InvalidProblem(f"cannot read parameters {text!r}: expected numbers separated by commas, e.g. 0.2,0.5")
    return tuple(float(p) for p in parts)


def _edges(pairs: tuple[str, ...]) -> dict[int, str]:
    out: dict[int, str] = {}
    for item in pairs:
        m = re.fullmatch(r"\s*(\d+)\s*=(.*)", item)
        if m is None:
            raise InvalidProblem(f"cannot read --edge {item!r}: expected CLASS=SHAPE, e.g. 0=bezier:0.3,0.2/0.7,-0.2")
        k = int(m.group(1))
        if k in out:
            raise InvalidProblem(f"--edge gives edge class {k} twice")
        out[k] = m.group(2)
    return out


@click.group(context_settings=opt.CONTEXT_SETTINGS,
             short_help="Isohedral tilings for design: the 93 types, edge shapes, SVG/PNG.")
def isohedral() -> None:
    """Isohedral tilings (Escher-like designs): one tile shape, every tile alike.

    A type IH1..IH93 fixes how the tile meets its neighbours; its parameters move the tiling
    vertices, and each edge class takes a shape of its kind: J (free), U (mirror-symmetric),
    S (symmetric by a half-turn) or I (straight). `list` shows the types; `draw` draws one.
    """


@isohedral.command("draw", context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
                   short_help="Draw a region of an isohedral tiling with your edge shapes.")
@click.option("--type", "type_", required=True, metavar="IHnn", help="The isohedral type, IH1..IH93 (e.g. IH41).")
@click.option("--params", metavar="P,P,...",
              help="The tiling-vertex parameters, as many as `tilesolve isohedral list` shows (default: the "
                   "type's own).")
@click.option("--edge", "edges", multiple=True, metavar="CLASS=SHAPE",
              help="The shape of an edge class (repeatable; the others stay straight), in the edge's frame from "
                   "0,0 to 1,0: 'line', 'line:X,Y/X,Y/...' (a polyline) or 'bezier:X,Y/X,Y' (a cubic's two "
                   "control points; 3k-1 points chain k cubics). U edges must be symmetric in x = 0.5, S edges "
                   "by a half-turn about 0.5,0, I edges straight.")
@click.option("--region", default="8x6", show_default=True, metavar="[X0,Y0,]WxH[px]",
              help="The rectangle drawn, in tile units (a tiling edge is about 1), y up; with 'px', in pixels "
                   "(800x600px: an 800 by 600 picture).")
@click.option("--scale", type=click.FloatRange(1, 1000), default=40.0, show_default=True, metavar="PX",
              help="Pixels per unit: the picture is W*PX by H*PX pixels.")
@click.option("-o", "--output", type=OutputFile("json"), metavar="T.json",
              help="Write the tiling JSON here ('-' for stdout); `tilesolve verify T.json` re-checks it.")
@click.option("--svg", type=OutputFile("svg"), metavar="T.svg", help="Draw the region as SVG.")
@click.option("--png", type=OutputFile("png", allow_dash=False), metavar="T.png", help="Draw the region as PNG.")
@click.pass_context
def draw(ctx, type_, params, edges, region, scale, output, svg, png) -> None:
    """Draw a region of an isohedral tiling: the type's template, your edge shapes, coloured by aspect.

    The tile is refused (one line, exit 2) when a shape breaks its edge's kind or the tile
    crosses itself. Every drawing is checked by the independent verifier (a tiling of the torus
    of its translations: areas and edges matched pairwise, tiles congruent) before it is
    written. The same command writes the same bytes.

    \b
    Examples:
      tilesolve isohedral draw --type IH41 --edge 0=bezier:0.3,0.25/0.6,-0.2 --edge 1=bezier:0.35,-0.2/0.7,0.2 --region 12x8 -o t.json --svg t.svg --png t.png
      tilesolve isohedral draw --type IH28 --params 0.2,0.5 --edge 0=bezier:0.3,0.2/0.7,-0.2 --region 10x8 --png fish.png
      tilesolve isohedral draw --type IH16 --edge 1=line:0.3,0.15/0.6,-0.1 --region -2,-2,10x8 --scale 30 --svg ih16.svg
      tilesolve isohedral draw --type IH90 --edge 0=bezier:0.3,0.3/0.7,-0.3 --region 800x600px --scale 50 --png ih90.png
      tilesolve verify t.json
    """
    from tilesolve.families import isohedral as facade
    from tilesolve.family import draw_solution, write_solution

    problem = facade.problem(type_, _params(params), _edges(edges) or None, _region(region, scale), scale)
    outs = Outputs(output, png, svg)
    sol = facade.solve(problem)
    with outs.commit(sol):
        if output:
            write_solution(output, problem, sol)
        for path, fmt in ((png, "png"), (svg, "svg")):
            if path:
                draw_solution(path, problem, sol, fmt=fmt)
    t = problem.template
    aspects = t.marking.aspects if t.marking else t.n_aspects
    marked = f", marked ({t.marking.group})" if t.marking else ""
    say(f"{sol.status.value}: {problem.describe()}: {sol.tiling.n_tiles:,} tiles, {aspects} aspect"
        f"{'s' if aspects != 1 else ''}{marked}, {t.n_colours} colours, verified, in {sol.time_s:.2f} s")
    if outs.files:
        say(f"  wrote {', '.join(outs.files)}")
    ctx.exit(sol.status.exit_code)


@isohedral.command("list", context_settings=opt.CONTEXT_SETTINGS,
                   short_help="The 93 types: parameters, aspects, edge classes.")
def list_types() -> None:
    """The 93 isohedral types: parameter count and defaults, aspects, and edge classes
    (their kinds, numbered as --edge takes them).

    Twelve types (IH19, 35, 48, 60, 63, 65, 70, 75, 80, 87, 89, 92) need marked tiles: their
    edges are straight, their outlines are those of another type, and each tile carries a
    marking (a motif of flags) that gives the tiling the type's smaller symmetry group.

    \b
    Example:
      tilesolve isohedral list
    """
    from tilesolve.model.isohedral import TYPES, isohedral_type

    click.echo(f"{'type':<6}{'params':>7}  {'aspects':>7}  {'edge classes':<24}defaults / notes")
    for n in TYPES:
        t = isohedral_type(n)
        classes = " ".join(f"{k}:{kind}" for k, kind in enumerate(t.edge_kinds))
        note = ",".join(f"{p:.6g}" for p in t.default_params) or "-"
        if t.outline_of:
            note += f"  (marked, {t.marking.group}: outline of IH{t.outline_of:02d})"
        click.echo(f"{t.name:<6}{t.n_params:>7}  {t.n_aspects:>7}  {classes:<24}{note}")
