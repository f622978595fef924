"""Importance sampling of an image: the density and the question (class notes Part IV,
Ostromoukhov's slides "Problem statement: find a discrete sample distribution locally
proportional to I(x, y)"; Part V, stippling).

A :class:`DensityMap` is a grid of non-negative pixel values (row 0 the top row, as an image is
stored) laid over the domain ``[0, width] x [0, height]`` of the plane, y up, whose longer side
is 1: a pixel is a square of side ``1 / max(rows, cols)``. The density is constant on each
pixel. An :class:`ImportanceProblem` asks for about ``points`` samples distributed with that
density, by one of :data:`METHODS`.

Examples
--------
>>> d = builtin_density("gradient", 8)
>>> d.values.shape, (d.width, d.height)
((8, 8), (1.0, 1.0))
>>> p = ImportanceProblem(d, 1000, "polyomino")
>>> p.describe()
'1,000 points, polyomino sampling (chair), corrected, gradient 8x8 pixels'
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tilesolve.errors import InvalidProblem

__all__ = ["METHODS", "TILES", "CORRECTED_TILES", "TEST_IMAGES", "MAX_POINTS", "MAX_PIXELS", "DensityMap",
           "builtin_density", "ImportanceProblem"]

#: The samplers: Penrose (Ostromoukhov, Donohue, Jodoin 2004), polyomino (Ostromoukhov 2007) and
#: plain rejection sampling, the anchor.
METHODS = ("penrose", "polyomino", "rejection")
#: Rep-tiles of the polyomino sampler (built-in rep-4 polyominoes of :mod:`tilesolve.constructive.reptile`).
TILES = ("x-pentomino", "chair", "l-tetromino", "p-pentomino")
#: The rep-tiles with a learnt correction table (``tilesolve/data/importance/``; Ostromoukhov
#: 2007's offsets by structural index and importance, rebuilt by
#: ``scripts/build_importance_corrections.py``).
CORRECTED_TILES = ("x-pentomino", "chair")
#: Built-in test images: a radial ramp (dark centre), a left-to-right gradient, a flat grey.
TEST_IMAGES = ("radial", "gradient", "flat")
#: Most samples one problem asks for (about 100 bytes of work a sample at peak).
MAX_POINTS = 2_000_000
#: Most pixels of a density image.
MAX_PIXELS = 1 << 24


@dataclass(frozen=True, eq=False)
class DensityMap:
    """Non-negative pixel values over the domain ``[0, width] x [0, height]`` (longer side 1).

    Attributes
    ----------
    values : numpy.ndarray
        ``(rows, cols)`` float64, row 0 the top row (``y = height``).
    name : str
        Where it came from (a file name or a test image's name), for captions.
    """

    values: np.ndarray
    name: str = "image"

    def __post_init__(self) -> None:
        v = np.asarray(self.values, dtype=np.float64)
        if v.ndim != 2 or v.size == 0:
            raise InvalidProblem("a density is a non-empty grid of pixels")
        if v.size > MAX_PIXELS:
            raise InvalidProblem(f"the image has {v.size:,} pixels; at most {MAX_PIXELS:,}")
        if not np.isfinite(v).all() or (v < 0).any():
            raise InvalidProblem("a density's values are finite and non-negative")
        if not v.sum() > 0:
            raise InvalidProblem(f"{self.name}: the density is zero everywhere (a white image): nothing to sample")
        object.__setattr__(self, "values", v)

    @property
    def rows(self) -> int:
        return self.values.shape[0]

    @property
    def cols(self) -> int:
        return self.values.shape[1]

    @property
    def pixel(self) -> float:
        """A pixel's side in domain units."""
        return 1.0 / max(self.rows, self.cols)

    @property
    def width(self) -> float:
        return self.cols * self.pixel

    @property
    def height(self) -> float:
        return self.rows * self.pixel

    def caption(self) -> str:
        return f"{self.name} {self.cols}x{self.rows} pixels"


def builtin_density(name: str, size: int = 256) -> DensityMap:
    """A test image as a density (darkness): ``radial`` (1 at the centre falling linearly to 0.05
    at the corners), ``gradient`` (0.05 at the left edge rising linearly to 1 at the right),
    ``flat`` (1 everywhere: the uniform case whose spectra the papers show)."""
    if name not in TEST_IMAGES:
        raise InvalidProblem(f"unknown test image {name!r}; choose one of {', '.join(TEST_IMAGES)}")
    c = (np.arange(size) + 0.5) / size
    x, y = np.meshgrid(c, c[::-1])
    if name == "radial":
        r = np.hypot(x - 0.5, y - 0.5) / np.sqrt(0.5)
        v = 1.0 - 0.95 * r
    elif name == "gradient":
        v = 0.05 + 0.95 * x
    else:
        v = np.ones_like(x)
    return DensityMap(v, name)


@dataclass(frozen=True, eq=False)
class ImportanceProblem:
    """About ``points`` samples of ``density`` by ``method``.

    Parameters
    ----------
    density : DensityMap
    points : int
        The expected number of samples, 1..:data:`MAX_POINTS`.
    method : str
        One of :data:`METHODS`.
    tile : str
        The polyomino sampler's rep-tile (:data:`TILES`).
    lloyd : int
        Density-weighted Lloyd steps applied to the samples afterwards (0..50).
    jitter : bool
        Penrose and polyomino: each sample at a uniform random point of its tile instead of its
        centroid (stratified sampling over the tiles).
    correct : bool
        Polyomino, unjittered, a tile of :data:`CORRECTED_TILES`: the 2007 paper's
        pseudo-non-deterministic sampling with its learnt correction table (children ranked in
        a seeded random order; each sample displaced by the offset of its structural index and
        importance). Ignored elsewhere (:attr:`corrected` says whether it applies).
    """

    density: DensityMap
    points: int
    method: str = "polyomino"
    tile: str = "chair"
    lloyd: int = 0
    jitter: bool = False
    correct: bool = True

    def __post_init__(self) -> None:
        if self.method not in METHODS:
            raise InvalidProblem(f"unknown sampling method {self.method!r}; choose one of {', '.join(METHODS)}")
        if self.tile not in TILES:
            raise InvalidProblem(f"unknown polyomino {self.tile!r}; choose one of {', '.join(TILES)}")
        for name, value, lo, hi in (("points", self.points, 1, MAX_POINTS), ("lloyd", self.lloyd, 0, 50)):
            if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
                raise InvalidProblem(f"{name} must be an integer, got {value!r}")
            if not lo <= value <= hi:
                raise InvalidProblem(f"{name} must be in {lo:,}..{hi:,}, got {value:,}")
        if not isinstance(self.correct, (bool, np.bool_)):
            raise InvalidProblem(f"correct must be true or false, got {self.correct!r}")

    @property
    def corrected(self) -> bool:
        """Whether the samples take the correction table (:attr:`correct` where it applies)."""
        return bool(self.correct) and self.method == "polyomino" and not self.jitter and self.tile in CORRECTED_TILES

    def describe(self) -> str:
        what = {"penrose": "Penrose sampling", "polyomino": f"polyomino sampling ({self.tile})",
                "rejection": "rejection sampling"}[self.method]
        more = (", jittered" if self.jitter and self.method != "rejection" else "") + \
            (", corrected" if self.corrected else "") + \
            (f", {self.lloyd} Lloyd steps" if self.lloyd else "")
        return f"{self.points:,} points, {what}{more}, {self.density.caption()}"
