"""``tilesolve dappled solve | count | crosscheck``: thin layers over :mod:`tilesolve.families.dappled`."""

from __future__ import annotations

import click

from tilesolve.cli import options as opt
from tilesolve.cli.common import build_problem, progress_wanted, say, sweep_trials
from tilesolve.cli.outputs import Outputs
from tilesolve.errors import InvalidProblem
from tilesolve.families.dappled import COUNT_METHODS, METHODS
from tilesolve.family import draw_seed, raise_if_interrupted

method_opt = click.option(
    "--method",
    type=click.Choice(METHODS),
    default="auto",
    show_default=True,
    help="auto: the papers' constructive algorithms when they apply, MaxSAT for --closest-to, SAT otherwise.",
)
count_method_opt = click.option(
    "--method",
    type=click.Choice(COUNT_METHODS),
    default="auto",
    show_default=True,
    help="transfer: row-by-row transfer matrix (exact, fast); enumerate: solver enumeration (any problem).",
)

__all__ = ["dappled", "solve", "count", "crosscheck"]


@click.group(context_settings=opt.CONTEXT_SETTINGS, short_help="Dappled tilings: solve, count, crosscheck.")
def dappled() -> None:
    """Dappled tilings: no long runs of a tile (Kaji, Derouet-Jourdan, Ochiai 2016).

    A tiling of a W x H grid by tiles 0..K-1 is L-dappled when it satisfies every
    condition in L, e.g. H0=2 (no horizontal run of tile 0 longer than 2).
    """


def _pictures_ok(ctx, problem, svg, png, repeat) -> None:
    """Refuse impossible pictures, and picture options without a picture, before any solving.

    The picture modules are imported only when a picture is asked for (start-up)."""
    if not (svg or png):
        given = [f"--{n}" for n in ("repeat", "grid") if ctx.get_parameter_source(n) == click.core.ParameterSource.COMMANDLINE]
        if given:
            raise InvalidProblem(f"{' and '.join(given)} only {'change' if len(given) > 1 else 'changes'} "
                                 "the picture: add --svg FILE or --png FILE")
    if svg:
        from tilesolve.io.svg import check_svg_size

        check_svg_size(problem.rows, problem.cols)
    if png:
        from tilesolve.io.png import MAX_PNG_PIXELS

        if problem.size * repeat * repeat > MAX_PNG_PIXELS:
            raise InvalidProblem(f"a {repeat}x{repeat} repeat of this grid is larger than the {MAX_PNG_PIXELS:,} px "
                                 "PNG limit")


def _summary(problem, sol, written: list[str], extra: list[str]) -> None:
    head = f"{sol.status.value}: {problem.describe()}"
    say(head)
    parts = [f"method {sol.method or '?'}"]
    if sol.solver:
        parts.append(f"solver {sol.solver}")
    if sol.seed is not None:
        parts.append(f"seed {sol.seed}")
    parts.append(f"{sol.time_s:.3f} s")
    say("  " + ", ".join(parts))
    if sol.objective is not None:
        say(f"  distance to the target: {sol.objective} cells")
    if sol.reason:
        say(f"  {'why' if sol.status.value == 'unsat' else 'stopped'}: {sol.reason}")
    for note in sol.notes:
        say(f"  note: {note}")
    for k, v in sol.stats.items():
        say(f"  {k}: {v}", level=1)
    for line in extra:
        say(f"  {line}")
    if written:
        say("  wrote " + ", ".join(written))


@dappled.command(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.CONDITION_HELP + "\n\n" + opt.READER_HELP)
@opt.problem_options()
@method_opt
@opt.seed_opt
@opt.time_limit_opt
@opt.proof_dir_opt
@opt.initial_opt
@opt.output_opt
@opt.picture_options
@click.pass_context
def solve(ctx, method, seed, time_limit, initial, output, svg, png, repeat, grid, **problem_kw) -> None:
    """Find an L-dappled tiling, or prove that none exists.

    \b
    Example:
      tilesolve dappled solve --size 12x8 --cond H0=2 --cond V1=3 -o t.json --svg t.svg
      tilesolve dappled solve --size 16x16 --cond H0=2,V0=2,H1=2,V1=2 --cyclic --svg t.svg --repeat 2
      tilesolve dappled solve --size 12x8 --cond H0=2 --cond V1=3 --fix t.json -o t2.json  # keeps t.json's cells

    The summary (status, method, time, notes, files) goes to stderr; without -o/--svg/--png
    the tiling itself is printed to stdout as a text grid (a digit per cell, top row first).
    The files are written together at the end, or none of them.
    """
    from tilesolve.families import dappled as facade
    from tilesolve.io.dappled_json import format_text_grid, read_tiling, write_solution

    outs = Outputs(output, svg, png)
    problem = build_problem(**problem_kw)
    _pictures_ok(ctx, problem, svg, png, repeat)
    init = read_tiling(initial, what="initial tiling") if initial else None
    if init is not None:
        if init.shape != problem.shape:
            raise InvalidProblem(
                f"{initial}: initial tiling is {init.shape[1]}x{init.shape[0]} (WxH), the grid is {problem.cols}x{problem.rows}"
            )
        if (init >= problem.n_tiles).any():
            raise InvalidProblem(f"{initial}: initial tiling uses tile {int(init.max())}; tiles are 0..{problem.n_tiles - 1}")
    extra: list[str] = []
    if repeat > 1 and not problem.cyclic:
        extra.append("note: --repeat draws copies side by side; without --cyclic the seams may break the conditions")
    sol = facade.solve(problem, method=method, seed=seed, time_limit=time_limit, initial=init, progress=progress_wanted())

    written: list[str] = []
    with outs.commit(sol):
        if output:
            write_solution(output, problem, sol)
            written.append(output)
        if sol.status.has_tiling:
            from tilesolve.family import draw_solution

            for path, fmt in ((svg, "svg"), (png, "png")):
                if path:  # the family's pictures: legend and caption
                    draw_solution(path, problem, sol, fmt=fmt, repeat=repeat, grid=grid)
                    written.append(path)
        elif svg or png:
            extra.append(f"no picture: status {sol.status.value}, no tiling")
    if not outs and sol.status.has_tiling:
        click.echo(format_text_grid(sol.tiling), nl=False)
    written = [w for w in written if w != "-"]
    _summary(problem, sol, written, extra)
    ctx.exit(sol.status.exit_code)


@dappled.command(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.CONDITION_HELP + "\n\n" + opt.READER_HELP)
@opt.problem_options(closest=False)
@count_method_opt
@opt.time_limit_opt
@click.option("--force", is_flag=True, help="Start a count estimated to take very long (a large torus, or an "
              "enumeration) without a time limit.")
@click.pass_context
def count(ctx, method, time_limit, force, **problem_kw) -> None:
    """Count the L-dappled tilings exactly; the count is the last line of stdout.

    \b
    Example:
      tilesolve dappled count --size 3x3 --cond H0=2 --cond V1=2        # prints 174
      tilesolve dappled count --size 8x8 --cond H0=2,V1=2 --cyclic       # prints 543336096522

    Exit 0 whenever the count is exact (0 included), 3 when the time limit ran out.
    """
    from tilesolve.families import dappled as facade
    from tilesolve.model.solution import Status

    problem = build_problem(**problem_kw)
    res = facade.count(problem, method=method, time_limit=time_limit, progress=progress_wanted(), force=force)
    raise_if_interrupted(res)
    exact = res.value is not None and res.status != Status.UNKNOWN
    say(f"{'count' if exact else 'unknown'}: {problem.describe()}")
    say(f"  method {res.method}, {res.time_s:.3f} s")
    if res.note:
        say(f"  note: {res.note}")
    if exact:
        click.echo(str(res.value))
        ctx.exit(0)
    ctx.exit(Status.UNKNOWN.exit_code)


@dappled.command(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.CONDITION_HELP + "\n\n" + opt.READER_HELP)
@opt.problem_options()
@opt.seed_opt
@opt.time_limit_opt
@click.option("--trials", type=click.IntRange(1, 1000), default=1, show_default=True,
              help="Run the cross-check N times with seeds SEED, SEED+1, ...")
@click.pass_context
def crosscheck(ctx, seed, time_limit, trials, **problem_kw) -> None:
    """Solve one problem by every route and check that they agree.

    The constructive output must pass the independent verifier and satisfy the CNF
    encoding; SAT and CP-SAT must agree on solvability; every tiling must verify; on
    small grids the transfer-matrix count must equal the enumeration count.

    \b
    Example:
      tilesolve dappled crosscheck --size 8x6 --cond H0=2 --cond V1=2 --trials 5

    Exit 0 when every check passes, 1 on any disagreement.
    """
    from tilesolve.families import dappled as facade

    problem = build_problem(**problem_kw)
    base = draw_seed() if seed is None else seed
    click.echo(f"crosscheck: {problem.describe()}")

    def run_trial(i):
        return f"seed {base + i}", facade.crosscheck(problem, seed=base + i, time_limit=time_limit)

    sweep_trials(ctx, trials, run_trial, "crosscheck: all routes agree")
