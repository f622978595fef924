"""The one solve pipeline: :func:`solve` looks the route up, runs it, certifies an
infeasibility claimed without a proof, verifies every tiling with the family's checker and
stamps the provenance."""

from __future__ import annotations

import functools
import os
from typing import Any, Mapping

from tilesolve.deadline import Deadline, TimeLimitReached, run_start
from tilesolve.errors import InternalError, InvalidProblem, MethodNotApplicable
from tilesolve.family.contract import Family, Route
from tilesolve.family.drawing import render
from tilesolve.family.registry import family_of
from tilesolve.family.seeds import check_seed, draw_seed
from tilesolve.model.run import RunOptions
from tilesolve.model.solution import CountResult, Solution, Status
from tilesolve.progress import Progress

__all__ = ["solve", "run_route", "run_deadline", "count", "interrupted", "raise_if_interrupted", "writing_proofs"]


def solve(
    problem: Any,
    method: str | Route = "auto",
    *,
    seed: int | None = None,
    time_limit: float | None = None,
    progress: Progress | bool = False,
    solver: str | None = None,
    workers: int | None = None,
    cluster: Any = None,
    options: Mapping[str, Any] | None = None,
) -> Solution:
    """Solve ``problem`` with its family's routes and verify the answer independently.

    Parameters
    ----------
    problem
        A problem of a registered family.
    method : str or callable
        ``"auto"``, a route name of the family, or a callable ``route(problem, run)``.
    seed : int, optional
        Drawn (and recorded in ``Solution.seed``) when not given.
    time_limit : float, optional
        Seconds for the whole run; expiry gives status ``unknown``, never ``unsat``.
    progress, solver, workers, cluster, options
        See :class:`RunOptions`.

    Returns
    -------
    Solution
        ``sat``/``optimal`` with a verified tiling, ``unsat`` with a reason, or ``unknown``.

    Raises
    ------
    MethodNotApplicable
        An explicitly requested route cannot take the problem (the message names one that can).
    InternalError
        A route returned a tiling (or report) that fails verification and no fallback exists (a bug).
    """
    fam = family_of(problem)
    if time_limit is not None and not (time_limit > 0 and time_limit < float("inf")):
        raise InvalidProblem(f"time limit must be a positive number of seconds, got {time_limit}")
    run = RunOptions(
        seed=draw_seed() if seed is None else check_seed(seed),
        deadline=run_deadline(time_limit),
        progress=progress,
        solver=solver,
        workers=workers,
        cluster=cluster,
        options=dict(options or {}),
    )
    return run_route(fam, problem, method, run)


def run_deadline(time_limit: float | None) -> Deadline:
    """The :class:`~tilesolve.deadline.Deadline` of one run, from the seconds a user gave
    (``None``: no limit): made once, where a run begins (:func:`solve`, :func:`count`, each run
    of a crosscheck), and passed down; nothing below an entry point makes one. Its clock starts
    now, or where the command line says (:func:`~tilesolve.deadline.run_start`).

    >>> run_deadline(None).time_limit, run_deadline(2.5).time_limit
    (None, 2.5)
    >>> run_deadline(float("inf"))
    Traceback (most recent call last):
    ...
    tilesolve.errors.InvalidProblem: time limit must be a finite number of seconds >= 0, got inf
    """
    if time_limit is not None and not 0 <= time_limit < float("inf"):
        raise InvalidProblem(f"time limit must be a finite number of seconds >= 0, got {time_limit}")
    return Deadline(time_limit, start=run_start())


def run_route(fam: Family, problem: Any, method: str | Route, run: RunOptions) -> Solution:
    """The pipeline of :func:`solve` once the run is resolved (also used by crosschecks)."""
    route, name = fam.lookup(method, problem)
    notes: list[str] = []
    if method == "auto":
        notes.append(f"auto chose {name!r}")
    with run.progress.task(f"{fam.name}: solving with {name!r}", unit=None):
        try:
            try:
                sol = route(problem, run)
            except MethodNotApplicable as exc:
                if method != "auto" or fam.fallback is None or name == fam.fallback:
                    raise
                notes.append(f"{name!r} not applicable ({exc}); solved with {fam.fallback!r}")
                name = fam.fallback
                sol = fam.routes[name](problem, run)
        except TimeLimitReached as exc:  # a route out of time while encoding or building
            sol = Solution(Status.UNKNOWN, None, name, None, run.seed, run.deadline.elapsed(), reason=str(exc))
    if _uncertified(sol) and name != "sat":
        sol = _certify_infeasible(fam, problem, run, name, sol)
    bad = fam.verify(problem, sol.answer) if sol.answer is not None else ()
    if bad and method == "auto" and fam.fallback is not None and name != fam.fallback:
        notes.append(f"{name!r} output failed verification ({len(bad)} violations, first: {bad[0]}); "
                     f"fell back to {fam.fallback!r}")
        name = fam.fallback
        with run.progress.task(f"{fam.name}: solving with {name!r}", unit=None):
            sol = fam.routes[name](problem, run)
        bad = fam.verify(problem, sol.answer) if sol.answer is not None else ()
    if bad:
        what = "a report" if sol.report is not None else "a tiling"
        raise InternalError(f"method {sol.method or name!r} returned {what} that fails verification "
                            f"({len(bad)} violations, first: {bad[0]})")
    if sol.status.has_tiling and fam.objective is not None:
        value = fam.objective(problem, sol.tiling)
        if sol.objective is not None and value != sol.objective:
            raise InternalError(f"method {name!r} reported objective {sol.objective}, the tiling has {value}")
        sol = sol.replace(objective=value)
    return sol.replace(
        method=sol.method or name,
        notes=tuple(notes) + sol.notes,
        time_s=run.deadline.elapsed(),
        seed=run.seed if sol.seed is None else sol.seed,
        renderer=functools.partial(render, problem) if fam.draw is not None else None,
    )


def _certify_infeasible(fam: Family, problem: Any, run: RunOptions, name: str, sol: Solution) -> Solution:
    """An infeasibility claimed without a checked proof (CP-SAT's, or a constructive route's
    clash) re-decided by the family's ``sat`` route, whose unsat carries a checked DRAT proof,
    within what is left of the run's deadline; ``unknown`` ("uncertified: ...") when that
    fails, so that ``unsat`` always comes with a checked proof."""
    from tilesolve.engine.certificates import UNCERTIFIED

    if sol.status is Status.UNSAT:
        claim = f"found it unsatisfiable without a checked proof ({sol.reason})"
    else:
        claim = "(CP-SAT) proved infeasibility without a proof"

    def uncertified(why: str) -> Solution:
        if sol.status is Status.UNKNOWN:
            return sol.replace(reason=f"{sol.reason}; {why}")
        return sol.replace(status=Status.UNKNOWN, reason=f"{UNCERTIFIED} {name!r} {claim}; {why}")

    if "sat" not in fam.routes:
        return uncertified(f"the {fam.name} family has no 'sat' route to certify it")
    if run.deadline.expired():
        return uncertified("no time left to certify it with the 'sat' route")
    with run.progress.task(f"{fam.name}: certifying {name!r}'s infeasibility with 'sat'", unit=None):
        try:
            cert = fam.routes["sat"](problem, run)
        except (TimeLimitReached, MethodNotApplicable) as exc:
            return uncertified(f"the 'sat' route could not certify it: {exc}")
    if cert.status is Status.UNSAT:
        return cert.with_note(f"{name!r} {claim}; certified by the 'sat' route")
    if cert.status.has_tiling:
        raise InternalError(f"{name!r} said infeasible but the 'sat' route found a tiling")
    return uncertified(f"the 'sat' route could not certify it: {cert.reason}")


def _uncertified(sol: Solution) -> bool:
    """An infeasibility claimed without a checked proof: CP-SAT's (reported ``unknown``) or
    any ``unsat`` whose stats do not record a verified proof."""
    from tilesolve.engine.certificates import UNCERTIFIED

    if sol.status is Status.UNSAT:
        return sol.stats.get("proof_status") != "verified"
    return sol.status is Status.UNKNOWN and (bool(sol.stats.get("cpsat_infeasible"))
                                             or (sol.reason or "").startswith(UNCERTIFIED))


def interrupted(result: Solution | CountResult) -> bool:
    """True when Ctrl-C stopped the run: the engine catches it inside a solver and returns
    ``unknown`` with a reason (a note, for counts) starting with "interrupted".

    The CLI exits 130 and writes nothing for such an answer; a time limit is not an interruption.
    """
    why = getattr(result, "reason", None) or getattr(result, "note", None) or ""
    return result.status is Status.UNKNOWN and why.startswith("interrupted")


def raise_if_interrupted(result):
    """Return ``result``, or raise KeyboardInterrupt if Ctrl-C stopped it (so loops over routes,
    trials or demos stop, and the CLI exits 130 without writing)."""
    if interrupted(result):
        raise KeyboardInterrupt
    return result


def count(problem: Any, *, method: str = "auto", time_limit: float | None = None,
          progress: Progress | bool = False, force: bool = False) -> CountResult:
    """Count the solutions of ``problem`` exactly with its family's counter."""
    fam = family_of(problem)
    if fam.count is None:
        raise MethodNotApplicable(f"{fam.name} problems have no counter")
    return fam.count(problem, method=method, time_limit=time_limit, progress=progress, force=force)


def writing_proofs(directory: str | os.PathLike | None):
    """Context manager: write each checked unsat proof (CNF + DRAT) to ``directory``
    (:func:`tilesolve.engine.certificates.writing_proofs`; the CLI's ``--proof-dir``)."""
    from tilesolve.engine.certificates import writing_proofs as writing

    return writing(directory)
