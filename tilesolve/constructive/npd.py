"""The repeatable non-procedural wall NPD (Derouet-Jourdan, Salvati, Jonchier, 004 App. A).

A wall that repeats with period ``cols x rows`` is a brick Wang tiling of the torus of that
size: a Wang tiling problem "with border constraints where the top border matches the bottom
one and the left border matches the right one" (App. A, Fig. 23 left). App. A builds it in two
steps:

1. a *cyclic* dappling ``D`` (Kaji et al.; the dappled paper §3.2, Algorithm 2) with classes
   0 (W_H, a horizontal line crosses the cell) and 1 (W_V) and the cyclic conditions
   ``H_0^p`` (no more than ``p`` horizontal tiles in a row, across the seam too) and
   ``V_1^q``; the caller (:func:`tilesolve.families.walls.npd_route`) solves it with the dappled family;
2. the Wang tiling on top (App. A, Algorithm 1, :func:`npd_legs`): the vertical edge colours of
   each row, then "the same way" the horizontal edge colours of each column.

Along a row the colour of the vertical edges changes exactly at the vertical tiles (eq. 1:
``V[i+1, j] != V[i, j]``) and stays at the horizontal ones (eq. 2), and the row closes on
itself (``V[n_R, j] = V[0, j] = c``). A row with no vertical tile is an endless line, and a row
with exactly one cannot close (one change around a cycle), so every row needs at least two
vertical tiles and every column two horizontal tiles. That is a cyclic line limit of
``cols - 2`` and ``rows - 2``: :func:`cyclic_limits` folds it into the dappling's limits, so
the "border constraint" of App. A is part of the dappled problem and Algorithm 1 never meets a
row it cannot close. A period under 3 cells has no such dappling at all.

Reading of Algorithm 1 (the extraction prints ``currentColor <- diff(c)`` at an ordinary
vertical tile): the colour after an ordinary vertical tile is drawn uniformly among the
colours unlike the *current* one (eq. 1 needs ``V[i+1, j] != V[i, j]``; ``diff(c)`` alone
could repeat the current colour when it differs from ``c``); at the second-to-last vertical
tile it is drawn among the colours unlike both the current one and ``c`` (``CS`` of App. A,
possible with ``nc >= 3``), and at the last one it returns to ``c``.
"""

from __future__ import annotations

import numpy as np

from tilesolve._random import rng_from_seed
from tilesolve.errors import InvalidProblem

__all__ = ["cyclic_limits", "npd_legs", "periodic_window"]


def cyclic_limits(rows: int, cols: int, max_h: int, max_v: int) -> tuple[int, int]:
    """The cyclic dappling limits ``(p, q)`` of a wall repeating with period ``cols x rows``.

    ``p = min(max_h, cols - 2)``, ``q = min(max_v, rows - 2)``: the line limits, tightened so
    that every row holds two vertical tiles and every column two horizontal ones (see the
    module docstring).

    Raises
    ------
    InvalidProblem
        A period under 3 cells either way, or a limit under 1.

    Examples
    --------
    >>> cyclic_limits(12, 16, 4, 4), cyclic_limits(5, 4, 10, 10)
    ((4, 4), (2, 3))
    """
    rows, cols, max_h, max_v = int(rows), int(cols), int(max_h), int(max_v)
    if min(max_h, max_v) < 1:
        raise InvalidProblem(f"the maximum line length must be >= 1 brick, got {min(max_h, max_v)}")
    if rows < 3 or cols < 3:
        raise InvalidProblem(f"a repeatable wall with line limits needs a period of at least 3x3 cells "
                             f"(each row needs two vertical bricks, each column two horizontal ones), "
                             f"got {cols}x{rows}")
    return min(max_h, cols - 2), min(max_v, rows - 2)


def _other(rng: np.random.Generator, nc: int, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """A colour drawn uniformly among those unlike ``a`` and ``b`` (element-wise)."""
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    same = a == b
    k = rng.integers(0, nc - 1 - (~same).astype(np.int64))  # nc - 1 or nc - 2 choices
    k = k + (k >= lo)
    return k + (~same & (k >= hi))


def _cycle_edges(change: np.ndarray, nc: int, rng: np.random.Generator) -> np.ndarray:
    """App. A, Algorithm 1 on every line at once: ``(m, L + 1)`` edge colours of ``m`` closed lines.

    ``change[k, i]`` marks the cells whose two edges across the line differ; the result has
    ``e[:, i + 1] != e[:, i]`` exactly there and ``e[:, L] = e[:, 0] = c`` (a random ``c`` per
    line). Every line needs two changes.
    """
    m, length = change.shape
    idx = np.arange(length)
    last = np.where(change, idx, -1).max(axis=1)
    second = np.where(change & (idx < last[:, None]), idx, -1).max(axis=1)
    c = rng.integers(0, nc, size=m)
    e = np.empty((m, length + 1), dtype=np.int64)
    e[:, 0] = c
    cur = c.copy()
    for i in range(length - 1):
        ordinary = (cur + rng.integers(1, nc, size=m)) % nc
        cs = _other(rng, nc, cur, c)
        nxt = np.where(i == last, c, np.where(i == second, cs, ordinary))
        cur = np.where(change[:, i], nxt, cur)
        e[:, i + 1] = cur
    e[:, length] = c
    return e


def npd_legs(classes, colors: int, *, seed=None) -> np.ndarray:
    """The brick Wang tiling of the torus on top of a cyclic dappling (004 App. A, Algorithm 1).

    Parameters
    ----------
    classes : array-like
        ``(rows, cols)`` cyclic dappling: 0 = W_H (horizontal tile), 1 = W_V (vertical tile);
        every row needs two 1s and every column two 0s (:func:`cyclic_limits`).
    colors : int
        ``nc >= 3`` edge colours.
    seed : int or numpy.random.Generator, optional
        Draws the border colours and the colours after each change.

    Returns
    -------
    numpy.ndarray
        ``(rows, cols, 4)`` int8 leg colours ``(N, E, S, W)``, row 0 at the top; the E legs of
        the last column equal the W legs of the first and the S legs of the last row the N legs
        of the first (the wall repeats), and a cell is W_H exactly where ``classes`` is 0.

    Examples
    --------
    >>> d = [[0, 1, 0, 1], [1, 0, 1, 0], [0, 1, 0, 1], [1, 0, 1, 0]]
    >>> t = npd_legs(d, 3, seed=1)
    >>> bool((t[:, -1, 1] == t[:, 0, 3]).all() and (t[-1, :, 2] == t[0, :, 0]).all())
    True
    """
    g = np.asarray(classes)
    if g.ndim != 2 or g.size == 0 or not np.isin(g, (0, 1)).all():
        raise InvalidProblem("a repeatable wall needs a 2-D dappling of classes 0 (W_H) and 1 (W_V)")
    nc = int(colors)
    if nc < 3:
        raise InvalidProblem(f"brick walls need at least 3 colours (004 §3.1, App. A), got {nc}")
    vert = g == 1
    if (vert.sum(axis=1) < 2).any() or ((~vert).sum(axis=0) < 2).any():
        raise InvalidProblem("every row of a repeatable wall needs two vertical tiles and every column two "
                             "horizontal ones (004 App. A); dapple with cyclic_limits()")
    rng = rng_from_seed(seed)
    rows, cols = g.shape
    v = _cycle_edges(vert, nc, rng)  # v[r, c] = W leg of cell (r, c); v[r, cols] = v[r, 0]
    h = _cycle_edges(~vert.T, nc, rng)  # h[c, r] = N leg of cell (r, c), going down the column
    out = np.empty((rows, cols, 4), dtype=np.int8)
    out[..., 0] = h[:, :-1].T
    out[..., 1] = v[:, 1:]
    out[..., 2] = h[:, 1:].T
    out[..., 3] = v[:, :-1]
    return out


def periodic_window(legs, x0: int, y0: int, w: int, h: int) -> np.ndarray:
    """Cells ``[x0, x0 + w) x [y0, y0 + h)`` of the wall that repeats one period ``legs``.

    Coordinates as in :func:`tilesolve.constructive.walls.wall_window` (``x`` east, ``y``
    north): wall cell ``(x, y)`` is period cell ``(rows - 1 - y mod rows, x mod cols)``, so
    the window at ``(0, 0)`` of the period's size is the period itself.

    Returns
    -------
    numpy.ndarray
        ``(h, w, 4)`` leg colours, row 0 at the top.

    Examples
    --------
    >>> p = npd_legs([[0, 1, 0, 1], [1, 0, 1, 0], [0, 1, 0, 1], [1, 0, 1, 0]], 3, seed=1)
    >>> bool((periodic_window(p, 0, 0, 4, 4) == p).all()), periodic_window(p, -5, 7, 9, 2).shape
    (True, (2, 9, 4))
    """
    t = np.asarray(legs)
    rows, cols = t.shape[:2]
    ys = int(y0) + int(h) - 1 - np.arange(int(h))
    r = (rows - 1 - ys) % rows
    c = (int(x0) + np.arange(int(w))) % cols
    return t[r[:, None], c[None, :]]
