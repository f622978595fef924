"""Stochastic Wang and corner tilings of windows of the plane (Lagae, class notes ch. 3).

A stochastic tiling covers the infinite plane with tiles of a Wang or corner tile set, each
tile chosen at random among those that fit (scanline algorithms, §3.2) or computed from
hashes of the lattice around it (direct algorithms, §3.3). A problem asks for one *window*
of such a tiling: the ``width x height`` block of cells whose SW (lower-left) cell is the
tile named ``(x0, y0)`` (tiles are named by their SW corner, §2.7, §3.3.1), a
:class:`~tilesolve.model.window.Window`. ``x`` is the column coordinate, growing east; ``y`` is
the row coordinate, growing *north* as in the notes (``y_up``). A solution is the grid
``grid[row, col]`` with row 0 at the top: ``grid[r, c]`` is the tile at
``window.cell(r, c) == (x0 + c, y0 + height - 1 - r)``. Coordinates may be negative; lattice
points beyond the 63-bit range the hashes address are refused.

Tiles are numbered by eq. 2.1 (Wang, ``c_N c_E c_S c_W``) or eq. 2.5 (corner,
``c_NE c_SE c_SW c_NW``) in every tile set variant (:class:`tilesolve.model.tiles.TileSet`).

Examples
--------
>>> p = StochasticProblem("corner", 3, window=(-4, 10, 8, 5))
>>> p.shape, p.tiles.n_tiles
((5, 8), 81)
>>> p.window
Window(x0=-4, y0=10, width=8, height=5, y_up=True)
>>> p.describe()
'stochastic corner tiling, window x -4..3, y 10..14 (y grows upwards), complete corner tile set over 3 colours (81 tiles)'
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.model.tiles import KINDS, VARIANTS, TileSet
from tilesolve.model.window import OnWindow, Window

__all__ = ["StochasticProblem", "HASHES", "WANG_DIRECT", "MAX_WINDOW_TILES", "MAX_SET_TILES", "LATTICE"]

#: Lattice hashes (§3.4): ``"long"``, the long-period hash of §3.4.3; ``"table"``, one
#: permutation table (§3.4.1, eq. 3.3).
HASHES: tuple[str, ...] = ("long", "table")
#: Direct algorithms for the complete Wang set: a hash at the tile edges (§3.3.2.3) or two
#: hashes at the corners (§3.3.2.1).
WANG_DIRECT: tuple[str, ...] = ("edges", "two")
#: Most tiles in one window: building, checking and writing one take about 32 bytes a tile
#: (measured: 0.6 GB at peak for 4096 x 4096 compact corner tiles), about 2 GiB here.
MAX_WINDOW_TILES = 1 << 26
#: Largest tile set: the verifier holds a colour table of 4 integers per tile (C = 32 complete).
MAX_SET_TILES = 1 << 20
#: ``(lowest, highest)`` lattice coordinate a window may touch: the edge hash of §3.3.2.3
#: evaluates ``2x + 2`` and ``2y + 2``, which must stay within 64-bit signed integers.
LATTICE = (-(1 << 63) // 2 + 2, ((1 << 63) - 1) // 2 - 2)

_BYTES_PER_TILE = 32


def _int(v, name: str) -> int:
    if isinstance(v, bool) or not isinstance(v, (int, np.integer)):
        raise InvalidProblem(f"{name} must be an integer, got {v!r}")
    return int(v)


def _gib(n_bytes: int) -> str:
    return f"{n_bytes / 2**30:,.1f} GiB"


@dataclass(frozen=True)
class StochasticProblem(OnWindow):
    """One window of a stochastic Wang or corner tiling (class notes ch. 3).

    Parameters
    ----------
    kind : {"wang", "corner"}
    colors : int
        ``C``, the number of edge (Wang) or corner (corner) colours.
    window : Window or (x0, y0, width, height)
        The cells ``[x0, x0 + width) x [y0, y0 + height)``, ``y`` pointing north (see the
        module docstring); kept as a :class:`Window`.
    variant : {"complete", "compact", "sums"}
        The tile set (:class:`TileSet`): complete (§2.7), compact (the scanline sets of
        §3.2.1-3.2.2) or sums (the direct compact Wang set of §3.3.2.2).
    hash : {"long", "table"}
        Lattice hash of the generators (§3.4); its tables are drawn from the run's seed.
    algorithm : {"edges", "two"}
        Direct route, complete Wang set only: hashes at the edges (§3.3.2.3) or two hashes at
        the corners (§3.3.2.1). Ignored otherwise.

    Raises
    ------
    InvalidProblem
        Unknown kind, variant, hash or algorithm; fewer than 1 colour (2 for compact sets);
        a tile set or window too large to build and check (the message says what it would
        need); a window that leaves the hashes' 63-bit lattice, or whose y grows downwards (the
        generators give row 0 the north-most tiles).
    """

    kind: str
    colors: int
    window: Window
    variant: str = "complete"
    hash: str = "long"
    algorithm: str = "edges"

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise InvalidProblem(f"unknown tile kind {self.kind!r}; choose one of {', '.join(KINDS)}")
        if self.variant not in VARIANTS:
            raise InvalidProblem(f"unknown tile set {self.variant!r}; choose one of {', '.join(VARIANTS)}")
        c = _int(self.colors, "colors")
        if c < 1:
            raise InvalidProblem(f"colors must be >= 1, got {c}")
        object.__setattr__(self, "colors", c)
        n_set = {"complete": c**4, "compact": 2 * c**2 if self.kind == "wang" else 2 * c**3, "sums": c**3}[self.variant]
        if n_set > MAX_SET_TILES:
            raise InvalidProblem(f"the {self.variant} {self.kind} set over {c:,} colours has {n_set:,} tiles: its "
                                 f"colour table needs {_gib(32 * n_set)} to check a tiling; tilesolve takes sets of "
                                 f"at most {MAX_SET_TILES:,} tiles")
        TileSet(self.kind, c, variant=self.variant)  # the set's own checks (sums is Wang only, ...)
        if self.hash not in HASHES:
            raise InvalidProblem(f"unknown hash {self.hash!r}; choose one of {', '.join(HASHES)}")
        if self.algorithm not in WANG_DIRECT:
            raise InvalidProblem(f"unknown direct Wang algorithm {self.algorithm!r}; "
                                 f"choose one of {', '.join(WANG_DIRECT)}")
        window = Window.of(self.window)
        if not window.y_up:
            raise InvalidProblem("a stochastic tiling's window has y growing upwards (row 0 is its north-most "
                                 "row, as the notes draw it); got a window whose y grows downwards")
        x0, y0, w, h = window.x0, window.y0, window.width, window.height
        lo, hi = LATTICE
        if not (lo <= x0 and x0 + w <= hi and lo <= y0 and y0 + h <= hi):
            raise InvalidProblem(f"window [{x0}, {x0 + w}) x [{y0}, {y0 + h}) leaves the lattice the hashes "
                                 f"address ({lo} .. {hi})")
        if w * h > MAX_WINDOW_TILES:
            raise InvalidProblem(f"a {w}x{h} window has {w * h:,} tiles and needs about "
                                 f"{_gib(_BYTES_PER_TILE * w * h)} to build and check; tilesolve builds at most "
                                 f"{MAX_WINDOW_TILES:,} tiles at once: ask for smaller windows")
        object.__setattr__(self, "window", window)

    @functools.cached_property
    def tiles(self) -> TileSet:
        """The tile set the window is tiled with."""
        return TileSet(self.kind, self.colors, variant=self.variant)

    def describe(self) -> str:
        return f"stochastic {self.kind} tiling, window {self.window.describe()}, {self.tiles.describe()}"
