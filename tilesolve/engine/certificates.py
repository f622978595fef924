"""Turning a solver's "unsatisfiable" into an answer tilesolve can stand behind.

SAT says unsat only with a checked proof (DESIGN.md): the DRAT proof the solver logged is
checked by :mod:`tilesolve.verify.drat`, which shares no code with the solver. Only a proof
that passes the check gives ``unsat``; every other case is ``unknown`` with a reason that
says why the proof was not checked (none logged, checking turned off, over the size guard,
out of time) or that it failed. The check counts against the run's time limit. Every family
(dappled, Wang boards, packings) uses this.
"""

from __future__ import annotations

import time

from tilesolve.deadline import Deadline
from tilesolve.engine.result import Result
from tilesolve.model.solution import Solution, Status
from tilesolve.verify.drat import check_drat

__all__ = ["unsat_solution", "PROOF_CHECK_MAX_SIZE"]

#: Literals (formula + proof) above which a DRAT proof is not checked in Python (the answer
#: is then ``unknown``): the pure-Python checker handles about a million literals a second.
PROOF_CHECK_MAX_SIZE = 5_000_000


def unsat_solution(formula, r: Result, *, method: str, seed, t0: float, stats: dict,
                   check_proof: bool = True, proof_time_limit: float | None = None,
                   deadline: Deadline | None = None) -> Solution:
    """``UNSAT`` when the solver's DRAT proof passes the check, else ``UNKNOWN``.

    Parameters
    ----------
    formula
        Exactly the clauses the solver was given (any family).
    r : Result
        The solver's ``UNSAT`` result (``r.proof`` the logged proof, or ``None``).
    method, seed, t0, stats
        Provenance for the Solution (``t0``: ``time.perf_counter()`` when the route began).
    check_proof : bool
        ``False`` skips the check, and the answer is then ``unknown`` ("not checked").
    proof_time_limit : float, optional
        Seconds for the check when no ``deadline`` is given.
    deadline : Deadline, optional
        The run's deadline: the check stops when it passes (answer ``unknown``).

    Examples
    --------
    >>> from tilesolve.engine.sat import solve_cnf
    >>> f = [[1, 2], [-1, 2], [1, -2], [-1, -2]]
    >>> r = solve_cnf(f, with_proof=True)
    >>> unsat_solution(f, r, method="sat", seed=0, t0=0.0, stats={}).status.value
    'unsat'
    >>> s = unsat_solution(f, r, method="sat", seed=0, t0=0.0, stats={}, check_proof=False)
    >>> s.status.value, s.reason
    ('unknown', 'cadical153 reported unsatisfiable; its DRAT proof of 3 lines was not checked (checking turned off)')
    """
    stats = dict(stats)
    solver = r.solver

    def unknown(why: str) -> Solution:
        return Solution(Status.UNKNOWN, None, method, solver, seed, time.perf_counter() - t0, reason=why,
                        stats=stats)

    if r.proof is None:
        why = f"{solver} reported unsatisfiable but logged no proof, so the answer was not checked"
        return unknown(why + (f" ({r.reason})" if r.reason else ""))
    stats["proof_lines"] = len(r.proof)
    if not check_proof:
        return unknown(f"{solver} reported unsatisfiable; its DRAT proof of {len(r.proof)} lines was not checked "
                       "(checking turned off)")
    if deadline is not None:
        if deadline.expired():
            return unknown(f"{solver} reported unsatisfiable; its DRAT proof was not checked: time limit of "
                           f"{deadline.time_limit:.3g} s reached before the check")
        proof_time_limit = deadline.remaining()
    chk = check_drat(formula, r.proof, max_size=PROOF_CHECK_MAX_SIZE, time_limit=proof_time_limit)
    stats.update(proof_status=chk.status, proof_lemmas=chk.lemmas, proof_check_s=round(chk.time_s, 6))
    if chk.status == "verified":
        reason = f"proved unsatisfiable by {solver}; DRAT proof of {chk.lemmas} lemma(s) checked by tilesolve.verify.drat"
        return Solution(Status.UNSAT, None, method, solver, seed, time.perf_counter() - t0, reason=reason, stats=stats)
    if chk.status == "failed":
        return unknown(f"{solver} reported unsatisfiable but its DRAT proof failed the check: {chk.reason}")
    # "skipped" (size guard) or "unknown" (out of time): the proof was not checked.
    return unknown(f"{solver} reported unsatisfiable; its DRAT proof was not checked: {chk.reason}")
