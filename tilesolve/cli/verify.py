"""``tilesolve verify FILE``: check every claim a solution file makes.

The work is :func:`tilesolve.family.verify_file` (usable from Python): the file's format
names its family in the registry, the family's codec reads it, and the family's independent
verifier checks the tiling (or the report: an aperiodicity check's certificates and verdict);
status and objective claims are checked too.
"""

from __future__ import annotations

import click

from tilesolve.cli import options as opt
from tilesolve.cli.common import progress_wanted

__all__ = ["verify"]


@click.command(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.READER_HELP)
@click.argument("file", type=click.Path(dir_okay=False))
@click.option("--proof-dir", type=click.Path(file_okay=False, exists=True), metavar="DIR", default=None,
              help="Re-check every unsat answer's (every refuted board's) DRAT proof against the CNF re-derived "
              "from the file's problem: DIR holds the .drat files the solving command's --proof-dir wrote.")
@opt.max_cnf_option("Re-derive no CNF estimated (before encoding) above SIZE of DIMACS text (e.g. 512M, 8G): "
                     "such an unsat claim is reported as not confirmed.")
@click.pass_context
def verify(ctx, file: str, proof_dir: str | None, max_cnf: int) -> None:
    """Check that the solution in FILE satisfies its own problem and claims.

    Re-checks exactly what the file holds (its problem fields and its tiling) with the
    family's independent verifier and lists every violation with its position. The file's
    status must match its content (sat/optimal need a valid tiling, unsat/unknown hold
    none) and a recorded objective must equal the tiling's. A report (an aperiodicity check) is
    not a tiling: its certificates are checked, and "ok: FILE is a valid aperiodicity report
    (...): verdict V" names its verdict (periodic, finite, open or undecided), which, like its
    status, must be what its certificates give.

    An unsat answer (or a refuted board of an aperiodicity report) is bound to the problem the
    file states: its CNF is re-derived with the named encoding the file records (name, version,
    options) and its SHA-256 must be the recorded one, else "the CNF is not the encoding of this
    problem" (exit 1). A file made with another version of the encoding is refused with "re-solve
    to re-certify". With --proof-dir, each DRAT proof (found in DIR by the recorded digests; its
    SHA-256 must match) is checked against the re-derived CNF, never against a file alone; a .cnf
    file beside it must be that CNF byte for byte (the files suit drat-trim or any DRAT checker).

    \b
    Example:
      tilesolve dappled solve --size 12x8 --cond H0=2,V1=2 -o t.json
      tilesolve verify t.json
      tilesolve dappled solve --size 3x3 --cond H0=1 --count 1=0 -o u.json --proof-dir proofs  # unsat
      tilesolve verify u.json --proof-dir proofs

    Exit 0 when the tiling is valid and every claim holds (an unsat file: when its proof
    re-checks with --proof-dir), 1 when a claim is false; a file that records unsat (1) or
    unknown (3) and holds no tiling exits with its status's code. Without --proof-dir an unsat
    claim is NOT re-checked, and the output says so (exit 1). A CNF estimated above --max-cnf is
    not re-derived: its claim is NOT confirmed, and the line gives the estimate (exit 1).
    """
    from tilesolve.family import verify_file

    report = verify_file(file, proof_dir, max_cnf=max_cnf, progress=progress_wanted())
    for line in report.lines:
        click.echo(line)
    ctx.exit(report.exit_code)
