"""Independent checker for tile packings (class notes §5.5).

Written from the definitions only, with numpy: a packing of the complete Wang or corner
tile set over ``C`` colours is a ``C**2 x C**2`` toroidal grid (``C_h**2 x C_v**2`` for Wang
tiles with separate vertical colours) that holds every tile index ``0 .. C**4 - 1`` exactly
once, such that adjoining edges (Wang) or corners (corner tiles) have equal colours. Tile
indices are decoded here from eq. 2.3 (Wang: ``c_N c_E c_S c_W``) and eq. 2.6 (corner:
``c_NE c_SE c_SW c_NW``), without importing :mod:`tilesolve.model.tiles`, the constructions
or the encodings.
"""

from __future__ import annotations

import numpy as np

from tilesolve.verify.dappled import Violation
from tilesolve.verify.grid import grid_violations

__all__ = ["packing_violations", "is_packing"]


def _decode(grid: np.ndarray, radices: tuple[int, int, int, int]) -> list[np.ndarray]:
    """The four base-``radices`` digits of each index, most significant first."""
    digits = []
    rest = grid.copy()
    for r in reversed(radices):
        digits.append(rest % r)
        rest = rest // r
    return digits[::-1]


def packing_violations(problem, grid) -> list[Violation]:
    """Every way ``grid`` fails to be a tile packing of ``problem``, with positions; empty when it is one.

    Parameters
    ----------
    problem : PackingProblem
        Read for its fields only (no method of the model is called): ``kind`` ("wang" or
        "corner"), ``colors`` (``C``, ``C_h`` with ``colors_v``), ``colors_v`` (Wang tiles with
        a different number of colours on the E/W edges, or None) and ``fixed`` (pinned
        ``(row, col, tile)`` that must be where they are pinned).
    grid : array-like of int
        ``grid[row][col]`` tile indices, row 0 at the top (row r-1 north of row r).

    Returns
    -------
    list of Violation
        kinds ``"shape"``, ``"tile"`` (index out of range), ``"duplicate"``, ``"missing"``,
        ``"match"`` (an edge or corner mismatch, at the western/northern cell of the pair),
        ``"fixed"``.

    Examples
    --------
    >>> from tilesolve.model.packing import PackingProblem
    >>> sorted({v.kind for v in packing_violations(PackingProblem("wang", 2), np.zeros((4, 4), int))})
    ['duplicate', 'missing']
    >>> fig_5_9 = [[0, 1, 3, 2]]   # not a 2D packing: wrong shape
    >>> str(packing_violations(PackingProblem("corner", 2), fig_5_9)[0])
    'packing has shape (1, 4), expected 4x4 for C=2'
    """
    kind, colors, colors_v, fixed = problem.kind, problem.colors, problem.colors_v, problem.fixed
    if kind not in ("wang", "corner"):
        return [Violation("shape", f"unknown tile kind {kind!r}")]
    ch = int(colors)
    cv = ch if colors_v is None else int(colors_v)
    if kind == "corner" and cv != ch:
        return [Violation("shape", "corner tiles have one number of colours")]
    g = np.asarray(grid)
    rows, cols = ch * ch, cv * cv
    n = rows * cols
    if g.ndim != 2 or g.shape != (rows, cols):
        return [Violation("shape", f"packing has shape {g.shape}, expected {rows}x{cols} for C={colors}"
                          + (f", C_v={cv}" if cv != ch else ""))]
    if g.size and not np.issubdtype(g.dtype, np.integer):
        return [Violation("tile", "packing must hold integer tile indices")]
    g = g.astype(np.int64)
    out: list[Violation] = []
    for r, c in np.argwhere((g < 0) | (g >= n)):
        out.append(Violation("tile", f"tile {int(g[r, c])} is not in 0..{n - 1}", int(r), int(c)))
    if out:
        return out
    # Each tile exactly once.
    counts = np.bincount(g.ravel(), minlength=n)
    for t in np.flatnonzero(counts > 1):
        where = [tuple(map(int, p)) for p in np.argwhere(g == t)]
        for r, c in where[1:]:
            out.append(Violation("duplicate", f"tile {int(t)} appears {int(counts[t])} times "
                                 f"(first at row {where[0][0]}, col {where[0][1]})", r, c))
    for t in np.flatnonzero(counts == 0):
        out.append(Violation("missing", f"tile {int(t)} is missing"))
    # Matching, toroidal: the shared grid-tiling checker over the tiles' colours (eq. 2.1 / 2.5
    # digits: N, E, S, W for Wang tiles, NE, SE, SW, NW for corner tiles).
    radices = (ch, cv, ch, cv) if kind == "wang" else (ch,) * 4
    colours = np.stack(_decode(np.arange(n, dtype=np.int64), radices), axis=1)
    out += grid_violations(colours, g, kind=kind, toroidal=True)
    for r, c, t in fixed:
        r, c, t = int(r), int(c), int(t)
        if not (0 <= r < rows and 0 <= c < cols):
            out.append(Violation("fixed", f"fixed cell ({r}, {c}) is outside the packing"))
        elif g[r, c] != t:
            out.append(Violation("fixed", f"fixed tile {t} replaced by {int(g[r, c])}", r, c))
    out.sort(key=lambda v: (v.row is None, v.row or 0, v.col or 0))
    return out


def is_packing(problem, grid) -> bool:
    """True when ``grid`` is a valid tile packing of ``problem`` (see :func:`packing_violations`)."""
    return not packing_violations(problem, grid)
