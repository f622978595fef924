"""``tilesolve export dimacs``: write a problem's SAT/MaxSAT encoding for external solvers."""

from __future__ import annotations

import click

from tilesolve.cli import options as opt
from tilesolve.cli.common import build_problem, check_writable, say
from tilesolve.errors import InvalidProblem

__all__ = ["export", "dimacs"]


@click.group(context_settings=opt.CONTEXT_SETTINGS)
def export() -> None:
    """Export problems to other tools' formats."""


@export.command(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.CONDITION_HELP + "\n\n" + opt.EXIT_HELP)
@opt.problem_options()
@click.option(
    "-o", "--output", required=True, type=click.Path(dir_okay=False), metavar="OUT.cnf|OUT.wcnf",
    help="Output file; .wcnf (weighted MaxSAT) for --closest-to, else .cnf.",
)
def dimacs(output: str, **problem_kw) -> None:
    """Write the CNF (or, with --closest-to, WCNF) encoding of a dappled problem.

    The header comments describe the problem and the variable numbering: with two tiles,
    variable 1 + r*W + c is true when cell (row r, col c) holds tile 1.

    \b
    Example:
      tilesolve export dimacs --size 12x8 --cond H0=2,V1=2 -o t.cnf
      tilesolve export dimacs --size 12x8 --cond H0=2,V1=2 --closest-to target.txt -o t.wcnf
    """
    problem = build_problem(**problem_kw)
    check_writable(output)
    weighted = output.lower().endswith(".wcnf")
    if problem.closest_to is not None and not weighted:
        raise InvalidProblem("a closest-tiling problem has soft clauses: write a .wcnf file (-o OUT.wcnf)")
    if weighted and problem.closest_to is None:
        raise InvalidProblem("a .wcnf file needs soft clauses: add --closest-to FILE, or write a .cnf file")
    from tilesolve.encodings import encode_cnf, encode_wcnf
    from tilesolve.io.dimacs import write_dimacs

    enc = encode_wcnf(problem) if weighted else encode_cnf(problem)
    write_dimacs(enc, output)
    soft = f", {len(enc.soft)} soft" if enc.soft is not None else ""
    say(f"wrote {output}: {problem.describe()}; {enc.n_vars} variables, {len(enc.hard)} hard clauses{soft}")
