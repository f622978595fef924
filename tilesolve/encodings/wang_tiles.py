"""A tile-selection CNF for Wang tilings of any board, built for squares and tori of large sets.

The board encoding of :mod:`tilesolve.encodings.wang` has a variable per (edge, colour) and
one per (cell, tile), linked by "tile t implies its leg colours": a solver must guess colours
before propagation reaches the next cell. Here there is one variable ``y(a, t)`` per (cell,
tile) only (class notes Part II §8.2: a tiling is a choice of one tile per cell with matching
edges), exactly one tile per cell, and for every leg of every cell joined to another the
*support* clauses

    ``y(a, t) -> OR { y(b, u) : u's leg kb has the colour of t's leg k }``

(``(a, k)`` meets ``(b, kb)``), from both sides. Unit propagation on them is arc consistency
between neighbouring cells, which the colour encoding reaches only after decisions; with them
CaDiCaL tiles a 40 x 40 Jeandel–Rao square in under a second (benchmarks/bench_aperiodic.py).

Optionally ``allowed`` restricts which pairs of tiles may sit side by side (E-W) or one above
the other (S-N), e.g. to the pairs seen in the interior of a smaller tiling: a *restricted*
formula whose models are still tilings (verified like any other) but whose unsatisfiability
proves nothing (``restricted = True``: :func:`tilesolve.engine.routes.sat_route` reports it
``unknown``).

Nothing here calls a solver (DESIGN.md, "Encodings").
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tilesolve.deadline import Deadline
from tilesolve.encodings import ClauseSet
from tilesolve.model.board import LEG_NAMES, PAPER_LEGS, E, N, S, W, Board, WangTileSet

__all__ = ["TileEncoding", "encode_tiles"]

_OPPOSITE = (2, 3, 0, 1)  # the leg a leg meets on a grid: W-E, N-S


@dataclass
class TileEncoding:
    """The CNF and how to read a tiling back.

    Attributes
    ----------
    clauses : ClauseSet
    n_cells, n_tiles : int
    labels : numpy.ndarray
        ``(n_cells, 2)`` (row, col) of each cell.
    restricted : bool
        True when ``allowed`` pairs cut the search space (an unsat answer proves nothing).
    """

    clauses: ClauseSet
    n_cells: int
    n_tiles: int
    labels: np.ndarray
    restricted: bool = False

    @property
    def hard(self) -> ClauseSet:
        return self.clauses

    @property
    def n_vars(self) -> int:
        return self.n_cells * self.n_tiles

    def projection(self) -> np.ndarray:
        return np.arange(1, self.n_vars + 1, dtype=np.int64)

    def decode(self, model) -> np.ndarray:
        """The ``(rows, cols)`` grid of tile indices (``-1`` where the board has no cell)."""
        m = np.asarray(model, dtype=np.int64)
        m = m[(m > 0) & (m <= self.n_vars)]
        vals = np.zeros(self.n_vars + 1, dtype=bool)
        vals[m] = True
        tile = vals[1:].reshape(self.n_cells, self.n_tiles).argmax(axis=1)
        rows, cols = self.labels[:, 0], self.labels[:, 1]
        grid = np.full((int(rows.max()) + 1, int(cols.max()) + 1), -1, dtype=np.int64)
        grid[rows, cols] = tile
        return grid

    def literals(self, grid) -> list[int]:
        """Unit literals pinning ``grid`` (to check it satisfies the CNF)."""
        g = np.asarray(grid, dtype=np.int64)
        t = g[self.labels[:, 0], self.labels[:, 1]]
        return (1 + np.arange(self.n_cells) * self.n_tiles + t).tolist()

    def part(self, cells) -> ClauseSet:
        """The clauses whose variables all belong to ``cells`` (a boolean mask over the board's
        cells), in this formula's variables: the formula of the sub-board on those cells, and
        the units that forbid a tile with no possible neighbour across a leg leaving them.

        A subset of this formula, so a DRAT proof of it whose lemmas are all RUP refutes this
        formula too (a refutation of a band of a torus refutes the torus).

        Examples
        --------
        >>> enc = encode_tiles(Board.rect(3, 1), WangTileSet([[0, 0, 0, 0]], 1))
        >>> len(enc.part([True, True, False])), len(enc.hard)
        (4, 7)
        """
        mask = np.asarray(cells, dtype=bool)
        out = ClauseSet()
        for b in self.clauses.blocks:  # encode_tiles builds rectangular blocks only
            out.add_array(b.lits[mask[(np.abs(b.lits) - 1) // self.n_tiles].all(axis=1)], b.label)
        return out

    def header(self) -> list[str]:
        return [f"tilesolve Wang tile selection: {self.n_cells} cells, {self.n_tiles} tiles",
                f"variable 1 + cell*{self.n_tiles} + tile: tile at cell (cells in board order, tiles sorted)"]


def encode_tiles(board: Board, tileset: WangTileSet, *, allowed: tuple[np.ndarray, np.ndarray] | None = None,
                 deadline: Deadline | None = None) -> TileEncoding:
    """Encode "``tileset`` tiles ``board``" (boundary legs free) as CNF (module docstring).

    Parameters
    ----------
    board : Board
        Any board; joined legs must be opposite legs (W-E, N-S), as on rectangles and (sheared) tori.
    tileset : WangTileSet
    allowed : (numpy.ndarray, numpy.ndarray), optional
        Boolean ``(m, m)`` matrices: ``[t, u]`` true when ``u`` may sit east of ``t`` (first)
        and south of ``t`` (second). Makes the formula restricted.
    deadline : Deadline, optional
        Checked between blocks of clauses.

    Examples
    --------
    >>> ws = WangTileSet([[0, 0, 0, 0], [1, 1, 1, 1]], 2)
    >>> enc = encode_tiles(Board.torus(2, 2), ws)
    >>> enc.n_vars, len(enc.hard)
    (8, 40)
    """
    tiles = tileset.tiles
    m = int(tiles.shape[0])
    n = board.n_cells
    nc, nl = board.nbr_cell, board.nbr_leg
    joined = nc >= 0
    if (joined & (nl != np.array(_OPPOSITE)[None, :])).any():
        raise ValueError("encode_tiles takes boards whose joined legs are opposite (W-E, N-S)")
    cs = ClauseSet()
    y0 = 1 + np.arange(n, dtype=np.int64)[:, None] * m  # y(a, t) = y0[a] + t
    cs.add_array(y0 + np.arange(m)[None, :], "cell has a tile")
    i, j = np.triu_indices(m, 1)
    if i.size:
        cs.add_array(np.stack([-(y0 + i[None, :]), -(y0 + j[None, :])], axis=2).reshape(-1, 2),
                     "cell has at most one tile")
    for k in PAPER_LEGS:  # l1..l4: the clause order of recorded CNFs
        a = np.flatnonzero(joined[:, k])
        if a.size == 0:
            continue
        b = nc[a, k]
        kb = _OPPOSITE[k]
        compat = tiles[:, k][:, None] == tiles[:, kb][None, :]  # [t, u]
        if allowed is not None:
            east, south = allowed
            pair = {E: east, S: south, W: east.T, N: south.T}[k]
            compat = compat & np.asarray(pair, dtype=bool)
        for t in range(m):
            us = np.flatnonzero(compat[t])
            lits = np.concatenate([-(y0[a] + t), y0[b] + us[None, :]], axis=1)
            cs.add_array(lits, f"tile {t} has a matching neighbour across leg {LEG_NAMES[k]}")
        if deadline is not None:
            deadline.check(f"encoding ({len(cs):,} clauses built)")
    return TileEncoding(cs, n, m, board.labels, restricted=allowed is not None)
