"""The one SAT route driver every family shares (DESIGN.md, "One pipeline").

A family's ``sat`` route builds its encoding (the protocol of
:class:`tilesolve.encodings.Encoding`) and calls :func:`sat_route`, which runs PySAT under the
run's deadline and turns the backend's :class:`~tilesolve.engine.result.Result` into a
:class:`~tilesolve.model.solution.Solution`:

- ``sat``: the decoded tiling (the pipeline then verifies it independently);
- ``unsat``: only with a DRAT proof checked by :mod:`tilesolve.verify.drat` whatever its size
  (:mod:`tilesolve.engine.certificates`), bound to the SHA-256 of the exact CNF
  (``stats["cnf_sha256"]``) and to the named encoding that re-derives it from the problem
  (``stats["encoding"]``, when the encoding was built by :func:`tilesolve.encodings.registry.encode`),
  and written to the ``--proof-dir`` when one is set; a
  *restricted* formula (one that searches part of the space, e.g. the lifted packings)
  proves nothing by being unsatisfiable, so its unsat is reported ``unknown``;
- ``unknown``: time limit or Ctrl-C, never ``unsat``.
"""

from __future__ import annotations

import time
from typing import Any, Mapping, Sequence

from tilesolve.model.solution import Solution, Status

__all__ = ["sat_route", "encoding_stats"]


def encoding_stats(encoding: Any, encode_s: float) -> dict:
    """Size figures of an encoding for ``Solution.stats``."""
    return {"variables": int(encoding.n_vars), "clauses": len(encoding.hard), "encode_s": round(encode_s, 6)}


def sat_route(
    encoding: Any,
    run: Any,
    *,
    method: str = "sat",
    solver: str,
    t0: float,
    phases: Sequence[int] | None = None,
    proof: bool = True,
    notes: tuple[str, ...] = (),
    options: Mapping[str, int] | None = None,
    seeded_phases: bool = True,
) -> Solution:
    """Decide ``encoding`` with a PySAT solver within ``run``'s deadline.

    Parameters
    ----------
    encoding
        Has ``hard`` (the clauses), ``n_vars``, ``decode(model)`` and ``restricted``; ``named``
        when :func:`tilesolve.encodings.registry.encode` built it (an unsat answer records it).
    run : tilesolve.family.RunOptions
        Seed (the solver's random seed) and deadline.
    method : str
        Recorded in the Solution.
    solver : str
        PySAT solver name.
    t0 : float
        ``time.perf_counter()`` when the route started (encoding included in ``time_s``).
    phases : sequence of int, optional
        Preferred literals (solver phases), e.g. a target tiling or seeded random colours.
    proof : bool
        Log a DRAT proof (checked on unsat). A restricted formula never logs one.
    notes : tuple of str
        Notes to attach to the Solution.
    options : mapping of str to int, optional
        The solver's own settings (CaDiCaL's, e.g. ``{"phase": 0}``).
    seeded_phases : bool
        Let the seed draw random preferred phases (:func:`tilesolve.engine.sat.seeded_phases`).
        CaDiCaL holds such phases for the whole search, above the phases it saves; False keeps
        the solver's own phase heuristics (``options`` and ``phases`` still apply).
    """
    from tilesolve.engine.certificates import unsat_solution
    from tilesolve.engine.sat import solve_cnf

    restricted = bool(getattr(encoding, "restricted", False))
    stats = encoding_stats(encoding, time.perf_counter() - t0)
    if run.deadline.expired():
        return Solution(Status.UNKNOWN, None, method, solver, run.seed, time.perf_counter() - t0,
                        reason=f"time limit of {run.deadline.time_limit:.3g} s reached while encoding",
                        notes=notes, stats=stats)
    r = solve_cnf(encoding.hard, solver=solver, deadline=run.deadline, with_proof=proof and not restricted,
                  seed=run.seed if seeded_phases else None, phases=phases, options=options)
    stats["solve_s"] = round(r.runtime, 6)
    stats.update({k: r.stats[k] for k in ("conflicts", "decisions", "propagations", "restarts") if k in r.stats})
    notes = notes + tuple(r.stats.get("notes", ()))
    if r.status is Status.SAT:
        return Solution(Status.SAT, encoding.decode(r.model), method, r.solver, run.seed, time.perf_counter() - t0,
                        notes=notes, stats=stats)
    if r.status is Status.UNSAT and restricted:
        return Solution(Status.UNKNOWN, None, method, r.solver, run.seed, time.perf_counter() - t0,
                        reason="the restricted search space holds no solution (this proves nothing about the "
                               "full problem)", notes=notes, stats=stats)
    if r.status is Status.UNSAT:
        sol = unsat_solution(encoding.hard, r, method=method, seed=run.seed, t0=t0, stats=stats, check_proof=True,
                             deadline=run.deadline, encoding=getattr(encoding, "named", None))
        return sol.replace(notes=sol.notes + notes)
    reason = r.reason
    if run.deadline.time_limit is not None and run.deadline.expired() and not (reason or "").startswith(
            ("interrupted", "time limit of")):
        reason = f"time limit of {run.deadline.time_limit:.3g} s reached"
    return Solution(Status.UNKNOWN, None, method, r.solver, run.seed, time.perf_counter() - t0, reason=reason,
                    notes=notes, stats=stats)
