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
    SAT (:data:`~tilesolve.engine.packing.PACKING_SAT_SOLVER`) on
    :func:`tilesolve.encodings.packing.encode_packing`: random-looking packings (the seed
    picks the tile pinned at the origin, the solver seed and preferred colours); honours
    pinned tiles; ``unsat`` comes with a checked DRAT proof. Practical up to C = 3.
``cpsat``
    OR-tools CP-SAT on the same encoding with native exactly-one constraints.
``hybrid``
    Wang only: random Eulerian N/S edge columns, then SAT for the E/W edges and the tiles.
``lift``
    A packing over ``m`` colours repeated over the torus plus a ``k``-ary layer found by SAT
    (``C = m*k``): corner and Wang C = 4 in a fraction of a second, C = 6 in about a second,
    C = 8 in 10-20 s (:mod:`tilesolve.engine.packing`).
``recursive``
    A packing over ``C - 1`` colours pinned in the bottom-left corner, completed by SAT
    (Figs. 5.11-5.12).

Heavy-tailed searches (:data:`PORTFOLIO_ROUTES`) get :data:`~tilesolve.engine.portfolio.QUICK_S` seconds in-process;
if undecided, a portfolio of fresh seeds runs on both cores (``workers``) or on a Dask
cluster (``cluster``), with per-run budgets that double with every wave
(:mod:`tilesolve.engine.portfolio`).

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
from tilesolve.engine import packing as search
from tilesolve.engine.packing import PACKING_SAT_SOLVER
from tilesolve.engine.routes import lookup, verified
from tilesolve.errors import MethodNotApplicable
from tilesolve.model.packing import PackingProblem
from tilesolve.model.solution import Solution, Status
from tilesolve.verify.packing import packing_violations

__all__ = ["SOLVERS", "METHODS", "PACKING_SAT_SOLVER", "solve", "count", "auto_method", "verify_solution"]

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


#: Packing routes by name. ``"auto"`` is not an entry: it picks one (see :func:`auto_method`).
SOLVERS: dict[str, Callable[..., Solution]] = {
    "euler": _euler,
    "outer": _outer,
    "known": _known,
    "sat": search.solve_sat,
    "cpsat": search.solve_cpsat,
    "hybrid": search.solve_hybrid,
    "lift": search.solve_lift,
    "recursive": search.solve_recursive,
}
METHODS: tuple[str, ...] = ("auto",) + tuple(SOLVERS)


#: Routes whose run times are heavy-tailed: with more than one worker, or a cluster, a run
#: that does not decide within :data:`~tilesolve.engine.portfolio.QUICK_S` seconds is followed by a portfolio of seeds.
PORTFOLIO_ROUTES: tuple[str, ...] = ("sat", "hybrid", "lift", "recursive")


def auto_method(problem: PackingProblem) -> str:
    """The route ``"auto"`` takes.

    More than one pinned tile needs the full search (``sat``). Otherwise ``C = 2`` and Wang
    ``C = 3`` get a random-looking SAT-built packing; Wang ``C = 4, 6`` and even corner sets a
    lifted packing (seconds; corner ``C = 8`` 10-20 s); odd corner sets the de Bruijn
    construction; other Wang sets (``C = 5`` or ``>= 7``, or ``C_h != C_v``) the outer product.
    """
    c = problem.colors
    square = problem.colors_v is None or problem.colors_v == problem.colors
    if len(set(problem.fixed)) > 1 or (square and (c == 2 or (c == 3 and problem.kind == "wang"))):
        return "sat"
    if not square:
        return "outer"
    if problem.kind == "wang":
        return "lift" if c in (4, 6) else "outer"
    if c % 2 == 1:
        return "outer"
    return "lift"


def _run_route(problem, runner, name, *, seed, time_limit, workers, cluster, progress, solver) -> Solution:
    """Run one route; heavy-tailed searches escalate to a portfolio (module docstring)."""
    from tilesolve.engine.portfolio import escalate
    from tilesolve.engine.progress import ticker

    if name not in PORTFOLIO_ROUTES:
        with ticker(f"{name} packing", progress):
            return runner(problem, seed=seed, time_limit=time_limit, workers=workers, progress=progress, solver=solver)
    return escalate(runner, problem, name=f"{name} packing", seed=seed, time_limit=time_limit, workers=workers,
                    cluster=cluster, progress=progress, solver=solver)


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
    cluster=None,
    progress: bool = False,
    solver: str | None = None,
) -> Solution:
    """Find a tile packing (or prove that the pinned tiles allow none) and verify it.

    Parameters
    ----------
    problem : PackingProblem
    method : {"auto", "euler", "outer", "known", "sat", "cpsat", "hybrid", "lift", "recursive"} or callable
    seed : int, optional
        The same seed gives the same packing, except when a search escalates to a portfolio
        (then the note and ``Solution.seed`` name the seed that won; rerun it with
        ``workers=1`` to reproduce it).
    time_limit : float, optional
        Seconds for the solver routes; expiry gives status ``unknown``.
    workers : int, optional
        CP-SAT workers for ``cpsat`` (default 2); for the heavy-tailed searches
        (:data:`PORTFOLIO_ROUTES`), the local processes of the portfolio that starts when the
        first run takes longer than :data:`~tilesolve.engine.portfolio.QUICK_S` (default 2; ``1`` runs one seed only).
    cluster : str or distributed.Client, optional
        A Dask scheduler address (``tcp://host:8786``): the portfolio's runs go there instead.
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
    sol = _run_route(problem, runner, name, seed=seed, time_limit=time_limit, workers=workers, cluster=cluster,
                     progress=progress, solver=solver)
    sol = verify_solution(problem, sol)
    notes = (f"auto chose {name!r}",) if method == "auto" else ()
    return sol.replace(notes=notes + sol.notes, time_s=time.perf_counter() - t0,
                       seed=seed if sol.seed is None else sol.seed)


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
