"""Turning a solver's "unsatisfiable" into an answer tilesolve can stand behind.

SAT says unsat only with a proof (DESIGN.md): the DRAT proof the solver logged is checked by
:mod:`tilesolve.verify.drat`, which shares no code with the solver. A proof that fails the
check turns the answer into ``unknown``; one too large to check in Python stays ``unsat``
with a note saying it was not checked. Every family (dappled, Wang boards, packings) uses this.
"""

from __future__ import annotations

import time

from tilesolve.engine.result import Result
from tilesolve.model.solution import Solution, Status
from tilesolve.verify.drat import check_drat

__all__ = ["unsat_solution", "PROOF_CHECK_MAX_SIZE"]

#: Literals (formula + proof) above which a DRAT proof is kept but not checked in Python.
PROOF_CHECK_MAX_SIZE = 5_000_000


def unsat_solution(formula, r: Result, *, method: str, seed, t0: float, stats: dict,
                    check_proof: bool, proof_time_limit: float | None) -> Solution:
    """UNSAT with the proof's verdict; a proof that fails the check downgrades to UNKNOWN.

    ``formula`` must be exactly the clauses the solver was given (any family).
    """
    stats = dict(stats)
    solver = r.solver
    if r.proof is None:
        reason = f"reported unsatisfiable by {solver} (no proof logged)"
        if r.reason:
            reason += f": {r.reason}"
        return Solution(Status.UNSAT, None, method, solver, seed, time.perf_counter() - t0, reason=reason, stats=stats)
    stats["proof_lines"] = len(r.proof)
    if not check_proof:
        return Solution(Status.UNSAT, None, method, solver, seed, time.perf_counter() - t0,
                        reason=f"proved unsatisfiable by {solver}; DRAT proof of {len(r.proof)} lines kept, not checked",
                        stats=stats)
    chk = check_drat(formula, r.proof, max_size=PROOF_CHECK_MAX_SIZE, time_limit=proof_time_limit)
    stats.update(proof_status=chk.status, proof_lemmas=chk.lemmas, proof_check_s=round(chk.time_s, 6))
    if chk.status == "verified":
        reason = f"proved unsatisfiable by {solver}; DRAT proof of {chk.lemmas} lemma(s) checked by tilesolve.verify.drat"
        return Solution(Status.UNSAT, None, method, solver, seed, time.perf_counter() - t0, reason=reason, stats=stats)
    if chk.status == "failed":
        return Solution(Status.UNKNOWN, None, method, solver, seed, time.perf_counter() - t0,
                        reason=f"{solver} reported unsatisfiable but its DRAT proof failed the check: {chk.reason}",
                        stats=stats)
    return Solution(Status.UNSAT, None, method, solver, seed, time.perf_counter() - t0,
                    reason=f"proved unsatisfiable by {solver}; {chk.reason}", stats=stats,
                    notes=("the DRAT proof was not fully checked",))
