"""OR-tools CP-SAT backend: time limit, workers, seed, Ctrl-C (STYLE.md §3, backend interface).

Generic over families: it solves any ``CpModel`` and reports the values of the Boolean
variables the caller names.

Seeds
-----
CP-SAT's presolve often finds a first solution of a satisfaction model by itself
("trivial exploration"), the same whatever ``random_seed`` says. So a seeded satisfaction
run hints every reported variable with a value drawn from the seed (unless the model
carries its own hint, e.g. a target tiling) and turns presolve off, so that the hint steers
the search: different seeds then give different solutions where there are many. A seeded
satisfaction run uses one worker, so the same seed gives the same solution (one worker is as
fast as several on these hinted models; CP-SAT's interleaved search, the other deterministic
mode, aborts the process on some trivially decided models with presolve off, ortools 9.15:
"Check failed: heuristics.fixed_search != nullptr"). Optimisation runs keep presolve and the parallel
portfolio: their optimum value is exact, but which optimal solution is reported may differ
between runs with several workers (``num_workers=1`` repeats it exactly).

Infeasibility
-------------
SAT says unsat only with a checked proof (DESIGN.md), and CP-SAT logs none: an ``INFEASIBLE``
answer comes back as ``UNKNOWN`` whose reason starts with
:data:`tilesolve.engine.certificates.UNCERTIFIED`, flagged ``cpsat_infeasible`` in the stats.
The pipeline (:func:`tilesolve.family.run_route`) then certifies it with the family's ``sat``
route (a DRAT proof on the family's CNF encoding, checked), or leaves it ``unknown``.
"""

from __future__ import annotations

import time
from typing import Sequence

from tilesolve.deadline import NO_LIMIT, Deadline
from tilesolve.engine.certificates import UNCERTIFIED
from tilesolve.engine.result import Result, run_interruptible
from tilesolve.errors import BackendUnavailable, InvalidProblem
from tilesolve.model.solution import Status

__all__ = ["DEFAULT_CPSAT_WORKERS", "solve_cp_model", "cpsat_version"]

#: Two workers: the machines tilesolve targets share their cores; more can be asked for.
DEFAULT_CPSAT_WORKERS = 2


def cpsat_version() -> str:
    try:
        import ortools
    except ImportError as exc:  # pragma: no cover - ortools is a core dependency
        raise BackendUnavailable("OR-tools is not installed") from exc
    return ortools.__version__


def solve_cp_model(
    model,
    variables: Sequence,
    *,
    num_workers: int = DEFAULT_CPSAT_WORKERS,
    seed: int | None = None,
    has_objective: bool = False,
    core_search: bool | None = None,
    deadline: Deadline = NO_LIMIT,
) -> Result:
    """Solve a CP-SAT model and read back ``variables``.

    Parameters
    ----------
    model : ortools.sat.python.cp_model.CpModel
    variables : sequence of BoolVar
        Their values form :attr:`Result.model` (a list of bools).
    num_workers : int
    seed : int, optional
        ``random_seed``; for satisfaction models also the seeded hint (see "Seeds").
    has_objective : bool
        Report ``OPTIMAL`` (with ``cost``) rather than ``SAT`` when the search completes.
    core_search : bool, optional
        Force a core-based worker for optimisation (CP-SAT's portfolio of two workers has
        none, and then rarely proves optimality of closest-tiling objectives); default:
        on when ``has_objective``.
    deadline : Deadline, optional
        The whole run's deadline (what is left of it is ``max_time_in_seconds``; the reason
        names its limit): expiry gives ``UNKNOWN`` (no solution yet) or ``SAT`` (a solution,
        optimality not proved).

    Examples
    --------
    >>> from ortools.sat.python import cp_model
    >>> m = cp_model.CpModel(); a = m.new_bool_var("a"); b = m.new_bool_var("b")
    >>> _ = m.add_bool_or([a, b]); m.minimize(a + b)
    >>> r = solve_cp_model(m, [a, b], has_objective=True)
    >>> r.status.value, r.cost
    ('optimal', 1)
    """
    from ortools.sat.python import cp_model

    if num_workers < 1:
        raise InvalidProblem(f"num_workers must be >= 1, got {num_workers}")
    t0 = time.perf_counter()
    time_limit = deadline.time_limit
    solver = cp_model.CpSolver()
    prm = solver.parameters
    prm.num_workers = int(num_workers)
    if seed is not None:
        prm.random_seed = int(seed)
        if not has_objective:
            if not model.proto.solution_hint.vars:
                _seeded_hint(model, variables, seed, deadline)
            prm.cp_model_presolve = False
            prm.num_workers = 1  # deterministic (see "Seeds")
    if deadline.expired():
        return Result(Status.UNKNOWN, None, time.perf_counter() - t0, None, {"workers": num_workers},
                      solver="cp-sat", reason=f"time limit of {time_limit:.3g} s reached before CP-SAT started")
    if time_limit is not None:
        prm.max_time_in_seconds = max(deadline.remaining(), 0.0)
    if core_search is None:
        core_search = has_objective
    if core_search:
        if num_workers == 1:
            prm.optimize_with_core = True
        else:
            prm.subsolvers.append("core")
            prm.subsolvers.append("default_lp")
            for extra in ("no_lp", "max_lp", "quick_restart", "pseudo_costs")[: max(0, num_workers - 2)]:
                prm.subsolvers.append(extra)
    # CP-SAT's own SIGINT handling leaves SIGINT at its default action after the solve
    # (the next Ctrl-C kills Python; ortools 9.15): keep Python's handler and stop the
    # search ourselves instead.
    prm.catch_sigint_signal = False
    reason = None
    status, stop = run_interruptible(lambda: solver.solve(model), solver.stop_search, deadline)
    if stop == "interrupted":
        reason = "interrupted (Ctrl-C)"
    rt = time.perf_counter() - t0
    stats = {
        "wall_s": solver.wall_time,
        "conflicts": solver.num_conflicts,
        "branches": solver.num_branches,
        "workers": num_workers,
    }
    if status == cp_model.MODEL_INVALID:
        raise InvalidProblem(f"CP-SAT rejected the model: {model.validate()}")
    if status in (cp_model.OPTIMAL, cp_model.FEASIBLE):
        values = [bool(solver.boolean_value(v)) for v in variables]
        cost = int(round(solver.objective_value)) if has_objective else None
        if has_objective:
            stats["lower_bound"] = int(round(solver.best_objective_bound))
        if status == cp_model.OPTIMAL:
            st = Status.OPTIMAL if has_objective else Status.SAT
        else:
            st = Status.SAT
            reason = reason or (f"time limit of {time_limit:.3g} s reached before optimality was proved"
                                if has_objective else None)
        return Result(st, values, rt, None, stats, cost=cost, solver="cp-sat", reason=reason)
    if status == cp_model.INFEASIBLE:
        # CP-SAT logs no proof: its word is not an unsat answer (see "Infeasibility").
        return Result(Status.UNKNOWN, None, rt, None, {**stats, "cpsat_infeasible": True}, solver="cp-sat",
                      reason=f"{UNCERTIFIED} CP-SAT proved infeasibility, but it logs no proof to check")
    if reason is None:
        reason = (f"time limit of {time_limit:.3g} s reached while solving" if time_limit is not None
                  else "CP-SAT gave up")
    return Result(Status.UNKNOWN, None, rt, None, stats, solver="cp-sat", reason=reason)


def _seeded_hint(model, variables: Sequence, seed: int, deadline: Deadline) -> None:
    """Hint each of ``variables`` with a value drawn from ``seed`` (see "Seeds")."""
    from tilesolve._random import rng_from_seed

    bits = (rng_from_seed(seed).random(len(variables)) < 0.5).tolist()
    hint = model.proto.solution_hint
    step = 1 << 16
    for lo in range(0, len(variables), step):
        if deadline.expired():
            return  # a partial hint is still a hint; the solve call reports the time limit
        hint.vars.extend(v.index for v in variables[lo : lo + step])
        hint.values.extend(int(b) for b in bits[lo : lo + step])
