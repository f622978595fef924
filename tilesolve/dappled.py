"""Dappled tilings end to end: one facade over the constructive and solver routes.

Every question about dappled tilings (Kaji, Derouet-Jourdan, Ochiai, *Dappled tiling*,
2016) goes through :func:`solve`, :func:`count` or :func:`crosscheck`:

``solve``
    looks the method up in :data:`SOLVERS` (a registry, so the CLI's ``--method``
    choices come from its keys), runs it, and checks every tiling it returns with the
    independent verifier :func:`tilesolve.verify.dappled_violations`. A constructive
    output that fails verification is never returned: the facade falls back to the SAT
    route and says so in ``Solution.notes``.
``count``
    the exact number of tilings by the transfer-matrix programme, or by solver
    enumeration (blocking clauses) where the transfer matrix does not apply.
``crosscheck``
    runs both routes on one problem and confirms that they agree.

Examples
--------
>>> from tilesolve.model import DappledProblem
>>> p = DappledProblem.from_strings("12x8", ["H0=2", "V1=2"])
>>> s = solve(p, seed=1)
>>> s.status.value, s.method
('sat', 'constructive')
>>> count(DappledProblem.from_strings("3x3", ["H0=2", "V1=2"])).value
174
"""

from __future__ import annotations

import time
from typing import Callable

import numpy as np

from tilesolve.engine.progress import ticker
from tilesolve.engine.routes import lookup, verified
from tilesolve.errors import InvalidProblem, MethodNotApplicable
from tilesolve.model.dappled import DappledProblem
from tilesolve.model.solution import CountResult, CrosscheckReport, Solution, Status
from tilesolve.verify.dappled import dappled_violations

__all__ = [
    "SOLVERS",
    "METHODS",
    "COUNT_METHODS",
    "CountResult",
    "CrosscheckReport",
    "solve",
    "count",
    "crosscheck",
]


def _constructive(problem: DappledProblem, *, seed=None, time_limit=None, initial=None, progress=False) -> Solution:
    from tilesolve.constructive.dappled import make_dappled

    t0 = time.perf_counter()
    tiling = make_dappled(problem, initial, seed=seed)
    return Solution(Status.SAT, tiling, method="constructive", seed=seed, time_s=time.perf_counter() - t0)


def _sat(problem: DappledProblem, *, seed=None, time_limit=None, initial=None, progress=False) -> Solution:
    from tilesolve.engine.dappled import solve_sat

    return solve_sat(problem, time_limit=time_limit, seed=seed)


def _maxsat(problem: DappledProblem, *, seed=None, time_limit=None, initial=None, progress=False) -> Solution:
    from tilesolve.engine.dappled import solve_maxsat

    return solve_maxsat(problem, time_limit=time_limit, seed=seed)


def _cpsat(problem: DappledProblem, *, seed=None, time_limit=None, initial=None, progress=False) -> Solution:
    from tilesolve.engine.dappled import solve_cpsat

    return solve_cpsat(problem, time_limit=time_limit, seed=seed)


#: Solving routes by name. ``"auto"`` is not an entry: it picks one (see :func:`solve`).
SOLVERS: dict[str, Callable[..., Solution]] = {
    "constructive": _constructive,
    "sat": _sat,
    "maxsat": _maxsat,
    "cpsat": _cpsat,
}
METHODS: tuple[str, ...] = ("auto",) + tuple(SOLVERS)
COUNT_METHODS: tuple[str, ...] = ("auto", "transfer", "enumerate")


def _auto_method(problem: DappledProblem) -> str:
    if problem.closest_to is not None:
        return "maxsat"
    if problem.is_plain:
        return "constructive"
    return "sat"


def _checked(problem: DappledProblem, sol: Solution) -> Solution:
    """Run the independent verifier on a returned tiling and recompute the distance."""
    sol = verified(sol, lambda tiling: dappled_violations(tiling, problem))
    if sol.status.has_tiling and problem.closest_to is not None:
        dist = int((sol.tiling != problem.closest_to).sum())
        if sol.objective is not None and sol.objective != dist:
            raise AssertionError(f"internal error: reported distance {sol.objective} but the tiling is at {dist}")
        sol = sol.replace(objective=dist)
    return sol


def solve(
    problem: DappledProblem,
    *,
    method: str | Callable[..., Solution] = "auto",
    seed: int | None = None,
    time_limit: float | None = None,
    initial: np.ndarray | None = None,
    progress: bool = False,
) -> Solution:
    """Find an L-dappled tiling (or prove none exists) and verify it independently.

    Parameters
    ----------
    problem : DappledProblem
    method : {"auto", "constructive", "sat", "maxsat", "cpsat"} or callable
        ``"auto"`` uses the constructive algorithms (Algorithm 1, the trivial |T|>=3
        algorithm, Algorithm 2 / Remark 3.4 for cyclic problems) when they apply, MaxSAT
        for closest tilings, and SAT otherwise. A callable takes ``(problem, seed=,
        time_limit=, initial=, progress=)`` and returns a :class:`Solution`.
    seed : int, optional
        Seeds the random initial tiling of the constructive route and solver randomness.
    time_limit : float, optional
        Seconds; a solver that runs out returns status ``unknown``.
    initial : numpy.ndarray, optional
        Input tiling for Algorithm 1/2 (§2: "we can start with a random tiling or a user
        specified one").
    progress : bool
        Show the running route and elapsed time on stderr (only when it is a terminal).

    Returns
    -------
    Solution
        ``sat``/``optimal`` with a verified tiling, ``unsat`` with a reason, or ``unknown``.

    Raises
    ------
    MethodNotApplicable
        An explicitly requested method cannot handle the problem; the message names one
        that can.
    """
    t0 = time.perf_counter()
    notes: list[str] = []
    runner, name = lookup(method, SOLVERS, lambda: _auto_method(problem))
    if name == "constructive" and problem.closest_to is not None:
        raise MethodNotApplicable("the constructive route does not minimise distance; use method 'maxsat'")
    if initial is not None and name != "constructive":
        notes.append(f"the initial tiling is only used by the constructive route, not by {name!r}")
    try:
        with ticker(f"solving with {name!r}", progress):
            sol = runner(problem, seed=seed, time_limit=time_limit, initial=initial, progress=progress)
    except MethodNotApplicable as exc:
        if method != "auto":
            raise
        notes.append(f"constructive route not applicable ({exc}); solved with 'sat'")
        with ticker("solving with 'sat'", progress):
            sol = SOLVERS["sat"](problem, seed=seed, time_limit=time_limit, progress=progress)
    if sol.method == "constructive" and sol.status.has_tiling:
        violations = dappled_violations(sol.tiling, problem)
        if violations:
            notes.append(
                f"constructive output failed verification ({len(violations)} violations, first at "
                f"row {violations[0].row}, col {violations[0].col}); fell back to 'sat'"
            )
            with ticker("solving with 'sat'", progress):
                sol = SOLVERS["sat"](problem, seed=seed, time_limit=time_limit, progress=progress)
    sol = _checked(problem, sol)
    return sol.replace(notes=tuple(notes) + sol.notes, time_s=time.perf_counter() - t0, seed=seed)


def count(
    problem: DappledProblem,
    *,
    method: str = "auto",
    time_limit: float | None = None,
    progress: bool = False,
) -> CountResult:
    """Count the tilings that satisfy ``problem`` exactly.

    ``"transfer"`` is the row-by-row transfer-matrix programme (exact big integers; plain
    conditions, fixed cells); ``"enumerate"`` enumerates solver models with blocking
    clauses (any problem, small counts); ``"auto"`` prefers the transfer matrix.
    For T = {0,1} and L = {H_0^2, V_1^2} the counts are OEIS A206994 (Remark 1.4).
    """
    from tilesolve.constructive.dappled_count import count_dappled

    if method not in COUNT_METHODS:
        raise InvalidProblem(f"unknown count method {method!r}; choose one of {', '.join(COUNT_METHODS)}")
    if problem.closest_to is not None:
        raise InvalidProblem("counting ignores a closest-to target; drop it")
    t0 = time.perf_counter()
    note = None
    if method in ("auto", "transfer"):
        try:
            value = count_dappled(problem, progress=progress)
            return CountResult(value, Status.SAT, "transfer", time.perf_counter() - t0)
        except MethodNotApplicable as exc:
            if method == "transfer":
                raise
            note = f"transfer matrix not applicable ({exc}); counted by solver enumeration"
    from tilesolve.engine.dappled import count_by_enumeration

    value, complete = count_by_enumeration(problem, time_limit=time_limit, progress=progress)
    if not complete:
        return CountResult(
            None, Status.UNKNOWN, "enumerate", time.perf_counter() - t0,
            f"time limit reached after {value} tilings" + (f"; {note}" if note else ""),
        )
    return CountResult(value, Status.SAT, "enumerate", time.perf_counter() - t0, note)


def crosscheck(problem: DappledProblem, *, seed: int | None = None, time_limit: float | None = None) -> CrosscheckReport:
    """Run the constructive and solver routes on ``problem`` and confirm they agree.

    Checks (DESIGN.md, "Cross-checks"): the constructive output passes the verifier and
    satisfies the CNF encoding; SAT and CP-SAT agree on solvability; every tiling they
    return passes the verifier; on small plain grids the transfer-matrix count equals the
    enumeration count.
    """
    from tilesolve.engine.dappled import tiling_satisfies_encoding

    report = CrosscheckReport()
    try:
        cons = SOLVERS["constructive"](problem, seed=seed)
    except MethodNotApplicable as exc:
        report.lines.append(f"skip constructive route: {exc}")
    else:
        bad = dappled_violations(cons.tiling, problem)
        report.add(not bad, f"constructive tiling verifies ({len(bad)} violations)")
        if not bad:
            report.add(tiling_satisfies_encoding(problem, cons.tiling), "constructive tiling satisfies the CNF encoding")
            report.verdicts["constructive"] = Status.SAT
    for name in ("sat", "cpsat") + (("maxsat",) if problem.closest_to is not None else ()):
        sol = SOLVERS[name](problem, seed=seed, time_limit=time_limit)
        if sol.status.has_tiling:
            bad = dappled_violations(sol.tiling, problem)
            report.add(not bad, f"{name}: {sol.status.value}, tiling verifies ({len(bad)} violations)")
        else:
            report.lines.append(f"     {name}: {sol.status.value}" + (f" ({sol.reason})" if sol.reason else ""))
        if sol.status != Status.UNKNOWN:
            report.verdicts[name] = Status.SAT if sol.status.has_tiling else Status.UNSAT
    report.add_agreement()
    if problem.closest_to is None and problem.size <= 16:
        a, b = count(problem, method="enumerate"), None
        try:
            b = count(problem, method="transfer")
        except MethodNotApplicable:
            pass
        if b is not None:
            report.add(a.value == b.value, f"count: enumeration {a.value} = transfer matrix {b.value}")
    return report
