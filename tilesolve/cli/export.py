"""``tilesolve export dimacs``: write any family's SAT/MaxSAT encoding for external solvers.

The problem comes from a problem or solution file of any family (through the registry's
codecs and each family's ``encode``), or from the dappled problem options.
"""

from __future__ import annotations

import click

from tilesolve.cli import options as opt
from tilesolve.cli.common import build_problem, check_writable, say
from tilesolve.cli.outputs import OutputFile
from tilesolve.errors import InvalidProblem

__all__ = ["export", "dimacs"]


@click.group(context_settings=opt.CONTEXT_SETTINGS)
def export() -> None:
    """Export problems to other tools' formats."""


@export.command(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.CONDITION_HELP + "\n\n" + opt.READER_HELP)
@click.argument("file", required=False, type=click.Path(dir_okay=False))
@opt.problem_options()
@click.option(
    "-o", "--output", required=True, type=OutputFile("cnf", "wcnf", allow_dash=False), metavar="OUT.cnf|OUT.wcnf",
    help="Output file; .wcnf (weighted MaxSAT) for closest-tiling problems, else .cnf.",
)
@opt.max_cnf_option("Refuse a problem whose CNF is estimated (before encoding) to exceed SIZE of DIMACS "
                     "text (e.g. 512M, 8G).")
def dimacs(file: str | None, output: str, max_cnf: int, **problem_kw) -> None:
    """Write the CNF (or WCNF) encoding of a problem.

    FILE is a problem or solution file of any family (dappled, board, packing); without it
    the dappled problem options describe the problem. The CNF's size is estimated before
    anything is encoded, and a problem above --max-cnf (1 GiB of text by default) is refused
    with the estimate. The header comments describe the problem and the variable numbering (for dappled tilings with two tiles, variable
    1 + r*W + c is true when cell (row r, col c) holds tile 1).

    \b
    Example:
      tilesolve export dimacs --size 12x8 --cond H0=2,V1=2 -o t.cnf
      tilesolve dappled solve --size 12x8 --cond H0=2,V1=3 -o target.json
      tilesolve export dimacs --size 12x8 --cond H0=2,V1=2 --closest-to target.json -o t.wcnf
      tilesolve pack --kind corner --colors 4 -o c4.json
      tilesolve export dimacs c4.json -o c4.cnf          # a packing (or board) file
    """
    from tilesolve.family import family_of, read_document

    if file is not None:
        given = [k for k, v in problem_kw.items() if v not in (None, (), False)]
        if given:
            raise InvalidProblem(f"FILE gives the whole problem; drop --{given[0].replace('_', '-')}")
        fam, codec, doc = read_document(file)
        problem, _ = codec.read(doc, file)
    else:
        problem = build_problem(**problem_kw)
        fam = family_of(problem)
    check_writable(output)
    if fam.encode is None:
        raise InvalidProblem(f"{fam.name} problems have no SAT encoding to export")
    _check_size(problem, max_cnf)
    enc = fam.encode(problem)
    weighted = output.lower().endswith(".wcnf")
    has_soft = getattr(enc, "soft", None) is not None
    if has_soft and not weighted:
        raise InvalidProblem("a closest-tiling problem has soft clauses: write a .wcnf file (-o OUT.wcnf)")
    if weighted and not has_soft:
        raise InvalidProblem("a .wcnf file needs soft clauses (a closest-tiling problem); write a .cnf file")
    from tilesolve.io.dimacs import write_dimacs

    write_dimacs(enc, output)
    soft = f", {len(enc.soft)} soft" if has_soft else ""
    say(f"wrote {output}: {problem.describe()}; {enc.n_vars} variables, {len(enc.hard)} hard clauses{soft}")


def _check_size(problem, max_cnf: int) -> None:
    """Refuse, before encoding, a CNF estimated larger than ``max_cnf`` bytes of DIMACS text."""
    from tilesolve.family import cnf_size_refusal

    why = cnf_size_refusal(problem, max_cnf)
    if why is not None:
        raise InvalidProblem(f"{why}; raise --max-cnf, or export a smaller problem")
