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

__all__ = ["PackingProblem", "MAX_PLACEMENTS", "estimated_size"]

#: Most placement variables (cell, tile) a solver route builds: the full encoding of the
#: ``C = 6`` set (1,296 tiles, ~1.7 million placements, ~10 million clauses). Larger searches
#: are refused before any clause is built. The ``lift`` route needs far fewer placements
#: (``cells * k**4``), so it reaches ``C = 8`` and beyond.
MAX_PLACEMENTS = 1296 * 1296


def estimated_size(placements: int) -> tuple[int, int]:
    """Rough ``(variables, clauses)`` of a packing encoding with ``placements`` placement
    variables: about six clauses per placement (four links to its colours, one back, its
    share of the at-most-one constraints)."""
    return placements, 6 * placements


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

    def check_search_size(self, placements: int | None = None, route: str = "sat") -> None:
        """Refuse searches too large to build, before anything is built.

        ``placements`` is the number of (cell, tile) variables the route would create
        (default: the full encoding, ``n_tiles**2``).
        """
        n = self.n_tiles
        placements = n * n if placements is None else placements
        if placements > MAX_PLACEMENTS:
            v, c = estimated_size(placements)
            raise InvalidProblem(
                f"method {route!r} on {n:,} tiles (C={self.colors}) needs about {v:,} variables and "
                f"{c:,} clauses; tilesolve builds up to {MAX_PLACEMENTS:,} placements. "
                + ("Use --method euler/outer (Wang) or an odd C (corner)" if route == "lift" else
                   "Use --method lift (C with a small prime factor), euler/outer (Wang) or an odd C (corner)")
            )

    def describe(self) -> str:
        rows, cols = self.shape
        s = f"{self.tiles.describe()} packed into a {rows}x{cols} torus"
        if self.fixed:
            s += f", {len(self.fixed)} fixed tile{'s' if len(self.fixed) != 1 else ''}"
        return s
