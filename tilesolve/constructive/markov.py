"""Jeandel-Rao and Labbé's U19 tilings as codings of toral Z²-rotations (Markov partitions).

S. Labbé, *Markov partitions for toral Z²-rotations featuring Jeandel-Rao Wang shift and model
sets*, Annales Henri Lebesgue 4 (2021) 283-324, arXiv:1903.06137, gives two partitions of a
2-torus into polygons labelled by Wang tiles:

``jeandel-rao``
    ``P0``: 24 polygons of ``R²/Γ0``, ``Γ0 = <(φ, 0), (1, φ + 3)>``, labelled by the 11
    Jeandel-Rao tiles, with the rotation ``R0^n(x) = x + n``;
``labbe-u19``
    ``PU``: 19 polygons of ``R²/Z²`` labelled by the 19 tiles of Labbé's self-similar set U,
    with the rotation ``RU^n(x) = x + φ⁻² n`` (``φ⁻² = 2 - φ``; of ``±φ⁻¹, ±φ⁻²`` on each
    axis, the one whose codings are valid U tilings, as the tests check).

The tile at cell ``n = (X, Y)`` is the label of the polygon that contains ``R^n(x0)``: the
coding of an orbit is a valid tiling (the paper's theorems; every window here is checked by
the tests). The polygons are data, transcribed in ``tilesolve/data/markov/NAME.json`` from
S. Labbé's ``slabbe/arXiv_1903_06137.py`` (see the file's ``about``), with every vertex in
``Q(φ)``, ``φ = (1 + √5)/2``.

Where the orbit starts, and the points on an edge
-------------------------------------------------
A coding is a tiling when no point of the orbit lies on a polygon edge. ``x0`` is chosen
*exactly* in ``Q(φ)²`` (from the seed: :func:`start_point`) and moved by an infinitesimal
``ε v`` along the fixed direction ``v = (1, 113/355)``, which is parallel to no edge: a point on
an edge takes the label of the polygon that ``v`` points into (at a vertex, the one polygon
whose corner contains ``v``). For any finite window this is the coding of the real point
``x0 + ε v`` for every small enough ``ε > 0``, whose window avoids every edge; so every
window is valid, whatever the seed, even for a start on a vertex
(:func:`orbit_window` takes any start).

Arithmetic
----------
Each cell is first decided in float64 from an exactly reduced base point (per block of at
most :data:`BLOCK` x :data:`BLOCK` cells, so the float error does not grow with the origin or
the window). A cell whose float point lies within the error bound :func:`float_tolerance` of
a polygon edge is decided again in exact arithmetic in ``Q(φ)`` (integers: the sign of
``a + b√5`` exactly). No origin is refused: every origin of the window lattice
(``|x|, |y| <= 2**62``, :class:`Window` refuses the others) is reduced modulo the lattice
exactly, so the float error bound depends on the block size only.

>>> w = markov_window("jeandel-rao", Window(-3, 5, 6, 2), seed=1)
>>> w.shape, w.dtype.name
((2, 6), 'uint8')
"""

from __future__ import annotations

import functools
import json
import math
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from fractions import Fraction
from importlib import resources
from typing import Any

import numpy as np

from tilesolve._random import rng_from_seed
from tilesolve.constructive._jit import cores as _cores
from tilesolve.errors import InternalError, InvalidProblem
from tilesolve.model.window import Window

__all__ = ["NAMES", "QPhi", "markov_window", "orbit_window", "start_point", "partition",
           "float_tolerance", "cell_point", "BLOCK", "PERTURBATION"]

#: The partitions shipped, by the name of their built-in tile set.
NAMES = ("jeandel-rao", "labbe-u19")

#: Cells per side of a block with its own exactly reduced base point.
BLOCK = 4096


@functools.total_ordering
class QPhi:
    """The number ``a + b φ`` of ``Q(φ)``, ``φ = (1 + √5)/2``, with rational ``a`` and ``b``.

    >>> phi = QPhi(0, 1)
    >>> phi * phi == phi + 1, (phi - 2).sign(), (phi * 7).floor(), float(1 / phi)
    (True, -1, 11, 0.6180339887498949)
    """

    __slots__ = ("a", "b")

    def __init__(self, a: Any = 0, b: Any = 0):
        self.a = Fraction(a)
        self.b = Fraction(b)

    @classmethod
    def of(cls, v: Any) -> "QPhi":
        """``v`` as a :class:`QPhi`: a QPhi as it is, a rational ``r`` as ``r + 0φ``, a pair
        ``[a, b]`` (ints or ``"p/q"`` strings, the data files' form) as ``a + bφ``."""
        if isinstance(v, QPhi):
            return v
        if isinstance(v, (list, tuple)):
            a, b = v
            return cls(Fraction(a), Fraction(b))
        return cls(Fraction(v))

    def __add__(self, o: Any) -> "QPhi":
        o = QPhi.of(o)
        return QPhi(self.a + o.a, self.b + o.b)

    __radd__ = __add__

    def __neg__(self) -> "QPhi":
        return QPhi(-self.a, -self.b)

    def __sub__(self, o: Any) -> "QPhi":
        return self + (-QPhi.of(o))

    def __rsub__(self, o: Any) -> "QPhi":
        return QPhi.of(o) - self

    def __mul__(self, o: Any) -> "QPhi":
        o = QPhi.of(o)
        bd = self.b * o.b  # φ² = φ + 1
        return QPhi(self.a * o.a + bd, self.a * o.b + self.b * o.a + bd)

    __rmul__ = __mul__

    def inverse(self) -> "QPhi":
        """``1 / self`` (the conjugate over the norm ``a² + ab - b²``, never 0 for ``self != 0``)."""
        n = self.a * self.a + self.a * self.b - self.b * self.b
        if n == 0:
            raise ZeroDivisionError("QPhi division by zero")
        return QPhi((self.a + self.b) / n, -self.b / n)

    def __truediv__(self, o: Any) -> "QPhi":
        return self * QPhi.of(o).inverse()

    def __rtruediv__(self, o: Any) -> "QPhi":
        return QPhi.of(o) * self.inverse()

    def __eq__(self, o: object) -> bool:
        if not isinstance(o, (QPhi, int, Fraction)):
            return NotImplemented
        o = QPhi.of(o)
        return self.a == o.a and self.b == o.b

    def __hash__(self) -> int:
        return hash((self.a, self.b))

    def __lt__(self, o: Any) -> bool:
        return (self - o).sign() < 0

    def __repr__(self) -> str:
        return f"QPhi({self.a}, {self.b})"

    def _root5_form(self) -> tuple[int, int, int]:
        """Integers ``(S, T, D)``, ``D > 0``, with ``self = (S + T√5) / (2D)``."""
        s, t = 2 * self.a + self.b, self.b
        d = s.denominator * t.denominator // math.gcd(s.denominator, t.denominator)
        return int(s * d), int(t * d), d

    def sign(self) -> int:
        """-1, 0 or 1: the sign of ``a + bφ``, exactly."""
        s, t, _ = self._root5_form()
        if t == 0 or (s >= 0 and t > 0) or (s <= 0 and t < 0):
            return (s > 0) - (s < 0) if t == 0 else (1 if t > 0 else -1)
        d = s * s - 5 * t * t  # opposite signs: |s| against |t|√5 (never equal: √5 is irrational)
        return (1 if d > 0 else -1) if s > 0 else (1 if d < 0 else -1)

    def floor(self) -> int:
        """The integer ``⌊a + bφ⌋``, exactly."""
        s, t, d = self._root5_form()
        if t == 0:
            return s // (2 * d)
        r = math.isqrt(5 * t * t)  # 5t² is no square: ⌊|t|√5⌋ = r
        return (s + (r if t > 0 else -r - 1)) // (2 * d)

    def __float__(self) -> float:
        """The nearest float64 (to within one unit in the last place), even when ``a`` and ``b``
        are huge and nearly cancel."""
        return (self * (1 << 64)).floor() / (1 << 64)


def _cross_sign(d: tuple[QPhi, QPhi], e: tuple[QPhi, QPhi]) -> int:
    return (d[0] * e[1] - d[1] * e[0]).sign()


#: The direction ``v`` of the infinitesimal move of the start (module docstring): both
#: components positive (a point on the fundamental domain's border stays in the half-open
#: domain) and parallel to no edge (checked when a partition is loaded).
PERTURBATION = (QPhi(1), QPhi(Fraction(113, 355)))


@dataclass(frozen=True)
class Edge:
    """A directed polygon edge ``a -> b``: ``d = b - a`` and the constant ``c = d × a`` of its
    line ``d × p = c``; ``side`` is the sign of ``d × v`` for the perturbation ``v``."""

    d: tuple[QPhi, QPhi]
    c: QPhi
    side: int

    def where(self, p: tuple[QPhi, QPhi]) -> int:
        """1 if ``p + εv`` lies left of the line (the polygon's side, counter-clockwise), else -1."""
        s = (self.d[0] * p[1] - self.d[1] * p[0] - self.c).sign()
        return s if s else self.side


@dataclass(frozen=True)
class Partition:
    """A Markov partition as the coding needs it.

    The lattice is spanned by ``(lx, 0)`` and ``(sx, ly)``; its fundamental domain is the
    half-open rectangle ``[0, lx) x [0, ly)``. The rotation moves a point by ``(hx, 0)`` per
    column and ``(0, hy)`` per row. ``atoms`` are ``(tile, vertices, edges)`` with the vertices
    counter-clockwise; ``tile`` is the index in the built-in tile set's order. ``ylo``,
    ``x0``, ``slope``, ``labels``, ``nbreaks`` are the float slab tables of
    :mod:`._markov_kernels`, ``ybounds`` the slab boundaries (vertex heights).
    """

    name: str
    lx: QPhi
    ly: QPhi
    sx: QPhi
    hx: QPhi
    hy: QPhi
    atoms: tuple
    ybounds: np.ndarray
    ylo: np.ndarray
    x0: np.ndarray
    slope: np.ndarray
    labels: np.ndarray
    nbreaks: np.ndarray
    max_slope: float

    def reduce(self, x: QPhi, y: QPhi) -> tuple[QPhi, QPhi]:
        """``(x, y)`` modulo the lattice, in the fundamental domain, exactly."""
        ell = (y / self.ly).floor()
        y = y - ell * self.ly
        x = x - ell * self.sx
        return x - (x / self.lx).floor() * self.lx, y

    def label_at(self, x: QPhi, y: QPhi) -> int:
        """The tile of the polygon that holds ``(x, y) + εv`` (any point of the plane), exactly."""
        p = self.reduce(x, y)
        for tile, _, edges in self.atoms:
            if all(e.where(p) > 0 for e in edges):
                return tile
        raise InternalError(f"{self.name}: no polygon holds {p!r} (the partition data is broken)")


def _data_dir():
    return resources.files("tilesolve") / "data" / "markov"


def _point(v: Any) -> tuple[QPhi, QPhi]:
    return QPhi.of(v[0]), QPhi.of(v[1])


@functools.lru_cache(maxsize=None)
def partition(name: str) -> Partition:
    """The partition ``name`` (one of :data:`NAMES`), read from its data file and checked:
    convex counter-clockwise polygons, no edge parallel to :data:`PERTURBATION`."""
    if name not in NAMES:
        raise InvalidProblem(f"no Markov partition for {name!r}; there are {', '.join(NAMES)}")
    doc = json.loads((_data_dir() / f"{name}.json").read_text(encoding="utf-8"))
    (lx, zero), (sx, ly) = (_point(g) for g in doc["lattice"])
    (hx, z1), (z2, hy) = (_point(g) for g in doc["rotation"])
    if zero != 0 or z1 != 0 or z2 != 0:
        raise InternalError(f"{name}: the coding needs a lattice ((lx, 0), (sx, ly)) and an axis-parallel rotation")
    tile_of = doc["tile_of_label"]
    atoms = []
    for atom in doc["atoms"]:
        vs = [_point(v) for v in atom["vertices"]]
        edges = []
        for a, b in zip(vs, vs[1:] + vs[:1]):
            d = (b[0] - a[0], b[1] - a[1])
            side = _cross_sign(d, PERTURBATION)
            if side == 0:
                raise InternalError(f"{name}: an edge is parallel to the perturbation direction")
            edges.append(Edge(d, d[0] * a[1] - d[1] * a[0], side))
        for e, f in zip(edges, edges[1:] + edges[:1]):
            if _cross_sign(e.d, f.d) <= 0:
                raise InternalError(f"{name}: atom {atom['label']} is not convex counter-clockwise")
        atoms.append((tile_of[atom["label"]], tuple(vs), tuple(edges)))
    return _with_slabs(name, lx, ly, sx, hx, hy, tuple(atoms))


def _with_slabs(name, lx, ly, sx, hx, hy, atoms) -> Partition:
    """Cut the fundamental domain at every vertex height into slabs; in each, order the edges
    crossing it from left to right and code the intervals between them (exactly)."""
    heights = sorted({v[1] for _, vs, _ in atoms for v in vs})
    if heights[0] != 0 or heights[-1] != ly:
        raise InternalError(f"{name}: the polygons do not span the fundamental domain's height")
    slabs = []
    for lo, hi in zip(heights, heights[1:]):
        mid = (lo + hi) * Fraction(1, 2)
        lines = {}
        for _, vs, _ in atoms:
            for a, b in zip(vs, vs[1:] + vs[:1]):
                if min(a[1], b[1]) <= lo and hi <= max(a[1], b[1]):
                    slope = (b[0] - a[0]) / (b[1] - a[1])
                    at_lo = a[0] + slope * (lo - a[1])
                    lines[(at_lo, slope)] = at_lo + slope * (mid - lo)
        order = sorted(lines, key=lines.__getitem__)
        xs = [lines[k] for k in order]
        if xs[0] != 0 or xs[-1] != lx:
            raise InternalError(f"{name}: the polygons do not span the fundamental domain's width")
        cuts, labels = [order[0]], []
        for k in range(1, len(order)):
            tile = _interior_label(name, atoms, ((xs[k - 1] + xs[k]) * Fraction(1, 2), mid))
            if labels and labels[-1] == tile:
                cuts[-1] = order[k]  # same tile on both sides: no breakpoint
            else:
                labels.append(tile)
                cuts.append(order[k])
        slabs.append((lo, cuts, labels))
    width = max(len(c) for _, c, _ in slabs)
    n = len(slabs)
    x0 = np.zeros((n, width))
    slope = np.zeros((n, width))
    labs = np.zeros((n, width), np.uint8)
    for s, (lo, cuts, labels) in enumerate(slabs):
        x0[s, :len(cuts)] = [float(c[0]) for c in cuts]
        slope[s, :len(cuts)] = [float(c[1]) for c in cuts]
        labs[s, :len(labels)] = labels
    return Partition(name, lx, ly, sx, hx, hy, atoms,
                     ybounds=np.array([float(h) for h in heights]),
                     ylo=np.array([float(s[0]) for s in slabs]), x0=x0, slope=slope, labels=labs,
                     nbreaks=np.array([len(s[1]) for s in slabs], np.int64),
                     max_slope=float(np.abs(slope).max()))


def _interior_label(name, atoms, p) -> int:
    inside = [tile for tile, _, edges in atoms
              if all((e.d[0] * p[1] - e.d[1] * p[0] - e.c).sign() > 0 for e in edges)]
    if len(inside) != 1:
        raise InternalError(f"{name}: {len(inside)} polygons hold an interior point (the partition data is broken)")
    return inside[0]


def start_point(name: str, seed: int) -> tuple[QPhi, QPhi]:
    """The start ``x0`` of the orbit for ``seed``: ``((a1 + b1 φ) / 2**32, (a2 + b2 φ) / 2**32)``
    with ``a1, b1, a2, b2`` uniform in ``[0, 2**32)`` drawn from the seed's generator.

    Any point works (the infinitesimal move of the module docstring makes every orbit
    generic); a random point of ``Q(φ)²`` with large denominators almost never meets an
    edge, so the exact path is almost never taken, and different seeds give different
    tilings (the coding of distinct orbits).

    >>> start_point("labbe-u19", 7) == start_point("labbe-u19", 7)
    True
    """
    partition(name)
    rng = rng_from_seed(seed)
    a1, b1, a2, b2 = (int(v) for v in rng.integers(0, 1 << 32, size=4, dtype=np.uint64))
    den = Fraction(1, 1 << 32)
    return QPhi(a1 * den, b1 * den), QPhi(a2 * den, b2 * den)


def float_tolerance(part: Partition, block: int = BLOCK) -> float:
    """A bound on the float64 error of a point's distance to a breakpoint in a block of at most
    ``block x block`` cells, times a safety factor of 4.

    The quantities of :mod:`._markov_kernels` (domain sizes, steps, a reduced base point) are
    at most 8 and each is stored to within ``2**-50``; a row's height ``yp = by + r hy - l ly``
    and its offset ``u = bx - l sx - k lx`` (``r, l, k <= 8 block``), a column's step
    ``v = c hx - k' lx`` (``c, k' <= 8 block``) and a cell's ``x = u + v`` each add at most a few
    roundings of numbers below ``8 (block + 1)``: the error of ``x`` and of ``yp`` is below
    ``25 (2 block + 2) 2**-50``. A breakpoint ``x0 + slope (yp - ylo)`` adds ``|slope|`` times
    the error of ``yp``. So ``|x - breakpoint|`` is off by less than
    ``(1 + max|slope|) 25 (2 block + 2) 2**-50``.
    """
    if part.max_slope > 8:
        raise InternalError(f"{part.name}: an edge is too flat for the float error bound")
    return 4 * (1 + part.max_slope) * 25 * (2 * block + 2) * 2.0 ** -50


def markov_window(name: str, window: Window, seed: int) -> np.ndarray:
    """The tiles of ``window`` in the tiling that codes the orbit of :func:`start_point`.

    Parameters
    ----------
    name : str
        ``"jeandel-rao"`` or ``"labbe-u19"`` (:data:`NAMES`).
    window : Window
        Where the cells sit (:mod:`tilesolve.model.window`).
    seed : int
        Chooses the orbit; the same seed gives the same tiling of the whole plane, so windows at
        different origins agree where they overlap.

    Returns
    -------
    numpy.ndarray
        ``uint8 (window.height, window.width)``: the index of each cell's tile in the built-in
        tile set ``name`` (``tilesolve/data/tilesets/NAME.json``), row 0 the top row when y
        grows upwards (:meth:`Window.cell`).
    """
    return orbit_window(name, window, start_point(name, seed))


def orbit_window(name: str, window: Window, start: tuple[Any, Any]) -> np.ndarray:
    """:func:`markov_window` for the orbit of an explicit start ``(x, y)`` (numbers of
    ``Q(φ)``: :class:`QPhi`, rationals or ``[a, b]`` pairs); it may lie on an edge or a vertex.

    Large windows run the compiled kernel on every core this process may use (threads over
    bands of rows); the output does not depend on the number of threads.
    """
    from tilesolve.constructive._markov_kernels import FLAG, KERNELS

    part = partition(name)
    window = Window.of(window)
    px, py = QPhi.of(start[0]), QPhi.of(start[1])
    h, w = window.shape
    out = np.empty((h, w), np.uint8)
    rows = np.arange(h, dtype=np.int64)
    ys = window.y0 + h - 1 - rows if window.y_up else window.y0 + rows
    kern = KERNELS.pick(h * w)
    compiled = kern is not KERNELS.plain()
    tol = float_tolerance(part, BLOCK)
    lx, ly, sx, hy = (float(getattr(part, f)) for f in ("lx", "ly", "sx", "hy"))
    steps = _wrap(np.arange(min(w, BLOCK)) * float(part.hx), lx)  # v[c]: c steps, in every block
    bands = []  # (first row, rows, first column, u, yp, slab)
    for r0 in range(0, h, BLOCK):
        block_ys = ys[r0:r0 + BLOCK]
        ybase = int(block_ys.min())
        y = py + ybase * part.hy
        ell = (y / part.ly).floor()
        yr = float(y - ell * part.ly) + (block_ys - ybase) * hy
        lr = np.floor(yr / ly)
        yp = yr - lr * ly
        slab = np.searchsorted(part.ybounds, yp, side="right") - 1
        near = np.abs(yp[:, None] - part.ybounds[None, :]).min(axis=1) < tol
        slab[near | (slab < 0) | (slab >= len(part.ylo))] = -1
        for c0 in range(0, w, BLOCK):
            x = px + (window.x0 + c0) * part.hx - ell * part.sx
            u = _wrap(float(x - (x / part.lx).floor() * part.lx) - lr * sx, lx)
            for a in range(0, len(block_ys), _BAND):
                bands.append((r0 + a, c0, u[a:a + _BAND], yp[a:a + _BAND], slab[a:a + _BAND]))
    bins = 1024 if compiled else 8  # the speed only (kernel docstring)

    def code(band):
        r0, c0, u, yp, slab = band
        view = out[r0:r0 + len(u), c0:c0 + BLOCK]
        return kern.code_block(view, steps[:view.shape[1]], u, yp, slab, part.ylo, part.x0, part.slope,
                               part.labels, part.nbreaks, lx, tol, np.empty(int(part.nbreaks.max())),
                               np.empty(2 * bins + 1, np.uint8), np.empty(view.shape[1], np.int64))

    threads = min(_cores(), len(bands)) if compiled else 1
    if threads > 1:
        with ThreadPoolExecutor(threads) as pool:
            flagged = list(pool.map(code, bands))
    else:
        flagged = [code(band) for band in bands]
    for (r0, c0, u, _, _), n in zip(bands, flagged):
        if n:
            view = out[r0:r0 + len(u), c0:c0 + BLOCK]
            for i, j in zip(*np.nonzero(view == FLAG)):
                view[i, j] = part.label_at(px + (window.x0 + c0 + int(j)) * part.hx, py + int(ys[r0 + i]) * part.hy)
    return out



def cell_point(name: str, seed: int, x: int, y: int) -> tuple[float, float]:
    """The point of cell ``(x, y)``'s orbit in the fundamental domain, reduced exactly and then
    rounded to float64: the anchor from which cell ``(x + c, y + r)`` lies at
    ``+ (c hx, r hy)`` modulo the lattice of :func:`partition`.

    >>> px, py = cell_point("labbe-u19", 3, 2**62, -5)
    >>> 0 <= px < 1 and 0 <= py < 1
    True
    """
    part = partition(name)
    sx, sy = start_point(name, seed)
    return tuple(float(v) for v in part.reduce(sx + x * part.hx, sy + y * part.hy))

#: Rows of one task of the thread pool.
_BAND = 256


def _wrap(a, lx: float):
    """``a mod lx`` in ``[0, lx)`` (float64, elementwise)."""
    a = np.asarray(a, dtype=np.float64)
    a = a - np.floor(a / lx) * lx
    return np.where(a >= lx, a - lx, np.where(a < 0, a + lx, a))
