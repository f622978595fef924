"""Packing searches that combine constructions with SAT (class notes §5.5).

They search a *restricted* space (some feature colours fixed by a construction), so an empty
space proves nothing: they retry with new random choices until the time limit (status
``unknown``), never ``unsat``. They sit above the engine because they use the constructions
of :mod:`tilesolve.constructive.packing`; the SAT calls go through
:func:`tilesolve.engine.packing.run_packing_sat`.

``hybrid``
    Wang only: the N/S edge columns are random Eulerian circuits; SAT colours the E/W edges.
``lift``
    A packing over ``C = m*k`` colours (``k`` the smallest prime factor of ``C``) whose
    colours are ``base + m*b``, where ``base`` is a packing over ``m`` colours repeated
    ``k**2`` times in each direction and ``b`` is a ``k``-ary layer found by SAT. The
    composite tile is the pair (base tile, layer tile), so the packing is valid exactly
    when, among the cells that share a base tile, the layer tiles are all different: a
    small search. This is the product idea of Hurlbert & Isaak's constructions of de Bruijn
    tori ("New constructions for de Bruijn tori", a ``k1*k2``-ary torus from a ``k1``-ary
    and a ``k2``-ary one) with the layer found by a solver instead of by a formula. Corner
    C = 4 and C = 8 packings, which took the notes' backtracking 280 CPU-days for C = 4,
    come out in well under a minute.
``recursive``
    Figs. 5.11-5.12: a packing over ``C - 1`` colours is pinned in the bottom-left corner
    and SAT completes it (the notes: "a solution for C colors can often be found faster by
    starting from a solution of C-1 colors").

Each route has the one route signature ``route(problem, run) -> Solution`` (``run`` a
:class:`~tilesolve.model.run.RunOptions`: seed, the run's deadline, solver), so that portfolio
workers (:func:`tilesolve.engine.portfolio.escalate`) run it as is.
"""

from __future__ import annotations

import time
from dataclasses import replace

import numpy as np

from tilesolve._random import rng_from_seed
from tilesolve.engine.packing import (
    PACKING_SAT_SOLVER,
    check_search_size,
    packing_stats,
    run_packing_sat,
    unknown_solution,
)
from tilesolve.errors import MethodNotApplicable
from tilesolve.model.packing import PackingProblem
from tilesolve.model.run import RunOptions
from tilesolve.model.solution import Solution, Status

__all__ = ["solve_hybrid", "solve_lift", "solve_recursive", "lift_factors", "lift_levels", "lift_domains", "embedding_pins"]


def _restricted_search(problem, method, make_domains, run: RunOptions) -> Solution:
    """Draw domains with ``make_domains(rng)`` and solve until a packing or the run's deadline;
    ``run.progress`` shows a line per level (a lift's base search is a level below, numbered
    down to 1, :func:`lift_levels`) and its attempts."""
    from tilesolve.encodings.packing import encode_packing

    t0 = time.perf_counter()
    deadline, seed, solver = run.deadline, run.seed, run.solver
    rng = rng_from_seed(seed)
    tries, stats, r = 0, {}, None
    level = f" level {lift_levels(problem.kind, problem.colors)}" if method == "lift" else ""  # 1: the lowest
    with run.progress.task(f"{method}{level}: {problem.colors} colours", unit=None) as bar:
        while True:
            tries += 1
            bar.note(f"attempt {tries}: drawing the restriction")
            domains = make_domains(rng)
            bar.note(f"attempt {tries}: SAT search")
            enc = encode_packing(problem, anchor_tile=None, domains=domains)
            r = run_packing_sat(enc, solver=solver, deadline=deadline, rng=rng)
            stats = packing_stats(enc, r, attempts=tries)
            if r.status is Status.SAT:
                return Solution(Status.SAT, enc.decode(r.model), method, r.solver, seed, time.perf_counter() - t0,
                                stats=stats)
            if r.status is Status.UNKNOWN or deadline.expired():
                return unknown_solution(method, r.solver, run, t0, r.reason, stats, tries)


def solve_hybrid(problem: PackingProblem, run: RunOptions) -> Solution:
    """Wang only: each column's N/S edges are a random Eulerian circuit (so every column holds
    each vertical domino once); SAT colours the E/W edges and places the tiles. The packing is
    not an outer product (the columns differ and the rows are solver-built)."""
    from tilesolve.constructive.packing import domino_sequence
    from tilesolve.encodings.packing import full_domains

    if problem.kind != "wang":
        raise MethodNotApplicable("method 'hybrid' builds Wang packings; use 'lift', 'sat' or 'euler' for corner tiles")
    if problem.fixed:
        raise MethodNotApplicable("method 'hybrid' fixes the N/S edges and cannot honour pinned tiles; use 'sat'")
    rows, cols = problem.shape
    check_search_size(problem, rows * cols * problem.tiles.cv**2, route="hybrid")

    def domains(rng):
        h = np.stack([domino_sequence(problem.colors, rng) for _ in range(cols)], axis=1)
        d = full_domains(problem)
        d[: rows * cols] = False
        d[np.arange(rows * cols), h.ravel()] = True  # H[r][c] is feature r*cols + c
        return d

    return _restricted_search(problem, "hybrid", domains, run)


def lift_factors(colors: int) -> tuple[int, int]:
    """``(m, k)`` with ``colors = m * k`` and ``k`` the smallest prime factor of ``colors``.

    >>> lift_factors(8), lift_factors(6), lift_factors(7)
    ((4, 2), (3, 2), (1, 7))
    """
    k = next(d for d in range(2, colors + 1) if colors % d == 0)
    return colors // k, k


def lift_levels(kind: str, colors: int) -> int:
    """How many SAT searches a lift to ``colors`` nests: one per level down to a base that is
    built (nothing below ``m = 1``; an odd corner base or a prime Wang base >= 5 is constructed,
    :func:`_base_packing`).

    >>> lift_levels("corner", 8), lift_levels("corner", 6), lift_levels("wang", 10), lift_levels("corner", 7)
    (3, 1, 1, 1)
    """
    m, _ = lift_factors(colors)
    if m == 1 or (kind == "corner" and m % 2 == 1) or (kind == "wang" and lift_factors(m)[0] == 1 and m >= 5):
        return 1
    return 1 + lift_levels(kind, m)


def lift_domains(problem: PackingProblem, base_features: np.ndarray | None, m: int) -> np.ndarray:
    """Feature domains of the lifted search: feature ``f`` may take the colours ``c`` with
    ``c mod m`` equal to the colour of the corresponding feature of the base packing (a
    packing over ``m`` colours, ``m**2 x m**2``, repeated over the torus). ``m = 1`` (no
    base) allows everything."""
    from tilesolve.encodings.packing import full_domains

    d = full_domains(problem)
    if base_features is None:
        return d
    rows, cols = problem.shape
    layers = d.shape[0] // (rows * cols)  # 2 for Wang (H, V), 1 for corner (P)
    rb = m * m
    base = np.asarray(base_features).reshape(layers, rb, rb)
    tiled = np.tile(base, (1, rows // rb, cols // rb)).ravel()
    colours = np.arange(d.shape[1])
    return d & (colours[None, :] % m == tiled[:, None])


def _base_packing(kind: str, m: int, rng, run: RunOptions):
    """A packing over ``m >= 2`` colours for :func:`solve_lift` (``None`` when its own search
    ran out of time): the odd corner construction, a random Wang outer product for primes
    >= 5, else a lifted search."""
    from tilesolve.constructive.packing import corner_packing_odd, wang_packing

    if kind == "corner" and m % 2 == 1:
        return corner_packing_odd(m, seed=rng)
    mm, _ = lift_factors(m)
    if kind == "wang" and mm == 1 and m >= 5:
        return wang_packing(m, seed=rng)
    return solve_lift(PackingProblem(kind, m), replace(run, seed=int(rng.integers(2**31)))).tiling


def solve_lift(problem: PackingProblem, run: RunOptions) -> Solution:
    """A packing over ``C = m*k`` colours as a base packing over ``m`` colours plus a ``k``-ary
    layer found by SAT (module docstring). Pins are honoured when the lifted space holds them."""
    from tilesolve.encodings.packing import features_of_packing

    if problem.kind == "wang" and problem.colors_v is not None and problem.colors_v != problem.colors:
        raise MethodNotApplicable("method 'lift' needs C_h = C_v; use 'outer' or 'sat'")
    m, k = lift_factors(problem.colors)
    rows, cols = problem.shape
    check_search_size(problem, rows * cols * k**4, route="lift")
    t0 = time.perf_counter()
    seed = run.seed
    base_info = []

    def domains(rng):
        if m == 1:
            return lift_domains(problem, None, 1)
        base = _base_packing(problem.kind, m, rng, run)
        if base is None:
            raise _NoBase()
        base_info.append(f"base packing over {m} colours, {k}-ary layer by SAT")
        return lift_domains(problem, features_of_packing(PackingProblem(problem.kind, m), base), m)

    try:
        sol = _restricted_search(problem, "lift", domains, run)
    except _NoBase:
        return unknown_solution("lift", PACKING_SAT_SOLVER, run, t0, f"no base packing over {m} colours found", {})
    if sol.tiling is not None and seed is not None and not problem.fixed:
        # A random symmetry (translation, rotation, reflection, colour permutation) hides the
        # base layer's colour classes: the classes c mod m map to unrelated colours.
        from tilesolve.constructive.packing import random_symmetry

        sol = sol.replace(tiling=random_symmetry(sol.tiling, problem.kind, problem.colors, seed=seed))
        base_info.append(base_info.pop() + ", then a random symmetry" if base_info else "a random symmetry")
    return sol.replace(notes=tuple(base_info[-1:]) + sol.notes) if base_info else sol


class _NoBase(Exception):
    """The base search of a lift ran out of time."""


def embedding_pins(sub_grid, kind: str, sub_colors: int, colors: int, at: tuple[int, int] | None = None):
    """Pins that place a packing over ``sub_colors`` colours inside a packing over ``colors``.

    The sub-packing's tiles keep their colours (a tile over ``C' < C`` colours is also a tile
    over ``C``), re-indexed by eq. 2.1 / 2.5. ``at`` is the top-left cell of the block; the
    default is the bottom-left corner, as in Figs. 5.11-5.12. The block needs its interior
    edges (or corners) to match, which a toroidal packing's do; its own wrap-around is not
    used.

    Examples
    --------
    >>> from tilesolve.constructive.packing import corner_packing_odd
    >>> pins = embedding_pins(corner_packing_odd(3), "corner", 3, 4)
    >>> len(pins), pins[0][:2]
    (81, (7, 0))
    """
    from tilesolve.model.tiles import TileSet

    sub = np.asarray(sub_grid, dtype=np.int64)
    small, big = TileSet(kind, sub_colors), TileSet(kind, colors)
    if sub_colors >= colors:
        raise MethodNotApplicable(f"an embedded packing needs fewer colours than {colors}, got {sub_colors}")
    n = colors * colors
    h = sub.shape[0]
    r0, c0 = (n - h, 0) if at is None else at
    if not (0 <= r0 <= n - h and 0 <= c0 <= n - sub.shape[1]):
        raise MethodNotApplicable(f"a {sub.shape[0]}x{sub.shape[1]} block does not fit at {(r0, c0)} in {n}x{n}")
    idx = big.index(*small.colors_of(sub))
    return tuple((r0 + r, c0 + c, int(idx[r, c])) for r in range(sub.shape[0]) for c in range(sub.shape[1]))


#: First per-attempt budget (seconds) of the ``recursive`` route; it doubles with every attempt.
RECURSIVE_ATTEMPT_S = 5.0


def solve_recursive(problem: PackingProblem, run: RunOptions) -> Solution:
    """Figs. 5.11-5.12: pin a packing over ``C - 1`` colours in the bottom-left corner and let
    SAT place the remaining tiles around it.

    Not every sub-packing can be completed, and a completion that does not exist is slow to
    refute, so each attempt draws a new random sub-packing and gets a budget that doubles
    (from :data:`RECURSIVE_ATTEMPT_S`). C = 3 around a C = 2 packing takes about a second;
    C = 4 around a C = 3 packing was not found in 150 s even around the notes' own C = 3 block
    (use ``lift`` for C = 4).
    """
    from tilesolve.constructive.packing import corner_packing_odd
    from tilesolve.encodings.packing import encode_packing

    if problem.colors < 3:
        raise MethodNotApplicable("a recursive packing embeds a packing over C-1 >= 2 colours; C must be >= 3")
    if problem.colors_v is not None and problem.colors_v != problem.colors:
        raise MethodNotApplicable("method 'recursive' needs C_h = C_v")
    check_search_size(problem, route="recursive")
    t0 = time.perf_counter()
    deadline, seed = run.deadline, run.seed
    rng = rng_from_seed(seed)
    sub_problem = PackingProblem(problem.kind, problem.colors - 1)
    tries, stats, r = 0, {}, None
    while not deadline.expired():
        tries += 1
        attempt = deadline.within(RECURSIVE_ATTEMPT_S * 2 ** (tries - 1))
        if problem.kind == "corner" and sub_problem.colors % 2 == 1:
            sub = corner_packing_odd(sub_problem.colors, seed=rng)
        else:
            s = solve_lift(sub_problem, replace(run, seed=int(rng.integers(2**31)), deadline=attempt))
            if s.tiling is None:
                continue
            sub = s.tiling
        pins = embedding_pins(sub, problem.kind, sub_problem.colors, problem.colors)
        full = PackingProblem(problem.kind, problem.colors, problem.colors_v, tuple(pins) + problem.fixed)
        enc = encode_packing(full)
        r = run_packing_sat(enc, solver=run.solver, deadline=attempt, rng=rng)
        stats = packing_stats(enc, r, attempts=tries)
        if r.status is Status.SAT:
            note = (f"embeds a packing over {sub_problem.colors} colours in rows {pins[0][0]}-{pins[-1][0]}, "
                    f"columns 0-{sub.shape[1] - 1} (attempt {tries})")
            return Solution(Status.SAT, enc.decode(r.model), "recursive", r.solver, seed, time.perf_counter() - t0,
                            stats=stats, notes=(note,))
        if "interrupted" in (r.reason or ""):
            break
    reason = r.reason if r is not None else "no attempt finished"
    return unknown_solution("recursive", PACKING_SAT_SOLVER, run, t0, reason, stats, tries)
