"""Polyform questions decided by SAT (class notes Part II §3; Kaplan, "Heesch numbers of
unmarked polyforms", 2022, whose program heesch-sat classifies polyforms the same way).

:func:`classify` answers, for one shape, in stages, cheapest first; the first witness or
refutation ends the search:

1. *Lattice tilings*: every sublattice ``L`` of the translations of index ``n / t`` (``n``
   cells, ``t`` cell types; Hermite forms ``(A, 0), (B, D)``, :func:`lattices`), the exact cover
   of the torus ``Z^2 / L`` by one copy (:func:`tilesolve.encodings.shapes.encode_tiling`).
2. *Isohedral tilings, any number of copies per period*: closed surrounds of the shape
   (:func:`tilesolve.encodings.shapes.encode_surround`), the neighbours of an isohedral tiling
   seen from one tile; the transforms of a model generate a group whose orbit of the shape is
   checked to be a torus tiling (:func:`surround_tiling`), else the model is blocked (at most
   :data:`SURROUNDS`), neighbours by translations and half-turns alone first (Conway's
   criterion), then all. An isohedral tiling may need as many copies per period as the point
   group has elements (4 for some 7-ominoes), which no torus bound guesses.
3. *Coronas* ``1 .. EARLY_LEVELS`` (:func:`tilesolve.encodings.shapes.encode_coronas`): a level
   that is unsatisfiable refutes the shape as a tiler, certified by a checked DRAT proof; without
   ``holes`` a model whose patch has a hole is blocked and the level solved again (the blocked
   holes are part of the refuted CNF's named encoding, so ``tilesolve verify`` re-derives it).
4. *Periodic tilings*: for ``k = 2, ..., max_copies`` copies per period, the exact cover of
   every torus of index ``k * n / t``. A torus tiling is kept as ``isohedral`` when a symmetry
   of it maps tile 0 onto each tile (:func:`is_isohedral`); tilings that are not are blocked and
   the search goes on (at most :data:`TILINGS_PER_TORUS` per torus), the first one kept as a
   ``periodic`` witness.
5. *Coronas* up to ``max_level``: the Heesch number of a non-tiler, or ``inconclusive``.

Unsatisfiable tori and surrounds prove nothing here and are not certified; a shape with a
periodic tiling is a tiler (Heesch number infinite), whatever coronas were found before.
"""

from __future__ import annotations

import time
from typing import Iterator

import numpy as np

from tilesolve.deadline import NO_LIMIT, Deadline
from tilesolve.encodings.shapes import encode_surround, encode_tiling, lattice_basis, torus_reducer
from tilesolve.engine.sat import solve_cnf
from tilesolve.errors import InvalidProblem
from tilesolve.model.shapes import Grid, ShapesProblem, ShapesReport, enclosed
from tilesolve.model.solution import Solution, Status

__all__ = ["SHAPES_SAT_SOLVER", "TILINGS_PER_TORUS", "SURROUNDS", "EARLY_LEVELS", "MAX_LITERALS", "lattices", "is_isohedral",
           "classify", "check_size", "surround_tiling"]

SHAPES_SAT_SOLVER = "cadical153"
#: Torus tilings tried per torus before the next torus (tilings that are not isohedral).
TILINGS_PER_TORUS = 20
#: Corona levels tried before the tori of 2 or more copies (a non-tiler refuted at these levels
#: needs no torus; a tiler with no isohedral tiling pays for them before its torus witness).
EARLY_LEVELS = 2
#: Closed surrounds tried (each whose group does not tile is blocked) before a surround search gives up.
SURROUNDS = 20
#: The largest tiling CNF built (an estimate of its literals, checked before building).
MAX_LITERALS = 10_000_000


def check_size(problem: ShapesProblem) -> None:
    """Refuse a tiling problem whose CNF would be absurdly large, with the estimate."""
    g = problem.geometry
    images = sum(len(g.images(s.cells, problem.reflections)) for s in problem.shapes)
    size = max(s.size for s in problem.shapes)
    cells = problem.n_cells()
    est = cells * images * size * (size + 2)
    if est > MAX_LITERALS:
        raise InvalidProblem(f"the tiling CNF would hold about {est:.2g} literals ({cells} cells x {images} "
                             f"orientations x {size} cells per shape); at most {MAX_LITERALS:.2g}")


def lattices(index: int) -> Iterator[tuple[tuple[int, int], tuple[int, int]]]:
    """Every sublattice of ``Z^2`` of ``index``, as Hermite bases ``(A, 0), (B, D)`` with
    ``A * D = index`` and ``0 <= B < A``.

    Examples
    --------
    >>> len(list(lattices(6)))  # sigma(6)
    12
    """
    for a in range(1, index + 1):
        if index % a == 0:
            for b in range(a):
                yield (a, 0), (b, index // a)


def is_isohedral(g: Grid, pieces: list, lattice, reflections: bool = True) -> bool:
    """Whether the torus tiling ``pieces`` (cell lists in the plane) is isohedral: for each
    tile a symmetry of the grid that keeps ``L`` and maps the tiling onto itself moves tile 0
    onto it."""
    reduce, reps = torus_reducer(g, lattice)
    owner = {}
    for i, cells in enumerate(pieces):
        for c in cells:
            owner[reduce(c)] = i
    sets = [frozenset(reduce(c) for c in cells) for cells in pieces]
    base = reps[0]
    p = g.period
    mats = g.matrices if reflections else g.matrices[: g.order]
    keeps = []
    for m in mats:
        ok = all(reduce((base[0] + p * int(w[0]), base[1] + p * int(w[1]))) == base
                 for w in (m @ np.asarray(v) for v in lattice))
        if ok:
            keeps.append(m)
    reached = set()
    p0 = np.asarray(pieces[0])
    for m in keeps:
        q = [tuple(v) for v in (p0 @ m.T).tolist()]
        for i, cells in enumerate(pieces):
            if i in reached:
                continue
            for c in cells:
                if g.cell_type(c) != g.cell_type(q[0]):
                    continue
                t = (c[0] - q[0][0], c[1] - q[0][1])
                if frozenset(reduce((x + t[0], y + t[1])) for x, y in q) != sets[i]:
                    continue
                if _maps_tiling(m, t, pieces, sets, owner, reduce):
                    reached.add(i)
                    break
    return len(reached) == len(pieces)


def _maps_tiling(m, t, pieces, sets, owner, reduce) -> bool:
    for cells in pieces:
        img = [(int(v[0]) + t[0], int(v[1]) + t[1]) for v in (np.asarray(cells) @ m.T).tolist()]
        red = frozenset(reduce(c) for c in img)
        j = owner.get(next(iter(red)))
        if j is None or sets[j] != red:
            return False
    return True


def _pieces(tiling: np.ndarray) -> list[list[tuple[int, int]]]:
    return [[tuple(r) for r in tiling[tiling[:, 0] == k][:, 2:].tolist()] for k in np.unique(tiling[:, 0])]


def _torus_search(problem: ShapesProblem, deadline: Deadline, solver: str, seed, copies: range):
    """``(found, tori tried)``: ``found`` the first isohedral torus tiling with a number of
    ``copies`` per period, else the first periodic one, else ``None``, as ``(verdict, copies,
    lattice, tiling)``."""
    from pysat.solvers import Solver

    shape = problem.shapes[0]
    g = shape.geometry
    types = 1 if g.period == 1 else 2
    first = None
    tried = 0
    for k in copies:
        if (k * shape.size) % types:
            continue
        for lattice in lattices(k * shape.size // types):
            if deadline.expired():
                return first, tried
            tried += 1
            enc = encode_tiling(ShapesProblem("tile", problem.shapes, lattice=lattice, reflections=problem.reflections))
            if not enc.placements:
                continue
            with Solver(name=solver, bootstrap_with=enc.hard.to_lists()) as s:
                for _ in range(TILINGS_PER_TORUS):
                    if not s.solve():
                        break
                    model = s.get_model()
                    tiling = enc.decode(model)
                    pieces = _pieces(tiling)
                    if is_isohedral(g, pieces, lattice, problem.reflections):
                        return ("isohedral", k, lattice, tiling), tried
                    if first is None:
                        first = ("periodic", k, lattice, tiling)
                    s.add_clause([-v for v in model if 0 < v <= len(enc.placements)])
    return first, tried


def surround_tiling(enc, used: list[int]):
    """The torus tiling of the group that the transforms ``used`` (of the surround encoding
    ``enc``) generate, as ``(copies, lattice, tiling)``, or ``None`` when its orbit of the shape
    is no tiling.

    The point parts ``H`` of the group and one element ``r_h`` per ``h`` come from a closure
    over the generators; the translations ``L`` are generated by the Schreier elements
    ``r_h'^-1 s r_h`` (Schreier's lemma); the tiles ``r_h(S)`` modulo ``L`` must cover the
    torus ``Z^2 / L`` exactly once. Then the group maps the tiling onto itself and moves
    ``S`` onto every tile: the tiling is isohedral.
    """
    g = enc.grid
    mats, product, inverse = enc.mats, enc.product, enc.inverse
    gens = [(int(enc.m[i]), np.asarray(enc.t[i], dtype=np.int64)) for i in used]
    reps = {0: np.zeros(2, dtype=np.int64)}  # point part -> translation of one element
    todo = [0]
    while todo:
        h = todo.pop()
        for ms, ts in gens:
            k = int(product[ms, h])
            if k not in reps:
                reps[k] = mats[ms] @ reps[h] + ts
                todo.append(k)
    p = g.period
    shifts = []
    for h, th in reps.items():
        for ms, ts in gens:
            k = int(product[ms, h])
            shift = mats[int(inverse[k])] @ (mats[ms] @ th + ts - reps[k])
            if shift.any():
                shifts.append(shift)
    if any(int(v) % p for sh in shifts for v in sh):
        return None
    lattice = lattice_basis([(int(x) // p, int(y) // p) for x, y in shifts])
    if lattice is None:
        return None
    reduce, cells = torus_reducer(g, lattice)
    x = np.asarray(enc.shape, dtype=np.int64)
    seen: dict = {}
    pieces = []
    covered: set = set()
    for h in sorted(reps):
        placed = [tuple(c) for c in (x @ mats[h].T + reps[h]).tolist()]
        key = frozenset(reduce(c) for c in placed)
        if key in seen:
            continue
        if len(key) != len(placed) or covered & key:
            return None
        seen[key] = len(pieces)
        covered |= key
        pieces.append(placed)
    if len(covered) != len(cells):
        return None
    tiling = np.asarray([(i, 0, cx, cy) for i, cs in enumerate(pieces) for cx, cy in cs], dtype=np.int64)
    return len(pieces), lattice, tiling


def _surround_search(problem: ShapesProblem, deadline: Deadline, solver: str, seed):
    """``(found, surrounds tried)``: ``found`` an isohedral torus tiling from a closed surround
    (:func:`tilesolve.encodings.shapes.encode_surround`, :func:`surround_tiling`) as
    ``("isohedral", copies, lattice, tiling)``, else ``None``: no closed surround, or
    :data:`SURROUNDS` of them whose groups do not tile, or the deadline.

    Neighbours by translations and half-turns are tried first, alone (a small CNF, and a group
    with few tiles per period, a cheap witness to check), then every transform, the solver
    preferring translations and half-turns."""
    from tilesolve.engine.sat import SatSession

    tried = 0
    for half_turns in (True, False):
        if deadline.expired():
            break
        enc = encode_surround(problem, half_turns)
        with SatSession(enc.clauses, solver=solver, seed=seed, deadline=deadline) as s:
            mats = enc.mats[enc.m]
            plain = (mats[:, 0, 1] == 0) & (mats[:, 1, 0] == 0) & (mats[:, 0, 0] == mats[:, 1, 1])
            s.set_phases(np.where(plain, enc.var, -enc.var).tolist())
            for _ in range(SURROUNDS):
                r = s.solve(deadline=deadline)
                if r.status is not Status.SAT:
                    break
                tried += 1
                used = enc.decode(r.model)
                found = surround_tiling(enc, used)
                if found is not None:
                    return ("isohedral", *found), tried
                s.add_clause(enc.block(used))
    return None, tried


def _holes_of(g: Grid, patch: np.ndarray) -> list:
    """Blocks for the holes of a patch: ``(tiles around the hole as (level, cells), hole cells)``."""
    cells = {tuple(c) for c in patch[:, 2:].tolist()}
    out = []
    for hole in enclosed(g, cells):
        border = {n for c in hole for n in g.neighbours(c)} - set(hole)
        tiles = []
        for k in np.unique(patch[:, 0]):
            rows = patch[patch[:, 0] == k]
            if k == 0:
                continue
            pc = [tuple(c) for c in rows[:, 2:].tolist()]
            if border & set(pc):
                tiles.append([int(rows[0, 1]), [list(c) for c in sorted(pc)]])
        out.append([tiles, [list(c) for c in hole]])
    return out


def _coronas(problem: ShapesProblem, levels: range, found: tuple, deadline: Deadline, solver: str, seed, t0: float,
             progress):
    """Heesch search over ``levels``, ``found`` the ``(heesch, patch)`` of the levels below:
    ``(heesch, patch, refutation stats or None, reason)``, ``reason`` None when every level of
    ``levels`` is possible.

    A level's models with holes are blocked in the same solver (the level's clauses are loaded
    once); a level found unsatisfiable after blocks is solved again from its named encoding
    with a proof, so that the proof refutes exactly the CNF that ``tilesolve verify`` rebuilds.
    """
    from tilesolve.encodings.registry import encode
    from tilesolve.engine.certificates import unsat_solution
    from tilesolve.engine.sat import SatSession

    g = problem.geometry
    heesch, patch = found
    for level in levels:
        blocked: list = []
        enc = encode("shapes-corona-cnf", problem, {"levels": level, "blocked": blocked}, deadline=deadline)
        with SatSession(enc.hard, solver=solver, with_proof=True, seed=seed, deadline=deadline) as s:
            while True:
                r = s.solve(deadline=deadline)
                if r.status is not Status.SAT:
                    break
                found = enc.decode(r.model)
                holes = [] if problem.holes else _holes_of(g, found)
                if not holes:
                    break
                for clause in enc.hole_clauses(holes):
                    s.add_clause(clause)
                blocked += holes
        if r.status is Status.SAT:
            patch, heesch = found, level
            progress.note(f"{level} corona(s)")
            continue
        if r.status is Status.UNSAT and blocked:
            enc = encode("shapes-corona-cnf", problem, {"levels": level, "blocked": blocked}, deadline=deadline)
            r = solve_cnf(enc.hard, solver=solver, with_proof=True, seed=seed, deadline=deadline)
        if r.status is Status.UNSAT:
            sol = unsat_solution(enc.hard, r, method="sat", seed=seed, t0=t0, stats={}, deadline=deadline,
                                 encoding=enc.named)
            if sol.status is Status.UNSAT:
                sol.stats["level"] = level
                return heesch, patch, sol.stats, sol.reason
            return heesch, patch, None, sol.reason
        return heesch, patch, None, r.reason or "stopped"
    return heesch, patch, None, None


def classify(problem: ShapesProblem, *, solver: str = SHAPES_SAT_SOLVER, seed=None, deadline: Deadline = NO_LIMIT,
             progress=None) -> Solution:
    """Classify one polyform (module docstring); a Solution with a :class:`ShapesReport`."""
    from tilesolve.progress import as_progress

    progress = as_progress(progress)
    t0 = time.perf_counter()
    stats = {"tori": 0}
    early = range(1, min(EARLY_LEVELS, problem.max_level) + 1)
    coronas = (0, np.asarray([(0, 0, x, y) for x, y in problem.shapes[0].cells], dtype=np.int64))
    for stage in ("lattice", "surround", "coronas", "tori", "coronas"):
        if stage == "coronas":
            levels = range(coronas[0] + 1, problem.max_level + 1) if coronas[0] else early
            with progress.task("coronas", total=problem.max_level, unit="level") as task:
                heesch, patch, refutation, reason = _coronas(problem, levels, coronas, deadline, solver, seed, t0,
                                                             task)
            coronas = (heesch, patch)
            if refutation is not None:
                report = ShapesReport("non-tiler", heesch=heesch, patch=patch, refutation=refutation,
                                      holes=problem.holes)
                return _done(report, solver, seed, t0, stats, reason)
            if reason is not None:
                break
            continue
        with progress.task(stage, total=None, unit="model") as task:
            if stage == "surround":
                found, stats["surrounds"] = _surround_search(problem, deadline, solver, seed)
            else:
                copies = range(1, 2) if stage == "lattice" else range(2, problem.max_copies + 1)
                found, tried = _torus_search(problem, deadline, solver, seed, copies)
                stats["tori"] += tried
            task.note(f"{stats['tori']} tori, {stats.get('surrounds', 0)} surround(s)")
        if found is not None:
            verdict, copies, lattice, tiling = found
            report = ShapesReport(verdict, copies=copies, lattice=lattice, tiling=tiling, holes=problem.holes)
            return _done(report, solver, seed, t0, stats)
    else:
        reason = f"{problem.max_level} corona(s) possible (the most tried)"
    heesch, patch = coronas
    return _done(ShapesReport("inconclusive", heesch=heesch, patch=patch, holes=problem.holes), solver, seed, t0,
                 stats, reason)


def _done(report: ShapesReport, solver: str, seed, t0: float, stats: dict, reason: str | None = None) -> Solution:
    return Solution(report.status, None, "sat", solver, seed, time.perf_counter() - t0, reason=reason, stats=stats,
                    report=report)
