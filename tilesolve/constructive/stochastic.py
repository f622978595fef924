"""Stochastic Wang and corner tilings, scanline and direct (class notes ch. 3).

Coordinates
-----------
Tiles sit with their corners on the integer lattice and are named by their SW (lower-left)
corner ``(x, y)``, ``y`` pointing north (§2.7, §3.3.1). A *window* ``(x0, y0, w, h)`` is the
block ``[x0, x0 + w) x [y0, y0 + h)`` of the infinite tiling, returned as
``grid[row, col]`` with row 0 at the top: ``grid[r, c]`` is the tile at
``(x0 + c, y0 + h - 1 - r)``. Tiles are numbered by eq. 2.1 (Wang: ``c_N c_E c_S c_W``) or
eq. 2.5 (corner: ``c_NE c_SE c_SW c_NW``), as :class:`tilesolve.model.tiles.TileSet` does;
:func:`tile_set` names the set a method's windows are drawn from.

Algorithms
----------
``direct`` (§3.3): every tile is a function of hashes of the lattice points around it.
  *corner* (§3.3.1): corner colours ``h(x+1, y+1), h(x+1, y), h(x, y), h(x, y+1)`` (NE,
  SE, SW, NW); the complete corner set. *wang, two hashes* (§3.3.2.1): edge colours are sums
  modulo ``C`` of the pairs ``(h_h, h_v)`` at the corners; the complete Wang set. *wang, edge
  hash* (§3.3.2.3): ``N, E, S, W = h(2x+1, 2y+2), h(2x+2, 2y+1), h(2x+1, 2y), h(2x, 2y+1)``;
  the complete Wang set. *wang, sums* (§3.3.2.2): one hash, edge colours are sums of corner
  colours; the ``C**3`` tiles of the "sums" set. Random access: the tile of a cell is the
  same in every window that contains it.

``scanline`` (§3.2): tiles are placed west to east, north to south, each matching the tile
  above and the tile to the left, the remaining colours chosen at random; complete or
  compact sets (§3.2.1: ``2 C**2`` Wang tiles; §3.2.2: ``2 C**3`` corner tiles). The random
  choice of a cell is a hash of its coordinates (not a sequential random stream), and the
  colours the window's first row and column take from outside the window are hashes of the
  lattice too. Hence: a tile depends only on the cells between it and the window's NW corner,
  so **two windows with the same NW corner** ``(x0, y0 + h)`` agree where they overlap; with
  a *complete* set every choice is free and a tile depends on its own cell only (random
  access as for ``direct``); with a *compact* set windows with different NW corners are
  different tilings (the algorithm has no random access, §3.3).

Hashes (§3.4.3): ``"long"`` (default), the long-period hash of :func:`tiling_hash` (period
5,930,659,848), or ``"table"``, one permutation table of the smallest multiple of ``C`` that
is at least 256 entries (period that size). Tables are drawn from ``seed``.
"""

from __future__ import annotations

import math

import numpy as np

from tilesolve._random import rng_from_seed
from tilesolve.constructive import _lattice_kernels as _k
from tilesolve.constructive.hashes import PermutationHash, check_int, check_window, permutation_table, tiling_hash
from tilesolve.errors import InvalidProblem, MethodNotApplicable
from tilesolve.model.tiles import TileSet

__all__ = [
    "METHODS",
    "WANG_DIRECT",
    "HASHES",
    "tile_set",
    "make_hash",
    "direct_corner",
    "direct_wang",
    "scanline_wang",
    "scanline_corner",
    "stochastic_window",
]

METHODS = ("direct", "scanline")
#: Direct algorithms for Wang tiles: two hash functions (§3.3.2.1), a hash at the edges (§3.3.2.3).
WANG_DIRECT = ("edges", "two")
HASHES = ("long", "table")


# ------------------------------------------------------------------------------------ checks
def tile_set(kind: str, method: str, colors: int, variant: str = "complete") -> TileSet:
    """The :class:`TileSet` that ``method`` tiles with; raises when the notes give no such algorithm.

    ``direct`` exists for the complete sets and, for Wang tiles, the ``"sums"`` set of
    §3.3.2.2 (the notes' "compact" direct algorithm); there is no direct algorithm for
    compact corner sets (§3.5). ``scanline`` uses complete or compact sets (§3.2).
    """
    if method not in METHODS:
        raise InvalidProblem(f"unknown method {method!r}; choose one of {', '.join(METHODS)}")
    ts = TileSet(kind, check_int(colors, "colors", 1), variant=variant)
    if method == "direct" and variant == "compact":
        hint = ("use variant 'sums' (the direct algorithm for compact sets, §3.3.2.2) or method 'scanline'"
                if kind == "wang" else "the notes have none (§3.5); use method 'scanline'")
        raise MethodNotApplicable(f"no direct stochastic algorithm for the compact {kind} set: {hint}")
    if method == "scanline" and variant == "sums":
        raise MethodNotApplicable("the sums set (§3.3.2.2) belongs to the direct algorithm; use method 'direct'")
    return ts


def make_hash(name, colors: int, seed=None):
    """A 2-D lattice hash whose range is a multiple of ``colors`` (so ``h % colors`` is uniform).

    ``name`` is ``"long"`` (§3.4.3, :func:`tiling_hash`) or ``"table"`` (§3.4.1, eq. 3.3, a
    table of the smallest multiple of ``colors`` that is at least 256 entries).
    """
    if name == "long":
        return tiling_hash(colors, seed=seed)
    if name == "table":
        return PermutationHash(permutation_table(colors * -(-256 // colors), seed))
    raise InvalidProblem(f"unknown hash {name!r}; choose one of {', '.join(HASHES)}")


def _out_dtype(colors: int):
    return np.int32 if colors**4 < 2**31 else np.int64


# ------------------------------------------------------------------------------------ direct
def direct_corner(x0, y0, w, h, *, colors: int, seed=None, hash="long") -> np.ndarray:
    """Window of the direct stochastic corner tiling (§3.3.1, Lagae and Dutré 2006).

    Parameters
    ----------
    x0, y0, w, h : int
        The window ``[x0, x0 + w) x [y0, y0 + h)`` (see the module docstring).
    colors : int
        ``C``; tiles of the complete corner set (``C**4`` tiles).
    seed : int
        Draws the permutation tables.
    hash : {"long", "table"}

    Returns
    -------
    numpy.ndarray
        ``(h, w)`` eq. 2.5 indices (int32 when C**4 < 2**31), row 0 at the top.

    Examples
    --------
    >>> g = direct_corner(-2, 5, 4, 3, colors=3, seed=1)
    >>> g.shape, bool((direct_corner(-1, 6, 1, 1, colors=3, seed=1) == g[1, 1]).all())
    ((3, 4), True)
    """
    x0, y0, w, h = check_window(x0, y0, w, h)
    c = check_int(colors, "colors", 1)
    tables = make_hash(hash, c, seed).row_tables(np.arange(x0, x0 + w + 1), c)
    return _k.direct_corner(*tables, y0, c, np.empty((h, w), dtype=_out_dtype(c)))


def direct_wang(x0, y0, w, h, *, colors: int, seed=None, algorithm: str = "edges", variant: str = "complete",
                hash="long") -> np.ndarray:
    """Window of a direct stochastic Wang tiling (§3.3.2).

    Parameters
    ----------
    x0, y0, w, h : int
        The window (see the module docstring).
    colors : int
        ``C``.
    algorithm : {"edges", "two"}
        Complete set only: a hash at the tile edges on the doubled lattice (§3.3.2.3), or two
        hashes ``h_h``, ``h_v`` at the corners summed along each edge (§3.3.2.1).
    variant : {"complete", "sums"}
        ``"sums"``: the direct algorithm for compact sets (§3.3.2.2), one hash at the corners,
        each edge the sum of its two corners modulo ``C``; ``C**3`` tiles.
    seed, hash
        As for :func:`direct_corner`.

    Returns
    -------
    numpy.ndarray
        ``(h, w)`` eq. 2.1 indices (int32 when C**4 < 2**31), row 0 at the top.

    Notes
    -----
    §3.3.2.1 prints the W edge as ``(c_SW^c + c_NW^v) % C``; ``c_SW^c`` is read as
    ``c_SW^v`` (vertical edges use ``h_v``, as the E edge does).
    """
    x0, y0, w, h = check_window(x0, y0, w, h)
    c = check_int(colors, "colors", 1)
    tile_set("wang", "direct", c, variant)
    if variant == "complete" and algorithm not in WANG_DIRECT:
        raise InvalidProblem(f"unknown direct Wang algorithm {algorithm!r}; choose one of {', '.join(WANG_DIRECT)}")
    out = np.empty((h, w), dtype=_out_dtype(c))
    xs = np.arange(x0, x0 + w + 1)
    if variant == "sums" or algorithm == "two":
        rng = rng_from_seed(seed)
        hh = make_hash(hash, c, rng).row_tables(xs, c)
        hv = hh if variant == "sums" else make_hash(hash, c, rng).row_tables(xs, c)
        return _k.direct_wang_sums(*hh, *hv, y0, c, out)
    hsh = make_hash(hash, c, seed)
    twice, sizes, podd, red = hsh.row_tables(2 * xs[:-1] + 1, c)
    peven = hsh.row_tables(2 * xs, c)[2]
    return _k.direct_wang_edges(twice, sizes, podd, peven, red, y0, c, out)


# ------------------------------------------------------------------------------------ scanline
def _choice_tables(x0, w, seed, hash, span: int):
    """Row tables of the choice hash over the columns ``x0 - 1 .. x0 + w - 1`` (column 0: the
    virtual cells west of the window). ``span`` is how many values one choice needs (``C**2``
    for two free colours, ``C`` or ``lcm(C, 2)`` otherwise); the hash range is a multiple of it,
    so every choice is uniform."""
    return make_hash(hash, span, seed).row_tables(np.arange(x0 - 1, x0 + w), span)


def scanline_wang(x0, y0, w, h, *, colors: int, seed=None, variant: str = "complete", hash="long") -> np.ndarray:
    """Window of the scanline stochastic Wang tiling (§3.2.1, Cohen et al. 2003).

    The window is tiled from its NW corner, west to east and north to south. Each cell's
    free choice is a hash of its coordinates; the N colours of the top row and the W colours
    of the left column are those the same rule gives the virtual cells just outside the
    window (see the module docstring for what that guarantees).

    Parameters
    ----------
    variant : {"complete", "compact"}
        ``"compact"``: the ``2 C**2`` tiles of :class:`TileSet` (``E = N + k``,
        ``S = W + k``), one random bit per cell.

    Returns
    -------
    numpy.ndarray
        ``(h, w)`` eq. 2.1 indices (int32 when C**4 < 2**31), row 0 at the top.
    """
    x0, y0, w, h = check_window(x0, y0, w, h)
    c = check_int(colors, "colors", 1)
    tile_set("wang", "scanline", c, variant)
    compact = variant == "compact"
    tables = _choice_tables(x0, w, seed, hash, math.lcm(c, 2) if compact else c * c)
    return _k.scanline_wang(*tables, y0, c, compact, np.empty((h, w), dtype=_out_dtype(c)))


def scanline_corner(x0, y0, w, h, *, colors: int, seed=None, variant: str = "complete", hash="long") -> np.ndarray:
    """Window of the scanline stochastic corner tiling (§3.2.2, Lagae and Dutré 2006).

    As :func:`scanline_wang`; the corners on the window's top and west edges are the SE
    corners the virtual cells just outside the window choose. ``variant="compact"``: the
    ``2 C**3`` tiles of :class:`TileSet` (``SE = NE + NW + SW + k``, ``k`` in ``{0, 1}``).

    Returns
    -------
    numpy.ndarray
        ``(h, w)`` eq. 2.5 indices (int32 when C**4 < 2**31), row 0 at the top.
    """
    x0, y0, w, h = check_window(x0, y0, w, h)
    c = check_int(colors, "colors", 1)
    tile_set("corner", "scanline", c, variant)
    compact = variant == "compact"
    tables = _choice_tables(x0, w, seed, hash, math.lcm(c, 2) if compact else c)
    return _k.scanline_corner(*tables, y0, c, compact, np.empty((h, w), dtype=_out_dtype(c)))


def stochastic_window(kind: str, method: str, region, *, colors: int, seed, variant: str = "complete",
                      algorithm: str = "edges", hash="long") -> np.ndarray:
    """One entry point: ``region = (x0, y0, w, h)``; dispatches to the four functions above.

    Examples
    --------
    >>> from tilesolve.verify.grid import is_grid_tiling
    >>> ts = tile_set("corner", "scanline", 3, "compact")
    >>> g = stochastic_window("corner", "scanline", (0, 0, 6, 4), colors=3, seed=2, variant="compact")
    >>> is_grid_tiling(ts.table(), g, kind="corner", labels=ts.indices)
    True
    """
    if kind not in ("wang", "corner"):
        raise InvalidProblem(f"unknown tile kind {kind!r}; choose wang or corner")
    tile_set(kind, method, colors, variant)
    x0, y0, w, h = region
    if method == "direct":
        if kind == "corner":
            return direct_corner(x0, y0, w, h, colors=colors, seed=seed, hash=hash)
        return direct_wang(x0, y0, w, h, colors=colors, seed=seed, algorithm=algorithm, variant=variant, hash=hash)
    fn = scanline_wang if kind == "wang" else scanline_corner
    return fn(x0, y0, w, h, colors=colors, seed=seed, variant=variant, hash=hash)
