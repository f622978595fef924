"""Boards, Wang tile sets and tiling problems on boards.

From Derouet-Jourdan, Kaji, Mizoguchi, *A linear algorithm for brick Wang tiling* (2016):
boards (Def. 1), restrictions ``G|U`` (Def. 4), the Möbius strip (Example 5), tiling
problems (Def. 2), the three-boundary condition (Def. 6) and the brick Wang tiles
(Def. 9).

Conventions
-----------
Cells carry ``[row, col]`` labels (row 0 at the top) and are numbered ``0 .. n-1`` in
row-major order of their labels.

A Wang tile has one edge order everywhere, **N, E, S, W** (class notes §2.7): the rows of
:class:`WangTileSet`, tile-set files, board-solution files (version 3), reports, the CLI's
text, and inside the board model. Every cell has four *legs*, numbered in that order,

    N (0), E (1), S (2), W (3)

going round the cell, so legs ``k`` and ``(k + 2) % 4`` are opposite. The brick paper
numbers the same legs l1 = W, l2 = N, l3 = E, l4 = S, so its l1..l4 are legs 3, 0, 1, 2
here; Def. 9's pairs l1/l3 and l2/l4 are the pairs W/E (legs 3, 1) and N/S (legs 0, 2). The
kernels, the encodings and the verifier read the legs; a board tiling (``Solution.tiling`` of
the board family) is the ``(n, 4)`` array of each cell's leg colours in this order, as the
columns of :attr:`Board.nbr_cell` are, so a row of it is the cell's tile as
:class:`WangTileSet` lists it. Colours are ``0 .. n_colors-1`` (the paper's ``C = {1..m}``
shifted by one). Board-solution files of versions 1 and 2 list the legs W, N, E, S; their
reader converts them (:mod:`tilesolve.io.board_json`).

A board is stored as two ``(n, 4)`` int64 arrays: ``nbr_cell[a, k]`` is the cell joined to
leg ``k`` of cell ``a`` and ``nbr_leg[a, k]`` the leg of that cell it meets, or
``nbr_cell[a, k] = -1`` for the wall and then ``nbr_leg[a, k]`` is the number of that
*boundary leg* (``0 .. n_boundary-1``; the builders number them in order of cell, then of leg,
so a boundary given as a list reads as the tiles do).

Boards cut from a grid (rectangles, tori, cylinders, Möbius strips, Klein bottles, rings,
masks, and their restrictions) also carry their :class:`GridSpec`: the grid's size and how
its sides are identified. With the mask of the cells present, that rebuilds the board
exactly (:meth:`Board.from_grid_spec`), which is how solution files store such boards.
Reading mask *files* (PNG or text) is :mod:`tilesolve.io.mask`'s job; this module parses
in-memory text only.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from tilesolve.errors import InvalidProblem

__all__ = [
    "N", "E", "S", "W", "LEG_NAMES", "PAPER_LEGS", "MAX_BOARD_CELLS", "MAX_BRICK_COLORS", "GRID_KINDS",
    "GridSpec", "Board", "grid_kind", "kind_mask", "described_board", "WangTileSet", "BoardProblem",
    "parse_board_spec", "parse_mask_text",
    "colour_rows", "random_boundary",
]

N, E, S, W = 0, 1, 2, 3
LEG_NAMES = ("N", "E", "S", "W")
#: The brick paper's legs l1..l4 (W, N, E, S) as leg numbers: the order in which the board
#: encodings number edges and list clauses, which recorded CNF digests fix.
PAPER_LEGS = np.array([W, N, E, S])
PAPER_LEGS.setflags(write=False)
#: Largest board any route accepts.
MAX_BOARD_CELLS = 1 << 26
#: Most colours for brick tiles: building W_B enumerates all K^4 colourings (64 bytes each
#: while it is built), so K = 64 already needs 1 GiB.
MAX_BRICK_COLORS = 63
#: The grid boards the builders make, by kind: how each identifies its sides
#: ``(wrap_rows, wrap_cols)`` (see :meth:`Board.grid`). A kind followed by ``|U`` is a
#: restriction of such a board (Def. 4), e.g. ``"mobius|U"``.
GRID_KINDS: dict[str, tuple[str | None, str | None]] = {
    "rect": (None, None), "torus": ("plain", "plain"), "cylinder": (None, "plain"), "mobius": (None, "twist"),
    "klein": ("plain", "twist"), "ring": (None, None), "mask": (None, None), "tree": (None, None),
}
_FULL_KINDS = frozenset({"rect", "torus", "cylinder", "mobius", "klein"})

_DELTA = {N: (-1, 0), E: (0, 1), S: (1, 0), W: (0, -1)}
_PAPER_RANK = np.argsort(PAPER_LEGS)  # where each leg N, E, S, W comes among l1..l4
_WRAPS = (None, "plain", "twist")


class GridSpec(NamedTuple):
    """The grid a board is cut from: ``rows x cols`` cells, sides identified by
    ``wrap_rows`` / ``wrap_cols`` (``None``, ``"plain"`` or ``"twist"``, see :meth:`Board.grid`).

    The board's cells are then the cells of a boolean ``(rows, cols)`` mask, numbered in
    row-major order, with the joins and boundary-leg numbers :meth:`Board.grid` gives them.
    """

    rows: int
    cols: int
    wrap_rows: str | None = None
    wrap_cols: str | None = None


@dataclass(frozen=True, eq=False)
class Board:
    """A board (Def. 1): cells with four ordered legs, joined to cells or to the wall.

    Parameters
    ----------
    labels : numpy.ndarray
        ``(n, 2)`` int64 ``[row, col]`` label of each cell.
    nbr_cell, nbr_leg : numpy.ndarray
        ``(n, 4)`` int64 joins (see the module docstring).
    kind : str
        How it was built (``"rect"``, ``"torus"``, ``"mobius"``, ``"mask"``, ...).
    grid_spec : GridSpec, optional
        The grid the board is cut from, set by the grid builders and kept by
        :meth:`restrict`; ``None`` for boards given by their joins alone. One given here is
        checked against the joins.

    Examples
    --------
    >>> b = Board.rect(3, 2)
    >>> b.n_cells, b.n_boundary, b.n_edges
    (6, 10, 17)
    >>> int(b.nbr_cell[0, E]), int(b.nbr_leg[0, E])  # cell 1's W leg
    (1, 3)
    """

    labels: np.ndarray
    nbr_cell: np.ndarray
    nbr_leg: np.ndarray
    kind: str = "board"
    grid_spec: GridSpec | None = None

    def __post_init__(self) -> None:
        lab = np.ascontiguousarray(np.asarray(self.labels, dtype=np.int64).reshape(-1, 2))
        nc = np.ascontiguousarray(np.asarray(self.nbr_cell, dtype=np.int64))
        nl = np.ascontiguousarray(np.asarray(self.nbr_leg, dtype=np.int64))
        n = lab.shape[0]
        if nc.shape != (n, 4) or nl.shape != (n, 4):
            raise InvalidProblem(f"board joins must have shape ({n}, 4), got {nc.shape} and {nl.shape}")
        if n > MAX_BOARD_CELLS:
            raise InvalidProblem(f"board has {n:,} cells; tilesolve refuses more than {MAX_BOARD_CELLS:,}")
        if n and lab.min() < 0:
            i = int(np.flatnonzero((lab < 0).any(axis=1))[0])
            raise InvalidProblem(f"cell {i} has the label {lab[i].tolist()}; labels are [row, col] with row, col >= 0")
        if n > 1:
            order = np.lexsort((lab[:, 1], lab[:, 0]))
            same = np.flatnonzero((lab[order[1:]] == lab[order[:-1]]).all(axis=1))
            if same.size:
                i, j = sorted(int(v) for v in order[same[0]:same[0] + 2])
                raise InvalidProblem(f"cells {i} and {j} have the same label {lab[i].tolist()}")
        if n and ((nc < -1) | (nc >= n)).any():
            raise InvalidProblem("board joins name a cell that does not exist")
        inner = nc >= 0
        if inner.any():
            a, k = np.nonzero(inner)
            b, kb = nc[a, k], nl[a, k]
            if ((kb < 0) | (kb > 3)).any():
                raise InvalidProblem("board joins name a leg outside 0..3")
            if not (np.array_equal(nc[b, kb], a) and np.array_equal(nl[b, kb], k)):
                i = int(np.flatnonzero((nc[b, kb] != a) | (nl[b, kb] != k))[0])
                raise InvalidProblem(
                    f"board joins are not symmetric: leg {int(k[i])} of cell {lab[a[i]].tolist()} meets leg "
                    f"{int(kb[i])} of cell {lab[b[i]].tolist()}, which does not meet it back"
                )
        wall = ~inner
        nb = int(wall.sum())
        if nb and not np.array_equal(np.sort(nl[wall]), np.arange(nb)):
            raise InvalidProblem("boundary legs must be numbered 0..n_boundary-1, each once")
        for name, arr in (("labels", lab), ("nbr_cell", nc), ("nbr_leg", nl)):
            arr.setflags(write=False)
            object.__setattr__(self, name, arr)
        if self.grid_spec is not None:
            spec = GridSpec(*self.grid_spec)
            same = Board.from_grid_spec(spec, self.mask_of(spec))
            if not (np.array_equal(same.labels, lab) and np.array_equal(same.nbr_cell, nc)
                    and np.array_equal(same.nbr_leg, nl)):
                raise InvalidProblem(f"the board's joins are not those of the grid {spec}")
            object.__setattr__(self, "grid_spec", spec)

    @classmethod
    def _built(cls, labels, nbr_cell, nbr_leg, kind: str, grid_spec: GridSpec | None) -> "Board":
        """A board from joins that a builder made correct by construction (no checks)."""
        self = object.__new__(cls)
        for name, arr in (("labels", labels), ("nbr_cell", nbr_cell), ("nbr_leg", nbr_leg)):
            arr = np.ascontiguousarray(arr, dtype=np.int64)
            arr.setflags(write=False)
            object.__setattr__(self, name, arr)
        object.__setattr__(self, "kind", kind)
        object.__setattr__(self, "grid_spec", grid_spec)
        return self

    def mask_of(self, spec: GridSpec | None = None) -> np.ndarray:
        """The ``(rows, cols)`` boolean mask of the cells present in ``spec`` (default: the
        board's own :attr:`grid_spec`)."""
        spec = self.grid_spec if spec is None else spec
        if spec is None:
            raise InvalidProblem(f"this {self.kind} board is not cut from a grid")
        rows, cols = int(spec[0]), int(spec[1])
        built = self.__dict__.get("_grid_mask")
        if built is not None and built.shape == (rows, cols):  # the mask the board was built from
            return built.copy()
        lab = self.labels
        if lab.size and (lab.min() < 0 or lab[:, 0].max() >= rows or lab[:, 1].max() >= cols):
            raise InvalidProblem(f"the board's cell labels do not fit a {cols}x{rows} grid")
        m = np.zeros((rows, cols), bool)
        m[lab[:, 0], lab[:, 1]] = True
        return m

    # ------------------------------------------------------------------ basics
    @property
    def n_cells(self) -> int:
        n = self.__dict__.get("_n_cells")  # a board built from its grid knows it before its labels
        return int(self.labels.shape[0]) if n is None else n

    @property
    def n_boundary(self) -> int:
        if "_grid_mask" in self.__dict__ and "nbr_cell" not in self.__dict__:  # counted on the grid
            m = self._grid_mask
            there = _padded(m, self.grid_spec, False)
            H, Wd = m.shape
            return int(sum(np.count_nonzero(m & ~there[1 + dr : H + 1 + dr, 1 + dc : Wd + 1 + dc])
                           for dr, dc in _DELTA.values()))
        return int((self.nbr_cell < 0).sum())

    @property
    def n_edges(self) -> int:
        """Edges of the board graph: joined leg pairs plus boundary legs."""
        inner = int((self.nbr_cell >= 0).sum())
        return inner // 2 + self.n_boundary

    @property
    def boundary_legs(self) -> np.ndarray:
        """``(n_boundary, 2)`` array: ``[cell, leg]`` of each boundary leg, by boundary number."""
        a, k = np.nonzero(self.nbr_cell < 0)
        out = np.empty((a.size, 2), dtype=np.int64)
        out[self.nbr_leg[a, k]] = np.stack([a, k], axis=1)
        return out

    def leg_edges(self) -> tuple[np.ndarray, int]:
        """Number every edge: ``(edge_of_leg (n, 4), n_edges)``; joined legs share an edge.

        Edges are numbered in order of cell, then of the paper's legs l1..l4 (W, N, E, S), each
        from the first of its legs in that order: the numbering of the board encodings'
        variables, which the CNF digests of recorded refutations fix.
        """
        n = self.n_cells
        nc, nl = self.nbr_cell, self.nbr_leg
        here = np.arange(n, dtype=np.int64)[:, None] * 4 + _PAPER_RANK  # each leg's place in that order
        own = (nc < 0) | (nc * 4 + _PAPER_RANK[nl & 3] >= here)  # the first of its legs (or self-joined)
        first = own[:, PAPER_LEGS]
        count = int(np.count_nonzero(first))
        eid = np.full((n, 4), -1, dtype=np.int64)
        eid[first] = np.arange(count, dtype=np.int64)  # numbered in the paper's order ...
        eid = eid[:, _PAPER_RANK]  # ... then in the columns N, E, S, W
        other = ~own
        eid[other] = eid[nc[other], nl[other]]
        return eid, count

    def index_of(self) -> dict[tuple[int, int], int]:
        """``{(row, col): cell index}``."""
        return {(int(r), int(c)): i for i, (r, c) in enumerate(self.labels)}

    def edge_array(self) -> np.ndarray:
        """``(n_edges, 4)`` int64 rows ``[a, ka, b, kb]``, one per edge (``b = -1``: wall,
        ``kb`` = boundary leg number); a joined pair is listed once, from its smaller
        ``(cell, leg)``, in order of ``(a, ka)``."""
        nc, nl = self.nbr_cell, self.nbr_leg
        here = np.arange(self.n_cells, dtype=np.int64)[:, None] * 4 + np.arange(4)
        a, k = np.nonzero((nc < 0) | (nc * 4 + nl >= here))
        return np.stack([a, k, nc[a, k], nl[a, k]], axis=1)

    def edge_list(self) -> list[list[int]]:
        """:meth:`edge_array` as lists."""
        return self.edge_array().tolist()

    def degree_in_cells(self) -> np.ndarray:
        return (self.nbr_cell >= 0).sum(axis=1)

    def to_networkx(self):
        """The board graph G as a :class:`networkx.MultiGraph`.

        Nodes are cell indices (attribute ``label``) plus ``"wall"``; each edge has
        ``legs=(ka, kb)`` (from the smaller endpoint's side as stored) and, for the wall,
        ``boundary`` = the boundary-leg number.
        """
        import networkx as nx

        g = nx.MultiGraph()
        g.add_node("wall")
        for i, (r, c) in enumerate(self.labels.tolist()):
            g.add_node(i, label=(r, c))
        for a, ka, b, kb in self.edge_list():
            if b < 0:
                g.add_edge(a, "wall", legs=(ka, None), boundary=kb)
            else:
                g.add_edge(a, b, legs=(ka, kb))
        return g

    def cell_graph(self):
        """G' (Def. 1): the cells and the edges between them, as a MultiGraph."""
        g = self.to_networkx()
        g.remove_node("wall")
        return g

    def restrict(self, keep) -> "Board":
        """The restriction ``G|U`` (Def. 4): cells outside ``U`` are contracted to the wall.

        ``keep`` is a boolean mask over cells or a list of cell indices. Cell numbering of
        the result follows the kept cells' order.
        """
        keep_arr = np.asarray(keep)
        if keep_arr.dtype != bool:
            m = np.zeros(self.n_cells, dtype=bool)
            m[keep_arr.astype(np.int64)] = True
            keep_arr = m
        if keep_arr.shape != (self.n_cells,):
            raise InvalidProblem("restriction mask must have one entry per cell")
        new = np.full(self.n_cells + 1, -1, dtype=np.int64)
        new[:-1][keep_arr] = np.arange(int(keep_arr.sum()))
        nc = self.nbr_cell[keep_arr]
        nl = self.nbr_leg[keep_arr].copy()
        nc2 = new[nc]  # -1 maps via new[-1] = -1 (wall stays wall)
        wall = nc2 < 0
        nl[wall] = np.arange(np.count_nonzero(wall), dtype=np.int64)  # by cell, then leg
        # a restriction of a valid board is valid; a grid board stays one (its mask shrinks)
        return Board._built(self.labels[keep_arr], nc2, nl, self.kind if keep_arr.all() else f"{self.kind}|U",
                            self.grid_spec)

    # ------------------------------------------------------------------ builders
    @classmethod
    def grid(cls, mask, *, wrap_rows: str | None = None, wrap_cols: str | None = None,
             kind: str | None = None) -> "Board":
        """Grid board on the cells where ``mask`` is true.

        ``wrap_cols`` joins the E legs of column ``W-1`` to the W legs of column 0:
        ``"plain"`` (row ``r`` to row ``r``) or ``"twist"`` (row ``r`` to row ``H-1-r``,
        the Möbius identification of Example 5); ``wrap_rows`` likewise joins S legs of the
        last row to N legs of row 0 (``"twist"``: column ``c`` to ``W-1-c``). ``kind``
        defaults to ``"mask"`` (a rectangle with holes) where no sides are identified, else
        ``"grid"``.
        """
        if kind is None:
            kind = "mask" if wrap_rows is None and wrap_cols is None else "grid"
        m = np.asarray(mask, dtype=bool)
        if m.ndim != 2 or m.size == 0:
            raise InvalidProblem("a board mask must be a non-empty 2-D array")
        if wrap_rows not in _WRAPS or wrap_cols not in _WRAPS:
            raise InvalidProblem(f"wrap must be one of {_WRAPS}")
        H, Wd = m.shape
        if H * Wd > MAX_BOARD_CELLS:
            raise InvalidProblem(f"board {Wd}x{H} is larger than {MAX_BOARD_CELLS:,} cells")
        if not m.any():
            raise InvalidProblem("the board mask has no cells")
        return cls.from_grid_spec(GridSpec(H, Wd, wrap_rows, wrap_cols), m, kind=kind)

    @classmethod
    def from_grid_spec(cls, spec: GridSpec, mask, *, kind: str = "mask") -> "Board":
        """The board of the cells of ``mask`` (shape ``(spec.rows, spec.cols)``) on ``spec``'s grid.

        The index of every cell is looked up in the grid padded by one cell all round, the
        padding holding ``-1`` (the wall) or, where sides are identified, the cells of the
        opposite side (reversed for a twist): one shifted view of the padded grid per leg,
        no per-cell Python. The joins are made on first use: a board only described, counted
        or checked against its grid (a file read and verified) never builds them.

        Examples
        --------
        >>> m = Board.mobius(4, 3)
        >>> m.grid_spec
        GridSpec(rows=3, cols=4, wrap_rows=None, wrap_cols='twist')
        >>> hole = m.restrict(m.labels[:, 1] != 2)  # drop column 2
        >>> again = Board.from_grid_spec(hole.grid_spec, hole.mask_of())
        >>> bool((again.nbr_cell == hole.nbr_cell).all() and (again.nbr_leg == hole.nbr_leg).all())
        True
        """
        H, Wd, wrap_rows, wrap_cols = int(spec[0]), int(spec[1]), spec[2], spec[3]
        if wrap_rows not in _WRAPS or wrap_cols not in _WRAPS:
            raise InvalidProblem(f"wrap must be one of {_WRAPS}")
        _check_dims(H, Wd)
        m = np.asarray(mask, dtype=bool)
        if m.shape != (H, Wd):
            raise InvalidProblem(f"a mask of shape {m.shape} does not fit a {Wd}x{H} grid")
        n = int(np.count_nonzero(m))
        if n == 0:
            raise InvalidProblem("the board mask has no cells")
        self = object.__new__(cls)
        m = m.copy()
        m.setflags(write=False)
        for name, value in (("kind", kind), ("grid_spec", GridSpec(H, Wd, wrap_rows, wrap_cols)), ("_grid_mask", m),
                            ("_n_cells", n)):
            object.__setattr__(self, name, value)
        if n < H * Wd:  # the labels of a full grid are made on first use too
            self._grid_labels()
        return self  # the joins are made on first use (_grid_joins)

    def __getattr__(self, name: str):
        """The labels and joins of a board built from its grid (:meth:`from_grid_spec`), made on
        first use."""
        if name in ("labels", "nbr_cell", "nbr_leg") and "_grid_mask" in self.__dict__:
            if name == "labels":
                self._grid_labels()
            else:
                self._grid_joins()
            return self.__dict__[name]
        raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")

    def _grid_labels(self) -> None:
        """Set :attr:`labels` of a board built by :meth:`from_grid_spec`: its cells' ``[row, col]``
        in row-major order."""
        lab = np.stack(np.nonzero(self._grid_mask), axis=1).astype(np.int64, copy=False)
        lab.setflags(write=False)
        object.__setattr__(self, "labels", lab)

    def _grid_joins(self) -> None:
        """Set :attr:`nbr_cell` and :attr:`nbr_leg` of a board built by :meth:`from_grid_spec`."""
        m, spec = self._grid_mask, self.grid_spec
        n = self.n_cells
        index = np.full(m.shape, -1, dtype=np.int64)
        index[m] = np.arange(n, dtype=np.int64)
        pad = _padded(index, spec, -1)
        H, Wd = m.shape
        full = n == H * Wd
        nc = np.empty((n, 4), dtype=np.int64)
        for k, (dr, dc) in _DELTA.items():
            seen = pad[1 + dr : H + 1 + dr, 1 + dc : Wd + 1 + dc]  # the neighbour across leg k
            if full:
                nc.reshape(H, Wd, 4)[:, :, k] = seen
            else:
                nc[:, k] = seen[m]
        nl = np.where(nc >= 0, (np.arange(4, dtype=np.int64) + 2) % 4, np.int64(-1))
        wall = nc < 0
        nl[wall] = np.arange(np.count_nonzero(wall), dtype=np.int64)  # by cell, then leg
        for name, arr in (("nbr_cell", nc), ("nbr_leg", nl)):
            arr.setflags(write=False)
            object.__setattr__(self, name, arr)

    @classmethod
    def _shape(cls, kind: str, width: int, height: int) -> "Board":
        """The ``width x height`` board of a shape of :data:`GRID_KINDS` (its sides and cells)."""
        _check_dims(height, width)
        wrap_rows, wrap_cols = GRID_KINDS[kind]
        return cls.grid(kind_mask(kind, height, width), wrap_rows=wrap_rows, wrap_cols=wrap_cols, kind=kind)

    @classmethod
    def rect(cls, width: int, height: int) -> "Board":
        """The rectangle of ``width`` columns and ``height`` rows with the wall all round.

        Every board builder takes its size width first, as the CLI's ``rect:WxH`` does
        (:func:`parse_board_spec`).

        >>> Board.rect(4, 2).describe()
        'rect board, 8 cells in 4x2, 12 boundary legs'
        """
        return cls._shape("rect", width, height)

    @classmethod
    def mask(cls, mask) -> "Board":
        """Rectangle with holes: cells where ``mask`` is true (Def. 4's restriction)."""
        return cls.grid(mask, kind="mask")

    @classmethod
    def torus(cls, width: int, height: int) -> "Board":
        """Both directions wrap: no boundary (periodic tilings, Remark 3)."""
        return cls._shape("torus", width, height)

    @classmethod
    def cylinder(cls, width: int, height: int) -> "Board":
        """Columns wrap; the top and bottom rows meet the wall."""
        return cls._shape("cylinder", width, height)

    @classmethod
    def mobius(cls, width: int, height: int) -> "Board":
        """The Möbius strip of Example 5, ``width`` columns around and ``height`` rows across:
        columns wrap with a twist, rows meet the wall.

        The E leg of cell ``(r, width-1)`` meets the W leg of ``(height-1-r, 0)`` (the paper's
        ``j = 1, j' = N, i + i' = N + 1``); the N legs of row 0 and the S legs of the last
        row are the boundary ``B``.
        """
        return cls._shape("mobius", width, height)

    @classmethod
    def klein(cls, width: int, height: int) -> "Board":
        """Klein bottle: columns wrap with a twist, rows wrap plainly; no boundary."""
        return cls._shape("klein", width, height)

    @classmethod
    def ring(cls, width: int, height: int) -> "Board":
        """The border of a ``width x height`` rectangle: G' is one cycle (tests of §4.3)."""
        return cls._shape("ring", width, height)

    @classmethod
    def random_tree(cls, n_cells: int, *, seed=None, span: int | None = None) -> "Board":
        """A planar grid board whose G' is a tree: cells added next to exactly one cell."""
        from tilesolve._random import rng_from_seed

        rng = rng_from_seed(seed)
        if n_cells < 1:
            raise InvalidProblem("a tree needs at least one cell")
        span = span or (2 * n_cells + 3)
        occ = {(0, 0)}
        frontier = [(0, 0)]
        tries = 0
        while len(occ) < n_cells and tries < 200 * n_cells:
            tries += 1
            r, c = frontier[int(rng.integers(len(frontier)))]
            dr, dc = _DELTA[int(PAPER_LEGS[rng.integers(4)])]  # drawn as seeds always drew them
            cand = (r + dr, c + dc)
            if cand in occ or abs(cand[0]) > span or abs(cand[1]) > span:
                continue
            nbrs = sum((cand[0] + a, cand[1] + b) in occ for a, b in _DELTA.values())
            if nbrs != 1:
                continue
            occ.add(cand)
            frontier.append(cand)
        pts = np.array(sorted(occ))
        pts -= pts.min(axis=0)
        m = np.zeros(tuple(pts.max(axis=0) + 1), bool)
        m[pts[:, 0], pts[:, 1]] = True
        return cls.grid(m, kind="tree")

    @classmethod
    def random_holes(cls, width: int, height: int, density: float = 0.1, *, seed=None) -> "Board":
        """``width x height`` rectangle with each cell removed with probability ``density``."""
        from tilesolve._random import rng_from_seed

        _check_dims(height, width)
        rng = rng_from_seed(seed)
        m = rng.random((height, width)) >= density
        if not m.any():
            m[0, 0] = True
        return cls.grid(m, kind="mask")

    @classmethod
    def with_holes(cls, width: int, height: int, n_holes: int, max_size: int = 8, *, seed=None) -> "Board":
        """``width x height`` rectangle with ``n_holes`` random rectangular holes of side 1..``max_size``."""
        from tilesolve._random import rng_from_seed

        _check_dims(height, width)
        rng = rng_from_seed(seed)
        m = np.ones((height, width), bool)
        for _ in range(int(n_holes)):
            h, w = rng.integers(1, max_size + 1, size=2)
            r, c = int(rng.integers(0, height)), int(rng.integers(0, width))
            m[r : r + h, c : c + w] = False
        if not m.any():
            m[0, 0] = True
        return cls.grid(m, kind="mask")

    @classmethod
    def from_edges(cls, cells, edges, *, kind: str = "board") -> "Board":
        """Board from plain data: ``cells`` ([row, col] labels) and ``edges`` ([a, ka, b, kb])."""
        try:
            lab = np.asarray(cells, dtype=np.int64).reshape(-1, 2)
            ed = np.asarray(edges, dtype=np.int64).reshape(-1, 4)
        except (TypeError, ValueError) as exc:
            raise InvalidProblem(f"board cells/edges are malformed: {exc}") from None
        n = lab.shape[0]
        a, ka, b, kb = ed.T
        bad = ~((a >= 0) & (a < n) & (ka >= 0) & (ka < 4))
        bad_b = ~bad & (b >= 0) & ~((b < n) & (kb >= 0) & (kb < 4))
        if bad.any() or bad_b.any():
            i = int(np.flatnonzero(bad | bad_b)[0])
            c, k = (a[i], ka[i]) if bad[i] else (b[i], kb[i])
            raise InvalidProblem(f"board edge names cell {int(c)} leg {int(k)}, which does not exist")
        # every edge fills the slot of (a, ka), and of (b, kb) too when it joins two legs
        back = (b >= 0) & ((b != a) | (kb != ka))
        slot = np.concatenate([a * 4 + ka, b[back] * 4 + kb[back]])
        to_cell = np.concatenate([np.where(b >= 0, b, -1), a[back]])
        to_leg = np.concatenate([kb, ka[back]])
        uses = np.bincount(slot, minlength=4 * n)
        if (uses > 1).any():
            s_ = int(np.flatnonzero(uses > 1)[0])
            raise InvalidProblem(f"leg {s_ % 4} of cell {lab[s_ // 4].tolist()} is joined twice")
        if (uses == 0).any():
            s_ = int(np.flatnonzero(uses == 0)[0])
            raise InvalidProblem(f"leg {s_ % 4} of cell {lab[s_ // 4].tolist()} is not joined to anything")
        nc = np.empty(4 * n, dtype=np.int64)
        nl = np.empty(4 * n, dtype=np.int64)
        nc[slot], nl[slot] = to_cell, to_leg
        nc, nl = nc.reshape(n, 4), nl.reshape(n, 4)
        return cls(lab, nc, nl, kind=str(kind))

    def describe(self) -> str:
        if "labels" not in self.__dict__ and "_grid_mask" in self.__dict__:  # a full grid, labels not made
            rows, cols = self._grid_mask.shape
        else:
            rows = int(self.labels[:, 0].max()) + 1 if self.n_cells else 0
            cols = int(self.labels[:, 1].max()) + 1 if self.n_cells else 0
        return f"{self.kind} board, {self.n_cells} cells in {cols}x{rows}, {self.n_boundary} boundary legs"


def _padded(grid: np.ndarray, spec: GridSpec, wall) -> np.ndarray:
    """``grid`` (one value per cell of ``spec``'s grid) padded by one cell all round: ``wall``,
    or where sides are identified the values of the opposite side (reversed for a twist)."""
    H, Wd = grid.shape
    pad = np.full((H + 2, Wd + 2), wall, dtype=grid.dtype)
    inner = pad[1:-1, 1:-1]
    inner[...] = grid
    if spec[3] is not None:
        flip = slice(None, None, -1) if spec[3] == "twist" else slice(None)
        pad[1:-1, 0] = inner[flip, -1]
        pad[1:-1, -1] = inner[flip, 0]
    if spec[2] is not None:
        flip = slice(None, None, -1) if spec[2] == "twist" else slice(None)
        pad[0, 1:-1] = inner[-1, flip]
        pad[-1, 1:-1] = inner[0, flip]
    return pad


def _check_dims(rows: int, cols: int) -> None:
    if int(rows) < 1 or int(cols) < 1:
        raise InvalidProblem(f"board size must be positive, got {cols}x{rows} (WxH)")
    if int(rows) * int(cols) > MAX_BOARD_CELLS:
        raise InvalidProblem(f"board {cols}x{rows} is larger than {MAX_BOARD_CELLS:,} cells")


def grid_kind(kind: str) -> str | None:
    """The kind of :data:`GRID_KINDS` a board's ``kind`` names, restricted (``"mobius|U"``) or
    not, else ``None``.

    >>> grid_kind("mobius|U"), grid_kind("sheared torus")
    ('mobius', None)
    """
    base, *rest = str(kind).split("|")
    return base if base in GRID_KINDS and all(r == "U" for r in rest) else None


def kind_mask(kind: str, rows: int, cols: int) -> np.ndarray | None:
    """The cells a board of ``kind`` (:data:`GRID_KINDS`) has on a ``rows x cols`` grid, or
    ``None`` where the kind allows any mask (``mask``, ``tree``, kinds not in the table).

    >>> kind_mask("ring", 3, 3).astype(int).tolist()
    [[1, 1, 1], [1, 0, 1], [1, 1, 1]]
    """
    if kind in _FULL_KINDS:
        return np.ones((rows, cols), bool)
    if kind != "ring":
        return None
    if rows < 2 or cols < 2:
        raise InvalidProblem("a ring needs at least 2x2 cells")
    m = np.zeros((rows, cols), bool)
    m[0, :] = m[-1, :] = m[:, 0] = m[:, -1] = True
    return m


def described_board(kind: str, spec: GridSpec, mask=None) -> "Board":
    """The board a file describes by its ``kind``, its grid ``spec`` and a ``mask`` of the cells
    present (``None``: every cell of the grid).

    A kind of :data:`GRID_KINDS` must agree with the rest: its sides are identified as the
    kind's are, and its cells are the kind's (any of them for a restriction ``kind|U``). Any
    other kind just names the board of the grid and mask. The size is checked before anything
    is allocated.

    Raises
    ------
    InvalidProblem
        The description contradicts itself, or the grid is larger than :data:`MAX_BOARD_CELLS`.

    Examples
    --------
    >>> described_board("mobius", GridSpec(3, 4, None, "twist")).describe()
    'mobius board, 12 cells in 4x3, 8 boundary legs'
    >>> described_board("rect", GridSpec(3, 4, "plain", "plain"))
    Traceback (most recent call last):
    ...
    tilesolve.errors.InvalidProblem: a rect board has wrap_rows None and wrap_cols None, not 'plain' and 'plain'
    """
    rows, cols, wrap_rows, wrap_cols = int(spec[0]), int(spec[1]), spec[2], spec[3]
    _check_dims(rows, cols)
    m = np.ones((rows, cols), bool) if mask is None else np.asarray(mask, dtype=bool)
    base = grid_kind(kind)
    if base is not None:
        wraps = GRID_KINDS[base]
        if (wrap_rows, wrap_cols) != wraps:
            raise InvalidProblem(f"a {base} board has wrap_rows {wraps[0]!r} and wrap_cols {wraps[1]!r}, "
                                 f"not {wrap_rows!r} and {wrap_cols!r}")
        need = kind_mask(base, rows, cols)
        if need is not None and m.shape == need.shape:
            wrong = (m & ~need) if base != kind else (m != need)
            if wrong.any():
                r, c = (int(v) for v in np.argwhere(wrong)[0])
                has = "has a cell" if need[r, c] else "has no cell"
                raise InvalidProblem(f"the mask is not that of a {kind} board of {cols}x{rows}: "
                                     f"the {base} board {has} at [{r}, {c}]")
    return Board.from_grid_spec(GridSpec(rows, cols, wrap_rows, wrap_cols), m, kind=str(kind))


# ---------------------------------------------------------------------- masks and specs
def parse_mask_text(text: str, source: str = "<mask>") -> np.ndarray:
    """ASCII mask: ``#`` = cell, ``.`` = hole, one board row per line (blank lines ignored)."""
    lines = [ln.rstrip("\r\n").rstrip() for ln in text.splitlines()]
    lines = [ln for ln in lines if ln.strip()]
    if not lines:
        raise InvalidProblem(f"{source}: the mask is empty")
    width = max(len(ln) for ln in lines)
    if len(lines) * width > MAX_BOARD_CELLS:
        raise InvalidProblem(f"{source}: a mask of {width}x{len(lines)} is too large a board "
                             f"(at most {MAX_BOARD_CELLS} cells)")
    m = np.zeros((len(lines), width), dtype=bool)
    for r, ln in enumerate(lines):
        for c, ch in enumerate(ln):
            if ch == "#":
                m[r, c] = True
            elif ch not in ". ":
                raise InvalidProblem(f"{source}: line {r + 1}, column {c + 1}: {ch!r} is not '#' (cell) or '.' (hole)")
    if not m.any():
        raise InvalidProblem(f"{source}: the mask has no '#' cells")
    return m


_SPEC_RE = re.compile(r"^\s*(rect|torus|cylinder|mobius|klein|ring)\s*:\s*(\d+)\s*[xX×]\s*(\d+)\s*$")


def parse_board_spec(spec: str) -> Board:
    """``rect:WxH``, ``torus:WxH``, ``cylinder:WxH``, ``mobius:WxH``, ``klein:WxH`` or
    ``ring:WxH`` (W columns, H rows). ``mask:FILE`` names a file, which
    :func:`tilesolve.io.mask.read_board_spec` reads.

    Examples
    --------
    >>> parse_board_spec("mobius:6x4").describe()
    'mobius board, 24 cells in 6x4, 12 boundary legs'
    """
    s = str(spec)
    if s.startswith("mask:"):
        raise InvalidProblem(f"board {spec!r} names a mask file; read it with tilesolve.io.mask.read_board_spec")
    m = _SPEC_RE.match(s)
    if not m:
        raise InvalidProblem(
            f"cannot read board {spec!r}: expected rect:WxH, torus:WxH, cylinder:WxH, mobius:WxH, "
            "klein:WxH, ring:WxH or mask:FILE"
        )
    kind, w, h = m.group(1), int(m.group(2)), int(m.group(3))
    return getattr(Board, kind)(w, h)


# ---------------------------------------------------------------------- tile sets
def colour_rows(tiles) -> np.ndarray:
    """Tiles as an ``(m, 4)`` int64 array of colours, from rows of four integers (lists or an
    integer array; a flat list of 4m integers too).

    Raises
    ------
    InvalidProblem
        A colour that is not an integer (a string, a float, a boolean, an integer beyond
        int64), or rows that are not four colours each.
    """
    try:
        t = np.asarray(tiles)
    except (TypeError, ValueError, OverflowError):
        raise InvalidProblem("tiles must be lists of 4 integer colours") from None
    if t.size and t.dtype.kind not in "iu" or t.dtype.kind == "u" and t.size and t.max() >= 2**63:
        raise InvalidProblem("tiles must be lists of 4 integer colours")
    if t.size % 4:
        raise InvalidProblem(f"each tile must have 4 colours; got shape {t.shape}")
    return t.astype(np.int64).reshape(-1, 4)


@dataclass(frozen=True, eq=False)
class WangTileSet:
    """A set of Wang tiles ``W ⊂ C^4`` (Def. 2), each given by the colours of its edges in
    the public order N, E, S, W.

    The tiles keep the order they are given in, so a tile's index means the same tile to the
    user and in every output (a tile given twice is kept where it first comes). A tile's
    colours are those of the board legs N, E, S, W (legs 0..3), the order the kernels,
    encodings and verifiers read.

    Parameters
    ----------
    tiles : array-like
        ``(m, 4)`` colours ``[N, E, S, W]`` per tile, in ``0 .. n_colors-1``.
    n_colors : int
        ``#C``.
    is_brick : bool
        The set is W_B (set by :meth:`brick`).

    Examples
    --------
    >>> wb = WangTileSet.brick(3)
    >>> len(wb), wb.is_brick, wb.three_boundary()
    (36, True, True)
    >>> ts = WangTileSet([[2, 0, 0, 1], [0, 1, 1, 0], [2, 0, 0, 1]], 3)  # N, E, S, W; a repeat
    >>> ts.tiles.tolist()
    [[2, 0, 0, 1], [0, 1, 1, 0]]
    """

    tiles: np.ndarray
    n_colors: int
    is_brick: bool = False

    def __post_init__(self) -> None:
        k = int(self.n_colors)
        if k < 1:
            raise InvalidProblem(f"a tile set needs at least one colour, got {self.n_colors}")
        try:
            t = np.asarray(self.tiles)
        except (TypeError, ValueError, OverflowError):
            raise InvalidProblem("tiles must be lists of 4 integer colours") from None
        if t.size == 0:
            raise InvalidProblem("the tile set is empty")
        if t.ndim != 2 or t.shape[1] != 4:
            raise InvalidProblem(f"each tile must have 4 colours (N, E, S, W); got shape {t.shape}")
        t = colour_rows(t)
        bad = (t < 0) | (t >= k)
        if bad.any():
            i = int(np.argwhere(bad)[0][0])
            raise InvalidProblem(f"tile {t[i].tolist()} (N, E, S, W) uses a colour outside C = 0..{k - 1}")
        first = np.unique(t, axis=0, return_index=True)[1]
        if first.size < t.shape[0]:
            t = t[np.sort(first)]
        t.setflags(write=False)
        object.__setattr__(self, "tiles", t)
        object.__setattr__(self, "n_colors", k)

    @classmethod
    def brick(cls, n_colors: int = 3) -> "WangTileSet":
        """The brick Wang tiles W_B (Def. 9): ``(c1 = c3 and c2 != c4) or (c1 != c3 and c2 = c4)``
        on the paper's legs l1..l4 = W, N, E, S, listed in lexicographic order of l1..l4."""
        k = int(n_colors)
        if k < 3:
            raise InvalidProblem(f"brick Wang tiles need #C >= 3 colours (Def. 9), got {k}")
        if k > MAX_BRICK_COLORS:
            raise InvalidProblem(f"brick Wang tiles with {k} colours: tilesolve builds W_B for up to "
                                 f"{MAX_BRICK_COLORS} colours")
        w, n, e, s = (a.ravel() for a in np.meshgrid(*[np.arange(k)] * 4, indexing="ij"))
        ok = ((w == e) & (n != s)) | ((w != e) & (n == s))
        return cls(np.stack([n[ok], e[ok], s[ok], w[ok]], axis=1), k, is_brick=True)

    @classmethod
    def from_tileset(cls, tileset) -> "WangTileSet":
        """The Wang tiles of a :class:`~tilesolve.model.tiles.TileSet` (complete or compact),
        as a board tile set (one palette of ``max(C_h, C_v)`` colours)."""
        if tileset.kind != "wang":
            raise InvalidProblem("corner tiles are not Wang tiles; convert their Wang images "
                                 "(TileSet.as_wang()) instead")
        return cls(tileset.table(), max(tileset.colors, tileset.cv))

    def __len__(self) -> int:
        return int(self.tiles.shape[0])

    def contains(self, colours) -> np.ndarray:
        """Boolean per row of leg colours ``colours`` ((m, 4) array, N, E, S, W): is it a tile
        of the set?"""
        c = np.asarray(colours, dtype=np.int64).reshape(-1, 4)
        k = self.n_colors
        inrange = ((c >= 0) & (c < k)).all(axis=1)
        key = lambda a: ((a[:, 0] * k + a[:, 1]) * k + a[:, 2]) * k + a[:, 3]  # noqa: E731
        return inrange & np.isin(key(np.where(c >= 0, c, 0)), key(self.tiles))

    def three_boundary(self) -> bool:
        """Def. 6: every projection forgetting one place is onto ``C^3``."""
        k = self.n_colors
        for i in range(4):
            rest = np.delete(self.tiles, i, axis=1)
            key = (rest[:, 0] * k + rest[:, 1]) * k + rest[:, 2]
            if np.unique(key).size != k**3:
                return False
        return True

    def to_json(self):
        return "brick" if self.is_brick else self.tiles.tolist()


def random_boundary(board: Board, n_colors: int, *, seed=None) -> np.ndarray:
    """A random colour for every boundary leg (``--boundary random``), drawn from ``seed``.

    The brick paper's question (Def. 2) is a tiling under *given* boundary colours β, which
    the brick tiles W_B meet for every β on planar grid boards (§4, Lemma 10): a random β
    shows the linear algorithm at work. It is asked for, never a default
    (:class:`BoardProblem`): a general tile set under random boundary colours almost never
    tiles a board (``periodic-7-30`` tiles no 3x3 rectangle under one).
    """
    from tilesolve._random import rng_from_seed

    return rng_from_seed(seed).integers(0, n_colors, size=board.n_boundary).astype(np.int64)


@dataclass(frozen=True, eq=False)
class BoardProblem:
    """A tiling problem ``(G, C, β, W)`` (Def. 2) on a board.

    Parameters
    ----------
    board : Board
    tileset : WangTileSet
        Its ``n_colors`` is ``#C``.
    boundary : array-like, optional
        Colour required on each boundary leg (by boundary-leg number), ``-1`` = free.
        ``None``, the default, leaves every boundary leg free: the question "does the tile
        set tile this board at all", which makes sense for every tile set and needs no seed.
        The CLI's ``--boundary`` defaults to ``free`` too. The brick paper's question, a
        tiling under given boundary colours (Def. 2; W_B meets any on planar boards, §4,
        Lemma 10), is asked by passing them: :func:`random_boundary` is
        ``--boundary random``. A random default would make nearly every general tile set
        unsat.
    max_h, max_v : int, optional
        Brick walls only (dappled paper §4): no run of more than ``max_h`` consecutive
        W_H tiles (``c1 = c3``) along a row, or ``max_v`` W_V tiles (``c2 = c4``) down a
        column. Runs follow the legs: from a cell out of its E (S) leg into the next cell.

    Examples
    --------
    >>> p = BoardProblem(Board.rect(3, 3), WangTileSet.brick(3), [0] * 12)
    >>> p.n_colors, int((p.boundary >= 0).sum())
    (3, 12)
    """

    board: Board
    tileset: WangTileSet
    boundary: np.ndarray | None = None
    max_h: int | None = None
    max_v: int | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.board, Board):
            raise InvalidProblem("board must be a Board")
        if not isinstance(self.tileset, WangTileSet):
            raise InvalidProblem("tileset must be a WangTileSet")
        nb = self.board.n_boundary
        if self.boundary is None:
            b = np.full(nb, -1, dtype=np.int64)
        else:
            try:
                b = np.asarray(self.boundary, dtype=np.int64).reshape(-1)
            except (TypeError, ValueError):
                raise InvalidProblem("boundary colours must be integers (-1 = free)") from None
            if b.size != nb:
                raise InvalidProblem(
                    f"boundary gives {b.size} colours but the board has {nb} boundary legs"
                    + (" (constraints on legs that are not on the boundary)" if b.size > nb else "")
                )
            bad = (b < -1) | (b >= self.tileset.n_colors)
            if bad.any():
                i = int(np.flatnonzero(bad)[0])
                raise InvalidProblem(
                    f"boundary leg {i} has colour {int(b[i])}, outside C = 0..{self.tileset.n_colors - 1} (-1 = free)"
                )
        b = b.copy()
        b.setflags(write=False)
        object.__setattr__(self, "boundary", b)
        for name in ("max_h", "max_v"):
            v = getattr(self, name)
            if v is not None:
                if int(v) < 1:
                    raise InvalidProblem(f"{name} must be >= 1, got {v}")
                if not self.tileset.is_brick:
                    raise InvalidProblem("line-length limits apply to brick Wang tiles only")
                object.__setattr__(self, name, int(v))

    @property
    def n_colors(self) -> int:
        return self.tileset.n_colors

    @property
    def has_line_limits(self) -> bool:
        return self.max_h is not None or self.max_v is not None

    @classmethod
    def from_boundary_legs(cls, board: Board, tileset: WangTileSet, fixed: dict) -> "BoardProblem":
        """Boundary from ``{(cell, leg): colour}``; a leg not on the boundary is an error."""
        b = np.full(board.n_boundary, -1, dtype=np.int64)
        for (a, k), col in fixed.items():
            a, k = int(a), int(k)
            if not (0 <= a < board.n_cells and 0 <= k < 4):
                raise InvalidProblem(f"cell {a} leg {k} does not exist")
            if board.nbr_cell[a, k] >= 0:
                raise InvalidProblem(
                    f"leg {LEG_NAMES[k]} of cell {board.labels[a].tolist()} is not on the boundary "
                    "(it meets another cell)"
                )
            b[board.nbr_leg[a, k]] = int(col)
        return cls(board, tileset, b)

    def describe(self) -> str:
        ts = f"brick Wang tiles, {self.n_colors} colours" if self.tileset.is_brick else \
            f"{len(self.tileset)} Wang tiles, {self.n_colors} colours"
        fixed = int((self.boundary >= 0).sum())
        extra = ""
        if self.has_line_limits:
            extra = f", lines <= {self.max_h or 'inf'} / {self.max_v or 'inf'}"
        return f"{self.board.describe()}; {ts}; {fixed} boundary legs fixed{extra}"
