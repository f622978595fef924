"""Hierarchical importance sampling on self-similar tilings: Penrose (Ostromoukhov, Donohue,
Jodoin, "Fast hierarchical importance sampling with blue noise properties", SIGGRAPH 2004) and
polyominoes (Ostromoukhov, "Sampling with polyominoes", SIGGRAPH 2007); class notes Part IV.
Plain rejection sampling is the anchor.

The seeds hold only the slides of Part IV (the papers' text is not among them), so the method is
reconstructed from the slides' outline ("adaptive subdivision, structural indices, corrective
vectors lookup table") and stated here in full:

* **Tiles.** A tiling that subdivides into smaller copies of its own tiles: the Robinson
  triangles of the Penrose tiling (:func:`tilesolve.constructive.penrose.deflate`: an acute
  triangle into 2, an obtuse one into 3, legs shrinking by phi); the X pentomino of the base
  ``2 + i`` number system (5 children, each level shrinking by ``sqrt 5`` and turning by
  ``atan(1/2)``; the reconstruction of the 2007 paper's rotated polyominoes); or a rep-4
  polyomino (:func:`tilesolve.constructive.reptile.rule`: 4 copies at half size). Root tiles
  (a sun of ten triangles, a patch of the pentomino lattice, one large polyomino), turned and
  placed by the seed, cover the image's domain.
* **One sample a tile**, at its centroid. A tile's children are ranked once per tile type (the
  *structural index*): rank 0 is the child that carries the parent's sample on (the largest
  child, the one nearest the parent's centroid among equals; the centre of the X pentomino,
  whose centroid is its parent's), the others follow farthest first from it (opposites first
  for the pentomino), so that the first new samples of a tile are spread.
* **Thresholds in density units.** Let ``a_l`` be the mean area of a tile of level ``l`` (all
  tiles for polyominoes; the Penrose triangles' two sizes averaged, obtuse : acute = phi : 1).
  A tile is subdivided where the mean density over it exceeds ``1 / a_l`` (its level's
  threshold: it would hold more than one sample). The samples born at level ``l + 1`` appear
  as the density rises from ``1 / a_l`` to ``1 / a_(l+1)``: child ``r >= 1`` of ``k`` has the
  threshold ``1/a_l + s (1/a_(l+1) - 1/a_l)``, ``s = (r - 1 + v_T) / (k - 1)``; rank 0 keeps its
  parent's threshold. ``v`` is the tile's place in its neighbourhood, ``v_child = (r + v_T) /
  k`` (a radical inverse along the hierarchy, as an ordered-dither matrix is built), so that
  neighbouring tiles take their next sample at staggered densities. A leaf (a tile not
  subdivided) emits its sample where the mean density over it exceeds its threshold. The
  expected count of a region of uniform density ``D`` is then ``D`` times its area on average
  over the tiles (exactly per tile for equal children); the 2004 paper's Fibonacci number
  system plays this part for the Penrose triangles.
* **Correction tables** (Ostromoukhov 2007: "the exact position of the sampling point within
  the polyomino is determined according to a structural index, which indicates the
  polyomino's local neighborhood; the variety of structural indices and associated sampling
  point positions are computed during the offline optimization process, and tabulated"; "the
  method allows both deterministic and pseudo-non-deterministic sampling"). The paper's
  tables are not in the seeds; :func:`learn_corrections` rebuilds them
  (``scripts/build_importance_corrections.py`` wrote the shipped file,
  ``tilesolve/data/importance/polyomino-corrections.json``, its command and seed inside): the
  sampler at constant densities, Lloyd-relaxed, the mean displacement of each sample in its
  tile's frame by structural index (:func:`structural_index`: which of 8 sectors around it
  hold a neighbour) and density bin, and the spread left around that mean. With
  ``correct`` (the default of :class:`~tilesolve.model.importance.ImportanceProblem`; the X
  pentomino and the chair), the sampler is the pseudo-non-deterministic variant: each tile's
  children ranked in a seeded random order (the ordered ranks make the uniform case periodic
  with a period of a few subdivisions, whatever the offsets), each sample moved by its
  entry's mean and by Gaussian noise of its entry's spread (the means alone leave the leaf
  lattice's peaks). Without it, the samples sit at tile centroids; ``jitter`` (each sample at
  a uniform random point of its tile) and ``lloyd`` steps of density-weighted Lloyd
  relaxation (:func:`lloyd`) are the other stand-ins.

The density integral over a rep-4 polyomino is exact (its cells are squares: a summed-area
table, bilinear between pixel corners); over a Penrose triangle it is the mean over its
bounding box, over the fractal pentomino the mean over its bounding square: approximations at
the tile's scale. Samples whose
tile centroid falls outside the domain are reflected into it across the edge; those on a white
pixel are dropped; :func:`sample` calibrates the count.

>>> from tilesolve.model.importance import ImportanceProblem, builtin_density
>>> pts = sample(ImportanceProblem(builtin_density("flat", 16), 500, "polyomino"), seed=1)
>>> bool(450 < len(pts) < 550 and pts.min() >= 0 and pts.max() <= 1)
True
"""

from __future__ import annotations

import functools

import numpy as np

from tilesolve._random import rng_from_seed
from tilesolve.constructive import penrose, reptile
from tilesolve.model.importance import CORRECTED_TILES, DensityMap, ImportanceProblem

__all__ = ["CALIBRATE", "CALIBRATION_PASSES", "CORRECTED_TILES", "MassTable", "CorrectionTable", "penrose_points",
           "polyomino_points", "rejection_points", "lloyd", "sample", "structural_index", "load_corrections",
           "voronoi_lloyd", "learn_corrections"]

_PHI = (1 + 5**0.5) / 2
#: The mean area of a Robinson triangle of legs 1 in a Penrose tiling (obtuse : acute = phi : 1).
_MEAN_AREA = (np.sin(np.pi / 5) + _PHI * np.sin(3 * np.pi / 5)) / (2 * (1 + _PHI))
#: Relative error of the count above which :func:`sample` calibrates the density once.
CALIBRATE = 0.01
#: Most extra passes of the calibration.
CALIBRATION_PASSES = 3
#: Deepest subdivision of a polyomino (its side shrinks by 2 a level: 2^-30 of the domain).
MAX_POLYOMINO_LEVELS = 30
#: Deepest subdivision of the Penrose sun (legs shrink by phi a level; ring coordinates up to phi^60 fit int64).
MAX_PENROSE_LEVELS = 60


class MassTable:
    """Integrals of a density scaled to ``total`` samples over axis-aligned boxes of the domain:
    a summed-area table, bilinear between pixel corners (exact for a density constant on each
    pixel)."""

    def __init__(self, density: DensityMap, total: float) -> None:
        v = density.values[::-1]  # row 0 at the bottom: y up
        s = np.zeros((v.shape[0] + 1, v.shape[1] + 1))
        s[1:, 1:] = v.cumsum(axis=0).cumsum(axis=1)
        self.rows, self.cols = v.shape
        self.per_unit = 1.0 / density.pixel
        self.sat = s * (total / s[-1, -1])
        self.flat = self.sat.ravel()
        #: The highest density, in samples per unit area.
        self.peak = float(v.max()) * total / float(s[-1, -1]) * self.per_unit**2

    def cumulative(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """The mass of ``[0, x] x [0, y]``."""
        u = np.clip(x * self.per_unit, 0, self.cols)
        w = np.clip(y * self.per_unit, 0, self.rows)
        j = np.minimum(u.astype(np.int64), self.cols - 1)
        i = np.minimum(w.astype(np.int64), self.rows - 1)
        fu, fw = u - j, w - i
        flat = i * (self.cols + 1) + j  # np.take on the flat table: several times faster than s[i, j]
        s, step = self.flat, self.cols + 1
        low = s.take(flat) + (s.take(flat + 1) - s.take(flat)) * fu
        high = s.take(flat + step) + (s.take(flat + step + 1) - s.take(flat + step)) * fu
        return low + (high - low) * fw

    def box(self, x0, y0, x1, y1) -> np.ndarray:
        """The mass of the boxes ``[x0, x1] x [y0, y1]`` (arrays)."""
        f = self.cumulative
        return f(x1, y1) - f(x0, y1) - f(x1, y0) + f(x0, y0)


def _ranks(parent_centre: np.ndarray, centres: np.ndarray, areas: np.ndarray) -> np.ndarray:
    """The structural index of each child slot: rank 0 the largest child (nearest the parent's
    centroid among equals), then the others farthest first from it."""
    big = np.flatnonzero(np.isclose(areas, areas.max()))
    first = big[np.argmin(np.hypot(*(centres[big] - parent_centre).T))]
    far = np.hypot(*(centres - centres[first]).T)
    order = [first] + [int(i) for i in np.argsort(-far, kind="stable") if i != first]
    ranks = np.empty(len(order), dtype=np.int64)
    ranks[order] = np.arange(len(order))
    return ranks


def _shuffled(rank: np.ndarray, parent: np.ndarray, rng) -> np.ndarray:
    """The ranks ``1..k-1`` of each parent's children in a random order (rank 0, the child that
    carries the parent's sample, kept)."""
    key = np.where(rank == 0, -1.0, rng.random(len(rank)))
    order = np.lexsort((key, parent))  # children grouped by parent, rank 0 first, the others shuffled
    out = np.empty_like(rank)
    start = np.r_[0, np.flatnonzero(np.diff(parent[order])) + 1]
    pos = np.arange(len(rank)) - np.repeat(start, np.diff(np.r_[start, len(rank)]))
    out[order] = pos
    return out


def _hierarchy(system, mass: MassTable, rng, max_levels: int, jitter: bool = False, shuffle: bool = False,
               frames: bool = False):
    """The samples of the adaptive subdivision (the module docstring's rule), level by level.

    ``system`` gives ``roots()`` (a state), ``size(state)``, ``measure(state, mass)`` (each
    tile's mean density, the mean area of a tile of its level, its centroid), ``take(state,
    which)``, ``uniform(state, rng)`` (a random point of each tile), ``split(state, which)``
    (the children of the tiles ``which``: their state, parent positions in ``which``,
    structural ranks, sibling counts) and ``frame(state)`` (each tile's similarity, a ``(n, 2,
    2)`` array). ``shuffle`` ranks each tile's children ``1..k-1`` in a random order. With
    ``frames``, also the frame and the load (mean density times area) of each sample's tile."""
    state = system.roots()
    n = system.size(state)
    v = (rng.permutation(n) + rng.random()) / n
    lo, s = np.zeros(n), v.copy()  # root thresholds s / A
    out, out_frames, out_loads = [], [], []
    for level in range(max_levels + 1):
        density, area, centre = system.measure(state, mass)
        inv = 1.0 / area
        theta = lo + s * (inv - lo)
        sub = density * area > 1.0 if level < max_levels else np.zeros(len(density), bool)
        emit = ~sub & (density > theta)
        out.append(system.uniform(system.take(state, emit), rng) if jitter else centre[emit])
        if frames:
            out_frames.append(np.asarray(system.frame(system.take(state, emit))))
            out_loads.append((density * area)[emit])
        which = np.flatnonzero(sub)
        if not len(which):
            break
        state, parent, rank, k = system.split(state, which)
        if shuffle:
            rank = _shuffled(rank, parent, rng)
        p = which[parent]
        first = rank == 0
        lo = np.where(first, theta[p], inv[p])
        s = np.where(first, 0.0, (rank - 1 + v[p]) / np.maximum(k - 1, 1))
        v = (rank + v[p]) / k
    pts = np.concatenate(out) if out else np.zeros((0, 2))
    if frames:
        return pts, np.concatenate(out_frames), np.concatenate(out_loads)
    return pts


class _Penrose:
    """Robinson triangles of a sun (exact ring coordinates, :mod:`tilesolve.constructive.penrose`),
    turned and placed in the plane by a similarity."""

    def __init__(self, levels: int, scale: float, angle: float, centre: np.ndarray) -> None:
        self.levels = levels
        c, s = np.cos(angle), np.sin(angle)
        self.turn = scale * np.array([[c, -s], [s, c]])
        self.centre = centre

    def roots(self):
        return penrose.sun(self.levels)

    @staticmethod
    def size(state) -> int:
        return len(state[0])

    def _xy(self, ring: np.ndarray) -> np.ndarray:
        return penrose.zeta_xy(ring) @ self.turn.T + self.centre

    def measure(self, state, mass: MassTable):
        _, a, b, c = state
        pa, pb, pc = self._xy(a), self._xy(b), self._xy(c)
        lo, hi = np.minimum(np.minimum(pa, pb), pc), np.maximum(np.maximum(pa, pb), pc)
        density = mass.box(lo[:, 0], lo[:, 1], hi[:, 0], hi[:, 1]) / np.prod(hi - lo, axis=1)
        legs = np.sum((pb - pa) ** 2, axis=1)  # every triangle of a level has the same legs
        return density, legs * _MEAN_AREA, (pa + pb + pc) / 3

    @staticmethod
    def take(state, which):
        return tuple(x[which] for x in state)

    def frame(self, state) -> np.ndarray:
        """Not used: Penrose samples take no correction table."""
        raise NotImplementedError

    def uniform(self, state, rng) -> np.ndarray:
        """A uniform random point of each triangle."""
        _, a, b, c = state
        pa, pb, pc = self._xy(a), self._xy(b), self._xy(c)
        u, v = rng.random((2, len(a), 1))
        flip = u + v > 1
        u, v = np.where(flip, 1 - u, u), np.where(flip, 1 - v, v)
        return pa + u * (pb - pa) + v * (pc - pa)

    def split(self, state, which: np.ndarray):
        t, a, b, c = self.take(state, which)
        acute = t == 0
        ia, io = np.flatnonzero(acute), np.flatnonzero(~acute)
        children = penrose.deflate(t, a, b, c)
        parent = np.concatenate([ia, ia, io, io, io])
        ranks_acute, ranks_obtuse = _penrose_ranks()
        rank = np.concatenate([np.repeat(ranks_acute, len(ia)), np.repeat(ranks_obtuse, len(io))])
        k = np.concatenate([np.full(2 * len(ia), 2), np.full(3 * len(io), 3)])
        return children, parent, rank, k


@functools.lru_cache(maxsize=None)
def _penrose_ranks() -> tuple[np.ndarray, np.ndarray]:
    """The structural ranks of the children slots of :func:`penrose.deflate` (acute: 2 slots,
    obtuse: 3), from one triangle of each type (ranks are invariant under similarities)."""
    out = []
    tri = penrose.sun(3)
    for kind in (0, 1):
        i = int(np.flatnonzero(tri[0] == kind)[0])
        one = tuple(x[i:i + 1] for x in tri)
        t, a, b, c = penrose.deflate(*one)
        corners = np.stack([penrose.zeta_xy(x) for x in (a, b, c)], axis=1)
        centres = corners.mean(axis=1)
        d1, d2 = corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]
        areas = 0.5 * np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
        parent = np.stack([penrose.zeta_xy(x) for x in (one[1], one[2], one[3])], axis=1).mean(axis=1)[0]
        out.append(_ranks(parent, centres, areas))
        tri = (t, a, b, c)  # its obtuse child is the next kind's example
    return out[0], out[1]


class _Polyomino:
    """Tiles ``x -> L x + t`` of a rep-4 polyomino (:func:`tilesolve.constructive.reptile.rule`),
    in floats (each level halves ``L``: exact in binary)."""

    def __init__(self, name: str, lin: np.ndarray, off: np.ndarray) -> None:
        proto = reptile.PROTOTILES[name]
        self.cells = np.array([c[:2] for c in proto.cells], dtype=np.float64)
        self.centre = self.cells.mean(axis=0) + 0.5
        maps = reptile.rule(name)
        self.mats = np.stack([g for g, _ in maps]).astype(np.float64) / 2
        self.trans = np.stack([t for _, t in maps]).astype(np.float64) / 2
        self.lin, self.off = lin, off
        centres = (self.mats @ self.centre) + self.trans
        self.ranks = _ranks(self.centre, centres, np.ones(len(maps)))

    def roots(self):
        return self.lin[None], self.off[None]

    @staticmethod
    def size(state) -> int:
        return len(state[0])

    def measure(self, state, mass: MassTable):
        lin, off = state
        p0 = np.einsum("nij,cj->nci", lin, self.cells) + off[:, None]
        p1 = np.einsum("nij,cj->nci", lin, self.cells + 1) + off[:, None]
        lo, hi = np.minimum(p0, p1), np.maximum(p0, p1)
        m = mass.box(lo[..., 0], lo[..., 1], hi[..., 0], hi[..., 1]).sum(axis=1)
        area = np.abs(np.linalg.det(lin)) * len(self.cells)
        return m / area, area, lin @ self.centre + off

    @staticmethod
    def take(state, which):
        return state[0][which], state[1][which]

    def frame(self, state) -> np.ndarray:
        """The tile's similarity scaled to the tile's size: ``|det| =`` its area."""
        return state[0] * np.sqrt(len(self.cells))

    def uniform(self, state, rng) -> np.ndarray:
        """A uniform random point of each tile (a random cell, a random point in it)."""
        lin, off = state
        cell = self.cells[rng.integers(len(self.cells), size=len(off))] + rng.random((len(off), 2))
        return np.einsum("nij,nj->ni", lin, cell) + off

    def split(self, state, which: np.ndarray):
        lin, off = self.take(state, which)
        k = len(self.mats)
        new_lin = (lin[:, None] @ self.mats[None]).reshape(-1, 2, 2)
        new_off = (off[:, None] + np.einsum("nij,mj->nmi", lin, self.trans)).reshape(-1, 2)
        parent = np.repeat(np.arange(len(which)), k)
        return (new_lin, new_off), parent, np.tile(self.ranks, len(which)), np.full(len(parent), k)


class _Cross:
    """The X-pentomino digit tiling: base ``c = 2 + i``, digits ``0, 1, i, -1, -i`` (a complete
    residue system modulo ``c``). A tile is its centre ``z`` (complex) at a level whose scale
    ``s`` is a complex number; its five children are centred at ``z + d s / c``. Each level
    shrinks by ``sqrt 5`` and turns by ``atan(1/2)`` (an irrational angle: the levels share no
    lattice). The tile is a self-similar fractal of area ``|s|^2`` around its centre, drawn one
    level down as five squares (an X pentomino); its density is measured over its bounding
    square (it lies within ``|s| / (sqrt 5 - 1)`` of its centre)."""

    digits = np.array([0, 1, -1, 1j, -1j])  # rank order: the centre (same centroid), then opposites

    def __init__(self, centres: np.ndarray, scale: complex) -> None:
        self.centres, self.scale = centres, scale
        self.ranks = np.arange(5)

    def roots(self):
        return self.centres, 0

    @staticmethod
    def size(state) -> int:
        return len(state[0])

    def _cells(self, state):
        z, level = state
        s = self.scale / (2 + 1j) ** (level + 1)
        return z[:, None] + s * self.digits, s

    def measure(self, state, mass: MassTable):
        z, level = state
        side = abs(self.scale) / 5 ** (level / 2)  # sqrt of the tile's area
        x, y, h = z.real, z.imag, side / (5**0.5 - 1)  # the fractal lies within this radius of its centre
        density = mass.box(x - h, y - h, x + h, y + h) / (2 * h) ** 2
        return density, np.full(len(z), side**2), np.column_stack([x, y])

    @staticmethod
    def take(state, which):
        return state[0][which], state[1]

    def frame(self, state) -> np.ndarray:
        """The tile's similarity: multiplication by its complex scale ``s / c^level``."""
        z, level = state
        s = self.scale / (2 + 1j) ** level
        m = np.array([[s.real, -s.imag], [s.imag, s.real]])
        return np.broadcast_to(m, (len(z), 2, 2))

    def uniform(self, state, rng) -> np.ndarray:
        """A uniform random point of each tile's X pentomino."""
        cells, s = self._cells(state)
        pick = cells[np.arange(len(cells)), rng.integers(5, size=len(cells))]
        u = rng.random((len(cells), 2)) - 0.5
        p = pick + s * (u[:, 0] + 1j * u[:, 1])
        return np.column_stack([p.real, p.imag])

    def split(self, state, which: np.ndarray):
        cells, _ = self._cells(self.take(state, which))
        parent = np.repeat(np.arange(len(which)), 5)
        return (cells.ravel(), state[1] + 1), parent, np.tile(self.ranks, len(which)), np.full(len(parent), 5)


def _cross_roots(density: DensityMap, rng) -> _Cross:
    """Level-0 tiles of side 0.5 (turned by the seed) whose tiles may meet the domain: the
    lattice ``s Z[i]`` near it (a tile lies within ``|s| / (sqrt 5 - 1)`` of its centre)."""
    s = 0.5 * np.exp(2j * np.pi * rng.random())
    shift = (rng.random() + 1j * rng.random()) * s
    reach = abs(s) / (5**0.5 - 1) + abs(s)
    span = int(np.ceil((np.hypot(density.width, density.height) + 2 * reach) / abs(s))) + 1
    m, n = np.meshgrid(np.arange(-span, span + 1), np.arange(-span, span + 1))
    z = (m.ravel() + 1j * n.ravel()) * s + shift + (density.width + 1j * density.height) / 2
    near = (z.real > -reach) & (z.real < density.width + reach) & (z.imag > -reach) & (z.imag < density.height + reach)
    return _Cross(z[near], s)


def _inside(points: np.ndarray, density: DensityMap) -> np.ndarray:
    """The points reflected into the domain across its nearest edge (a tile that straddles the
    edge may have its centroid outside), then those on a pixel of positive density (a tile
    that straddles the edge of a white region may have its centroid in it)."""
    points = points.copy()
    for d, top in ((0, density.width), (1, density.height)):
        x = points[:, d]
        points[:, d] = np.where(x < 0, -x, np.where(x >= top, 2 * top - x, x))
    x, y = points[:, 0], points[:, 1]
    points = points[(x >= 0) & (x < density.width) & (y >= 0) & (y < density.height)]
    col = np.minimum((points[:, 0] / density.pixel).astype(np.int64), density.cols - 1)
    row = np.minimum(((density.height - points[:, 1]) / density.pixel).astype(np.int64), density.rows - 1)
    return points[density.values[row, col] > 0]


def penrose_points(density: DensityMap, n: int, *, jitter: bool = False, seed=None) -> np.ndarray:
    """About ``n`` samples of ``density`` by adaptive subdivision of a Penrose tiling's Robinson
    triangles (the module docstring; Ostromoukhov et al. 2004). A ``(m, 2)`` array."""
    rng = rng_from_seed(seed)
    mass = MassTable(density, n)
    centre = np.array([density.width, density.height]) / 2 + (rng.random(2) - 0.5) * 0.1
    far = np.maximum(centre, [density.width - centre[0], density.height - centre[1]])
    radius = 1.01 * np.hypot(*far) / np.cos(np.pi / 10)  # the sun's inner radius covers the domain
    root_area = 0.5 * radius**2 * np.sin(np.pi / 5)
    levels = int(np.clip(np.ceil(np.log(max(mass.peak * root_area, 1.0)) / (2 * np.log(_PHI))) + 2, 1,
                         MAX_PENROSE_LEVELS))
    system = _Penrose(levels, radius / _PHI**levels, rng.random() * 2 * np.pi, centre)
    return _inside(_hierarchy(system, mass, rng, levels, jitter), density)


def polyomino_points(density: DensityMap, n: int, *, tile: str = "chair", jitter: bool = False,
                     correct: bool = False, seed=None) -> np.ndarray:
    """About ``n`` samples of ``density`` by adaptive subdivision of a rep-4 polyomino or the X
    pentomino (the module docstring; Ostromoukhov 2007). With ``correct`` (and no ``jitter``,
    for a tile of :data:`CORRECTED_TILES`), the 2007 paper's pseudo-non-deterministic
    variant: each tile's children ranked in a seeded random order and each sample displaced by
    the learnt correction table (:func:`load_corrections`, :meth:`CorrectionTable.apply`).
    A ``(m, 2)`` array."""
    table = load_corrections(tile) if correct and not jitter and tile in CORRECTED_TILES else None
    return _polyomino(density, n, tile, jitter, seed, shuffle=table is not None, table=table)


def _polyomino(density: DensityMap, n: float, tile: str, jitter: bool, seed, *, shuffle: bool = False,
               table: "CorrectionTable | None" = None, noise: bool = True) -> np.ndarray:
    """:func:`polyomino_points` with its ingredients apart (``shuffle``: children ranked in a
    random order; ``table``: the correction offsets; ``noise``: their learnt spread added)."""
    rng = rng_from_seed(seed)
    mass = MassTable(density, n)
    system = _polyomino_system(density, tile, rng)
    if table is None:
        return _inside(_hierarchy(system, mass, rng, MAX_POLYOMINO_LEVELS, jitter, shuffle), density)
    centre, frame, load = _hierarchy(system, mass, rng, MAX_POLYOMINO_LEVELS, False, shuffle, frames=True)
    return _inside(table.apply(centre, frame, load, rng if noise else None), density)


def _polyomino_system(density: DensityMap, tile: str, rng):
    """The root tiles of the polyomino sampler over ``density``'s domain, turned and placed by ``rng``."""
    if tile == "x-pentomino":
        return _cross_roots(density, rng)
    side = 1.25  # the root's cell (0, 0) is a square of this side around the domain
    sym = reptile._symmetries("square")[int(rng.integers(8))].astype(np.float64) * side
    corner = np.minimum(np.minimum(sym @ [0, 0], sym @ [1, 1]), np.minimum(sym @ [1, 0], sym @ [0, 1]))
    slack = np.array([side - density.width, side - density.height])
    off = -corner - rng.random(2) * slack
    return _Polyomino(tile, sym, off)


def rejection_points(density: DensityMap, n: int, *, seed=None) -> np.ndarray:
    """Exactly ``n`` samples of ``density`` by rejection: uniform points of the domain, each kept
    with probability (its pixel's value) / (the largest value). A ``(n, 2)`` array."""
    rng = rng_from_seed(seed)
    v = density.values
    accept = (v / v.max()).ravel()
    rate = float(accept.mean())
    out, have = [], 0
    while have < n:
        m = int((n - have) / rate * 1.05) + 16
        xy = rng.random((m, 2)) * [density.width, density.height]
        col = np.minimum((xy[:, 0] / density.pixel).astype(np.int64), density.cols - 1)
        row = np.minimum(((density.height - xy[:, 1]) / density.pixel).astype(np.int64), density.rows - 1)
        keep = xy[rng.random(m) < accept[row * density.cols + col]]
        out.append(keep[: n - have])
        have += len(out[-1])
    return np.concatenate(out)


def lloyd(points: np.ndarray, density: DensityMap, steps: int, *, resolution: int = 16) -> np.ndarray:
    """``steps`` of density-weighted Lloyd relaxation: each point moves to the density-weighted
    centroid of its Voronoi cell, the cells measured on a grid of about ``resolution`` sample
    positions per point (or one per pixel, whichever is finer). scipy's KD-tree finds each
    position's nearest point."""
    if steps == 0 or len(points) == 0:
        return points
    from scipy.spatial import cKDTree

    want = max(resolution * len(points), density.rows * density.cols)
    per = max(1, int(np.ceil(np.sqrt(want / (density.rows * density.cols)))))
    step = density.pixel / per
    gx = (np.arange(density.cols * per) + 0.5) * step
    gy = (np.arange(density.rows * per) + 0.5) * step
    x, y = np.meshgrid(gx, gy)
    w = np.repeat(np.repeat(density.values[::-1], per, axis=0), per, axis=1).ravel()
    grid = np.column_stack([x.ravel(), y.ravel()])[w > 0]
    w = w[w > 0]
    pts = points.copy()
    for _ in range(steps):
        _, idx = cKDTree(pts).query(grid)
        total = np.bincount(idx, w, minlength=len(pts))
        moved = total > 0
        for d in (0, 1):
            pts[moved, d] = np.bincount(idx, w * grid[:, d], minlength=len(pts))[moved] / total[moved]
    return pts


# --- Correction tables (Ostromoukhov 2007: structural indices, offsets learnt offline) --------------------

#: The correction tables' file (its provenance inside: the command, the seed, the settings).
CORRECTIONS_FILE = "polyomino-corrections.json"
CORRECTIONS_FORMAT = "tilesolve/importance-corrections"
#: The neighbourhood read by :func:`structural_index`: 8 sectors of 45 degrees within this
#: radius (in units of the square root of the tile's area).
SECTOR_RADIUS = 1.6
SECTORS = 8
_CHUNK = 1 << 16


def structural_index(centre: np.ndarray, frame: np.ndarray) -> np.ndarray:
    """Each sample's structural index (Ostromoukhov 2007: "the polyomino's local
    neighbourhood"): bit ``j`` set where another sample's centroid lies in sector ``j`` (45
    degrees, sector 0 centred on the tile's own x axis) within :data:`SECTOR_RADIUS` of it,
    measured in the tile's frame (``frame``: its similarity, ``|det|`` its area), so that the
    index is the same for a turned or mirrored copy of a neighbourhood. 0..255. scipy's
    KD-tree finds the neighbours."""
    from scipy.spatial import cKDTree

    if len(centre) < 2:
        return np.zeros(len(centre), dtype=np.int64)
    reach = SECTOR_RADIUS * float(np.sqrt(np.abs(np.linalg.det(frame))).max())
    k = min(12, len(centre) - 1)
    tree, inverse = cKDTree(centre), np.linalg.inv(frame)
    out = np.empty(len(centre), dtype=np.int64)
    for a in range(0, len(centre), _CHUNK):  # chunks: the neighbour arrays stay small
        b = min(a + _CHUNK, len(centre))
        dist, idx = tree.query(centre[a:b], k=k + 1, distance_upper_bound=reach)
        ok = np.isfinite(dist[:, 1:])
        idx = np.where(ok, idx[:, 1:], 0)
        local = np.einsum("nij,nkj->nki", inverse[a:b], centre[idx] - centre[a:b, None])
        ok &= np.hypot(local[..., 0], local[..., 1]) < SECTOR_RADIUS
        sector = np.floor(np.arctan2(local[..., 1], local[..., 0]) / (2 * np.pi / SECTORS) + 0.5).astype(np.int64)
        out[a:b] = np.bitwise_or.reduce(np.where(ok, np.left_shift(1, sector % SECTORS), 0), axis=1)
    return out


def _density_bin(load: np.ndarray, k: int, bins: int) -> np.ndarray:
    """The importance bin of each sample: its tile's load (mean density times area, in ``(1/k,
    1]`` for a leaf of a subdivided parent) on a log scale, ``bins`` bins."""
    t = 1.0 + np.log(np.clip(load, 1.0 / k, 1.0)) / np.log(k)
    return np.minimum((t * bins).astype(np.int64), bins - 1)


class CorrectionTable:
    """Offsets of a polyomino's sample point by structural index and importance (Ostromoukhov
    2007's "variety of structural indices and associated sampling point positions computed
    during the offline optimization process, and tabulated"), learnt by :func:`learn_corrections`.

    ``mean[index, bin]`` is the mean displacement of the samples by Lloyd relaxation, in the
    tile's frame; ``spread[index, bin]`` the root mean square of what is left per axis (the
    pseudo-non-deterministic part: added as seeded Gaussian noise); ``count`` the samples each
    entry was learnt from (entries never seen stay 0)."""

    def __init__(self, tile: str, children: int, mean: np.ndarray, spread: np.ndarray, count: np.ndarray,
                 provenance: dict | None = None) -> None:
        self.tile, self.children = tile, children
        self.mean, self.spread, self.count = mean, spread, count
        self.bins = mean.shape[1]
        self.provenance = provenance or {}

    def apply(self, centre: np.ndarray, frame: np.ndarray, load: np.ndarray, rng=None) -> np.ndarray:
        """The samples at ``centre`` (their tiles' centroids) displaced by the table (and, with
        ``rng``, by the learnt spread)."""
        if not len(centre):
            return centre
        index, b = structural_index(centre, frame), _density_bin(load, self.children, self.bins)
        off = self.mean[index, b]
        if rng is not None:
            off = off + self.spread[index, b][:, None] * rng.standard_normal((len(centre), 2))
        return centre + np.einsum("nij,nj->ni", frame, off)

    def to_dict(self) -> dict:
        return {"format": CORRECTIONS_FORMAT, "version": 1, "tile": self.tile, "children": self.children,
                "bins": self.bins, "sectors": SECTORS, "sector_radius": SECTOR_RADIUS,
                "provenance": self.provenance,
                "mean": np.round(self.mean, 5).tolist(), "spread": np.round(self.spread, 5).tolist(),
                "count": self.count.astype(np.int64).tolist()}

    @classmethod
    def from_dict(cls, doc: dict) -> "CorrectionTable":
        if doc.get("format") != CORRECTIONS_FORMAT or doc.get("version") != 1:
            raise ValueError(f"not a {CORRECTIONS_FORMAT} version 1 table")
        if doc.get("sectors") != SECTORS or doc.get("sector_radius") != SECTOR_RADIUS:
            raise ValueError("the table was learnt with another structural index")
        mean, spread = np.array(doc["mean"], dtype=np.float64), np.array(doc["spread"], dtype=np.float64)
        count = np.array(doc["count"], dtype=np.int64)
        if mean.shape != (1 << SECTORS, doc["bins"], 2) or not spread.shape == count.shape == mean.shape[:2]:
            raise ValueError("the table's arrays have the wrong shape")
        return cls(doc["tile"], int(doc["children"]), mean, spread, count, doc.get("provenance"))


@functools.lru_cache(maxsize=None)
def _correction_file() -> dict:
    import json
    from importlib import resources

    text = (resources.files("tilesolve") / "data" / "importance" / CORRECTIONS_FILE).read_text(encoding="utf-8")
    return json.loads(text)


@functools.lru_cache(maxsize=None)
def load_corrections(tile: str) -> CorrectionTable:
    """The shipped correction table of ``tile`` (``tilesolve/data/importance/``, built by
    ``scripts/build_importance_corrections.py``; its provenance is in the file)."""
    doc = _correction_file()
    for t in doc["tables"]:
        if t["tile"] == tile:
            return CorrectionTable.from_dict(t)
    raise KeyError(f"no correction table for {tile!r}")


def voronoi_lloyd(points: np.ndarray, steps: int, movable: np.ndarray) -> np.ndarray:
    """``steps`` of Lloyd relaxation (class notes §4.2.4.3): each ``movable`` point whose
    Voronoi cell is bounded moves to the cell's centroid; the others stay (a frame of fixed
    points around the region learnt from). The cells are scipy's (Qhull); each cell's centroid
    is summed over the triangles from its site to its ridges (the cell is convex)."""
    from scipy.spatial import Voronoi

    x = np.array(points, dtype=np.float64)
    n = len(x)
    for _ in range(steps):
        vor = Voronoi(x)
        ridge, verts = vor.ridge_points, np.asarray(vor.ridge_vertices)
        open_ = (verts < 0).any(axis=1)
        bounded = np.ones(n, bool)
        bounded[ridge[open_].ravel()] = False
        ridge, verts = ridge[~open_], verts[~open_]
        a, b = vor.vertices[verts[:, 0]], vor.vertices[verts[:, 1]]
        area, cx, cy = np.zeros(n), np.zeros(n), np.zeros(n)
        for side in (0, 1):
            site = x[ridge[:, side]]
            u, v = a - site, b - site
            w = 0.5 * np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0])
            c = (site + a + b) / 3
            area += np.bincount(ridge[:, side], w, n)
            cx += np.bincount(ridge[:, side], w * c[:, 0], n)
            cy += np.bincount(ridge[:, side], w * c[:, 1], n)
        move = movable & bounded & (area > 0)
        x[move, 0], x[move, 1] = cx[move] / area[move], cy[move] / area[move]
    return x


def learn_corrections(tile: str, *, runs: int, n_min: float, n_max: float, steps: int, bins: int,
                      seed: int) -> CorrectionTable:
    """Ostromoukhov 2007's offline step, reconstructed (the paper's tables are not in the seeds):
    ``runs`` point sets of the sampler (children ranked in a random order, samples at their
    tiles' centroids) on the unit square at constant densities drawn log-uniformly from
    ``n_min..n_max`` samples, each relaxed by ``steps`` Lloyd steps (:func:`voronoi_lloyd`, a
    frame of 3 spacings fixed at the border), and the displacement of every sample at least
    ``steps + 6`` spacings inside recorded in its tile's frame under its structural index and
    density bin. The table holds each entry's mean and the spread left around it."""
    from tilesolve.model.importance import builtin_density

    children = 5 if tile == "x-pentomino" else 4
    rng = rng_from_seed(seed)
    flat = builtin_density("flat", 16)
    shape = (1 << SECTORS, bins)
    total, sq, count = np.zeros(shape + (2,)), np.zeros(shape), np.zeros(shape)
    for _ in range(runs):
        n = float(np.exp(rng.uniform(np.log(n_min), np.log(n_max))))
        run = rng_from_seed(int(rng.integers(1 << 62)))
        system = _polyomino_system(flat, tile, run)
        centre, frame, load = _hierarchy(system, MassTable(flat, n), run, MAX_POLYOMINO_LEVELS, False, True,
                                         frames=True)
        spacing = 1 / np.sqrt(n)
        inside = lambda m: ((centre > m) & (centre < 1 - m)).all(axis=1)  # noqa: E731
        moved = voronoi_lloyd(centre, steps, inside(3 * spacing))
        keep = inside((steps + 6) * spacing)
        local = np.linalg.solve(frame[keep], (moved - centre)[keep][..., None])[..., 0]
        at = structural_index(centre, frame)[keep] * bins + _density_bin(load[keep], children, bins)
        size = shape[0] * bins
        for d in (0, 1):
            total[..., d] += np.bincount(at, local[:, d], size).reshape(shape)
        sq += np.bincount(at, (local**2).sum(axis=1), size).reshape(shape)
        count += np.bincount(at, None, size).reshape(shape)
    mean = total / np.maximum(count, 1)[..., None]
    spread = np.sqrt(np.maximum(sq / np.maximum(count, 1) - (mean**2).sum(axis=-1), 0) / 2)
    return CorrectionTable(tile, children, mean, spread, count)


def sample(problem: ImportanceProblem, *, seed=None) -> np.ndarray:
    """The samples ``problem`` asks for: its method, then its Lloyd steps. A hierarchical
    sampler whose count is off by more than :data:`CALIBRATE` of the target runs again on the
    same tiling with the target scaled by the error, at most :data:`CALIBRATION_PASSES` times,
    and the closest count is kept (the Penrose triangles' two sizes and the samples dropped at
    the border bias the count by a few percent)."""
    d, n = problem.density, problem.points
    if problem.method == "rejection":
        return lloyd(rejection_points(d, n, seed=seed), d, problem.lloyd)
    if problem.method == "penrose":
        def run(target, s):
            return penrose_points(d, target, jitter=problem.jitter, seed=s)
    else:
        def run(target, s):
            return polyomino_points(d, target, tile=problem.tile, jitter=problem.jitter, correct=problem.correct,
                                    seed=s)
    s = int(rng_from_seed(seed).integers(1 << 62))
    target = float(n)
    best = pts = run(target, s)
    for _ in range(CALIBRATION_PASSES):  # the same tiling, the density scaled by the last pass's error
        if not len(pts) or abs(len(pts) - n) <= CALIBRATE * n:
            break
        target *= n / len(pts)
        pts = run(target, s)
        if abs(len(pts) - n) < abs(len(best) - n):
            best = pts
    return lloyd(best, d, problem.lloyd)
