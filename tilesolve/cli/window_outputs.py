"""What the commands that tile a window of the plane (``tiling``, ``aperiodic tiling``) write and
say: the JSON, PNG and SVG of the window, or its grid printed, then the summary."""

from __future__ import annotations

import click

from tilesolve.cli.common import say
from tilesolve.errors import InvalidProblem
from tilesolve.io.units import big
from tilesolve.progress import Progress

__all__ = ["check_svg_size", "finish_window"]


def check_svg_size(problem, svg) -> None:
    """Refuse ``--svg`` of a window too large for SVG, before any work."""
    from tilesolve.io.svg_packing import MAX_SVG_TILES

    if svg and problem.n_cells > MAX_SVG_TILES:
        rows, cols = problem.shape
        raise InvalidProblem(f"a {cols}x{rows} window is too large for SVG (at most {MAX_SVG_TILES:,} tiles); "
                             "use --png")


def finish_window(ctx: click.Context, problem, sol, outs, progress: Progress, output, png, svg, **svg_options) -> None:
    """Write the verified window ``sol`` to the outputs given (all or none: ``outs``), or print its
    grid of tile numbers when none is; say what was done and exit with the status's code."""
    from tilesolve.family import draw_solution, write_solution

    with outs.commit(sol), progress.task(f"writing a window of {big(problem.n_cells)} tiles", unit=None):
        if output:
            write_solution(output, problem, sol)
        if png:
            draw_solution(png, problem, sol, fmt="png")
        if svg:
            draw_solution(svg, problem, sol, fmt="svg", **svg_options)
    if not outs:
        width = len(str(int(sol.tiling.max())))
        for row in sol.tiling.tolist():
            click.echo(" ".join(f"{v:{width}d}" for v in row))
    say(f"{sol.status.value}: {problem.describe()} by {sol.method}, seed {sol.seed}, in {sol.time_s:.2f} s")
    if outs.files:
        say(f"  wrote {', '.join(outs.files)}")
    ctx.exit(sol.status.exit_code)
