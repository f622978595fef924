"""Independent checker of aperiodicity reports (class notes Part II §8.2).

Every witness in a report is re-checked as a board tiling with
:func:`tilesolve.verify.board.board_violations` (Def. 2: tiles of the set, joined legs of
equal colour) on the square or (sheared) torus its name stands for; every refutation must
carry the digests of its CNF and of its checked proof (SAT) or its route's evidence; every
period certificate must name a distinct board, and a refuted or undecided one a lattice of the
check (a witness may tile any torus: it is periodic all the same); a sweep's report without a
witness holds every lattice of the check once, in order (its conclusion counts them all); the largest square claimed must
have its witness, and the refuted square above it when it is below the bound. (That each
refutation's CNF encodes its board, and its proof, are re-checked by ``tilesolve verify``,
which re-derives the CNF: :attr:`tilesolve.family.Family.refutations`.) Numpy only; nothing here calls a solver or the code that wrote the report.
"""

from __future__ import annotations

import numpy as np

from tilesolve.model.aperiodic import (
    MAX_CLAUSES,
    AperiodicProblem,
    AperiodicReport,
    board_of,
    clauses_per_cell,
    leg_colours,
    parse_board_name,
)
from tilesolve.model.board import BoardProblem
from tilesolve.verify.board import board_violations
from tilesolve.verify.dappled import Violation

__all__ = ["aperiodic_violations", "witness_violations"]


def witness_violations(problem: AperiodicProblem, cert) -> list[Violation]:
    """Every violation of one witness certificate (``status == "tiles"``) as a tiling of its board."""
    rows, cols, _ = parse_board_name(cert.board)
    t = np.asarray(cert.tiling)
    if t.shape != (rows, cols):
        return [Violation("shape", f"{cert.board}: witness has shape {t.shape}, expected ({rows}, {cols})")]
    if t.size and (not np.issubdtype(t.dtype, np.integer) or t.min() < 0 or t.max() >= len(problem.tileset)):
        return [Violation("tile", f"{cert.board}: tile indices outside 0..{len(problem.tileset) - 1}")]
    board = board_of(cert.board)
    bad = board_violations(BoardProblem(board, problem.tileset), leg_colours(problem.tileset, t))
    return [Violation(v.kind, f"{cert.board}: {v.message}", v.row, v.col) for v in bad]


def aperiodic_violations(problem: AperiodicProblem, report) -> list[Violation]:
    """Every false claim in ``report`` (an :class:`AperiodicReport`) about ``problem``."""
    if not isinstance(report, AperiodicReport):
        return [Violation("shape", f"expected an aperiodicity report, got {type(report).__name__}")]
    out: list[Violation] = []
    names = [lat.name() for lat in problem.lattices()]
    lattices = set(names)
    seen: set[str] = set()
    for cert in report.periods:
        if cert.board not in lattices and cert.status != "tiles":  # a witness of any torus is periodic
            out.append(Violation("board", f"{cert.board}: not a lattice of this check (sides 1..{problem.max_period}"
                                          f"{', shears 0..rows-1' if problem.shears else ', no shear'})"))
        elif cert.board in seen:
            out.append(Violation("board", f"{cert.board}: certified twice"))
        seen.add(cert.board)
    transducer = any("transducer" in str(c.method) for c in report.squares + report.periods)
    if transducer and any(c.status != "tiles" for c in report.periods):
        out.append(Violation("board", "a transducer's report holds no period but its torus witness"))
    witness = any(c.status == "tiles" for c in report.periods)
    if not transducer and not witness and report.periods and [c.board for c in report.periods] != names:
        out.append(Violation("board", "the periods are not every lattice of this check, each once, in order "
                                      f"({len(report.periods)} certificates for {len(lattices)} lattices)"))
    squares_seen: set[str] = set()
    for cert in report.squares:
        if parse_board_name(cert.board)[2] != -1:
            out.append(Violation("board", f"{cert.board}: not a square or rectangle"))
        elif cert.board in squares_seen:  # one certificate a board: a second could contradict the first
            out.append(Violation("board", f"{cert.board}: certified twice"))
        squares_seen.add(cert.board)
    per = clauses_per_cell(len(problem.tileset))
    for cert in report.squares + report.periods:
        rows, cols, _ = parse_board_name(cert.board)
        if rows < 1 or cols < 1 or rows * cols * per > MAX_CLAUSES:
            out.append(Violation("board", f"{cert.board}: no board of this size is checked (at most {MAX_CLAUSES:,} "
                                          "clauses)"))
    if out:
        return out
    for cert in report.squares + report.periods:
        if cert.status == "tiles":
            out += witness_violations(problem, cert)
        elif cert.status == "refuted":
            ev = cert.evidence
            sat = str(cert.method).startswith("sat")
            if sat and not (ev.get("cnf_sha256") and ev.get("drat_sha256")):
                out.append(Violation("proof", f"{cert.board}: refuted by SAT without the digests of a checked proof"))
            if not sat and not ev:
                out.append(Violation("proof", f"{cert.board}: refuted by {cert.method!r} without evidence"))
            if "guided" in str(cert.method):
                out.append(Violation("proof", f"{cert.board}: a guided (restricted) search refutes nothing"))
    n = report.largest_square
    if n is not None:
        squares = {parse_board_name(c.board)[:2]: c.status for c in report.squares}
        if n > 0 and squares.get((n, n)) != "tiles":
            out.append(Violation("square", f"largest square {n}x{n} claimed without its witness"))
        if n < problem.max_square and squares.get((n + 1, n + 1)) != "refuted":
            out.append(Violation("square", f"largest square {n}x{n} claimed, but the {n + 1}x{n + 1} square "
                                           "is not refuted in the report"))
    return out
