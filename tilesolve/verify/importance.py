"""Checks of an importance sample against its density (class notes Part IV: "a discrete sample
distribution locally proportional to I(x, y)"), written from that definition and sharing no
code with the samplers.

The density is a grid of pixel values (row 0 the top row) over ``[0, width] x [0, height]``,
y up, each pixel a square of side ``1 / max(rows, cols)``.

* :func:`importance_violations`: every point finite and inside the domain; the number of
  points near the number asked for; and, on grids of ``g x g`` blocks of pixels, the points in
  each block near their share ``n M_block / M`` of the density's mass ``M``.
* :func:`weighted_discrepancy`: the density-weighted star discrepancy over anchored boxes
  ``[0, x] x [0, y]`` with corners on pixel edges: ``max |points in box / n - mass of box / M|``.

A block's count is allowed ``max(rel * e, z * sqrt(e), 1)`` away from its share ``e``: ``z``
standard deviations of independent sampling (the rejection sampler's spread) or a relative
error ``rel``, whichever is larger.

>>> import numpy as np
>>> v = np.ones((4, 4))
>>> importance_violations(np.array([[0.2, 0.2], [0.7, 0.7]]), v, expected=2)
[]
>>> [x.kind for x in importance_violations(np.array([[1.5, 0.2]]), v)]
['bounds']
"""

from __future__ import annotations

import numpy as np

from tilesolve.verify.dappled import Violation

__all__ = ["REL", "Z", "block_counts", "importance_violations", "weighted_discrepancy"]

#: Relative error allowed a block's count.
REL = 0.05
#: Standard deviations of independent sampling allowed a block's count.
Z = 4.0


def _domain(values: np.ndarray) -> tuple[float, float, float]:
    rows, cols = values.shape
    pixel = 1.0 / max(rows, cols)
    return cols * pixel, rows * pixel, pixel


def _edges(n: int, g: int) -> np.ndarray:
    """Pixel indices of the ``g + 1`` block edges along ``n`` pixels."""
    return np.unique(np.rint(np.linspace(0, n, g + 1)).astype(np.int64))


def block_counts(points: np.ndarray, values: np.ndarray, g: int) -> tuple[np.ndarray, np.ndarray]:
    """``(counts, shares)`` of a ``g x g`` grid of pixel blocks (rows from the bottom): the points
    in each block and ``n`` times the block's fraction of the density's mass."""
    up = np.asarray(values, dtype=np.float64)[::-1]
    _, _, pixel = _domain(up)
    er, ec = _edges(up.shape[0], g), _edges(up.shape[1], g)
    mass = np.add.reduceat(np.add.reduceat(up, er[:-1], axis=0), ec[:-1], axis=1)
    pts = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    counts, _, _ = np.histogram2d(pts[:, 1], pts[:, 0], bins=[er * pixel, ec * pixel])
    return counts, len(pts) * mass / up.sum()


def importance_violations(points, values, *, expected: int | None = None, grids=(2, 4), rel: float = REL,
                          z: float = Z) -> list[Violation]:
    """What is wrong with ``points`` as a sample of the density ``values`` (an empty list when
    nothing is): points outside the domain or not finite (``bounds``), a total far from
    ``expected`` (``count``), a block of a ``g x g`` grid (``g`` in ``grids``) far from its share
    (``density``)."""
    pts = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    values = np.asarray(values, dtype=np.float64)
    width, height, _ = _domain(values)
    out = []
    bad = ~(np.isfinite(pts).all(axis=1) & (pts[:, 0] >= 0) & (pts[:, 0] <= width) & (pts[:, 1] >= 0)
            & (pts[:, 1] <= height))
    if bad.any():
        x, y = pts[np.flatnonzero(bad)[0]]
        return [Violation("bounds", f"{int(bad.sum()):,} points outside the domain [0, {width:g}] x [0, {height:g}], "
                                    f"e.g. ({x:.6g}, {y:.6g})")]

    def allowed(e):
        return np.maximum(np.maximum(rel * e, z * np.sqrt(e)), 1.0)

    if expected is not None and abs(len(pts) - expected) > allowed(float(expected)):
        out.append(Violation("count", f"{len(pts):,} points where {expected:,} were asked for"))
    for g in grids:
        counts, shares = block_counts(pts, values, g)
        far = np.abs(counts - shares) > allowed(shares)
        for r, c in zip(*np.nonzero(far)):
            out.append(Violation("density", f"block ({c}, {r}) of a {g}x{g} grid (from the bottom left) holds "
                                            f"{int(counts[r, c]):,} points, its share of the density is "
                                            f"{shares[r, c]:,.1f}"))
    return out


def weighted_discrepancy(points, values, *, anchors: int = 64) -> float:
    """The density-weighted star discrepancy over anchored boxes whose corners lie on (at most
    ``anchors + 1``) pixel edges along each axis."""
    up = np.asarray(values, dtype=np.float64)[::-1]
    _, _, pixel = _domain(up)
    er, ec = _edges(up.shape[0], anchors), _edges(up.shape[1], anchors)
    mass = np.add.reduceat(np.add.reduceat(up, er[:-1], axis=0), ec[:-1], axis=1)
    mass = np.pad(mass.cumsum(axis=0).cumsum(axis=1), ((1, 0), (1, 0))) / up.sum()
    pts = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    counts, _, _ = np.histogram2d(pts[:, 1], pts[:, 0], bins=[er * pixel, ec * pixel])
    frac = np.pad(counts.cumsum(axis=0).cumsum(axis=1), ((1, 0), (1, 0))) / max(len(pts), 1)
    return float(np.abs(frac - mass).max())
