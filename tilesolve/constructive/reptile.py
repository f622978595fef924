"""Rep-tile substitution tilings: the chair, the sphinx and polyomino rep-tiles (Kaplan, class
notes Part II §8.1, Fig. 29).

A rep-tile ``P`` of scale ``k`` is the union of ``k^2`` copies of itself shrunk by ``k``. The rule
is found, not transcribed: the cells of ``kP`` are covered exactly by congruent copies of ``P``
(an exact cover by backtracking over the lattice's symmetries: 8 on the square grid, 12 on the
triangle grid). A tile is an affine map ``x -> L x + t`` of the lattice (``L`` an integer matrix,
``t`` an integer vector); ``n`` substitution steps from ``k^n P`` leave every tile a unit copy,
so all coordinates are integers: on the square grid ``(x, y)``, on the triangle grid the
coordinates ``(a, b)`` of ``a + b w``, ``w = exp(i pi / 3)``.
"""

from __future__ import annotations

import functools
from typing import NamedTuple

import numpy as np

from tilesolve.errors import InvalidProblem

__all__ = ["Prototile", "PROTOTILES", "rule", "substitute", "tiles", "outline", "lattice_xy"]


class Prototile(NamedTuple):
    """A polyform: its grid (``"square"`` or ``"triangle"``), its cells and a caption."""

    grid: str
    cells: tuple[tuple[int, int, int], ...]  # (x, y, 0) squares; (x, y, 0 up / 1 down) triangles
    caption: str


#: The built-in rep-tiles (all of scale 2: four copies make the doubled tile).
PROTOTILES = {
    "chair": Prototile("square", ((0, 0, 0), (1, 0, 0), (0, 1, 0)), "the chair (L-tromino), rep-4"),
    "l-tetromino": Prototile("square", ((0, 0, 0), (1, 0, 0), (2, 0, 0), (0, 1, 0)), "the L-tetromino, rep-4"),
    "p-pentomino": Prototile("square", ((0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0), (0, 2, 0)),
                             "the P-pentomino, rep-4"),
    "sphinx": Prototile("triangle", ((0, 0, 0), (0, 0, 1), (1, 0, 0), (1, 0, 1), (2, 0, 0), (0, 1, 0)),
                        "the sphinx hexiamond, rep-4"),
}

_SQUARE = (np.array([[0, -1], [1, 0]]), np.array([[1, 0], [0, -1]]))
_TRIANGLE = (np.array([[0, -1], [1, 1]]), np.array([[1, 1], [0, -1]]))  # 60 degrees, mirror in the x axis


def _symmetries(grid: str) -> list[np.ndarray]:
    rot, mirror = _SQUARE if grid == "square" else _TRIANGLE
    turns = 4 if grid == "square" else 6
    out, m = [], np.eye(2, dtype=np.int64)
    for _ in range(turns):
        out += [m, m @ mirror]
        m = rot @ m
    return out


def _cell_vertices(grid: str, cell) -> np.ndarray:
    x, y, d = cell
    if grid == "square":
        return np.array([[x, y], [x + 1, y], [x + 1, y + 1], [x, y + 1]])
    if d == 0:
        return np.array([[x, y], [x + 1, y], [x, y + 1]])
    return np.array([[x + 1, y], [x + 1, y + 1], [x, y + 1]])


def _key(vertices: np.ndarray) -> tuple:
    return tuple(sorted(map(tuple, vertices.tolist())))


def outline(proto: Prototile) -> np.ndarray:
    """The polygon of the prototile, counter-clockwise, corners only (collinear points dropped)."""
    edges = {}
    for cell in proto.cells:
        v = _cell_vertices(proto.grid, cell)
        for a, b in zip(v, np.roll(v, -1, axis=0)):
            edges[(tuple(a), tuple(b))] = None
    boundary = {a: b for a, b in edges if (b, a) not in edges}
    start = min(boundary)
    path, p = [start], boundary[start]
    while p != start:
        path.append(p)
        p = boundary[p]
    pts = np.array(path)
    prev, nxt = np.roll(pts, 1, axis=0), np.roll(pts, -1, axis=0)
    d1, d2 = pts - prev, nxt - pts
    keep = d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0] != 0
    return pts[keep]


@functools.lru_cache(maxsize=None)
def rule(name: str, k: int = 2) -> tuple[tuple[np.ndarray, np.ndarray], ...]:
    """The substitution rule of a built-in rep-tile: ``k^2`` maps ``(g, t)`` with
    ``k P = union of g P + t``, found by exact cover (the first cover in a fixed order).

    Raises
    ------
    InvalidProblem
        The tile is no rep-tile of scale ``k``.
    """
    proto = PROTOTILES[name]
    cells = [_cell_vertices(proto.grid, c) for c in proto.cells]
    region = set()
    lo = k * np.min([v.min(axis=0) for v in cells], axis=0)
    hi = k * np.max([v.max(axis=0) for v in cells], axis=0)
    kinds = (0,) if proto.grid == "square" else (0, 1)
    for x in range(lo[0] - 1, hi[0] + 1):
        for y in range(lo[1] - 1, hi[1] + 1):
            for d in kinds:
                v = _cell_vertices(proto.grid, (x, y, d))
                if _inside_scaled(proto.grid, cells, k, v):
                    region.add(_key(v))
    placements = []
    for g in _symmetries(proto.grid):
        shape = [v @ g.T for v in cells]
        anchor = shape[0]
        for target in region:
            t = np.array(target[0]) - np.array(_key(anchor)[0])
            keys = [_key(v + t) for v in shape]
            if all(q in region for q in keys) and len(set(keys)) == len(keys):
                placements.append((frozenset(keys), g, t))
    uniq = {}
    for p in placements:
        uniq.setdefault(p[0], p)
    placements = list(uniq.values())
    chosen = _cover(frozenset(region), placements, [])
    if chosen is None:
        raise InvalidProblem(f"{name} is no rep-tile of scale {k}")
    return tuple((g, t) for _, g, t in chosen)


def _inside_scaled(grid: str, cells, k: int, v: np.ndarray) -> bool:
    """Whether the unit cell ``v`` lies in ``k`` times the prototile (its centre inside a scaled cell)."""
    c = v.sum(axis=0) / len(v)
    for cell in cells:
        poly = k * cell
        inside = True
        for a, b in zip(poly, np.roll(poly, -1, axis=0)):
            ax, ay = _cart(grid, b - a)
            px, py = _cart(grid, c - a)
            if ax * py - ay * px <= 0:
                inside = False
                break
        if inside:
            return True
    return False


def _cart(grid: str, v) -> tuple[float, float]:
    if grid == "square":
        return float(v[0]), float(v[1])
    return float(v[0] + v[1] / 2), float(v[1]) * 3 ** 0.5 / 2


def _cover(free: frozenset, placements, chosen):
    if not free:
        return list(chosen)
    cell = min(free)
    for p in placements:
        if cell in p[0] and p[0] <= free:
            out = _cover(free - p[0], placements, chosen + [p])
            if out is not None:
                return out
    return None


def substitute(name: str, steps: int) -> tuple[np.ndarray, np.ndarray]:
    """The tiles of ``2^steps P`` after ``steps`` substitutions: ``(L, t)`` arrays of shapes
    ``(n, 2, 2)`` and ``(n, 2)``, every ``L`` a symmetry of the lattice."""
    maps = rule(name)
    k = 2
    mats = np.stack([g for g, _ in maps]).astype(np.int64)
    trans = np.stack([t for _, t in maps]).astype(np.int64)
    lin = np.eye(2, dtype=np.int64)[None] * k**steps
    off = np.zeros((1, 2), dtype=np.int64)
    for _ in range(steps):
        lin, off = ((lin[:, None] @ mats[None]) // k).reshape(-1, 2, 2), \
            (off[:, None] + np.einsum("nij,mj->nmi", lin, trans) // k).reshape(-1, 2)
    return lin, off


def tiles(name: str, steps: int) -> np.ndarray:
    """Tile polygons ``(n, m, 2)`` in lattice coordinates, each counter-clockwise."""
    lin, off = substitute(name, steps)
    poly = outline(PROTOTILES[name])
    v = np.einsum("nij,mj->nmi", lin, poly) + off[:, None]
    flip = np.linalg.det(lin) < 0
    v[flip] = v[flip][:, ::-1]
    return v


def lattice_xy(grid: str, v: np.ndarray) -> np.ndarray:
    """Cartesian coordinates of lattice points ``(..., 2)``."""
    v = np.asarray(v, dtype=np.float64)
    if grid == "square":
        return v
    return np.stack([v[..., 0] + v[..., 1] / 2, v[..., 1] * 3 ** 0.5 / 2], axis=-1)
