"""Corner-based Poisson disk tiles: building a set, and the points of a window (class notes §4.3).

Building (§4.3, figures 4.5-4.11; regions as in :mod:`tilesolve.model.poisson`)
-----------------------------------------------------------------------------
1. **Corner tiles**, one per colour: ``N`` points on the unit torus by relaxation dart
   throwing (§4.2.4.2), optionally Lloyd steps (§4.2.4.3); the square ``[-a, a)^2`` is cut
   out of it (figure 4.5).
2. **Edge tiles**, one per pair of end colours: the two corner tiles are placed at the ends of
   the edge; the box ``[-a, 1 + a) x [-1/2, 1/2)`` around the edge is filled at density ``N``
   without entering the corner tiles, optionally relaxed with the corner points fixed and the
   others kept out of the corner tiles (the notes clip their displacements), and the strip
   ``[a, 1 - a) x [-d, d)`` is cut out (figure 4.7). Vertical edges are built the same way in
   the transposed frame.
3. **Interior tiles**, one per corner tile of the complete set: the cell is assembled with its
   four corner tiles and four edge tiles, and its interior region filled with the points that
   bring the cell to ``N`` (figure 4.10), optionally relaxed.

Every dart keeps at least ``d`` (:attr:`~tilesolve.model.poisson.PoissonTilesProblem.distance`,
with a relative slack of 1e-9) from every point it can meet in any tiling, so each tiling of
the plane is a Poisson disk distribution; relaxation dart throwing starts at the radius of the
hexagonal lattice (``rho = 1``) and gives up radius only when darts keep missing, so the
distances come out above ``d`` where there is room. Lloyd steps that would bring two points
closer than ``d`` are undone point by point. The notes repeat a tile whose radius falls short;
here the radius never falls short, and what can fall short is an interior tile's count (the
set's ``stats["short"]`` says by how many points).

Windows
-------
:func:`window_points` colours the lattice with the project's stochastic corner tilings
(:func:`tilesolve.constructive.stochastic.stochastic_window`: direct, §3.3.1, or scanline,
§3.2.2) and places the tiles: corner tiles on lattice points, edge tiles on edges, interior
tiles in cells; the points are returned relative to the window's bottom-left corner.

Examples
--------
>>> from tilesolve.model.poisson import PoissonTilesProblem
>>> ts = build_tiles(PoissonTilesProblem(1, 32, 0.7), seed=3)
>>> [len(ts.tiles[k]) for k in ("corner", "hedge", "vedge", "interior")]
[1, 1, 1, 1]
>>> w = window_points(ts, (100, -50, 4, 3), seed=1)
>>> w.n_points
384
"""

from __future__ import annotations

import numpy as np

from tilesolve._random import rng_from_seed
from tilesolve.constructive import _poisson_kernels as _k
from tilesolve.constructive.stochastic import stochastic_window
from tilesolve.errors import InvalidProblem
from tilesolve.model.poisson import SLACK, PoissonTilesProblem, PoissonTileSet, PoissonWindow, PoissonWindowProblem

__all__ = ["build_tiles", "window_points", "place_tiles", "corner_lattice", "dart_throwing", "lloyd", "object_distribution"]

#: The radius shrinks by this factor when darts keep missing (McCool and Fiume 1992).
SHRINK = 0.97
#: Darts in a row that may miss before the radius shrinks.
PATIENCE = 300
#: Darts in a row that may miss at the smallest radius before a fill gives up.
FINAL = 30000
#: Further tries for an interior tile that falls short of its count.
RETRIES = 7
#: Random samples per point of a Monte Carlo Lloyd step.
LLOYD_SAMPLES = 64

_TORUS = np.array([[0.0, 1.0, 0.0, 1.0]])
_NO_BOXES = np.zeros((0, 4))


def _fill(fixed, allow, forbid, target: int, r0: float, rmin: float, seed: int, torus: bool = False):
    out = np.empty((max(target, 0), 2))
    if target <= 0:
        return out
    ker = _k.KERNELS.pick(target)
    n, _ = ker.dart_fill(np.ascontiguousarray(fixed, dtype=np.float64), allow, forbid, int(target), float(r0),
                         float(rmin), SHRINK, PATIENCE, FINAL, torus, int(seed), out)
    return out[:n]


def dart_throwing(n: int, distance: float, *, seed=None, patience: int = PATIENCE) -> np.ndarray:
    """Plain dart throwing on the unit torus (Cook 1986; §4.2.4.1): darts at one distance
    until ``patience`` in a row miss, at most ``n`` points. The baseline the tiles are compared
    with.

    >>> p = dart_throwing(50, 0.08, seed=1)
    >>> p.shape[1], len(p) <= 50
    (2, True)
    """
    out = np.empty((n, 2))
    seed32 = int(rng_from_seed(seed).integers(2**31))
    m, _ = _k.KERNELS.pick(n).dart_fill(np.zeros((0, 2)), _TORUS, _NO_BOXES, n, distance, distance, SHRINK,
                                          patience, patience, True, seed32, out)
    return out[:m]


def _allowed(points: np.ndarray, allow, forbid) -> np.ndarray:
    ok = np.zeros(len(points), bool)
    for x0, x1, y0, y1 in allow:
        ok |= (points[:, 0] >= x0) & (points[:, 0] < x1) & (points[:, 1] >= y0) & (points[:, 1] < y1)
    for x0, x1, y0, y1 in forbid:
        ok &= ~((points[:, 0] >= x0) & (points[:, 0] < x1) & (points[:, 1] >= y0) & (points[:, 1] < y1))
    return ok


def lloyd(moving, fixed, allow, forbid, distance: float, steps: int, rng, torus: bool = False) -> np.ndarray:
    """``steps`` Lloyd steps (§4.2.4.3) of ``moving`` among ``fixed``, inside ``allow`` less ``forbid``.

    Each point moves to the centroid of its Voronoi cell, estimated from random samples of the
    region (``scipy.spatial.cKDTree`` finds each sample's nearest point): the cells are clipped
    by the region and by the fixed points, which ``scipy.spatial.Voronoi`` (unbounded cells,
    no clipping) does not do. A point whose move would leave the region stays (the notes clip
    such moves); moves that would bring a point closer than ``distance`` to another are undone.
    """
    from scipy.spatial import cKDTree

    pts = np.array(moving, dtype=np.float64)
    if steps == 0 or len(pts) == 0:
        return pts
    m = len(pts)
    fixed = np.asarray(fixed, dtype=np.float64).reshape(-1, 2)
    area = sum((b[1] - b[0]) * (b[3] - b[2]) for b in allow)
    box = 1.0 if torus else None
    for _ in range(steps):
        sites = np.vstack([pts, fixed % 1.0 if torus else fixed])
        tree = cKDTree(sites, boxsize=box)
        k = LLOYD_SAMPLES * m
        pick = rng.choice(len(allow), size=k, p=[(b[1] - b[0]) * (b[3] - b[2]) / area for b in allow])
        lo, hi = allow[pick][:, [0, 2]], allow[pick][:, [1, 3]]
        samples = lo + rng.random((k, 2)) * (hi - lo)
        samples = samples[_allowed(samples, allow, forbid)]
        _, owner = tree.query(samples)
        mine = owner < m
        offs = samples[mine] - pts[owner[mine]]
        if torus:
            offs -= np.floor(offs + 0.5)
        counts = np.bincount(owner[mine], minlength=m)
        shift = np.stack([np.bincount(owner[mine], offs[:, i], minlength=m) for i in (0, 1)], axis=1)
        new = pts + shift / np.maximum(counts, 1)[:, None]
        if torus:
            new %= 1.0
        inside = _allowed(new, allow, forbid)
        new[~inside] = pts[~inside]
        while True:  # undo the moves that bring two points too close, until none does
            tree = cKDTree(np.vstack([new, sites[m:]]), boxsize=box)
            pairs = tree.query_pairs(distance, output_type="ndarray")
            bad = np.unique(pairs[pairs < m]) if len(pairs) else np.zeros(0, np.int64)
            bad = bad[(new[bad] != pts[bad]).any(axis=1)]
            if len(bad) == 0:
                break
            new[bad] = pts[bad]
        pts = new
    return pts


def _box(x0, x1, y0, y1) -> list[float]:
    return [x0, x1, y0, y1]


def _edge(problem: PoissonTilesProblem, west: np.ndarray, east: np.ndarray, seed: int, rng) -> np.ndarray:
    """A horizontal edge tile between corner tiles ``west`` at (0, 0) and ``east`` at (1, 0)."""
    a, d, n = problem.corner_half, problem.distance, problem.points
    dd = d * (1 + SLACK)
    fixed = np.vstack([west, east + [1.0, 0.0]])
    allow = np.array([_box(-a, 1 + a, -0.5, 0.5)])
    forbid = np.array([_box(-a, a, -a, a), _box(1 - a, 1 + a, -a, a)])
    target = round(n * ((1 + 2 * a) - 8 * a * a))
    pts = _fill(fixed, allow, forbid, target, 2 * problem.r_max, dd, seed)
    pts = lloyd(pts, fixed, allow, forbid, dd, problem.lloyd, rng)
    keep = (pts[:, 0] >= a) & (pts[:, 0] < 1 - a) & (pts[:, 1] >= -d) & (pts[:, 1] < d)
    return pts[keep]


def build_tiles(problem: PoissonTilesProblem, *, seed=None) -> PoissonTileSet:
    """Build the ``C + 2 C^2 + C^4`` tiles of ``problem`` (see the module docstring).

    Parameters
    ----------
    problem : PoissonTilesProblem
    seed : int
        The same seed gives the same set, point for point.

    Returns
    -------
    PoissonTileSet
        ``stats``: ``short`` (points the interior tiles lack, summed), ``min_distance`` (the
        least distance the build measured between a new point and any point it can meet, as
        a relative radius ``rho_built``).
    """
    if not isinstance(problem, PoissonTilesProblem):
        raise InvalidProblem(f"expected a PoissonTilesProblem, got {type(problem).__name__}")
    rng = rng_from_seed(seed)
    c, n, a, d = problem.colors, problem.points, problem.corner_half, problem.distance
    dd = d * (1 + SLACK)
    r0 = 2 * problem.r_max
    seeds = iter(rng.integers(2**31, size=problem.n_tiles).tolist())
    corners = []
    for _ in range(c):
        pts = _fill(np.zeros((0, 2)), _TORUS, _NO_BOXES, n, r0, dd, next(seeds), torus=True)
        pts = lloyd(pts, np.zeros((0, 2)), _TORUS, _NO_BOXES, dd, problem.lloyd, rng, torus=True)
        pts = (pts + 0.5) % 1.0 - 0.5  # the torus around the lattice point; cut [-a, a)^2
        corners.append(pts[((pts >= -a) & (pts < a)).all(axis=1)])
    hedge = [_edge(problem, corners[w], corners[e], next(seeds), rng) for w in range(c) for e in range(c)]
    vedge = [_edge(problem, corners[s][:, ::-1], corners[t][:, ::-1], next(seeds), rng)[:, ::-1].copy()
             for s in range(c) for t in range(c)]
    interior, short = [], 0
    allow = np.array([_box(d, 1 - d, d, 1 - d)])
    forbid = np.array([_box(-a, a, -a, a), _box(1 - a, 1 + a, -a, a), _box(1 - a, 1 + a, 1 - a, 1 + a),
                       _box(-a, a, 1 - a, 1 + a)])
    for idx in range(c**4):
        ne, se, sw, nw = idx // c**3, idx // c**2 % c, idx // c % c, idx % c
        fixed = np.vstack([corners[sw], corners[se] + [1, 0], corners[ne] + [1, 1], corners[nw] + [0, 1],
                           hedge[sw * c + se], hedge[nw * c + ne] + [0, 1],
                           vedge[sw * c + nw], vedge[se * c + ne] + [1, 0]])
        inside = int(((fixed >= 0) & (fixed < 1)).all(axis=1).sum())
        target = n - inside
        pts = _fill(fixed, allow, forbid, target, r0, dd, next(seeds))
        for retry in range(RETRIES):  # the notes repeat a tile that falls short; keep the fullest
            if len(pts) >= target:
                break
            again = _fill(fixed, allow, forbid, target, r0, dd, int(rng.integers(2**31)))
            pts = again if len(again) > len(pts) else pts
        short += max(0, target - len(pts))
        interior.append(lloyd(pts, fixed, allow, forbid, dd, problem.lloyd, rng))
    tiles = {"corner": corners, "hedge": hedge, "vedge": vedge, "interior": interior}
    return PoissonTileSet(problem, tiles, seed=seed if isinstance(seed, int) else None, stats={"short": short})


def _padded(arrays: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    k = max((len(a) for a in arrays), default=0)
    out = np.zeros((len(arrays), max(k, 1), 2))
    for i, a in enumerate(arrays):
        out[i, :len(a)] = a
    return out, np.array([len(a) for a in arrays], dtype=np.int64)


def _place(origins: np.ndarray, which: np.ndarray, arrays: list[np.ndarray]):
    """The points of tiles ``arrays[which[i]]`` at integer ``origins[i]``: each point's origin,
    its coordinates in its tile's frame, its index in its tile and its tile's size."""
    pad, counts = _padded(arrays)
    mask = np.arange(pad.shape[1])[None, :] < counts[which][:, None]
    index = np.broadcast_to(np.arange(pad.shape[1])[None, :], mask.shape)[mask]
    size = np.broadcast_to(counts[which][:, None], mask.shape)[mask]
    return np.broadcast_to(origins[:, None, :], pad[which].shape)[mask], pad[which][mask], index, size


def window_points(tileset: PoissonTileSet, window, *, tiling: str = "direct", variant: str = "complete",
                  hash: str = "long", seed=None) -> PoissonWindow:
    """The points of a tiling with ``tileset`` in ``window`` (see the module docstring).

    Parameters
    ----------
    tileset : PoissonTileSet
    window : Window or (x0, y0, width, height)
        Cells ``[x0, x0 + width) x [y0, y0 + height)``, y north.
    tiling, variant, hash
        The stochastic corner tiling that colours the lattice (:class:`PoissonWindowProblem`).
    seed : int
        Seed of the tiling's hashes: windows with the same seed agree where they overlap
        (direct tiling; scanline on the complete set).

    Returns
    -------
    PoissonWindow
        Points relative to ``(x0, y0)``, ordered by kind of tile, then by tile position.
    """
    problem = PoissonWindowProblem(tileset, window, tiling, variant, hash)
    offsets, frame = _window_parts(problem, seed)
    return PoissonWindow(problem.window, np.ascontiguousarray(offsets + frame), tileset.problem.distance)


def corner_lattice(grid: np.ndarray, colors: int) -> np.ndarray:
    """The lattice colouring of a window of a corner tiling: ``lat[j, i]`` is the colour of
    lattice point ``(x0 + i, y0 + j)`` (y north) of the ``(h, w)`` grid of eq. 2.5 tiles
    ``grid`` (row 0 at the top, as :func:`~tilesolve.constructive.stochastic.stochastic_window`
    gives it).

    >>> corner_lattice(np.array([[0b0110]]), 2).tolist()  # NE 0, SE 1, SW 1, NW 0
    [[1, 1], [0, 0]]
    """
    c = colors
    grid = np.asarray(grid, dtype=np.int64)[::-1]  # row j: y0 + j
    ne, se, sw, nw = grid // c**3, grid // c**2 % c, grid // c % c, grid % c
    h, wd = grid.shape
    lat = np.empty((h + 1, wd + 1), np.int64)
    lat[:h, :wd] = sw
    lat[:h, wd] = se[:, -1]
    lat[h, :wd] = nw[-1, :]
    lat[h, wd] = ne[-1, -1]
    return lat


def place_tiles(tileset: PoissonTileSet, lat: np.ndarray) -> tuple[np.ndarray, ...]:
    """Every point of the tiles a coloured lattice places (§4.3), none cropped.

    Parameters
    ----------
    tileset : PoissonTileSet
    lat : (h + 1, w + 1) int array
        ``lat[j, i]``: the colour of lattice point ``(i, j)`` (y north).

    Returns
    -------
    (offsets, frame, index, size)
        Each point's tile origin (integer, float64) and its coordinates in its tile's frame
        (their sum is the point), the point's index in its tile and the number of points of its
        tile; points ordered by kind of tile, then by tile position.
    """
    c = tileset.problem.colors
    lat = np.asarray(lat, dtype=np.int64)
    sw, se, ne, nw = lat[:-1, :-1], lat[:-1, 1:], lat[1:, 1:], lat[1:, :-1]
    grid = ((ne * c + se) * c + sw) * c + nw
    jj, ii = np.mgrid[0:lat.shape[0], 0:lat.shape[1]]
    lattice = np.stack([ii, jj], axis=-1).astype(np.float64)
    t = tileset.tiles
    parts = [
        _place(lattice.reshape(-1, 2), lat.ravel(), t["corner"]),
        _place(lattice[:, :-1].reshape(-1, 2), (lat[:, :-1] * c + lat[:, 1:]).ravel(), t["hedge"]),
        _place(lattice[:-1, :].reshape(-1, 2), (lat[:-1, :] * c + lat[1:, :]).ravel(), t["vedge"]),
        _place(lattice[:-1, :-1].reshape(-1, 2), grid.ravel(), t["interior"]),
    ]
    return tuple(np.concatenate([part[i] for part in parts]) for i in range(4))


def _window_parts(problem: PoissonWindowProblem, seed) -> tuple[np.ndarray, np.ndarray]:
    """The points of a window as integer offsets from its corner (float64) plus coordinates in
    their tile's frame: their sum is the point."""
    w, tileset = problem.window, problem.tileset
    c = tileset.problem.colors
    grid = stochastic_window("corner", problem.tiling, (w.x0, w.y0, w.width, w.height), colors=c, seed=seed,
                             variant=problem.variant, hash=problem.hash)
    h, wd = grid.shape
    offsets, frame, _, _ = place_tiles(tileset, corner_lattice(grid, c))
    pts = offsets + frame
    keep = (pts[:, 0] >= 0) & (pts[:, 0] < wd) & (pts[:, 1] >= 0) & (pts[:, 1] < h)
    return offsets[keep], frame[keep]




def object_distribution(tileset: PoissonTileSet, xy, *, origin=(0, 0), seed=None, hash: str = "long") -> dict:
    """The 2-D procedural object distribution function (class notes §6.6.2.1, figure 6.5).

    For each point of evaluation ``origin + xy[i]``, the closest point of the tiled Poisson
    disk distribution (direct corner tiling, random access: the same answer whatever else is
    evaluated), found among the tile of the point and its eight neighbours (exact: every
    evaluation here finds a point within one tile side, which the builder's density ensures and
    this function checks).

    Parameters
    ----------
    tileset : PoissonTileSet
    xy : (n, 2) array_like
        Points of evaluation relative to ``origin`` (tile units, y north).
    origin : (int, int)
        An integer offset, so that points far from the origin keep full precision.
    seed, hash
        The direct corner tiling's hash (the texture's randomisation, §6.6.2.1).

    Returns
    -------
    dict
        ``inside`` (bool: within the Poisson disk, radius ``distance / 2``, of the closest point),
        ``closest`` (its coordinates relative to ``origin``), ``distance`` (to it), ``local``
        (the point of evaluation in the disk's frame: offset over the disk radius, so ``inside``
        is ``|local| < 1``), ``id`` (``(n, 3)`` int64: the cell of the closest point, relative to
        ``origin``, and its rank among that cell's points in lexicographic order).
    """
    from scipy.spatial import cKDTree

    q = np.asarray(xy, dtype=np.float64).reshape(-1, 2)
    if not np.isfinite(q).all():
        raise InvalidProblem("points of evaluation must be finite")
    ox, oy = (int(v) for v in origin)
    cells = np.floor(q).astype(np.int64)
    r = tileset.problem.distance / 2
    n = len(q)
    out = {"inside": np.zeros(n, bool), "closest": np.zeros((n, 2)), "distance": np.zeros(n),
           "local": np.zeros((n, 2)), "id": np.zeros((n, 3), np.int64)}
    if n == 0:
        return out
    ucells, group = np.unique(cells, axis=0, return_inverse=True)
    group = group.ravel()
    lo, hi = ucells.min(axis=0) - 1, ucells.max(axis=0) + 2
    if int(np.prod(hi - lo)) <= max(64, 9 * len(ucells)):  # one window around them all
        blocks = [(lo, np.arange(n))]
    else:  # far apart: a 3 x 3 block around each cell
        blocks = [(ucells[g] - 1, np.flatnonzero(group == g)) for g in range(len(ucells))]
    for corner, which in blocks:
        size = (hi - lo) if len(blocks) == 1 else np.array([3, 3])
        problem = PoissonWindowProblem(tileset, (ox + int(corner[0]), oy + int(corner[1]), int(size[0]), int(size[1])),
                                       hash=hash)
        offsets, frame = _window_parts(problem, seed)
        pts = offsets + frame
        cell = np.floor(pts).astype(np.int64)
        order = np.lexsort((pts[:, 1], pts[:, 0], cell[:, 1], cell[:, 0]))
        pts, cell, offsets, frame = pts[order], cell[order], offsets[order], frame[order]
        first = np.r_[True, (cell[1:] != cell[:-1]).any(axis=1)]
        rank = np.arange(len(pts)) - np.maximum.accumulate(np.where(first, np.arange(len(pts)), 0))
        _, k = cKDTree(pts).query(q[which] - corner)
        # in the frame of the point of evaluation's own cell, so that every window gives the same bits
        own = cells[which]
        p = (offsets[k] + corner - own) + frame[k]
        f = q[which] - own
        dist = np.hypot(f[:, 0] - p[:, 0], f[:, 1] - p[:, 1])
        if (dist > 1).any():
            from tilesolve.errors import InternalError

            raise InternalError("a point of evaluation lies farther than one tile side from every point of the set")
        out["distance"][which] = dist
        out["closest"][which] = own + p
        out["local"][which] = (f - p) / r
        out["id"][which] = np.column_stack([cell[k] + corner, rank[k]])
    out["inside"] = out["distance"] < r
    return out
