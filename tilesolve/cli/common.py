"""Pieces the commands share: error display, problem building, output checks, summaries."""

from __future__ import annotations

import re
from typing import Iterable

import click

from tilesolve.errors import InvalidProblem
from tilesolve.io.units import big, human_bytes
from tilesolve.progress import Progress, terminal

__all__ = ["CliError", "usage_error", "build_problem", "check_writable", "say", "verbosity", "progress_wanted",
           "sweep_trials",
           "split_conditions", "check_colors", "human_bytes", "big",
           "MAX_COMPLETE_TILES"]

#: Most tiles in a complete tile set the CLI builds (``pack``, ``tiles``): C^2 x C_v^2 = 2^24,
#: i.e. C = 64, a 128 MiB grid of int64 tile indices.
MAX_COMPLETE_TILES = 2**24


class CliError(click.ClickException):
    """A user-facing error: one line ``tilesolve: error: ...`` on stderr and an exit code."""

    def __init__(self, message: str, exit_code: int = 2) -> None:
        super().__init__(message)
        self.exit_code = exit_code

    def show(self, file=None) -> None:  # noqa: D102 - click API
        message = " ".join(self.format_message().split())
        click.echo(f"tilesolve: error: {message}", err=True)


def usage_error(exc: click.UsageError) -> CliError:
    """A click usage error (bad option value, unknown command, missing argument) as one line.

    ``tilesolve: error: dappled solve: Invalid value for '--method': ... (see tilesolve dappled solve --help)``
    """
    path = exc.ctx.command_path if exc.ctx is not None else "tilesolve"
    where = path.split(" ", 1)[1] + ": " if " " in path else ""
    return CliError(f"{where}{exc.format_message()} (see {path} --help)", 2)


def verbosity() -> int:
    """``-v`` count minus ``-q`` count of the current invocation (0 without a context)."""
    ctx = click.get_current_context(silent=True)
    obj = ctx.find_root().obj if ctx else None
    return obj.get("verbosity", 0) if isinstance(obj, dict) else 0


def say(message: str, *, level: int = 0) -> None:
    """Print a human summary line on stderr when verbosity >= ``level`` (``-q`` hides level 0)."""
    if verbosity() >= level:
        click.echo(message, err=True)


def progress_wanted() -> Progress:
    """Where a command reports progress: bars on stderr when it is a terminal and ``-q`` is not
    given, else silence (:func:`tilesolve.progress.terminal`; false when silent)."""
    return terminal(quiet=verbosity() < 0)


_SPLIT = re.compile(r"[,\s]+(?![^{]*\})")


def split_conditions(items: Iterable[str]) -> list[str]:
    """Split ``--cond`` values on commas/spaces outside braces: ``"H0=2,V{0,1}=3"`` -> two."""
    return [part for item in items for part in _SPLIT.split(item.strip()) if part]


def build_problem(
    *,
    size: str | None,
    conditions: Iterable[str],
    n_tiles: int | None,
    cyclic: bool,
    fix: str | None,
    problem_file: str | None,
    counts: Iterable[str] = (),
    closest_to: str | None = None,
):
    """The :class:`~tilesolve.model.DappledProblem` described by the problem options.

    The size is checked first (absurd sizes are refused before anything is allocated),
    then the conditions and counts, then the files.
    """
    from tilesolve.cli.options import MAX_INT
    from tilesolve.io.dappled_json import read_problem, read_tiling
    from tilesolve.model.dappled import DappledProblem, parse_condition, parse_count, parse_size

    conditions, counts = list(conditions), list(counts)
    if problem_file:
        given = [name for name, v in (("--size", size), ("--cond", conditions), ("--tiles", n_tiles),
                                      ("--cyclic", cyclic), ("--fix", fix), ("--count", counts),
                                      ("--closest-to", closest_to)) if v]
        if given:
            raise InvalidProblem(f"--problem gives the whole problem; drop {', '.join(given)}")
        return read_problem(problem_file)
    if not size:
        raise InvalidProblem("--size is required, e.g. --size 12x8 (12 columns, 8 rows), or give --problem FILE")
    rows, cols = parse_size(size)
    conds = tuple(parse_condition(c) for c in split_conditions(conditions))
    tile_counts = tuple(parse_count(k) for k in counts)
    for what, c, numbers in [("condition", c, (*c.tiles, c.limit or 0)) for c in conds] + \
                            [("count", k, (k.tile, k.low, k.high or 0)) for k in tile_counts]:
        if max(numbers) > MAX_INT:
            hint = "; a limit of inf means no limit" if what == "condition" else ""
            raise InvalidProblem(f"{what} {c}: {big(max(numbers))} is absurdly large (at most {MAX_INT:,}{hint})")
    fixed = read_tiling(fix, allow_free=True, what="partial tiling") if fix else None
    target = read_tiling(closest_to, what="target tiling") if closest_to else None
    try:
        return DappledProblem(
            rows,
            cols,
            n_tiles=2 if n_tiles is None else n_tiles,
            conditions=conds,
            cyclic=cyclic,
            fixed=fixed,
            counts=tile_counts,
            closest_to=target,
        )
    except InvalidProblem as exc:
        src = [f for f, a in ((fix, "partial tiling"), (closest_to, "target tiling")) if f and a in str(exc)]
        raise InvalidProblem(f"{src[0]}: {exc}" if src else str(exc)) from None


def check_writable(path: str | None) -> None:
    """Refuse an output that cannot be written, before any work (see :class:`~tilesolve.cli.outputs.Outputs`)."""
    from tilesolve.cli.outputs import Outputs

    Outputs(path)


def check_colors(kind: str, colors: int, colors_v: int | None = None) -> None:
    """Refuse colour counts below 2, or so large that the complete tile set cannot be built
    (it has C^2 x C_v^2 tiles), saying what it would need."""
    for name, c in (("--colors", colors), ("--colors-v", colors_v)):
        if c is not None and c < 2:
            raise InvalidProblem(f"{name} must be at least 2, got {c}")
    cv = colors if colors_v is None else colors_v
    n = colors**2 * cv**2
    if n > MAX_COMPLETE_TILES:
        raise InvalidProblem(
            f"{big(colors)} colours: the complete {kind} tile set has {big(n)} tiles ({human_bytes(8 * n)} as int64 "
            f"indices, before any search); tilesolve builds up to {MAX_COMPLETE_TILES:,} tiles (C = 64)"
        )


def sweep_trials(ctx: click.Context, trials: int, run_trial, agreed: str) -> None:
    """The cross-check commands' loop: ``run_trial(i)`` gives ``(label, report)`` for trial
    ``i``; each is printed with its lines as it comes, then ``agreed`` or the failure, and the
    command exits 0 when every trial agrees, else 1. A trial during which Ctrl-C or SIGTERM
    arrived ends the sweep as the interruption, whatever a route made of the signal (an
    ``unknown``, a failed check): it is never reported as a result."""
    from tilesolve.cli.outputs import stop_if_interrupted

    ok = True
    for i in range(trials):
        label, rep = run_trial(i)
        stop_if_interrupted()
        ok &= bool(rep.ok)
        click.echo(f"trial {i + 1}/{trials} ({label}): {'ok' if rep.ok else 'FAILED'}")
        for line in rep.lines:
            click.echo(f"  {line}")
    click.echo(agreed if ok else "crosscheck: FAILED (see the FAIL lines above)")
    ctx.exit(0 if ok else 1)
