"""Tile packings end to end (class notes §5.5): one facade over constructions and solvers.

:func:`solve` looks the method up in :data:`SOLVERS` (so the CLI's ``--method`` choices come
from its keys), runs it, and checks every packing it returns with the independent verifier
:func:`tilesolve.verify.packing.packing_violations`; :func:`count` counts all packings for
``C = 2`` with or without symmetry reduction.

Methods
-------
``euler``
    Eulerian constructions over Wei's 1D packing: the Wang outer product (§5.5.2, Fig. 5.10,
    closed-form tile positions) and, for odd ``C``, the corner packing
    ``a[i][j] = s[(j + i(i-1)/2) mod C**2]`` (a 2D de Bruijn torus).
``outer``
    The same constructions over random Eulerian circuits (seeded): varied, but still
    structured (a Wang outer product has equal W/E sequences in every row).
``known``
    The notes' published C = 4 packings (Figs. 5.11, 5.12), under a random symmetry when seeded.
``sat``
    CaDiCaL on :func:`tilesolve.encodings.packing.encode_packing`: random-looking packings
    (the seed picks the tile pinned at the origin, the solver seed and preferred phases);
    honours pinned tiles; ``unsat`` comes with a checked DRAT proof.
``cpsat``
    OR-tools CP-SAT on the same encoding with native exactly-one constraints.
``hybrid``
    Wang only: random Eulerian N/S edge columns, then SAT for the E/W edges and the tiles;
    random-looking C = 4 Wang packings in about a second (plain ``sat`` does not finish C = 4
    in 90 s).

Examples
--------
>>> from tilesolve.model.packing import PackingProblem
>>> s = solve(PackingProblem("corner", 2), method="sat", seed=1)
>>> s.status.value, s.tiling.shape
('sat', (4, 4))
>>> count("corner", 2).value, count("corner", 2, up_to_symmetry=True).value
(32, 1)
"""

from __future__ import annotations

import time
from typing import Callable

import numpy as np

from tilesolve._random import rng_from_seed
from tilesolve.engine.routes import lookup, verified
from tilesolve.errors import MethodNotApplicable
from tilesolve.model.packing import PackingProblem
from tilesolve.model.solution import Solution, Status
from tilesolve.verify.packing import packing_violations

__all__ = ["SOLVERS", "METHODS", "PACKING_SAT_SOLVER", "solve", "count", "auto_method", "verify_solution"]

#: SAT solver of the ``sat`` route. Glucose 4.2 stops by ``interrupt()``, so one seeded run is
#: deterministic (the same seed gives the same packing); CaDiCaL's conflict-budget slices are
#: sized from wall-clock rates and are not. Both show heavy-tailed run times on corner C = 3.
PACKING_SAT_SOLVER = "glucose42"


def _pin_by_translation(problem: PackingProblem, grid: np.ndarray, method: str) -> np.ndarray:
    """Constructions ignore pins; one pin can always be met by translating the torus."""
    if not problem.fixed:
        return grid
    pins = set(problem.fixed)
    if len(pins) > 1:
        raise MethodNotApplicable(f"method {method!r} can honour one pinned tile (by translation), "
                                  f"not {len(pins)}; use method 'sat'")
    (r, c, t), = pins
    r0, c0 = np.argwhere(grid == t)[0]
    return np.roll(grid, (r - int(r0), c - int(c0)), axis=(0, 1))


def _euler(problem: PackingProblem, *, seed=None, time_limit=None, workers=None, progress=False, solver=None) -> Solution:
    from tilesolve.constructive.packing import corner_packing_odd, wang_packing

    t0 = time.perf_counter()
    if problem.kind == "wang":
        g = wang_packing(problem.colors, problem.colors_v)
    else:
        g = corner_packing_odd(problem.colors)
    g = _pin_by_translation(problem, g, "euler")
    return Solution(Status.SAT, g, method="euler", seed=seed, time_s=time.perf_counter() - t0)


def _outer(problem: PackingProblem, *, seed=None, time_limit=None, workers=None, progress=False, solver=None) -> Solution:
    from tilesolve.constructive.packing import corner_packing_odd, wang_packing

    t0 = time.perf_counter()
    rng = rng_from_seed(seed)
    if problem.kind == "wang":
        g = wang_packing(problem.colors, problem.colors_v, seed=rng)
    else:
        g = corner_packing_odd(problem.colors, seed=rng)
    g = _pin_by_translation(problem, g, "outer")
    return Solution(Status.SAT, g, method="outer", seed=seed, time_s=time.perf_counter() - t0)


def _known(problem: PackingProblem, *, seed=None, time_limit=None, workers=None, progress=False, solver=None) -> Solution:
    from tilesolve.constructive.packing_known import known_packing

    t0 = time.perf_counter()
    if problem.colors_v is not None and problem.colors_v != problem.colors:
        raise MethodNotApplicable("the notes publish no packing with C_h != C_v; use method 'outer' or 'sat'")
    fig, g = known_packing(problem.kind, problem.colors, seed=seed)
    g = _pin_by_translation(problem, g, "known")
    note = f"the packing of the class notes' {fig}" + (" under a random symmetry" if seed is not None else "")
    return Solution(Status.SAT, g, method="known", seed=seed, time_s=time.perf_counter() - t0, notes=(note,))


def _enc_for(problem: PackingProblem, seed, *, amo_tiles: bool = True):
    from tilesolve.encodings.packing import encode_packing

    anchor = None if problem.fixed else int(rng_from_seed(seed).integers(problem.n_tiles)) if seed is not None else 0
    return encode_packing(problem, anchor_tile=anchor, amo_tiles=amo_tiles)


def _sat(problem: PackingProblem, *, seed=None, time_limit=None, workers=None, progress=False, solver=None) -> Solution:
    from tilesolve.engine.certificates import unsat_solution
    from tilesolve.engine.result import Deadline
    from tilesolve.engine.sat import solve_cnf

    t0 = time.perf_counter()
    deadline = Deadline(time_limit)
    enc = _enc_for(problem, seed)
    stats = {"variables": enc.n_vars, "clauses": len(enc.clauses), "encode_s": round(time.perf_counter() - t0, 6)}
    phases = None
    if seed is not None:
        # Prefer a random arrangement: random-looking packings rather than the solver's default order.
        perm = rng_from_seed(seed + 1).permutation(problem.n_tiles)
        pv = enc.place_vars
        pref = np.zeros(pv.shape, dtype=bool)
        pref[np.arange(pv.shape[0]), perm] = True
        phases = np.where(pref, pv, -pv).ravel().tolist()
    r = solve_cnf(enc.clauses, solver=solver or PACKING_SAT_SOLVER, time_limit=deadline.remaining(),
                  with_proof=bool(problem.fixed), seed=seed, phases=phases)
    stats["solve_s"] = round(r.runtime, 6)
    for k in ("conflicts", "decisions"):
        if k in r.stats:
            stats[k] = r.stats[k]
    if r.status is Status.SAT:
        return Solution(Status.SAT, enc.decode(r.model), "sat", r.solver, seed, time.perf_counter() - t0, stats=stats)
    if r.status is Status.UNSAT:
        if not problem.fixed:  # the anchor only breaks symmetry: an UNSAT here would be a bug
            raise AssertionError("internal error: the unpinned packing encoding was reported unsatisfiable")
        rem = deadline.remaining()
        return unsat_solution(enc.clauses, r, method="sat", seed=seed, t0=t0, stats=stats, check_proof=True,
                               proof_time_limit=None if rem is None else max(rem, 1.0))
    reason = r.reason
    if time_limit is not None and deadline.expired() and "interrupted" not in (reason or ""):
        reason = f"time limit of {time_limit:.3g} s reached (encoding included)"
    return Solution(Status.UNKNOWN, None, "sat", r.solver, seed, time.perf_counter() - t0, reason=reason, stats=stats)


def _cpsat(problem: PackingProblem, *, seed=None, time_limit=None, workers=None, progress=False, solver=None) -> Solution:
    from tilesolve.encodings.packing import build_cpsat_packing
    from tilesolve.engine.cpsat import DEFAULT_CPSAT_WORKERS, solve_cp_model

    t0 = time.perf_counter()
    problem.check_search_size()
    anchor = None if problem.fixed else (int(rng_from_seed(seed).integers(problem.n_tiles)) if seed is not None else 0)
    model, place, enc = build_cpsat_packing(problem, anchor_tile=anchor)
    stats = {"variables": enc.n_vars, "encode_s": round(time.perf_counter() - t0, 6)}
    rem = None if time_limit is None else max(0.0, time_limit - (time.perf_counter() - t0))
    r = solve_cp_model(model, place, time_limit=rem, num_workers=workers or DEFAULT_CPSAT_WORKERS, seed=seed)
    stats.update({k: v for k, v in r.stats.items() if k in ("conflicts", "branches", "workers")})
    if r.status is Status.SAT:
        return Solution(Status.SAT, enc.decode(r.model), "cpsat", "cp-sat", seed, time.perf_counter() - t0, stats=stats)
    if r.status is Status.UNSAT and not problem.fixed:
        raise AssertionError("internal error: the unpinned packing model was reported infeasible")
    reason = r.reason
    if r.status is Status.UNKNOWN and time_limit is not None and "interrupted" not in (reason or ""):
        reason = f"time limit of {time_limit:.3g} s reached (model building included)"
    return Solution(r.status, None, "cpsat", "cp-sat", seed, time.perf_counter() - t0, reason=reason, stats=stats)


def _hybrid(problem: PackingProblem, *, seed=None, time_limit=None, workers=None, progress=False,
            solver=None) -> Solution:
    """Wang only: each column's N/S edges are a random Eulerian circuit (so every column holds
    each vertical domino once); SAT colours the E/W edges and places the tiles. The packing is
    not an outer product (the columns differ and the rows are solver-built). A column choice
    that admits no completion is not a proof of anything: the route draws new columns until
    the time limit (status ``unknown``)."""
    from tilesolve.constructive.packing import domino_sequence
    from tilesolve.encodings.packing import encode_packing, fix_horizontal_edges
    from tilesolve.engine.result import Deadline
    from tilesolve.engine.sat import solve_cnf

    if problem.kind != "wang":
        raise MethodNotApplicable("method 'hybrid' builds Wang packings; use 'sat', 'cpsat', 'euler' or 'known' "
                                  "for corner tiles")
    if problem.fixed:
        raise MethodNotApplicable("method 'hybrid' fixes the N/S edges and cannot honour pinned tiles; use 'sat'")
    problem.check_search_size()
    t0 = time.perf_counter()
    deadline = Deadline(time_limit)
    rng = rng_from_seed(seed)
    rows, cols = problem.shape
    attempts = 0
    stats: dict = {}
    while True:
        attempts += 1
        h = np.stack([domino_sequence(problem.colors, rng) for _ in range(cols)], axis=1)
        enc = encode_packing(problem, anchor_tile=None)
        fix_horizontal_edges(enc, h)
        stats = {"variables": enc.n_vars, "clauses": len(enc.clauses), "attempts": attempts}
        r = solve_cnf(enc.clauses, solver=solver or PACKING_SAT_SOLVER, time_limit=deadline.remaining(),
                      seed=int(rng.integers(2**31)))
        if r.status is Status.SAT:
            return Solution(Status.SAT, enc.decode(r.model), "hybrid", r.solver, seed, time.perf_counter() - t0,
                            stats=stats)
        if r.status is Status.UNKNOWN or deadline.expired():
            reason = (f"time limit of {time_limit:.3g} s reached" if time_limit is not None else r.reason) + \
                     f" after {attempts} column choice(s)"
            return Solution(Status.UNKNOWN, None, "hybrid", r.solver, seed, time.perf_counter() - t0,
                            reason=reason, stats=stats)


#: Packing routes by name. ``"auto"`` is not an entry: it picks one (see :func:`auto_method`).
SOLVERS: dict[str, Callable[..., Solution]] = {
    "euler": _euler,
    "outer": _outer,
    "known": _known,
    "sat": _sat,
    "cpsat": _cpsat,
    "hybrid": _hybrid,
}
METHODS: tuple[str, ...] = ("auto",) + tuple(SOLVERS)


def auto_method(problem: PackingProblem) -> str:
    """The route ``"auto"`` takes.

    Pinned tiles (more than one) need a solver. Otherwise Wang sets with C <= 3 and the corner
    set with C = 2 get a random-looking solver-built packing (SAT, well under a second); larger
    Wang sets the outer product; odd corner sets the de Bruijn construction (SAT on corner C = 3
    takes 1-40 s, heavy-tailed: ask for it with method 'sat'); C = 4 the notes' packings; the
    corner set with C = 6 a SAT search, which may end ``unknown``; even C >= 8 corner sets are
    refused (no construction is known, and the search is too large).
    """
    c = problem.colors
    square = problem.colors_v is None or problem.colors_v == problem.colors
    if len(set(problem.fixed)) > 1 or (square and (c == 2 or (c == 3 and problem.kind == "wang"))):
        return "sat"
    if problem.kind == "wang":
        return "outer"
    if c % 2 == 1:
        return "outer"
    if c == 4:
        return "known"
    return "sat"


def verify_solution(problem: PackingProblem, sol: Solution) -> Solution:
    """Run the independent verifier on a returned packing; a failure is a bug, never 'sat'."""
    return verified(
        sol,
        lambda grid: packing_violations(grid, problem.kind, problem.colors, colors_v=problem.colors_v,
                                        fixed=problem.fixed),
        "packing",
    )


def solve(
    problem: PackingProblem,
    *,
    method: str | Callable[..., Solution] = "auto",
    seed: int | None = None,
    time_limit: float | None = None,
    workers: int | None = None,
    progress: bool = False,
    solver: str | None = None,
) -> Solution:
    """Find a tile packing (or prove that the pinned tiles allow none) and verify it.

    Parameters
    ----------
    problem : PackingProblem
    method : {"auto", "euler", "outer", "known", "sat", "cpsat", "hybrid"} or callable
    seed : int, optional
        The same seed gives the same packing.
    time_limit : float, optional
        Seconds for the solver routes; expiry gives status ``unknown``.
    workers : int, optional
        CP-SAT workers (default 2).
    solver : str, optional
        PySAT solver of the ``sat`` route (default :data:`PACKING_SAT_SOLVER`).

    Returns
    -------
    Solution
        ``tiling`` is the packing grid (tile indices per eq. 2.1 / 2.5), verified.

    Raises
    ------
    MethodNotApplicable
        E.g. ``euler`` for an even number of corner colours; the message names a route that works.
    InvalidProblem
        Absurd sizes for a solver route (refused before any clause is built).
    """
    t0 = time.perf_counter()
    runner, name = lookup(method, SOLVERS, lambda: auto_method(problem))
    if name in ("sat", "cpsat", "hybrid"):
        problem.check_search_size()
    sol = runner(problem, seed=seed, time_limit=time_limit, workers=workers, progress=progress, solver=solver)
    sol = verify_solution(problem, sol)
    notes = (f"auto chose {name!r}",) if method == "auto" else ()
    return sol.replace(notes=notes + sol.notes, time_s=time.perf_counter() - t0, seed=seed)


def count(kind: str, colors: int, *, up_to_symmetry: bool = False, time_limit: float | None = None):
    """Count all packings (C = 2): the notes publish 32 corner and 203,520 Wang packings.

    With ``up_to_symmetry`` the packings are counted up to translation, rotation, reflection
    and colour permutation (§5.5.3): 1 for corner tiles (as published), 911 for Wang tiles
    (computed here; the notes give no number). Returns a
    :class:`~tilesolve.constructive.packing_count.PackingCount`.
    """
    from tilesolve.constructive.packing_count import count_packings

    PackingProblem(kind, colors)  # checks kind and colours
    return count_packings(kind, colors, up_to_symmetry=up_to_symmetry, time_limit=time_limit)
