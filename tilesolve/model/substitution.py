"""Substitution tilings: Penrose P3 (rhombs) and P2 (kites and darts), and rep-tiles (Kaplan,
class notes Part II §8.1, §8.3).

A :class:`SubstitutionProblem` asks for one patch: a Penrose patch after ``steps`` deflations
of a sun, or the Penrose tiles whose centre lies in a window of the plane (``region``, in the
plane's units: the rhomb edge is 1); or a rep-tile's patch ``2^steps P`` after ``steps``
substitutions. The answer is a :class:`Patch`: polygons with exact integer coordinates.

Examples
--------
>>> p = SubstitutionProblem("p3", region=(-10, -5, 20, 10))
>>> p.describe()
'Penrose rhomb (P3) tiling, window x -10..10, y -5..5 (about 246 tiles)'
>>> SubstitutionProblem("chair", steps=3).estimate
64
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tilesolve.errors import InvalidProblem

__all__ = ["PENROSE", "REPTILES", "KINDS", "GRIDS", "MAX_TILES", "MAX_COORDINATE", "Patch", "SubstitutionProblem",
           "TILE_NAMES"]

#: Penrose kinds: rhombs (thin 0, thick 1) and kites (0) and darts (1).
PENROSE = ("p3", "p2")
#: The built-in rep-tiles (scale 2).
REPTILES = ("chair", "sphinx", "l-tetromino", "p-pentomino")
KINDS = PENROSE + REPTILES
#: Each kind's coordinates: ``zeta5`` (four integers on ``1, zeta, zeta^2, zeta^3``,
#: ``zeta = exp(2 pi i / 5)``), ``square`` (x, y) or ``triangle`` (a, b of ``a + b exp(i pi / 3)``).
GRIDS = {"p3": "zeta5", "p2": "zeta5", "chair": "square", "l-tetromino": "square", "p-pentomino": "square",
         "sphinx": "triangle"}
#: Tile type names by kind.
TILE_NAMES = {"p3": ("thin", "thick"), "p2": ("kite", "dart")}
#: Most tiles in one patch: generating, verifying and writing take about 1 KB a tile at peak.
MAX_TILES = 4_000_000
#: Window coordinates stay within this bound: the pentagrid decides its floors in float64 with a
#: margin of 1e-14 of the coordinates (:data:`tilesolve.constructive.penrose.TOLERANCE`).
MAX_COORDINATE = 10**6

_PHI = (1 + 5**0.5) / 2
_PHI2 = _PHI**2
_S36, _S72 = np.sin(np.radians(36)), np.sin(np.radians(72))
#: Mean area of a Penrose rhomb (thick:thin = phi:1, areas sin 72, sin 36) and of a kite or dart
#: (kite:dart = phi:1, areas phi^2 sin 36, sin 72).
_MEAN_AREA = {"p3": (_PHI * _S72 + _S36) / (_PHI + 1), "p2": (_PHI * _PHI2 * _S36 + _S72) / (_PHI + 1)}


@dataclass(frozen=True, eq=False)
class Patch:
    """A finite patch of polygons.

    Attributes
    ----------
    kind : str
        One of :data:`KINDS`.
    types : numpy.ndarray
        ``(n,)`` int8: the tile's type (:data:`TILE_NAMES`; 0 for rep-tiles).
    vertices : numpy.ndarray
        ``(n, m, d)`` int64: each tile's ``m`` vertices counter-clockwise in the coordinates
        of :data:`GRIDS` (``d`` = 4 or 2). Penrose tiles start at their marked vertex
        (:mod:`tilesolve.constructive.penrose`).
    """

    kind: str
    types: np.ndarray
    vertices: np.ndarray

    @property
    def grid(self) -> str:
        """The coordinates' lattice (:data:`GRIDS`)."""
        return GRIDS[self.kind]

    @property
    def n_tiles(self) -> int:
        """Number of tiles."""
        return len(self.types)

    @property
    def size(self) -> int:
        """Number of tiles (what a picture's size depends on, as a grid's ``size``)."""
        return len(self.types)

    def xy(self) -> np.ndarray:
        """Cartesian coordinates ``(n, m, 2)`` of the vertices (floats, for drawing)."""
        v = np.asarray(self.vertices, dtype=np.float64)
        if self.grid == "zeta5":
            turn = 2 * np.pi * np.arange(4) / 5
            return np.stack([v @ np.cos(turn), v @ np.sin(turn)], axis=-1)
        if self.grid == "triangle":
            return np.stack([v[..., 0] + v[..., 1] / 2, v[..., 1] * 3**0.5 / 2], axis=-1)
        return v

    def centres(self) -> np.ndarray:
        """Cartesian coordinates ``(n, 2)`` of the tiles' vertex centroids: the vertices summed
        exactly, converted once per tile (:meth:`xy` is linear)."""
        v = np.asarray(self.vertices)
        return Patch(self.kind, self.types, v.sum(axis=1, keepdims=True)).xy()[:, 0] / v.shape[1]

    def counts(self) -> dict[str, int]:
        """Tiles by type name."""
        names = TILE_NAMES.get(self.kind, (self.kind,))
        return {name: int(np.count_nonzero(self.types == i)) for i, name in enumerate(names)}


def _int(v, name: str) -> int:
    if isinstance(v, bool) or not isinstance(v, (int, np.integer)):
        raise InvalidProblem(f"{name} must be an integer, got {v!r}")
    return int(v)


@dataclass(frozen=True)
class SubstitutionProblem:
    """One patch of a substitution tiling.

    Parameters
    ----------
    kind : str
        One of :data:`KINDS`.
    steps : int, optional
        Substitution steps (deflations of a sun for Penrose, of ``2^steps P`` for rep-tiles).
    region : (x0, y0, width, height), optional
        Penrose only: the window of the plane (units: the rhomb edge) whose tiles are wanted.
        Exactly one of ``steps`` and ``region``.

    Raises
    ------
    InvalidProblem
        Unknown kind, both or neither of steps and region, negative steps, an empty or
        far-away window, a rep-tile with a region, or a patch of more than :data:`MAX_TILES`
        tiles (the message gives the estimate).
    """

    kind: str
    steps: int | None = None
    region: tuple[int, int, int, int] | None = None

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise InvalidProblem(f"unknown tiling {self.kind!r}; choose one of {', '.join(KINDS)}")
        if (self.steps is None) == (self.region is None):
            raise InvalidProblem("give either steps or a region")
        if self.steps is not None:
            s = _int(self.steps, "steps")
            if s < 0:
                raise InvalidProblem(f"steps must be >= 0, got {s}")
            object.__setattr__(self, "steps", s)
        if self.region is not None:
            if self.kind not in PENROSE:
                raise InvalidProblem(f"{self.kind} patches are grown by steps, not cut from a region; use steps")
            if len(self.region) != 4:
                raise InvalidProblem("a region is x0, y0, width, height")
            x0, y0, w, h = (_int(v, name) for v, name in zip(self.region, ("x0", "y0", "width", "height")))
            if w < 1 or h < 1:
                raise InvalidProblem(f"a region needs a positive width and height, got {w}x{h}")
            if max(abs(x0), abs(y0), abs(x0 + w), abs(y0 + h)) > MAX_COORDINATE:
                raise InvalidProblem(f"the region leaves the plane's coordinates here (|x|, |y| <= {MAX_COORDINATE:,})")
            object.__setattr__(self, "region", (x0, y0, w, h))
        n = self.estimate
        if n > MAX_TILES:
            raise InvalidProblem(f"this patch would have about {n:,.0f} tiles; at most {MAX_TILES:,} here "
                                 f"(about 1 KB of memory a tile)")

    @property
    def estimate(self) -> int:
        """About how many tiles the patch has."""
        if self.region is not None:
            return int(self.region[2] * self.region[3] / _MEAN_AREA[self.kind])
        if self.kind in PENROSE:
            return int(min((3.6 if self.kind == "p3" else 2.1) * _PHI2**self.steps, 1e30))
        return 4 ** min(self.steps, 60)

    def describe(self) -> str:
        """One line."""
        name = {"p3": "Penrose rhomb (P3) tiling", "p2": "Penrose kite and dart (P2) tiling"}.get(
            self.kind, f"{self.kind} rep-tile tiling")
        if self.region is not None:
            x0, y0, w, h = self.region
            where = f"window x {x0}..{x0 + w}, y {y0}..{y0 + h}"
        else:
            where = f"{self.steps} substitution step{'s' if self.steps != 1 else ''}"
        return f"{name}, {where} (about {self.estimate:,} tiles)"
