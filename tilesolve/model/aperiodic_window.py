"""A window of a tiling of the plane by an aperiodic Wang tile set (issue 20, §1).

An aperiodic set tiles the plane, never periodically, and its constructive routes give any
window of one such tiling: a Markov partition of a torus codes the Jeandel-Rao and Labbé U19
tilings (Labbé, arXiv:1903.06137), balanced sequences the Kari and Culik tilings (Kari 1996,
Culik 1996). A problem names a built-in tile set and a :class:`~tilesolve.model.window.Window`:
the ``width x height`` cells whose bottom-left cell is ``(x0, y0)``, y growing upwards. A
solution is the grid ``grid[row, col]`` of tile indices into the set's tiles (the built-in
file's order), row 0 the top row: ``grid[r, c]`` is the tile at ``window.cell(r, c) ==
(x0 + c, y0 + height - 1 - r)``. The seed of the run chooses which tiling of the plane the
window is cut from: windows of one seed agree where they overlap.

Examples
--------
>>> from tilesolve.model.board import WangTileSet
>>> ts = WangTileSet([[0, 0, 0, 0]], 1)
>>> p = AperiodicWindowProblem("one-tile", ts, (-3, 4, 5, 2))
>>> p.shape, p.n_cells
((2, 5), 10)
>>> p.describe()
'window x -3..1, y 4..5 (y grows upwards) of the one-tile set (1 Wang tiles)'
"""

from __future__ import annotations

from dataclasses import dataclass

from tilesolve.errors import InvalidProblem
from tilesolve.model.board import WangTileSet
from tilesolve.model.window import OnWindow, Window

__all__ = ["AperiodicWindowProblem", "MAX_WINDOW_TILES", "BYTES_PER_TILE"]

#: Peak memory of building, checking and writing a window, per tile (measured: ``tilesolve
#: aperiodic tiling --builtin jeandel-rao --region 0,0,10000x10000 -o t.json --png t.png``, 0.8 GiB).
BYTES_PER_TILE = 8
#: Most tiles in one window (a 11,585 x 11,585 square): its file (4/3 bytes a tile) stays within
#: the default input limit of ``tilesolve verify`` (256 MiB) and its PNG within the pixel limit.
MAX_WINDOW_TILES = 1 << 27


@dataclass(frozen=True, eq=False)
class AperiodicWindowProblem(OnWindow):
    """One window of a tiling of the plane by a built-in aperiodic Wang tile set.

    Parameters
    ----------
    name : str
        The built-in tile set's name (``tilesolve tiles --builtin`` lists them); its
        constructive route is chosen by it.
    tileset : WangTileSet
        Its tiles, in the built-in file's order (grid entries index them).
    window : Window or (x0, y0, width, height)
        The cells, y growing upwards (kept as a :class:`Window`).

    Raises
    ------
    InvalidProblem
        A window whose y grows downwards (row 0 is the top row), or one too large to build
        and check (the message gives the memory it would need).
    """

    name: str
    tileset: WangTileSet
    window: Window

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name:
            raise InvalidProblem(f"a built-in tile set is named by a string, got {self.name!r}")
        if not isinstance(self.tileset, WangTileSet):
            raise InvalidProblem(f"expected a WangTileSet, got {type(self.tileset).__name__}")
        window = Window.of(self.window)
        if not window.y_up:
            raise InvalidProblem("an aperiodic window has y growing upwards (row 0 is its top row); got a window "
                                 "whose y grows downwards")
        n = window.width * window.height
        if n > MAX_WINDOW_TILES:
            raise InvalidProblem(f"a {window.width}x{window.height} window has {n:,} tiles and needs about "
                                 f"{BYTES_PER_TILE * n / 2**30:,.1f} GiB to build and check; tilesolve builds at "
                                 f"most {MAX_WINDOW_TILES:,} tiles at once: ask for smaller windows")
        object.__setattr__(self, "window", window)

    def describe(self) -> str:
        return f"window {self.window.describe()} of the {self.name} set ({len(self.tileset)} Wang tiles)"
