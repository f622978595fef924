"""Isohedral tilings from their templates (class notes Part II §7.3-7.4): the prototile from the
tiling vertices and edge shapes, the translational unit, and the tiles that meet a region.

The tables (:func:`tilesolve.model.isohedral.isohedral_type`) give everything as linear functions
of the parameters (§7.4.1); the prototile's outline is built as in §7.4.2: each tiling edge maps
its class's shape from the unit frame onto the segment between its tiling vertices, after the
edge's orientation (flip, rotate). The region is filled lattice cell by lattice cell, the way
tactile's ``fillRegion`` does, but exactly: every (cell, aspect) whose tile's bounding box meets
the region, and no other. Tiles are coloured by the type's colouring (§7.4.1, Fig. 20).

>>> from tilesolve.model.isohedral import IsohedralProblem
>>> t = layout(IsohedralProblem(41, region=(0, 0, 4, 3)))
>>> t.n_tiles, t.aspects.shape, int(t.colours.max()) < 3
(15, (1, 2, 3), True)
"""

from __future__ import annotations

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.model.isohedral import (
    BEZIER_CHORDS,
    MAX_OUTLINE,
    MAX_TILES,
    EdgeShape,
    IsohedralProblem,
    IsohedralTiling,
    IsohedralType,
)

__all__ = ["edge_path", "side_maps", "prototile", "layout"]

# tactile's M_orients by (flip, rotate): identity, half-turn about (1/2, 0), mirror in x = 1/2,
# reflection in the x axis.
_ORIENT = {
    (False, False): np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]),
    (False, True): np.array([[-1.0, 0.0, 1.0], [0.0, -1.0, 0.0]]),
    (True, False): np.array([[-1.0, 0.0, 1.0], [0.0, 1.0, 0.0]]),
    (True, True): np.array([[1.0, 0.0, 0.0], [0.0, -1.0, 0.0]]),
}


def edge_path(shape: EdgeShape) -> np.ndarray:
    """The shape as points from (0, 0) to (1, 0), both included; a Bézier chain as
    :data:`~tilesolve.model.isohedral.BEZIER_CHORDS` chords per cubic (uniform in t).

    >>> edge_path(EdgeShape("line", ((0.5, 0.25),))).tolist()
    [[0.0, 0.0], [0.5, 0.25], [1.0, 0.0]]
    """
    pts = np.array([(0.0, 0.0), *shape.points, (1.0, 0.0)], float)
    if shape.kind == "line":
        return pts
    t = np.linspace(0.0, 1.0, BEZIER_CHORDS + 1)[:-1, None]
    basis = np.hstack([(1 - t) ** 3, 3 * t * (1 - t) ** 2, 3 * t ** 2 * (1 - t), t ** 3])
    pieces = [basis @ pts[k:k + 4] for k in range(0, len(pts) - 1, 3)]
    return np.vstack(pieces + [pts[-1:]])


def _evaluate(coeffs: np.ndarray, params: tuple[float, ...]) -> np.ndarray:
    return coeffs @ np.array((*params, 1.0))


def side_maps(t: IsohedralType, params: tuple[float, ...]) -> list[tuple[np.ndarray, bool]]:
    """Per tiling edge ``k`` (vertex ``k`` to ``k + 1``): the affine map ``(2, 3)`` from its class's
    unit frame onto the edge, after the edge's orientation (§7.4.2), and whether the mapped path
    runs backwards (exactly one of flip and rotate).

    Raises
    ------
    InvalidProblem
        Two tiling vertices coincide.

    >>> from tilesolve.model.isohedral import isohedral_type
    >>> m, reverse = side_maps(isohedral_type(41), (0.5, 0.5))[0]
    >>> m.shape, reverse
    ((2, 3), False)
    """
    verts = _evaluate(t.vertex_coeffs, params)
    size = float(np.abs(verts).max()) + 1.0
    out = []
    for k in range(t.n_vertices):
        p, q = verts[k], verts[(k + 1) % t.n_vertices]
        d = q - p
        if float(np.hypot(*d)) <= 1e-9 * size:
            raise InvalidProblem(f"{t.name}'s parameters {list(params)} make tiling edge {k} vanish "
                                 f"(vertices {k} and {(k + 1) % t.n_vertices} coincide)")
        orient = _ORIENT[t.orientations[k]]
        match = np.array([[d[0], -d[1], p[0]], [d[1], d[0], p[1]]])
        m = np.hstack([match[:, :2] @ orient[:, :2], match[:, :2] @ orient[:, 2:] + match[:, 2:]])
        out.append((m, t.orientations[k][0] != t.orientations[k][1]))
    return out


def prototile(t: IsohedralType, params: tuple[float, ...], edges: tuple[EdgeShape, ...]) -> tuple[np.ndarray, tuple[int, ...]]:
    """The prototile's outline (tiling-vertex order, not closed) and the index of each tiling vertex.

    Raises
    ------
    InvalidProblem
        Two tiling vertices coincide, the outline is too long, or the tile crosses or touches itself.
    """
    paths = [edge_path(e) for e in edges]
    out, corners = [], []
    for k, (m, reverse) in enumerate(side_maps(t, params)):
        pts = paths[t.edge_classes[k]] @ m[:, :2].T + m[:, 2]
        if reverse:
            pts = pts[::-1]
        corners.append(sum(len(o) for o in out))
        out.append(pts[:-1])
    outline = np.vstack(out)
    if len(outline) > MAX_OUTLINE:
        raise InvalidProblem(f"the prototile's outline has {len(outline):,} points, at most {MAX_OUTLINE:,}: "
                             "use fewer points per edge")
    _refuse_crossings(outline, t.name)
    return outline, tuple(corners)


def _refuse_crossings(poly: np.ndarray, name: str) -> None:
    """Refuse an outline two of whose non-neighbouring chords meet (blocks of rows, vectorised)."""
    n = len(poly)
    a, b = poly, np.roll(poly, -1, axis=0)
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    idx = np.arange(n)

    def orient(p, q, r):
        return (q[..., 0] - p[..., 0]) * (r[..., 1] - p[..., 1]) - (q[..., 1] - p[..., 1]) * (r[..., 0] - p[..., 0])

    for s in range(0, n, 256):
        i = idx[s:s + 256, None]
        ai, bi = a[s:s + 256, None], b[s:s + 256, None]
        o1, o2 = orient(ai, bi, a[None]), orient(ai, bi, b[None])
        o3, o4 = orient(a[None], b[None], ai), orient(a[None], b[None], bi)
        boxes = np.all((lo[s:s + 256, None] <= hi[None] + 1e-12) & (lo[None] <= hi[s:s + 256, None] + 1e-12), axis=-1)
        near = (np.abs(i - idx[None]) <= 1) | (np.abs(i - idx[None]) == n - 1)
        hit = (o1 * o2 <= 0) & (o3 * o4 <= 0) & boxes & ~near
        if hit.any():
            r, c = np.argwhere(hit)[0]
            raise InvalidProblem(f"the {name} tile crosses itself (outline chords {s + r} and {c} meet): "
                                 "make the edge shapes smaller or change the parameters")


def _colour_table(t: IsohedralType) -> np.ndarray:
    """``table[a, i mod nc, j mod nc]``: colour of aspect ``a`` in lattice cell (i, j) (tactile's getColour)."""
    c, nc = t.colouring, t.n_colours
    table = np.zeros((t.n_aspects, nc, nc), np.int8)
    for a in range(t.n_aspects):
        for i in range(nc):
            for j in range(nc):
                col = c[a]
                for _ in range(i):
                    col = c[12 + col]
                for _ in range(j):
                    col = c[15 + col]
                table[a, i, j] = col
    return table


def layout(problem: IsohedralProblem) -> IsohedralTiling:
    """The prototile, its translational unit and the coloured tiles whose bounding boxes meet the region.

    Raises
    ------
    InvalidProblem
        A bad prototile (:func:`prototile`), or a region of more than
        :data:`~tilesolve.model.isohedral.MAX_TILES` tiles.
    """
    t = problem.template
    outline, corners = prototile(t, problem.params, problem.edges)
    aspects = _evaluate(t.aspect_coeffs, problem.params)
    trans = _evaluate(t.translation_coeffs, problem.params)
    det = float(np.linalg.det(trans))
    if abs(det) <= 1e-9:
        raise InvalidProblem(f"{t.name}'s parameters {list(problem.params)} make the translation vectors parallel")
    tiles = [outline @ m[:, :2].T + m[:, 2] for m in aspects]
    boxes = np.array([[p[:, 0].min(), p[:, 1].min(), p[:, 0].max(), p[:, 1].max()] for p in tiles])
    x0, y0, w, h = problem.region
    span = np.array([[x0 - boxes[:, 2].max(), y0 - boxes[:, 3].max()], [x0 + w - boxes[:, 0].min(), y0 + h - boxes[:, 1].min()]])
    cells_area = float(np.prod(span[1] - span[0]))
    if cells_area / abs(det) * t.n_aspects > 4 * MAX_TILES:
        raise InvalidProblem(f"the region {w:g}x{h:g} holds about {int(w * h / abs(det) * t.n_aspects):,} tiles, "
                             f"at most {MAX_TILES:,}")
    corners_xy = np.array([[span[u][0], span[v][1]] for u in (0, 1) for v in (0, 1)])
    ij = corners_xy @ np.linalg.inv(trans)
    (i0, j0), (i1, j1) = np.floor(ij.min(axis=0)).astype(int), np.ceil(ij.max(axis=0)).astype(int)
    jj, ii, aa = np.meshgrid(np.arange(j0, j1 + 1), np.arange(i0, i1 + 1), np.arange(t.n_aspects), indexing="ij")
    cand = np.stack([ii.ravel(), jj.ravel(), aa.ravel()], axis=1)
    shift = cand[:, :1] * trans[0] + cand[:, 1:2] * trans[1]
    b = boxes[cand[:, 2]]
    keep = (b[:, 0] + shift[:, 0] < x0 + w) & (b[:, 2] + shift[:, 0] > x0) & \
           (b[:, 1] + shift[:, 1] < y0 + h) & (b[:, 3] + shift[:, 1] > y0)
    placed = cand[keep].astype(np.int64)
    if len(placed) > MAX_TILES:
        raise InvalidProblem(f"the region holds {len(placed):,} tiles, at most {MAX_TILES:,}")
    nc = t.n_colours
    colours = _colour_table(t)[placed[:, 2], placed[:, 0] % nc, placed[:, 1] % nc]
    return IsohedralTiling(t.number, outline, corners, aspects, trans, placed, colours)
