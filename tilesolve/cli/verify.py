"""``tilesolve verify FILE``: re-check a solution file with the independent verifier.

Dispatches on the file's ``"format"`` through :data:`CHECKERS`; a new family adds its
format and a checker ``(document, source) -> (exit_code, lines)``.
"""

from __future__ import annotations

from typing import Callable

import click

from tilesolve.cli import options as opt
from tilesolve.errors import InvalidProblem

__all__ = ["verify", "CHECKERS", "check_dappled_solution", "check_board_solution"]

#: Lines of violations printed before "... and N more".
MAX_SHOWN = 50


def no_tiling_report(source: str, sol, what: str = "tiling") -> tuple[int, list[str]]:
    """The answer for a file whose status recorded no tiling: its status's exit code."""
    why = f" ({sol.reason})" if sol.reason else ""
    return sol.status.exit_code, [f"{source}: status {sol.status.value}{why}; the file holds no {what} to verify"]


def violations_report(source: str, violations, of: str) -> tuple[int, list[str]]:
    """Exit code 1 and the first :data:`MAX_SHOWN` violations, one per line."""
    n = len(violations)
    lines = [f"{source}: {n} violation{'s' if n != 1 else ''} of {of}"]
    lines += [f"  {v}" for v in violations[:MAX_SHOWN]]
    if n > MAX_SHOWN:
        lines.append(f"  ... and {n - MAX_SHOWN} more")
    return 1, lines


def check_dappled_solution(doc: dict, source: str) -> tuple[int, list[str]]:
    """Check a ``tilesolve/dappled-solution`` document exactly as written.

    The problem fields and ``"tiling"`` go to :func:`tilesolve.verify.dappled_violations`;
    for a closest-tiling problem the recorded ``objective`` must equal the Hamming distance.
    """
    from tilesolve.io.jsonio import solution_from_dict
    from tilesolve.verify.dappled import Violation, dappled_violations, hamming_distance

    problem, sol = solution_from_dict(doc, source)
    if sol.tiling is None:
        return no_tiling_report(source, sol)
    violations = list(dappled_violations(sol.tiling, problem))
    if (
        not violations
        and problem.closest_to is not None
        and sol.objective is not None
        and sol.objective != hamming_distance(sol.tiling, problem.closest_to)
    ):
        dist = hamming_distance(sol.tiling, problem.closest_to)
        violations.append(Violation("objective", f"recorded distance {sol.objective}, but the tiling is at distance {dist}"))
    if violations:
        return violations_report(source, violations, problem.describe())
    lines = [f"ok: {source} is a valid tiling of {problem.describe()}"]
    if not sol.status.has_tiling:
        lines.append(f"  note: the file records status {sol.status.value!r}, yet its tiling is valid")
    return 0, lines


def check_board_solution(doc: dict, source: str) -> tuple[int, list[str]]:
    """Check a ``tilesolve/board-solution`` document (board, boundary, tiles as written)."""
    from tilesolve.io.board_json import board_solution_from_dict
    from tilesolve.verify.board import board_violations

    problem, sol = board_solution_from_dict(doc, source)
    if sol.tiling is None:
        return no_tiling_report(source, sol)
    violations = board_violations(sol.tiling, problem)
    if violations:
        return violations_report(source, violations, problem.describe())
    return 0, [f"ok: {source} is a valid tiling of {problem.describe()}"]


#: Checkers by file format.
CHECKERS: dict[str, Callable[[dict, str], tuple[int, list[str]]]] = {
    "tilesolve/dappled-solution": check_dappled_solution,
    "tilesolve/board-solution": check_board_solution,
}


def _check_packing(doc: dict, source: str) -> tuple[int, list[str]]:
    from tilesolve.cli.pack import check_packing_file  # tile packings (issue 4)

    return check_packing_file(doc, source)


CHECKERS["tilesolve/packing"] = _check_packing


@click.command(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP)
@click.argument("file", type=click.Path(dir_okay=False))
@click.pass_context
def verify(ctx, file: str) -> None:
    """Check that the solution in FILE satisfies its own problem.

    Re-checks exactly what the file holds (its problem fields and its "tiling") with
    the independent verifier, and lists every violation with its position.

    \b
    Example:
      tilesolve dappled solve --size 12x8 --cond H0=2,V1=2 -o t.json
      tilesolve verify t.json

    Exit 0 when the tiling is valid, 1 with the list of violations otherwise.
    """
    from tilesolve.io.jsonio import load_document

    doc = load_document(file)
    checker = CHECKERS.get(doc["format"])
    if checker is None:
        raise InvalidProblem(f"{file}: a {doc['format']} file holds no solution to verify; solve it first")
    code, lines = checker(doc, file)
    for line in lines:
        click.echo(line)
    ctx.exit(code)
