"""Corner-based Poisson sphere tiles: building a set, and the points of a box (class notes §4.4).

Building (§4.4.3, figures 4.20-4.23; regions as in :mod:`tilesolve.model.poisson_sphere`)
----------------------------------------------------------------------------------------
Every fill is relaxation dart throwing in 3-D (:func:`._poisson_sphere_kernels.dart_fill3`),
starting at the radius of the densest packing (``rho = 1``) and giving up radius only when
darts keep missing, never below ``d`` (with a relative slack of 1e-9) from any point the new
point can meet in a tiling. Lloyd relaxation (the notes' optional step) is not done in 3-D.

1. **Corner tiles**, one per colour: ``N`` points on the unit torus; the cube ``[-a, a)^3``
   around a lattice point is cut out (figure 4.20).
2. **Edge tiles**, one per axis and pair of end colours: the two corner tiles at the ends;
   the box ``[-a, 1 + a)`` along the edge, ``[-1/2, 1/2)`` across it, is filled at density
   ``N`` outside the corner tiles and the edge's bar is cut out (figure 4.21).
3. **Face tiles**, one per normal and colouring of four corners: the face's four corner and
   four edge tiles; the box ``[0, 1)^2`` in the face, ``[-1/2, 1/2)`` across it, is filled
   outside them and the face's slab is cut out (figure 4.22).
4. **Interior tiles**, one per corner cube: the cell with its 8 corner, 12 edge and 6 face
   tiles; its interior region gets the points that bring the cell to ``N`` (figure 4.23). The
   notes repeat a tile that falls short; here the fill is repeated a few times and the fullest
   kept (the set's ``stats["short"]`` says how many points are missing in all).

Boxes: the direct 3-D corner tiling
-----------------------------------
:func:`window_points` colours every lattice point of the box with a 3-D lattice hash, the
long-period hash of §3.4 (:func:`tilesolve.constructive.hashes.tiling_hash`, eq. 3.7: period
5,930,659,848 in each axis) by default, reduced modulo ``C`` (the direct stochastic tiling
algorithm for corner tiles, §3.3.1, which §4.4.2 says generalizes to 3-D): random access, so
boxes with the same seed agree where they overlap, at any distance from the origin. Each
corner, edge, face and cell of the box then gets its tile (:func:`lattice_slots`), and the
tiles' points inside the box are returned relative to its least corner.

Examples
--------
>>> from tilesolve.model.poisson_sphere import PoissonSphereTilesProblem
>>> ts = build_tiles(PoissonSphereTilesProblem(1, 100, 0.6), seed=1)
>>> [len(ts.tiles[k]) for k in ("corner", "xedge", "xface", "interior")]
[1, 1, 1, 1]
>>> w = window_points(ts, (2**40, -7, 3, 2, 2, 2), seed=4)
>>> w.n_points == 8 * (100 - ts.stats["short"])   # C = 1: every cell holds the same points
True
"""

from __future__ import annotations

import itertools

import numpy as np

from tilesolve._random import rng_from_seed
from tilesolve.constructive import _poisson_sphere_kernels as _k
from tilesolve.constructive.stochastic import make_hash
from tilesolve.errors import InvalidProblem
from tilesolve.model.poisson import SLACK
from tilesolve.model.poisson_sphere import (
    KINDS,
    PoissonSphereTilesProblem,
    PoissonSphereTileSet,
    PoissonSphereWindow,
    PoissonSphereWindowProblem,
    r_max3,
)

__all__ = ["build_tiles", "window_points", "lattice_colors", "lattice_slots", "dart_throwing3", "SPANS"]

#: The radius shrinks by this factor when darts keep missing (McCool and Fiume 1992).
SHRINK = 0.97
#: Darts in a row that may miss before the radius shrinks.
PATIENCE = 300
#: Darts in a row that may miss at the smallest radius before a fill gives up.
FINAL = 3000
#: Further tries for an interior tile that falls short of its count.
RETRIES = 1
#: The axes each kind of tile spans (its corners differ along them): a corner none, an edge
#: its axis, a face the two axes of its plane, a cell all three.
SPANS = {"corner": (), "xedge": (0,), "yedge": (1,), "zedge": (2,), "xface": (1, 2), "yface": (0, 2),
         "zface": (0, 1), "interior": (0, 1, 2)}

_TORUS = np.array([[0.0, 1.0, 0.0, 1.0, 0.0, 1.0]])
_NO_BOXES = np.zeros((0, 6))


def _fill(fixed, allow, forbid, target: int, r0: float, rmin: float, seed: int, torus: bool = False):
    out = np.empty((max(target, 0), 3))
    if target <= 0:
        return out
    n, _ = _k.KERNELS.pick(target).dart_fill3(np.ascontiguousarray(fixed, dtype=np.float64).reshape(-1, 3),
                                              np.ascontiguousarray(allow), np.ascontiguousarray(forbid).reshape(-1, 6),
                                              int(target), float(r0), float(rmin), SHRINK, PATIENCE, FINAL, torus,
                                              int(seed), out)
    return out[:n]


def dart_throwing3(n: int, distance: float, *, seed=None, patience: int = PATIENCE) -> np.ndarray:
    """Plain dart throwing in the unit 3-torus (Cook 1986; §4.4.1.3): darts at one distance
    until ``patience`` in a row miss, at most ``n`` points. The baseline of the benchmarks.

    >>> p = dart_throwing3(40, 0.2, seed=1)
    >>> p.shape[1], len(p) <= 40
    (3, True)
    """
    out = np.empty((n, 3))
    seed32 = int(rng_from_seed(seed).integers(2**31))
    m, _ = _k.KERNELS.pick(n).dart_fill3(np.zeros((0, 3)), _TORUS, _NO_BOXES, n, distance, distance, SHRINK,
                                         patience, patience, True, seed32, out)
    return out[:m]


def _box(lo, hi) -> list[float]:
    return [lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]]


def _cube(at, half: float) -> list[float]:
    return _box(np.asarray(at, float) - half, np.asarray(at, float) + half)


def _bar(at, axis: int, a: float, b: float) -> list[float]:
    """The edge region of axis ``axis`` from lattice point ``at``."""
    lo, hi = np.asarray(at, float) - b, np.asarray(at, float) + b
    lo[axis], hi[axis] = at[axis] + a, at[axis] + 1 - a
    return _box(lo, hi)


def _in(points: np.ndarray, box) -> np.ndarray:
    return ((points[:, 0] >= box[0]) & (points[:, 0] < box[1]) & (points[:, 1] >= box[2]) & (points[:, 1] < box[3])
            & (points[:, 2] >= box[4]) & (points[:, 2] < box[5]))


def lattice_colors(box, colors: int, *, seed=None, hash: str = "long") -> np.ndarray:
    """The colours of the lattice points ``box.origin + (i, j, k)``, ``0 <= i <= width`` (and so
    on), at ``[i, j, k]``: ``h(x, y, z) % C`` with the 3-D lattice hash (eq. 3.4 or 3.7)."""
    h = make_hash(hash, colors, seed)
    x0, y0, z0 = box.origin
    xs = np.arange(x0, x0 + box.width + 1, dtype=np.int64)[:, None, None]
    ys = np.arange(y0, y0 + box.height + 1, dtype=np.int64)[None, :, None]
    zs = np.arange(z0, z0 + box.depth + 1, dtype=np.int64)[None, None, :]
    return np.asarray(h(xs, ys, zs) % colors, dtype=np.int64)


def lattice_slots(lat: np.ndarray, colors: int) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Every corner, edge, face and cell of the lattice whose point colours are ``lat[i, j, k]``:
    ``kind -> (offsets (n, 3) int64, tile indices (n,))``. A tile's index has the colours of
    its corners as base-``C`` digits, the corners in lexicographic order of their offsets
    along the axes it spans (:data:`SPANS`; :func:`~tilesolve.model.poisson_sphere.cube_index`)."""
    cells = np.array(lat.shape) - 1
    out = {}
    for kind, spans in SPANS.items():
        ext = [int(cells[a]) if a in spans else int(cells[a]) + 1 for a in range(3)]
        idx = np.zeros(ext, np.int64)
        for shift in itertools.product((0, 1), repeat=len(spans)):
            s = [0, 0, 0]
            for a, v in zip(spans, shift):
                s[a] = v
            idx = idx * colors + lat[s[0]:s[0] + ext[0], s[1]:s[1] + ext[1], s[2]:s[2] + ext[2]]
        out[kind] = (np.indices(ext).reshape(3, -1).T.astype(np.int64), idx.ravel())
    return out


def _assembled(tiles: dict, slots: dict, kinds) -> np.ndarray:
    """The points of the tiles of ``kinds`` in ``slots``, each moved to its slot."""
    parts = [tiles[k][t] + off for k in kinds for off, t in zip(*slots[k])]
    return np.concatenate(parts) if parts else np.zeros((0, 3))


def _unit_lattice(index: int, colors: int, spans) -> np.ndarray:
    """The 2 x 2 x 2 lattice of colours in which the tile ``index`` spanning ``spans`` sits at
    the origin (digits along the other axes repeated)."""
    lat = np.zeros((2, 2, 2), np.int64)
    shifts = list(itertools.product((0, 1), repeat=len(spans)))
    digits = [(index // colors ** (len(shifts) - 1 - i)) % colors for i in range(len(shifts))]
    for shift, v in zip(shifts, digits):
        sl = [slice(None)] * 3
        for a, s in zip(spans, shift):
            sl[a] = s
        lat[tuple(sl)] = v
    return lat


def build_tiles(problem: PoissonSphereTilesProblem, *, seed=None) -> PoissonSphereTileSet:
    """Build the ``C + 3 C^2 + 3 C^4 + C^8`` tiles of ``problem`` (module docstring).

    Parameters
    ----------
    problem : PoissonSphereTilesProblem
    seed : int
        The same seed gives the same set, point for point.

    Returns
    -------
    PoissonSphereTileSet
        ``stats["short"]``: points the interior tiles lack to reach ``N``, summed.
    """
    if not isinstance(problem, PoissonSphereTilesProblem):
        raise InvalidProblem(f"expected a PoissonSphereTilesProblem, got {type(problem).__name__}")
    rng = rng_from_seed(seed)
    c, n, a, b, d = problem.colors, problem.points, problem.corner_half, problem.edge_half, problem.distance
    dd = d * (1 + SLACK)
    r0 = 2 * r_max3(n)
    seeds = iter(rng.integers(2**31, size=problem.n_tiles).tolist())
    tiles: dict[str, list[np.ndarray]] = {k: [] for k in KINDS}
    for _ in range(c):
        pts = _fill(np.zeros((0, 3)), _TORUS, _NO_BOXES, n, r0, dd, next(seeds), torus=True)
        pts = (pts + 0.5) % 1.0 - 0.5  # the torus around the lattice point; cut [-a, a)^3
        tiles["corner"].append(pts[((pts >= -a) & (pts < a)).all(axis=1)])
    for axis, kind in enumerate(("xedge", "yedge", "zedge")):
        e = np.eye(3)[axis]
        lo, hi = np.full(3, -0.5), np.full(3, 0.5)
        lo[axis], hi[axis] = -a, 1 + a
        allow = np.array([_box(lo, hi)])
        forbid = np.array([_cube(0 * e, a), _cube(e, a)])
        target = round(n * ((1 + 2 * a) - 16 * a**3))
        region = _bar(np.zeros(3), axis, a, b)
        for lo_c, hi_c in itertools.product(range(c), repeat=2):
            fixed = np.vstack([tiles["corner"][lo_c], tiles["corner"][hi_c] + e])
            pts = _fill(fixed, allow, forbid, target, r0, dd, next(seeds))
            tiles[kind].append(pts[_in(pts, region)])
    for normal, kind in zip(range(3), ("xface", "yface", "zface")):
        u, v = SPANS[kind]
        lo, hi = np.zeros(3), np.ones(3)
        lo[normal], hi[normal] = -0.5, 0.5
        allow = np.array([_box(lo, hi)])
        slab_lo, slab_hi = np.zeros(3), np.ones(3)
        slab_lo[[u, v]], slab_hi[[u, v]] = b, 1 - b
        slab_lo[normal], slab_hi[normal] = -d, d
        target = round(n * (1 - 8 * a**3 - 8 * b * b * (1 - 2 * a)))
        for index in range(c**4):
            slots = lattice_slots(_unit_lattice(index, c, (u, v)), c)
            on_face = {k: _on_face(slots[k], normal) for k in KINDS[:4] if k != kind[0] + "edge"}
            fixed = _assembled(tiles, on_face, on_face)
            pts = _fill(fixed, allow, _taken(on_face, a, b), target, r0, dd, next(seeds))
            keep = _in(pts, _box(slab_lo, slab_hi))
            nu, nv = (pts[:, u] < a) | (pts[:, u] >= 1 - a), (pts[:, v] < a) | (pts[:, v] >= 1 - a)
            tiles[kind].append(pts[keep & ~(nu & nv)])
    allow = np.array([_box(np.full(3, d), np.full(3, 1 - d))])
    short = 0
    for index in range(c**8):
        slots = lattice_slots(_unit_lattice(index, c, (0, 1, 2)), c)
        fixed = _assembled(tiles, slots, KINDS[:-1])
        forbid = _taken({k: slots[k] for k in KINDS[:4]}, a, b)
        target = n - int(((fixed >= 0) & (fixed < 1)).all(axis=1).sum())
        pts = _fill(fixed, allow, forbid, target, r0, dd, next(seeds))
        for _ in range(RETRIES):  # the notes repeat a tile that falls short; keep the fullest
            if len(pts) >= target:
                break
            again = _fill(fixed, allow, forbid, target, r0, dd, int(rng.integers(2**31)))
            pts = again if len(again) > len(pts) else pts
        short += max(0, target - len(pts))
        tiles["interior"].append(pts)
    return PoissonSphereTileSet(problem, tiles, seed=seed if isinstance(seed, int) else None, stats={"short": short})


def _taken(slots: dict, a: float, b: float) -> np.ndarray:
    """The regions of the corner and edge tiles in ``slots``, as boxes a fill keeps out of."""
    return np.array([_cube(o, a) if k == "corner" else _bar(o, "xyz".index(k[0]), a, b)
                     for k, (offsets, _) in slots.items() for o in offsets])


def _on_face(slot: tuple[np.ndarray, np.ndarray], normal: int) -> tuple[np.ndarray, np.ndarray]:
    """The slots of a unit lattice that lie in its face ``normal = 0`` (edges along the normal do not)."""
    keep = slot[0][:, normal] == 0
    return slot[0][keep], slot[1][keep]


def window_points(tileset: PoissonSphereTileSet, box, *, hash: str = "long", seed=None) -> PoissonSphereWindow:
    """The points of the direct 3-D corner tiling with ``tileset`` in ``box`` (module docstring).

    Parameters
    ----------
    tileset : PoissonSphereTileSet
    box : Box or (x0, y0, z0, width, height, depth)
    hash : {"long", "table"}
    seed : int
        Seed of the lattice hash: boxes with the same seed agree where they overlap.

    Returns
    -------
    PoissonSphereWindow
        Points relative to the box's least corner, ordered by kind of tile, then by slot.
    """
    problem = PoissonSphereWindowProblem(tileset, box, hash)
    box = problem.box
    c = tileset.problem.colors
    slots = lattice_slots(lattice_colors(box, c, seed=seed, hash=hash), c)
    size = np.array(box.size, dtype=np.float64)
    parts = []
    for kind in KINDS:
        arrays = tileset.tiles[kind]
        counts = np.array([len(t) for t in arrays], dtype=np.int64)
        pad = np.zeros((len(arrays), max(1, int(counts.max())), 3))
        for i, t in enumerate(arrays):
            pad[i, :len(t)] = t
        off, which = slots[kind]
        mask = np.arange(pad.shape[1])[None, :] < counts[which][:, None]
        pts = (pad[which] + off[:, None, :])[mask]
        parts.append(pts[((pts >= 0) & (pts < size)).all(axis=1)])
    return PoissonSphereWindow(box, np.concatenate(parts), tileset.problem.distance)
