"""Independent checks of Poisson sphere distributions and tile sets (class notes §4.4).

Written from the definitions, sharing no code with the builder
(:mod:`tilesolve.constructive.poisson_sphere`):

* :func:`point_violations3`: points are a Poisson sphere distribution at distance ``d`` when no
  two are closer than ``d`` (§4.4.1.1). A grid of ``d x d x d`` cells (numpy, or the compiled
  scan of :mod:`tilesolve.verify._poisson_kernel` for a large box) finds every closer pair: a
  close pair lies in one cell or two neighbouring ones (13 neighbours each, every pair of cells
  once). Points must also lie in their box.
* :func:`tileset_violations3`: every tile's points lie in its modified region (§4.4.3;
  :mod:`tilesolve.model.poisson_sphere`), and no tiling of space brings two points closer than
  ``d``. Two points closer than ``d`` come from two *slots* (lattice points, edges, faces,
  cells, each carrying a tile) whose regions' bounding boxes are closer than ``d``: every such
  pair of slots (found by measuring the boxes, not from the design) is checked for every
  colouring of the lattice points the two slots touch (up to 16 of them), which checks every
  tiling, and every 2 x 2 x 2 block of cells in particular. A pair with more than
  ``max_colourings`` colourings is checked on that many random ones (C = 2 never needs it:
  at most ``2^8`` colourings a pair, since overlapping slots share corners).
* :func:`placed_points3`: the points a coloured lattice of corner cubes places, from the
  regions' definition (a box file's points are re-derived with it from its set and the lattice
  its seed colours, and compared exactly by :func:`tilesolve.verify.poisson.match_violations`).
* :func:`cell_counts3`: the points a unit cell holds under each colouring of its eight
  corners, counted from the same placement; with it (the 2-D sets'
  :func:`~tilesolve.verify.poisson.shortfall_violations`), a set's stated shortfall
  (``stats["short"]``) must be the one its tiles give, so that a set cannot claim ``N`` points
  a cell that its tiles do not hold.

>>> import numpy as np
>>> pts = np.array([[0.1, 0.1, 0.1], [0.3, 0.1, 0.1], [0.35, 0.12, 0.1]])
>>> [v.message for v in point_violations3(pts, 0.1, (1, 1, 1))]
['points 1 and 2 are 0.05385 apart, closer than 0.1']
"""

from __future__ import annotations

import itertools

import numpy as np

from tilesolve.model.poisson_sphere import PoissonSphereTileSet
from tilesolve.verify import _poisson_kernel
from tilesolve.verify.dappled import Violation
from tilesolve.verify.poisson import shortfall_violations

__all__ = ["point_violations3", "tileset_violations3", "close_pairs3", "placed_points3", "cell_counts3"]

#: Violations listed at most (the count is always given).
MAX_LISTED = 20
#: A d-cube holds at most 8 points pairwise d apart (its eight half-side cubes hold one each).
_CELL_MAX = 8
#: Pairs of tiles searched at once by :func:`tileset_violations3`.
_BATCH = 1024
#: The cell itself and the 13 neighbours that come after it: each pair of cells once.
_OFFSETS = [(0, 0, 0)] + [o for o in itertools.product((-1, 0, 1), repeat=3) if o > (0, 0, 0)]


def close_pairs3(points: np.ndarray, distance: float, *, kernel=None) -> np.ndarray:
    """Every pair ``(i, j)``, ``i < j``, of 3-D ``points`` closer than ``distance``, sorted.

    A cell of more than eight points holds a close pair (pigeonhole); there its first nine
    points are compared, so that a file of many equal points costs no more than a valid one.
    The neighbouring cells are scanned with numpy, or for a large set by the compiled loop of
    :mod:`tilesolve.verify._poisson_kernel` (``kernel``: that loop, or None to choose); either
    scan gives candidates, kept here by their exact distance.
    """
    n = len(points)
    if n < 2:
        return np.zeros((0, 2), np.int64)
    cell = np.floor((points - points.min(axis=0)) / distance).astype(np.int64) + 1
    dims = cell.max(axis=0) + 2
    key = (cell[:, 0] * dims[1] + cell[:, 1]) * dims[2] + cell[:, 2]
    order = np.argsort(key, kind="stable")
    skey = key[order]
    start = np.flatnonzero(np.r_[True, skey[1:] != skey[:-1]])
    ukey, count = skey[start], np.diff(np.r_[start, n])
    kernel = kernel or _poisson_kernel.compiled(n, distance)
    if kernel is not None:
        offsets = [(dx * dims[1] + dy) * dims[2] + dz for dx, dy, dz in _OFFSETS]
        pairs = _poisson_kernel.candidates(kernel, points, order, ukey, start, count, offsets, _CELL_MAX, distance)
        return _exact(points, pairs, distance)
    total = int(np.prod(dims))
    if total <= 16 * n + (1 << 22):  # a dense table of the cells: one lookup a point and offset
        slot = np.full(total, -1, np.int64)
        slot[ukey] = np.arange(len(ukey))
    found = []
    for c in np.flatnonzero(count > _CELL_MAX):
        members = order[start[c]:start[c] + _CELL_MAX + 1]
        a, b = np.triu_indices(len(members), 1)
        found.append(np.stack([members[a], members[b]], axis=1))
    keep = np.repeat(count <= _CELL_MAX, count)
    sp = points[order]  # in cell order: neighbours lie close in memory
    reach = (distance * (1 + 1e-9)) ** 2  # a first cut without square roots; the exact one follows
    for dx, dy, dz in _OFFSETS:
        target = skey + (dx * dims[1] + dy) * dims[2] + dz
        if total <= 16 * n + (1 << 22):
            at = slot[target]
            hit = at >= 0
        else:  # sparse points (a forged file): search the sorted cells
            at = np.minimum(np.searchsorted(ukey, target), len(ukey) - 1)
            hit = ukey[at] == target
        hit &= keep & (count[at] <= _CELL_MAX)
        src = np.flatnonzero(hit)
        reps = count[at[src]]
        i = np.repeat(src, reps)
        j = start[np.repeat(at[src], reps)] + (np.arange(reps.sum()) - np.repeat(np.cumsum(reps) - reps, reps))
        if (dx, dy, dz) == (0, 0, 0):
            i, j = i[i < j], j[i < j]
        diff = sp[i] - sp[j]
        close = np.einsum("ij,ij->i", diff, diff) < reach
        found.append(np.stack([order[i[close]], order[j[close]]], axis=1))
    return _exact(points, np.concatenate(found), distance)


def _exact(points: np.ndarray, pairs: np.ndarray, distance: float) -> np.ndarray:
    """The candidate ``pairs`` closer than ``distance``, each once, ``i < j``, sorted."""
    pairs = np.sort(pairs, axis=1)
    if len(pairs) == 0:
        return pairs
    pairs = pairs[np.linalg.norm(points[pairs[:, 0]] - points[pairs[:, 1]], axis=1) < distance]
    return np.unique(pairs, axis=0).reshape(-1, 2)


def point_violations3(points, distance: float, size) -> list[Violation]:
    """Every way ``points`` (relative to the box's least corner) fail to be a Poisson sphere
    distribution at ``distance`` inside the box ``[0, size)``."""
    pts = np.asarray(points, dtype=np.float64)
    if pts.ndim != 2 or (len(pts) and pts.shape[1] != 3):
        return [Violation("shape", f"points must be an (n, 3) array, got shape {pts.shape}")]
    pts = pts.reshape(-1, 3)
    if not np.isfinite(pts).all():
        return [Violation("shape", "points must be finite numbers")]
    out = []
    outside = np.flatnonzero(((pts < 0) | (pts >= np.asarray(size, dtype=np.float64))).any(axis=1))
    out += [Violation("window", f"point {i} at {tuple(round(float(v), 6) for v in pts[i])} lies outside the box")
            for i in outside[:MAX_LISTED]]
    pairs = close_pairs3(pts, distance)
    for i, j in pairs[:MAX_LISTED]:
        gap = float(np.linalg.norm(pts[i] - pts[j]))
        out.append(Violation("distance", f"points {i} and {j} are {gap:.4g} apart, closer than {distance:.6g}"))
    if len(pairs) > MAX_LISTED:
        out.append(Violation("distance", f"{len(pairs):,} pairs in all are closer than {distance:.6g}"))
    return out


# ----------------------------------------------------------------------------------- tile sets
#: Kinds of slots: the axes along which a slot's lattice points differ (a corner none, an edge
#: its axis, a face its plane's two axes, a cell all three), and the set's list of tiles.
_SLOTS = (("corner", ()), ("xedge", (0,)), ("yedge", (1,)), ("zedge", (2,)), ("xface", (1, 2)),
          ("yface", (0, 2)), ("zface", (0, 1)), ("interior", (0, 1, 2)))


def _regions(ts: PoissonSphereTileSet) -> dict:
    """``kind -> (lo, hi, holes)``: the box of each kind's region in its slot's frame and the
    boxes cut out of it (§4.4.3)."""
    p = ts.problem
    d, a, b = p.distance, p.corner_half, p.edge_half
    out = {"corner": (np.full(3, -a), np.full(3, a), [])}
    for kind, spans in _SLOTS[1:4]:
        lo, hi = np.full(3, -b), np.full(3, b)
        lo[spans[0]], hi[spans[0]] = a, 1 - a
        out[kind] = (lo, hi, [])
    for kind, spans in _SLOTS[4:7]:
        lo, hi = np.full(3, -d), np.full(3, d)
        lo[list(spans)], hi[list(spans)] = b, 1 - b
        holes = []
        for cu, cv in itertools.product((0, 1), repeat=2):  # the corner squares of side a
            hlo, hhi = np.full(3, -1.0), np.full(3, 1.0)
            for ax, cc in zip(spans, (cu, cv)):
                hlo[ax], hhi[ax] = (-1.0, a) if cc == 0 else (1 - a, 2.0)
            holes.append((hlo, hhi))
        out[kind] = (lo, hi, holes)
    holes = [(np.array(v, float) - a, np.array(v, float) + a) for v in itertools.product((0, 1), repeat=3)]
    for axis in range(3):
        for v in itertools.product((0, 1), repeat=2):
            c = np.insert(np.array(v, float), axis, 0.0)
            lo, hi = c - b, c + b
            lo[axis], hi[axis] = a, 1 - a
            holes.append((lo, hi))
    out["interior"] = (np.full(3, d), np.full(3, 1 - d), holes)
    return out


def _corners(spans, offset) -> list[tuple[int, int, int]]:
    """The lattice points of a slot at ``offset``, in the order of its tile index's digits."""
    out = []
    for shift in itertools.product((0, 1), repeat=len(spans)):
        p = list(offset)
        for ax, s in zip(spans, shift):
            p[ax] += s
        out.append(tuple(p))
    return out


def placed_points3(ts: PoissonSphereTileSet, lat) -> np.ndarray:
    """Every point the tiles of a coloured lattice place (§4.4.2-4.4.3, from the regions'
    definition): ``lat[i, j, k]`` is the colour of lattice point ``(i, j, k)``. A slot (a lattice
    point, or an edge, face or cell whose least lattice point is ``p``) lying wholly in the
    lattice carries the tile whose index has its corners' colours as digits (:func:`_corners`'
    order); a point ``t`` of that tile is placed at ``p + t``. Points are grouped by tile, not
    cropped."""
    c, lat = ts.problem.colors, np.asarray(lat, dtype=np.int64)
    parts = [np.zeros((0, 3))]
    for kind, spans in _SLOTS:
        corners = _corners(spans, (0, 0, 0))
        ext = [n - 1 if ax in spans else n for ax, n in enumerate(lat.shape)]
        index = np.zeros(ext, np.int64)
        for x, y, z in corners:
            index = index * c + lat[x:x + ext[0], y:y + ext[1], z:z + ext[2]]
        index = index.ravel()
        at = np.stack(np.unravel_index(np.arange(index.size), ext), axis=1).astype(np.float64)
        order = np.argsort(index, kind="stable")
        tiles, first = np.unique(index[order], return_index=True)
        for k, group in zip(tiles, np.split(order, first[1:])):
            parts.append((at[group][:, None, :] + ts.tiles[kind][k][None, :, :]).reshape(-1, 3))
    return np.concatenate(parts)


def cell_counts3(ts: PoissonSphereTileSet) -> np.ndarray:
    """The points the unit cell ``[0, 1)^3`` of any tiling holds, for each colouring of its eight
    corners (index: the corners' colours as digits in :func:`_corners`' order, the interior
    tile's index): every slot of the cell's 2 x 2 x 2 lattice carries the tile
    :func:`placed_points3` gives it, and its points inside the cell are counted (§4.4.3: the
    corner, edge and face tiles around the cell and its interior tile).

    Each tile's points inside the cell are counted once for each place a slot of its kind takes
    in the cell, and summed over the colourings with numpy (``C^8`` of them: 65,536 for C = 4).
    """
    c = ts.problem.colors
    digits = (np.arange(c**8)[:, None] // c ** np.arange(7, -1, -1)[None, :]) % c  # corner (x, y, z) at 4x + 2y + z
    total = np.zeros(c**8, np.int64)
    for kind, spans in _SLOTS:
        for off in itertools.product(*[(0,) if ax in spans else (0, 1) for ax in range(3)]):
            index = np.zeros(c**8, np.int64)
            for x, y, z in _corners(spans, off):
                index = index * c + digits[:, 4 * x + 2 * y + z]
            o = np.array(off, np.float64)
            inside = np.array([int(((t + o >= 0) & (t + o < 1)).all(axis=1).sum()) for t in ts.tiles[kind]], np.int64)
            total += inside[index]
    return total


def _gap(lo1, hi1, lo2, hi2) -> float:
    return float(np.linalg.norm(np.maximum(0.0, np.maximum(lo1 - hi2, lo2 - hi1))))


def _slot_pairs(regions: dict, distance: float) -> list[tuple]:
    """Every pair of slots (one at the origin) whose region boxes come closer than ``distance``,
    each pair once up to translation."""
    seen, out = set(), []
    for (k1, s1), (k2, s2) in itertools.product(_SLOTS, repeat=2):
        for off in itertools.product(range(-2, 3), repeat=3):
            lo1, hi1, _ = regions[k1]
            lo2, hi2, _ = regions[k2]
            if _gap(lo1, hi1, lo2 + off, hi2 + off) >= distance:
                continue
            key = min(((k1, (0, 0, 0)), (k2, off)), ((k2, (0, 0, 0)), (k1, tuple(-o for o in off))))
            if key in seen:
                continue
            seen.add(key)
            out.append(((k1, s1), (k2, s2, off)))
    return out


def tileset_violations3(ts: PoissonSphereTileSet, *, max_colourings: int = 4096, seed: int = 0) -> list[Violation]:
    """Every way the tile set fails: a point outside its region, or two points of some tiling
    closer than the set's distance (module docstring)."""
    if not isinstance(ts, PoissonSphereTileSet):
        return [Violation("shape", "the answer is no Poisson sphere tile set")]
    out = []
    regions = _regions(ts)
    for kind, (lo, hi, holes) in regions.items():
        for k, pts in enumerate(ts.tiles[kind]):
            bad = ~np.isfinite(pts).all(axis=1) | ((pts < lo) | (pts >= hi)).any(axis=1)
            for hlo, hhi in holes:
                bad |= ((pts >= hlo) & (pts < hhi)).all(axis=1)
            if bad.any():
                out.append(Violation("region", f"{kind} tile {k}: {int(bad.sum())} points outside its region"))
    if out:
        return out[:MAX_LISTED]
    out += shortfall_violations(ts, cell_counts3)
    c, d = ts.problem.colors, ts.problem.distance
    rng = np.random.default_rng(seed)
    for (k1, s1), (k2, s2, off) in _slot_pairs(regions, d):
        c1, c2 = _corners(s1, (0, 0, 0)), _corners(s2, off)
        points = sorted(set(c1) | set(c2))
        n = len(points)
        if c**n <= max_colourings:
            colourings = (np.arange(c**n)[:, None] // c ** np.arange(n)[None, :]) % c
        else:
            colourings = rng.integers(c, size=(max_colourings, n))
        place = {p: i for i, p in enumerate(points)}
        weights = lambda cs: c ** np.arange(len(cs) - 1, -1, -1)  # noqa: E731 - most significant first
        i1 = colourings[:, [place[p] for p in c1]] @ weights(c1)
        i2 = colourings[:, [place[p] for p in c2]] @ weights(c2)
        combos = np.unique(np.stack([i1, i2], axis=1), axis=0)
        same = k1 == k2 and not any(off)
        for at in range(0, len(combos), _BATCH):  # bounded memory: a batch of combinations at a time
            bad = _first_close(ts.tiles[k1], None if same else ts.tiles[k2], combos[at:at + _BATCH],
                               np.array(off, float), d)
            if bad is not None:
                break
        if bad is not None:
            (t1, t2, gap), sides = bad
            where = [f"{k1} tile {t1} at (0, 0, 0)", f"{k2} tile {t2} at {off}"]
            what = f"{where[0]} and {where[1]}" if sides == {0, 1} else f"{where[sides.pop()]}, within the tile"
            out.append(Violation("distance", f"{what}: two points {gap:.4g} apart, closer than {d:.6g}"))
            if len(out) >= MAX_LISTED:
                break
    return out


def _first_close(tiles1, tiles2, combos: np.ndarray, off: np.ndarray, distance: float):
    """The first ``(tile 1, tile 2, gap)`` of ``combos`` whose points (tile 2 moved by ``off``;
    one slot when ``tiles2`` is None) come closer than ``distance``, with the set of sides (0:
    tile 1, 1: tile 2) the two points come from; or None. The combinations are laid side by
    side, 8 units apart along x, and searched at once."""
    pts, owner, side = [], [], []
    for j, (t1, t2) in enumerate(combos):
        a = tiles1[t1]
        b = np.zeros((0, 3)) if tiles2 is None else tiles2[t2] + off
        pts += [a + (8.0 * j, 0, 0), b + (8.0 * j, 0, 0)]
        owner.append(np.full(len(a) + len(b), j))
        side.append(np.repeat([0, 1], [len(a), len(b)]))
    if not pts:
        return None
    pts, owner, side = np.concatenate(pts), np.concatenate(owner), np.concatenate(side)
    pairs = close_pairs3(pts, distance)
    if len(pairs) == 0:
        return None
    i, k = pairs[0]
    t1, t2 = combos[owner[i]]
    return (int(t1), int(t2), float(np.linalg.norm(pts[i] - pts[k]))), {int(side[i]), int(side[k])}
