"""``tilesolve verify``: every claim a solution document makes, re-checked (the tiling by
the family's independent verifier, each refutation's CNF re-derived and its proof re-checked)."""

from __future__ import annotations

import os
from dataclasses import dataclass
from typing import Any, Mapping, Sequence

from tilesolve.errors import InvalidProblem
from tilesolve.family.contract import Family
from tilesolve.family.files import identify
from tilesolve.model.solution import Solution, Status
from tilesolve.progress import Progress, as_progress

__all__ = [
    "cnf_estimate",
    "cnf_size_refusal",
    "DEFAULT_MAX_CNF",
    "FileReport",
    "verify_document",
    "verify_file",
]


def cnf_estimate(problem: Any) -> tuple[int, int, int] | None:
    """``(variables, clauses, literals)`` the CNF of ``problem`` is estimated to hold, before
    encoding, or None where no model exists (:func:`tilesolve.encodings.sizing.cnf_estimate`)."""
    from tilesolve.encodings.sizing import cnf_estimate as estimate

    return estimate(problem)


#: Most bytes of DIMACS text a CNF may be estimated at before it is built (``--max-cnf``'s default).
DEFAULT_MAX_CNF = 1 << 30


def cnf_size_refusal(problem: Any, limit: int) -> str | None:
    """Why the CNF of ``problem`` is not built: its :func:`cnf_estimate` as DIMACS text exceeds
    ``limit`` bytes (``export dimacs`` and ``verify``'s ``--max-cnf``); ``None`` when it fits or
    when no estimate exists."""
    from tilesolve.io.units import big, human_bytes

    sized = cnf_estimate(problem)
    if sized is None:
        return None
    n_vars, clauses, lits = sized
    text = lits * (len(str(n_vars)) + 2) + 2 * clauses  # a literal, its sign and a space; "0\n"
    if text <= limit:
        return None
    return (f"the CNF of {problem.describe()} would hold about {big(clauses)} clauses and {big(lits)} literals, "
            f"about {human_bytes(text)} of DIMACS text (and as much memory while encoding), more than --max-cnf "
            f"{human_bytes(limit)}")


#: Violation lines printed before "... and N more".
MAX_SHOWN = 50


@dataclass(frozen=True)
class FileReport:
    """What :func:`verify_file` found: the exit code (0 valid, 1 a false claim) and lines."""

    exit_code: int
    lines: tuple[str, ...]

    @property
    def ok(self) -> bool:
        return self.exit_code == 0


def _refutations(fam: Family, problem: Any, sol: Solution) -> Sequence[tuple[str, Any, Mapping[str, Any]]]:
    """Every refutation ``sol`` claims: ``(what, problem of its CNF, evidence)``."""
    if fam.refutations is not None:
        return fam.refutations(problem, sol)
    return [("the unsat claim", problem, sol.stats)] if sol.status is Status.UNSAT else []


#: What re-checking an unsat claim needs, for the lines that say it was not re-checked.
RECHECK_NEEDS = ("re-checking needs the DRAT proof: solve with --proof-dir DIR, then "
                 "tilesolve verify FILE --proof-dir DIR")


#: How a refutation whose CNF is too large to re-derive (:func:`cnf_size_refusal`) is reported.
TOO_LARGE = "cannot be re-derived here"


def _recheck(claims, proof_dir, workers: int, max_cnf: int, progress: Progress) -> tuple[list[str], list[str], int]:
    """Re-derive and (with ``proof_dir``) re-check each claimed refutation
    (:func:`tilesolve.engine.certificates.recheck_all`, on ``workers`` processes): ``(refused
    lines, detail lines, refutations re-checked)``. A claim whose CNF is estimated above
    ``max_cnf`` bytes of DIMACS text (:func:`cnf_size_refusal`) is not re-derived, and so not
    confirmed. The claims re-checked are counted on ``progress``."""
    if not claims:  # a tiling's file claims no refutation: nothing to load
        return [], [], 0
    from tilesolve.engine.certificates import recheck_all

    claims = [(what, problem, evidence if isinstance(evidence, Mapping) else {}) for what, problem, evidence in claims]
    refused, details, checked = [], [], 0
    sized = [(what, cnf_size_refusal(problem, max_cnf)) for what, problem, _ in claims]
    for what, why in sized:
        if why is not None:
            line = f"{what}: the certificate {TOO_LARGE}: {why}; raise --max-cnf to re-derive it"
            refused.append(line)
            details.append(f"  {line}")
    claims = [c for c, (_, why) in zip(claims, sized) if why is None]
    for (what, _, _), rc in zip(claims, recheck_all(claims, proof_dir, workers=workers, progress=progress)):
        if rc.verdict == "refused":
            refused.append(f"{what}: {rc.lines[-1]}")
        checked += rc.ok
        details += [f"  {what}: {ln}" for ln in rc.lines]
    return refused, details, checked


def verify_document(doc: dict, source: str = "<document>", proof_dir: str | os.PathLike | None = None, *,
                    workers: int = 1, max_cnf: int = DEFAULT_MAX_CNF, progress: Progress | bool = False) -> FileReport:
    """Check every claim a solution document makes (``tilesolve verify``).

    The tiling must pass the family's independent verifier; the status must match the
    file's content (``sat``/``optimal`` need a tiling, ``unsat``/``unknown`` must hold none);
    ``optimal`` needs a problem with an objective and the recorded objective must equal the
    tiling's value. Field types are checked by the family's codec.

    Every refutation the file claims (an ``unsat`` answer, a report's refuted boards:
    :attr:`Family.refutations`) is bound to the problem the file states: its CNF is re-derived
    with the named encoding it records and must have the recorded SHA-256 ("the CNF is not the
    encoding of this problem" otherwise). With ``proof_dir`` each DRAT proof, located by the
    recorded digests, is checked against the re-derived formula. Without it an ``unsat`` claim
    is reported as *not* re-checked (exit 1, the status's code). ``workers`` local processes
    share the re-checking of many refutations (a report's). A CNF estimated above ``max_cnf``
    bytes of DIMACS text is not built: its claim is not confirmed (exit 1), and the line says
    so with the estimate.

    A report (``Solution.report``, e.g. an aperiodicity check's) is checked by the family's
    verifier and its refutations as above; the first line names it with its own words: ``ok:
    FILE is a valid aperiodicity report of ...: verdict periodic (...)``. A valid report is exit
    0 whatever its verdict (``undecided`` included): what is checked is that its claims hold.

    The first line is the verdict (``ok: ...`` only when every check passed); detail lines follow,
    indented. ``progress`` (:func:`tilesolve.progress.as_progress`) counts the refutations re-checked.
    """
    progress = as_progress(progress)
    fam, codec = identify(doc, source)
    problem, sol = codec.read(doc, source)
    if sol is None:
        raise InvalidProblem(f"{source}: a {codec.format} file holds no solution to verify; solve it first")
    what = problem.describe() if hasattr(problem, "describe") else fam.name
    if sol.report is not None:
        return _verify_report(fam, problem, sol, source, what, proof_dir, workers, max_cnf, progress)
    false: list[str] = []
    if sol.tiling is None:
        if sol.status.has_tiling:
            false.append(f"status {sol.status.value!r} claims a tiling, but the file holds none")
        elif sol.status is Status.UNSAT:
            return _verify_unsat(fam, problem, sol, source, proof_dir, workers, max_cnf, progress)
        else:
            why = f" ({sol.reason})" if sol.reason else ""
            return FileReport(sol.status.exit_code, (f"{source}: status {sol.status.value}{why}; "
                                                     "the file holds no tiling to verify",))
    else:
        if not sol.status.has_tiling:
            false.append(f"status {sol.status.value!r} claims no tiling was found, but the file holds one")
        violations = list(fam.verify(problem, sol.tiling))
        if violations:
            return _violations_report(source, what, violations, false)
        value = fam.objective(problem, sol.tiling) if fam.objective is not None else None
        if value is None:
            if sol.status is Status.OPTIMAL:
                false.append("status 'optimal' claims an optimum, but the problem has no objective")
            if sol.objective is not None:
                false.append(f"objective {sol.objective} recorded, but the problem has no objective")
        elif sol.objective != value:
            false.append(f"recorded objective {sol.objective}, but the tiling's value is {value}")
    return _claims_checked(fam, problem, sol, source, proof_dir, workers, max_cnf, progress, false,
                           f"ok: {source} is a valid {fam.answer} of {what}")


def _violations_report(source: str, what: str, violations: Sequence, false: Sequence[str]) -> FileReport:
    """Exit 1: the verifier's violations of ``what`` (the first :data:`MAX_SHOWN`), then other false claims."""
    n = len(violations)
    lines = [f"{source}: {n} violation{'s' if n != 1 else ''} of {what}"]
    lines += [f"  {v}" for v in violations[:MAX_SHOWN]]
    if n > MAX_SHOWN:
        lines.append(f"  ... and {n - MAX_SHOWN} more")
    return FileReport(1, tuple(lines + [f"  {f}" for f in false]))


def _verify_report(fam: Family, problem: Any, sol: Solution, source: str, what: str, proof_dir, workers: int,
                   max_cnf: int, progress: Progress) -> FileReport:
    """:func:`verify_document` of a file whose answer is a report (``Solution.report``) about ``what``."""
    report = sol.report
    false = [] if sol.status is report.status else [
        f"status {sol.status.value!r} NOT confirmed: the {report.title}'s certificates give {report.status.value!r}"]
    violations = list(fam.verify(problem, report))
    if violations:
        return _violations_report(source, f"{report.title} of {what}", violations, false)
    return _claims_checked(fam, problem, sol, source, proof_dir, workers, max_cnf, progress, false,
                           f"ok: {source} is a valid {report.title} ({what}): verdict {report.verdict}",
                           (f"  conclusion: {report.conclusion}",))


def _claims_checked(fam: Family, problem: Any, sol: Solution, source: str, proof_dir, workers: int, max_cnf: int,
                    progress: Progress, false: list[str], head: str, said: tuple[str, ...] = ()) -> FileReport:
    """The end of :func:`verify_document` once the answer itself holds: its refutations re-derived
    (and re-checked with ``proof_dir``); exit 1 with ``false`` and the refused ones, else ``head``
    with what was re-checked, then the lines ``said`` and the details."""
    claims = _refutations(fam, problem, sol) if not false else []
    refused, details, checked = _recheck(claims, proof_dir, workers, max_cnf, progress)
    false += refused
    if false:
        verdict = "NOT confirmed" if all(TOO_LARGE in f for f in false) else "false"
        return FileReport(1, (f"{source}: the file's claims are {verdict}",) + tuple(f"  {f}" for f in false))
    if claims and proof_dir is not None:
        head += f"; {checked} refutation(s) re-checked: each DRAT proof refutes the CNF re-derived from the problem"
    elif claims:
        head += (f"; the CNFs of {len(claims)} refutation(s) re-derived from the problem match their digests, "
                 "but their proofs were NOT re-checked (give --proof-dir DIR)")
    return FileReport(0, (head,) + said + tuple(details))


def _verify_unsat(fam: Family, problem: Any, sol: Solution, source: str, proof_dir, workers: int,
                  max_cnf: int, progress: Progress) -> FileReport:
    """:func:`verify_document` of a file whose status is ``unsat``."""
    why = f" ({sol.reason})" if sol.reason else ""
    claims = _refutations(fam, problem, sol)
    if not claims:
        return FileReport(1, (f"{source}: status unsat NOT confirmed: the file names no refutation to re-check",))
    refused, details, _ = _recheck(claims, proof_dir, workers, max_cnf, progress)
    if refused:
        size_only = all(TOO_LARGE in line for line in refused)
        head = f"{source}: status unsat NOT confirmed: its certificate {TOO_LARGE if size_only else 'does not hold'}"
        return FileReport(1, (head,) + tuple(details))
    if proof_dir is None:
        head = (f"{source}: status unsat{why}; the file holds no tiling to verify, and the unsat claim was NOT "
                f"re-checked: {RECHECK_NEEDS}")
        return FileReport(sol.status.exit_code, (head,) + tuple(details))
    head = f"ok: {source}: unsat re-checked: the DRAT proof refutes the CNF re-derived from the file's problem"
    return FileReport(0, (head,) + tuple(details))


#: Suffixes of the files tilesolve writes beside its JSON (points, pictures), which verify cannot read.
_NOT_VERIFIABLE = {".npy": "NumPy point file", ".csv": "CSV point file", ".png": "PNG picture", ".svg": "SVG picture"}


def verify_file(path: str | os.PathLike, proof_dir: str | os.PathLike | None = None, *,
                workers: int = 1, max_cnf: int = DEFAULT_MAX_CNF, progress: Progress | bool = False) -> FileReport:
    """:func:`verify_document` on a file (one-line errors for unreadable or malformed files;
    a point set or a picture tilesolve wrote is named as such: only its JSON files verify)."""
    from tilesolve.io.jsonio import read_json

    suffix = os.path.splitext(str(path))[1].lower()
    if suffix in _NOT_VERIFIABLE:
        raise InvalidProblem(f"{path}: a {_NOT_VERIFIABLE[suffix]} holds no problem to check it against; "
                             f"tilesolve verify reads the JSON files tilesolve writes (-o NAME.json)")
    return verify_document(read_json(path), str(path), proof_dir, workers=workers, max_cnf=max_cnf, progress=progress)
