"""Independent checks of isohedral tilings (class notes Part II §7). Written from the definitions;
shares no code with :mod:`tilesolve.constructive.isohedral` (it reads the same tables, as data).

:func:`tiling_violations` checks an :class:`~tilesolve.model.isohedral.IsohedralTiling` against
its problem:

1. *The template.* The tiling vertices, translation vectors and aspect motions are the type's
   table at the stated parameters; between consecutive tiling vertices the outline is the stated
   edge shape of that edge's class, moved from its unit frame onto the edge after the edge's
   orientation (Bézier pieces evaluated here by de Casteljau's construction); every edge shape
   keeps its J/U/S/I constraint (§7.3.1).
2. *Congruence.* Every aspect's motion is an isometry (orthonormal linear part), so every tile,
   the prototile's image under an aspect motion and a translation, is congruent to it; the
   prototile is a simple polygon (no two of its chords meet, but neighbours at their shared end).
3. *A tiling of the torus* (the plane modulo the lattice of T1, T2; one copy of each aspect):
   with every tile turned counter-clockwise, every chord of every tile is run backwards by
   exactly one chord of a tile (adjacency, edges matched pairwise with opposite orientation),
   and the tiles' areas sum to the fundamental domain's, ``|det(T1, T2)|``. Then the sum of the
   tiles' winding numbers is the same on both sides of every chord, hence constant, and equal to
   the area ratio, 1: no overlap and no gap, in the torus and so in the plane.
4. *The drawing.* The placed tiles are distinct, each meets the region (its bounding box, within
   the length tolerance), a grid of points of the region each lies in a placed tile, and two
   placed tiles that share a chord have different colours (from the colours' range).

Tolerances: lengths are compared within ``1e-7`` times the prototile's size (coordinates are
floats computed from floats; the tables hold 12 significant digits); areas within ``1e-6``
relative; symmetry of edge shapes within ``1e-9`` of the unit frame.
"""

from __future__ import annotations

import numpy as np

from tilesolve.model.isohedral import BEZIER_CHORDS, SYMMETRY_TOL, IsohedralProblem, IsohedralTiling, isohedral_type
from tilesolve.verify.dappled import Violation

__all__ = ["tiling_violations", "REL_TOL"]

#: Relative tolerance of lengths (times the prototile's size).
REL_TOL = 1e-7
#: Points of the region tested for cover, per side.
_COVER_GRID = 9


def _linear(coeffs: np.ndarray, params) -> np.ndarray:
    """Evaluate a table entry: the last coefficient is the constant term."""
    c = np.asarray(coeffs, float)
    return c[..., -1] + sum(c[..., i] * p for i, p in enumerate(params))


def _casteljau(ctrl: list[complex], t: float) -> complex:
    while len(ctrl) > 1:
        ctrl = [a + (b - a) * t for a, b in zip(ctrl, ctrl[1:])]
    return ctrl[0]


def _unit_path(shape) -> list[complex]:
    """The edge's points in its unit frame as complex numbers, ends included."""
    pts = [0j] + [complex(x, y) for x, y in shape.points] + [1 + 0j]
    if shape.kind == "line":
        return pts
    out = []
    for k in range(0, len(pts) - 1, 3):
        out += [_casteljau(pts[k:k + 4], s / BEZIER_CHORDS) for s in range(BEZIER_CHORDS)]
    return out + [pts[-1]]


def _kind_ok(shape, kind: str) -> bool:
    pts = [complex(x, y) for x, y in shape.points]
    mirror = [complex(1 - z.real, z.imag) for z in reversed(pts)]
    turn = [1 - z for z in reversed(pts)]
    if kind == "U":
        return all(abs(a - b) <= SYMMETRY_TOL for a, b in zip(pts, mirror))
    if kind == "S":
        return all(abs(a - b) <= SYMMETRY_TOL for a, b in zip(pts, turn))
    if kind == "I":
        ext = [0j] + pts + [1 + 0j]
        return all(abs(z.imag) <= SYMMETRY_TOL for z in pts) and all(a.real <= b.real + SYMMETRY_TOL
                                                                      for a, b in zip(ext, ext[1:]))
    return True


def _template(problem: IsohedralProblem, tiling: IsohedralTiling, tol: float) -> list[Violation]:
    t = isohedral_type(problem.type)
    out = []
    for i, (shape, kind) in enumerate(zip(problem.edges, t.edge_kinds)):
        if not _kind_ok(shape, kind):
            out.append(Violation("edge", f"edge class {i} breaks its {kind} constraint"))
    verts = _linear(t.vertex_coeffs, problem.params)
    poly = tiling.outline
    corners = list(tiling.corners) + [len(poly)]
    for k in range(t.n_vertices):
        p = complex(*verts[k])
        q = complex(*verts[(k + 1) % t.n_vertices])
        flip, rot = t.orientations[k]
        path = _unit_path(problem.edges[t.edge_classes[k]])
        if flip and rot:
            path = [z.conjugate() for z in path]
        elif flip:
            path = [complex(1 - z.real, z.imag) for z in reversed(path)]
        elif rot:
            path = [1 - z for z in reversed(path)]
        want = [p + (q - p) * z for z in path]
        got = [complex(*xy) for xy in poly[corners[k]:corners[k + 1]]] + [complex(*poly[corners[k + 1] % len(poly)])]
        if len(got) != len(want) or max(abs(a - b) for a, b in zip(got, want)) > tol:
            out.append(Violation("template", f"tiling edge {k} of the outline is not edge class {t.edge_classes[k]}'s "
                                             f"shape between tiling vertices {k} and {(k + 1) % t.n_vertices}"))
    if np.abs(_linear(t.translation_coeffs, problem.params) - tiling.translations).max() > tol:
        out.append(Violation("template", f"the translation vectors are not {t.name}'s"))
    if tiling.aspects.shape[0] != t.n_aspects or \
            np.abs(_linear(t.aspect_coeffs, problem.params) - tiling.aspects).max() > tol:
        out.append(Violation("template", f"the aspects' motions are not {t.name}'s"))
    return out


def _crossings(poly: np.ndarray, tol: float) -> list[Violation]:
    """Chords of a closed polygon that meet (but neighbours at their shared end): one row at a time."""
    z = poly[:, 0] + 1j * poly[:, 1]
    a, b = z, np.roll(z, -1)
    n = len(z)

    def side(p, q, r):
        return ((q - p).conjugate() * (r - p)).imag

    for i in range(n - 2):
        j = np.arange(i + 2, n if i > 0 else n - 1)
        if not len(j):
            continue
        s1, s2 = side(a[i], b[i], a[j]), side(a[i], b[i], b[j])
        s3, s4 = side(a[j], b[j], a[i]), side(a[j], b[j], b[i])
        box = (np.minimum(a[j].real, b[j].real) <= max(a[i].real, b[i].real) + tol) & \
              (np.minimum(a[i].real, b[i].real) <= np.maximum(a[j].real, b[j].real) + tol) & \
              (np.minimum(a[j].imag, b[j].imag) <= max(a[i].imag, b[i].imag) + tol) & \
              (np.minimum(a[i].imag, b[i].imag) <= np.maximum(a[j].imag, b[j].imag) + tol)
        hit = (s1 * s2 <= 0) & (s3 * s4 <= 0) & box
        if hit.any():
            return [Violation("simple", f"the prototile is not a simple polygon: chords {i} and {int(j[hit][0])} meet")]
    return []


def _area(poly: np.ndarray) -> float:
    x, y = poly[:, 0], poly[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


class _TorusChords:
    """Every chord of the translational unit's tiles, keyed by its midpoint modulo the lattice."""

    def __init__(self, tiles: list[np.ndarray], lattice: np.ndarray, tol: float):
        self.lattice, self.inv, self.tol = lattice, np.linalg.inv(lattice), tol
        self.q = tol * 100  # key cell: 100 tolerances wide
        self.starts = np.vstack(tiles)
        self.ends = np.vstack([np.roll(p, -1, axis=0) for p in tiles])
        self.owner = np.concatenate([np.full(len(p), a) for a, p in enumerate(tiles)])
        mid = (self.starts + self.ends) / 2
        uv = mid @ self.inv
        self.cell = np.floor(uv + 0.5 * self.q).astype(np.int64)  # lattice cell of each midpoint
        self.mid = (uv - self.cell) @ lattice  # the midpoint moved into the fundamental cell
        self.keys: dict[tuple[int, int], list[int]] = {}
        for s, key in enumerate(map(tuple, np.floor(self.mid / self.q).astype(np.int64).tolist())):
            self.keys.setdefault(key, []).append(s)

    def partners(self, s: int) -> list[int]:
        """Chords whose midpoint is chord ``s``'s (modulo the lattice) and that run it backwards."""
        m = self.mid[s]
        found = set()
        for shift in ((0, 0), (1, 0), (-1, 0), (0, 1), (0, -1), (1, 1), (1, -1), (-1, 1), (-1, -1)):
            mm = m + np.array(shift) @ self.lattice
            base = np.floor(mm / self.q).astype(np.int64)
            for dx in (-1, 0, 1):
                for dy in (-1, 0, 1):
                    for r in self.keys.get((int(base[0] + dx), int(base[1] + dy)), ()):
                        if r != s and np.abs(self.mid[r] - mm).max() <= self.tol and \
                                np.abs((self.ends[r] - self.starts[r]) + (self.ends[s] - self.starts[s])).max() <= self.tol:
                            found.add(r)
        return sorted(found)

    def shift_to(self, s: int, r: int) -> tuple[int, int]:
        """The lattice step from chord ``s``'s tile to chord ``r``'s neighbouring copy."""
        d = ((self.starts[s] + self.ends[s]) - (self.starts[r] + self.ends[r])) / 2 @ self.inv
        return int(round(d[0])), int(round(d[1]))


def _inside(points: np.ndarray, poly: np.ndarray) -> np.ndarray:
    """Even-odd test of each point against a simple polygon (crossings of a ray to +x)."""
    x, y = points[:, :1], points[:, 1:]
    ax, ay = poly[None, :, 0], poly[None, :, 1]
    bx, by = np.roll(ax, -1, axis=1), np.roll(ay, -1, axis=1)
    straddle = (ay > y) != (by > y)
    with np.errstate(divide="ignore", invalid="ignore"):
        xc = ax + (y - ay) * (bx - ax) / (by - ay)
    return ((straddle & (xc > x)).sum(axis=1) % 2) == 1


def tiling_violations(problem: IsohedralProblem, tiling: IsohedralTiling) -> list[Violation]:
    """Every way ``tiling`` fails ``problem`` (empty when it is a valid tiling of the stated type).

    >>> from tilesolve.constructive.isohedral import layout
    >>> p = IsohedralProblem(16, region=(0, 0, 3, 3))
    >>> tiling_violations(p, layout(p))
    []
    """
    t = isohedral_type(problem.type)
    if not isinstance(tiling, IsohedralTiling) or tiling.type != problem.type:
        return [Violation("shape", f"the answer is no {t.name} tiling")]
    poly, corners = np.asarray(tiling.outline, float), list(tiling.corners)
    if poly.ndim != 2 or poly.shape[1] != 2 or len(poly) < 3 or not np.isfinite(poly).all():
        return [Violation("shape", "the outline must be at least 3 finite points x, y")]
    if len(corners) != t.n_vertices or corners[0] != 0 or any(b <= a for a, b in zip(corners, corners[1:])) \
            or corners[-1] >= len(poly):
        return [Violation("shape", f"corners must be {t.n_vertices} increasing indices into the outline from 0")]
    if tiling.aspects.shape != (t.n_aspects, 2, 3) or tiling.translations.shape != (2, 2) or \
            not (np.isfinite(tiling.aspects).all() and np.isfinite(tiling.translations).all()):
        return [Violation("shape", f"{t.name} has {t.n_aspects} aspects (2x3 motions) and two translation vectors")]
    size = float(np.abs(poly).max()) + 1.0
    tol = REL_TOL * size
    out = _template(problem, tiling, tol)
    for a, m in enumerate(tiling.aspects):
        lin = m[:, :2]
        if np.abs(lin @ lin.T - np.eye(2)).max() > 1e-7:
            out.append(Violation("congruence", f"aspect {a}'s motion is not an isometry"))
    out += _crossings(poly, tol)
    det = float(tiling.translations[0, 0] * tiling.translations[1, 1] - tiling.translations[0, 1] * tiling.translations[1, 0])
    if out or abs(det) <= tol:
        return out or [Violation("torus", "the translation vectors are parallel")]
    tiles = []
    for m in tiling.aspects:
        p = poly @ m[:, :2].T + m[:, 2]
        tiles.append(p if _area(p) > 0 else p[::-1])
    total = sum(_area(p) for p in tiles)
    if abs(total - abs(det)) > 1e-6 * abs(det):
        out.append(Violation("torus", f"the tiles' areas sum to {total:.9g}, the fundamental domain's is {abs(det):.9g}"))
    chords = _TorusChords(tiles, tiling.translations, tol)
    links: set[tuple[int, int, int, int]] = set()
    for s in range(len(chords.owner)):
        found = chords.partners(s)
        if len(found) != 1:
            x, y = chords.starts[s]
            out.append(Violation("torus", f"tile {int(chords.owner[s])}'s chord from ({x:.6g}, {y:.6g}) is run backwards "
                                          f"by {len(found)} chords, not exactly 1 (a gap or an overlap)"))
            if len(out) > 20:
                return out
            continue
        di, dj = chords.shift_to(s, found[0])
        links.add((int(chords.owner[s]), int(chords.owner[found[0]]), di, dj))
    return out or _drawing(problem, tiling, tiles, links, tol)


def _drawing(problem: IsohedralProblem, tiling: IsohedralTiling, tiles: list[np.ndarray],
             links: set[tuple[int, int, int, int]], tol: float) -> list[Violation]:
    t = isohedral_type(problem.type)
    placed, colours = np.asarray(tiling.placements), np.asarray(tiling.colours)
    if placed.ndim != 2 or placed.shape[1] != 3 or colours.shape != (len(placed),):
        return [Violation("drawing", "placements must be rows i, j, aspect with one colour each")]
    if len(placed) and (placed[:, 2].min() < 0 or placed[:, 2].max() >= t.n_aspects):
        return [Violation("drawing", f"a placement names an aspect outside 0..{t.n_aspects - 1}")]
    if len(placed) and (colours.min() < 0 or colours.max() >= t.n_colours):
        return [Violation("drawing", f"a colour lies outside 0..{t.n_colours - 1}")]
    lo = placed[:, :2].min(axis=0, initial=0) - 1
    span = placed[:, :2].max(axis=0, initial=0) - lo + 2

    def key(i, j, a):  # one integer per (i, j, aspect) near the placed ones
        return ((i - lo[0]) * span[1] + (j - lo[1])) * t.n_aspects + a

    keys = key(placed[:, 0], placed[:, 1], placed[:, 2])
    order = np.argsort(keys, kind="stable")
    if len(keys) and (np.diff(keys[order]) == 0).any():
        return [Violation("drawing", "a tile is placed twice")]
    out = []
    T = tiling.translations
    x0, y0, w, h = problem.region
    boxes = np.array([[p[:, 0].min(), p[:, 1].min(), p[:, 0].max(), p[:, 1].max()] for p in tiles])
    b = boxes[placed[:, 2]] + np.tile(placed[:, :2] @ T, 2)
    away = (b[:, 0] > x0 + w + tol) | (b[:, 2] < x0 - tol) | (b[:, 1] > y0 + h + tol) | (b[:, 3] < y0 - tol)
    if away.any():
        out.append(Violation("drawing", f"placed tile {int(np.argmax(away))} lies outside the region"))
    for a, a2, di, dj in sorted(links):
        mine = np.flatnonzero(placed[:, 2] == a)
        want = key(placed[mine, 0] + di, placed[mine, 1] + dj, a2)
        inside = (placed[mine, 0] + di >= lo[0]) & (placed[mine, 0] + di < lo[0] + span[0]) & \
                 (placed[mine, 1] + dj >= lo[1]) & (placed[mine, 1] + dj < lo[1] + span[1])
        pos = np.clip(np.searchsorted(keys[order], want), 0, max(len(keys) - 1, 0))
        found = inside & (keys[order][pos] == want)
        other = order[pos[found]]
        clash = colours[mine[found]] == colours[other]
        if clash.any():
            k = int(np.argmax(clash))
            out.append(Violation("colour", f"placed tiles {int(mine[found][k])} and {int(other[k])} share an edge "
                                           "and a colour"))
            return out
    # Cover: each grid point of the region lies in some tile of the plane; that tile must be placed.
    g = (np.arange(_COVER_GRID) + 0.5 + 0.0137) / (_COVER_GRID + 0.03)
    pts = np.array([[x0 + u * w, y0 + v * h] for u in g for v in g])
    covered = np.zeros(len(pts), bool)
    inv = np.linalg.inv(T)
    uv = pts @ inv
    for a, p in enumerate(tiles):
        box_uv = np.array([[boxes[a, u], boxes[a, v]] for u in (0, 2) for v in (1, 3)]) @ inv
        first = np.floor(uv - box_uv.max(axis=0)).astype(np.int64) - 1  # the cells whose tile's box may hold a point
        reach = np.ceil(box_uv.max(axis=0) - box_uv.min(axis=0)).astype(np.int64) + 3
        di, dj = np.meshgrid(np.arange(reach[0]), np.arange(reach[1]), indexing="ij")
        n = np.repeat(np.arange(len(pts)), di.size)
        i, j = first[n, 0] + np.tile(di.ravel(), len(pts)), first[n, 1] + np.tile(dj.ravel(), len(pts))
        ok = (i >= lo[0]) & (i < lo[0] + span[0]) & (j >= lo[1]) & (j < lo[1] + span[1])
        want = key(i, j, a)
        pos = np.clip(np.searchsorted(keys[order], want), 0, max(len(keys) - 1, 0))
        ok &= keys[order][pos] == want
        local = pts[n[ok]] - np.stack([i[ok], j[ok]], axis=1) @ T
        covered[n[ok][_inside(local, p)]] = True
    if not covered.all():
        x, y = pts[np.argmin(covered)]
        out.append(Violation("drawing", f"the point ({x:.6g}, {y:.6g}) of the region lies in no placed tile"))
    return out
