"""Recursive Wang tiles for multi-density blue noise (Kopf, Cohen-Or, Deussen and Lischinski,
*Recursive Wang tiles for real-time blue noise*, SIGGRAPH 2006; class notes Part V).

The tiles
---------
The Wang tiles here are the Wang tile set equivalent to the complete corner tile set over ``C``
colours (class notes §2.9: an edge's colour is the pair of its end colours; for ``C = 2``, 16
tiles over 4 edge colours). Such a set is free of the corner problem (§2.6), which is what lets
every level below be *guaranteed* a Poisson disk distribution across seams. Each tile carries
the points of the corner-based Poisson disk tiles (§4.3, :mod:`tilesolve.model.poisson`: its
corner, edge and interior regions) in *progressive* order (every prefix of a region's points is
spread out, so a prefix is a sparser distribution; Kopf et al.), and a **subdivision rule**:
the colours of the ``(n + 1) x (n + 1)`` lattice points of its ``n x n`` sub-tiles, so that
the sub-tiles are tiles of the same set. A rule keeps the parent's corner colours at its
corners, and the sub-colours along an edge depend only on the edge's end colours (one sequence
for each ordered pair, horizontal and vertical apart): neighbouring parents then subdivide
into a valid tiling across their common edge, at every depth (Kopf et al.).

Levels (what ``level l`` means)
-------------------------------
Depth-``k`` tiles have side ``n^-k``; the candidates of level ``k`` are the tile set's points
placed on the depth-``k`` lattice, ``N n^(2k)`` a unit area, pairwise at least
``d_k = d n^-k`` apart (``d = 2 rho r_max(N)``, §4.3). The point set of level ``l`` is

    ``S_0`` = the candidates of level 0,
    ``S_l`` = ``S_(l-1)`` and every candidate of level ``l`` at least ``d_l`` from all of ``S_(l-1)``.

So ``S_(l-1)`` is a subset of ``S_l`` (the parent's points stay, new points are added), and
``S_l`` is a Poisson disk distribution at distance ``d_l``: old pairs are ``d_(l-1) > d_l``
apart, new pairs ``d_l`` (the corner tiles' guarantee), mixed pairs ``d_l`` (the rule). The
paper is not among the project's sources (the class notes' Part V holds its slides only), and
this rule is the project's own way to keep the parent's points and a stated distance at every
level; a window stays random access: a point's fate depends on the points within
``d_(l-1) + d_l + ... < d`` of it only. The price: the new points within ``d_l`` of the
parent's are dropped, so level ``l`` holds about 83 % (``n = 2``), 90 % (``n = 3``) or 94 %
(``n = 4``) of ``N n^(2l)`` points a tile.

Density
-------
Every point has a *level* and a *rank* ``u`` in ``[0, 1)``: ``(i + h) / m`` for the ``i``-th
of the ``m`` points of its region in progressive order, ``h`` a hash of where the region is
placed (so that the regions of one point each, at every lattice point, do not all appear at
one density, a lattice). For a density ``D`` (points a unit area), level ``k`` spans
``(lo_k, hi_k]`` with ``hi_k = N n^(2k)``, ``lo_0 = 0``, ``lo_k = hi_(k-1)``: a point of level
``k`` at ``x`` is kept when ``u < (D(x) - lo_k) / (hi_k - lo_k)`` (Kopf et al.: a point is
kept if its rank fits the local density). The density can thus vary continuously, and a
window at the uniform density ``hi_l`` is ``S_l``.

>>> p = RecursiveTilesProblem(2, 16, 0.7, 4)
>>> p.n_tiles, p.base.n_tiles, round(p.distance_at(2), 5)
(16, 26, 0.01175)
>>> p.level_for(16 * 16 + 1), p.level_for(16 * 16)
(2, 1)
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.model.poisson import PoissonTilesProblem, PoissonTileSet
from tilesolve.model.window import OnWindow, Window

__all__ = ["RecursiveProblem", "RecursiveTilesProblem", "RecursiveTileSet", "RecursiveWindowProblem",
           "RecursiveWindow", "check_level", "MAX_LEVEL", "MAX_SUBDIVISION", "MAX_CANDIDATES"]

#: Deepest level a window reaches (``n^MAX_LEVEL`` sub-tiles a side).
MAX_LEVEL = 12
#: Largest ``n`` of the ``n x n`` subdivision.
MAX_SUBDIVISION = 8
#: Most candidates a window's deepest level may hold (about 40 bytes each while it is built).
MAX_CANDIDATES = 1 << 25


class RecursiveProblem:
    """Either question of the ``recursive-wang`` family: build a set, or a window of points."""


@dataclass(frozen=True)
class RecursiveTilesProblem(RecursiveProblem):
    """Build a set of recursive Wang tiles (see the module docstring).

    Parameters
    ----------
    colors : int
        ``C``, corner colours: ``C^4`` Wang tiles.
    points : int
        ``N``, points a tile at level 0.
    rho : float
        Relative radius of every level (eq. 4.3 at that level's density).
    subdivision : int
        ``n``: each tile splits into ``n x n`` sub-tiles (2..8); density grows by ``n^2`` a level.
    lloyd : int
        Lloyd steps of the corner-based tiles (§4.2.4.3).
    """

    colors: int
    points: int
    rho: float
    subdivision: int = 4
    lloyd: int = 0

    def __post_init__(self) -> None:
        n = self.subdivision
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or not 2 <= int(n) <= MAX_SUBDIVISION:
            raise InvalidProblem(f"subdivision must be an integer within 2..{MAX_SUBDIVISION}, got {n!r}")
        object.__setattr__(self, "subdivision", int(n))
        base = PoissonTilesProblem(self.colors, self.points, self.rho, self.lloyd)
        for name in ("colors", "points", "rho", "lloyd"):
            object.__setattr__(self, name, getattr(base, name))

    @property
    def base(self) -> PoissonTilesProblem:
        """The corner-based Poisson disk tiles every level places (§4.3)."""
        return PoissonTilesProblem(self.colors, self.points, self.rho, self.lloyd)

    @property
    def n_tiles(self) -> int:
        """``C^4`` Wang tiles (the complete corner set, §2.9)."""
        return self.colors**4

    @property
    def distance(self) -> float:
        """``d``, the distance of level 0."""
        return self.base.distance

    def distance_at(self, level: int) -> float:
        """``d_l = d n^-l``."""
        return self.distance / self.subdivision**level

    def density_at(self, level: int) -> float:
        """``hi_l = N n^(2l)``: candidates a unit area at level ``l``."""
        return float(self.points) * self.subdivision ** (2 * level)

    def level_for(self, density: float) -> int:
        """The least level whose ``hi_l`` reaches ``density`` (points a unit area)."""
        level = 0
        while self.density_at(level) < density and level < MAX_LEVEL:
            level += 1
        return level

    def describe(self) -> str:
        return (f"recursive Wang tiles: C = {self.colors} ({self.n_tiles} tiles), N = {self.points} points a tile, "
                f"rho = {self.rho:g}, {self.subdivision}x{self.subdivision} subdivision"
                + (f", {self.lloyd} Lloyd steps" if self.lloyd else ""))


@dataclass(frozen=True, eq=False)
class RecursiveTileSet:
    """Recursive Wang tiles: the corner-based tiles every level places, and the subdivision rules.

    Attributes
    ----------
    problem : RecursiveTilesProblem
    base : PoissonTileSet
        Each region's points in progressive order (the rank of a point is its index).
    rules : (C^4, n + 1, n + 1) int64 array
        ``rules[t, b, a]``: the colour of sub-lattice point ``(a, b)`` (x east, y north, in
        sub-tile units) of Wang tile ``t`` (numbered by eq. 2.5: ``c_NE c_SE c_SW c_NW``).
    seed : int or None
    """

    problem: RecursiveTilesProblem
    base: PoissonTileSet = field(repr=False)
    rules: np.ndarray = field(repr=False)
    seed: int | None = None

    def __post_init__(self) -> None:
        p = self.problem
        if not isinstance(self.base, PoissonTileSet) or self.base.problem != p.base:
            raise InvalidProblem("the corner tiles of a recursive set must be built for its colours, points and rho")
        r = self.rules
        shape = (p.n_tiles, p.subdivision + 1, p.subdivision + 1)
        if not isinstance(r, np.ndarray) or r.shape != shape or r.dtype != np.int64:
            raise InvalidProblem(f"subdivision rules must be a {shape} int64 array")
        if r.size and (r.min() < 0 or r.max() >= p.colors):
            raise InvalidProblem(f"subdivision rules hold colours outside 0..{p.colors - 1}")

    @property
    def n_points(self) -> int:
        return self.base.n_points

    def describe(self) -> str:
        return f"{self.problem.describe()}, {self.n_points:,} points"


def _density_grid(density) -> np.ndarray | None:
    if density is None:
        return None
    grid = np.asarray(density, dtype=np.float64)
    if grid.ndim == 0:
        grid = grid.reshape(1, 1)
    if grid.ndim != 2 or grid.size == 0 or not np.isfinite(grid).all() or (grid < 0).any():
        raise InvalidProblem("a density is a number or a 2-D grid of non-negative numbers (points a unit area)")
    return grid


@dataclass(frozen=True, eq=False)
class RecursiveWindowProblem(RecursiveProblem, OnWindow):
    """A window of the recursive Wang tiling's points, at one level or at a density.

    Parameters
    ----------
    tileset : RecursiveTileSet
    window : Window or (x0, y0, width, height)
        Level-0 cells ``[x0, x0 + width) x [y0, y0 + height)``, y north, coloured by the
        direct corner tiling (§3.3.1).
    level : int or None
        ``S_level``, every point of that level; ``None`` with a ``density``.
    density : float or 2-D array or None
        Points a unit area: one number, or a grid stretched over the window (row 0 at the top,
        nearest cell), e.g. from an image. The level is the least that reaches its maximum.
    label : str
        How the density was given, for people (files keep it).
    hash : {"long", "table"}
    """

    tileset: RecursiveTileSet
    window: Window
    level: int | None = None
    density: np.ndarray | None = field(default=None, repr=False)
    label: str = ""
    hash: str = "long"

    def __post_init__(self) -> None:
        if not isinstance(self.tileset, RecursiveTileSet):
            raise InvalidProblem(f"expected a RecursiveTileSet, got {type(self.tileset).__name__}")
        window = Window.of(self.window)
        if not window.y_up:
            raise InvalidProblem("a recursive Wang window's y grows upwards")
        object.__setattr__(self, "window", window)
        grid = _density_grid(self.density)
        object.__setattr__(self, "density", grid)
        p = self.tileset.problem
        if (self.level is None) == (grid is None):
            raise InvalidProblem("give a window either a level or a density")
        if grid is not None:
            object.__setattr__(self, "level", p.level_for(float(grid.max())))
        object.__setattr__(self, "level", check_level(self.level))
        if self.hash not in ("long", "table"):
            raise InvalidProblem(f"unknown hash {self.hash!r}; choose long or table")
        if (window.width + 2) * (window.height + 2) * p.points > MAX_CANDIDATES:  # before any work
            self._too_many((window.width + 2) * (window.height + 2) * p.points)
        n = sum(bw * bh * p.density_at(k) for k, (_, _, bw, bh) in enumerate(self.boxes()))
        if n > MAX_CANDIDATES:
            self._too_many(n)
        if not self.label:
            object.__setattr__(self, "label", f"level {self.level}" if grid is None else
                               f"density up to {float(grid.max()):g} a unit area")

    def _too_many(self, n: float) -> None:
        w = self.window
        raise InvalidProblem(f"a {w.width}x{w.height} window at level {self.level} holds about {n:,.0f} candidate "
                             f"points; tilesolve builds at most {MAX_CANDIDATES:,} at once: ask for a smaller "
                             "window or a lower level or density")

    def level_map(self) -> np.ndarray:
        """``(height, width)``: the deepest level each cell of the window needs (row 0 at the
        top): the least level whose ``hi_l`` reaches the cell's largest density."""
        w, p = self.window, self.tileset.problem
        if self.density is None:
            return np.full((w.height, w.width), self.level, np.int64)
        rows, cols = self.density.shape
        # the density cells a window cell meets: those of its nearest-cell lookups
        c0, c1 = (np.arange(w.width) * cols) // w.width, -((-(np.arange(1, w.width + 1)) * cols) // w.width)
        r0, r1 = (np.arange(w.height) * rows) // w.height, -((-(np.arange(1, w.height + 1)) * rows) // w.height)
        by_col = np.stack([self.density[:, a:b].max(axis=1) for a, b in zip(c0, c1)], axis=1)
        top = np.stack([by_col[a:b].max(axis=0) for a, b in zip(r0, r1)])
        return sum((top > p.density_at(k)).astype(np.int64) for k in range(MAX_LEVEL))

    def boxes(self) -> list[tuple[int, int, int, int]]:
        """For each level ``0..level``, the cells ``(x, y, width, height)`` of the *block* (the
        window and a margin of one cell, ``(x0 - 1, y0 - 1)`` its cell ``(0, 0)``, y north)
        whose candidates a window computes: the cells that need the level, with a margin of one
        cell, as a rectangle (a level needs the levels above it wherever it needs itself)."""
        w = self.window
        need = self.level_map()[::-1]  # row j: y0 + j
        out = [(0, 0, w.width + 2, w.height + 2)]
        for k in range(1, self.level + 1):
            js, iis = np.nonzero(need >= k)
            if len(js) == 0:
                break
            out.append((int(iis.min()), int(js.min()), int(iis.max() - iis.min()) + 3, int(js.max() - js.min()) + 3))
        return out

    @property
    def distance(self) -> float:
        """The distance of the window's deepest level."""
        return self.tileset.problem.distance_at(self.level)

    def describe(self) -> str:
        at = self.label if self.label == f"level {self.level}" else f"{self.label} (level {self.level})"
        return (f"recursive Wang window {self.window.describe()} at {at}, "
                f"{self.tileset.problem.describe()}")


@dataclass(frozen=True, eq=False)
class RecursiveWindow:
    """The points of a window, coarsest level first and by rank within a level.

    ``local[i] + (x0, y0)`` is point ``i`` of the plane; ``level[i]`` its level, ``rank[i]``
    its rank in ``[0, 1)``. Level ``l``'s points (those of level ``<= l``) are at least
    ``distance / subdivision**l`` apart.
    """

    window: Window
    local: np.ndarray = field(repr=False)
    level: np.ndarray = field(repr=False)
    rank: np.ndarray = field(repr=False)
    distance: float = 0.0
    subdivision: int = 4

    @property
    def n_points(self) -> int:
        return len(self.local)

    def distance_at(self, level: int) -> float:
        return self.distance / self.subdivision**level

    def absolute(self) -> np.ndarray:
        """``(n, 2)`` float64 plane coordinates (exact only while the origin is below 2**31 or so)."""
        return self.local + np.array([self.window.x0, self.window.y0], dtype=np.float64)


def check_level(value, name: str = "level") -> int:
    """An integer level within ``0..MAX_LEVEL`` (one-line error otherwise)."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not 0 <= int(value) <= MAX_LEVEL:
        raise InvalidProblem(f"{name} must be an integer within 0..{MAX_LEVEL}, got {value!r}")
    return int(value)

