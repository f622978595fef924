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

    @property
    def tiles(self) -> TileSet:
        return TileSet(self.kind, self.colors, self.colors_v)

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
