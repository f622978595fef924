"""``tilesolve demo``: solve a few showcase problems into a folder of pictures.

:data:`DEMOS` is a list of small functions ``demo(out_dir, seed, time_limit) -> DemoResult``;
each solves its problem, writes its files and returns what to print. Later families append
their own.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import click
import numpy as np

from tilesolve.cli import options as opt
from tilesolve.cli.common import progress_wanted

__all__ = ["demo", "DEMOS", "DemoResult"]


@dataclass
class DemoResult:
    """``ok`` when the demo produced its picture; ``lines`` to print."""

    ok: bool
    lines: list[str] = field(default_factory=list)


def _solve_and_draw(out: Path, name: str, what: str, problem, *, seed: int, time_limit: float,
                    repeat: int = 1) -> DemoResult:
    """Solve ``problem`` and write ``name.json`` and ``name.svg``; return the report lines."""
    from tilesolve import dappled as facade
    from tilesolve.io.jsonio import write_solution
    from tilesolve.io.svg import write_svg

    sol = facade.solve(problem, seed=seed, time_limit=time_limit, progress=progress_wanted())
    json_path, svg_path = out / f"{name}.json", out / f"{name}.svg"
    write_solution(json_path, problem, sol)
    line = f"{name:12s} {what}: {sol.status.value} by {sol.method} in {sol.time_s:.2f} s"
    if sol.objective is not None:
        line += f", distance {sol.objective}"
    lines = [line]
    if sol.status.has_tiling:
        notes = [f"{sol.status.value} by {sol.method}, seed {seed}"]
        if sol.objective is not None:
            notes.append(f"distance to the target: {sol.objective} cells")
        write_svg(svg_path, sol.tiling, problem=problem, repeat=repeat, title=what, notes=notes)
        lines.append(f"{'':12s} -> {svg_path}")
    else:
        lines.append(f"{'':12s} no picture ({sol.reason or sol.status.value})")
    return DemoResult(sol.status.has_tiling, lines)


def plain(out: Path, seed: int, time_limit: float) -> DemoResult:
    """Algorithm 1 (dappled §2) on T = {0, 1}, L = {H0=2, V1=3}."""
    from tilesolve.model.dappled import DappledProblem

    p = DappledProblem.from_strings("32x20", ["H0=2", "V1=3"])
    return _solve_and_draw(out, "plain", "tile 0 runs <= 2 across, tile 1 runs <= 3 down", p,
                           seed=seed, time_limit=time_limit)


def cyclic(out: Path, seed: int, time_limit: float) -> DemoResult:
    """Algorithm 2 (dappled §3.2, Prop. 3.2): a torus tiling, drawn 2 x 2 to show the seams."""
    from tilesolve.model.dappled import DappledProblem

    p = DappledProblem.from_strings("16x12", ["H0=3", "V0=3", "H1=3", "V1=3"], cyclic=True)
    return _solve_and_draw(out, "cyclic", "cyclic, runs <= 3 both ways, shown 2x2", p,
                           seed=seed, time_limit=time_limit, repeat=2)


def nonuniform(out: Path, seed: int, time_limit: float) -> DemoResult:
    """Example 3.1 (dappled §3.1): limits that vary across the grid.

    The paper gives ``p0(i, j) = q1(i, j) = ceil((i+1)/5) + 1`` and ``p1(i, j) = ceil((m-i)/5) + 1``
    with ``i`` the column; the extraction lost ``q0``, which we take equal to ``p1`` so that
    the text's description holds (left: short white rows and orange columns; right: the reverse).
    """
    from tilesolve.model.dappled import Condition, DappledProblem

    rows, m = 30, 60
    i = np.arange(m)
    left = np.array([math.ceil((k + 1) / 5) + 1 for k in i], dtype=np.int32)
    right = np.array([math.ceil((m - k) / 5) + 1 for k in i], dtype=np.int32)
    grid = lambda v: np.tile(v, (rows, 1))  # noqa: E731
    conds = (Condition("H", (0,), grid(left)), Condition("V", (1,), grid(left)),
             Condition("H", (1,), grid(right)), Condition("V", (0,), grid(right)))
    p = DappledProblem(rows, m, conditions=conds)
    return _solve_and_draw(out, "nonuniform", "Example 3.1: limits vary from left to right", p,
                           seed=seed, time_limit=time_limit)


def closest(out: Path, seed: int, time_limit: float) -> DemoResult:
    """The closest dappled tiling to a picture (dappled §6 item 3), by MaxSAT."""
    from tilesolve.io.svg import write_svg
    from tilesolve.model.dappled import DappledProblem

    n = 24
    yy, xx = np.mgrid[0:n, 0:n]
    target = (((yy - (n - 1) / 2) ** 2 + (xx - (n - 1) / 2) ** 2) <= (n * 0.36) ** 2).astype(np.int8)
    p = DappledProblem.from_strings(f"{n}x{n}", ["H0=3", "V0=3", "H1=3", "V1=3"], closest_to=target)
    target_svg = out / "closest-target.svg"
    write_svg(target_svg, target, n_tiles=2, title="the target picture (a disc)")
    res = _solve_and_draw(out, "closest", "nearest tiling with runs <= 3 to a disc", p,
                          seed=seed, time_limit=time_limit)
    res.lines.append(f"{'':12s} -> {target_svg} (the target)")
    return res


def three_tiles(out: Path, seed: int, time_limit: float) -> DemoResult:
    """Three tiles, every run at most 2 (the |T| >= 3 case of dappled §2)."""
    from tilesolve.model.dappled import DappledProblem

    p = DappledProblem.from_strings("30x18", ["H0=2", "V0=2", "H1=2", "V1=2", "H2=2", "V2=2"], n_tiles=3)
    return _solve_and_draw(out, "three-tiles", "|T| = 3, no run longer than 2", p,
                           seed=seed, time_limit=time_limit)


#: The demos, in the order they run.
DEMOS: list[Callable[[Path, int, float], DemoResult]] = [plain, cyclic, nonuniform, closest, three_tiles]

from tilesolve.cli.pack import demo_packing  # noqa: E402 - tile packings (issue 4)

DEMOS.append(demo_packing)

from tilesolve.cli.brick import demo_brick  # noqa: E402 - brick Wang tilings of boards (issue 3)

DEMOS.append(demo_brick)


@click.command(context_settings=opt.CONTEXT_SETTINGS)
@click.option("--out", "out_dir", type=click.Path(file_okay=False), default="tilesolve-demo", show_default=True,
              help="Folder for the pictures (created if missing).")
@click.option("--seed", type=click.IntRange(min=0), default=1, show_default=True, help="Random seed.")
@click.option("--time-limit", type=click.FloatRange(min=0, min_open=True), default=60.0, show_default=True,
              metavar="S", help="Seconds allowed per demo.")
@click.pass_context
def demo(ctx, out_dir: str, seed: int, time_limit: float) -> None:
    """Solve a few showcase problems into a folder of SVG pictures (and their JSON).

    \b
    Example:
      tilesolve demo --out pictures
      tilesolve verify pictures/plain.json

    Exit 0 when every demo produced its picture, 1 otherwise.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    click.echo(f"tilesolve demo: writing to {out}/")
    ok = True
    for fn in DEMOS:
        res = fn(out, seed, time_limit)
        ok &= res.ok
        for line in res.lines:
            click.echo(line)
    click.echo(f"done: open {out}/*.svg in a browser" if ok else "some demos produced no picture")
    ctx.exit(0 if ok else 1)
