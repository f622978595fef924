"""Independent checks of polyform answers (class notes Part II §3), written from the definitions
in the plane, apart from the encoder's integer placements:

- a *congruent copy*: the piece's cell centroids (Cartesian, from the cells' corners) are the
  shape's under a rotation by a multiple of 360/order degrees, optionally a reflection, and a
  translation;
- a *tiling* of a region: every region cell covered exactly once, no cell outside; of a torus
  ``Z^2 / L``: every class of cells modulo the periods covered exactly once;
- *isohedral*: for every tile an isometry of the plane that maps the periodic tiling onto itself
  (modulo ``L``) and tile 0 onto that tile;
- *coronas*: tiles disjoint; a tile's level is its distance from the shape in the graph of tiles
  that share a corner; every cell sharing a corner with the tiles of levels ``< j`` is covered by
  a tile of level ``<= j``, for ``j = 1..H``; without holes, every cell outside the patch
  reaches the far outside through edges of cells outside the patch.
"""

from __future__ import annotations

import math

import numpy as np

from tilesolve.model.shapes import VERDICTS, Grid, ShapesProblem, ShapesReport

__all__ = ["shapes_violations", "tiling_violations", "report_violations"]

_ROUND = 6


def shapes_violations(problem: ShapesProblem, answer) -> list[str]:
    """Violations of a tiling (``tile``) or a report (``classify``); empty when valid."""
    if isinstance(answer, ShapesReport):
        return report_violations(problem, answer)
    return tiling_violations(problem, answer)


def _isometries(g: Grid, reflections: bool) -> list[np.ndarray]:
    out = []
    for k in range(g.order):
        a = 2 * math.pi * k / g.order
        r = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
        out.append(r)
        if reflections:
            out.append(r @ np.array([[1.0, 0.0], [0.0, -1.0]]))
    return out


def _centroids(g: Grid, cells) -> np.ndarray:
    return np.asarray([g.to_xy(g.vertices(c)).mean(axis=0) for c in cells]).reshape(-1, 2)


def _pointset(points: np.ndarray) -> set:
    return {(round(float(x), _ROUND) + 0.0, round(float(y), _ROUND) + 0.0) for x, y in points}


def _congruent(g: Grid, cells, shape_cells, reflections: bool) -> bool:
    if len(cells) != len(shape_cells):
        return False
    a = _centroids(g, cells)
    b = _centroids(g, shape_cells)
    target = _pointset(a)
    for m in _isometries(g, reflections):
        img = b @ m.T
        img = img + (a.mean(axis=0) - img.mean(axis=0))
        if _pointset(img) == target:
            return True
    return False


def _pieces(tiling) -> tuple[dict, list[str]]:
    t = np.asarray(tiling)
    if t.ndim != 2 or t.shape[1] != 4 or t.shape[0] == 0:
        return {}, ["the tiling must be rows (piece, shape or level, x, y)"]
    pieces: dict = {}
    bad = []
    for piece, label, x, y in t.tolist():
        entry = pieces.setdefault(int(piece), (int(label), []))
        if entry[0] != label:
            bad.append(f"piece {piece}: its rows name both {entry[0]} and {label}")
        entry[1].append((int(x), int(y)))
    return pieces, bad


class _Torus:
    """Cells or points modulo ``period * L``, by their coordinates in the basis of ``L``."""

    def __init__(self, g: Grid, lattice):
        scale = 1 if g.name == "omino" else 3  # a translation unit in the corners' frame
        self.cart = g.to_xy(scale * np.asarray(lattice, dtype=float))  # rows: the periods in the plane
        self.inv = np.linalg.inv(self.cart)

    def key(self, point) -> tuple:
        """A Cartesian point modulo the periods."""
        c = np.asarray(point, dtype=float) @ self.inv
        c = c - np.floor(c + 1e-9)
        return tuple(round(float(v), _ROUND) % 1.0 for v in c)


def _cover_errors(cells_of: dict, universe: set | None, key) -> list[str]:
    seen: dict = {}
    bad = []
    for piece, (_, cells) in cells_of.items():
        for c in cells:
            k = key(c)
            if universe is not None and k not in universe:
                bad.append(f"piece {piece} covers {c}, outside the region")
            elif k in seen:
                bad.append(f"cell {c} is covered by pieces {seen[k]} and {piece}")
            else:
                seen[k] = piece
    if universe is not None:
        missing = sorted(universe - set(seen))
        bad += [f"cell {c} is not covered" for c in missing[:20]]
    return bad


def tiling_violations(problem: ShapesProblem, tiling) -> list[str]:
    """Violations of a tiling of the problem's region or torus by copies of its shapes."""
    g = problem.geometry
    pieces, bad = _pieces(tiling)
    if bad or not pieces:
        return bad
    for piece, (shape, cells) in sorted(pieces.items()):
        if not 0 <= shape < len(problem.shapes):
            bad.append(f"piece {piece} names shape {shape}, not one of 0..{len(problem.shapes) - 1}")
            continue
        if not all(g.is_cell(c) for c in cells) or not _congruent(g, cells, problem.shapes[shape].cells,
                                                                   problem.reflections):
            bad.append(f"piece {piece} is not a congruent copy of shape {shape}")
    if bad:
        return bad
    if problem.region is not None:
        return _cover_errors(pieces, set(problem.region), lambda c: c)
    return _torus_cover(g, problem.lattice, pieces, problem.n_cells())


def _torus_cover(g: Grid, lattice, pieces: dict, n_cells: int) -> list[str]:
    torus = _Torus(g, lattice)
    bad = _cover_errors(pieces, None, lambda c: torus.key(_centroids(g, [c])[0]))
    covered = sum(len(c) for _, c in pieces.values())
    if not bad and covered != n_cells:
        bad.append(f"the pieces cover {covered} cells, but the torus has {n_cells}")
    return bad


def _isohedral_errors(g: Grid, lattice, pieces: dict, reflections: bool) -> list[str]:
    torus = _Torus(g, lattice)
    cents = {p: _centroids(g, cells) for p, (_, cells) in pieces.items()}
    keys = {p: frozenset(torus.key(x) for x in c) for p, c in cents.items()}
    tiles = set(keys.values())
    first = min(cents)
    a0 = cents[first]
    lat = torus.cart
    out = []
    for p in sorted(cents):
        ok = False
        for m in _isometries(g, reflections):
            # the isometry must keep the periods' lattice
            img_l = lat @ m.T
            coeff = img_l @ torus.inv
            if not np.allclose(coeff, np.round(coeff), atol=1e-6):
                continue
            img0 = a0 @ m.T
            for target in cents[p]:
                shift = target - img0[0]
                if frozenset(torus.key(x) for x in img0 + shift) != keys[p]:
                    continue
                if all(frozenset(torus.key(x) for x in c @ m.T + shift) in tiles for c in cents.values()):
                    ok = True
                    break
            if ok:
                break
        if not ok:
            out.append(f"no symmetry of the tiling maps piece {first} onto piece {p}: it is not isohedral")
    return out


def _corner_cells(g: Grid, cells: set) -> set:
    """Cells outside ``cells`` that share a corner with one of them."""
    corners = {v for c in cells for v in g.vertices(c)}
    xs = [c[0] for c in cells]
    ys = [c[1] for c in cells]
    m = 2 * g.period + 1
    out = set()
    for x in range(min(xs) - m, max(xs) + m + 1):
        for y in range(min(ys) - m, max(ys) + m + 1):
            c = (x, y)
            if c not in cells and g.is_cell(c) and corners & set(g.vertices(c)):
                out.add(c)
    return out


def _patch_errors(problem: ShapesProblem, report: ShapesReport) -> list[str]:
    g = problem.geometry
    pieces, bad = _pieces(report.patch)
    if bad:
        return bad
    shape = problem.shapes[0].cells
    if 0 not in pieces or pieces[0][0] != 0 or sorted(pieces[0][1]) != sorted(shape):
        return ["piece 0 of the patch must be the shape itself, at level 0"]
    owner = {}
    for p, (_, cells) in pieces.items():
        if p and not _congruent(g, cells, shape, problem.reflections):
            bad.append(f"patch piece {p} is not a congruent copy of the shape")
        for c in cells:
            if c in owner:
                bad.append(f"cell {c} is covered by patch pieces {owner[c]} and {p}")
            owner[c] = p
    if bad:
        return bad
    corners = {p: {v for c in cells for v in g.vertices(c)} for p, (_, cells) in pieces.items()}
    level = {0: 0}
    frontier = [0]
    while frontier:
        nxt = []
        for p in frontier:
            for q in pieces:
                if q not in level and corners[p] & corners[q]:
                    level[q] = level[p] + 1
                    nxt.append(q)
        frontier = nxt
    for p, (lv, _) in sorted(pieces.items()):
        if level.get(p) != lv:
            bad.append(f"patch piece {p} is recorded at level {lv}, but its distance from the shape is {level.get(p)}")
    if bad:
        return bad
    top = max(level.values())
    if top != report.heesch:
        return [f"the patch has {top} corona(s), but the report says {report.heesch}"]
    for j in range(1, top + 1):
        inner = {c for p, (lv, cells) in pieces.items() if lv < j for c in cells}
        upto = {c for p, (lv, cells) in pieces.items() if lv <= j for c in cells}
        missing = sorted(_corner_cells(g, inner) - upto)
        if missing:
            bad.append(f"corona {j} does not surround the patch inside it: cell {missing[0]} is uncovered")
    if not bad and not report.holes:
        bad += _hole_errors(g, set(owner))
    return bad


def _hole_errors(g: Grid, cells: set) -> list[str]:
    """A cell outside ``cells`` from which no path through edge-sharing outside cells leaves
    the box around them."""
    ring = _corner_cells(g, cells)
    ring |= _corner_cells(g, cells | ring)
    xs = [c[0] for c in ring]
    ys = [c[1] for c in ring]
    far = {c for c in ring if c[0] in (min(xs), max(xs)) or c[1] in (min(ys), max(ys))}
    free = ring | {c for c in _box(g, ring) if c not in cells}
    reach, todo = set(far), list(far)
    while todo:
        c = todo.pop()
        vs = set(g.vertices(c))
        for d in _near(g, c):
            if d in free and d not in reach and len(vs & set(g.vertices(d))) == 2:
                reach.add(d)
                todo.append(d)
    holes = sorted(c for c in free if c not in reach)
    return [f"the patch has a hole at cell {holes[0]} (H_c counts patches without holes)"] if holes else []


def _box(g: Grid, cells: set) -> set:
    xs = [c[0] for c in cells]
    ys = [c[1] for c in cells]
    return {(x, y) for x in range(min(xs), max(xs) + 1) for y in range(min(ys), max(ys) + 1) if g.is_cell((x, y))}


def _near(g: Grid, c) -> list:
    r = 2 * g.period
    return [(c[0] + dx, c[1] + dy) for dx in range(-r, r + 1) for dy in range(-r, r + 1)
            if (dx, dy) != (0, 0) and g.is_cell((c[0] + dx, c[1] + dy))]


def report_violations(problem: ShapesProblem, report: ShapesReport) -> list[str]:
    """Violations of a classification report's certificates."""
    if report.verdict not in VERDICTS:
        return [f"unknown verdict {report.verdict!r}"]
    g = problem.geometry
    shape = problem.shapes[0]
    if report.verdict in ("isohedral", "periodic"):
        if report.tiling is None or report.lattice is None or report.copies is None:
            return [f"a {report.verdict} verdict needs a torus tiling, its lattice and its copies"]
        pieces, bad = _pieces(report.tiling)
        if bad:
            return bad
        if len(pieces) != report.copies:
            bad.append(f"the torus tiling has {len(pieces)} pieces, but the report says {report.copies} copies")
        for p, (_, cells) in sorted(pieces.items()):
            if not _congruent(g, cells, shape.cells, problem.reflections):
                bad.append(f"torus piece {p} is not a congruent copy of the shape")
        if bad:
            return bad
        (a, b), (c, d) = report.lattice
        n = abs(a * d - b * c) * (2 if g.name == "iamond" else 1)
        bad += _torus_cover(g, report.lattice, pieces, n)
        if not bad and report.verdict == "isohedral":
            bad += _isohedral_errors(g, report.lattice, pieces, problem.reflections)
        return bad
    bad = []
    if report.patch is None:
        return ["the report holds no corona patch"]
    bad += _patch_errors(problem, report)
    if report.verdict == "non-tiler":
        ref = report.refutation or {}
        spec = ref.get("encoding") or {}
        opts = spec.get("options") or {}
        if spec.get("name") != "shapes-corona-cnf" or opts.get("levels") != (report.heesch or 0) + 1:
            bad.append(f"a non-tiler needs a refutation of {(report.heesch or 0) + 1} coronas")
    return bad
