"""CNF encodings of polyform questions (class notes Part II §3; Kaplan, "Heesch numbers of
unmarked polyforms", Contributions to Discrete Mathematics 17(2), 2022).

Placements
    A placement is a congruent copy of a shape on the grid: an image under the point group
    (:meth:`tilesolve.model.shapes.Grid.images`) translated by a grid translation. Variable
    ``i + 1`` says placement ``i`` is used.

Tilings of a region or a torus (:func:`encode_tiling`)
    Every cell of the region (or of the torus ``Z^2 / L``, cells reduced modulo the periods)
    is covered by exactly one used placement: one clause "at least one" and an at-most-one
    (pairwise up to :data:`PAIRWISE_MAX` placements, else PySAT's sequential counter) per cell.
    A placement that would cover a torus cell twice is left out.

Coronas (:func:`encode_coronas`)
    Level 0 is the shape ``S`` itself. ``x[j, p]`` puts placement ``p`` in corona ``j``
    (1 <= j <= k) and ``y[j, c]`` says a tile of corona ``j`` covers cell ``c``. Two used
    placements never share a cell; a corona-``j`` tile touches (shares a corner with) a tile of
    corona ``j - 1`` and no tile of a lower corona, so the levels are the distances from ``S``
    in the touching graph; every cell touching ``S`` or a tile of corona ``j - 1`` is covered
    by a tile of corona ``<= j``. So the tiles of coronas ``0..j`` cover a neighbourhood of
    those of coronas ``0..j-1``: the patch has ``k`` coronas. ``blocked`` holes (a set of
    uncovered cells and the tiles around it, found in an earlier model) add a clause "one of
    these tiles is absent or one of these cells is covered" (the ``H_c`` variant: no holes).

Closed surrounds (:func:`encode_surround`)
    The neighbours of an isohedral tiling seen from one tile (Kaplan's heesch-sat checks
    isohedral tilings the same way). A *transform* ``T = (M, t)`` maps a cell ``x`` to
    ``M x + t`` (``M`` in the point group, ``t`` a grid translation). The candidates are the
    transforms whose image of ``S`` is *adjacent* to ``S`` (disjoint from it, sharing an edge);
    a shape with symmetries has several transforms per placement. ``T`` and ``T^-1`` share one
    variable (``T(S)`` is a neighbour of ``S`` iff ``S`` is one of ``T(S)``). Clauses: the cells
    sharing an edge with ``S`` are covered; two neighbours that overlap are not both used; and
    two used neighbours ``T_i(S)``, ``T_j(S)`` adjacent to each other imply ``T_i^-1 T_j`` used
    (mapped back by ``T_i^-1`` they are ``S`` and a neighbour of it). In an isohedral tiling
    whose symmetries move each tile onto each other tile in one way, the neighbours of ``S``
    satisfy all of these; a model is only a candidate, and the group its transforms generate
    is checked to tile (:mod:`tilesolve.engine.shapes`).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field

import numpy as np

from tilesolve.encodings import ClauseSet
from tilesolve.model.shapes import Grid, ShapesProblem

__all__ = ["PAIRWISE_MAX", "TilingEncoding", "CoronaEncoding", "SurroundEncoding", "encode_tiling", "encode_coronas",
           "encode_surround", "torus_reducer", "lattice_basis", "orientations", "placements_at", "point_group",
           "sequential_at_most_one"]

#: Cells covered by at most this many placements get a pairwise at-most-one.
PAIRWISE_MAX = 8


def orientations(problem: ShapesProblem) -> list[list[tuple[tuple[int, int], ...]]]:
    """Per shape, its distinct images under the allowed part of the point group."""
    g = problem.geometry
    return [g.images(s.cells, problem.reflections) for s in problem.shapes]


def torus_reducer(g: Grid, lattice):
    """``(reduce, cells)``: ``reduce(cell)`` is the representative of a cell modulo
    ``period * L``, and ``cells`` lists the representatives.

    ``L``'s Hermite form has periods ``(A, 0)`` and ``(B, D)`` with ``0 <= B < A``; a cell's
    translation part is reduced to ``[0, A) x [0, D)``.
    """
    (a, b), (c, d) = lattice
    dd, u, w = _egcd(b, d)
    bb = u * a + w * c
    aa = abs(a * d - b * c) // dd
    bb %= aa
    p = g.period

    def reduce(cell):
        i, sx = divmod(cell[0], p)
        j, sy = divmod(cell[1], p)
        k = j // dd
        i, j = i - k * bb, j - k * dd
        return (i % aa * p + sx, j * p + sy)

    def reduce_unit(cell):  # the same for period 1, where it runs most
        x, y = cell
        k = y // dd
        return ((x - k * bb) % aa, y - k * dd)

    types = [(0, 0)] if p == 1 else [(1, 1), (2, 2)]
    return (reduce_unit if p == 1 else reduce), [(p * i + t[0], p * j + t[1]) for i in range(aa) for j in range(dd)
                                                 for t in types]


def _egcd(x: int, y: int) -> tuple[int, int, int]:
    """``(g, u, w)`` with ``u*x + w*y = g = gcd(x, y) > 0``."""
    if y == 0:
        return (abs(x), (1 if x >= 0 else -1), 0)
    g, u, w = _egcd(y, x % y)
    return g, w, u - (x // y) * w


def lattice_basis(vectors) -> tuple[tuple[int, int], tuple[int, int]] | None:
    """The Hermite basis ``(A, 0), (B, D)`` (``A, D > 0``, ``0 <= B < A``) of the lattice that
    integer ``vectors`` generate, or ``None`` when they span less than the plane.

    Examples
    --------
    >>> lattice_basis([(2, 1), (0, 3), (4, 2)])
    ((6, 0), (2, 1))
    >>> lattice_basis([(1, 1), (2, 2)]) is None
    True
    """
    a, pivot = 0, None
    for x, y in vectors:
        x, y = int(x), int(y)
        if y == 0:
            a = math.gcd(a, x)
            continue
        if pivot is None:
            pivot = (x, y)
            continue
        px, py = pivot
        d, u, w = _egcd(py, y)
        pivot = (u * px + w * x, d)
        a = math.gcd(a, (y // d) * px - (py // d) * x)
    if pivot is None or a == 0:
        return None
    px, py = pivot if pivot[1] > 0 else (-pivot[0], -pivot[1])
    return (a, 0), (px % a, py)


def placements_at(g: Grid, images, cells) -> dict:
    """Placements of each image (``[(shape, image cells), ...]``, image cells sorted) that cover
    one of ``cells``: ``{sorted cells: shape}``.

    A translation keeps the cells' order, so each distinct translation of an image is built once,
    already sorted."""
    out: dict = {}
    types = [g.cell_type(h) for h in cells]
    for shape, img in images:
        by_type: dict = {}
        for c in img:
            by_type.setdefault(g.cell_type(c), []).append(c)
        shifts: dict = {}
        for h, t in zip(cells, types):
            for c in by_type.get(t, ()):
                shifts[(h[0] - c[0], h[1] - c[1])] = None
        for dx, dy in shifts:
            out.setdefault(tuple((x + dx, y + dy) for x, y in img), shape)
    return out


def _exactly_one(cs: ClauseSet, lits: list[int], top: int, label: str) -> int:
    """Clauses "exactly one of ``lits``"; returns the new top variable."""
    cs.add_lists([lits], f"{label}: at least one")
    return _at_most_one(cs, lits, top, label)


def _at_most_one(cs: ClauseSet, lits: list[int], top: int, label: str) -> int:
    if len(lits) <= PAIRWISE_MAX:
        cs.add_array(_pairs([[-a, -b] for i, a in enumerate(lits) for b in lits[i + 1:]]), f"{label}: at most one")
        return top
    clauses = sequential_at_most_one(lits, top)
    cs.add_array(clauses, f"{label}: at most one", grid_only=False)
    return max(top, int(np.abs(clauses).max()))


def sequential_at_most_one(lits, top: int) -> np.ndarray:
    """Sinz's sequential counter "at most one of ``lits``" (three or more) with auxiliary
    variables ``top + 1 .. top + n - 1``, as rows of two literals: the clauses of PySAT's
    ``CardEnc.atmost(lits, 1, top_id=top, encoding=1)`` in its order, built with numpy.

    Examples
    --------
    >>> sequential_at_most_one([1, 2, 3], 3).tolist()
    [[-1, 4], [-4, 5], [-2, -4], [-2, 5], [-3, -5]]
    """
    x = np.asarray(lits, dtype=np.int64)
    n = len(x)
    aux = top + 1 + np.arange(n - 1, dtype=np.int64)
    mid = np.stack((np.stack((-aux[:-1], aux[1:]), axis=1), np.stack((-x[1:-1], -aux[:-1]), axis=1),
                    np.stack((-x[1:-1], aux[1:]), axis=1)), axis=1).reshape(-1, 2)
    return np.concatenate(([[-x[0], aux[0]]], mid, [[-x[-1], -aux[-1]]])).astype(np.int64)


@dataclass
class TilingEncoding:
    """Exact cover of a region or torus by placements (:func:`encode_tiling`).

    ``tiling`` arrays (what :meth:`decode` gives) hold one row ``(piece, shape, x, y)`` per cell
    of every piece, in plane coordinates (on a torus: the piece as placed, unreduced).
    """

    problem: ShapesProblem
    placements: list = field(default_factory=list)  # [(shape, cells)]
    hard: ClauseSet = field(default_factory=ClauseSet)
    n_vars: int = 0
    restricted: bool = False

    def projection(self) -> np.ndarray:
        return np.arange(1, len(self.placements) + 1)

    def decode(self, model) -> np.ndarray:
        rows = []
        used = [v for v in model if 0 < v <= len(self.placements)]
        for piece, v in enumerate(used):
            shape, cells = self.placements[v - 1]
            rows += [(piece, shape, x, y) for x, y in cells]
        return np.asarray(rows, dtype=np.int64).reshape(-1, 4)

    def literals(self, tiling) -> list[int]:
        key = {}
        t = np.asarray(tiling, dtype=np.int64).reshape(-1, 4)
        for piece in np.unique(t[:, 0]):
            rows = t[t[:, 0] == piece]
            key[(int(rows[0, 1]), self._key(rows[:, 2:].tolist()))] = True
        return [(i + 1) if (s, self._key(c)) in key else -(i + 1) for i, (s, c) in enumerate(self.placements)]

    def _key(self, cells) -> tuple:
        if self.problem.lattice is None:
            return tuple(sorted(map(tuple, cells)))
        reduce, _ = torus_reducer(self.problem.geometry, self.problem.lattice)
        return tuple(sorted(reduce(tuple(c)) for c in cells))

    def header(self) -> list[str]:
        return [f"tilesolve polyform tiling: {self.problem.describe()}",
                f"variables 1..{len(self.placements)}: placements (congruent copies) of the shapes",
                "per cell: at least one placement covers it, and at most one"]


def encode_tiling(problem: ShapesProblem) -> TilingEncoding:
    """The exact-cover CNF of a ``tile`` problem.

    Examples
    --------
    >>> from tilesolve.model.shapes import parse_ascii
    >>> p = ShapesProblem("tile", (parse_ascii("##", "omino"),), region=((0, 0), (1, 0), (0, 1), (1, 1)))
    >>> enc = encode_tiling(p)
    >>> len(enc.placements), len(enc.hard)
    (4, 8)
    """
    g = problem.geometry
    images = [(s, img) for s, imgs in enumerate(orientations(problem)) for img in imgs]
    if problem.region is not None:
        region = set(problem.region)
        cells = sorted(region)
        found = placements_at(g, images, cells)
        places = [(s, c) for c, s in found.items() if set(c) <= region]
        index = {c: i for i, c in enumerate(cells)}
        covers = [[index[x] for x in c] for _, c in places]
    else:
        # Modulo the periods a placement is its image with the image's first cell on one of the
        # representatives: each is built once (not once per cell it covers).
        # Each placement's cells are reduced once, and its cover read from them.
        reduce, reps = torus_reducer(g, problem.lattice)
        index = {c: i for i, c in enumerate(reps)}
        rep_types = [g.cell_type(r) for r in reps]
        seen, places, covers = set(), [], []
        for s, img in images:
            x0, y0 = img[0]
            t0 = g.cell_type((x0, y0))
            offsets = [(x - x0, y - y0) for x, y in img]
            for (hx, hy), t in zip(reps, rep_types):
                if t != t0:
                    continue
                c = tuple((hx + dx, hy + dy) for dx, dy in offsets)
                reduced = [reduce(x) for x in c]
                red = tuple(sorted(reduced))
                if len(set(red)) == len(red) and (s, red) not in seen:
                    seen.add((s, red))
                    places.append((s, c))
                    covers.append([index[x] for x in reduced])
        cells = reps
    enc = TilingEncoding(problem, places)
    by_cell: list[list[int]] = [[] for _ in cells]
    for i, cover in enumerate(covers):
        for j in cover:
            by_cell[j].append(i + 1)
    top = len(places)
    for lits in by_cell:
        top = _exactly_one(enc.hard, lits, top, "cells")
    enc.n_vars = max(top, 1)
    return enc


@dataclass
class CoronaEncoding:
    """``k`` coronas around one shape (:func:`encode_coronas`)."""

    grid: Grid
    shape: tuple
    levels: int
    candidates: list = field(default_factory=list)   # per level: [cells]
    var: dict = field(default_factory=dict)           # (level, index) -> variable
    cellvar: dict = field(default_factory=dict)       # (level, cell) -> variable
    hard: ClauseSet = field(default_factory=ClauseSet)
    n_vars: int = 0
    restricted: bool = False

    def projection(self) -> np.ndarray:
        return np.asarray(sorted(self.var.values()), dtype=np.int64)

    def decode(self, model) -> np.ndarray:
        """Rows ``(piece, level, x, y)``: piece 0 is the shape (level 0)."""
        true = {v for v in model if v > 0}
        rows = [(0, 0, x, y) for x, y in self.shape]
        piece = 1
        for (level, i), v in sorted(self.var.items()):
            if v in true:
                rows += [(piece, level, x, y) for x, y in self.candidates[level - 1][i]]
                piece += 1
        return np.asarray(rows, dtype=np.int64).reshape(-1, 4)

    def literals(self, tiling) -> list[int]:
        t = np.asarray(tiling, dtype=np.int64).reshape(-1, 4)
        used = set()
        for piece in np.unique(t[:, 0]):
            rows = t[t[:, 0] == piece]
            used.add((int(rows[0, 1]), tuple(sorted(map(tuple, rows[:, 2:].tolist())))))
        return [v if (lv, self.candidates[lv - 1][i]) in used else -v for (lv, i), v in sorted(self.var.items())]

    def hole_clauses(self, blocked) -> list[list[int]]:
        """The clauses "no hole" of ``blocked`` holes (:func:`encode_coronas`), in their order."""
        index = {(lv, c): i for lv, cands in enumerate(self.candidates, 1) for i, c in enumerate(cands)} if blocked else {}
        out = []
        for tiles, cells in blocked:
            clause = [-self.var[(lv, index[(lv, tuple(map(tuple, c)))])] for lv, c in tiles]
            clause += [self.cellvar[(j, tuple(c))] for c in cells for j in range(1, self.levels + 1)
                       if (j, tuple(c)) in self.cellvar]
            out.append(clause)
        return out

    def header(self) -> list[str]:
        return [f"tilesolve coronas: {self.levels} corona(s) around a {self.grid.name} polyform of {len(self.shape)} "
                "cells", "x[j, p]: placement p is a tile of corona j; y[j, c]: a corona-j tile covers cell c"]


@functools.lru_cache(maxsize=1 << 16)
def _halo(g: Grid, cells: tuple) -> frozenset:
    """The cells outside ``cells`` that share a corner with one of them (cached: a candidate
    tile's halo is asked for at every level of every corona encoding), translated from the
    halo of the same cells moved to the origin (the tiles of a corona are few shapes, many
    places)."""
    p = g.period
    x0, y0 = cells[0][0] // p * p, cells[0][1] // p * p
    if not (x0 or y0):
        return _halo_at_origin(g, cells)
    at_origin = _halo_at_origin(g, tuple((x - x0, y - y0) for x, y in cells))
    return frozenset((x + x0, y + y0) for x, y in at_origin)


@functools.lru_cache(maxsize=1 << 12)
def _halo_at_origin(g: Grid, cells: tuple) -> frozenset:
    offsets = _touching_offsets(g)
    s = set(cells)
    return frozenset((x + dx, y + dy) for x, y in s for dx, dy in offsets[g.cell_type((x, y))]) - s


@functools.lru_cache(maxsize=8)
def _touching_offsets(g: Grid) -> dict:
    """Per cell type, the offsets of the cells sharing a corner with a cell of that type."""
    types = [(0, 0)] if g.period == 1 else [(1, 1), (2, 2)]
    return {t: tuple((x - t[0], y - t[1]) for x, y in g.touching(t)) for t in types}


@functools.lru_cache(maxsize=64)
def _corona_candidates(g: Grid, shape: tuple, reflections: bool, levels: int) -> tuple:
    """Per level ``1..levels``, the sorted placements that may be a tile of that corona: those
    covering a cell of the previous level's halo, off the shape, and (above level 1) off the
    shape's halo. Level ``j``'s list does not depend on ``levels``, so each is built once."""
    S = set(shape)
    halo_s = _halo(g, shape)
    if levels == 1:
        lower: tuple = ()
        frontier = set(halo_s)
    else:
        lower = _corona_candidates(g, shape, reflections, levels - 1)
        frontier = set().union(*(_halo(g, c) for c in lower[-1])) - S if lower[-1] else set()
    images = [(0, img) for img in g.images(shape, reflections)]
    found = placements_at(g, images, sorted(frontier))
    cands = [c for c in found if not S & set(c) and (levels == 1 or not halo_s & set(c))]
    return lower + (tuple(sorted(cands)),)


def encode_coronas(problem: ShapesProblem, levels: int, blocked=()) -> CoronaEncoding:
    """The CNF "the shape has ``levels`` coronas" (module docstring), with ``blocked`` holes:
    pairs ``(tiles, cells)``, tiles as ``(level, sorted cells)``.

    Examples
    --------
    >>> from tilesolve.model.shapes import parse_ascii
    >>> p = ShapesProblem("classify", (parse_ascii("#", "omino"),))
    >>> enc = encode_coronas(p, 1)
    >>> [len(c) for c in enc.candidates]
    [8]
    """
    g = problem.geometry
    shape = problem.shapes[0].cells
    base = _corona_base(g, shape, problem.reflections, levels)
    enc = CoronaEncoding(g, shape, levels)
    enc.candidates = [list(c) for c in base.candidates]
    enc.var, enc.cellvar = base.var, base.cellvar
    enc.hard.blocks = list(base.blocks)
    enc.hard.add_lists(enc.hole_clauses(blocked), "no hole (H_c): these tiles absent or the hole's cells covered")
    enc.n_vars = base.n_vars
    return enc


@dataclass(frozen=True)
class _CoronaBase:
    """The clauses of ``levels`` coronas without blocked holes, shared by every encoding of
    that level (a level is encoded again for each hole found in its models)."""

    candidates: tuple
    var: dict
    cellvar: dict
    blocks: tuple
    n_vars: int

    def covered_up_to(self, c, level) -> list[int]:
        return [self.cellvar[(j, c)] for j in range(1, level + 1) if (j, c) in self.cellvar]


def _pairs(clauses: list) -> np.ndarray:
    return np.asarray(clauses, dtype=np.int64).reshape(-1, 2)


@functools.lru_cache(maxsize=8)
def _corona_base(g: Grid, shape: tuple, reflections: bool, levels: int) -> _CoronaBase:
    S = set(shape)
    halo_s = _halo(g, shape)
    candidates = _corona_candidates(g, shape, reflections, levels)
    var: dict = {}
    top = 0
    for level, cands in enumerate(candidates, 1):
        for i in range(len(cands)):
            top += 1
            var[(level, i)] = top
    covering: dict = {}
    for (level, i), v in var.items():
        for c in candidates[level - 1][i]:
            covering.setdefault((level, c), []).append(v)
    cellvar: dict = {}
    for key in sorted(covering):
        top += 1
        cellvar[key] = top
    cs = ClauseSet()
    # y[j, c] <-> some corona-j tile covers c
    cs.add_lists([[-y] + covering[key] for key, y in sorted(cellvar.items())], "cell of a corona: some tile")
    cs.add_array(_pairs([[-v, cellvar[(level, c)]] for (level, i), v in sorted(var.items())
                         for c in candidates[level - 1][i]]), "tile covers its cells")
    by_cell: dict = {}
    for (level, c), lits in covering.items():
        by_cell.setdefault(c, []).extend(lits)
    for c in sorted(by_cell):
        top = _at_most_one(cs, by_cell[c], top, "tiles disjoint")
    base = _CoronaBase(candidates, var, cellvar, (), top)
    covered_up_to = base.covered_up_to
    cs.add_lists([covered_up_to(c, 1) for c in sorted(halo_s)], "the shape is surrounded by corona 1")
    adjacency, lower, surround = [], [], []
    for (level, i), v in sorted(var.items()):
        halo = sorted(_halo(g, candidates[level - 1][i]) - S)
        if level >= 2:
            adjacency.append([-v] + [cellvar[(level - 1, c)] for c in halo if (level - 1, c) in cellvar])
            lower += [[-v, -cellvar[(j, c)]] for j in range(1, level - 1) for c in halo if (j, c) in cellvar]
        if level < levels:
            surround += [[-v] + covered_up_to(c, level + 1) for c in halo]
    cs.add_lists(adjacency, "a corona-j tile touches corona j-1")
    cs.add_array(_pairs(lower), "a corona-j tile touches no lower corona")
    cs.add_lists(surround, "corona j+1 surrounds corona j")
    return _CoronaBase(candidates, var, cellvar, tuple(cs.blocks), max(top, 1))


#: Cell codes of the surround encoding: ``(x + _OFF) * _W + (y + _OFF)`` (cells of a polyform of up
#: to :data:`tilesolve.model.shapes.MAX_CELLS` cells and its neighbours fit).
_OFF, _W = 1 << 16, 1 << 17


def _codes(cells: np.ndarray) -> np.ndarray:
    return (cells[..., 0] + _OFF) * _W + (cells[..., 1] + _OFF)


@functools.lru_cache(maxsize=8)
def point_group(g: Grid, reflections: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(matrices, product, inverse)``: the point group used (``(G, 2, 2)``, the identity
    first), its multiplication table (``product[a, b]`` is the index of ``M_a M_b``) and each
    element's inverse.

    Examples
    --------
    >>> from tilesolve.model.shapes import GRIDS
    >>> mats, product, inverse = point_group(GRIDS["omino"], True)
    >>> len(mats), int(product[1, 3]), int(inverse[1])
    (8, 0, 3)
    """
    mats = np.stack(g.matrices if reflections else g.matrices[: g.order])
    index = {m.tobytes(): i for i, m in enumerate(mats)}
    product = np.array([[index[(a @ b).tobytes()] for b in mats] for a in mats], dtype=np.int64)
    inverse = np.argmin(product, axis=1)  # the identity is element 0
    return mats, product, inverse


@dataclass
class SurroundEncoding:
    """A closed first corona around one shape (:func:`encode_surround`).

    Attributes
    ----------
    mats, product, inverse : numpy.ndarray
        The point group used (:func:`point_group`).
    m, t : numpy.ndarray
        Per candidate transform ``i``: its matrix's index ``m[i]`` and translation ``t[i]``
        (cell coordinates).
    var : numpy.ndarray
        Per candidate transform, its variable: ``T`` and ``T^-1`` share one (a closed surround
        holds both or neither).
    clauses : list of list of int
        The CNF.
    """

    grid: Grid
    shape: tuple
    mats: np.ndarray
    product: np.ndarray
    inverse: np.ndarray
    m: np.ndarray
    t: np.ndarray
    var: np.ndarray
    clauses: list = field(default_factory=list)

    @property
    def n_vars(self) -> int:
        return int(self.var.max(initial=0))

    def decode(self, model) -> list[int]:
        """The indices of the used transforms."""
        true = np.zeros(self.n_vars + 1, dtype=bool)
        lits = np.asarray(model, dtype=np.int64)
        true[lits[(lits > 0) & (lits <= self.n_vars)]] = True
        return np.flatnonzero(true[self.var]).tolist()

    def block(self, used: list[int]) -> list[int]:
        """The clause "not all of these transforms"."""
        return (-np.unique(self.var[used])).tolist()


def _rows(*cols: np.ndarray) -> list:
    """Clauses from literal columns: repeated literals and clauses left out, tautologies dropped."""
    a = np.sort(np.stack(cols, axis=1), axis=1)
    base = 2 * int(np.abs(a).max(initial=0)) + 1
    key = np.zeros(len(a), dtype=np.int64)
    for c in range(a.shape[1]):
        key = key * base + a[:, c] + base // 2
    a = a[np.unique(key, return_index=True)[1]]
    taut = np.zeros(len(a), dtype=bool)
    repeat = np.zeros(len(a), dtype=bool)
    for c in range(a.shape[1]):
        for d in range(c + 1, a.shape[1]):
            taut |= a[:, c] == -a[:, d]
            repeat |= a[:, c] == a[:, d]
    out = a[~taut & ~repeat].tolist()
    return out + [sorted(set(r)) for r in a[~taut & repeat].tolist()]


def encode_surround(problem: ShapesProblem, half_turns: bool = False) -> SurroundEncoding:
    """The CNF "``S`` has a closed surround" (module docstring); with ``half_turns``, of
    neighbours by translations and half-turns only (a group of them is closed: the tilings of
    Conway's criterion, and the lattice tilings), a CNF a quarter to a sixth the size.

    Every pair of candidates is classified at once from ``T_i^-1 T_j`` (whether its image of
    ``S`` overlaps ``S``, is adjacent to it or neither), with integer arrays.

    Examples
    --------
    >>> from tilesolve.model.shapes import parse_ascii
    >>> enc = encode_surround(ShapesProblem("classify", (parse_ascii("#", "omino"),)))
    >>> len(enc.m), enc.n_vars  # the 4 edge neighbours of a square under 8 symmetries; T and T^-1 paired
    (32, 20)
    """
    g = problem.geometry
    shape = problem.shapes[0].cells
    mats, product, inverse = point_group(g, problem.reflections)
    x = np.asarray(shape, dtype=np.int64)
    halo = np.asarray(sorted({n for c in shape for n in g.neighbours(c)} - set(shape)), dtype=np.int64)
    p = g.period
    images = np.einsum("gab,nb->gna", mats, x)  # (G, n, 2): M_g S
    # translations putting a cell of M_g S on a cell of S or on a cell sharing an edge with S
    near = np.concatenate((x, halo))
    t = (near[None, :, None, :] - images[:, None, :, :]).reshape(len(mats), -1, 2)
    keys, cells_of = [], []
    s_codes, h_codes = _codes(x), _codes(halo)
    plain = (mats[:, 0, 1] == 0) & (mats[:, 1, 0] == 0) & (mats[:, 0, 0] == mats[:, 1, 1])  # I and -I
    for gi in np.flatnonzero(plain) if half_turns else range(len(mats)):
        tg = t[gi]
        tc = np.unique(_codes(tg[(tg[:, 0] % p == 0) & (tg[:, 1] % p == 0)]))
        tg = np.stack((tc // _W - _OFF, tc % _W - _OFF), axis=1)
        c = _codes(images[gi][None, :, :] + tg[:, None, :])
        overlap = np.isin(c, s_codes).any(axis=1)
        adjacent = np.isin(c, h_codes).any(axis=1)
        # overlapping transforms (the identity too) get key parity 1, adjacent ones 0
        kind = np.where(overlap, 1, np.where(adjacent, 0, -1))
        keep = kind >= 0
        keys.append(((gi * _W * _W + tc) * 2 + kind)[keep])
        cells_of.append(c[keep & ~overlap])
    allkeys = np.sort(np.concatenate(keys))
    cand = allkeys[allkeys % 2 == 0] // 2  # adjacent transforms, sorted
    m = cand // (_W * _W)
    rest = cand % (_W * _W)
    t = np.stack((rest // _W - _OFF, rest % _W - _OFF), axis=1)
    k = len(m)
    # T^-1 of each candidate (a candidate too: T(S) is adjacent to S iff S is to T^-1(S)); a pair shares a variable
    inv_m = inverse[m]
    minv = mats[inv_m]
    ikey = inv_m * _W * _W + _codes(-np.einsum("kab,kb->ka", minv, t))
    inv_pos = np.searchsorted(cand, ikey)
    first = np.minimum(np.arange(k), inv_pos)
    var = np.unique(first, return_inverse=True)[1].reshape(-1) + 1
    enc = SurroundEncoding(g, shape, mats, product, inverse, m, t, var)
    # the cells sharing an edge with S are covered (each grid element's translations came sorted, as ``cand``)
    codes = np.concatenate(cells_of)
    clauses = [np.unique(var[(codes == h).any(axis=1)]).tolist() for h in h_codes]
    # every pair i < j: u = T_i^-1 T_j overlapping S (the tiles overlap) or adjacent to it (closure)
    i, j = np.triu_indices(k, 1)
    dx, dy = t[j, 0] - t[i, 0], t[j, 1] - t[i, 1]
    mi = minv[i]
    ux = mi[:, 0, 0] * dx + mi[:, 0, 1] * dy
    uy = mi[:, 1, 0] * dx + mi[:, 1, 1] * dy
    ukey = (product[inv_m[i], m[j]] * _W * _W + (ux + _OFF) * _W + (uy + _OFF)) * 2
    pos = np.searchsorted(allkeys, ukey)
    pos[pos >= len(allkeys)] = 0
    found = allkeys[pos]
    over = found == ukey + 1
    clauses += _rows(-var[i[over]], -var[j[over]])
    adjacent = found == ukey
    u = var[np.searchsorted(cand, ukey[adjacent] // 2)]
    clauses += _rows(-var[i[adjacent]], -var[j[adjacent]], u)
    enc.clauses = clauses
    return enc
