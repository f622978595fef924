"""Solver routes for dappled tilings (Kaji, Derouet-Jourdan, Ochiai 2016, §6).

Each function takes a :class:`~tilesolve.model.dappled.DappledProblem`, encodes it with
:mod:`tilesolve.encodings.dappled`, runs a generic backend and returns a
:class:`~tilesolve.model.solution.Solution` whose tiling is ready for the independent
verifier (:func:`tilesolve.verify.dappled.dappled_violations`).

=========================  ==================================================================
function                   question
=========================  ==================================================================
:func:`solve_sat`          is there a tiling? (§6 item 8; UNSAT answers carry a checked DRAT
                           proof, e.g. Example 6.2)
:func:`solve_maxsat`       the closest tiling to ``closest_to``, proved optimal (§6 item 3)
:func:`solve_cpsat`        either question with OR-tools CP-SAT
:func:`enumerate_tilings`  every tiling, one by one (blocking clauses)
:func:`count_by_enumeration`  how many tilings (a CountResult: exact, or unknown)
=========================  ==================================================================
"""

from __future__ import annotations

import dataclasses
import time
from typing import Iterator

import numpy as np

from tilesolve.encodings.dappled import DappledEncoding, build_cpsat, encode_cnf, encode_wcnf
from tilesolve.encodings.registry import encode
from tilesolve.engine.cpsat import DEFAULT_CPSAT_WORKERS, solve_cp_model
from tilesolve.engine.maxsat import DEFAULT_MAXSAT_ORACLE, RC2Options, solve_lazy, solve_wcnf
from tilesolve.engine.routes import sat_route
from tilesolve.deadline import NO_LIMIT, Deadline, TimeLimitReached
from tilesolve.engine.sat import DEFAULT_SAT_SOLVER, ModelEnumerator, count_models, solve_cnf
from tilesolve.errors import InternalError, InvalidProblem
from tilesolve.model.dappled import DappledProblem
from tilesolve.model.run import RunOptions
from tilesolve.model.solution import CountResult, Solution, Status
from tilesolve.progress import Progress, as_progress

__all__ = [
    "solve_sat",
    "solve_maxsat",
    "solve_cpsat",
    "enumerate_tilings",
    "count_by_enumeration",
    "tiling_satisfies_encoding",
    "TilingEnumerator",
    "MAXSAT_METHODS",
]

def _check_problem(problem) -> None:
    if not isinstance(problem, DappledProblem):
        raise InvalidProblem(f"expected a DappledProblem, got {type(problem).__name__}")


def _enc_stats(enc: DappledEncoding, encode_s: float) -> dict:
    return {"variables": enc.n_vars, "clauses": len(enc.hard), "encode_s": round(encode_s, 6)}


def solve_sat(
    problem: DappledProblem,
    *,
    deadline: Deadline = NO_LIMIT,
    solver: str = DEFAULT_SAT_SOLVER,
    seed: int | None = None,
) -> Solution:
    """Decide a dappled problem with a SAT solver (dappled paper §6 item 8).

    Parameters
    ----------
    problem : DappledProblem
        Any variant (subsets, per-cell limits, cyclic, fixed cells, counts).
        ``closest_to`` only guides the search (solver phases); use
        :func:`solve_maxsat` for the closest tiling.
    deadline : Deadline, optional
        The whole run's deadline, encoding included (messages name its limit); expiry gives
        ``Status.UNKNOWN``, never ``UNSAT``.
    solver : str
        PySAT solver name (see :func:`tilesolve.engine.sat.proof_solvers`). UNSAT answers
        carry the DRAT proof it logged, checked by :mod:`tilesolve.verify.drat`
        (:func:`tilesolve.engine.routes.sat_route`).
    seed : int, optional
        Solver random seed (CaDiCaL, Glucose 4.2); recorded in the Solution.

    Returns
    -------
    Solution
        ``SAT`` with a tiling, ``UNSAT`` with the proof's verdict in ``reason``, or
        ``UNKNOWN``.

    Examples
    --------
    Example 6.2 of the paper has no cyclic extension:

    >>> import numpy as np
    >>> fixed = np.array([[1, -1, -1, -1], [-1, 0, -1, -1], [-1, 0, 1, 1], [-1, 0, -1, -1]])
    >>> p = DappledProblem.from_strings("4x4", ["H0=2", "V1=2"], cyclic=True, fixed=fixed)
    >>> s = solve_sat(p)
    >>> s.status.value, s.reason.startswith("proved unsatisfiable by cadical153; DRAT proof of")
    ('unsat', True)
    """
    _check_problem(problem)
    t0 = time.perf_counter()
    run = RunOptions(seed, deadline)
    try:
        enc = encode("dappled-cnf", problem, deadline=run.deadline)
    except TimeLimitReached as exc:
        return Solution(Status.UNKNOWN, None, "sat", solver, seed, time.perf_counter() - t0, reason=str(exc))
    phases = enc.literals(problem.closest_to) if problem.closest_to is not None else None
    notes = ()
    if problem.closest_to is not None:
        notes = ("closest_to only guided the search; use solve_maxsat for the closest tiling",)
    return sat_route(enc, run, solver=solver, t0=t0, phases=phases, notes=notes)


def tiling_satisfies_encoding(problem: DappledProblem, tiling, *, solver: str = DEFAULT_SAT_SOLVER) -> bool:
    """True when ``tiling`` satisfies the CNF encoding of ``problem`` (a cross-check).

    Without auxiliary variables the clauses are evaluated directly; with counts the
    formula is solved under the tiling's literals as assumptions (DESIGN.md,
    "Cross-checks": the constructive output must satisfy the encoding).

    Examples
    --------
    >>> p = DappledProblem.from_strings("3x1", ["H0=2"])
    >>> tiling_satisfies_encoding(p, [[0, 1, 0]]), tiling_satisfies_encoding(p, [[0, 0, 0]])
    (True, False)
    """
    _check_problem(problem)
    enc = encode_cnf(problem)
    if all(b.grid_only for b in enc.hard.blocks):
        return not enc.hard.falsified(enc.target_values(np.asarray(tiling)))
    r = solve_cnf(enc.hard, solver=solver, assumptions=enc.literals(tiling))
    return r.status is Status.SAT


#: Exact MaxSAT routes for the closest tiling; "auto" picks by measurement
#: (benchmarks/bench_closest.py).
MAXSAT_METHODS = ("auto", "rc2", "lazy")

#: Grids with at least this many cells use the lazy decomposition under method="auto"
#: (with clauses over grid variables only); smaller ones one RC2 run (bench_closest.py).
LAZY_MIN_CELLS = 10_000


def solve_maxsat(
    problem: DappledProblem,
    *,
    deadline: Deadline = NO_LIMIT,
    method: str = "auto",
    solver: str = DEFAULT_MAXSAT_ORACLE,
    seed: int | None = None,
    options: RC2Options = RC2Options(),
) -> Solution:
    """The closest dappled tiling to ``problem.closest_to``, proved optimal (§6 item 3).

    The objective is the paper's Hamming distance ``d(f1, f2)``; ``Solution.objective``
    holds it and ``Status.OPTIMAL`` means no tiling is closer. Problems without
    ``closest_to`` are simply solved (:func:`solve_sat`).

    Parameters
    ----------
    problem : DappledProblem
    deadline : Deadline, optional
        The whole run's deadline: expiry gives ``UNKNOWN`` with ``stats["lower_bound"]``.
    method : {"auto", "rc2", "lazy"}
        ``rc2``: one RC2 run on the whole weighted formula; ``lazy``: the exact lazy
        decomposition of :func:`tilesolve.engine.maxsat.solve_lazy` (not with counts).
    solver : str
        RC2's SAT oracle.
    seed : int, optional
        Recorded (RC2 is deterministic).
    options : RC2Options

    Examples
    --------
    >>> import numpy as np
    >>> p = DappledProblem.from_strings("3x1", ["H0=2"], closest_to=np.zeros((1, 3), int))
    >>> s = solve_maxsat(p)
    >>> s.status.value, s.objective
    ('optimal', 1)
    """
    _check_problem(problem)
    if method not in MAXSAT_METHODS:
        raise InvalidProblem(f"unknown MaxSAT method {method!r}; choose one of {', '.join(MAXSAT_METHODS)}")
    t0 = time.perf_counter()
    if problem.closest_to is None:
        sol = solve_sat(problem, deadline=deadline, seed=seed)
        return sol.with_note("no closest_to target: solved as a satisfaction problem")
    try:
        enc = encode_wcnf(problem, deadline=deadline)
    except TimeLimitReached as exc:
        return Solution(Status.UNKNOWN, None, "maxsat", solver, seed, time.perf_counter() - t0, reason=str(exc))
    stats = _enc_stats(enc, time.perf_counter() - t0)
    lazy_ok = all(b.grid_only for b in enc.hard.blocks)
    if method == "lazy" and not lazy_ok:
        raise InvalidProblem("method 'lazy' cannot handle global counts or auxiliary variables; use 'rc2'")
    use_lazy = method == "lazy" or (method == "auto" and lazy_ok and problem.size >= LAZY_MIN_CELLS)
    if use_lazy:
        r = solve_lazy(enc.hard, enc.soft, enc.target_values(problem.closest_to), solver=solver,
                       deadline=deadline, options=options)
    else:
        r = solve_wcnf(enc.hard, enc.soft, solver=solver, deadline=deadline, options=options, seed=seed)
    stats.update({k: v for k, v in r.stats.items() if isinstance(v, (int, float, str))})
    stats["solve_s"] = round(r.runtime, 6)
    if r.status is Status.OPTIMAL:
        tiling = enc.decode(r.model)
        dist = int((tiling != problem.closest_to).sum())
        if dist != r.cost:  # the decoder and the soft clauses disagree: a bug, never a result
            raise InternalError(f"MaxSAT cost {r.cost} differs from the Hamming distance {dist} of its tiling")
        stats["lower_bound"] = dist
        return Solution(Status.OPTIMAL, tiling, "maxsat", r.solver, seed, time.perf_counter() - t0,
                        objective=dist, stats=stats)
    if r.status is Status.UNSAT:
        # Certify infeasibility with a proof-logging SAT run on the same hard clauses.
        sat = solve_sat(dataclasses.replace(problem, closest_to=None), deadline=deadline, seed=seed)
        if sat.status is Status.UNSAT:
            return sat.replace(method="maxsat", time_s=time.perf_counter() - t0,
                               stats={**stats, **sat.stats}).with_note(f"{r.solver} found the hard clauses unsatisfiable")
        if sat.status is Status.SAT:  # cannot happen; never report a wrong UNSAT
            raise InternalError(f"{r.solver} said unsatisfiable but {sat.solver} found a tiling")
        return Solution(Status.UNKNOWN, None, "maxsat", r.solver, seed, time.perf_counter() - t0,
                        reason=f"{r.solver} found no tiling; certifying it ran out of time", stats=stats)
    return Solution(Status.UNKNOWN, None, "maxsat", r.solver, seed, time.perf_counter() - t0, reason=r.reason,
                    stats=stats)


def solve_cpsat(
    problem: DappledProblem,
    *,
    deadline: Deadline = NO_LIMIT,
    num_workers: int = DEFAULT_CPSAT_WORKERS,
    seed: int | None = None,
    hint: bool = True,
) -> Solution:
    """Solve (or, with ``closest_to``, optimise) a dappled problem with OR-tools CP-SAT.

    Same semantics as :func:`solve_sat` / :func:`solve_maxsat`: the model shares the
    CNF encoding's clauses, counts are linear constraints and ``closest_to`` is the
    objective (§6 item 3). CP-SAT gives no DRAT proof; its UNSAT is CP-SAT's word.

    Parameters
    ----------
    hint : bool
        Hint the target tiling to CP-SAT (with ``closest_to``).

    Examples
    --------
    >>> s = solve_cpsat(DappledProblem.from_strings("5x4", ["H0=2", "V1=2"]), seed=1)
    >>> s.status.value, s.tiling.shape
    ('sat', (4, 5))
    """
    _check_problem(problem)
    t0 = time.perf_counter()
    try:
        m = build_cpsat(problem, deadline=deadline)
    except TimeLimitReached as exc:
        return Solution(Status.UNKNOWN, None, "cpsat", "cp-sat", seed, time.perf_counter() - t0, reason=str(exc))
    stats = _enc_stats(m.encoding, time.perf_counter() - t0)
    if hint and problem.closest_to is not None:
        m.add_hint(problem.closest_to)
    r = solve_cp_model(m.model, m.variables, deadline=deadline, num_workers=num_workers, seed=seed,
                       has_objective=m.objective)
    stats.update({k: v for k, v in r.stats.items() if isinstance(v, (int, float, str))})
    if r.status.has_tiling:
        tiling = m.decode(r.model)
        obj = int((tiling != problem.closest_to).sum()) if m.objective else None
        if m.objective and obj != r.cost:
            raise InternalError(f"CP-SAT objective {r.cost} differs from the Hamming distance {obj}")
        return Solution(r.status, tiling, "cpsat", "cp-sat", seed, time.perf_counter() - t0, objective=obj,
                        reason=r.reason, stats=stats)
    return Solution(r.status, None, "cpsat", "cp-sat", seed, time.perf_counter() - t0, reason=r.reason, stats=stats)


class TilingEnumerator:
    """Iterate over the tilings of a dappled problem (see :func:`enumerate_tilings`).

    After (or during) iteration, :attr:`count` is the number yielded so far and
    :attr:`complete` is True once every tiling has been seen.
    """

    def __init__(self, problem: DappledProblem, limit: int | None, deadline: Deadline, solver: str) -> None:
        _check_problem(problem)
        self.problem = problem
        self.encoding = encode_cnf(problem)
        self._enum = ModelEnumerator(self.encoding.hard, self.encoding.projection(), solver=solver, limit=limit,
                                     deadline=deadline)

    def __iter__(self) -> Iterator[np.ndarray]:
        for model in self._enum:
            yield self.encoding.decode(model)

    @property
    def count(self) -> int:
        return self._enum.count

    @property
    def complete(self) -> bool:
        return self._enum.complete

    @property
    def reason(self) -> str | None:
        return self._enum.reason


def enumerate_tilings(
    problem: DappledProblem,
    limit: int | None = None,
    *,
    deadline: Deadline = NO_LIMIT,
    solver: str = DEFAULT_SAT_SOLVER,
) -> TilingEnumerator:
    """Every tiling of ``problem`` (``closest_to`` ignored), each once.

    The paper notes (§1) that enumeration is straightforward but exponential; this one
    uses blocking clauses over the grid variables, so it suits small grids.

    Examples
    --------
    >>> tilings = list(enumerate_tilings(DappledProblem.from_strings("3x1", ["H0=2"])))
    >>> len(tilings)
    7
    """
    return TilingEnumerator(problem, limit, deadline, solver)


def count_by_enumeration(
    problem: DappledProblem,
    *,
    deadline: Deadline = NO_LIMIT,
    limit: int | None = None,
    solver: str = DEFAULT_SAT_SOLVER,
    progress: Progress | bool = False,
) -> CountResult:
    """Count tilings by enumeration (:func:`tilesolve.engine.sat.count_models` on the CNF,
    projected on the grid variables): exact, or ``unknown`` with ``stats["found"]`` a lower bound.

    Parameters
    ----------
    progress : Progress or bool
        Where the tilings found so far are counted (:func:`tilesolve.progress.as_progress`).

    Examples
    --------
    On a 2x2 grid no run of three fits, so all 16 tilings satisfy ``{H0^2, V1^2}``:

    >>> count_by_enumeration(DappledProblem.from_strings("2x2", ["H0=2", "V1=2"])).value
    16
    """
    _check_problem(problem)
    enc = encode_cnf(problem)
    with as_progress(progress).task("counting by enumeration", unit="tiling") as bar:
        return count_models(enc.hard, enc.projection(), solver=solver, deadline=deadline, limit=limit,
                            on_model=bar.set)
