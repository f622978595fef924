"""``tilesolve verify FILE``: check every claim a solution file makes.

The work is :func:`tilesolve.family.verify_file` (usable from Python): the file's format
names its family in the registry, the family's codec reads it, and the family's independent
verifier checks the tiling; status and objective claims are checked too.
"""

from __future__ import annotations

import click

from tilesolve.cli import options as opt

__all__ = ["verify"]


@click.command(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP)
@click.argument("file", type=click.Path(dir_okay=False))
@click.pass_context
def verify(ctx, file: str) -> None:
    """Check that the solution in FILE satisfies its own problem and claims.

    Re-checks exactly what the file holds (its problem fields and its tiling) with the
    family's independent verifier and lists every violation with its position. The file's
    status must match its content (sat/optimal need a valid tiling, unsat/unknown hold
    none) and a recorded objective must equal the tiling's.

    \b
    Example:
      tilesolve dappled solve --size 12x8 --cond H0=2,V1=2 -o t.json
      tilesolve verify t.json

    Exit 0 when the tiling is valid and every claim holds, 1 when a claim is false; a file
    that records unsat (1) or unknown (3) and holds no tiling exits with its status's code.
    """
    from tilesolve.family import verify_file

    report = verify_file(file)
    for line in report.lines:
        click.echo(line)
    ctx.exit(report.exit_code)
