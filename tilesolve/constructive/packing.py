"""Constructive tile packings (class notes §5.5.1-5.5.3; Wei 2004; de Bruijn tori).

* :func:`domino_sequence` -- a 1D packing of the ``C**2`` dominoes over ``C`` colours: a
  cyclic colour sequence ``s`` whose dominoes ``(s[k], s[k+1])`` are all distinct, i.e. an
  Eulerian circuit of the complete directed graph with loops (§5.5.1), which is also a de
  Bruijn sequence B(C, 2). Without a seed it is Wei's sequence, whose tile positions have a
  closed form (:func:`domino_position`); with a seed, a random Eulerian circuit (networkx).
* :func:`wang_packing` -- Wei's outer product of two 1D packings (§5.5.2), with the closed-form
  position of any tile (:func:`wang_position`).
* :func:`corner_packing_odd` -- for odd ``C`` the corner packing whose corner colours are rows
  of a de Bruijn sequence shifted by triangular numbers, ``a[i][j] = s[(j + i(i-1)/2) mod C**2]``
  (see its docstring for the proof). No construction is known to the notes for even ``C``.

Grids follow :mod:`tilesolve.model.packing`: ``grid[row, col]``, row 0 at the top.

References
----------
.. [1] A. Lagae, *Tile-Based Methods in Computer Graphics*, PhD thesis, KU Leuven, 2007, §5.5.
.. [2] L.-Y. Wei, "Tile-based texture mapping on graphics hardware", Graphics Hardware 2004.
"""

from __future__ import annotations

import numpy as np

from tilesolve._random import rng_from_seed
from tilesolve.errors import InvalidProblem, MethodNotApplicable
from tilesolve.model.tiles import corner_index, wang_index

__all__ = [
    "MAX_CONSTRUCT_TILES",
    "wei_sequence",
    "domino_position",
    "domino_sequence",
    "is_domino_packing",
    "outer_product",
    "wang_packing",
    "wang_position",
    "triangular_shift_rows",
    "corner_packing_odd",
    "corner_packing_from_colors",
    "symmetry_tile_map",
    "apply_symmetry",
    "random_symmetry",
]

#: Largest tile set the constructions build (C = 64: 16.7 million tiles, 128 MiB of int64).
MAX_CONSTRUCT_TILES = 1 << 24


def _check(colors: int, what: str = "colors") -> int:
    if isinstance(colors, bool) or not isinstance(colors, (int, np.integer)):
        raise InvalidProblem(f"{what} must be an integer, got {colors!r}")
    c = int(colors)
    if c < 2:
        raise InvalidProblem(f"a tile packing needs at least 2 colours, got {what}={c}")
    if c**4 > MAX_CONSTRUCT_TILES:
        raise InvalidProblem(
            f"{what}={c} gives {c**4:,} tiles ({8 * c**4 / 2**20:,.0f} MiB for the grid alone); "
            f"the constructions stop at {MAX_CONSTRUCT_TILES:,} tiles (C=64)"
        )
    return c


def wei_sequence(colors: int) -> np.ndarray:
    """Wei's Eulerian 1D packing: colour ``k`` is spliced in as the closed walk
    ``0, k, 1, k, ..., k-1, k, k`` (back to 0), appended after the packing over ``k`` colours.

    It is the sequence along both axes of Fig. 5.10.

    Examples
    --------
    >>> wei_sequence(3).tolist()
    [0, 0, 1, 1, 0, 2, 1, 2, 2]
    """
    out = [0]
    for k in range(1, int(colors)):
        walk = []
        for j in range(k):
            walk += [j, k]
        walk.append(k)
        out += walk
    return np.asarray(out, dtype=np.int64)


def domino_position(a, b):
    """Closed-form position of domino ``(a, b)`` in :func:`wei_sequence` (Wei 2004).

    ``s[p] = a`` and ``s[p+1] = b`` (cyclically) for ``p = domino_position(a, b)``::

        a <  b        : b**2 + 2a
        a >  b >= 1   : a**2 + 2b - 1
        a == b >= 1   : (a+1)**2 - 2
        a >  b == 0   : (a+1)**2 - 1
        a == b == 0   : 0

    Works on numpy arrays.

    Examples
    --------
    >>> s = wei_sequence(4); p = domino_position(3, 1)
    >>> int(p), int(s[p]), int(s[(p + 1) % 16])
    (10, 3, 1)
    """
    a = np.asarray(a, dtype=np.int64)
    b = np.asarray(b, dtype=np.int64)
    p = np.where(
        a < b,
        b * b + 2 * a,
        np.where(a == b, np.where(a == 0, 0, (a + 1) ** 2 - 2), np.where(b == 0, (a + 1) ** 2 - 1, a * a + 2 * b - 1)),
    )
    return p if p.ndim else int(p)


def domino_sequence(colors: int, seed=None) -> np.ndarray:
    """A 1D packing over ``colors`` colours: an Eulerian circuit of the complete digraph (§5.5.1).

    Parameters
    ----------
    colors : int
    seed : int, optional
        ``None`` gives :func:`wei_sequence` (closed-form positions); a seed gives a random
        Eulerian circuit: networkx's Hierholzer algorithm on the complete directed graph with
        loops, its edges inserted in a random order, under a random colour permutation.

    Returns
    -------
    numpy.ndarray
        ``s`` of length ``colors**2``; the dominoes ``(s[k], s[(k+1) % C**2])`` are all distinct.

    Examples
    --------
    >>> is_domino_packing(domino_sequence(5, seed=3), 5)
    True
    """
    import networkx as nx

    c = int(colors)
    if c < 1:
        raise InvalidProblem(f"colours must be >= 1, got {c}")
    if seed is None:
        return wei_sequence(c)
    rng = rng_from_seed(seed)
    edges = [(a, b) for a in range(c) for b in range(c)]
    order = rng.permutation(len(edges))
    g = nx.MultiDiGraph()
    g.add_nodes_from(range(c))
    g.add_edges_from(edges[i] for i in order)
    start = int(rng.integers(c))
    seq = np.asarray([u for u, _ in nx.eulerian_circuit(g, source=start)], dtype=np.int64)
    perm = rng.permutation(c)
    return perm[seq]


def is_domino_packing(seq, colors: int) -> bool:
    """True when the cyclic sequence ``seq`` holds each of the ``colors**2`` dominoes once."""
    s = np.asarray(seq, dtype=np.int64)
    c = int(colors)
    if s.shape != (c * c,) or s.min(initial=0) < 0 or s.max(initial=0) >= c:
        return False
    d = s * c + np.roll(s, -1)
    return np.unique(d).size == c * c


def outer_product(x, y, colors: int, colors_v: int | None = None) -> np.ndarray:
    """Wei's outer product of two 1D packings into a Wang packing (§5.5.2, Fig. 5.10).

    ``x`` (over ``C_v`` colours) runs along the rows, giving W and E edges; ``y`` (over
    ``C_h`` colours) runs up the columns from the bottom row, as in Fig. 5.10::

        grid[r, c] = tile(N = y[R + 1], E = x[c + 1], S = y[R], W = x[c]),   R = C_h**2 - 1 - r
    """
    x = np.asarray(x, dtype=np.int64)
    y = np.asarray(y, dtype=np.int64)
    rows = y.size
    big_r = rows - 1 - np.arange(rows)
    n = y[(big_r + 1) % rows][:, None]
    s = y[big_r][:, None]
    w = x[None, :]
    e = np.roll(x, -1)[None, :]
    return wang_index(n, e, s, w, colors=colors, colors_v=colors_v).astype(np.int64)


def wang_packing(colors: int, colors_v: int | None = None, seed=None) -> np.ndarray:
    """A Wang packing as the outer product of two 1D packings (Wei 2004; §5.5.2).

    Without a seed both axes use :func:`wei_sequence` and the result is Fig. 5.10 for
    ``C = 3``; :func:`wang_position` then gives any tile's cell in closed form. With a seed the
    two 1D packings are random Eulerian circuits (the packing stays separable: every row has
    the same W/E sequence).

    Examples
    --------
    >>> g = wang_packing(3)
    >>> g[-1].tolist()      # bottom row of Fig. 5.10
    [0, 9, 10, 1, 18, 11, 19, 20, 2]
    """
    ch = _check(colors)
    cv = ch if colors_v is None else _check(colors_v, "colors_v")
    if ch**2 * cv**2 > MAX_CONSTRUCT_TILES:
        raise InvalidProblem(f"{ch**2 * cv**2:,} tiles is more than the constructions build ({MAX_CONSTRUCT_TILES:,})")
    if seed is None:
        x, y = wei_sequence(cv), wei_sequence(ch)
    else:
        rng = rng_from_seed(seed)
        x, y = domino_sequence(cv, rng), domino_sequence(ch, rng)
    return outer_product(x, y, ch, None if colors_v is None else cv)


def wang_position(tile, colors: int, colors_v: int | None = None) -> tuple:
    """Closed-form ``(row, col)`` of ``tile`` in the seedless :func:`wang_packing` (§5.5.2).

    The closed form of the 1D case applied along each axis: ``col = p(c_W, c_E)`` and the row,
    counted from the bottom, is ``p(c_S, c_N)`` with ``p`` = :func:`domino_position`.

    Examples
    --------
    >>> g = wang_packing(4); r, c = wang_position(200, 4)
    >>> int(g[r, c])
    200
    """
    from tilesolve.model.tiles import wang_colors

    ch = int(colors)
    n, e, s, w = wang_colors(np.asarray(tile, dtype=np.int64), colors=ch, colors_v=colors_v)
    row = ch * ch - 1 - domino_position(s, n)
    col = domino_position(w, e)
    return row, col


def triangular_shift_rows(seq) -> np.ndarray:
    """The ``n x n`` colour torus ``a[i][j] = s[(j + i(i-1)/2) mod n]`` for a sequence of length ``n``."""
    s = np.asarray(seq, dtype=np.int64)
    n = s.size
    i = np.arange(n)[:, None]
    j = np.arange(n)[None, :]
    return s[(j + i * (i - 1) // 2) % n]


def corner_packing_from_colors(a, colors: int) -> np.ndarray:
    """The corner tiles cut from a toroidal grid of corner colours.

    ``a[i][j]`` is the colour of the lattice point north-west of cell ``(i, j)``; cell
    ``(i, j)`` gets NW = ``a[i][j]``, NE = ``a[i][j+1]``, SW = ``a[i+1][j]``, SE = ``a[i+1][j+1]``
    (indices mod the size). The result is a corner packing exactly when every 2x2 window of
    ``a`` is distinct, i.e. when ``a`` is a de Bruijn torus.
    """
    a = np.asarray(a, dtype=np.int64)
    ne = np.roll(a, -1, axis=1)
    sw = np.roll(a, -1, axis=0)
    se = np.roll(sw, -1, axis=1)
    return corner_index(ne, se, sw, a, colors=colors).astype(np.int64)


def corner_packing_odd(colors: int, seed=None) -> np.ndarray:
    """A corner packing for odd ``C`` from a de Bruijn sequence B(C, 2) (2D de Bruijn torus).

    Let ``s`` be a 1D packing (:func:`domino_sequence`) of length ``n = C**2`` and
    ``T(i) = i(i-1)/2``. The corner colours are ``a[i][j] = s[(j + T(i)) mod n]``.

    Proof. The 2x2 window at ``(i, j)`` reads ``s[k], s[k+1]`` on top and ``s[k+i], s[k+i+1]``
    below, with ``k = j + T(i)``, because ``T(i+1) - T(i) = i``. Its top domino fixes ``k mod n``
    and its bottom domino fixes ``k + i mod n`` (each domino occurs once in ``s``), hence ``i``;
    then ``j = k - T(i)``. So distinct windows have distinct ``(i, j)``: all ``n**2 = C**4``
    windows, i.e. all tiles, are distinct. Toroidal closure needs the row after ``n - 1`` to be
    row 0, i.e. ``T(n) = n(n-1)/2 ≡ T(0) = 0 (mod n)``, which holds iff ``n - 1`` is even, iff
    ``C`` is odd. For even ``C`` the construction fails (``MethodNotApplicable``).

    With a seed, ``s`` is a random Eulerian circuit and the picture is also translated at random.

    Examples
    --------
    >>> g = corner_packing_odd(3)
    >>> sorted(g.ravel().tolist()) == list(range(81))
    True
    """
    c = _check(colors)
    if c % 2 == 0:
        raise MethodNotApplicable(
            f"the triangular-shift de Bruijn construction needs an odd number of colours, got C={c}; "
            "use method 'lift' for even C"
        )
    if seed is None:
        s = wei_sequence(c)
        return corner_packing_from_colors(triangular_shift_rows(s), c)
    rng = rng_from_seed(seed)
    s = domino_sequence(c, rng)
    g = corner_packing_from_colors(triangular_shift_rows(s), c)
    return np.roll(g, (int(rng.integers(c * c)), int(rng.integers(c * c))), axis=(0, 1))


def symmetry_tile_map(kind: str, colors: int, perm, mirrored: bool, turns: int) -> np.ndarray:
    """Image of every tile under a colour permutation, a left-right mirror, then ``turns``
    clockwise quarter turns (§5.5.3 lists these symmetries of the packing problem).

    A Wang tile turned clockwise has ``N' = W, E' = N, S' = E, W' = S``; a corner tile has
    ``NE' = NW, SE' = NE, SW' = SE, NW' = SW``. Mirroring swaps E/W, resp. NE/NW and SE/SW.
    """
    from tilesolve.model.tiles import TileSet

    ts = TileSet(kind, colors)
    p = np.asarray(perm, dtype=np.int64)
    t = p[ts.table()]
    if mirrored:
        t = t[:, [0, 3, 2, 1]] if kind == "wang" else t[:, [3, 2, 1, 0]]
    for _ in range(int(turns) % 4):
        t = t[:, [3, 0, 1, 2]]
    return np.asarray(ts.index(t[:, 0], t[:, 1], t[:, 2], t[:, 3]), dtype=np.int64)


def apply_symmetry(grid, turns: int, mirrored: bool, tile_map: np.ndarray, shift=(0, 0)) -> np.ndarray:
    """Image of a packing: mirror left-right, turn clockwise, map the tiles, translate."""
    g = np.asarray(grid)
    if mirrored:
        g = g[:, ::-1]
    g = np.rot90(g, k=-int(turns))
    return np.roll(np.asarray(tile_map)[g], tuple(int(v) for v in shift), axis=(0, 1))


def random_symmetry(grid, kind: str, colors: int, seed=None) -> np.ndarray:
    """A packing's image under a random symmetry (colour permutation, rotation, reflection,
    translation); it is again a packing (square grids, one number of colours)."""
    rng = rng_from_seed(seed)
    g = np.asarray(grid)
    perm = rng.permutation(int(colors))
    mirrored = bool(rng.integers(2))
    turns = int(rng.integers(4))
    shift = (int(rng.integers(g.shape[0])), int(rng.integers(g.shape[1])))
    return apply_symmetry(g, turns, mirrored, symmetry_tile_map(kind, colors, perm, mirrored, turns), shift)
