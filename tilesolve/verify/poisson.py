"""Independent checks and measures of Poisson disk distributions (class notes §4.2, §4.3).

Written from the definitions, sharing no code with the builder
(:mod:`tilesolve.constructive.poisson`):

* :func:`point_violations`: a point set is a Poisson disk distribution at distance ``d`` when
  no two points are closer than ``d`` (§4.2.1); a grid of ``d x d`` cells (numpy, or for a
  large set a compiled loop of its own, :mod:`tilesolve.verify._poisson_kernel`; it does what a
  KD-tree's range query would) finds every closer pair in any window. Points must also lie in
  their window.
* :func:`tileset_violations`: every tile's points lie in its modified region (§4.3, figure
  4.3(b); :mod:`tilesolve.model.poisson`), and the tiles of *every* 2 x 2 block of cells are a
  Poisson disk distribution: any two points closer than ``d < 1/2`` lie in a common 2 x 2
  block, so checking all ``C^9`` colourings of its 3 x 3 lattice points checks every tiling.
  Sets with more than ``max_blocks`` colourings are checked on that many random ones.
* :func:`placed_points`: the points a coloured lattice of corner tiles places, from the
  regions' definition (a window file's points are re-derived with it from its set and the
  lattice its seed colours), and :func:`match_violations`: the points a file holds against
  those re-derived, compared exactly (a point deleted, added or moved is found).
* :func:`relative_radius` (eq. 4.2-4.3) and :func:`radial_spectrum` (the periodogram, its
  radial average and anisotropy, Ulichney 1987; §4.2.2).

>>> import numpy as np
>>> pts = np.array([[0.1, 0.1], [0.3, 0.1], [0.35, 0.12]])
>>> [v.message for v in point_violations(pts, 0.1, 1, 1)]
['points 1 and 2 are 0.05385 apart, closer than 0.1']
"""

from __future__ import annotations

import math

import numpy as np

from tilesolve.model.poisson import PoissonTileSet, r_max
from tilesolve.verify import _poisson_kernel
from tilesolve.verify.dappled import Violation

__all__ = ["point_violations", "tileset_violations", "placed_points", "match_violations", "window_size_violations",
           "cell_counts", "shortfall_violations", "min_distance", "relative_radius", "radial_spectrum", "periodogram"]

#: Violations listed at most (the count is always given).
MAX_LISTED = 20


#: A d x d cell holds at most 4 points pairwise d apart (its four quarters hold one each).
_CELL_MAX = 4
#: Neighbouring cells a pair may span, each pair of cells once: itself, E, NW, N, NE.
_OFFSETS = ((0, 0), (1, 0), (-1, 1), (0, 1), (1, 1))


def _close_pairs(points: np.ndarray, distance: float, *, kernel=None) -> np.ndarray:
    """Every pair ``(i, j)``, ``i < j``, of ``points`` closer than ``distance``, sorted.

    A uniform grid of cells of side ``distance``: a close pair lies in one cell or in two
    neighbouring ones. A cell of more than four points holds a close pair by the pigeonhole
    principle; there the first five points are compared, so that a file of many equal points
    costs no more than a valid one. The neighbouring cells are scanned with numpy, or for a large
    set by the compiled loop of :mod:`tilesolve.verify._poisson_kernel` (``kernel``: that loop,
    or None to choose); either scan gives candidates, kept here by their exact distance.
    """
    n = len(points)
    if n < 2:
        return np.zeros((0, 2), np.int64)
    cell = np.floor((points - points.min(axis=0)) / distance).astype(np.int64)
    rows = int(cell[:, 1].max()) + 3
    key = (cell[:, 0] + 1) * rows + (cell[:, 1] + 1)
    order = np.argsort(key, kind="stable")
    skey = key[order]
    start = np.flatnonzero(np.r_[True, skey[1:] != skey[:-1]])  # runs of one cell in the sorted keys
    ukey, count = skey[start], np.diff(np.r_[start, n])
    kernel = kernel or _poisson_kernel.compiled(n, distance)
    if kernel is not None:
        offsets = [dx * rows + dy for dx, dy in _OFFSETS]
        pairs = _poisson_kernel.candidates(kernel, points, order, ukey, start, count, offsets, _CELL_MAX, distance)
    else:
        pairs = _numpy_scan(points, distance, rows, order, skey, ukey, start, count)
    pairs = np.sort(pairs, axis=1)
    if len(pairs) == 0:
        return pairs
    gap = np.hypot(*(points[pairs[:, 0]] - points[pairs[:, 1]]).T)
    return np.unique(pairs[gap < distance], axis=0).reshape(-1, 2)


def _numpy_scan(points, distance, rows, order, skey, ukey, start, count) -> np.ndarray:
    """The candidate pairs of :func:`_close_pairs`, by whole-array numpy operations."""
    found = [np.zeros((0, 2), np.int64)]
    for c in np.flatnonzero(count > _CELL_MAX):  # pigeonhole: five points hold a close pair
        members = order[start[c]:start[c] + _CELL_MAX + 1]
        a, b = np.triu_indices(len(members), 1)
        found.append(np.stack([members[a], members[b]], axis=1))
    keep = np.repeat(count <= _CELL_MAX, count)  # points of cells that are not overfull, in key order
    for dx, dy in _OFFSETS:
        target = skey + dx * rows + dy
        at = np.searchsorted(ukey, target)
        at[at >= len(ukey)] = 0
        hit = (ukey[at] == target) & keep & (count[at] <= _CELL_MAX)
        src = np.flatnonzero(hit)
        reps = count[at[src]]
        i = np.repeat(src, reps)
        j = start[np.repeat(at[src], reps)] + (np.arange(reps.sum()) - np.repeat(np.cumsum(reps) - reps, reps))
        if (dx, dy) == (0, 0):
            i, j = i[i < j], j[i < j]
        pi, pj = order[i], order[j]
        gap = np.hypot(*(points[pi] - points[pj]).T)
        close = gap < distance
        found.append(np.stack([pi[close], pj[close]], axis=1))
    return np.concatenate(found)


def point_violations(points, distance: float, width: float, height: float) -> list[Violation]:
    """Every way ``points`` (relative to the window's bottom-left corner) fail to be a Poisson
    disk distribution at ``distance`` inside the ``width x height`` window."""
    pts = np.asarray(points, dtype=np.float64)
    if pts.ndim != 2 or (len(pts) and pts.shape[1] != 2):
        return [Violation("shape", f"points must be an (n, 2) array, got shape {pts.shape}")]
    pts = pts.reshape(-1, 2)
    if not np.isfinite(pts).all():
        return [Violation("shape", "points must be finite numbers")]
    out = []
    outside = np.flatnonzero((pts[:, 0] < 0) | (pts[:, 0] >= width) | (pts[:, 1] < 0) | (pts[:, 1] >= height))
    out += [Violation("window", f"point {i} at ({pts[i, 0]:.6g}, {pts[i, 1]:.6g}) lies outside the window")
            for i in outside[:MAX_LISTED]]
    pairs = _close_pairs(pts, distance)
    for i, j in pairs[:MAX_LISTED]:
        gap = float(np.hypot(*(pts[i] - pts[j])))
        out.append(Violation("distance", f"points {i} and {j} are {gap:.4g} apart, closer than {distance:.6g}"))
    if len(pairs) > MAX_LISTED:
        out.append(Violation("distance", f"{len(pairs):,} pairs in all are closer than {distance:.6g}"))
    return out


def min_distance(points) -> float:
    """The least distance between two of ``points`` (``inf`` for fewer than two)."""
    pts = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    if len(pts) < 2:
        return math.inf
    reach = max(float(np.ptp(pts, axis=0).max()) / math.sqrt(len(pts)), 1e-300)  # about the mean spacing
    while len(_close_pairs(pts, reach)) == 0:
        reach *= 2
    while True:  # shrink to the least gap found, until no pair is closer (then no cell is overfull)
        pairs = _close_pairs(pts, reach)
        if len(pairs) == 0:
            return reach
        reach = float(np.hypot(*(pts[pairs[:, 0]] - pts[pairs[:, 1]]).T).min())
        if reach == 0.0:  # two equal points
            return 0.0


def relative_radius(points, area: float) -> float:
    """``rho = r / r_max`` (eq. 4.3) of ``points`` over ``area``: half the least distance over
    the largest radius of that many points a unit area (eq. 4.2, scaled to the area)."""
    n = len(points)
    if n < 2:
        return 0.0
    return (min_distance(points) / 2) / (r_max(n / area))


def _regions(ts: PoissonTileSet):
    """``kind -> (x0, x1, y0, y1, [excluded boxes])`` of the modified regions (§4.3)."""
    d, a = ts.problem.distance, ts.problem.corner_half
    corners = [(-a, a, -a, a), (1 - a, 1 + a, -a, a), (1 - a, 1 + a, 1 - a, 1 + a), (-a, a, 1 - a, 1 + a)]
    return {"corner": (-a, a, -a, a, []), "hedge": (a, 1 - a, -d, d, []), "vedge": (-d, d, a, 1 - a, []),
            "interior": (d, 1 - d, d, 1 - d, corners)}


def placed_points(ts: PoissonTileSet, lat) -> np.ndarray:
    """Every point the tiles of a coloured lattice place (§4.3, from the regions' definition):
    ``lat[j, i]`` is the colour of lattice point ``(i, j)`` (y north); its corner tile sits at
    ``(i, j)``, the edge tiles of its east and north edges and the interior tile of the cell
    ``[i, i + 1) x [j, j + 1)`` start there too. A point ``(x, y)`` of a tile is placed at
    ``(i + x, j + y)``; points are grouped by tile, not cropped."""
    c, t = ts.problem.colors, ts.tiles
    lat = np.asarray(lat, dtype=np.int64)
    sw, se, ne, nw = lat[:-1, :-1], lat[:-1, 1:], lat[1:, 1:], lat[1:, :-1]
    groups = (("corner", lat), ("hedge", lat[:, :-1] * c + lat[:, 1:]), ("vedge", lat[:-1, :] * c + lat[1:, :]),
              ("interior", ((ne * c + se) * c + sw) * c + nw))
    parts = [np.zeros((0, 2))]
    for kind, index in groups:
        for k in np.unique(index):
            j, i = np.nonzero(index == k)
            at = np.stack([i, j], axis=1).astype(np.float64)
            parts.append((at[:, None, :] + t[kind][k][None, :, :]).reshape(-1, 2))
    return np.concatenate(parts)


def match_violations(claimed, rebuilt, what: str) -> list[Violation]:
    """Every way the rows of ``claimed`` (points, with any further columns) differ from those of
    ``rebuilt``, compared exactly and as multisets: rows missing from ``claimed``, rows that are
    not among ``rebuilt`` (a row moved is both). ``what`` names where ``rebuilt`` came from."""
    a, b = (np.asarray(x, dtype=np.float64) for x in (claimed, rebuilt))
    width = next((x.shape[1] for x in (a, b) if x.ndim == 2 and x.size), 0)
    a, b = (np.ascontiguousarray(x.reshape(len(x), -1) if x.size else x.reshape(len(x), width)) for x in (a, b))
    if a.shape == b.shape and (not a.size or np.array_equal(a[np.lexsort(a.T[::-1])], b[np.lexsort(b.T[::-1])])):
        return []
    if a.shape[1] != b.shape[1]:
        return [Violation("seed", f"rows of {a.shape[1]} numbers, but {what} gives rows of {b.shape[1]}")]
    from collections import Counter

    have, want = Counter(map(bytes, a)), Counter(map(bytes, b))
    out = []
    for rows, says in ((want - have, f"{{n:,}} point(s) {what} gives are missing from the file"),
                       (have - want, f"{{n:,}} point(s) of the file are not among those {what} gives")):
        if rows:
            first = np.frombuffer(next(iter(rows)), dtype=np.float64)
            out.append(Violation("seed", says.format(n=sum(rows.values()))
                                 + f", e.g. ({', '.join(f'{v:.9g}' for v in first)})"))
    if not out:
        out.append(Violation("seed", f"{len(a):,} points in the file, {len(b):,} from {what}"))
    return out


def window_size_violations(interior, cells: int, claimed: int) -> list[Violation]:
    """Whether a window of ``cells`` lattice cells can hold the ``claimed`` points a file lists,
    before they are re-derived (2-D or 3-D sets alike): each cell holds every point of its own
    interior tile (``interior``: the set's interior tiles, whose regions lie inside the cell),
    so a window of more cells than the file's points allow is refused unseen, and an absurd window
    of a small file costs nothing. A set with an empty interior tile bounds nothing: its window
    is re-derived only while it has few cells beside the file's points."""
    least = min((len(t) for t in interior), default=0)
    if cells * least > claimed:
        return [Violation("seed", f"the window's {cells:,} cells hold at least {cells * least:,} points (every "
                                  f"interior tile of the set holds {least} or more); the file holds {claimed:,}")]
    if least == 0 and cells > 4 * claimed + _FEW_CELLS:
        return [Violation("size", f"NOT confirmed: the set has an empty interior tile, so its window of {cells:,} "
                                  f"cells is not bounded by the file's {claimed:,} points; it was not re-derived")]
    return []


#: Cells a window of a set with an empty interior tile may have beyond four for each point of its file.
_FEW_CELLS = 1 << 16


def cell_counts(ts: PoissonTileSet) -> np.ndarray:
    """The points a unit cell of any tiling holds, for each colouring of its corners (eq. 2.5's
    index ``((NE C + SE) C + SW) C + NW``): its interior tile and the parts of the corner and edge
    tiles around it that fall inside ``[0, 1)^2``, placed from the regions' definition
    (:func:`placed_points` on the cell's 2 x 2 lattice points)."""
    c = ts.problem.colors
    out = np.zeros(c**4, np.int64)
    for k in range(c**4):
        ne, se, sw, nw = k // c**3, k // c**2 % c, k // c % c, k % c
        pts = placed_points(ts, np.array([[sw, se], [nw, ne]]))
        out[k] = int(((pts >= 0) & (pts < 1)).all(axis=1).sum())
    return out


def shortfall_violations(ts, counts=cell_counts) -> list[Violation]:
    """A set's stated shortfall (``stats["short"]``, the points its cells lack beside ``N`` a
    cell, summed over the colourings; the build's own count, shown when the set is built) must be
    the one its tiles give (``counts(ts)``, the points of a cell under each colouring:
    :func:`cell_counts`, or the 3-D sets' ``cell_counts3``): a set whose points were deleted
    cannot keep claiming ``N`` points a tile. A set that states none (built in memory without
    stats) is not held to one."""
    if "short" not in ts.stats:
        return []
    stated = ts.stats["short"]
    short = int(np.maximum(ts.problem.points - counts(ts), 0).sum())
    if isinstance(stated, bool) or not isinstance(stated, int) or stated != short:
        return [Violation("short", f"the set states its cells lack {stated!r} points in all (N = "
                                   f"{ts.problem.points} a cell), but its tiles lack {short:,}")]
    return []


def tileset_violations(ts: PoissonTileSet, *, max_blocks: int = 4096, seed: int = 0) -> list[Violation]:
    """Every way the tile set fails: a point outside its region, or two points of some tiling
    closer than the set's distance (see the module docstring)."""
    if not isinstance(ts, PoissonTileSet):
        return [Violation("shape", "the answer is no Poisson tile set")]
    out = []
    for kind, (x0, x1, y0, y1, holes) in _regions(ts).items():
        for k, pts in enumerate(ts.tiles[kind]):
            bad = (pts[:, 0] < x0) | (pts[:, 0] >= x1) | (pts[:, 1] < y0) | (pts[:, 1] >= y1)
            for hx0, hx1, hy0, hy1 in holes:
                bad |= (pts[:, 0] >= hx0) & (pts[:, 0] < hx1) & (pts[:, 1] >= hy0) & (pts[:, 1] < hy1)
            if not np.isfinite(pts).all() or bad.any():
                out.append(Violation("region", f"{kind} tile {k}: {int(bad.sum())} points outside its region"))
    if out:
        return out[:MAX_LISTED]
    out += shortfall_violations(ts)
    c = ts.problem.colors
    n_blocks = c**9
    if n_blocks <= max_blocks:
        colourings = (np.arange(n_blocks)[:, None] // c ** np.arange(9)[None, :]) % c
    else:
        colourings = np.random.default_rng(seed).integers(c, size=(max_blocks, 9))
    for col in colourings:
        pts = placed_points(ts, col.reshape(3, 3))
        pairs = _close_pairs(pts, ts.problem.distance)
        if len(pairs):
            i, j = pairs[0]
            gap = float(np.hypot(*(pts[i] - pts[j])))
            out.append(Violation("distance", f"lattice colours {col.tolist()}: two points {gap:.4g} apart, closer "
                                             f"than {ts.problem.distance:.6g}"))
            if len(out) >= MAX_LISTED:
                break
    return out


def periodogram(points, side: float, *, k_max: int = 64) -> np.ndarray:
    """The periodogram ``P(k) = |sum_j exp(-2 pi i k . x_j / side)|^2 / n`` of points in
    ``[0, side)^2`` over integer ``k`` with ``|k_x|, |k_y| <= k_max`` (``power[k_x + k_max, k_y +
    k_max]``), averaged over the point sets given (``points``: one ``(n, 2)`` array or a list)."""
    sets = [points] if isinstance(points, np.ndarray) else list(points)
    k = np.arange(-k_max, k_max + 1)
    power = np.zeros((len(k), len(k)))
    for pts in sets:
        pts = np.asarray(pts, dtype=np.float64).reshape(-1, 2)
        ex = np.exp(-2j * np.pi * np.outer(pts[:, 0] / side, k))
        ey = np.exp(-2j * np.pi * np.outer(pts[:, 1] / side, k))
        power += np.abs(ex.T @ ey) ** 2 / max(len(pts), 1) / len(sets)
    return power


def radial_spectrum(points, side: float, *, k_max: int = 64) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Radially averaged power spectrum and anisotropy of points in ``[0, side)^2`` (§4.2.2).

    The periodogram ``P(k) = |sum_j exp(-2 pi i k . x_j / side)|^2 / n`` over integer ``k``
    with ``|k_x|, |k_y| <= k_max``, averaged over the point sets given (``points``: one
    ``(n, 2)`` array or a list of them, Ulichney's averaged periodogram), then over annuli of
    width 1.

    Returns
    -------
    (frequency, power, anisotropy)
        ``frequency`` in cycles per unit length, ``power`` the annulus mean (1 for white noise),
        ``anisotropy`` ``10 log10(var / mean^2)`` in dB (about 0 dB for one periodogram of an
        isotropic process, ``-10 log10(m)`` dB for the average of ``m``).
    """
    power = periodogram(points, side, k_max=k_max)
    k = np.arange(-k_max, k_max + 1)
    kx, ky = np.meshgrid(k, k, indexing="ij")
    ring = np.rint(np.hypot(kx, ky)).astype(np.int64).ravel()
    p = power.ravel()
    keep = (ring >= 1) & (ring <= k_max)
    counts = np.bincount(ring[keep], minlength=k_max + 1)[1:]
    mean = np.bincount(ring[keep], p[keep], minlength=k_max + 1)[1:] / counts
    sq = np.bincount(ring[keep], p[keep] ** 2, minlength=k_max + 1)[1:] / counts
    var = np.maximum(sq - mean**2, 1e-300) * counts / np.maximum(counts - 1, 1)
    return np.arange(1, k_max + 1) / side, mean, 10 * np.log10(var / np.maximum(mean, 1e-300) ** 2)
