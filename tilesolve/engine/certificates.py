"""Turning a solver's "unsatisfiable" into an answer tilesolve can stand behind.

SAT says unsat only with a checked proof (DESIGN.md): the DRAT proof the solver logged is
checked by :mod:`tilesolve.verify.drat`, which shares no code with the solver and has no size
cut-off. Only a proof that passes the check gives ``unsat``; every other case is ``unknown``
with a reason that says why (no proof logged, checking turned off, the check failed, the
run's deadline passed before the check ended). The check counts against the run's time limit.
Every family (dappled, Wang boards, packings) uses this.

Each checked proof is bound to the SHA-256 of the exact CNF it refutes, written in DIMACS by
:func:`tilesolve.verify.drat.dimacs_bytes`; the Solution's stats record ``cnf_sha256``,
``drat_sha256`` (of the proof text, one step a line) and the checker's figures. Inside
:func:`writing_proofs` (the CLI's ``--proof-dir``) the CNF and the proof are also written as
``<name>.cnf`` and ``<name>.drat`` (``name``: ``unsat-``, 16 hex digits of the CNF digest, ``-``,
8 of the proof's; stats ``proof_name``) for anyone to re-check with their own tools; ``tilesolve verify --proof-dir`` re-checks
them.

When unit propagation alone refutes the formula (no lemma needed), the reason says which
constraints clash: the labels of the encoding's clause blocks (e.g. ``"H0=2 windows"``) that
the refutation uses.
"""

from __future__ import annotations

import contextlib
import contextvars
import hashlib
import os
import time
from collections import Counter
from typing import Iterator

from tilesolve.deadline import Deadline
from tilesolve.engine.result import Result
from tilesolve.model.solution import Solution, Status
from tilesolve.verify.drat import check_drat, dimacs_bytes, formula_arrays

__all__ = ["unsat_solution", "writing_proofs", "proof_text", "UNCERTIFIED"]

#: How an infeasibility claimed without a checked proof (CP-SAT's, a constructive route's)
#: begins its reason: the answer is ``unknown``, after :func:`tilesolve.family.run_route`
#: tried to certify it with the family's ``sat`` route.
UNCERTIFIED = "uncertified:"

_PROOF_DIR: contextvars.ContextVar[str | None] = contextvars.ContextVar("tilesolve_proof_dir", default=None)


@contextlib.contextmanager
def writing_proofs(directory: str | os.PathLike | None) -> Iterator[None]:
    """Within the block, every checked unsat proof is also written to ``directory``.

    ``None`` writes nothing. The directory is created when the first proof is written.
    Routes run in other processes (the portfolio's workers) do not write here; their
    Solutions still record the digests.
    """
    if directory is None:
        yield
        return
    token = _PROOF_DIR.set(os.fspath(directory))
    try:
        yield
    finally:
        _PROOF_DIR.reset(token)


def proof_text(proof) -> bytes:
    """The proof as the bytes ``drat_sha256`` hashes: one step a line, ``\\n`` ends."""
    if isinstance(proof, (bytes, bytearray)):
        return bytes(proof)
    if isinstance(proof, str):
        return proof.encode("ascii")
    return ("\n".join(proof) + "\n").encode("ascii") if len(proof) else b""


def _write_atomic(path: str, data: bytes) -> None:
    tmp = f"{path}.tmp{os.getpid()}"
    with open(tmp, "wb") as fh:
        fh.write(data)
    os.replace(tmp, path)


def _clash(formula, core) -> str:
    """Which labelled constraints a propagation-only refutation uses, in words."""
    _, _, blocks = formula_arrays(formula) if hasattr(formula, "blocks") else (None, None, [])
    named = [(label, lo, n) for label, lo, n in blocks if label]
    if not named or core is None:
        return ""
    counts: Counter[str] = Counter()
    for label, lo, n in named:
        k = int(((core >= lo) & (core < lo + n)).sum())
        if k:
            counts[label] += k
    parts = [f"{k} {label!r}" for label, k in counts.most_common(8)]
    more = len(counts) - len(parts)
    return "; the clash is between " + ", ".join(parts) + (f" and {more} more kinds" if more > 0 else "") + \
        " clause(s)"


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
    >>> s = unsat_solution(f, r, method="sat", seed=0, t0=0.0, stats={})
    >>> s.status.value, s.stats["cnf_sha256"][:12], s.stats["proof_checked_lemmas"]
    ('unsat', 'd9231948f391', 1)
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
    proof = list(r.proof) if not isinstance(r.proof, (str, bytes, bytearray)) else r.proof
    if isinstance(proof, list) and (not proof or proof[-1].strip() != "0"):
        # The solver's unsat claim is the empty clause; some solvers (MapleCM) leave it out of
        # the proof. It is appended here and checked like any lemma (it must be RUP).
        proof.append("0")
        stats["proof_empty_clause_appended"] = True
    stats["proof_lines"] = len(r.proof)
    if not check_proof:
        return unknown(f"{solver} reported unsatisfiable; its DRAT proof of {len(r.proof)} lines was not checked "
                       "(checking turned off)")
    if deadline is not None:
        if deadline.expired():
            return unknown(f"{solver} reported unsatisfiable; its DRAT proof was not checked: time limit of "
                           f"{deadline.time_limit:.3g} s reached before the check")
        proof_time_limit = deadline.remaining()
    chk = check_drat(formula, proof, time_limit=proof_time_limit)
    stats.update(proof_status=chk.status, proof_lemmas=chk.lemmas, proof_checked_lemmas=chk.checked,
                 proof_check_s=round(chk.time_s, 6))
    if chk.status == "failed":
        return unknown(f"{solver} reported unsatisfiable but its DRAT proof failed the check: {chk.reason}")
    if chk.status != "verified":
        return unknown(f"{solver} reported unsatisfiable; its DRAT proof was not checked: {chk.reason}")
    cnf = dimacs_bytes(formula)
    drat = proof_text(proof)
    stats["cnf_sha256"] = hashlib.sha256(cnf).hexdigest()
    stats["drat_sha256"] = hashlib.sha256(drat).hexdigest()
    stats["proof_core_clauses"] = int(chk.core.size) if chk.core is not None else None
    directory = _PROOF_DIR.get()
    if directory is not None:
        name = f"unsat-{stats['cnf_sha256'][:16]}-{stats['drat_sha256'][:8]}"
        os.makedirs(directory, exist_ok=True)
        _write_atomic(os.path.join(directory, name + ".cnf"), cnf)
        _write_atomic(os.path.join(directory, name + ".drat"), drat)
        stats["proof_name"] = name
    if chk.trivial:
        reason = (f"proved unsatisfiable by {solver}: unit propagation on the input clauses refutes it "
                  f"({chk.core.size if chk.core is not None else '?'} clauses take part{_clash(formula, chk.core)}); "
                  "DRAT proof checked by tilesolve.verify.drat")
    else:
        reason = (f"proved unsatisfiable by {solver}; DRAT proof of {chk.lemmas} lemma(s) ({chk.checked} of them "
                  "used) checked by tilesolve.verify.drat")
    return Solution(Status.UNSAT, None, method, solver, seed, time.perf_counter() - t0, reason=reason, stats=stats)
