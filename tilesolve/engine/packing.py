"""Solver routes for tile packings (class notes §5.5) over one CNF encoding.

``sat``
    The full problem (:func:`tilesolve.encodings.packing.encode_packing`). With pinned tiles
    its ``unsat`` carries a checked DRAT proof.
``cpsat``
    The same encoding in OR-tools CP-SAT, native exactly-one constraints.

The searches that combine constructions with SAT (``hybrid``, ``lift``, ``recursive``) live
one layer up, in :mod:`tilesolve.families.packing_search`; they use :func:`run_packing_sat` and
:func:`check_search_size` from here.
"""

from __future__ import annotations

import time

import numpy as np

from tilesolve._random import rng_from_seed
from tilesolve.deadline import Deadline, TimeLimitReached
from tilesolve.errors import InternalError, InvalidProblem
from tilesolve.model.packing import PackingProblem
from tilesolve.model.run import RunOptions
from tilesolve.model.solution import Solution, Status

__all__ = [
    "PACKING_SAT_SOLVER",
    "MAX_PLACEMENTS",
    "check_search_size",
    "run_packing_sat",
    "packing_stats",
    "unknown_solution",
    "solve_sat",
    "solve_cpsat",
]

#: SAT solver of the packing routes. Glucose 4.2 stops by ``interrupt()``, so one seeded run is
#: deterministic (the same seed gives the same packing); CaDiCaL's conflict-budget slices are
#: sized from wall-clock rates and are not. Both show heavy-tailed run times on corner C = 3.
PACKING_SAT_SOLVER = "glucose42"


#: Most placement variables (cell, tile) a solver route builds: the full encoding of the
#: ``C = 6`` set (1,296 tiles, ~1.7 million placements, ~10 million clauses). Larger searches
#: are refused before any clause is built. The ``lift`` route needs far fewer placements
#: (``cells * k**4``), so it reaches ``C = 8`` and beyond.
MAX_PLACEMENTS = 1296 * 1296


def estimated_size(placements: int) -> tuple[int, int]:
    """Rough ``(variables, clauses)`` of a packing encoding with ``placements`` placement
    variables: about six clauses per placement (four links to its colours, one back, its
    share of the at-most-one constraints)."""
    return placements, 6 * placements


def check_search_size(problem: PackingProblem, placements: int | None = None, route: str = "sat") -> None:
    """Refuse searches too large to build, before anything is built.

    ``placements`` is the number of (cell, tile) variables the route would create
    (default: the full encoding, ``n_tiles**2``).
    """
    n = problem.n_tiles
    placements = n * n if placements is None else placements
    if placements > MAX_PLACEMENTS:
        v, c = estimated_size(placements)
        raise InvalidProblem(
            f"method {route!r} on {n:,} tiles (C={problem.colors}) needs about {v:,} variables and "
            f"{c:,} clauses; tilesolve builds up to {MAX_PLACEMENTS:,} placements. "
            + ("Use method euler/outer (Wang) or an odd C (corner)" if route == "lift" else
               "Use method lift (C with a small prime factor), euler/outer (Wang) or an odd C (corner)")
        )


def _random_phases(enc, rng) -> list[int]:
    """Prefer one random colour per feature: random-looking packings rather than the solver's
    default order (a phase is only a preference; the search still decides)."""
    ids = enc.feat_ids
    allowed = ids > 0
    pick = np.argmax(rng.random(ids.shape) * allowed, axis=1)
    pref = np.zeros(ids.shape, dtype=bool)
    pref[np.arange(ids.shape[0]), pick] = True
    return np.where(pref, ids, -ids)[allowed].tolist()


def run_packing_sat(enc, *, solver, deadline: Deadline, rng, with_proof: bool = False):
    from tilesolve.engine.sat import solve_cnf

    return solve_cnf(enc.clauses, solver=solver or PACKING_SAT_SOLVER, deadline=deadline,
                     with_proof=with_proof, seed=int(rng.integers(2**31)), phases=_random_phases(enc, rng))


def packing_stats(enc, r=None, **more) -> dict:
    out = {"variables": enc.n_vars, "clauses": len(enc.clauses), "placements": enc.n_placements}
    if r is not None:
        out["solve_s"] = round(r.runtime, 6)
        out.update({k: r.stats[k] for k in ("conflicts", "decisions") if k in r.stats})
    out.update(more)
    return out


def unknown_solution(method: str, solver: str | None, run: RunOptions, t0: float, reason: str | None, stats: dict,
                     tries: int | None = None) -> Solution:
    """An ``unknown`` answer of a packing search begun at ``t0``: the reason names the run's time
    limit when its deadline passed (unless it says so already, or says it was interrupted)."""
    limit, expired = run.deadline.time_limit, run.deadline.expired()
    if limit is not None and expired and not (reason or "").startswith(("interrupted", "time limit of")):
        reason = f"time limit of {limit:.3g} s reached"
    if tries is not None:
        reason = f"{reason} after {tries} attempt(s)"
    return Solution(Status.UNKNOWN, None, method, solver, run.seed, time.perf_counter() - t0, reason=reason,
                    stats=stats)


# --------------------------------------------------------------------------- full problem


def solve_sat(problem: PackingProblem, run: RunOptions) -> Solution:
    """The full encoding (the seed picks the tile pinned at the origin and preferred phases)."""
    from tilesolve.encodings.registry import encode
    from tilesolve.engine.certificates import unsat_solution

    check_search_size(problem)
    t0 = time.perf_counter()
    deadline, seed, solver = run.deadline, run.seed, run.solver
    rng = rng_from_seed(seed)
    anchor = None if problem.fixed else (int(rng.integers(problem.n_tiles)) if seed is not None else 0)
    try:
        enc = encode("packing-cnf", problem, {"anchor_tile": anchor}, deadline=deadline)
    except TimeLimitReached as exc:
        return unknown_solution("sat", solver or PACKING_SAT_SOLVER, run, t0, str(exc), {})
    encode_s = time.perf_counter() - t0
    if deadline.expired():
        return unknown_solution("sat", solver or PACKING_SAT_SOLVER, run, t0, "time limit reached while encoding",
                                packing_stats(enc, encode_s=round(encode_s, 6)))
    r = run_packing_sat(enc, solver=solver, deadline=deadline, rng=rng, with_proof=bool(problem.fixed))
    stats = packing_stats(enc, r, encode_s=round(encode_s, 6))
    if r.status is Status.SAT:
        return Solution(Status.SAT, enc.decode(r.model), "sat", r.solver, seed, time.perf_counter() - t0, stats=stats)
    if r.status is Status.UNSAT:
        if not problem.fixed:  # the anchor only breaks symmetry: an UNSAT here would be a bug
            raise InternalError("the unpinned packing encoding was reported unsatisfiable")
        return unsat_solution(enc.clauses, r, method="sat", seed=seed, t0=t0, stats=stats, check_proof=True,
                              deadline=deadline, encoding=enc.named)
    return unknown_solution("sat", r.solver, run, t0, r.reason, stats)


def solve_cpsat(problem: PackingProblem, run: RunOptions) -> Solution:
    """The full encoding in CP-SAT (``run.workers`` parallel workers, default 2)."""
    from tilesolve.encodings.packing import build_cpsat_packing
    from tilesolve.engine.cpsat import DEFAULT_CPSAT_WORKERS, solve_cp_model

    check_search_size(problem, route="cpsat")
    t0 = time.perf_counter()
    deadline, seed = run.deadline, run.seed
    anchor = None if problem.fixed else (int(rng_from_seed(seed).integers(problem.n_tiles)) if seed is not None else 0)
    try:
        model, place, enc = build_cpsat_packing(problem, anchor_tile=anchor, deadline=deadline)
    except TimeLimitReached as exc:
        return unknown_solution("cpsat", "cp-sat", run, t0, str(exc), {})
    stats = packing_stats(enc, encode_s=round(time.perf_counter() - t0, 6))
    r = solve_cp_model(model, place, deadline=deadline, num_workers=run.workers or DEFAULT_CPSAT_WORKERS, seed=seed)
    stats.update({k: v for k, v in r.stats.items() if k in ("conflicts", "branches", "workers")})
    if r.status is Status.SAT:
        return Solution(Status.SAT, enc.decode(r.model), "cpsat", "cp-sat", seed, time.perf_counter() - t0, stats=stats)
    if r.status is Status.UNSAT and not problem.fixed:
        raise InternalError("the unpinned packing model was reported infeasible")
    if r.status is Status.UNSAT:
        return Solution(Status.UNSAT, None, "cpsat", "cp-sat", seed, time.perf_counter() - t0, reason=r.reason,
                        stats=stats)
    return unknown_solution("cpsat", "cp-sat", run, t0, r.reason, stats)
