"""SAT and CP-SAT encodings of the tile packing problem (class notes §5.5).

One encoding serves Wang and corner tiles: both are "four shared features per cell".
A Wang tile's colours live on the torus's edges, a corner tile's on its lattice points
(the notes' "pegs", §5.5.3), and each tile is the base-C number of its four features
(eq. 2.1 / 2.5). Variables:

``place(p, t)``
    cell ``p = row * cols + col`` holds tile ``t``; one variable per *placement*, i.e. per
    pair ``(p, t)`` that the feature domains allow (all pairs unless domains are given);
``feat(f, k)``
    feature ``f`` (an edge or a lattice point) has colour ``k``; one variable per colour in
    the feature's domain.

Clauses: every feature has exactly one colour of its domain; ``place(p, t)`` implies the
four feature colours of ``t`` at ``p`` and is implied by them (so each cell holds exactly
the tile its features spell); every cell holds a tile; every tile is placed at least once
(the pigeonhole principle then makes it exactly once, and ``amo_tiles`` adds the
at-most-one side explicitly, which helps propagation). Pinned tiles are unit clauses, and
with no pins one tile may be pinned to cell (0, 0) to break the translation symmetry (every
packing has a translate with that tile there).

Feature domains are how the search routes shrink the problem without a second encoding:
the ``hybrid`` route fixes the colours of the horizontal edges and the ``lift`` route allows
each feature only the colours ``base + m*b`` over a packing with ``m`` colours. A restricted formula that is
unsatisfiable proves nothing about the packing problem itself; only the full-domain
formula's ``unsat`` is a proof.

Feature layout (``grid[row, col]``, row 0 at the top):

* Wang: ``H[r][c]`` is the edge north of cell ``(r, c)`` and ``V[r][c]`` the edge west of
  it, so the cell reads ``N = H[r][c]``, ``E = V[r][c+1]``, ``S = H[r+1][c]``, ``W = V[r][c]``.
  Feature ids: ``H[r][c] = r*cols + c``, ``V[r][c] = rows*cols + r*cols + c``.
* corner: ``P[r][c]`` is the lattice point north-west of cell ``(r, c)``, so the cell reads
  ``NE = P[r][c+1]``, ``SE = P[r+1][c+1]``, ``SW = P[r+1][c]``, ``NW = P[r][c]`` (mod the size).
  Feature ids: ``P[r][c] = r*cols + c``.

The encoding calls no solver (DESIGN.md, "Encodings").
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from tilesolve.deadline import Deadline
from tilesolve.encodings import ClauseSet, cardinality
from tilesolve.model.packing import PackingProblem

__all__ = [
    "PackingEncoding",
    "encode_packing",
    "build_cpsat_packing",
    "packing_features",
    "features_of_packing",
    "full_domains",
]


@dataclass
class PackingEncoding:
    """Clauses of a packing problem and the maps between variables and meaning.

    Attributes
    ----------
    problem : PackingProblem
    clauses : ClauseSet
    n_vars : int
    cell_features : numpy.ndarray
        ``(cells, 4)`` feature ids of each cell in the tile's side order.
    pair_cell, pair_tile : numpy.ndarray
        The placements: variable ``1 + i`` is "cell ``pair_cell[i]`` holds tile ``pair_tile[i]``",
        sorted by cell, then tile.
    feat_ids : numpy.ndarray
        ``(features, colours)`` variable of "feature ``f`` has colour ``k``", 0 where the
        domain excludes the colour.
    anchor : tuple or None
        ``(row, col, tile)`` pinned for symmetry breaking (``None`` when the problem has pins).
    restricted : bool
        True when domains exclude some colours: ``unsat`` then proves nothing.
    """

    problem: PackingProblem
    clauses: ClauseSet
    n_vars: int
    cell_features: np.ndarray
    pair_cell: np.ndarray
    pair_tile: np.ndarray
    feat_ids: np.ndarray
    anchor: tuple[int, int, int] | None = None
    amo_tiles: bool = True
    restricted: bool = False
    labels: list[str] = field(default_factory=list)

    @property
    def hard(self) -> ClauseSet:  # for tilesolve.io.dimacs
        return self.clauses

    @property
    def n_cells(self) -> int:
        return self.cell_features.shape[0]

    @property
    def n_placements(self) -> int:
        return int(self.pair_cell.size)

    def place_var(self, p, t):
        """Variable of "cell ``p`` holds tile ``t``" (works on arrays); 0 where the pair is not
        a placement of this encoding."""
        n = self.problem.n_tiles
        keys = self.pair_cell * n + self.pair_tile
        want = np.asarray(p, dtype=np.int64) * n + np.asarray(t, dtype=np.int64)
        i = np.minimum(np.searchsorted(keys, want), keys.size - 1)
        return np.where(keys[i] == want, i + 1, 0)

    def decode(self, model) -> np.ndarray:
        """The packing grid of a model (signed DIMACS literals, or CP-SAT's list of bools over
        the placement variables in order)."""
        m = np.asarray(model)
        if m.dtype == bool:
            val = m[: self.n_placements]
        else:
            truth = np.zeros(self.n_vars + 1, dtype=bool)
            m = m.astype(np.int64)
            m = m[np.abs(m) <= self.n_vars]
            truth[m[m > 0]] = True
            val = truth[1 : self.n_placements + 1]
        grid = np.full(self.n_cells, -1, dtype=np.int64)
        grid[self.pair_cell[val]] = self.pair_tile[val]
        rows, cols = self.problem.shape
        return grid.reshape(rows, cols)

    def projection(self) -> np.ndarray:
        """The placement variables (a model restricted to them determines the packing)."""
        return np.arange(1, self.n_placements + 1, dtype=np.int64)

    def literals(self, grid) -> list[int]:
        """Unit literals placing the tiles of ``grid`` (0 entries: pairs outside the domains)."""
        g = np.asarray(grid, dtype=np.int64).reshape(-1)
        return self.place_var(np.arange(g.size), g).tolist()

    def header(self) -> list[str]:
        p = self.problem
        lines = [
            f"tilesolve tile packing: {p.describe()}",
            f"variables 1..{self.n_placements}: placements (cell, tile), cell = row*{p.shape[1]} + col "
            "(row 0 at the top), sorted by cell then tile; tile index per eq. 2.1 (Wang N E S W) / 2.5 "
            "(corner NE SE SW NW)" + ("" if self.restricted else f"; variable = 1 + cell*{p.n_tiles} + tile"),
            f"variables {self.n_placements + 1}..{int(self.feat_ids.max())}: feature colours "
            + ("(Wang: edges)" if p.kind == "wang" else "(corner: lattice points)"),
        ]
        if self.anchor is not None:
            lines.append(f"symmetry breaking: tile {self.anchor[2]} pinned at row {self.anchor[0]}, col {self.anchor[1]}")
        return lines


def packing_features(problem: PackingProblem) -> tuple[np.ndarray, np.ndarray]:
    """``(cell_features, feature_colours)``: the ``(cells, 4)`` feature ids of every cell in
    the tile's side order, and the number of colours of every feature (layout: module doc)."""
    rows, cols = problem.shape
    r = np.arange(rows)[:, None].repeat(cols, 1)
    c = np.arange(cols)[None, :].repeat(rows, 0)
    rd, cr = (r + 1) % rows, (c + 1) % cols
    if problem.kind == "wang":
        ts = problem.tiles
        h = lambda rr, cc: rr * cols + cc  # noqa: E731 - H[r][c]
        v = lambda rr, cc: rows * cols + rr * cols + cc  # noqa: E731 - V[r][c]
        cf = np.stack([h(r, c), v(r, cr), h(rd, c), v(r, c)], axis=-1).reshape(-1, 4)
        colors = np.concatenate([np.full(rows * cols, ts.colors), np.full(rows * cols, ts.cv)])
    else:
        pt = lambda rr, cc: rr * cols + cc  # noqa: E731 - P[r][c]
        cf = np.stack([pt(r, cr), pt(rd, cr), pt(rd, c), pt(r, c)], axis=-1).reshape(-1, 4)
        colors = np.full(rows * cols, problem.colors)
    return cf.astype(np.int64), colors.astype(np.int64)


def features_of_packing(problem: PackingProblem, grid) -> np.ndarray:
    """The colour of every feature of a packing grid (edges for Wang, lattice points for corner).

    Each feature is read from the first cell that touches it; on a valid packing every cell
    agrees.
    """
    cf, fcol = packing_features(problem)
    tab = problem.tiles.table()
    out = np.full(fcol.size, -1, dtype=np.int64)
    cols = tab[np.asarray(grid, dtype=np.int64).ravel()]  # (cells, 4)
    out[cf.ravel()[::-1]] = cols.ravel()[::-1]
    return out


def full_domains(problem: PackingProblem) -> np.ndarray:
    """``(features, max colours)`` boolean mask allowing every colour of every feature."""
    _, fcol = packing_features(problem)
    return np.arange(fcol.max())[None, :] < fcol[:, None]


def _placements(cf: np.ndarray, domains: np.ndarray, radices) -> tuple[np.ndarray, np.ndarray]:
    """All (cell, tile) pairs whose four feature colours lie in the domains, sorted by cell
    then tile. Cells are grouped by the sizes of their four domains so that each group is
    one numpy broadcast (a full domain gives every tile to every cell)."""
    sizes = domains.sum(axis=1)
    order = np.argsort(~domains, axis=1, kind="stable")  # allowed colours first, ascending
    weights = np.array([radices[1] * radices[2] * radices[3], radices[2] * radices[3], radices[3], 1])
    csz = sizes[cf]  # (cells, 4)
    cells_out, tiles_out = [], []
    for key in np.unique(csz, axis=0):
        ps = np.flatnonzero((csz == key).all(axis=1))
        if (key == 0).any():
            continue
        code = np.zeros((ps.size, 1), dtype=np.int64)
        for s in range(4):
            cols = order[cf[ps, s], : key[s]]  # (cells, size_s)
            code = (code[:, :, None] + weights[s] * cols[:, None, :]).reshape(ps.size, -1)
        cells_out.append(np.repeat(ps, code.shape[1]))
        tiles_out.append(code.ravel())
    if not cells_out:
        return np.zeros(0, np.int64), np.zeros(0, np.int64)
    pc, pt = np.concatenate(cells_out), np.concatenate(tiles_out)
    srt = np.lexsort((pt, pc))
    return pc[srt].astype(np.int64), pt[srt].astype(np.int64)


def _ragged_groups(keys: np.ndarray, lits: np.ndarray, n_groups: int) -> list[list[int]]:
    """The literals grouped by key (0..n_groups-1), as one list per key (empty lists kept)."""
    srt = np.argsort(keys, kind="stable")
    bounds = np.searchsorted(keys[srt], np.arange(n_groups + 1))
    flat = lits[srt].tolist()
    return [flat[bounds[g] : bounds[g + 1]] for g in range(n_groups)]


def encode_packing(problem: PackingProblem, *, anchor_tile: int | None = 0, amo_tiles: bool = True,
                   domains: np.ndarray | None = None, deadline: Deadline | None = None) -> PackingEncoding:
    """CNF of a packing problem.

    Parameters
    ----------
    problem : PackingProblem
    anchor_tile : int or None
        Tile pinned to cell (0, 0) to break translation symmetry when the problem has no
        pins of its own (``None``: no symmetry breaking, e.g. to count all packings).
    amo_tiles : bool
        Add "each tile at most once" explicitly (sequential counter, :mod:`pysat.card`).
    domains : numpy.ndarray, optional
        ``(features, max colours)`` booleans: the colours each feature may take (default: all,
        :func:`full_domains`). An empty domain, or a tile no cell can hold, gives an empty
        clause (unsatisfiable).
    deadline : Deadline, optional
        Checked between blocks of clauses (:class:`~tilesolve.deadline.TimeLimitReached`).

    Examples
    --------
    >>> enc = encode_packing(PackingProblem("corner", 2))
    >>> enc.n_placements, enc.restricted
    (256, False)
    """
    from pysat.card import EncType
    from pysat.formula import IDPool

    ts = problem.tiles
    n = ts.n_tiles
    cf, fcol = packing_features(problem)
    full = full_domains(problem)
    if domains is None:
        domains = full
    domains = np.asarray(domains, dtype=bool)
    if domains.shape != full.shape:
        raise ValueError(f"domains must have shape {full.shape}, got {domains.shape}")
    domains = domains & full
    restricted = bool((domains != full).any())
    pc, pt = _placements(cf, domains, ts.radices)
    n_place = pc.size
    feat_ids = np.zeros(domains.shape, dtype=np.int64)
    feat_ids[domains] = n_place + 1 + np.arange(int(domains.sum()))
    top = n_place + int(domains.sum())
    enc = PackingEncoding(problem, ClauseSet(), top, cf, pc, pt, feat_ids, amo_tiles=amo_tiles, restricted=restricted)
    cs = enc.clauses

    def check() -> None:
        if deadline is not None:
            n = len(cs)
            deadline.check(f"encoding ({n / 1e6:.1f} M clauses built)" if n >= 100_000
                           else f"encoding ({n:,} clauses built)")

    check()
    # Features: exactly one colour of the domain (grouped by domain size for numpy blocks).
    sizes = domains.sum(axis=1)
    if (sizes == 0).any():
        cs.add_lists([[]], "a feature with an empty domain")
    srt = np.sort(feat_ids, axis=1)[:, ::-1]  # allowed variables first
    for k in np.unique(sizes[sizes > 0]):
        lits = srt[sizes == k][:, :k]
        cs.add_array(lits, f"feature has a colour ({k} allowed)")
        for a in range(k):
            for b in range(a + 1, k):
                cs.add_array(-np.stack([lits[:, a], lits[:, b]], axis=1), "feature has one colour")
            check()
    # Links between placements and features.
    pv = np.arange(1, n_place + 1, dtype=np.int64)
    tab = ts.table()
    fv = feat_ids[cf[pc], tab[pt]]  # (placements, 4)
    for s in range(4):
        check()
        cs.add_array(np.stack([-pv, fv[:, s]], axis=1), f"placement implies side {ts.sides[s]}")
    check()
    cs.add_array(np.concatenate([-fv, pv[:, None]], axis=1), "sides imply placement")
    cs.add_lists(_ragged_groups(pc, pv, enc.n_cells), "cell holds a tile")
    check()
    by_tile = _ragged_groups(pt, pv, n)
    cs.add_lists(by_tile, "tile is placed")
    check()
    if amo_tiles:
        pool = IDPool(start_from=top + 1)
        ragged: list = []
        for i, group in enumerate(by_tile):
            if len(group) > 1:
                ragged.extend(cardinality("atmost", group, 1, vpool=pool, encoding=EncType.seqcounter))
            if len(ragged) >= 1 << 15 or i == len(by_tile) - 1:  # in parts, with deadline checks
                cs.add_lists(ragged, "tile placed at most once", grid_only=False)
                ragged = []
                check()
        enc.n_vars = max(top, pool.top)
    # Pins: unit clauses on placements; a pin its cell's domains exclude is unsatisfiable here.
    pins = list(problem.fixed)
    if not pins and anchor_tile is not None:
        enc.anchor = (0, 0, int(anchor_tile))
        pins = [enc.anchor]
    rows, cols = problem.shape
    units = []
    for r, c, t in pins:
        v = int(enc.place_var(r * cols + c, t))
        units.append([v] if v else [])
    cs.add_lists(units, "pinned tiles" if problem.fixed else "symmetry breaking (translation)")
    return enc


def build_cpsat_packing(problem: PackingProblem, *, anchor_tile: int | None = 0, deadline: Deadline | None = None):
    """CP-SAT model of the same encoding, with native exactly-one constraints.

    Returns ``(model, place, enc)``; ``place`` is the list of the placement Booleans in
    variable order, which :meth:`PackingEncoding.decode` reads back. Building costs a Python
    call per constraint, so a ``deadline`` is checked every 4096 of them
    (:class:`~tilesolve.deadline.TimeLimitReached`).
    """
    from ortools.sat.python import cp_model

    enc = encode_packing(problem, anchor_tile=anchor_tile, amo_tiles=False, deadline=deadline)
    m = cp_model.CpModel()
    total = len(enc.clauses)
    if deadline is not None:
        deadline.check(f"building the CP-SAT model (0 of {total:,} constraints added)")
    bools = [None]
    for lo in range(1, enc.n_vars + 1, 4096):
        if deadline is not None:
            deadline.check(f"building the CP-SAT model ({lo - 1:,} of {enc.n_vars:,} variables created)")
        bools.extend(m.new_bool_var(f"v{i}") for i in range(lo, min(enc.n_vars, lo + 4095) + 1))
    done = 0
    for block in enc.clauses.blocks:
        exactly_one = block.label in ("cell holds a tile", "tile is placed")
        for chunk in block.lists(4096):
            if deadline is not None:
                deadline.check(f"building the CP-SAT model ({done:,} of {total:,} constraints added)")
            done += len(chunk)
            for cl in chunk:
                if exactly_one:
                    m.add_exactly_one([bools[v] for v in cl])
                elif len(cl) == 1:
                    m.add(bools[abs(cl[0])] == (1 if cl[0] > 0 else 0))
                else:
                    m.add_bool_or([bools[v] if v > 0 else bools[-v].Not() for v in cl])
    place = bools[1 : enc.n_placements + 1]
    return m, place, enc
