"""SAT and CP-SAT encodings of the tile packing problem (class notes §5.5).

One encoding serves Wang and corner tiles: both are "four shared features per cell".
A Wang tile's colours live on the torus's edges, a corner tile's on its lattice points
(the notes' "pegs", §5.5.3), and each tile is the base-C number of its four features
(eq. 2.1 / 2.5). Variables:

``place(p, t)``
    cell ``p = row * cols + col`` holds tile ``t``;
``feat(f, k)``
    feature ``f`` (an edge or a lattice point) has colour ``k``.

Clauses: every feature has exactly one colour; ``place(p, t)`` implies the four feature
colours of ``t`` at ``p`` and is implied by them (so each cell holds exactly the tile its
features spell); every cell holds a tile; every tile is placed at least once (the
pigeonhole principle then makes it exactly once, and :data:`PackingEncoding.amo_tiles`
adds the at-most-one side explicitly, which helps propagation). Pinned tiles are unit
clauses, and with no pins one tile is pinned to cell (0, 0) to break the translation
symmetry (every packing has a translate with that tile there).

Feature layout (``grid[row, col]``, row 0 at the top):

* Wang: ``H[r][c]`` is the edge north of cell ``(r, c)`` and ``V[r][c]`` the edge west of
  it, so the cell reads ``N = H[r][c]``, ``E = V[r][c+1]``, ``S = H[r+1][c]``, ``W = V[r][c]``.
* corner: ``P[r][c]`` is the lattice point north-west of cell ``(r, c)``, so the cell reads
  ``NE = P[r][c+1]``, ``SE = P[r+1][c+1]``, ``SW = P[r+1][c]``, ``NW = P[r][c]`` (mod the size).

The encoding calls no solver (DESIGN.md, "Encodings").
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from tilesolve.encodings import ClauseSet
from tilesolve.model.packing import PackingProblem

__all__ = ["PackingEncoding", "encode_packing", "build_cpsat_packing", "fix_horizontal_edges"]


@dataclass
class PackingEncoding:
    """Clauses of a packing problem and the maps between variables and meaning.

    Attributes
    ----------
    problem : PackingProblem
    clauses : ClauseSet
    n_vars : int
    anchor : tuple or None
        ``(row, col, tile)`` pinned for symmetry breaking (``None`` when the problem has pins).
    """

    problem: PackingProblem
    clauses: ClauseSet
    n_vars: int
    cell_features: np.ndarray  # (cells, 4) feature ids in the tile's side order
    feature_colors: np.ndarray  # (features,) domain size of each feature
    feature_offset: np.ndarray  # (features,) first variable of each feature
    anchor: tuple[int, int, int] | None = None
    amo_tiles: bool = True
    labels: list[str] = field(default_factory=list)

    @property
    def hard(self) -> ClauseSet:  # for tilesolve.io.dimacs
        return self.clauses

    @property
    def n_cells(self) -> int:
        return self.cell_features.shape[0]

    def place_var(self, p, t):
        """Variable of "cell ``p`` holds tile ``t``" (works on arrays)."""
        return 1 + np.asarray(p) * self.problem.n_tiles + np.asarray(t)

    def feat_var(self, f, k):
        """Variable of "feature ``f`` has colour ``k``" (works on arrays)."""
        return self.feature_offset[np.asarray(f)] + np.asarray(k)

    @property
    def place_vars(self) -> np.ndarray:
        """All placement variables, shape ``(cells, tiles)``."""
        n = self.problem.n_tiles
        return 1 + np.arange(self.n_cells * n, dtype=np.int64).reshape(self.n_cells, n)

    def decode(self, model) -> np.ndarray:
        """The packing grid of a model (signed DIMACS literals, or CP-SAT's list of bools over
        :attr:`place_vars` in row-major order)."""
        pv = self.place_vars
        m = np.asarray(model)
        if m.dtype == bool:
            val = m.reshape(pv.shape)
        else:
            truth = np.zeros(self.n_vars + 1, dtype=bool)
            m = m.astype(np.int64)
            m = m[np.abs(m) <= self.n_vars]
            truth[m[m > 0]] = True
            val = truth[pv]
        rows, cols = self.problem.shape
        return np.argmax(val, axis=1).reshape(rows, cols).astype(np.int64)

    def header(self) -> list[str]:
        p = self.problem
        rows, cols = p.shape
        lines = [
            f"tilesolve tile packing: {p.describe()}",
            f"variables 1..{self.n_cells * p.n_tiles}: place(cell, tile) = 1 + cell*{p.n_tiles} + tile, "
            f"cell = row*{cols} + col (row 0 at the top); tile index per eq. 2.1 (Wang N E S W) / 2.5 (corner NE SE SW NW)",
            f"variables {self.n_cells * p.n_tiles + 1}..{self.n_vars}: feature colours "
            + ("(Wang: edges)" if p.kind == "wang" else "(corner: lattice points)"),
        ]
        if self.anchor is not None:
            lines.append(f"symmetry breaking: tile {self.anchor[2]} pinned at row {self.anchor[0]}, col {self.anchor[1]}")
        return lines


def fix_horizontal_edges(enc: PackingEncoding, colours) -> None:
    """Wang only: pin the colour of every horizontal edge, ``colours[r][c]`` = ``H[r][c]`` (the
    edge north of cell ``(r, c)``), as unit clauses. With the N/S edges fixed, the search only
    places tiles along the rows and colours the vertical edges (the ``hybrid`` route)."""
    p = enc.problem
    if p.kind != "wang":
        raise ValueError("horizontal edges exist only for Wang tiles")
    rows, cols = p.shape
    h = np.asarray(colours, dtype=np.int64)
    if h.shape != (rows, cols):
        raise ValueError(f"expected a {rows}x{cols} array of edge colours, got {h.shape}")
    f = np.arange(rows * cols)  # H[r][c] is feature r * cols + c
    enc.clauses.add_array(enc.feat_var(f, h.ravel())[:, None], "horizontal edges fixed")


def _features(problem: PackingProblem) -> tuple[np.ndarray, np.ndarray]:
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


def encode_packing(problem: PackingProblem, *, anchor_tile: int | None = 0, amo_tiles: bool = True) -> PackingEncoding:
    """CNF of a packing problem.

    Parameters
    ----------
    problem : PackingProblem
    anchor_tile : int or None
        Tile pinned to cell (0, 0) to break translation symmetry when the problem has no
        pins of its own (``None``: no symmetry breaking, e.g. to count all packings).
    amo_tiles : bool
        Add "each tile at most once" explicitly (sequential counter, :mod:`pysat.card`).

    Examples
    --------
    >>> enc = encode_packing(PackingProblem("corner", 2))
    >>> enc.n_vars > 256, len(enc.clauses) > 0
    (True, True)
    """
    from pysat.card import CardEnc, EncType
    from pysat.formula import IDPool

    problem.check_search_size()
    ts = problem.tiles
    n = ts.n_tiles
    cf, fcol = _features(problem)
    cells = cf.shape[0]
    n_place = cells * n
    offset = n_place + 1 + np.concatenate([[0], np.cumsum(fcol)[:-1]]).astype(np.int64)
    top = int(n_place + fcol.sum())
    enc = PackingEncoding(problem, ClauseSet(), top, cf, fcol, offset, amo_tiles=amo_tiles)
    cs = enc.clauses
    # Features: exactly one colour.
    for k in np.unique(fcol):
        fs = np.flatnonzero(fcol == k)
        lits = offset[fs][:, None] + np.arange(k)[None, :]
        cs.add_array(lits, f"feature has a colour (C={k})")
        for a in range(k):
            for b in range(a + 1, k):
                cs.add_array(-np.stack([lits[:, a], lits[:, b]], axis=1), "feature has one colour")
    # Links between placements and features.
    tab = ts.table()  # (n, 4) colours in side order
    pv = enc.place_vars  # (cells, n)
    fv = offset[cf][:, None, :] + tab[None, :, :]  # (cells, n, 4)
    for s in range(4):
        cs.add_array(np.stack([-pv.ravel(), fv[:, :, s].ravel()], axis=1), f"placement implies side {ts.sides[s]}")
    cs.add_array(np.concatenate([-fv.reshape(-1, 4), pv.reshape(-1, 1)], axis=1), "sides imply placement")
    cs.add_array(pv, "cell holds a tile")
    cs.add_array(pv.T.copy(), "tile is placed")
    if amo_tiles:
        pool = IDPool(start_from=top + 1)
        ragged = []
        for t in range(n):
            ragged.extend(CardEnc.atmost(pv[:, t].tolist(), 1, vpool=pool, encoding=EncType.seqcounter).clauses)
        cs.add_lists(ragged, "tile placed at most once", grid_only=False)
        enc.n_vars = max(top, pool.top)
    # Pins.
    pins = list(problem.fixed)
    if not pins and anchor_tile is not None:
        enc.anchor = (0, 0, int(anchor_tile))
        pins = [enc.anchor]
    rows, cols = problem.shape
    units = [[int(enc.place_var(r * cols + c, t))] for r, c, t in pins]
    cs.add_lists(units, "pinned tiles" if problem.fixed else "symmetry breaking (translation)")
    return enc


def build_cpsat_packing(problem: PackingProblem, *, anchor_tile: int | None = 0):
    """CP-SAT model of the same encoding, with native exactly-one constraints.

    Returns ``(model, place_vars)``; ``place_vars`` is the flat row-major list of the
    placement Booleans, which :meth:`PackingEncoding.decode` reads back.
    """
    from ortools.sat.python import cp_model

    enc = encode_packing(problem, anchor_tile=anchor_tile, amo_tiles=False)
    m = cp_model.CpModel()
    bools = [None] + [m.new_bool_var(f"v{i}") for i in range(1, enc.n_vars + 1)]
    for block in enc.clauses.blocks:
        if block.label in ("cell holds a tile", "tile is placed"):
            continue
        for chunk in block.lists():
            for cl in chunk:
                if len(cl) == 1:
                    m.add(bools[abs(cl[0])] == (1 if cl[0] > 0 else 0))
                else:
                    m.add_bool_or([bools[v] if v > 0 else bools[-v].Not() for v in cl])
    pv = enc.place_vars
    for p in range(pv.shape[0]):
        m.add_exactly_one([bools[int(v)] for v in pv[p]])
    for t in range(pv.shape[1]):
        m.add_exactly_one([bools[int(v)] for v in pv[:, t]])
    place = [bools[int(v)] for v in pv.ravel()]
    return m, place, enc
