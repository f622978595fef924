"""Procedural stochastic brick walls (Derouet-Jourdan, Salvati, Jonchier, 004 §3-4, App. B).

The model (§3.1)
----------------
Cell ``(i, j)`` (``i`` east, ``j`` north) has a bottom edge ``H[i, j]``, a top edge
``H[i, j+1]``, a left edge ``V[i, j]`` and a right edge ``V[i+1, j]``. A *vertical* tile has
``H[i, j+1] = H[i, j]`` and ``V[i+1, j] != V[i, j]`` (eq. 1), a *horizontal* tile
``H[i, j+1] != H[i, j]`` and ``V[i+1, j] = V[i, j]`` (eq. 2): ``2 nc**2 (nc - 1)`` tiles
over ``nc`` colours (36 for ``nc = 3``), no crosses and no extra bricks. In tilesolve's board
leg order (N, E, S, W) = ``(H[i, j+1], V[i+1, j], H[i, j], V[i, j])`` this is exactly the set
``W_B`` of brick Wang tiles (:meth:`tilesolve.model.board.WangTileSet.brick`, Def. 9 of the
brick paper): horizontal tiles are ``W_H`` (``c1 = c3``), vertical tiles ``W_V``
(``c2 = c4``), and a line of ``k`` bricks is a run of ``k`` horizontal tiles along a row or of
``k`` vertical tiles up a column (``max_h``/``max_v`` of :class:`BoardProblem`).

The procedure (§4.2-4.3)
------------------------
The plane is cut into 2x2 blocks with bottom-left cell ``(i', j') = (i - i % 2, j - j % 2)``.
Their outer edges get pseudo-random colours ``h(i, j) = ℋ(i, j) % nc`` (even ``j``) and
``v(i, j) = 𝒱(i, j) % nc`` (even ``i``); the four inner edges come from the base-case solver
of App. B, which lists, for each of the 16 patterns of equal opposite outer edges, one to
three fillings (:data:`APPENDIX_B`); tilesolve picks one with a third hash of the block.
Every ``u % k`` of a hash value ``u`` (32 bits) is computed as the multiply-shift
``(u * k) >> 32``, which spreads the values over ``0 .. k-1`` as evenly as ``%`` does and
needs no division (``_reduce``).

Procedural dappling limits lines to ``n`` bricks by making some blocks 2x2 checkerboards:
a block whose opposite outer edges all differ can only be filled with one horizontal and one
vertical tile per row and column. For even ``n > 2`` the blocks with ``i' % n = j' % n``
(diagonals ``n - 2`` cells apart) get their bottom edge ``h' = hd1(i, j, h(i, j + 2))``
and their left edge ``v' = vd1(i, j, v(i + 2, j))``, colours unlike the opposite edge. For
``n = 2`` every block is a checkerboard: ``h'(i, j) = hd2(i, j, h(i, j - 2), h(i, j + 2))``
when ``j % 4 = 2`` (likewise ``v'`` when ``i % 4 = 2``). For odd ``n`` the paper only says:
"use only one type of checkerboard and separate each diagonal from the other one by ``n - 1``
cells". tilesolve's reading: the diagonals ``i' % (n + 1) = j' % (n + 1)``, built as for the
even ``n + 1``, always filled with the first App. B option of the all-different case (bottom
left tile vertical); ``n = 1`` is then one global checkerboard. A row meets a checkerboard
every ``n`` (even) or ``n + 1`` (odd) cells, so no run of horizontal tiles exceeds ``n``, and
likewise for columns (tested for ``n = 1..10``).

Hashes (§4.2): ℋ, 𝒱 and the option choice are :class:`FnvXorshift` streams 0, 1 and 2 of the
seed; a hash's *value* is its high 32 bits.

Reconstructions (the extraction is garbled or silent)
------------------------------------------------------
* ``vd2``/``hd2`` (App. B) print ``m'`` without its definition. Read as
  ``m' = 𝒱(i, j) % (nc - 2)``, the count of colours left when two distinct ones are excluded;
  when ``c1 = c2`` only one colour is excluded and ``vd2 = vd1`` (the printed cases would
  skip ``c1 - 1`` as well). ``hd1``/``hd2`` are the same functions of ℋ.
* App. B names its 16 cases ``b1 b2 b3 b4`` for the equalities ``H[i, j+2] = H[i, j]``,
  ``H[i+1, j] = H[i+1, j+2]``, ``V[i, j+1] = V[i+2, j+1]``, ``V[i, j] = V[i+2, j]`` in that
  order (checked: it is the only order under which every listed filling is valid).

Public functions return numpy arrays; ``seed`` is a non-negative integer.
"""

from __future__ import annotations

import numpy as np

from tilesolve.constructive._lattice_kernels import d1, d2, wall_kernel
from tilesolve.constructive.hashes import LATTICE_BOUND, FnvXorshift, check_int, check_window
from tilesolve.errors import InvalidProblem
from tilesolve.model.board import WangTileSet

__all__ = [
    "APPENDIX_B",
    "SOURCES",
    "brick_tile_set",
    "dappling_period",
    "wall_window",
    "wall_tile_scalar",
    "block_fillings",
    "orientation",
    "line_lengths",
]


#: Names of the values a 2x2 filling is made of: the eight outer edges of block ``(i, j)``
#: (``VT0 = V[i, j+1]``, ``VT2 = V[i+2, j+1]``, ``HL0 = H[i, j]``, ``HL2 = H[i, j+2]``,
#: ``VB0 = V[i, j]``, ``VB2 = V[i+2, j]``, ``HR0 = H[i+1, j]``, ``HR2 = H[i+1, j+2]``) and the
#: four "different colour" helpers ``vd2T = vd2(i+1, j+1, VT0, VT2)``,
#: ``hd2L = hd2(i, j+1, HL2, HL0)``, ``vd2B = vd2(i+1, j, VB0, VB2)``,
#: ``hd2R = hd2(i+1, j+1, HR0, HR2)``.
SOURCES = ("VT0", "VT2", "HL0", "HL2", "VB0", "VB2", "HR0", "HR2", "vd2T", "hd2L", "vd2B", "hd2R")

#: App. B, transcribed: for each case ``b1 b2 b3 b4`` the fillings
#: ``(V[i+1, j+1], H[i, j+1], V[i+1, j], H[i+1, j+1])`` in the paper's order.
APPENDIX_B: dict[str, tuple[tuple[str, str, str, str], ...]] = {
    "0000": (("VT0", "HL0", "VB2", "HR2"), ("VT2", "HL2", "VB0", "HR0")),
    "0001": (("vd2T", "HL2", "VB0", "HR2"), ("VT2", "HL2", "VB0", "hd2R"), ("VT0", "hd2L", "VB0", "HR2")),
    "0010": (("VT0", "HL0", "vd2B", "HR0"), ("VT0", "HL0", "VB2", "hd2R"), ("VT0", "hd2L", "VB0", "HR0")),
    "0011": (("VT0", "hd2L", "VB0", "hd2R"), ("VT0", "HL0", "vd2B", "HR0"), ("vd2T", "HL2", "VB0", "HR2")),
    "0100": (("VT0", "hd2L", "VB0", "HR0"), ("vd2T", "HL2", "VB0", "HR0"), ("VT0", "HL0", "vd2B", "HR0")),
    "0101": (("VT0", "HL0", "vd2B", "HR0"), ("VT2", "HL2", "VB0", "hd2R")),
    "0110": (("vd2T", "HL2", "VB0", "HR0"), ("VT2", "HL0", "VB2", "hd2R")),
    "0111": (("VT0", "hd2L", "VB0", "hd2R"),),
    "1000": (("VT2", "HL2", "VB2", "hd2R"), ("vd2T", "HL2", "VB2", "HR2"), ("VT2", "HL2", "vd2B", "HR0")),
    "1001": (("VT2", "HL2", "vd2B", "HR0"), ("VT0", "hd2L", "VB0", "HR2")),
    "1010": (("vd2T", "HL2", "VB2", "HR2"), ("VT2", "hd2L", "VB0", "HR0")),
    "1011": (("VT0", "hd2L", "VB0", "hd2R"),),
    "1100": (("vd2T", "HL2", "vd2B", "HR0"), ("VT0", "hd2L", "VB0", "HR0"), ("VT2", "HL2", "VB2", "hd2R")),
    "1101": (("vd2T", "HL2", "vd2B", "HR0"),),
    "1110": (("vd2T", "HL2", "vd2B", "HR0"),),
    "1111": (("vd2T", "HL2", "vd2B", "HR0"), ("VT0", "hd2L", "VB0", "hd2R")),
}


def _option_table() -> tuple[np.ndarray, np.ndarray]:
    opt = np.zeros((16, 3, 4), dtype=np.int64)
    nopt = np.zeros(16, dtype=np.int64)
    for key, fills in APPENDIX_B.items():
        k = int(key, 2)
        nopt[k] = len(fills)
        for o, fill in enumerate(fills):
            opt[k, o] = [SOURCES.index(s) for s in fill]
    return opt, nopt


_OPT, _NOPT = _option_table()
_VT0, _VT2, _HL0, _HL2, _VB0, _VB2, _HR0, _HR2, _VD2T, _HD2L, _VD2B, _HD2R = range(12)


# ------------------------------------------------------------------------------------ checks
def _check_params(colors, max_line, seed) -> tuple[int, int, int]:
    """``(nc, P, seed)``: ``P`` is the dappling period (0: no limit), see :func:`dappling_period`."""
    nc = check_int(colors, "colors")
    if nc < 3:
        raise InvalidProblem(f"brick walls need at least 3 colours (004 §3.1, App. A), got {nc}")
    if nc > 127:
        raise InvalidProblem(f"tilesolve draws walls with at most 127 colours, got {nc}")
    p = dappling_period(max_line)
    s = check_int(seed, "seed", 0)
    if s >= 1 << 64:
        raise InvalidProblem(f"seed must be below 2**64, got {s}")
    return nc, p, s


def dappling_period(max_line) -> int:
    """Distance between checkerboard diagonals for lines of at most ``max_line`` bricks (§4.3).

    ``n`` for even ``n``, ``n + 1`` for odd ``n`` (one checkerboard type), ``0`` for ``None``
    (no limit: the general solution of §4.2).
    """
    if max_line is None:
        return 0
    n = check_int(max_line, "max_line")
    if n < 1:
        raise InvalidProblem(f"the maximum line length must be >= 1 brick, got {n}")
    return n if n % 2 == 0 else n + 1


def brick_tile_set(colors: int = 3) -> WangTileSet:
    """The wall tiles of §3.1 (eq. 1 and 2) as a :class:`WangTileSet` in leg order (N, E, S, W).

    Built from the paper's definition; it equals :meth:`WangTileSet.brick` (Def. 9 of the
    brick paper) and has ``2 nc**2 (nc - 1)`` tiles.

    Examples
    --------
    >>> len(brick_tile_set(3)), len(brick_tile_set(4))
    (36, 96)
    """
    nc = check_int(colors, "colors")
    if nc < 3:
        raise InvalidProblem(f"brick walls need at least 3 colours, got {nc}")
    v0, htop, v1, hbot = np.meshgrid(*[np.arange(nc)] * 4, indexing="ij")
    vertical = (htop == hbot) & (v1 != v0)  # eq. 1
    horizontal = (htop != hbot) & (v1 == v0)  # eq. 2
    keep = vertical | horizontal
    tiles = np.stack([htop[keep], v1[keep], hbot[keep], v0[keep]], axis=1)
    return WangTileSet(tiles, nc, is_brick=True)


# ------------------------------------------------------------------------------------ scalar form
def _reduce(raw, k):
    """``raw % k`` in distribution, without a division: ``floor(raw * k / 2**32)`` for a 32-bit ``raw``.

    Every one of the ``k`` results takes ``floor(2**32 / k)`` or ``ceil(2**32 / k)`` of the
    inputs, as with ``%`` (Lemire's multiply-shift range reduction).
    """
    return (raw * k) >> 32


def block_fillings(outer, colors: int, raws=(0, 0, 0, 0)) -> list[tuple[int, int, int, int]]:
    """Every App. B filling ``(V[i+1, j+1], H[i, j+1], V[i+1, j], H[i+1, j+1])`` of one 2x2 block.

    ``outer`` holds the eight outer colours in :data:`SOURCES` order; ``raws`` the hash
    values behind ``vd2T, hd2L, vd2B, hd2R``.

    Examples
    --------
    >>> block_fillings([0, 1, 0, 1, 0, 1, 0, 1], 3)   # case 0000: the two checkerboards
    [(0, 0, 1, 1), (1, 1, 0, 0)]
    """
    o = [int(x) for x in outer]
    nc = int(colors)
    helpers = [d2(raws[0], nc, o[_VT0], o[_VT2]), d2(raws[1], nc, o[_HL2], o[_HL0]),
               d2(raws[2], nc, o[_VB0], o[_VB2]), d2(raws[3], nc, o[_HR0], o[_HR2])]
    vals = o + helpers
    case = _case(o)
    return [tuple(vals[int(s)] for s in _OPT[case, k]) for k in range(int(_NOPT[case]))]


def _case(o) -> int:
    """App. B case number ``b1 b2 b3 b4`` (binary) of the outer colours ``o`` (:data:`SOURCES` order)."""
    return (8 * (o[_HL2] == o[_HL0]) + 4 * (o[_HR0] == o[_HR2]) + 2 * (o[_VT0] == o[_VT2])
            + (o[_VB0] == o[_VB2]))


class _ScalarWall:
    """The procedure of §4.2-4.3 for one cell at a time, in plain Python (the reference form)."""

    def __init__(self, nc: int, period: int, fixed: bool, seed: int) -> None:
        self.nc, self.p, self.fixed = nc, period, fixed
        self.hh, self.vv, self.oo = FnvXorshift(seed, 0), FnvXorshift(seed, 1), FnvXorshift(seed, 2)

    def raw(self, hsh, i, j):
        return hsh.scalar(i, j) >> 32

    def d1(self, hsh, i, j, c):
        return d1(self.raw(hsh, i, j), self.nc, c)

    def d2(self, hsh, i, j, c1, c2):
        return d2(self.raw(hsh, i, j), self.nc, c1, c2)

    def h(self, i, j):
        return _reduce(self.raw(self.hh, i, j), self.nc)

    def v(self, i, j):
        return _reduce(self.raw(self.vv, i, j), self.nc)

    def diagonal(self, i, j):
        """Is the block with bottom-left cell ``(i, j)`` a checkerboard?"""
        return self.p == 2 or (self.p > 2 and i % self.p == j % self.p)

    def h1(self, i, j):
        """``h'(i, j)`` for even ``j``."""
        if self.p == 2:
            return self.h(i, j) if j % 4 == 0 else self.d2(self.hh, i, j, self.h(i, j - 2), self.h(i, j + 2))
        if self.p > 2 and self.diagonal(i - i % 2, j):
            return self.d1(self.hh, i, j, self.h(i, j + 2))
        return self.h(i, j)

    def v1(self, i, j):
        """``v'(i, j)`` for even ``i``."""
        if self.p == 2:
            return self.v(i, j) if i % 4 == 0 else self.d2(self.vv, i, j, self.v(i - 2, j), self.v(i + 2, j))
        if self.p > 2 and self.diagonal(i, j - j % 2):
            return self.d1(self.vv, i, j, self.v(i + 2, j))
        return self.v(i, j)

    def tile(self, i, j):
        """Leg colours ``(N, E, S, W)`` of cell ``(i, j)``."""
        bi, bj = i - i % 2, j - j % 2
        o = [self.v1(bi, bj + 1), self.v1(bi + 2, bj + 1), self.h1(bi, bj), self.h1(bi, bj + 2),
             self.v1(bi, bj), self.v1(bi + 2, bj), self.h1(bi + 1, bj), self.h1(bi + 1, bj + 2)]
        case = _case(o)
        if self.fixed and self.diagonal(bi, bj):
            option = 0  # odd n: one checkerboard type (bottom-left tile vertical)
        else:
            option = _reduce(self.raw(self.oo, bi, bj), int(_NOPT[case]))

        def source(s):
            if s < 8:
                return o[s]
            if s == _VD2T:
                return self.d2(self.vv, bi + 1, bj + 1, o[_VT0], o[_VT2])
            if s == _HD2L:
                return self.d2(self.hh, bi, bj + 1, o[_HL2], o[_HL0])
            if s == _VD2B:
                return self.d2(self.vv, bi + 1, bj, o[_VB0], o[_VB2])
            return self.d2(self.hh, bi + 1, bj + 1, o[_HR0], o[_HR2])

        vt1, hl1, vb1, hr1 = (source(int(s)) for s in _OPT[case, option])
        di, dj = i - bi, j - bj
        if dj == 0:
            return (hl1, vb1, o[_HL0], o[_VB0]) if di == 0 else (hr1, o[_VB2], o[_HR0], vb1)
        return (o[_HL2], vt1, hl1, o[_VT0]) if di == 0 else (o[_HR2], o[_VT2], hr1, vt1)


_STRIP_CELLS = 1 << 16


def wall_window(x0, y0, w, h, *, colors: int = 3, max_line: int | None = None, seed: int = 0) -> np.ndarray:
    """The procedural wall (004 §4.2-4.3) on the cells ``[x0, x0 + w) x [y0, y0 + h)``.

    Parameters
    ----------
    x0, y0, w, h : int
        Window: cells ``(i, j)`` with ``x0 <= i < x0 + w`` and ``y0 <= j < y0 + h``
        (``j`` grows northwards); ``|coordinates| < 2**62``.
    colors : int
        ``nc >= 3`` edge colours.
    max_line : int, optional
        ``n >= 1``: no line longer than ``n`` bricks (procedural dappling, §4.3); ``None``: the
        general solution of §4.2 (no limit).
    seed : int
        Seeds the hashes ℋ, 𝒱 and the App. B option choice.

    Returns
    -------
    numpy.ndarray
        ``(h, w, 4)`` int8 leg colours ``(N, E, S, W)``, row 0 at the top: ``out[r, c]`` is
        cell ``(x0 + c, y0 + h - 1 - r)``, i.e. ``(H[i, j+1], V[i+1, j], H[i, j], V[i, j])``.
        The same cell has the same tile in every window (random access).

    Examples
    --------
    >>> t = wall_window(-3, 5, 4, 2, colors=3, max_line=2, seed=1)
    >>> t.shape, tuple(int(x) for x in t[1, 0]) == wall_tile_scalar(-3, 5, colors=3, max_line=2, seed=1)
    ((2, 4, 4), True)
    """
    x0, y0, w, h = check_window(x0, y0, w, h, what="wall window")
    nc, p, s = _check_params(colors, max_line, seed)
    fixed = max_line is not None and int(max_line) % 2 == 1
    out = np.empty((h, w, 4), dtype=np.int8)
    basis = [np.uint64(FnvXorshift(s, k).basis) for k in range(3)]
    # Strips of about 2**16 cells keep the kernel's scratch arrays in cache; random access makes
    # each strip the same as the corresponding rows of one big window.
    rows = max(2, min(h, _STRIP_CELLS // w))
    for top in range(0, h, rows):
        hh = min(rows, h - top)
        wall_kernel(x0, y0 + h - top - hh, w, hh, nc, p, fixed, basis[0], basis[1], basis[2], _OPT, _NOPT,
                     out[top: top + hh])
    return out


def wall_tile_scalar(i, j, *, colors: int = 3, max_line: int | None = None,
                     seed: int = 0) -> tuple[int, int, int, int]:
    """Leg colours ``(N, E, S, W)`` of cell ``(i, j)``: the same procedure, one cell, plain Python.

    A straight transcription of §4.2-4.3 (what a shader does per pixel); :func:`wall_window`
    is its compiled, window-at-a-time form and agrees with it bit for bit.
    """
    nc, p, s = _check_params(colors, max_line, seed)
    i, j = check_int(i, "i"), check_int(j, "j")
    if not (-LATTICE_BOUND <= i < LATTICE_BOUND and -LATTICE_BOUND <= j < LATTICE_BOUND):
        raise InvalidProblem(f"cell ({i}, {j}) is outside |coordinates| < 2**62")
    return _ScalarWall(nc, p, max_line is not None and int(max_line) % 2 == 1, s).tile(i, j)


def orientation(legs) -> np.ndarray:
    """``True`` where a tile is horizontal (``W = E``, eq. 2), ``False`` where vertical (eq. 1)."""
    t = np.asarray(legs)
    return t[..., 3] == t[..., 1]


def line_lengths(legs) -> tuple[np.ndarray, np.ndarray]:
    """Lengths of the maximal runs of horizontal tiles along rows and of vertical tiles along columns.

    Runs are cut at the window's border (a run that leaves the window counts only its cells
    inside). Returns ``(horizontal_lines, vertical_lines)``, each a 1-D int64 array.
    """
    hor = orientation(legs)

    def runs(m: np.ndarray) -> np.ndarray:
        pad = np.zeros((m.shape[0], 1), dtype=np.int8)
        d = np.diff(np.concatenate([pad, m.astype(np.int8), pad], axis=1), axis=1)
        starts, ends = np.nonzero(d == 1), np.nonzero(d == -1)
        return (ends[1] - starts[1]).astype(np.int64)

    return runs(hor), runs((~hor).T)
