"""Independent checks of substitution patches: Penrose P3/P2 and rep-tiles (class notes Part II
§8.1, §8.3). Written from the definitions; shares no code with the generators.

Penrose patches (:func:`penrose_violations`)
    1. *Shapes.* Every tile is a thin or thick rhomb of edge 1 (P3) or a kite or dart with
       long edges ``phi`` and short edges 1 (P2), counter-clockwise from its marked vertex
       (P3: the thin rhomb's marked obtuse, the thick's marked acute vertex; P2: the kite's
       head, the dart's tip). Coordinates are exact integers in ``Z[zeta5]``, and so is the
       check: every edge vector must be one of the ten unit vectors ``exp(i pi d / 5)`` or
       ``phi`` times one (a table of the ring's elements with coordinates -2..2), and the
       angles follow from the directions ``d``.
    2. *Edges.* Every edge (exact endpoints) belongs to at most two tiles, which run it in
       opposite directions (same direction = two tiles on one side: an overlap).
    3. *Matching rules* across every shared edge (Penrose's arrows): every edge carries an
       arrow of a class; both tiles must give the same class and the same direction. P3: the
       two edges at the marked vertex carry double arrows (away from it on the thick rhomb,
       towards it on the thin), the other two single arrows towards the vertex opposite it.
       P2: long edges arrows from the head (kite) or towards the tip (dart), short edges towards
       the tail (kite) or away from the reflex vertex (dart).
    4. *No overlap and no gap around a vertex.* The tile angles at a vertex sum to at most
       360 degrees, and to exactly 360 at an interior vertex (all its edges shared).
    5. *No holes.* ``V - E + F = 1`` (a hole lowers it).
    6. *One sheet, one piece.* The edges that only one tile runs (the boundary) meet only at
       common endpoints (none within 1e-3 of another elsewhere, none lying along another); the
       boundary is connected; and a point just inside each boundary edge (1e-4 from its
       midpoint) lies in exactly one tile (a spatial grid finds the tiles near it).

    Why that excludes every overlap, even far from any shared edge: by checks 2 and 4 the tiles
    cover a point ``x`` (off the edges) ``w(x)`` times, where ``w`` is the winding number of the
    boundary around ``x`` (the tiles' boundaries sum to the boundary: inner edges cancel). ``w``
    is constant on each face of the boundary, which is a plane graph by check 6, and drops by
    exactly 1 across each boundary edge, from its tile's side. A face of largest ``w`` lies on
    the tile's side of each of its edges, so the point just inside such an edge lies in ``w``
    tiles: check 6 makes ``w <= 1``, no overlap. The patch is then a plane region whose boundary
    is connected, so one piece, and without holes by check 5: a disk (joined at single
    vertices, perhaps, where a window's edge cuts it). Checks 1-5 alone let a second sheet lie
    over the first with no edge or vertex in common (tests/verify/test_substitution.py).

Rep-tile patches (:func:`reptile_violations`)
    1. Every tile is congruent to the prototile (its edge vectors are the prototile's under a
       symmetry of the lattice, from some starting corner), counter-clockwise.
    2. Cut every edge into unit lattice steps: an inner step is run by exactly two tiles in
       opposite directions, and the steps run once are exactly the boundary of ``2^n P``. Then the
       tiles' indicator functions sum to the region's (the sum jumps only across the region's
       boundary): no gap and no overlap.
"""

from __future__ import annotations

import numpy as np

from tilesolve.verify.dappled import Violation

__all__ = ["penrose_violations", "reptile_violations", "PROTOTILE_OUTLINES"]

_PHI = (1 + 5**0.5) / 2

#: Per Penrose kind and type: the edge lengths (1 or phi) and the interior angles in units of
#: 36 degrees at vertices 0..3.
_SHAPES = {
    ("p3", 0): ((1, 1, 1, 1), (4, 1, 4, 1)),       # thin rhomb from its marked obtuse vertex
    ("p3", 1): ((1, 1, 1, 1), (2, 3, 2, 3)),       # thick rhomb from its marked acute vertex
    ("p2", 0): ((_PHI, 1, 1, _PHI), (2, 2, 4, 2)),  # kite from its head
    ("p2", 1): ((_PHI, 1, 1, _PHI), (2, 1, 6, 1)),  # dart from its tip
}
def _edge_table() -> tuple[np.ndarray, np.ndarray]:
    """Every ring element with coordinates in -2..2, by code ``sum (c_k + 2) 5^k``: its direction
    in units of 36 degrees and its length class (0: length 1, 1: length phi), -1 for the others
    (classified from floats with a margin of 1e-9: no two of these 625 values are that close)."""
    c = np.array(list(np.ndindex(5, 5, 5, 5)))[:, ::-1] - 2
    xy = _xy5(c)
    length = np.hypot(xy[:, 0], xy[:, 1])
    turns = np.arctan2(xy[:, 1], xy[:, 0]) / (np.pi / 5)
    on_grid = np.abs(turns - np.rint(turns)) < 1e-9
    size = np.where(on_grid & (np.abs(length - 1) < 1e-9), 0, np.where(on_grid & (np.abs(length - _PHI) < 1e-9), 1, -1))
    direction = np.where(size >= 0, np.rint(turns).astype(np.int64) % 10, -1)
    return direction, size


_NAMES = {("p3", 0): "thin rhomb", ("p3", 1): "thick rhomb", ("p2", 0): "kite", ("p2", 1): "dart"}

#: The rep-tiles' corners, counter-clockwise, in lattice coordinates (square: x, y; triangle:
#: a, b of a + b exp(i pi / 3)).
PROTOTILE_OUTLINES = {
    "chair": ("square", ((0, 0), (2, 0), (2, 1), (1, 1), (1, 2), (0, 2))),
    "l-tetromino": ("square", ((0, 0), (3, 0), (3, 1), (1, 1), (1, 2), (0, 2))),
    "p-pentomino": ("square", ((0, 0), (2, 0), (2, 2), (1, 2), (1, 3), (0, 3))),
    "sphinx": ("triangle", ((0, 0), (3, 0), (2, 1), (1, 1), (0, 2))),
}


def _xy5(v: np.ndarray) -> np.ndarray:
    ang = 2 * np.pi * np.arange(4) / 5
    v = v.astype(np.float64)
    return np.stack([v @ np.cos(ang), v @ np.sin(ang)], axis=-1)


_EDGE_DIRECTION, _EDGE_LENGTH = _edge_table()


def _labels(x: np.ndarray) -> np.ndarray:
    """Labels 0..k-1 of integers, equal exactly for equal values."""
    return np.unique(x, return_inverse=True)[1].ravel()


def _keys(rows: np.ndarray) -> np.ndarray:
    """Integer labels, equal exactly for equal rows: the rows packed into one int64 in mixed
    radix when their ranges allow, else compared as bytes."""
    rows = np.ascontiguousarray(rows, dtype=np.int64)
    lo = rows.min(axis=0)
    span = (rows.max(axis=0) - lo + 1).astype(object)
    if int(np.prod(span)) < 2**62:
        packed = np.zeros(len(rows), dtype=np.int64)
        for col in range(rows.shape[1]):
            packed = packed * int(span[col]) + (rows[:, col] - lo[col])
        return _labels(packed)
    return _labels(rows.view(np.dtype((np.void, 8 * rows.shape[1]))).ravel())


def penrose_violations(kind: str, types, vertices) -> list[Violation]:
    """Every way ``(types, vertices)`` fails to be a Penrose patch of ``kind`` (``"p3"`` or
    ``"p2"``) with its matching rules (the module docstring's checks 1-6); ``[]`` when valid."""
    types = np.asarray(types)
    v = np.asarray(vertices)
    out: list[Violation] = []
    n = len(types)
    if v.shape != (n, 4, 4) or not np.issubdtype(v.dtype, np.integer):
        return [Violation("shape", f"expected {n} tiles of 4 vertices with 4 integer coordinates, got {list(v.shape)}")]
    if n == 0:
        return [Violation("count", "the patch has no tiles")]
    if not np.isin(types, (0, 1)).all():
        return [Violation("tile", "a tile type is not 0 or 1")]
    # 1. shapes: every edge vector, exactly, by its small integer coordinates
    e = np.roll(v, -1, axis=1) - v
    small = (np.abs(e) <= 2).all(axis=2)
    code = np.where(small, e[..., 0] + 5 * e[..., 1] + 25 * e[..., 2] + 125 * e[..., 3] + 312, 0)  # sum (e_k + 2) 5^k
    d, size = _EDGE_DIRECTION[code], _EDGE_LENGTH[code]
    d[~small], size[~small] = -1, -1
    angle = (np.roll(d, 1, axis=1) + 5 - d) % 10  # interior angle at vertex i: from edge i to reversed edge i-1
    for t in (0, 1):
        lengths, angles = _SHAPES[(kind, t)]
        sel = types == t
        bad = (size[sel] != np.array([int(x != 1) for x in lengths])).any(axis=1) | (d[sel] < 0).any(axis=1) | \
            (angle[sel] != np.array(angles)).any(axis=1)
        for i in np.flatnonzero(sel)[bad][:20]:
            out.append(Violation("tile", f"tile {i} is no {_NAMES[(kind, t)]} counter-clockwise from its marked vertex"))
    if out:
        return out
    # 2. edges: each (tile, side) runs from vertex s to s+1; vertices and edges by exact labels.
    # One sort of the undirected edges groups each edge's runs; `first`, `second` pair an edge's two runs.
    vkeys = _keys(v.reshape(-1, 4))
    n_vertices = int(vkeys.max()) + 1
    start = vkeys.reshape(n, 4)
    end = np.roll(start, -1, axis=1)
    key = (np.minimum(start, end) * n_vertices + np.maximum(start, end)).ravel()
    order = np.argsort(key, kind="stable")
    new_edge = np.concatenate([[True], key[order][1:] != key[order][:-1]])
    undirected = np.empty(len(key), np.int64)
    undirected[order] = np.cumsum(new_edge) - 1
    counts = np.diff(np.append(np.flatnonzero(new_edge), len(key)))
    for u in np.flatnonzero(counts > 2)[:20]:
        out.append(Violation("overlap", f"an edge is shared by {counts[u]} tiles (tiles "
                                        f"{sorted(set((np.flatnonzero(undirected == u) // 4).tolist()))})"))
    if out:
        return out
    twice = np.flatnonzero(new_edge)[counts == 2]
    first, second = order[twice], order[twice + 1]
    same_way = start.ravel()[first] == start.ravel()[second]
    for i, j in zip(first[same_way][:20], second[same_way][:20]):
        out.append(Violation("overlap", f"tiles {[i // 4, j // 4]} run one edge the same way "
                                        "(they lie on the same side of it)"))
    if out:
        return out
    # 3. matching rules: class (0 single / 1 double, or 0 short / 1 long) and arrow sense
    side = np.tile(np.arange(4), n)
    t4 = np.repeat(types, 4)
    near = (side == 0) | (side == 3)                  # the edges at the marked vertex
    # whether the canonical arrow (near: away from vertex 0; far: towards vertex 2) points along the side's run
    canonical = np.where(near, side == 0, side == 1)
    if kind == "p3":
        sense = np.where(near & (t4 == 0), ~canonical, canonical)  # thin rhomb's double arrows point in
    else:
        sense = np.where(t4 == 1, ~canonical, canonical)           # the dart's arrows are the kite's reversed
    cls = near.astype(np.int64)
    shared = counts[undirected] == 2
    # the two tiles run the edge in opposite directions: equal arrows means opposite senses
    bad = (cls[first] != cls[second]) | (sense[first] == sense[second])
    for i, j in zip(first[bad][:20], second[bad][:20]):
        out.append(Violation("matching", f"tiles {i // 4} and {j // 4} break the matching rule on their shared edge"))
    if out:
        return out
    # 4. angles around vertices
    total = np.bincount(vkeys, weights=angle.ravel()).astype(np.int64)
    for u in np.flatnonzero(total > 10)[:20]:
        out.append(Violation("overlap", f"the tiles at vertex {v.reshape(-1, 4)[np.flatnonzero(vkeys == u)[0]].tolist()}"
                                        f" fill {36 * total[u]} degrees"))
    open_edge = ~shared
    on_boundary = np.zeros(len(total), bool)
    on_boundary[start.ravel()[open_edge]] = True
    on_boundary[end.ravel()[open_edge]] = True
    for u in np.flatnonzero(~on_boundary & (total != 10))[:20]:
        out.append(Violation("gap", f"the tiles around interior vertex {v.reshape(-1, 4)[np.flatnonzero(vkeys == u)[0]].tolist()}"
                                    f" fill {36 * total[u]} degrees, not 360"))
    # 5. no holes
    chi = len(total) - len(counts) + n  # labels are 0..V-1 and 0..E-1
    if chi != 1:
        out.append(Violation("gap", f"the patch is not one piece without holes (V - E + F = {chi})"))
    return out or _one_sheet(v, start.ravel(), end.ravel(), np.flatnonzero(open_edge))


def _near(a: np.ndarray, b: np.ndarray, size: float) -> tuple[np.ndarray, np.ndarray]:
    """Pairs ``(i, j)`` of points ``a[i]``, ``b[j]`` in the same or adjacent cells of a grid of
    squares of side ``size`` (every pair closer than ``size``, and some farther)."""
    ca, cb = np.floor(a / size).astype(np.int64), np.floor(b / size).astype(np.int64)
    lo = np.minimum(ca.min(axis=0), cb.min(axis=0)) - 1
    rows = int(max(ca[:, 1].max(), cb[:, 1].max()) - lo[1]) + 3
    key_b = (cb[:, 0] - lo[0]) * rows + (cb[:, 1] - lo[1])
    shifts = [(dx, dy) for dx in (-1, 0, 1) for dy in (-1, 0, 1)]
    keys_a = [(ca[:, 0] + dx - lo[0]) * rows + (ca[:, 1] + dy - lo[1]) for dx, dy in shifts]
    near_a = np.flatnonzero(np.isin(key_b, np.concatenate(keys_a)))  # sort only the points of b near a's
    order = near_a[np.argsort(key_b[near_a], kind="stable")]
    sorted_b = key_b[order]
    ia, ib = [], []
    for key in keys_a:
        first, last = np.searchsorted(sorted_b, key), np.searchsorted(sorted_b, key, side="right")
        count = last - first
        ia.append(np.repeat(np.arange(len(a)), count))
        ib.append(order[np.repeat(first, count) + np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)])
    return np.concatenate(ia), np.concatenate(ib)


def _cross(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]


def _to_segment(x: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distance from points ``x`` to segments ``ab`` (row by row)."""
    d = b - a
    t = np.clip(np.sum((x - a) * d, axis=1) / np.sum(d * d, axis=1), 0, 1)
    return np.hypot(*(a + t[:, None] * d - x).T)


def _one_sheet(v: np.ndarray, start: np.ndarray, end: np.ndarray, boundary: np.ndarray) -> list[Violation]:
    """Check 6 of the module docstring: ``boundary`` indexes the (tile, side) pairs, ``tile * 4 +
    side``, that only one tile runs; ``start`` and ``end`` are their vertex labels."""
    out: list[Violation] = []
    corners = v.reshape(-1, 4)
    p, q = _xy5(corners[boundary]), _xy5(corners[(boundary // 4) * 4 + (boundary + 1) % 4])
    s, e = start[boundary], end[boundary]
    # the boundary is connected (union-find over its vertices)
    parent = {int(v): int(v) for v in np.concatenate([s, e])}

    def root(v):
        while parent[v] != v:
            parent[v] = parent[parent[v]]
            v = parent[v]
        return v

    for a, b in zip(s.tolist(), e.tolist()):
        parent[root(a)] = root(b)
    pieces = len({root(v) for v in parent})
    if pieces > 1:
        out.append(Violation("gap", f"the patch's boundary is {pieces} separate curves (several pieces, or a hole)"))
    # boundary edges meet only at common endpoints
    i, j = _near((p + q) / 2, (p + q) / 2, 2.0)
    keep = i < j
    i, j = i[keep], j[keep]
    shared = (s[i] == s[j]) | (s[i] == e[j]) | (e[i] == s[j]) | (e[i] == e[j])
    ends = [(p[i], s[i], p[j], q[j], s[j], e[j]), (q[i], e[i], p[j], q[j], s[j], e[j]),
            (p[j], s[j], p[i], q[i], s[i], e[i]), (q[j], e[j], p[i], q[i], s[i], e[i])]
    # each endpoint's distance to the other edge; a common endpoint's (0) does not count
    gaps = [_to_segment(x, a, b) for x, _, a, b, _, _ in ends]
    far = np.minimum.reduce([np.where((lab == la) | (lab == lb), np.inf, g) for g, (_, lab, _, _, la, lb) in zip(gaps, ends)])
    cross = (_cross(q[i] - p[i], p[j] - p[i]) * _cross(q[i] - p[i], q[j] - p[i]) < 0) & \
        (_cross(q[j] - p[j], p[i] - p[j]) * _cross(q[j] - p[j], q[i] - p[j]) < 0)
    touch = (far < 1e-3) | (cross & ~shared)
    for a, b in zip(i[touch][:20], j[touch][:20]):
        out.append(Violation("overlap", f"boundary edges of tiles {boundary[a] // 4} and {boundary[b] // 4} cross or "
                                        "touch away from a common vertex (the patch lies over itself)"))
    if touch.any():
        return out
    # just inside each boundary edge, exactly one tile
    d = q - p
    probe = (p + q) / 2 + 1e-4 * np.stack([-d[:, 1], d[:, 0]], axis=1) / np.hypot(d[:, 0], d[:, 1])[:, None]
    k, t = _near(probe, _xy5(v.sum(axis=1)) / 4, 2.0)
    rel = _xy5(v[t]) - probe[k][:, None, :]
    side = _cross(rel, np.roll(rel, -1, axis=1))  # >= 0 on all sides of a triangle: inside (closed)
    diag = _cross(rel[:, 0], rel[:, 2])
    inside = ((side[:, 0] >= -1e-9) & (side[:, 1] >= -1e-9) & (-diag >= -1e-9)) | \
        ((diag >= -1e-9) & (side[:, 2] >= -1e-9) & (side[:, 3] >= -1e-9))
    covered = np.bincount(k[inside], minlength=len(probe))
    for a in np.flatnonzero(covered != 1)[:20]:
        out.append(Violation("overlap", f"tiles {sorted(set(t[(k == a) & inside].tolist()))} lie over one point "
                                        f"near {np.round(probe[a], 3).tolist()} (the patch lies over itself)"))
    return out


def _lattice_xy(grid: str, p: np.ndarray) -> np.ndarray:
    p = p.astype(np.float64)
    if grid == "square":
        return p
    return np.stack([p[..., 0] + 0.5 * p[..., 1], p[..., 1] * (3**0.5 / 2)], axis=-1)


def _symmetries(grid: str) -> list[np.ndarray]:
    """The lattice's point group as integer matrices (8 on the square grid, 12 on the triangle grid)."""
    if grid == "square":
        gens = [np.array([[0, -1], [1, 0]]), np.array([[-1, 0], [0, 1]])]
    else:
        gens = [np.array([[0, -1], [1, 1]]), np.array([[0, 1], [1, 0]])]
    found = {tuple(np.eye(2, dtype=np.int64).ravel())}
    frontier = [np.eye(2, dtype=np.int64)]
    while frontier:
        m = frontier.pop()
        for g in gens:
            p = g @ m
            if tuple(p.ravel()) not in found:
                found.add(tuple(p.ravel()))
                frontier.append(p)
    return [np.array(k).reshape(2, 2) for k in sorted(found)]


def _unit_steps(polys: np.ndarray) -> np.ndarray:
    """The polygons' edges ``(n, m, 2)`` cut into unit lattice steps: rows ``(x0, y0, x1, y1)``."""
    a = polys.reshape(-1, 2)
    d = (np.roll(polys, -1, axis=1) - polys).reshape(-1, 2)
    g = np.gcd(np.abs(d[:, 0]), np.abs(d[:, 1]))
    step = d // np.maximum(g, 1)[:, None]
    first = np.repeat(np.cumsum(g) - g, g)
    i = np.arange(int(g.sum())) - first
    start = np.repeat(a, g, axis=0) + i[:, None] * np.repeat(step, g, axis=0)
    return np.concatenate([start, start + np.repeat(step, g, axis=0)], axis=1)


def reptile_violations(kind: str, steps: int, vertices) -> list[Violation]:
    """Every way ``vertices`` (tiles ``(n, m, 2)``) fails to tile ``2^steps P`` with copies of
    the rep-tile ``kind`` (the module docstring's checks 1-2); ``[]`` when valid."""
    grid, corners = PROTOTILE_OUTLINES[kind]
    proto = np.array(corners, dtype=np.int64)
    v = np.asarray(vertices)
    m = len(proto)
    if v.ndim != 3 or v.shape[1:] != (m, 2) or not np.issubdtype(v.dtype, np.integer) or not len(v):
        return [Violation("shape", f"expected tiles of {m} corners with 2 integer coordinates, got {list(v.shape)}")]
    v = v.astype(np.int64)
    out: list[Violation] = []
    # 1. congruence: the edge vectors, from some corner, are g (prototile edge vectors)
    pe = np.roll(proto, -1, axis=0) - proto
    allowed = []
    for g in _symmetries(grid):
        ge = pe @ g.T
        if np.linalg.det(g) < 0:  # a mirror reverses the order: walk the image backwards
            ge = -ge[::-1]
        allowed += [np.roll(ge, -s, axis=0).ravel() for s in range(m)]
    te = (np.roll(v, -1, axis=1) - v).reshape(len(v), -1)
    labels = _keys(np.concatenate([np.array(allowed), te]))
    bad = ~np.isin(labels[len(allowed):], labels[:len(allowed)])
    out += [Violation("tile", f"tile {i} is no counter-clockwise copy of the {kind}") for i in np.flatnonzero(bad)[:20]]
    if out:
        return out
    # 2. unit steps: inner ones twice in opposite directions, the rest exactly the region's boundary
    fwd = _unit_steps(v)
    region = _unit_steps(proto[None] * (2**steps))
    rows = np.concatenate([fwd, fwd[:, [2, 3, 0, 1]], region])
    lab = _keys(rows)
    n = len(fwd)
    f, r, e = lab[:n], lab[n:2 * n], lab[2 * n:]
    counts = np.bincount(f, minlength=len(rows))
    for u in np.flatnonzero(counts > 1)[:20]:
        row = rows[np.flatnonzero(lab == u)[0]]
        out.append(Violation("overlap", f"two tiles run the step {tuple(row[:2])} -> {tuple(row[2:])} the same way"))
    if out:
        return out
    once = np.setdiff1d(f, r)  # steps whose reverse no tile runs
    for u in np.setdiff1d(once, e)[:20]:
        row = rows[np.flatnonzero(lab == u)[0]]
        out.append(Violation("gap", f"the step {tuple(row[:2])} -> {tuple(row[2:])} borders a gap or an overlap "
                                    "inside the patch"))
    for u in np.setdiff1d(e, once)[:20]:
        row = rows[np.flatnonzero(lab == u)[0]]
        out.append(Violation("gap", f"the region's boundary step {tuple(row[:2])} -> {tuple(row[2:])} is not a tile's"))
    return out
