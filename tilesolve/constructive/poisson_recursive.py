"""Recursive Wang tiles: building a set, and the points of a window at any level or density
(Kopf, Cohen-Or, Deussen and Lischinski 2006; class notes Part V; the definitions are in
:mod:`tilesolve.model.poisson_recursive`).

Building
--------
1. The corner-based Poisson disk tiles of the set's ``C``, ``N``, ``rho`` (§4.3,
   :func:`tilesolve.constructive.poisson.build_tiles`).
2. Each region's points put in progressive order (Kopf et al.): farthest-point order, from
   the point nearest the region's centroid, each next point the one farthest from those taken,
   so that every prefix is spread out; a point's rank is its place in that order.
3. The subdivision rules (Kopf et al.): one random sequence of ``n - 1`` sub-colours for
   each ordered pair of end colours of a horizontal edge, one for a vertical edge, the
   parent's corner colours at the sub-lattice corners, and random colours inside each tile.

Windows
-------
The level-0 lattice of the window and a margin of one tile is coloured by the direct corner
tiling (§3.3.1, random access); the lattice of depth ``k + 1`` is the depth-``k`` lattice with
every tile replaced by its rule, only over the tiles whose density needs level ``k + 1`` and a
margin of one tile (:meth:`~tilesolve.model.poisson_recursive.RecursiveWindowProblem.boxes`):
the cost follows the density box by box (Part V's slides: "cost ~ integral over density"; here
a level costs its whole box at the level's full density, whatever the ranks then keep). Level
by level, the tile set's points are placed on the depth-``k`` lattice (scaled by ``n^-k``) and
kept where they are at least ``d_k`` from the points already kept (a grid search,
:mod:`._poisson_recursive_kernels`). The margin holds every point that can decide a point of
the window (they lie within ``d_0 + d_1 + ... < 1`` of it), so any window gives the same points
where windows overlap. Last, a density keeps the points whose rank fits it, and the window is
cut out.

Examples
--------
>>> from tilesolve.model.poisson_recursive import RecursiveTilesProblem, RecursiveWindowProblem
>>> ts = build_recursive(RecursiveTilesProblem(1, 16, 0.7, 2), seed=3)
>>> ts.rules.shape
(1, 3, 3)
>>> w = sample_window(RecursiveWindowProblem(ts, (2**40, -3, 2, 2), level=1), seed=1)
>>> int(w.level.max()), w.n_points > 2 * 2 * 16
(1, True)
"""

from __future__ import annotations

import numpy as np

from tilesolve._random import rng_from_seed
from tilesolve.constructive import _poisson_recursive_kernels as _k
from tilesolve.constructive.poisson import build_tiles, corner_lattice, place_tiles
from tilesolve.constructive.stochastic import direct_corner
from tilesolve.errors import InvalidProblem
from tilesolve.model.poisson import KINDS, SLACK, PoissonTileSet
from tilesolve.model.poisson_recursive import (
    RecursiveTilesProblem,
    RecursiveTileSet,
    RecursiveWindow,
    RecursiveWindowProblem,
)

__all__ = ["build_recursive", "progressive_order", "subdivision_rules", "subdivide", "sample_window"]


def progressive_order(points: np.ndarray) -> np.ndarray:
    """The farthest-point order of ``points`` (indices): first the point nearest their centroid,
    then each time the point farthest from those already taken (ties: the lowest index).

    >>> progressive_order(np.array([[0.5, 0.5], [0.0, 0.0], [0.45, 0.5], [1.0, 1.0]])).tolist()
    [0, 1, 3, 2]
    """
    pts = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    k = len(pts)
    if k == 0:
        return np.zeros(0, np.int64)
    first = int(np.argmin(((pts - pts.mean(axis=0)) ** 2).sum(axis=1)))
    order = [first]
    gap = ((pts - pts[first]) ** 2).sum(axis=1)
    for _ in range(k - 1):
        nxt = int(np.argmax(gap))
        order.append(nxt)
        gap = np.minimum(gap, ((pts - pts[nxt]) ** 2).sum(axis=1))
    return np.array(order, dtype=np.int64)


def subdivision_rules(colors: int, n: int, rng) -> np.ndarray:
    """Random subdivision rules of the ``C^4`` Wang tiles into ``n x n`` sub-tiles (see the
    module docstring): ``rules[t, b, a]`` is the colour of sub-lattice point ``(a, b)`` of tile
    ``t`` (eq. 2.5), y north.

    >>> r = subdivision_rules(2, 3, np.random.default_rng(0))
    >>> r.shape, bool((r[:, 0, 1:3] == r[:, 3, 1:3][[0] * 16]).any())
    ((16, 4, 4), True)
    """
    c = colors
    horizontal = rng.integers(c, size=(c, c, n - 1))  # by (west, east) end colours
    vertical = rng.integers(c, size=(c, c, n - 1))  # by (south, north)
    rules = rng.integers(c, size=(c**4, n + 1, n + 1)).astype(np.int64)
    t = np.arange(c**4)
    ne, se, sw, nw = t // c**3, t // c**2 % c, t // c % c, t % c
    rules[:, 0, 0], rules[:, 0, n], rules[:, n, n], rules[:, n, 0] = sw, se, ne, nw
    rules[:, 0, 1:n] = horizontal[sw, se]
    rules[:, n, 1:n] = horizontal[nw, ne]
    rules[:, 1:n, 0] = vertical[sw, nw]
    rules[:, 1:n, n] = vertical[se, ne]
    return rules


def build_recursive(problem: RecursiveTilesProblem, *, seed=None) -> RecursiveTileSet:
    """Build the recursive Wang tiles of ``problem`` (see the module docstring).

    Parameters
    ----------
    problem : RecursiveTilesProblem
    seed : int
        The same seed gives the same set.
    """
    if not isinstance(problem, RecursiveTilesProblem):
        raise InvalidProblem(f"expected a RecursiveTilesProblem, got {type(problem).__name__}")
    rng = rng_from_seed(seed)
    base = build_tiles(problem.base, seed=int(rng.integers(2**62)))
    ordered = {kind: [a[progressive_order(a)] for a in base.tiles[kind]] for kind in KINDS}
    base = PoissonTileSet(problem.base, ordered, seed=base.seed, stats=base.stats)
    rules = subdivision_rules(problem.colors, problem.subdivision, rng)
    return RecursiveTileSet(problem, base, rules, seed=seed if isinstance(seed, int) else None)


def subdivide(lat: np.ndarray, rules: np.ndarray, colors: int) -> np.ndarray:
    """The lattice colouring of depth ``k + 1`` from that of depth ``k`` (``lat[j, i]``: lattice
    point ``(i, j)``, y north): every tile replaced by its rule."""
    c, n = colors, rules.shape[1] - 1
    sw, se, ne, nw = lat[:-1, :-1], lat[:-1, 1:], lat[1:, 1:], lat[1:, :-1]
    r = rules[((ne * c + se) * c + sw) * c + nw]  # (h, w, n + 1, n + 1), [j, i, b, a]
    h, w = sw.shape
    out = np.empty((n * h + 1, n * w + 1), np.int64)
    out[:-1, :-1] = r[:, :, :n, :n].transpose(0, 2, 1, 3).reshape(n * h, n * w)
    out[-1, :-1] = r[-1, :, n, :n].reshape(n * w)
    out[:-1, -1] = r[:, -1, :n, n].reshape(n * h)
    out[-1, -1] = r[-1, -1, n, n]
    return out


def _density_at(grid: np.ndarray, local: np.ndarray, width: int, height: int) -> np.ndarray:
    """The density grid (row 0 at the top, stretched over the window) at window points."""
    rows, cols = grid.shape
    col = np.clip((local[:, 0] / width * cols).astype(np.int64), 0, cols - 1)
    row = np.clip(rows - 1 - (local[:, 1] / height * rows).astype(np.int64), 0, rows - 1)
    return grid[row, col]


def _far_from(kept: np.ndarray, pts: np.ndarray, reach: float, width: float, height: float) -> np.ndarray:
    """Whether each of ``pts`` is at least ``reach`` from all of ``kept`` (both in ``[0, width)
    x [0, height)``): a grid of at most 2048 x 2048 cells of side at least ``reach``."""
    side = max(reach, width / 2048, height / 2048)
    nx, ny = max(1, int(width / side)), max(1, int(height / side))
    side = max(width / nx, height / ny)
    keep = np.empty(len(pts), bool)
    return _k.KERNELS.pick(len(pts)).far_from(np.ascontiguousarray(kept), np.ascontiguousarray(pts), reach, side,
                                               nx, ny, keep)


def _mix(z: np.ndarray) -> np.ndarray:
    """splitmix64's finaliser (Steele, Lea and Flood 2014), on uint64 arrays (wrapping)."""
    z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
    z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    return z ^ (z >> np.uint64(31))


def _placement_hash(offsets: np.ndarray, bx: int, by: int, level: int, seed) -> np.ndarray:
    """A number in ``[0, 1)`` for each tile placement: a hash of its absolute depth-``level``
    lattice point ``(bx + ox, by + oy)`` (modulo 2**64, so the same in every window), the
    level and the seed. Ranks are ``(index + hash) / size``: progressive within a region, and
    the one-point regions of all lattice points do not share one rank (they would appear
    together, a lattice, as the density grows)."""
    salt = (int(seed or 0) * 0x9E3779B97F4A7C15 + level * 0xD1B54A32D192ED03) % 2**64
    x = offsets[:, 0].astype(np.uint64) + np.uint64(bx % 2**64)
    y = offsets[:, 1].astype(np.uint64) + np.uint64(by % 2**64)
    h = _mix(_mix(x ^ np.uint64(salt)) + y)
    return (h >> np.uint64(11)).astype(np.float64) / float(2**53)


def sample_window(problem: RecursiveWindowProblem, *, seed=None) -> RecursiveWindow:
    """The points of ``problem``'s window (see the module docstring).

    Parameters
    ----------
    problem : RecursiveWindowProblem
    seed : int
        Seed of the direct corner tiling's hashes: windows with the same seed agree where they
        overlap.

    Returns
    -------
    RecursiveWindow
        Points relative to ``(x0, y0)``, coarsest level first, then by rank.
    """
    ts, w = problem.tileset, problem.window
    p = ts.problem
    c, n = p.colors, p.subdivision
    boxes = problem.boxes()
    bw, bh = boxes[0][2], boxes[0][3]  # the block: the window and a margin of one tile
    lat = corner_lattice(direct_corner(w.x0 - 1, w.y0 - 1, bw, bh, colors=c, seed=seed, hash=problem.hash), c)
    kept = np.zeros((0, 2))
    points, levels, ranks = [], [], []
    for k, (bx, by, wk, hk) in enumerate(boxes):
        if k:  # the previous level's lattice, cut to this level's box, subdivided
            m, (px, py) = n ** (k - 1), boxes[k - 1][:2]
            lat = subdivide(lat[(by - py) * m:(by - py + hk) * m + 1, (bx - px) * m:(bx - px + wk) * m + 1],
                            ts.rules, c)
        offsets, frame, index, size = place_tiles(ts.base, lat)
        pts = (offsets + frame) / float(n**k)
        inside = (pts[:, 0] >= 0) & (pts[:, 0] < wk) & (pts[:, 1] >= 0) & (pts[:, 1] < hk)
        jitter = _placement_hash(offsets[inside], (w.x0 - 1 + bx) * n**k, (w.y0 - 1 + by) * n**k, k, seed)
        pts, rank = pts[inside] + [bx, by], (index[inside] + jitter) / size[inside]
        if len(kept):
            reach = p.distance_at(k) * (1 + SLACK)
            near = ((kept[:, 0] >= bx - reach) & (kept[:, 0] < bx + wk + reach) & (kept[:, 1] >= by - reach)
                    & (kept[:, 1] < by + hk + reach))
            far = _far_from(kept[near] - [bx, by], pts - [bx, by], reach, wk, hk)
            pts, rank = pts[far], rank[far]
        kept = np.vstack([kept, pts])
        points.append(pts)
        levels.append(np.full(len(pts), k, np.int8))
        ranks.append(rank)
    local = np.concatenate(points) - 1.0
    level, rank = np.concatenate(levels), np.concatenate(ranks)
    keep = (local[:, 0] >= 0) & (local[:, 0] < w.width) & (local[:, 1] >= 0) & (local[:, 1] < w.height)
    if problem.density is not None:
        d = _density_at(problem.density, local, w.width, w.height)
        hi = p.points * float(n * n) ** level
        lo = np.where(level == 0, 0.0, hi / (n * n))
        keep &= rank < (d - lo) / (hi - lo)
    local, level, rank = local[keep], level[keep], rank[keep]
    order = np.argsort(level + rank, kind="stable")  # level, then rank (rank < 1); ties: placement order
    return RecursiveWindow(w, np.ascontiguousarray(local[order]), level[order], rank[order], p.distance, n)
