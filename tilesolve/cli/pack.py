"""``tilesolve pack``: tile packings (class notes §5.5) -- build, count, export.

Fixed forms (issue 4)::

    tilesolve pack --kind corner|wang --colors C [--method ...] [--seed N] [--time-limit S]
                   [--workers N] -o PACK.json [--svg PACK.svg]
    tilesolve pack count --kind wang|corner --colors 2 [--up-to-symmetry]   # count on the last line
    tilesolve verify PACK.json
"""

from __future__ import annotations

import click

from tilesolve.cli import options as opt
from tilesolve.cli.common import check_colors, progress_wanted, say
from tilesolve.cli.outputs import OutputFile, Outputs
from tilesolve.errors import InvalidProblem

__all__ = ["pack"]

_KINDS = click.Choice(["corner", "wang"])


def _methods() -> list[str]:
    from tilesolve.families.packing import METHODS

    return list(METHODS)


def _refuse_contradictions(ctx, dimacs, svg) -> None:
    """Refuse options that would be silently ignored: solving options with --dimacs, --indices without --svg."""
    from click.core import ParameterSource

    given = [p for p in ctx.command.params
             if p.name and ctx.get_parameter_source(p.name) == ParameterSource.COMMANDLINE]
    if dimacs:
        clash = [p.opts[-1] if p.name != "output" else "-o" for p in given
                 if p.name not in ("kind", "colors", "colors_v", "fix", "dimacs")]
        if clash:
            raise InvalidProblem(f"--dimacs writes the encoding instead of solving; drop {', '.join(clash)}")
    elif ctx.params.get("indices") and not svg:
        raise InvalidProblem("--indices labels the SVG tiles: add --svg FILE")


def _parse_fix(items) -> tuple[tuple[int, int, int], ...]:
    out = []
    for item in items:
        parts = item.replace(":", ",").split(",")
        try:
            r, c, t = (int(p) for p in parts)
        except ValueError:
            raise InvalidProblem(f"--fix takes ROW,COL,TILE (e.g. 0,0,5), got {item!r}") from None
        out.append((r, c, t))
    return tuple(out)


@click.group(invoke_without_command=True, context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
             short_help="Tile packings: all C^4 Wang or corner tiles on a C^2 x C^2 torus.")
@click.option("--kind", type=_KINDS, default=None, help="Wang tiles (coloured edges) or corner tiles (coloured corners).")
@click.option("--colors", type=int, default=None, metavar="C", help="Number of colours C (>= 2).")
@click.option("--colors-v", type=int, default=None, metavar="CV",
              help="Wang tiles only: colours of the vertical (E/W) edges if different from C.")
@click.option("--method", type=click.Choice(_methods()), default="auto", show_default=True,
              help="euler: Eulerian constructions (Wei's closed form; odd C for corner tiles); outer: the same "
                   "over random Eulerian circuits; known: the notes' C=4 packings; sat/cpsat: the full search "
                   "(random-looking, C <= 3, proves pins contradictory); hybrid (Wang): random Eulerian N/S "
                   "columns, SAT for the rest; lift: a packing over C/k colours plus a k-ary layer by SAT "
                   "(even C up to 12 and beyond; timings in README); recursive: a C-1 packing pinned in the "
                   "bottom-left corner, SAT for the rest (Figs. 5.11-5.12). auto picks by kind and C.")
@click.option("--fix", "fix", multiple=True, metavar="R,C,T", help="Pin tile T at row R, column C (repeatable).")
@opt.seed_opt
@opt.time_limit_opt
@opt.proof_dir_opt
@click.option("--workers", type=click.IntRange(1, 256), default=None, metavar="N",
              help="CP-SAT workers; for sat/hybrid/lift/recursive, the processes of the seed portfolio that starts "
                   "beside a first run that has not decided quickly, this one included (1: one seed, reproducible) "
                   "[default: up to 2, as idle cores allow].")
@click.option("--cluster", default=None, metavar="ADDRESS",
              help="Run the seed portfolio on this Dask scheduler (e.g. tcp://host:8786) instead of local "
                   "processes; needs pip install \"tilesolve[cluster]\".")
@click.option("-o", "--output", type=OutputFile("json"), metavar="PACK.json",
              help="Write the packing JSON here ('-' for stdout). Without -o or --svg the grid is printed.")
@click.option("--svg", type=OutputFile("svg"), metavar="PACK.svg",
              help="Also draw the packing as SVG ('-' for stdout).")
@click.option("--indices", is_flag=True, help="Write tile indices on the SVG tiles (needs --svg).")
@click.option("--dimacs", type=OutputFile("cnf"), metavar="PACK.cnf",
              help="Write the SAT encoding as DIMACS CNF instead of solving (a hard benchmark for C >= 4); "
                   "takes no solving or drawing options.")
@click.pass_context
def pack(ctx, kind, colors, colors_v, method, fix, seed, time_limit, workers, cluster, output, svg, indices,
         dimacs) -> None:
    """Pack the C^4 tiles of a complete Wang or corner tile set into a C^2 x C^2 torus.

    Every packing is checked by the independent verifier before it is written.

    \b
    Examples:
      tilesolve pack --kind wang --colors 4 -o wang4.json --svg wang4.svg
      tilesolve pack --kind wang --colors 3 --method sat --seed 1 -o w3.json
      tilesolve pack --kind corner --colors 5 --method euler -o c5.json
      tilesolve pack --kind wang --colors 4 --method hybrid --seed 1 -o w4.json
      tilesolve pack --kind corner --colors 8 --method lift --seed 1 -o c8.json
      tilesolve pack --kind corner --colors 3 --method recursive --seed 1 --svg c3.svg --indices
      tilesolve pack count --kind wang --colors 2 --up-to-symmetry
      tilesolve verify wang4.json
    """
    if ctx.invoked_subcommand is not None:
        return
    from tilesolve.families import packing as facade
    from tilesolve.model.packing import PackingProblem

    if kind is None or colors is None:
        raise InvalidProblem("tilesolve pack needs --kind corner|wang and --colors C (or: tilesolve pack count ...)")
    _refuse_contradictions(ctx, dimacs, svg)
    outs = Outputs(output, svg, dimacs)
    check_colors(kind, colors, colors_v)
    problem = PackingProblem(kind, colors, colors_v, _parse_fix(fix))
    if svg:
        from tilesolve.io.svg_packing import MAX_SVG_TILES

        if problem.n_tiles > MAX_SVG_TILES:
            rows, cols = problem.shape
            raise InvalidProblem(f"a {rows}x{cols} packing is too large for SVG (at most {MAX_SVG_TILES:,} tiles); "
                                 "write the JSON with -o instead")
    if dimacs:
        from tilesolve.io.dimacs import write_dimacs

        enc = facade.FAMILY.encode(problem)
        with outs.commit():
            write_dimacs(enc, dimacs)
        say(f"wrote {'the encoding' if dimacs == '-' else dimacs}: {enc.n_vars:,} variables, {len(enc.clauses):,} clauses ({problem.describe()})")
        return
    sol = facade.solve(problem, method=method, seed=seed, time_limit=time_limit, workers=workers, cluster=cluster,
                       progress=progress_wanted())
    written = []
    with outs.commit(sol):
        if output:
            from tilesolve.io.packing_json import write_packing

            write_packing(output, problem, sol)
            written.append(output)
        if svg and sol.status.has_tiling:
            from tilesolve.io.svg_packing import write_packing_svg

            write_packing_svg(svg, sol.tiling, kind, colors, colors_v=colors_v, indices=indices,
                              title=f"{kind} packing, C={colors} ({sol.method})")
            written.append(svg)
    written = [w for w in written if w != "-"]
    if not outs and sol.status.has_tiling:
        width = len(str(problem.n_tiles - 1))
        for row in sol.tiling.tolist():
            click.echo(" ".join(f"{v:{width}d}" for v in row))
    line = f"{sol.status.value}: {problem.describe()} by {sol.method} in {sol.time_s:.2f} s"
    if sol.reason:
        line += f" ({sol.reason})"
    say(line)
    for n in sol.notes:
        say(f"  note: {n}")
    if written:
        say(f"  wrote {', '.join(written)}")
    ctx.exit(sol.status.exit_code)


@pack.command("count", context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP)
@click.option("--kind", type=_KINDS, required=True, help="Wang or corner tiles.")
@click.option("--colors", type=int, required=True, metavar="C", help="Number of colours (C = 2).")
@click.option("--up-to-symmetry", is_flag=True,
              help="Count orbits under translation, rotation, reflection and colour permutation.")
@opt.time_limit_opt
@click.pass_context
def count_cmd(ctx, kind, colors, up_to_symmetry, time_limit) -> None:
    """Count all packings (C = 2); the count is the last line of output.

    The notes (§5.5.3) publish 32 corner packings (1 up to symmetry) and 203,520 Wang packings.

    \b
    Examples:
      tilesolve pack count --kind wang --colors 2                     # 203520
      tilesolve pack count --kind corner --colors 2 --up-to-symmetry  # 1
    """
    from tilesolve.families import packing as facade
    from tilesolve.model.packing import PackingProblem

    res = facade.count(PackingProblem(kind, colors), up_to_symmetry=up_to_symmetry, time_limit=time_limit)
    what = ("packing" if res.value == 1 else "packings") + (" up to symmetry" if up_to_symmetry else "")
    if not res.exact:
        say(f"unknown: {res.note} after {res.stats['anchored']} anchored packings")
        ctx.exit(3)
    say(f"{kind} C={colors}: {res.value:,} {what} ({res.stats['anchored']:,} with tile 0 at the origin, "
        f"{res.stats['nodes']:,} search nodes, {res.time_s:.2f} s)")
    click.echo(str(res.value))
