"""SAT and CP-SAT encodings of Wang tiling problems on boards (Def. 2 of the brick paper).

One variable per (edge, colour): ``x(e, c)`` is true when edge ``e`` has colour ``c``
(one-hot, exactly one colour per edge; legs that are joined share their edge, so matching
colours is built in). Boundary constraints are unit clauses.

Cells, for any tile set ``W``: one selector per (cell, tile) with "some tile" per cell and
"tile t at cell a implies the colour of each leg" (the support encoding of a table
constraint; no at-most-one is needed since the legs' colours pin the tile). For brick
Wang tiles (Def. 9) a smaller exact encoding: two auxiliary variables per cell,
``h(a) <-> W = E`` and ``v(a) <-> N = S`` (c1 = c3, c2 = c4), and ``h(a) xor v(a)``. Line limits (dappled
paper §4) forbid ``max_h + 1`` consecutive ``h`` cells along a row (out of the E leg into
the W leg of the next) and ``max_v + 1`` consecutive ``v`` cells down a column.

Nothing here calls a solver (DESIGN.md, "Encodings").
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Iterator

import numpy as np

from tilesolve.deadline import Deadline
from tilesolve.encodings import ClauseSet
from tilesolve.model.board import PAPER_LEGS, E, N, S, W, BoardProblem

__all__ = ["WangEncoding", "encode_wang", "build_cpsat_wang", "line_windows"]


@dataclass
class WangEncoding:
    """A CNF for a board problem plus what is needed to decode a model.

    Attributes
    ----------
    clauses : ClauseSet
    edge_of_leg : numpy.ndarray
        ``(n_cells, 4)`` edge number of each leg.
    n_edges, n_colors : int
    n_vars : int
        Largest variable used.
    """

    clauses: ClauseSet
    edge_of_leg: np.ndarray
    n_edges: int
    n_colors: int
    n_vars: int
    h_var: np.ndarray | None = None
    v_var: np.ndarray | None = None

    @property
    def hard(self) -> ClauseSet:
        """The clauses (the name the engine's proof checking uses)."""
        return self.clauses

    def var(self, edge, colour):
        """The variable ``x(edge, colour)`` (vectorised)."""
        return 1 + np.asarray(edge, dtype=np.int64) * self.n_colors + np.asarray(colour, dtype=np.int64)

    #: The formula is the whole problem: an unsat answer is a refutation.
    restricted = False

    def projection(self) -> np.ndarray:
        """The edge-colour variables (a tiling is determined by them)."""
        return np.arange(1, self.n_edges * self.n_colors + 1, dtype=np.int64)

    def decode(self, model) -> np.ndarray:
        """``(n_cells, 4)`` leg colours from a DIMACS model (signed literals)."""
        m = np.asarray(model, dtype=np.int64)
        vals = np.zeros(self.n_vars + 1, dtype=bool)
        m = m[np.abs(m) <= self.n_vars]
        vals[np.abs(m)] = m > 0
        onehot = vals[1 : self.n_edges * self.n_colors + 1].reshape(self.n_edges, self.n_colors)
        colour = onehot.argmax(axis=1)
        return colour[self.edge_of_leg]

    def header(self) -> list[str]:
        """DIMACS comment lines describing the variables."""
        return [
            f"tilesolve board tiling: {self.n_edges} edges, {self.n_colors} colours",
            f"variables 1..{self.n_edges * self.n_colors}: x(edge, colour) = 1 + edge*{self.n_colors} + colour "
            "(edge numbers: tilesolve.model.board.Board.leg_edges; legs N, E, S, W)",
            f"variables above {self.n_edges * self.n_colors}: tile selectors and line-length auxiliaries",
        ]

    def literals(self, tiling) -> list[int]:
        """Unit literals that pin the edge colours of ``tiling`` (to check it satisfies the CNF)."""
        t = np.asarray(tiling, dtype=np.int64)
        col = np.zeros(self.n_edges, dtype=np.int64)
        col[self.edge_of_leg.ravel()] = t.ravel()
        return self.var(np.arange(self.n_edges), col).tolist()


def line_windows(nbr_cell: np.ndarray, nbr_leg: np.ndarray, axis: str, length: int) -> np.ndarray:
    """Cell indices of every straight run of ``length`` cells, one row per window.

    A run steps out of the E leg into the W leg of the next cell (``"H"``) or out of the S
    leg into the N leg (``"V"``); windows that leave the board are dropped. A run that comes
    back to its first cell goes round a cycle (a torus's row) for ever: once every run still on
    the board has done so, its windows stop there, each holding its whole cycle (a longer window
    would only repeat those cells, and forbid the same lines). So the work is bounded by the
    board, not by ``length``: windows shorter than the board's longest run (or cycle) are the
    same whatever ``length`` is, and a ``length`` beyond every straight run gives none.

    >>> from tilesolve.model.board import Board
    >>> t = Board.torus(3, 1)
    >>> line_windows(t.nbr_cell, t.nbr_leg, "H", 10**9).tolist()
    [[0, 1, 2, 0], [1, 2, 0, 1], [2, 0, 1, 2]]
    """
    out_leg, in_leg = (E, W) if axis == "H" else (S, N)
    n = nbr_cell.shape[0]
    nxt = np.where((nbr_cell[:, out_leg] >= 0) & (nbr_leg[:, out_leg] == in_leg), nbr_cell[:, out_leg], -1)
    cols = [np.arange(n, dtype=np.int64)]
    ok = np.ones(n, dtype=bool)
    cycled = np.zeros(n, dtype=bool)  # runs that came back to their first cell
    for _ in range(length - 1):
        if not (ok & ~cycled).any():
            break
        prev = cols[-1]
        step = np.where(ok, nxt[np.where(ok, prev, 0)], -1)
        ok &= step >= 0
        cycled |= ok & (step == cols[0])
        cols.append(np.where(ok, step, 0))
    return np.stack(cols, axis=1)[ok]


def _exactly_one(first: np.ndarray, k: int) -> Iterator[np.ndarray]:
    """Clauses saying exactly one of ``first[:, None] + arange(k)`` is true (pairwise AMO),
    one block at a time (the caller checks its deadline between blocks)."""
    lits = first[:, None] + np.arange(k)[None, :]
    yield lits
    for i in range(k):
        for j in range(i + 1, k):
            yield np.stack([-lits[:, i], -lits[:, j]], axis=1)


def encode_wang(problem: BoardProblem, *, deadline: Deadline | None = None) -> WangEncoding:
    """Encode ``problem`` as CNF (see the module docstring).

    A ``deadline`` is checked after every block of clauses
    (:class:`~tilesolve.deadline.TimeLimitReached` when it has passed).

    Examples
    --------
    >>> from tilesolve.model.board import Board, WangTileSet, BoardProblem
    >>> enc = encode_wang(BoardProblem(Board.rect(2, 2), WangTileSet.brick(3)))
    >>> enc.n_edges, enc.n_vars
    (12, 44)
    """
    board = problem.board
    k = problem.n_colors
    eid, ne = board.leg_edges()
    n = board.n_cells
    if deadline is not None:
        deadline.check("encoding (numbering the edges)")
    cs = _CheckedClauseSet(deadline)
    for i, b in enumerate(_exactly_one(1 + np.arange(ne, dtype=np.int64) * k, k)):
        cs.add_array(b, "edge has a colour" if i == 0 else "edge has at most one colour")
    top = ne * k
    x = lambda e, c: 1 + e * k + c  # noqa: E731
    # boundary constraints, by cell, then by leg l1..l4 (the clause order of recorded CNFs)
    wa, wl = np.nonzero(board.nbr_cell[:, PAPER_LEGS] < 0)
    wl = PAPER_LEGS[wl]
    beta = problem.boundary[board.nbr_leg[wa, wl]]
    fixed = beta >= 0
    cs.add_array(x(eid[wa[fixed], wl[fixed]], beta[fixed])[:, None], "boundary colours")
    h_var = v_var = None
    if problem.tileset.is_brick:
        h_var = top + 1 + np.arange(n, dtype=np.int64)
        v_var = top + 1 + n + np.arange(n, dtype=np.int64)
        top += 2 * n
        for aux, (p, q) in ((h_var, (W, E)), (v_var, (N, S))):
            ep, eq = eid[:, p], eid[:, q]
            for c in range(k):
                # x(ep,c) & x(eq,c) -> aux ; aux & x(ep,c) -> x(eq,c)
                cs.add_array(np.stack([-x(ep, c), -x(eq, c), aux], axis=1), "brick: equal colours -> straight")
                cs.add_array(np.stack([-aux, -x(ep, c), x(eq, c)], axis=1), "brick: straight -> equal colours")
        cs.add_array(np.stack([h_var, v_var], axis=1), "brick: a straight line (Def. 9)")
        cs.add_array(np.stack([-h_var, -v_var], axis=1), "brick: no cross (Def. 9)")
        for lim, aux, axis in ((problem.max_h, h_var, "H"), (problem.max_v, v_var, "V")):
            if lim is not None:
                win = line_windows(board.nbr_cell, board.nbr_leg, axis, lim + 1)
                cs.add_array(-aux[win], f"no {axis} line longer than {lim}")
    else:
        tiles = problem.tileset.tiles
        m = tiles.shape[0]
        y = top + 1 + np.arange(n, dtype=np.int64)[:, None] * m + np.arange(m)[None, :]
        top += n * m
        cs.add_array(y, "cell has a tile")
        for leg in PAPER_LEGS:
            cs.add_array(
                np.stack([-y.ravel(), x(np.repeat(eid[:, leg], m), np.tile(tiles[:, leg], n))], axis=1),
                "tile fixes its leg colours",
            )
    out = ClauseSet()
    out.blocks = cs.blocks
    return WangEncoding(out, eid, ne, k, top, h_var, v_var)


class _CheckedClauseSet(ClauseSet):
    """A ClauseSet under construction that checks a deadline after every block added."""

    def __init__(self, deadline: Deadline | None) -> None:
        super().__init__()
        self.deadline = deadline

    def add_array(self, lits, label: str, grid_only: bool = True) -> None:
        super().add_array(lits, label, grid_only)
        if self.deadline is not None:
            n = len(self)
            built = f"{n / 1e6:.1f} M" if n >= 100_000 else f"{n:,}"
            self.deadline.check(f"encoding ({built} clauses built)")


@dataclass
class CpSatWang:
    """A CP-SAT model of a board problem: ``model``, the one-hot ``bools`` (edge-major)."""

    model: object
    bools: list
    edge_of_leg: np.ndarray
    n_edges: int
    n_colors: int

    def decode(self, values) -> np.ndarray:
        v = np.asarray(values, dtype=bool).reshape(self.n_edges, self.n_colors)
        return v.argmax(axis=1)[self.edge_of_leg]


def build_cpsat_wang(problem: BoardProblem, *, deadline: Deadline | None = None) -> CpSatWang:
    """CP-SAT model: an integer colour per edge, a table constraint (allowed tuples = W) per
    cell, boundary colours fixed; one-hot Booleans channelled to the integers for read-back.

    Line-length limits are not modelled here (use the SAT route for them). Building costs a
    few Python calls per edge and cell, so a ``deadline`` is checked every 4096 of them
    (:class:`~tilesolve.deadline.TimeLimitReached`).
    """
    from ortools.sat.python import cp_model

    from tilesolve.errors import MethodNotApplicable

    if problem.has_line_limits:
        raise MethodNotApplicable("the CP-SAT model has no line-length limits; use method 'sat'")
    board = problem.board
    k = problem.n_colors
    eid, ne = board.leg_edges()
    m = cp_model.CpModel()
    def check(i: int, total: int, what: str) -> None:
        if deadline is not None and i % 4096 == 0:
            deadline.check(f"building the CP-SAT model ({i:,} of {total:,} {what})")

    ints = []
    for e in range(ne):
        check(e, ne, "edge variables")
        ints.append(m.new_int_var(0, k - 1, f"e{e}"))
    bools = []
    for e in range(ne):
        check(e, ne, "edges")
        bs = [m.new_bool_var(f"e{e}c{c}") for c in range(k)]
        m.add_exactly_one(bs)
        m.add(ints[e] == sum(c * b for c, b in enumerate(bs)))
        bools.extend(bs)
    wa, wl = np.nonzero(board.nbr_cell < 0)
    for a, leg in zip(wa.tolist(), wl.tolist()):
        col = int(problem.boundary[board.nbr_leg[a, leg]])
        if col >= 0:
            m.add(ints[eid[a, leg]] == col)
    table = [tuple(int(v) for v in t) for t in problem.tileset.tiles]
    for a in range(board.n_cells):
        check(a, board.n_cells, "cells")
        m.add_allowed_assignments([ints[int(e)] for e in eid[a]], table)
    return CpSatWang(m, bools, eid, ne, k)
