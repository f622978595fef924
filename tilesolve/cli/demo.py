"""``tilesolve demo``: solve every family's showcase problems into a folder of pictures.

The demos are the families' :class:`~tilesolve.family.Demo` records (registry order); each is
solved with one worker (so the same seed gives the same pictures), written as JSON in its
family's format and drawn as SVG.
"""

from __future__ import annotations

from pathlib import Path

import click

from tilesolve.cli import options as opt
from tilesolve.cli.common import progress_wanted

__all__ = ["demo"]


@click.command(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP)
@click.option("--out", "out_dir", type=click.Path(file_okay=False), default="tilesolve-demo", show_default=True,
              help="Folder for the pictures (created if missing).")
@click.option("--seed", type=click.IntRange(min=0), default=1, show_default=True, help="Random seed.")
@click.option("--time-limit", type=click.FloatRange(min=0, min_open=True, max=1e9), default=60.0, show_default=True,
              metavar="S", help="Seconds allowed per demo.")
@click.option("--family", "only", multiple=True, metavar="NAME", help="Only this family's demos (repeatable).")
@click.pass_context
def demo(ctx, out_dir: str, seed: int, time_limit: float, only: tuple[str, ...]) -> None:
    """Solve every family's showcase problems into a folder of SVG pictures (and their JSON).

    \b
    Example:
      tilesolve demo --out pictures
      tilesolve demo --family packing
      tilesolve verify pictures/plain.json

    Exit 0 when every demo produced its picture, 1 otherwise.
    """
    from tilesolve.family import draw_solution, get, iter_demos, raise_if_interrupted, solve, write_solution

    for name in only:
        get(name)  # an unknown family name is a usage error, before anything is written
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    click.echo(f"tilesolve demo: writing to {out}/")
    ok, n = True, 0
    for fam, d in iter_demos():
        if only and fam.name not in only:
            continue
        n += 1
        problem = d.make()
        sol = raise_if_interrupted(solve(problem, d.method, seed=seed, time_limit=time_limit, workers=1,
                                         progress=progress_wanted()))
        write_solution(out / f"{d.name}.json", problem, sol)
        click.echo(f"{d.name:16s} {d.caption}: {sol.verdict} by {sol.method} in {sol.time_s:.2f} s")
        if sol.answer is not None:
            svg = out / f"{d.name}.svg"
            draw_solution(svg, problem, sol, title=d.caption, **d.draw_options)
            click.echo(f"{'':16s} -> {svg}")
        else:
            ok = False
            click.echo(f"{'':16s} no picture ({sol.reason or sol.status.value})")
    click.echo(f"done: {n} demos; open {out}/*.svg in a browser" if ok else "some demos produced no picture")
    ctx.exit(0 if ok else 1)
