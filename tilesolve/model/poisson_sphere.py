"""Corner-based Poisson sphere tiles (Lagae, class notes §4.4, §2.10): problems and tile sets.

A *Poisson sphere distribution* is a 3-D point set in which no two points are closer than a
minimum distance ``2 r`` (§4.4.1.1). Its quality is the relative radius ``rho = r / r_max``
with ``r_max = (1 / (4 sqrt(2) N))^(1/3)`` for ``N`` points a unit volume (eq. 4.4-4.6: the
densest sphere packing fills ``pi / (3 sqrt 2)`` of space).

Corner cubes (§2.10, §4.4.2)
----------------------------
Unit cubes with coloured corners, placed with their corners on the integer lattice; the
complete set over ``C`` colours has a cube for each of the ``C^8`` colourings of its corners.
The notes say the enumeration of corner tiles (§2.8) "easily generalizes"; tilesolve's reading:
cube ``(x, y, z)`` has the index whose base-``C`` digits, most significant first, are the
colours of its corners ``(x + i, y + j, z + k)`` in the order of the binary number ``ijk``
(``000, 001, ..., 111``), i.e. ``sum c(i, j, k) C^(7 - (4i + 2j + k))`` (:func:`cube_index`).

Modified regions (unit cells, ``d = 2 r``; §4.4.3, figures 4.16-4.17)
--------------------------------------------------------------------
* a **corner tile** around every lattice point: the cube ``[-a, a)^3``; one per colour, ``C``;
* an **edge tile** along every lattice edge of axis ``k`` from ``p`` to ``p + e_k``: the bar
  ``a <= t_k < 1 - a``, ``-b <= t_j < b`` for the two other axes (``t = point - p``); one per
  pair of end colours (``lo * C + hi``) and axis, ``3 C^2``;
* a **face tile** on every lattice face of normal ``k`` (the square ``p + [0, 1]^2`` in the two
  other axes ``u < v``): ``-d <= t_k < d``, ``b <= t_u, t_v < 1 - b``, less the squares of
  side ``a`` at its four corners (those lie in the corner tiles); one per colouring of its four
  corners (digits ``(u, v) = 00, 01, 10, 11``, most significant first) and normal, ``3 C^4``;
* an **interior tile** in every cell: ``[d, 1 - d)^3`` less the corner cubes and edge bars;
  one per corner cube, ``C^8``.

The corners are enlarged so that edges are ``d`` apart (edges meeting at a corner are
``sqrt(2) (a - b) = d`` apart), the edges so that faces are ``d`` apart (faces meeting at an
edge are ``sqrt(2) (b - d) >= d`` apart): ``b = d (1 + 1/sqrt 2)``, ``a = b + d / sqrt 2 =
d (1 + sqrt 2)`` (with a relative slack of ``SLACK``). Corner tiles are ``1 - 2a >= d`` apart,
which needs ``d <= 1 / (3 + 2 sqrt 2)``: :class:`PoissonSphereTilesProblem` refuses fewer points
a tile than that allows (97 at ``rho = 0.7``, 119 at 0.75). Each tile is then built against the tiles it
can touch (corners, then edges, faces, interiors), and every colouring of the lattice gives a
Poisson sphere distribution. ``C + 3 C^2 + 3 C^4 + C^8`` tiles in all (318 for C = 2).

Examples
--------
>>> p = PoissonSphereTilesProblem(2, 128, 0.7)
>>> p.n_tiles, round(p.r_max, 4), round(p.distance, 4), round(p.edge_half, 4), round(p.corner_half, 4)
(318, 0.1114, 0.1559, 0.2662, 0.3764)
>>> cube_index([0, 0, 0, 0, 0, 0, 0, 1], 2), cube_index([1, 0, 0, 0, 0, 0, 0, 0], 2)
(1, 128)
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from typing import Any, Mapping

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.model.poisson import SLACK, check_tiles
from tilesolve.model.window import MAX_COORDINATE

__all__ = [
    "PoissonSphereProblem",
    "PoissonSphereTilesProblem",
    "PoissonSphereWindowProblem",
    "PoissonSphereTileSet",
    "PoissonSphereWindow",
    "Box",
    "parse_box",
    "r_max3",
    "cube_index",
    "KINDS",
    "MAX_COLORS",
    "MAX_POINTS",
    "MAX_WINDOW_POINTS",
]

#: Most colours: ``C^8`` interior tiles (65,536 at C = 4, the notes' largest set, §4.4.2).
MAX_COLORS = 4
#: Most points a tile.
MAX_POINTS = 4096
#: Most points one window holds (24 bytes each, about twice that while it is built).
MAX_WINDOW_POINTS = 1 << 25
#: The kinds of tiles in the order they are built: corners, edges of axis x, y, z, faces of
#: normal x, y, z, interiors (§4.4.3).
KINDS = ("corner", "xedge", "yedge", "zedge", "xface", "yface", "zface", "interior")

_BOX = re.compile(r"\s*([+-]?\d+)\s*,\s*([+-]?\d+)\s*,\s*([+-]?\d+)\s*,\s*(\d+)\s*[xX×]\s*(\d+)\s*[xX×]\s*(\d+)\s*")


def r_max3(points: float) -> float:
    """Largest sphere radius of ``points`` points in the unit torus (eq. 4.5).

    >>> round(r_max3(1), 6)
    0.561231
    """
    return (1.0 / (4.0 * math.sqrt(2.0) * points)) ** (1.0 / 3.0)


def cube_index(colors, c: int) -> int:
    """The index of the corner cube whose corners ``ijk = 000 .. 111`` have ``colors`` (module docstring)."""
    out = 0
    for v in colors:
        out = out * c + int(v)
    return out


def _halves(distance: float) -> tuple[float, float]:
    """``(a, b)``: the corner cubes' and edge bars' half sides for ``distance`` (module docstring)."""
    dd = distance * (1 + SLACK)
    b = dd * (1 + 1 / math.sqrt(2))
    return b + dd / math.sqrt(2), b


def _fits(points: int, rho: float) -> bool:
    d = 2 * rho * r_max3(points)
    return 1.0 - 2.0 * _halves(d)[0] >= d * (1 + SLACK)


class PoissonSphereProblem:
    """Either question of the ``poisson-sphere`` family: build a tile set, or a window of points."""


@dataclass(frozen=True)
class PoissonSphereTilesProblem(PoissonSphereProblem):
    """Build a set of corner-based Poisson sphere tiles (§4.4.3).

    Parameters
    ----------
    colors : int
        ``C``, corner colours (1..4).
    points : int
        ``N``, points a unit cell on average.
    rho : float
        Relative radius (eq. 4.6) every tiling keeps: no two points closer than
        ``2 rho r_max3(N)``; within 0.05..0.85.

    Raises
    ------
    InvalidProblem
        Values out of range, or a distance too large for the regions to fit in a cell (the
        message gives the fewest points that fit).
    """

    colors: int
    points: int
    rho: float

    def __post_init__(self) -> None:
        values = check_tiles(self.colors, self.points, self.rho, MAX_COLORS, _fits, "§4.4.3")
        for name, v in zip(("colors", "points", "rho"), values):
            object.__setattr__(self, name, v)

    @property
    def n_tiles(self) -> int:
        """``C + 3 C^2 + 3 C^4 + C^8``."""
        c = self.colors
        return c + 3 * c * c + 3 * c**4 + c**8

    def counts(self) -> dict[str, int]:
        """Tiles of each kind of :data:`KINDS`."""
        c = self.colors
        return {k: (c if k == "corner" else c * c if k.endswith("edge") else c**4 if k.endswith("face") else c**8)
                for k in KINDS}

    @property
    def r_max(self) -> float:
        return r_max3(self.points)

    @property
    def distance(self) -> float:
        """``d = 2 rho r_max``: no two points of a tiling come closer."""
        return 2.0 * self.rho * self.r_max

    @property
    def corner_half(self) -> float:
        """``a``: corner tiles are ``[-a, a)^3`` around their lattice point."""
        return _halves(self.distance)[0]

    @property
    def edge_half(self) -> float:
        """``b``: edge tiles reach ``b`` from their lattice edge in the two other axes."""
        return _halves(self.distance)[1]

    def describe(self) -> str:
        return (f"corner-based Poisson sphere tiles: C = {self.colors} colours, N = {self.points} points a cell, "
                f"rho = {self.rho:g} ({self.n_tiles:,} tiles)")


@dataclass(frozen=True, eq=False)
class PoissonSphereTileSet:
    """The points of a corner-based Poisson sphere tile set, by kind of tile.

    Attributes
    ----------
    problem : PoissonSphereTilesProblem
    tiles : dict
        For each kind of :data:`KINDS`, a list of ``(k, 3)`` float64 arrays of points in the
        tile's own frame (its lattice point ``p`` at the origin): ``corner`` by colour, edges by
        ``lo * C + hi``, faces and interiors by their corners' digits (module docstring).
    seed : int or None
    stats : dict
        ``short``: points the interior tiles lack to reach ``N``, summed.
    """

    problem: PoissonSphereTilesProblem
    tiles: dict = field(repr=False)
    seed: int | None = None
    stats: dict = field(default_factory=dict)

    def __post_init__(self) -> None:
        if not isinstance(self.tiles, dict) or set(self.tiles) != set(KINDS):
            raise InvalidProblem(f"a Poisson sphere tile set has the tiles {', '.join(KINDS)}")
        for kind, n in self.problem.counts().items():
            arrs = self.tiles[kind]
            if len(arrs) != n:
                raise InvalidProblem(f"a set over {self.problem.colors} colours has {n} {kind} tiles, got {len(arrs)}")
            for a in arrs:
                if not (isinstance(a, np.ndarray) and a.ndim == 2 and a.shape[1] == 3 and a.dtype == np.float64):
                    raise InvalidProblem(f"{kind} tile points must be (k, 3) float64 arrays")

    @property
    def n_points(self) -> int:
        return sum(len(a) for arrs in self.tiles.values() for a in arrs)

    def describe(self) -> str:
        return f"{self.problem.describe()}, {self.n_points:,} points"


@dataclass(frozen=True)
class Box:
    """``width x height x depth`` cells of space whose least cell is ``(x0, y0, z0)`` (z up).

    >>> b = parse_box("-3,2,1000000,4x5x6")
    >>> b, b.n_cells
    (Box(x0=-3, y0=2, z0=1000000, width=4, height=5, depth=6), 120)
    >>> Box.from_dict(b.to_dict()) == b
    True
    """

    x0: int
    y0: int
    z0: int
    width: int
    height: int
    depth: int

    def __post_init__(self) -> None:
        for name in ("x0", "y0", "z0", "width", "height", "depth"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, np.integer)):
                raise InvalidProblem(f"box {name} must be an integer, got {v!r}")
            object.__setattr__(self, name, int(v))
        if min(self.size) < 1:
            raise InvalidProblem(f"box size must be positive, got {'x'.join(map(str, self.size))} (WxHxD)")
        for lo, n in zip(self.origin, self.size):
            if abs(lo) > MAX_COORDINATE or abs(lo + n) > MAX_COORDINATE:
                raise InvalidProblem(f"box {self.describe()} leaves the lattice tilesolve addresses "
                                     "(coordinates within +-2**62)")

    @property
    def origin(self) -> tuple[int, int, int]:
        return self.x0, self.y0, self.z0

    @property
    def size(self) -> tuple[int, int, int]:
        return self.width, self.height, self.depth

    @property
    def n_cells(self) -> int:
        return self.width * self.height * self.depth

    def describe(self) -> str:
        return ", ".join(f"{a} {lo}..{lo + n - 1}" for a, lo, n in zip("xyz", self.origin, self.size))

    def to_dict(self) -> dict[str, int]:
        return {"x0": self.x0, "y0": self.y0, "z0": self.z0, "width": self.width, "height": self.height,
                "depth": self.depth}

    @classmethod
    def from_dict(cls, d: Any) -> "Box":
        keys = ("x0", "y0", "z0", "width", "height", "depth")
        if not isinstance(d, Mapping) or set(d) != set(keys):
            raise InvalidProblem(f"a box is an object with exactly the fields {', '.join(keys)}")
        return cls(*(d[k] for k in keys))


def parse_box(text: str) -> Box:
    """``--region X0,Y0,Z0,WxHxD``: the box whose least cell is ``(X0, Y0, Z0)``."""
    m = _BOX.fullmatch(str(text))
    if m is None:
        raise InvalidProblem(f"cannot read region {text!r}: expected X0,Y0,Z0,WxHxD, e.g. -4,0,10,8x8x8")
    return Box(*(int(g) for g in m.groups()))


@dataclass(frozen=True, eq=False)
class PoissonSphereWindowProblem(PoissonSphereProblem):
    """A box of the Poisson sphere distribution of the direct 3-D corner tiling with ``tileset``.

    Parameters
    ----------
    tileset : PoissonSphereTileSet
    box : Box or (x0, y0, z0, width, height, depth)
    hash : {"long", "table"}
        The lattice hash that colours the corners (§3.4: the long-period hash by default).
    """

    tileset: PoissonSphereTileSet
    box: Box
    hash: str = "long"

    def __post_init__(self) -> None:
        if not isinstance(self.tileset, PoissonSphereTileSet):
            raise InvalidProblem(f"expected a PoissonSphereTileSet, got {type(self.tileset).__name__}")
        box = self.box
        if not isinstance(box, Box):
            try:
                box = Box(*box)
            except TypeError:
                raise InvalidProblem(f"a box is (x0, y0, z0, width, height, depth), got {self.box!r}") from None
        object.__setattr__(self, "box", box)
        if self.hash not in ("long", "table"):
            raise InvalidProblem(f"unknown hash {self.hash!r}; choose long or table")
        n = box.n_cells * self.tileset.problem.points
        if n > MAX_WINDOW_POINTS:
            raise InvalidProblem(f"a {'x'.join(map(str, box.size))} box holds about {n:,} points; tilesolve "
                                 f"builds at most {MAX_WINDOW_POINTS:,} at once: ask for smaller boxes")

    @property
    def distance(self) -> float:
        return self.tileset.problem.distance

    def describe(self) -> str:
        return f"Poisson sphere box {self.box.describe()} (direct corner tiling), {self.tileset.problem.describe()}"


@dataclass(frozen=True, eq=False)
class PoissonSphereWindow:
    """The points of a box: ``local[i] + box.origin`` is point ``i`` of space (coordinates kept
    relative to the box's least corner, so boxes far from the origin keep full precision)."""

    box: Box
    local: np.ndarray = field(repr=False)
    distance: float = 0.0

    @property
    def n_points(self) -> int:
        return len(self.local)

    def absolute(self) -> np.ndarray:
        """``(n, 3)`` float64 coordinates of space (exact only near the origin)."""
        return self.local + np.array(self.box.origin, dtype=np.float64)
