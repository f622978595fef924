"""Polyform questions decided by SAT (class notes Part II §3; Kaplan, "Heesch numbers of
unmarked polyforms", 2022, whose program heesch-sat classifies polyforms the same way).

:func:`classify` answers, for one shape:

1. *Tiler?* For ``k = 1, 2, ..., max_copies`` copies per period, every sublattice ``L`` of the
   translations of index ``k * n / t`` (``n`` cells, ``t`` cell types; Hermite forms
   ``(A, 0), (B, D)``), the exact cover of the torus ``Z^2 / L``
   (:func:`tilesolve.encodings.shapes.encode_tiling`). An isohedral tiling has a translation
   lattice with at most as many tiles per period as the grid's point group has elements, so it
   is found here for ``max_copies`` large enough. A torus tiling is kept as ``isohedral`` when
   a symmetry of it maps tile 0 onto each tile (:func:`is_isohedral`); tilings that are not
   are blocked and the search goes on (at most :data:`TILINGS_PER_TORUS` per torus), the first
   one kept as a ``periodic`` witness. Unsatisfiable tori prove nothing here and are not
   certified.
   A shape with a periodic tiling is a tiler (Heesch number infinite): no coronas are tried.
2. Else its *Heesch number*: coronas ``1, 2, ...``
   (:func:`tilesolve.encodings.shapes.encode_coronas`) until a level is unsatisfiable, that
   refutation certified by a checked DRAT proof; without ``holes`` a model whose patch has a
   hole is blocked and the level solved again (the blocked holes are part of the refuted CNF's
   named encoding, so ``tilesolve verify`` re-derives it).
"""

from __future__ import annotations

import time
from typing import Iterator

import numpy as np

from tilesolve.deadline import NO_LIMIT, Deadline
from tilesolve.encodings.shapes import encode_tiling, torus_reducer
from tilesolve.engine.sat import solve_cnf
from tilesolve.errors import InvalidProblem
from tilesolve.model.shapes import Grid, ShapesProblem, ShapesReport, enclosed
from tilesolve.model.solution import Solution, Status

__all__ = ["SHAPES_SAT_SOLVER", "TILINGS_PER_TORUS", "MAX_LITERALS", "lattices", "is_isohedral", "classify",
           "check_size"]

SHAPES_SAT_SOLVER = "cadical153"
#: Torus tilings tried per torus before the next torus (tilings that are not isohedral).
TILINGS_PER_TORUS = 20
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


def _torus_search(problem: ShapesProblem, deadline: Deadline, solver: str, seed):
    """``(found, tori tried)``: ``found`` the first isohedral torus tiling, else the first
    periodic one, else ``None``, as ``(verdict, copies, lattice, tiling)``."""
    from pysat.solvers import Solver

    shape = problem.shapes[0]
    g = shape.geometry
    types = 1 if g.period == 1 else 2
    first = None
    tried = 0
    for k in range(1, problem.max_copies + 1):
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


def _coronas(problem: ShapesProblem, deadline: Deadline, solver: str, seed, t0: float, progress):
    """Heesch search: ``(heesch, patch, refutation stats or None, reason)``."""
    from tilesolve.encodings.registry import encode
    from tilesolve.engine.certificates import unsat_solution

    g = problem.geometry
    patch = np.asarray([(0, 0, x, y) for x, y in problem.shapes[0].cells], dtype=np.int64)
    heesch = 0
    for level in range(1, problem.max_level + 1):
        blocked: list = []
        while True:
            enc = encode("shapes-corona-cnf", problem, {"levels": level, "blocked": blocked}, deadline=deadline)
            r = solve_cnf(enc.hard, solver=solver, with_proof=True, seed=seed, deadline=deadline)
            if r.status is Status.SAT:
                found = enc.decode(r.model)
                holes = [] if problem.holes else _holes_of(g, found)
                if holes:
                    blocked += holes
                    continue
                patch, heesch = found, level
                progress.note(f"{level} corona(s)")
                break
            if r.status is Status.UNSAT:
                sol = unsat_solution(enc.hard, r, method="sat", seed=seed, t0=t0, stats={}, deadline=deadline,
                                     encoding=enc.named)
                if sol.status is Status.UNSAT:
                    sol.stats["level"] = level
                    return heesch, patch, sol.stats, sol.reason
                return heesch, patch, None, sol.reason
            return heesch, patch, None, r.reason or "stopped"
    return heesch, patch, None, f"{problem.max_level} corona(s) possible (the most tried)"


def classify(problem: ShapesProblem, *, solver: str = SHAPES_SAT_SOLVER, seed=None, deadline: Deadline = NO_LIMIT,
             progress=None) -> Solution:
    """Classify one polyform (module docstring); a Solution with a :class:`ShapesReport`."""
    from tilesolve.progress import as_progress

    progress = as_progress(progress)
    t0 = time.perf_counter()
    with progress.task("tori", total=None, unit="torus") as task:
        found, tried = _torus_search(problem, deadline, solver, seed)
        task.note(f"{tried} tori")
    stats = {"tori": tried}
    if found is not None:
        verdict, copies, lattice, tiling = found
        return _done(ShapesReport(verdict, copies=copies, lattice=lattice, tiling=tiling, holes=problem.holes),
                     solver, seed, t0, stats)
    with progress.task("coronas", total=problem.max_level, unit="level") as task:
        heesch, patch, refutation, reason = _coronas(problem, deadline, solver, seed, t0, task)
    if refutation is not None:
        report = ShapesReport("non-tiler", heesch=heesch, patch=patch, refutation=refutation, holes=problem.holes)
        return _done(report, solver, seed, t0, stats, reason)
    return _done(ShapesReport("inconclusive", heesch=heesch, patch=patch, holes=problem.holes), solver, seed, t0,
                 stats, reason)


def _done(report: ShapesReport, solver: str, seed, t0: float, stats: dict, reason: str | None = None) -> Solution:
    return Solution(report.status, None, "sat", solver, seed, time.perf_counter() - t0, reason=reason, stats=stats,
                    report=report)
