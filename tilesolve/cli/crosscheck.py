"""``tilesolve crosscheck wall | tiling``: the random-access generators against the SAT route,
on random windows (a thin layer over :mod:`tilesolve.families.crosscheck_windows`)."""

from __future__ import annotations

import click

from tilesolve.cli import options as opt
from tilesolve.cli.common import sweep_trials
from tilesolve.family import draw_seed

__all__ = ["crosscheck"]

trials_opt = click.option("--trials", type=click.IntRange(1, 100_000), default=20, show_default=True, metavar="N",
                          help="Number of random windows.")
max_size_opt = click.option("--max-size", type=click.IntRange(1, 16), default=None, metavar="N",
                            help="Largest window side in cells  [default: 8 for walls, 6 for tilings]")
time_limit_opt = click.option("--time-limit", type=click.FloatRange(min=0, min_open=True), default=None,
                              metavar="SECONDS", help="Time limit of each SAT call (unknown is reported, not failed).")


@click.group(context_settings=opt.CONTEXT_SETTINGS, short_help="Generators against the SAT route on random windows.")
def crosscheck() -> None:
    """Cross-check the random-access generators against the solver route on random windows.

    Each trial draws a window (sizes up to --max-size, coordinates near the origin, far
    away, or near the edge of the 63-bit lattice), runs the generator, and checks that the
    window verifies, that it satisfies the SAT encoding of that window with its own boundary,
    and that the SAT route solves the same window too (its tiling verified). Exit 0 when
    every trial agrees, 1 on any disagreement, 130 on Ctrl-C.
    """


@crosscheck.command(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP)
@trials_opt
@opt.seed_opt
@click.option("--max-line", type=opt.positive_int, default=None, metavar="N",
              help="Line limit n of every window  [default: each trial draws 1 to 10, or no limit]")
@click.option("--colors", type=click.IntRange(3, 63), default=None, metavar="K",
              help="Colours of every window  [default: each trial draws 3 to 5]")
@max_size_opt
@time_limit_opt
@click.pass_context
def wall(ctx, trials, seed, max_line, colors, max_size, time_limit) -> None:
    """Procedural wall windows (004 §3-4, App. B) against the board CNF and the SAT route.

    Every window, with its own boundary and the line limit it was built with, must verify
    with the board verifier, satisfy the board CNF (line-limit clauses included, the
    assignment checked clause by clause), and be solved by the SAT route.

    \b
    Example:
      tilesolve crosscheck wall --trials 5 --seed 1
      tilesolve crosscheck wall --trials 3 --max-line 2 --colors 4 --max-size 6 --seed 2
    """
    import numpy as np

    from tilesolve.families.crosscheck_windows import crosscheck_wall_window, random_wall_window

    base = draw_seed() if seed is None else seed

    def run_trial(i):
        p = random_wall_window(np.random.default_rng((base, i)), max_side=max_size or 8, max_line=max_line,
                               colors=colors)
        x0, y0, w, h = p["window"]
        n = "no limit" if p["max_line"] is None else f"n {p['max_line']}"
        label = f"seed {base + i}, window {w}x{h} at ({x0}, {y0}), {n}, {p['colors']} colours"
        return label, crosscheck_wall_window(p["window"], colors=p["colors"], max_line=p["max_line"], seed=base + i,
                                             time_limit=time_limit)

    sweep_trials(ctx, trials, run_trial, f"crosscheck: all {trials} windows agree (seed {base})")


@crosscheck.command(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP)
@trials_opt
@opt.seed_opt
@click.option("--kind", type=click.Choice(("wang", "corner")), default=None,
              help="Tile kind of every window  [default: each trial draws one]")
@click.option("--method", type=click.Choice(("scanline", "direct")), default=None,
              help="Route of every window  [default: each trial draws one that applies]")
@click.option("--colors", type=click.IntRange(2, 4), default=None, metavar="C",
              help="Colours of every window  [default: each trial draws 2 or 3]")
@max_size_opt
@time_limit_opt
@click.pass_context
def tiling(ctx, trials, seed, kind, method, colors, max_size, time_limit) -> None:
    """Stochastic Wang and corner tiling windows (class notes ch. 3) against the grid-tiling CNF and SAT.

    Every window (complete, compact or sums sets; scanline or direct route) must verify with
    the grid verifier, its Wang images (§2.9) with the window's own boundary must satisfy the
    board CNF of the set's tiles, and the SAT route must solve the same window.

    \b
    Example:
      tilesolve crosscheck tiling --trials 5 --seed 1
      tilesolve crosscheck tiling --trials 3 --kind corner --method direct --seed 2
    """
    import numpy as np

    from tilesolve.families.crosscheck_windows import crosscheck_tiling_window, random_tiling_window

    base = draw_seed() if seed is None else seed

    def run_trial(i):
        problem, route = random_tiling_window(np.random.default_rng((base, i)), max_side=max_size or 6, kind=kind,
                                              method=method, colors=colors)
        win = problem.window
        label = (f"seed {base + i}, {route} {problem.variant} {problem.kind} C={problem.colors}, "
                 f"window {win.width}x{win.height} at ({win.x0}, {win.y0})")
        return label, crosscheck_tiling_window(problem, method=route, seed=base + i, time_limit=time_limit)

    sweep_trials(ctx, trials, run_trial, f"crosscheck: all {trials} windows agree (seed {base})")
