"""The tile packing problem (Lagae, class notes §5.5).

Arrange the ``C**4`` tiles of a complete Wang or corner tile set into a ``C**2 x C**2``
torus so that adjoining edges (Wang) or corners (corner tiles) match, each tile exactly
once. A packing is a numpy array ``grid[row, col]`` of tile indices (eq. 2.1 / 2.5), row 0
at the top, row ``r - 1`` north of row ``r``; both directions wrap.

For Wang tiles with ``C_h != C_v`` the torus has ``C_h**2`` rows and ``C_v**2`` columns.

Optional constraints (§5.5.4: puzzles; Figs. 5.11-5.12): ``fixed`` pins given tiles to
given cells. Contradictory pins (a tile at two cells, two tiles at one cell, or pins that
cannot be completed) are a problem with no packing, answered ``unsat``, not an error.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

from tilesolve.errors import InvalidProblem
from tilesolve.model.tiles import TileSet

__all__ = ["PackingProblem"]

@dataclass(frozen=True)
class PackingProblem:
    """A tile packing problem.

    Parameters
    ----------
    kind : {"wang", "corner"}
    colors : int
        ``C >= 2`` (``C_h`` for Wang tiles with ``colors_v``).
    colors_v : int, optional
        Wang tiles only: colours of the vertical (E, W) edges.
    fixed : tuple of (row, col, tile)
        Tiles pinned to cells.

    Examples
    --------
    >>> p = PackingProblem("corner", 3, fixed=((0, 0, 40),))
    >>> p.shape, p.tiles.n_tiles
    ((9, 9), 81)
    """

    kind: str
    colors: int
    colors_v: int | None = None
    fixed: tuple[tuple[int, int, int], ...] = ()

    def __post_init__(self) -> None:
        ts = TileSet(self.kind, self.colors, self.colors_v)  # checks kind and colours
        if self.colors < 2 or ts.cv < 2:
            raise InvalidProblem(f"a tile packing needs at least 2 colours, got C={self.colors}"
                                 + (f", C_v={self.colors_v}" if self.colors_v is not None else ""))
        rows, cols = self.shape
        fixed = []
        for item in self.fixed:
            try:
                r, c, t = (int(v) for v in item)
            except (TypeError, ValueError):
                raise InvalidProblem(f"a fixed tile is (row, col, tile), got {item!r}") from None
            if not (0 <= r < rows and 0 <= c < cols):
                raise InvalidProblem(f"fixed cell ({r}, {c}) is outside the {rows}x{cols} packing")
            if not 0 <= t < ts.n_tiles:
                raise InvalidProblem(f"fixed tile {t} is not in 0..{ts.n_tiles - 1}")
            fixed.append((r, c, t))
        object.__setattr__(self, "fixed", tuple(fixed))

    @functools.cached_property
    def tiles(self) -> TileSet:
        return TileSet(self.kind, self.colors, self.colors_v)

    def pin_clashes(self) -> list[str]:
        """Why the pinned tiles cannot all hold in any packing, in words (empty when no two
        pins clash): a tile pinned at two cells (each tile appears once), a cell given two
        tiles, or side-by-side pins whose shared edge (Wang) or corners (corner) differ on
        the torus (class notes §2.7)."""
        out: list[str] = []
        rows, cols = self.shape
        at: dict[tuple[int, int], int] = {}
        where: dict[int, tuple[int, int]] = {}
        for r, c, t in self.fixed:
            if (r, c) in at and at[(r, c)] != t:
                out.append(f"cell ({r}, {c}) is given tiles {at[(r, c)]} and {t}")
            if t in where and where[t] != (r, c):
                out.append(f"tile {t} is pinned at {where[t]} and at {(r, c)}, but a packing holds each tile once")
            at.setdefault((r, c), t)
            where.setdefault(t, (r, c))
        sides = self.tiles.sides
        # (own side, neighbour side) pairs that must agree, for the east and the south neighbour
        if self.kind == "wang":
            pairs = {(0, 1): ((1, 3),), (1, 0): ((2, 0),)}
        else:  # NE SE SW NW
            pairs = {(0, 1): ((0, 3), (1, 2)), (1, 0): ((2, 3), (1, 0))}
        for (r, c), t in at.items():
            for (dr, dc), checks in pairs.items():
                u = at.get(((r + dr) % rows, (c + dc) % cols))
                if u is None:
                    continue
                a, b = self.tiles.colors_of(t), self.tiles.colors_of(u)
                for i, j in checks:
                    if a[i] != b[j]:
                        where_ = "east of" if dc else "below"
                        out.append(f"tile {u} cannot sit {where_} tile {t} at ({r}, {c}): {sides[i]} colour {a[i]} "
                                   f"meets {sides[j]} colour {b[j]}")
        return out

    @property
    def shape(self) -> tuple[int, int]:
        """``(rows, cols)`` of the torus: ``(C_h**2, C_v**2)``."""
        cv = self.colors if self.colors_v is None else self.colors_v
        return self.colors**2, cv**2

    @property
    def n_tiles(self) -> int:
        return self.tiles.n_tiles

    def describe(self) -> str:
        rows, cols = self.shape
        s = f"{self.tiles.describe()} packed into a {rows}x{cols} torus"
        if self.fixed:
            s += f", {len(self.fixed)} fixed tile{'s' if len(self.fixed) != 1 else ''}"
        return s
