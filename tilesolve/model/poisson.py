"""Corner-based Poisson disk tiles (Lagae, class notes §4.2.3, §4.3): problems and tile sets.

A *Poisson disk distribution* is a point set in which no two points are closer than a minimum
distance ``2 r`` (``r`` is the disk radius, §4.2). Its quality is the *relative radius*
``rho = r / r_max`` with ``r_max = sqrt(1 / (2 sqrt(3) N))`` for ``N`` points a unit area
(eq. 4.1-4.3): 0 for plain random points, 1 for the hexagonal lattice; good distributions sit
between 0.65 and 0.85.

Geometry (unit tiles, corners on the integer lattice, ``y`` north; §4.3, figure 4.3)
-------------------------------------------------------------------------------------
With ``d = 2 r`` (:attr:`PoissonTilesProblem.distance`), the *modified regions* are

* a **corner tile** around every lattice point: the square ``[-a, a)^2``, with
  ``a = d (1 + 1/sqrt 2)`` (:attr:`~PoissonTilesProblem.corner_half`): the corner regions are
  enlarged so that edge regions of neighbouring edges are ``d`` apart (the strips' inner
  corners ``(a, d)`` and ``(d, a)`` are ``sqrt(2) (a - d) = d`` apart); one per colour, ``C``;
* a **horizontal edge tile** on every edge ``(x, y)-(x+1, y)``: ``[a, 1 - a) x [-d, d)``
  relative to its west end; one per pair of end colours (west, east), ``C^2``;
* a **vertical edge tile** on every edge ``(x, y)-(x, y+1)``: ``[-d, d) x [a, 1 - a)``
  relative to its south end; one per pair (south, north), ``C^2``;
* an **interior tile** in every cell: ``[d, 1 - d)^2`` less the four corner squares; one per
  corner tile of the complete set, numbered by eq. 2.5 (``c_NE c_SE c_SW c_NW``), ``C^4``.

``C + 2 C^2 + C^4`` tiles in all. A point of an interior tile is at least ``d`` from every
point outside its cell; a point of an edge tile is within ``d`` only of the two corner tiles
at its ends and of the interiors of its two cells; corner tiles are ``1 - 2a >= d`` apart.
Hence when each tile is built against the tiles it can touch (corners first, then edges,
then interiors, §4.3), *every* colouring of the lattice gives a Poisson disk distribution.
That needs ``1 - 2a >= d``, i.e. ``d <= 1 / (3 + sqrt 2)``: :class:`PoissonTilesProblem`
refuses fewer points a tile than that allows (about 13 at ``rho = 0.75``).

Examples
--------
>>> p = PoissonTilesProblem(2, 64, 0.75)
>>> p.n_tiles, round(p.r_max, 4), round(p.distance, 4), round(p.corner_half, 4)
(26, 0.0672, 0.1007, 0.172)
>>> p.describe()
'corner-based Poisson disk tiles: C = 2 colours, N = 64 points a tile, rho = 0.75 (26 tiles)'
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.model.window import OnWindow, Window

__all__ = [
    "PoissonProblem",
    "PoissonTilesProblem",
    "PoissonWindowProblem",
    "PoissonTileSet",
    "PoissonWindow",
    "check_tiles",
    "r_max",
    "MAX_COLORS",
    "MAX_POINTS",
    "MAX_WINDOW_POINTS",
    "KINDS",
]

#: Most colours: ``C^4`` interior tiles (4,096 at C = 8, the notes' largest set, §4.3).
MAX_COLORS = 8
#: Most points a tile.
MAX_POINTS = 4096
#: Most points one window holds (about 16 bytes each, twice that while it is built).
MAX_WINDOW_POINTS = 1 << 26
#: The four kinds of modified regions, in the order they are built (§4.3).
KINDS = ("corner", "hedge", "vedge", "interior")
#: Relative slack of the built geometry over the distance it guarantees: points are built at
#: least ``distance * (1 + SLACK)`` apart, so rounding when a tile is moved into place never
#: brings two below ``distance``.
SLACK = 1e-9
#: Relative radii tilesolve builds: relaxation dart throwing reaches about 0.85 (§4.2.4).
RHO_RANGE = (0.05, 0.85)


def r_max(points: int) -> float:
    """Largest disk radius of ``points`` points on the unit torus (eq. 4.2).

    >>> round(r_max(1), 6)
    0.537285
    """
    return math.sqrt(1.0 / (2.0 * math.sqrt(3.0) * points))


def _corner_half(distance: float) -> float:
    return distance * (1 + SLACK) * (1 + 1 / math.sqrt(2))


def _fits(points: int, rho: float) -> bool:
    """Whether corner tiles of ``points`` points at ``rho`` leave ``d`` between them (§4.3)."""
    d = 2 * rho * r_max(points)
    return 1.0 - 2.0 * _corner_half(d) >= d * (1 + SLACK)


def _int(v, name: str, lo: int, hi: int) -> int:
    if isinstance(v, bool) or not isinstance(v, (int, np.integer)):
        raise InvalidProblem(f"{name} must be an integer, got {v!r}")
    if not lo <= int(v) <= hi:
        raise InvalidProblem(f"{name} must be within {lo}..{hi:,}, got {int(v):,}")
    return int(v)


def check_tiles(colors, points, rho, max_colors: int, fits, section: str) -> tuple[int, int, float]:
    """``(C, N, rho)`` of a corner-based tile set, checked: ranges, and ``fits(N, rho)``, that
    the corner regions leave the distance between them (``section`` of the notes says so; the
    message gives the fewest points that fit)."""
    colors, points = _int(colors, "colors", 1, max_colors), _int(points, "points a tile", 1, MAX_POINTS)
    if isinstance(rho, bool) or not isinstance(rho, (int, float, np.floating)) or not math.isfinite(rho):
        raise InvalidProblem(f"rho must be a number, got {rho!r}")
    lo, hi = RHO_RANGE
    if not lo <= float(rho) <= hi:
        raise InvalidProblem(f"rho must be within {lo}..{hi} (relaxation dart throwing reaches about {hi}), "
                             f"got {rho}")
    rho = float(rho)
    if not fits(points, rho):
        fewest = next((n for n in range(points, MAX_POINTS + 1) if fits(n, rho)), MAX_POINTS)
        raise InvalidProblem(f"{points} points a tile at rho {rho} leave no room between the corner "
                             f"regions ({section} needs 1 - 2a >= 2r): use at least {fewest} points a tile")
    return colors, points, rho


class PoissonProblem:
    """Either question of the ``poisson`` family: build a tile set, or a window of points."""


@dataclass(frozen=True)
class PoissonTilesProblem(PoissonProblem):
    """Build a set of corner-based Poisson disk tiles (§4.3).

    Parameters
    ----------
    colors : int
        ``C``, corner colours (1..8).
    points : int
        ``N``, points a tile on average (each cell of a tiling holds exactly ``N`` where the
        interior tiles could be filled, see :class:`PoissonTileSet`).
    rho : float
        Relative radius ``rho`` (eq. 4.3) every tiling keeps: no two points closer than
        ``2 rho r_max(N)``; within 0.05..0.85.
    lloyd : int
        Lloyd relaxation steps after the dart throwing of each tile (§4.2.4.3), 0..100.

    Raises
    ------
    InvalidProblem
        Values out of range, or a distance too large for the regions to fit in a tile (the
        message gives the fewest points that fit).
    """

    colors: int
    points: int
    rho: float
    lloyd: int = 0

    def __post_init__(self) -> None:
        values = check_tiles(self.colors, self.points, self.rho, MAX_COLORS, _fits, "§4.3")
        for name, v in zip(("colors", "points", "rho"), values):
            object.__setattr__(self, name, v)
        object.__setattr__(self, "lloyd", _int(self.lloyd, "Lloyd steps", 0, 100))

    @property
    def n_tiles(self) -> int:
        """``C + 2 C^2 + C^4``."""
        c = self.colors
        return c + 2 * c * c + c**4

    @property
    def r_max(self) -> float:
        return r_max(self.points)

    @property
    def radius(self) -> float:
        """``r = rho r_max`` (eq. 4.3): half the minimum distance."""
        return self.rho * self.r_max

    @property
    def distance(self) -> float:
        """``d = 2 r``, the distance no two points of a tiling come closer than."""
        return 2.0 * self.radius

    @property
    def corner_half(self) -> float:
        """``a``: corner tiles are ``[-a, a)^2`` around their lattice point (with the slack)."""
        return _corner_half(self.distance)

    def describe(self) -> str:
        return (f"corner-based Poisson disk tiles: C = {self.colors} colours, N = {self.points} points a tile, "
                f"rho = {self.rho:g}" + (f", {self.lloyd} Lloyd steps" if self.lloyd else "")
                + f" ({self.n_tiles} tiles)")


@dataclass(frozen=True, eq=False)
class PoissonTileSet:
    """The points of a corner-based Poisson disk tile set, by kind of tile.

    Attributes
    ----------
    problem : PoissonTilesProblem
    tiles : dict
        For each kind of :data:`KINDS`, a list of ``(k, 2)`` float64 arrays of points in the
        tile's own frame (see the module docstring): ``"corner"`` by colour, ``"hedge"`` by
        ``west * C + east``, ``"vedge"`` by ``south * C + north``, ``"interior"`` by eq. 2.5.
    seed : int or None
        The seed it was built with.
    stats : dict
        What the build measured (e.g. ``short``: points interior tiles lack to reach ``N``).
    """

    problem: PoissonTilesProblem
    tiles: dict = field(repr=False)
    seed: int | None = None
    stats: dict = field(default_factory=dict)

    def __post_init__(self) -> None:
        c = self.problem.colors
        want = {"corner": c, "hedge": c * c, "vedge": c * c, "interior": c**4}
        if not isinstance(self.tiles, dict) or set(self.tiles) != set(KINDS):
            raise InvalidProblem(f"a Poisson tile set has the tiles {', '.join(KINDS)}")
        for kind, n in want.items():
            arrs = self.tiles[kind]
            if len(arrs) != n:
                raise InvalidProblem(f"a set over {c} colours has {n} {kind} tiles, got {len(arrs)}")
            for a in arrs:
                if not (isinstance(a, np.ndarray) and a.ndim == 2 and a.shape[1] == 2 and a.dtype == np.float64):
                    raise InvalidProblem(f"{kind} tile points must be (k, 2) float64 arrays")

    @property
    def n_points(self) -> int:
        return sum(len(a) for arrs in self.tiles.values() for a in arrs)

    def describe(self) -> str:
        return f"{self.problem.describe()}, {self.n_points:,} points"


@dataclass(frozen=True, eq=False)
class PoissonWindowProblem(PoissonProblem, OnWindow):
    """A window of the Poisson disk distribution that a tiling of the plane with ``tileset`` gives.

    Parameters
    ----------
    tileset : PoissonTileSet
    window : Window or (x0, y0, width, height)
        Cells ``[x0, x0 + width) x [y0, y0 + height)``, y north (tile units).
    tiling : {"direct", "scanline"}
        The stochastic corner tiling that colours the lattice (class notes §3.3.1, §3.2.2).
    variant : {"complete", "compact"}
        Its corner tile set (``compact``: scanline only, §3.2.2).
    hash : {"long", "table"}
        Lattice hash (§3.4).
    """

    tileset: PoissonTileSet
    window: Window
    tiling: str = "direct"
    variant: str = "complete"
    hash: str = "long"

    def __post_init__(self) -> None:
        if not isinstance(self.tileset, PoissonTileSet):
            raise InvalidProblem(f"expected a PoissonTileSet, got {type(self.tileset).__name__}")
        window = Window.of(self.window)
        if not window.y_up:
            raise InvalidProblem("a Poisson window's y grows upwards")
        object.__setattr__(self, "window", window)
        if self.tiling not in ("direct", "scanline"):
            raise InvalidProblem(f"unknown corner tiling {self.tiling!r}; choose direct or scanline")
        if self.variant not in ("complete", "compact"):
            raise InvalidProblem(f"unknown corner tile set {self.variant!r}; choose complete or compact")
        if self.tiling == "direct" and self.variant == "compact":
            raise InvalidProblem("the direct corner tiling has no compact set (§3.5): use --tiling scanline")
        if self.hash not in ("long", "table"):
            raise InvalidProblem(f"unknown hash {self.hash!r}; choose long or table")
        n = self.n_cells * self.tileset.problem.points
        if n > MAX_WINDOW_POINTS:
            raise InvalidProblem(f"a {window.width}x{window.height} window holds about {n:,} points; tilesolve "
                                 f"builds at most {MAX_WINDOW_POINTS:,} at once: ask for smaller windows")

    @property
    def distance(self) -> float:
        return self.tileset.problem.distance

    def describe(self) -> str:
        return (f"Poisson disk window {self.window.describe()} ({self.tiling} corner tiling), "
                f"{self.tileset.problem.describe()}")


@dataclass(frozen=True, eq=False)
class PoissonWindow:
    """The points of a window: ``local[i] + (x0, y0)`` is point ``i`` of the plane.

    Coordinates are kept relative to the window's bottom-left corner so that windows far from
    the origin (up to 2**62) keep full float64 precision; :meth:`absolute` adds the origin.
    """

    window: Window
    local: np.ndarray = field(repr=False)
    distance: float = 0.0

    @property
    def n_points(self) -> int:
        return len(self.local)

    def absolute(self) -> np.ndarray:
        """``(n, 2)`` float64 plane coordinates (exact only while the origin is below 2**31 or so)."""
        return self.local + np.array([self.window.x0, self.window.y0], dtype=np.float64)
