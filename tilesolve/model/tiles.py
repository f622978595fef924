"""Wang tiles and corner tiles with the class notes' indexing (Lagae, §2.7-2.9).

Conventions
-----------
*Wang tiles* have coloured edges N, E, S, W (in that order, §2.7). The tile with edge
colours ``c_N c_E c_S c_W`` over ``C`` colours has index (eq. 2.1/2.2)::

    i = ((c_N * C + c_E) * C + c_S) * C + c_W

and the colours of index ``i`` follow from eq. 2.3/2.4. With ``C_h`` colours on the
horizontal edges (N, S) and ``C_v`` on the vertical edges (E, W) the notes give no index;
tilesolve uses the mixed-radix generalisation ``i = ((c_N * C_v + c_E) * C_h + c_S) * C_v + c_W``,
which is eq. 2.1 when ``C_h = C_v``.

*Corner tiles* have coloured corners NE, SE, SW, NW (in that order, §2.7); the index of
``c_NE c_SE c_SW c_NW`` is eq. 2.5 ``i = ((c_NE * C + c_SE) * C + c_SW) * C + c_NW`` and
eq. 2.6/2.7 invert it.

*Corner tiles as Wang tiles* (§2.9): a pair of corner colours becomes one edge colour
over ``C**2`` colours. tilesolve reads each edge from west to east or from north to south:
``N = (NW, NE)``, ``E = (NE, SE)``, ``S = (SW, SE)``, ``W = (NW, SW)``, the pair ``(a, b)``
being the edge colour ``a * C + b``. Two corner tiles then match along an edge exactly when
their Wang images match.

Examples
--------
>>> wang_index(1, 0, 2, 1, colors=3)   # eq. 2.1: 1*27 + 0*9 + 2*3 + 1
34
>>> wang_colors(34, colors=3)
(1, 0, 2, 1)
>>> corner_colors(corner_index(1, 1, 0, 1, colors=2), colors=2)
(1, 1, 0, 1)
>>> TileSet("wang", 2).n_tiles, TileSet("corner", 4).n_tiles
(16, 256)
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tilesolve.errors import InvalidProblem

__all__ = [
    "KINDS",
    "WANG_SIDES",
    "CORNER_SIDES",
    "wang_index",
    "wang_colors",
    "corner_index",
    "corner_colors",
    "corner_to_wang",
    "TileSet",
]

#: Tile kinds.
KINDS: tuple[str, ...] = ("wang", "corner")
#: The order of the four colours of a Wang tile in its index (eq. 2.1).
WANG_SIDES: tuple[str, ...] = ("N", "E", "S", "W")
#: The order of the four colours of a corner tile in its index (eq. 2.5).
CORNER_SIDES: tuple[str, ...] = ("NE", "SE", "SW", "NW")


def _check_colors(c, what: str = "colors") -> int:
    if isinstance(c, bool) or not isinstance(c, (int, np.integer)):
        raise InvalidProblem(f"{what} must be an integer, got {c!r}")
    if c < 1:
        raise InvalidProblem(f"{what} must be >= 1, got {c}")
    return int(c)


def wang_index(n, e, s, w, *, colors: int, colors_v: int | None = None):
    """Index of the Wang tile ``c_N c_E c_S c_W`` (eq. 2.1; works on numpy arrays).

    Parameters
    ----------
    n, e, s, w : int or array of int
        Edge colours.
    colors : int
        ``C``, or ``C_h`` (colours of the horizontal edges N and S) when ``colors_v`` is given.
    colors_v : int, optional
        ``C_v``, colours of the vertical edges E and W (default: ``colors``).
    """
    ch = colors
    cv = colors if colors_v is None else colors_v
    return ((n * cv + e) * ch + s) * cv + w


def wang_colors(i, *, colors: int, colors_v: int | None = None):
    """Edge colours ``(c_N, c_E, c_S, c_W)`` of Wang tile ``i`` (eq. 2.4; works on arrays)."""
    ch = colors
    cv = colors if colors_v is None else colors_v
    w = i % cv
    i = i // cv
    s = i % ch
    i = i // ch
    e = i % cv
    n = i // cv
    return n, e, s, w


def corner_index(ne, se, sw, nw, *, colors: int):
    """Index of the corner tile ``c_NE c_SE c_SW c_NW`` (eq. 2.5; works on numpy arrays)."""
    c = colors
    return ((ne * c + se) * c + sw) * c + nw


def corner_colors(i, *, colors: int):
    """Corner colours ``(c_NE, c_SE, c_SW, c_NW)`` of corner tile ``i`` (eq. 2.7)."""
    c = colors
    nw = i % c
    i = i // c
    sw = i % c
    i = i // c
    se = i % c
    ne = i // c
    return ne, se, sw, nw


def corner_to_wang(i, *, colors: int):
    """The Wang tile (over ``colors**2`` colours) equivalent to corner tile ``i`` (§2.9).

    Examples
    --------
    >>> # corner tile NE=1, SE=0, SW=0, NW=0 over 2 colours: N=(0,1), E=(1,0), S=(0,0), W=(0,0)
    >>> corner_to_wang(corner_index(1, 0, 0, 0, colors=2), colors=2) == wang_index(1, 2, 0, 0, colors=4)
    True
    """
    ne, se, sw, nw = corner_colors(i, colors=colors)
    c = colors
    return wang_index(nw * c + ne, ne * c + se, sw * c + se, nw * c + sw, colors=c * c)


@dataclass(frozen=True)
class TileSet:
    """The complete set of Wang or corner tiles over ``colors`` colours (§2.7).

    Parameters
    ----------
    kind : {"wang", "corner"}
    colors : int
        ``C`` (for Wang tiles: ``C_h``, the colours of the N and S edges).
    colors_v : int, optional
        Wang tiles only: ``C_v``, the colours of the E and W edges (default ``colors``).

    Attributes
    ----------
    n_tiles : int
        ``C**4`` (``(C_h C_v)**2`` for Wang tiles with ``C_h != C_v``).
    sides : tuple of str
        Names of the four colours in index order.

    Examples
    --------
    >>> ts = TileSet("wang", 2, colors_v=3)
    >>> ts.n_tiles, ts.colors_of(ts.index(1, 2, 0, 1))
    (36, (1, 2, 0, 1))
    """

    kind: str
    colors: int
    colors_v: int | None = None

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise InvalidProblem(f"unknown tile kind {self.kind!r}; choose one of {', '.join(KINDS)}")
        _check_colors(self.colors)
        if self.colors_v is not None:
            if self.kind != "wang":
                raise InvalidProblem("separate vertical colours (C_v) exist only for Wang tiles")
            _check_colors(self.colors_v, "colors_v")

    @property
    def cv(self) -> int:
        """Colours of the vertical edges (Wang) or of the corners (corner)."""
        return self.colors if self.colors_v is None else self.colors_v

    @property
    def n_tiles(self) -> int:
        return (self.colors * self.cv) ** 2

    @property
    def sides(self) -> tuple[str, ...]:
        return WANG_SIDES if self.kind == "wang" else CORNER_SIDES

    @property
    def radices(self) -> tuple[int, int, int, int]:
        """Number of colours of each of the four sides, in index order."""
        if self.kind == "corner":
            return (self.colors,) * 4
        return (self.colors, self.cv, self.colors, self.cv)

    def index(self, a, b, c, d):
        """Tile index of the four colours in :attr:`sides` order."""
        if self.kind == "corner":
            return corner_index(a, b, c, d, colors=self.colors)
        return wang_index(a, b, c, d, colors=self.colors, colors_v=self.colors_v)

    def colors_of(self, i):
        """The four colours of tile ``i`` (or of an array of indices) in :attr:`sides` order."""
        if self.kind == "corner":
            out = corner_colors(i, colors=self.colors)
        else:
            out = wang_colors(i, colors=self.colors, colors_v=self.colors_v)
        return tuple(int(x) for x in out) if np.ndim(i) == 0 else out

    def table(self) -> np.ndarray:
        """``(n_tiles, 4)`` array: row ``i`` holds the colours of tile ``i``."""
        i = np.arange(self.n_tiles)
        return np.stack(self.colors_of(i), axis=1).astype(np.int64)

    def as_wang(self) -> "TileSet":
        """The equivalent Wang tile set (§2.9): itself for Wang tiles, ``C**2`` colours for corner tiles."""
        return self if self.kind == "wang" else TileSet("wang", self.colors**2)

    def wang_images(self) -> np.ndarray:
        """Index, in :meth:`as_wang`, of each tile (the identity for Wang tiles)."""
        i = np.arange(self.n_tiles)
        return i if self.kind == "wang" else corner_to_wang(i, colors=self.colors)

    def describe(self) -> str:
        if self.kind == "wang" and self.colors_v is not None and self.colors_v != self.colors:
            return f"complete Wang tile set, C_h={self.colors}, C_v={self.colors_v} ({self.n_tiles} tiles)"
        return f"complete {self.kind} tile set over {self.colors} colours ({self.n_tiles} tiles)"
