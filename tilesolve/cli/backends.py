"""``tilesolve backends``: which solver backends are installed (CPMpy ``SolverLookup`` style),
and every family's routes (read from the registry, :mod:`tilesolve.family`)."""

from __future__ import annotations

import click

from tilesolve.cli import options as opt

__all__ = ["backends"]


@click.command(context_settings=opt.CONTEXT_SETTINGS)
@click.pass_context
def backends(ctx) -> None:
    """List the solver backends (and whether each is installed) and every family's routes.

    \b
    Example:
      tilesolve backends

    Exit 0 when every required backend works (at least one SAT solver), 1 otherwise.
    """
    from tilesolve.family import backend_report

    backends_rows, route_rows, missing_required = backend_report()
    _table(("backend", "kind", "installed", "version / reason", "used by"), backends_rows)
    click.echo("")
    _table(("family", "route", "what it does"), route_rows)
    ctx.exit(1 if missing_required else 0)


def _table(header: tuple[str, ...], rows: list[tuple[str, ...]]) -> None:
    widths = [max(len(r[i]) for r in rows + [header]) for i in range(len(header))]
    for r in [header] + rows:
        click.echo("  ".join(c.ljust(w) for c, w in zip(r, widths)).rstrip())
