"""Turning a solver's "unsatisfiable" into an answer tilesolve can stand behind.

SAT says unsat only with a checked proof (DESIGN.md): the DRAT proof the solver logged is
checked by :mod:`tilesolve.verify.drat`, which shares no code with the solver and has no size
cut-off. Only a proof that passes the check gives ``unsat``; every other case is ``unknown``
with a reason that says why (no proof logged, checking turned off, the check failed, the
run's deadline passed before the check ended). The check counts against the run's time limit.
Every family (dappled, Wang boards, packings) uses this.

A certificate binds the problem, not only files (DESIGN.md, "Trust model"): problem -> named
encoding -> CNF digest -> checked proof. Each checked proof is bound to the SHA-256 of the exact
CNF it refutes, written in DIMACS by :func:`tilesolve.verify.drat.dimacs_bytes`, and that CNF
to the problem by the named encoding that built it (:mod:`tilesolve.encodings.registry`); the
Solution's stats record ``encoding`` (name, version, options), ``cnf_sha256``, ``drat_sha256``
(of the proof text, one step a line) and the checker's figures. Inside :func:`writing_proofs`
(the CLI's ``--proof-dir``) the CNF and the proof are also written as ``<name>.cnf`` and
``<name>.drat`` (:func:`proof_name`: ``unsat-``, 16 hex digits of the CNF digest, ``-``, 8 of
the proof's; stats ``proof_name``) for anyone to re-check with their own tools.
:func:`recheck_unsat` (``tilesolve verify``, a sweep's cache) re-derives the CNF from the
problem alone, compares its digest, and checks the proof against the re-derived formula.

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
from dataclasses import dataclass
from typing import Any, Iterator, Mapping

from tilesolve.deadline import NO_LIMIT, Deadline
from tilesolve.engine.result import Result
from tilesolve.model.solution import Solution, Status
from tilesolve.progress import SILENT, Progress

__all__ = ["unsat_solution", "writing_proofs", "proofs_wanted", "proof_text", "proof_name", "write_proof_files", "recheck_unsat",
           "recheck_all", "Recheck", "NOT_THE_ENCODING", "UNCERTIFIED"]

#: How an infeasibility claimed without a checked proof (CP-SAT's, a constructive route's)
#: begins its reason: the answer is ``unknown``, after :func:`tilesolve.family.run_route`
#: tried to certify it with the family's ``sat`` route.
UNCERTIFIED = "uncertified:"

_PROOF_DIRS: contextvars.ContextVar[tuple[tuple[str, bool], ...]] = contextvars.ContextVar("tilesolve_proof_dirs",
                                                                                           default=())


@contextlib.contextmanager
def writing_proofs(directory: str | os.PathLike | None, *, cnf: bool = True) -> Iterator[None]:
    """Within the block, every checked unsat proof is also written to ``directory``.

    ``None`` writes nothing. The directory is created when the first proof is written. Blocks
    nest: inside two of them a proof goes to both directories. ``cnf=False`` writes only the
    ``.drat`` file (a sweep's cache keeps its proofs so: the CNF is re-derived when they are
    re-checked). Routes run in other processes (the portfolio's workers) do not write here;
    their Solutions still record the digests.
    """
    if directory is None:
        yield
        return
    token = _PROOF_DIRS.set(_PROOF_DIRS.get() + ((os.fspath(directory), cnf),))
    try:
        yield
    finally:
        _PROOF_DIRS.reset(token)


def proofs_wanted() -> bool:
    """True inside :func:`writing_proofs` (a run asked for proof files)."""
    return bool(_PROOF_DIRS.get())


def proof_name(cnf_sha256: str, drat_sha256: str) -> str:
    """The file name (without suffix) of a proof: ``unsat-`` + 16 hex digits of the CNF's digest
    + ``-`` + 8 of the proof's. Verifiers locate proofs by it (never by a name a file states)."""
    return f"unsat-{cnf_sha256[:16]}-{drat_sha256[:8]}"


def write_proof_files(directory: str | os.PathLike, name: str, cnf: bytes | None, drat: bytes) -> None:
    """``<name>.cnf`` (unless ``cnf`` is ``None``) and ``<name>.drat`` in ``directory``, atomically."""
    directory = os.fspath(directory)
    os.makedirs(directory, exist_ok=True)
    if cnf is not None:
        _write_atomic(os.path.join(directory, name + ".cnf"), cnf)
    _write_atomic(os.path.join(directory, name + ".drat"), drat)


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
    from tilesolve.verify.drat import formula_arrays

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
                   check_proof: bool = True, deadline: Deadline = NO_LIMIT,
                   encoding: Mapping[str, Any] | None = None) -> Solution:
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
    deadline : Deadline, optional
        The run's deadline: the check stops when it passes (answer ``unknown``).
    encoding : Mapping, optional
        ``{"name", "version", "options"}`` of the named encoding
        (:mod:`tilesolve.encodings.registry`) that built ``formula`` from the problem; recorded
        as ``stats["encoding"]``, so that ``tilesolve verify`` can re-derive the CNF. Without it
        the answer's CNF cannot be re-derived and ``verify`` refuses to re-check it.

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
    from tilesolve.verify.drat import check_drat, dimacs_bytes  # loaded on use: a sat answer needs no checker

    stats = dict(stats)
    if encoding is not None:
        stats["encoding"] = {"name": encoding["name"], "version": encoding["version"],
                             "options": dict(encoding["options"])}
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
    if deadline.expired():
        return unknown(f"{solver} reported unsatisfiable; its DRAT proof was not checked: time limit of "
                       f"{deadline.time_limit:.3g} s reached before the check")
    chk = check_drat(formula, proof, time_limit=deadline.remaining())
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
    name = proof_name(stats["cnf_sha256"], stats["drat_sha256"])
    for directory, with_cnf in _PROOF_DIRS.get():
        write_proof_files(directory, name, cnf if with_cnf else None, drat)
        stats["proof_name"] = name
    if chk.trivial:
        reason = (f"proved unsatisfiable by {solver}: unit propagation on the input clauses refutes it "
                  f"({chk.core.size if chk.core is not None else '?'} clauses take part{_clash(formula, chk.core)}); "
                  "DRAT proof checked by tilesolve.verify.drat")
    else:
        reason = (f"proved unsatisfiable by {solver}; DRAT proof of {chk.lemmas} lemma(s) ({chk.checked} of them "
                  "used) checked by tilesolve.verify.drat")
    return Solution(Status.UNSAT, None, method, solver, seed, time.perf_counter() - t0, reason=reason, stats=stats)


# ----------------------------------------------------------------------------- re-checking
_HEX64 = frozenset("0123456789abcdef")


def _digest(value: Any) -> str | None:
    """A recorded SHA-256 (64 lower-case hex digits), else ``None``."""
    return value if isinstance(value, str) and len(value) == 64 and set(value) <= _HEX64 else None


@dataclass(frozen=True)
class Recheck:
    """What re-deriving (and, with proof files, re-checking) one unsat claim found.

    Attributes
    ----------
    verdict : {"re-checked", "bound", "refused"}
        ``re-checked``: the CNF re-derived from the problem has the recorded digest and the
        DRAT proof refutes it; ``bound``: the re-derived CNF has the recorded digest, but no
        proof was re-checked (no proof directory given); ``refused``: the claim is not
        confirmed (``lines`` say why).
    lines : tuple of str
        What was found, one line each.
    cnf, drat : bytes or None
        The re-derived CNF (DIMACS, as hashed) and the proof read, when they got that far.
    check_s : float
        Seconds spent re-deriving the CNF and checking the proof.
    """

    verdict: str
    lines: tuple[str, ...]
    cnf: bytes | None = None
    drat: bytes | None = None
    check_s: float = 0.0

    @property
    def ok(self) -> bool:
        return self.verdict == "re-checked"


#: The end of the message of a CNF that does not encode the problem.
NOT_THE_ENCODING = "the CNF is not the encoding of this problem"


def recheck_unsat(problem: Any, evidence: Mapping[str, Any], proof_dir: str | os.PathLike | None = None, *,
                  deadline: Deadline = NO_LIMIT) -> Recheck:
    """Re-derive the CNF of ``problem`` with the named encoding ``evidence`` records and check the
    recorded claim against it (``tilesolve verify``, ``aperiodic verify``, a sweep's cache).

    The CNF is rebuilt by :func:`tilesolve.encodings.registry.encode` from the problem alone;
    its SHA-256 must be the recorded ``cnf_sha256``. With ``proof_dir``, the proof is located by
    the recorded digests (``unsat-<cnf>-<drat>.drat``, :func:`proof_name`), its SHA-256 must be
    ``drat_sha256``, a ``.cnf`` file beside it must hold exactly the re-derived CNF, and the
    proof is checked by :func:`tilesolve.verify.drat.check_drat` against the *re-derived*
    formula, never against a file.

    Examples
    --------
    >>> from tilesolve.engine.sat import solve_cnf
    >>> from tilesolve.encodings.registry import encode
    >>> from tilesolve.model.dappled import DappledProblem
    >>> p = DappledProblem.from_strings("3x1", ["H0=1", "H1=1"], counts=["1=3"])
    >>> enc = encode("dappled-cnf", p)
    >>> s = unsat_solution(enc.hard, solve_cnf(enc.hard, with_proof=True), method="sat", seed=0, t0=0.0,
    ...                    stats={}, encoding=enc.named)
    >>> recheck_unsat(p, s.stats).verdict
    'bound'
    >>> recheck_unsat(DappledProblem.from_strings("3x1", ["H0=1"]), s.stats).lines[0][:43]
    'the CNF is not the encoding of this problem'
    """
    from tilesolve.encodings.registry import encode, resolve
    from tilesolve.errors import InvalidProblem
    from tilesolve.inputs import read_input
    from tilesolve.verify.drat import check_drat, dimacs_bytes, formula_arrays

    t0 = time.perf_counter()

    def refused(*lines: str, cnf: bytes | None = None) -> Recheck:
        return Recheck("refused", lines, cnf, None, time.perf_counter() - t0)

    spec = evidence.get("encoding")
    if spec is None:
        return refused("it records no named encoding, so its CNF cannot be re-derived from the problem: "
                       "re-solve to re-certify")
    try:
        entry, options = resolve(spec)
        enc = encode(entry.name, problem, options)
    except InvalidProblem as exc:
        return refused(str(exc))
    flat = formula_arrays(enc.hard)[:2]  # flattened once, for the digest and the check
    cnf = dimacs_bytes(flat)
    got = hashlib.sha256(cnf).hexdigest()
    what = f"encoding {entry.name} v{entry.version}"
    recorded = _digest(evidence.get("cnf_sha256"))
    if recorded != got:
        shown = f"{recorded[:16]}..." if recorded else repr(evidence.get("cnf_sha256"))[:40]
        return refused(f"{NOT_THE_ENCODING}: the CNF re-derived from it ({what}, {len(enc.hard)} clauses) has "
                       f"SHA-256 {got[:16]}..., the file records {shown}", cnf=cnf)
    bound = f"CNF re-derived from the problem ({what}, {len(enc.hard)} clauses): SHA-256 {got[:16]}... as recorded"
    if proof_dir is None:
        return Recheck("bound", (bound,), cnf, None, time.perf_counter() - t0)
    drat_digest = _digest(evidence.get("drat_sha256"))
    if drat_digest is None:
        return refused(bound, "no DRAT proof digest recorded (drat_sha256), so no proof can be located", cnf=cnf)
    base = os.path.join(os.fspath(proof_dir), proof_name(got, drat_digest))
    if not os.path.isfile(base + ".drat"):
        return refused(bound, f"missing proof file {base}.drat", cnf=cnf)
    try:  # through the input limit, as every file a user hands in (tilesolve --max-input)
        drat = read_input(base + ".drat", "proof ")
    except InvalidProblem as exc:
        return refused(bound, str(exc), cnf=cnf)
    if hashlib.sha256(drat).hexdigest() != drat_digest:
        return refused(bound, f"{base}.drat: SHA-256 {hashlib.sha256(drat).hexdigest()[:16]}... differs from the "
                              f"recorded {drat_digest[:16]}...", cnf=cnf)
    if os.path.isfile(base + ".cnf"):
        with open(base + ".cnf", "rb") as fh:
            if fh.read(len(cnf) + 1) != cnf:  # never more than the re-derived CNF's size
                return refused(bound, f"{NOT_THE_ENCODING}: {base}.cnf differs from the CNF re-derived from it",
                               cnf=cnf)
    chk = check_drat(flat, drat, time_limit=deadline.remaining())
    line = f"{base}.drat: {chk.status} against the re-derived CNF: {chk.reason} ({chk.time_s:.3g} s)"
    verdict = "re-checked" if chk.verified else "refused"
    return Recheck(verdict, (bound, line), cnf, drat, time.perf_counter() - t0)


#: Fewest claims that :func:`recheck_all` spreads over worker processes (each costs an interpreter start).
PARALLEL_RECHECK_MIN = 16


def _recheck_job(claims: list, proof_dir: str | None, *, seed: int) -> Recheck:
    """Claim number ``seed`` re-checked, in a worker process."""
    _, problem, evidence = claims[seed]
    return recheck_unsat(problem, evidence, proof_dir)


def _proof_size(evidence: Mapping[str, Any], proof_dir: str | os.PathLike | None) -> int:
    """Bytes of the proof file the recorded digests locate (0 when there is none)."""
    cnf, drat = _digest(evidence.get("cnf_sha256")), _digest(evidence.get("drat_sha256"))
    if proof_dir is None or cnf is None or drat is None:
        return 0
    path = os.path.join(os.fspath(proof_dir), proof_name(cnf, drat) + ".drat")
    return os.path.getsize(path) if os.path.isfile(path) else 0


def recheck_all(claims, proof_dir: str | os.PathLike | None = None, *, workers: int = 1,
                progress: Progress = SILENT) -> list[Recheck]:
    """:func:`recheck_unsat` of every ``(what, problem, evidence)`` claim (results in the claims'
    order); on ``workers`` local processes when there are at least :data:`PARALLEL_RECHECK_MIN`
    claims (a report's refuted boards), else here. The claims done are counted on ``progress``.
    Ctrl-C raises ``KeyboardInterrupt``.

    The largest proofs are checked first: the checker's compiled kernels, loaded for them, then
    serve the small ones too (checked first, each small proof would run interpreted), and the
    long checks start while the short ones fill the gaps (5-6x faster on a Jeandel-Rao report).
    """
    claims = list(claims)
    order = sorted(range(len(claims)), key=lambda i: -_proof_size(claims[i][2], proof_dir))
    out: list[Recheck | None] = [None] * len(claims)
    if not claims:
        return out
    with progress.task("re-checking refutations", total=len(claims), unit="claim") as bar:
        if workers <= 1 or len(claims) < PARALLEL_RECHECK_MIN:
            for i in order:
                _, problem, evidence = claims[i]
                out[i] = recheck_unsat(problem, evidence, proof_dir)
                bar.advance()
        else:
            _recheck_on_workers(claims, order, proof_dir, workers, out, bar)
    return out


def _recheck_on_workers(claims, order, proof_dir, workers: int, out: list, bar) -> None:
    """:func:`recheck_all` on local worker processes, the largest proofs first."""
    import functools

    from tilesolve.engine.aperiodic import _on_pool
    from tilesolve.model.run import RunOptions

    def take(i: int, rc: Recheck) -> bool:
        out[order[i]] = rc
        bar.advance()
        return False

    task = functools.partial(_recheck_job, [claims[i] for i in order],
                             None if proof_dir is None else os.fspath(proof_dir))
    if _on_pool(task, len(claims), min(workers, len(claims)), RunOptions(seed=0, deadline=NO_LIMIT), take,
                lambda: None):
        raise KeyboardInterrupt
