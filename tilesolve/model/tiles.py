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

*Tile sets* (:class:`TileSet`): the *complete* set holds every tile (§2.7, the default); the
*compact* sets of the scanline stochastic tiling algorithms hold two tiles for each colouring
of the edges or corners a scanline placement has already fixed (§3.2.1, ``2 C**2`` Wang tiles;
§3.2.2, ``2 C**3`` corner tiles); the *sums* set is the ``C**3`` Wang tiles of the direct
stochastic tiling algorithm for compact sets, whose edge colours are sums of corner colours
(§3.3.2.2). :attr:`TileSet.indices` lists the tiles of a set by their eq. 2.1/2.5 index.

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
>>> TileSet("wang", 2, variant="compact").indices.tolist()   # the notes' Fig. 3.2
[0, 3, 5, 6, 9, 10, 12, 15]
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from tilesolve.errors import InvalidProblem

__all__ = [
    "KINDS",
    "VARIANTS",
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
#: Tile set variants (see :class:`TileSet`).
VARIANTS: tuple[str, ...] = ("complete", "compact", "sums")
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


def _compact_wang_indices(c: int) -> np.ndarray:
    """The ``2 C**2`` tiles of the compact Wang set (§3.2.1); see :class:`TileSet`."""
    n, w = np.divmod(np.arange(c * c), c)  # every (N, W) combination
    k = np.arange(2)[:, None]  # two tiles per (N, W): E = N + k, S = W + k
    e, s = (n + k) % c, (w + k) % c
    return np.unique(wang_index(n, e, s, w, colors=c))


def _compact_corner_indices(c: int) -> np.ndarray:
    """The ``2 C**3`` tiles of the compact corner set (§3.2.2); see :class:`TileSet`."""
    ne, nw, sw = np.unravel_index(np.arange(c**3), (c, c, c))  # every (NE, NW, SW) combination
    x = (ne + nw + sw) % c
    se = np.stack([x, (x + 1) % c])  # two SE colours per (NE, NW, SW)
    return np.unique(corner_index(ne, se, sw, nw, colors=c))


def _sums_wang_indices(c: int) -> np.ndarray:
    """The ``C**3`` Wang tiles of the direct algorithm for compact sets (§3.3.2.2).

    Corner colours (NE, SE, SW, NW) and (NE - t, SE + t, SW - t, NW + t) give the same edge
    sums, so fixing NW = 0 reaches every tile once and needs ``C**3`` rather than ``C**4`` work.
    """
    ne, se, sw = np.unravel_index(np.arange(c**3), (c, c, c))
    nw = 0
    return np.unique(wang_index((nw + ne) % c, (ne + se) % c, (se + sw) % c, (sw + nw) % c, colors=c))


@dataclass(frozen=True)
class TileSet:
    """A set of Wang or corner tiles over ``colors`` colours: complete (§2.7) or compact (§3.2-3.3).

    Parameters
    ----------
    kind : {"wang", "corner"}
    colors : int
        ``C`` (for Wang tiles: ``C_h``, the colours of the N and S edges).
    colors_v : int, optional
        Complete Wang sets only: ``C_v``, the colours of the E and W edges (default ``colors``).
    variant : {"complete", "compact", "sums"}
        ``"complete"`` (default): every tile, ``C**4`` of them (§2.7).

        ``"compact"``, Wang tiles (§3.2.1): two tiles for each combination of N and W edge
        colours, ``2 C**2`` tiles, so that a scanline tiling (west to east, north to south)
        always has two tiles to choose from. For ``C = 2`` this is the notes' set
        0 3 5 6 9 10 12 15 (Fig. 3.2). The notes give no rule for ``C > 2``; tilesolve's
        choice generalises the published set: for each ``(N, W)`` the tiles with
        ``E = N + k`` and ``S = W + k (mod C)``, ``k = 0, 1``. The two tiles of each ``(N, W)``
        differ in both ``E`` and ``S``, and every colour occurs on every edge, so a scanline
        tiling keeps using all colours.

        ``"compact"``, corner tiles (§3.2.2): two tiles for each combination of NE, NW and SW
        corner colours, ``2 C**3`` tiles. tilesolve's choice (the notes give none):
        ``SE`` is ``x`` or ``x + 1 (mod C)`` with ``x = (NE + NW + SW) mod C``. For ``C = 2``
        this is the complete corner set, as the notes remark.

        ``"sums"``, Wang tiles only (§3.3.2.2): the ``C**3`` tiles of the direct stochastic
        tiling algorithm for compact sets, whose edge colours are sums mod ``C`` of corner
        colours: ``N = NW + NE``, ``E = NE + SE``, ``S = SE + SW``, ``W = SW + NW``. For
        ``C = 2`` it equals the compact Wang set.

    Attributes
    ----------
    n_tiles : int
        Size of the set: ``C**4`` complete (``(C_h C_v)**2`` for Wang tiles with
        ``C_h != C_v``), ``2 C**2`` compact Wang, ``2 C**3`` compact corner, ``C**3`` sums.
    indices : numpy.ndarray
        The sorted eq. 2.1 (Wang) or eq. 2.5 (corner) indices of the tiles of the set.
    sides : tuple of str
        Names of the four colours in index order.

    Notes
    -----
    :meth:`index` and :meth:`colors_of` are the eq. 2.1/2.5 arithmetic of the complete set
    for every variant; :meth:`table` lists the tiles of the set, in :attr:`indices` order.

    Examples
    --------
    >>> ts = TileSet("wang", 2, colors_v=3)
    >>> ts.n_tiles, ts.colors_of(ts.index(1, 2, 0, 1))
    (36, (1, 2, 0, 1))
    >>> TileSet("corner", 3, variant="compact").n_tiles, TileSet("wang", 3, variant="sums").n_tiles
    (54, 27)
    """

    kind: str
    colors: int
    colors_v: int | None = None
    variant: str = "complete"

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise InvalidProblem(f"unknown tile kind {self.kind!r}; choose one of {', '.join(KINDS)}")
        _check_colors(self.colors)
        if self.colors_v is not None:
            if self.kind != "wang":
                raise InvalidProblem("separate vertical colours (C_v) exist only for Wang tiles")
            _check_colors(self.colors_v, "colors_v")
        if self.variant not in VARIANTS:
            raise InvalidProblem(f"unknown tile set {self.variant!r}; choose one of {', '.join(VARIANTS)}")
        if self.variant != "complete":
            if self.cv != self.colors:
                raise InvalidProblem("separate vertical colours (C_v) exist only for complete Wang tile sets")
            if self.variant == "sums" and self.kind != "wang":
                raise InvalidProblem("the sums tile set (§3.3.2.2) exists only for Wang tiles")
            if self.variant == "compact" and self.colors < 2:
                raise InvalidProblem(f"a compact tile set needs at least 2 colours, got {self.colors}")

    @property
    def cv(self) -> int:
        """Colours of the vertical edges (Wang) or of the corners (corner)."""
        return self.colors if self.colors_v is None else self.colors_v

    @property
    def n_tiles(self) -> int:
        c = self.colors
        if self.variant == "compact":
            return 2 * c**2 if self.kind == "wang" else 2 * c**3
        if self.variant == "sums":
            return c**3
        return (c * self.cv) ** 2

    @cached_property
    def indices(self) -> np.ndarray:
        """Sorted indices of the tiles of the set (read-only; ``arange(n_tiles)`` when complete)."""
        if self.variant == "complete":
            out = np.arange(self.n_tiles, dtype=np.int64)
        elif self.variant == "sums":
            out = _sums_wang_indices(self.colors)
        elif self.kind == "wang":
            out = _compact_wang_indices(self.colors)
        else:
            out = _compact_corner_indices(self.colors)
        out = out.astype(np.int64)
        out.setflags(write=False)
        return out

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

    def check_numbers(self, grid) -> None:
        """Refuse a grid cell that holds no tile number over these colours (``0 .. C_h^2 C_v^2 - 1``
        for Wang tiles, ``0 .. C^4 - 1`` for corner tiles): such a cell has no colours to draw.

        >>> TileSet("wang", 2).check_numbers([[0, 15], [16, 3]])
        Traceback (most recent call last):
        ...
        tilesolve.errors.InvalidProblem: the grid holds 16 at row 1, col 0, not a tile number over C = 2 (0..15); tilesolve verify lists the violations
        """
        g = np.asarray(grid, dtype=np.int64)
        n = (self.colors * self.cv) ** 2
        outside = (g < 0) | (g >= n)
        if outside.any():
            r, c = (int(i) for i in np.argwhere(outside)[0])
            raise InvalidProblem(f"the grid holds {int(g[r, c])} at row {r}, col {c}, not a tile number over "
                                 f"C = {self.colors} (0..{n - 1}); tilesolve verify lists the violations")

    def table(self) -> np.ndarray:
        """``(n_tiles, 4)`` array: row ``k`` holds the colours of tile ``indices[k]``.

        For the complete set, row ``i`` holds the colours of tile ``i``.
        """
        i = np.array(self.indices)
        return np.stack(self.colors_of(i), axis=1).astype(np.int64)

    def as_wang(self) -> "TileSet":
        """The Wang tile set that holds the images (§2.9): itself for Wang tiles; for corner
        tiles the complete Wang set over ``C**2`` colours."""
        return self if self.kind == "wang" else TileSet("wang", self.colors**2)

    def wang_images(self) -> np.ndarray:
        """Index, in :meth:`as_wang`, of each tile of :attr:`indices` (the indices themselves for Wang tiles)."""
        i = np.array(self.indices)
        return i if self.kind == "wang" else corner_to_wang(i, colors=self.colors)

    def describe(self) -> str:
        if self.variant == "sums":
            return f"sums Wang tile set (§3.3.2.2) over {self.colors} colours ({self.n_tiles} tiles)"
        if self.variant == "compact":
            return f"compact {self.kind} tile set over {self.colors} colours ({self.n_tiles} tiles)"
        if self.kind == "wang" and self.colors_v is not None and self.colors_v != self.colors:
            return f"complete Wang tile set, C_h={self.colors}, C_v={self.colors_v} ({self.n_tiles} tiles)"
        return f"complete {self.kind} tile set over {self.colors} colours ({self.n_tiles} tiles)"
