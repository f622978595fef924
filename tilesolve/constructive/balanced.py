"""Windows of Kari's and Culik's aperiodic tilings, row by row from balanced sequences (issue 20, §1).

J. Kari, *A small aperiodic set of Wang tiles*, Discrete Math. 160 (1996) 259-264 (14 tiles),
and K. Culik II, *An aperiodic set of 13 Wang tiles*, Discrete Math. 160 (1996) 245-251.

The construction
----------------
The *balanced representation* of a real ``x`` is the sequence of digits
``d_j(x) = floor((j + 1) x) - floor(j x)``, ``j`` in Z; every digit is ``floor(x)`` or
``ceil(x)``, and any ``n`` consecutive digits sum to ``n x`` within 1. A tile of these sets is
a transition of a sequential machine that multiplies by ``q = p / r``: it reads a digit ``a``
(its N edge), writes a digit ``b`` (its S edge), and takes a carry ``s`` in on its W edge and
gives ``t`` out on its E edge with

    ``p a + s = r b + t``.

With ``y = q x`` and the carry ``c_j = p floor(j x) - r floor(j y)`` on the edge between cells
``j - 1`` and ``j``, the cell ``j`` of a row is the transition ``(d_j(x), d_j(y), c_j,
c_{j+1})``; ``c_j`` lies in ``{1 - p, ..., r - 1}`` for every real ``x`` (from ``z - 1 <
floor(z) <= z``). A row whose N edges carry ``x`` thus carries ``f(x)`` on its S edges, and
the row below it carries ``f(f(x))``: the rows of a tiling run **downwards** through an orbit of

    ``f(x) = 2 x``  for ``x <= 1``,     ``f(x) = 2 x / J``  for ``x > 1``,

with ``J = 3`` for Kari's set (``q = 2/3``) and ``J = 6`` for Culik's (``q = 1/3``); the
papers differ on the side of the boundary point, here ``x = 1`` multiplies by 2. On
``I = (2/J, 2]`` the map ``f`` is a bijection of ``I`` (in ``log x`` it is the rotation by
``log 2`` of a circle of length ``log(2 J / 2) = log J``), so every ``x0`` in ``I`` has a
bi-infinite orbit, in closed form:

    row ``y`` carries ``x(y) = x0 2**-y J**-m``, ``m`` the one integer that puts it in ``I``.

Any window is therefore cut from one tiling of the plane fixed by ``x0`` (drawn from the seed):
windows of a seed agree where they overlap, at any origin. ``x0`` is a rational and ``x(y)`` a
rational of about ``1.6 |y|`` bits. Every floor is decided exactly: the fast path
(:func:`balanced_window`) bounds ``x(y) 2**PREC`` between two integers (from the closed form,
then by ``f`` row by row) and decides a floor from the bounds where they agree, from sharper
bounds or exact rationals (rows ``|y| <= MAX_EXACT_ROW``) where they do not. Beyond
``MAX_EXACT_ROW`` no floor that matters falls on an integer (``x(y)`` has a denominator above
``2**600000``), so sharper bounds decide it; a floor still undecided at 4096 bits is refused
rather than guessed (an ``InvalidProblem`` naming the row).

The tiles as transitions
------------------------
The built-in files (``kari-14.json``, ``kari-culik-13.json``, N, E, S, W) are read here as the
transitions :attr:`Machine.tiles` (kind, primed, ``a``, ``b``, ``s``), in the files' order; the
colours follow from :attr:`Machine.carry_colours` (the E/W colours of each kind's carries) and
the digits (the N/S colour of digit ``d`` is ``d``), as :func:`tile_colours` rebuilds them
(the tests compare them with the files). *Kind* 0 is a row with ``x <= 1`` (``q = 2``), kind 1
one with ``x > 1`` (``q = 2/J``). In Culik's set a digit 0 written by a kind-0 row has a colour
of its own (3, "primed"): a kind-0 row below a kind-0 row reads it, and only with the one tile
(index 3) that turns it into a 1 -- the only output a kind-0 row below a kind-0 row can write
there (its ``x`` is in ``(2/3, 1]``).

Examples
--------
>>> from tilesolve.model.window import Window
>>> balanced_window("kari-14", Window(0, 0, 8, 3), seed=1)
array([[13, 11, 10, 13, 11, 10, 13, 11],
       [ 2,  1,  3,  2,  1,  3,  2,  1],
       [13, 11,  6, 11, 10,  5, 10,  9]], dtype=uint8)
"""

from __future__ import annotations

import math
import threading
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from decimal import ROUND_CEILING, Decimal, localcontext

import numpy as np

from tilesolve._random import rng_from_seed
from tilesolve.constructive import _balanced_kernels as _k
from tilesolve.constructive._jit import cores as _cores
from tilesolve.errors import InternalError, InvalidProblem
from tilesolve.model.window import Window

__all__ = ["NAMES", "MAX_EXACT_ROW", "Machine", "machine", "tile_colours", "balanced_window", "balanced_window_exact"]

#: The built-in tile sets this route draws.
NAMES = ("kari-14", "kari-culik-13")
#: Rows whose ``x(y)`` (about ``1.6 |y|`` bits) exact arithmetic reaches: the fast path's last
#: resort and the reference :func:`balanced_window_exact`.
MAX_EXACT_ROW = 1 << 20
#: Bits of the lines' bounds: ``x 2**PREC`` within a few units (two more a row), so that
#: ``floor(j x 2**BITS)``, ``|j| < 2**63``, is decided unless ``j x`` lies within about
#: ``2**(88 - PREC)`` of a multiple of ``2**-BITS``.
PREC = 256
#: Sharper bounds, tried in turn where a floor is undecided.
_SHARPER = (1024, 4096)
#: Fixed-point bits of the fast path: ``floor(phi + c x)`` is read from ``phi`` and ``x`` to
#: ``BITS`` bits, decided exactly wherever the rounding could change it.
BITS = 47
#: Columns per exact restart of the fast path, so that ``phi + c x`` stays below ``2**63``
#: (``x <= 2``: ``CHUNK * 2**(BITS + 1) + 2**BITS < 2**63``).
CHUNK = 1 << 14
#: Column chunks of one job: a job builds a block of at most ``CHUNK * _BLOCK_CHUNKS`` columns.
_BLOCK_CHUNKS = 4
#: ``G`` values (the floors of one job) per job, and its most rows: they size its rows.
_BAND_CELLS = 1 << 20
_BAND_ROWS = 1 << 12


@dataclass(frozen=True)
class Machine:
    """The sequential machine of one tile set.

    Attributes
    ----------
    name : str
        The built-in tile set.
    jump : int
        ``J``: ``f(x) = 2 x`` on ``(2/J, 1]``, ``2 x / J`` on ``(1, 2]``.
    steps : ((int, int), (int, int))
        ``(p, r)`` of kind 0 (``q = 2``) and kind 1 (``q = 2/J`` in lowest terms).
    primed_colour : int or None
        The colour of a digit 0 written by a kind-0 row (Culik's set), ``None`` where a 0 has
        colour 0 whoever wrote it (Kari's).
    carry_colours : (dict, dict)
        The E/W colour of each carry, for kind 0 and kind 1.
    tiles : tuple of (kind, primed, a, b, s)
        Tile ``i`` of the built-in file is the transition reading ``a`` (primed: a 0 written by
        a kind-0 row), writing ``b``, with carry ``s`` in (W) and ``s + p a - r b`` out (E).
    """

    name: str
    jump: int
    steps: tuple[tuple[int, int], tuple[int, int]]
    primed_colour: int | None
    carry_colours: tuple[dict[int, int], dict[int, int]]
    tiles: tuple[tuple[int, int, int, int, int], ...]

    def carries(self, kind: int) -> range:
        """The carries a row of ``kind`` can hold: ``1 - p .. r - 1``."""
        p, r = self.steps[kind]
        return range(1 - p, r)

    def transition(self, i: int) -> tuple[int, int, int, int, int, int]:
        """Tile ``i`` as ``(kind, primed, a, b, s, t)``, ``t`` its carry out."""
        kind, primed, a, b, s = self.tiles[i]
        p, r = self.steps[kind]
        return kind, primed, a, b, s, s + p * a - r * b


_MACHINES = {
    "kari-14": Machine(
        "kari-14", 3, ((2, 1), (2, 3)), None,
        ({-1: 7, 0: 0}, {-1: 4, 0: 3, 1: 5, 2: 6}),
        ((0, 0, 1, 2, -1), (0, 0, 1, 1, -1), (0, 0, 0, 1, 0), (0, 0, 1, 2, 0),
         (1, 0, 2, 1, -1), (1, 0, 2, 1, 0), (1, 0, 2, 1, 1), (1, 0, 2, 2, 1), (1, 0, 2, 2, 2),
         (1, 0, 1, 1, 0), (1, 0, 1, 1, 1), (1, 0, 1, 1, 2), (1, 0, 1, 0, -1), (1, 0, 1, 0, 0))),
    "kari-culik-13": Machine(
        "kari-culik-13", 6, ((2, 1), (1, 3)), 3,
        ({-1: 4, 0: 3}, {0: 2, 1: 1, 2: 0}),
        ((0, 0, 0, 0, 0), (0, 0, 1, 2, 0), (0, 0, 0, 1, 0), (0, 1, 0, 1, 0), (0, 0, 0, 0, -1),
         (0, 0, 1, 2, -1), (0, 0, 1, 1, -1),
         (1, 0, 2, 1, 2), (1, 0, 1, 1, 2), (1, 0, 2, 1, 1), (1, 0, 1, 0, 1), (1, 0, 2, 0, 0),
         (1, 0, 1, 0, 0))),
}


def machine(name: str) -> Machine:
    """The machine of built-in set ``name`` (one of :data:`NAMES`)."""
    try:
        return _MACHINES[name]
    except (KeyError, TypeError):
        raise InvalidProblem(f"no balanced-sequence route for {name!r}; it draws {', '.join(NAMES)}") from None


def tile_colours(name: str) -> list[list[int]]:
    """The tiles ``[N, E, S, W]`` of ``name`` rebuilt from the machine's transitions.

    >>> tile_colours("kari-culik-13")[3]
    [3, 4, 1, 3]
    """
    m = machine(name)
    out = []
    for i in range(len(m.tiles)):
        kind, primed, a, b, s, t = m.transition(i)
        north = m.primed_colour if primed else a
        south = m.primed_colour if (m.primed_colour is not None and kind == 0 and b == 0) else b
        out.append([north, m.carry_colours[kind][t], south, m.carry_colours[kind][s]])
    return out


# --------------------------------------------------------------------------- the orbit
def _start(m: Machine, seed: int) -> tuple[int, int]:
    """``x0 = u / v`` in ``(2/J, 2)``, drawn from ``seed``."""
    k = int(rng_from_seed(seed).integers(1, 1 << 62))
    # x0 = (2/J) (1 + (J - 1) k / 2**62)
    return 2 * ((1 << 62) + (m.jump - 1) * k), m.jump << 62


def _row_value(m: Machine, start: tuple[int, int], y: int) -> tuple[int, int]:
    """``x(y) = P / Q`` (not in lowest terms): ``x0 2**-y J**-m`` in ``(2/J, 2]``."""
    u, v = start
    num, den = (u << -y, v) if y <= 0 else (u, v << y)
    # x = num / den J**-m with the least m that makes x <= 2: m estimated, then corrected.
    e = math.floor((num.bit_length() - den.bit_length() - 1) / math.log2(m.jump))
    p, q = (num, den * m.jump**e) if e >= 0 else (num * m.jump**-e, den)
    while p > 2 * q:
        q *= m.jump
    while m.jump * p <= 2 * q:
        p *= m.jump
    return p, q


def _check_exact_rows(window: Window) -> None:
    lo, hi = window.y0 - 1, window.y0 + window.height
    if max(abs(lo), abs(hi)) > MAX_EXACT_ROW:
        raise InvalidProblem(f"window {window.describe()}: exact arithmetic draws rows y within "
                             f"+-{MAX_EXACT_ROW:,} (row y holds a rational of about 1.6 |y| bits)")


class _X:
    """``x(y)`` as the fast path knows it: ``lo <= x 2**S <= hi``, or (``S`` None) ``x = lo /
    hi`` exactly."""

    __slots__ = ("lo", "hi", "S")

    def __init__(self, lo: int, hi: int, S: int | None):
        self.lo, self.hi, self.S = lo, hi, S

    def floor(self, j: int, k: int) -> int | None:
        """``floor(j x 2**k)`` (``k <= S``), or None where the bounds do not decide it."""
        if self.S is None:
            return (j * self.lo << k) // self.hi
        a, b = (j * self.lo, j * self.hi) if j >= 0 else (j * self.hi, j * self.lo)
        sh = self.S - k
        f = a >> sh
        return f if f == b >> sh else None

    def kind(self) -> int | None:
        """``int(x > 1)``, or None where the bounds do not decide it."""
        if self.S is None:
            return int(self.lo > self.hi)
        one = 1 << self.S
        return 1 if self.lo > one else 0 if self.hi <= one else None

    def step(self, p: int, r: int) -> "_X":
        """``x p / r`` (bounds at :data:`PREC` bits after an exact ``x``)."""
        if self.S is None:
            lo = (self.lo * p << PREC) // (self.hi * r)
            return _X(lo, lo + 1, PREC)
        return _X(self.lo * p // r, -(-self.hi * p // r), self.S)


def _sharpen(m: Machine, start: tuple[int, int], y: int, X: _X) -> _X:
    """``x(y)`` known better than ``X``: bounds at the next of :data:`_SHARPER`, else exact
    (rows within :data:`MAX_EXACT_ROW`)."""
    for S in _SHARPER:
        if X.S is not None and S > X.S:
            sharper = _row_bounds(m, start, y, S)
            if sharper is not None:
                return sharper
    if X.S is not None and abs(y) <= MAX_EXACT_ROW:
        return _X(*_row_value(m, start, y), None)
    raise InvalidProblem(f"row y = {y}: a floor of x(y) is undecided at {X.S} bits and the row is "
                         f"beyond +-{MAX_EXACT_ROW:,}, where exact arithmetic stops; try another seed")


def _decide(m: Machine, start: tuple[int, int], y: int, X: _X, ask) -> tuple[int, _X]:
    """``ask(X)`` for ``x(y)``, sharpening ``X`` until it answers; returns the answer and the ``X``."""
    while (v := ask(X)) is None:
        X = _sharpen(m, start, y, X)
    return v, X


def _row_bounds(m: Machine, start: tuple[int, int], y: int, S: int) -> _X | None:
    """Bounds of ``x(y) 2**S`` from the closed form at any row, or None where ``S`` bits cannot
    tell which ``J**-m`` puts ``x(y)`` in ``(2/J, 2]``."""
    u, v = start
    J = m.jump
    with localcontext() as ctx:  # the least e with x0 2**-y J**-e <= 2, to within one
        ctx.prec = 60
        ln2 = Decimal(2).ln()
        e = ((Decimal(u) / Decimal(v)).ln() / ln2 - y - 1) / (Decimal(J).ln() / ln2)
        e = int(e.to_integral_value(rounding=ROUND_CEILING))
    two = 2 << S
    while True:
        lo_p, lo_e, hi_p, hi_e = _pow_bounds(J, abs(e), S + 16)
        if e >= 0:  # x 2**S = u 2**(S - y) / (v J**e)
            X = _X(_fdiv(u, v * hi_p, S - y - hi_e), -_fdiv(-u, v * lo_p, S - y - lo_e), S)
        else:  # x 2**S = u J**-e 2**(S - y) / v
            X = _X(_fdiv(u * lo_p, v, S - y + lo_e), -_fdiv(-u * hi_p, v, S - y + hi_e), S)
        if X.lo > two:
            e += 1
        elif X.hi <= two and J * X.hi <= two:
            e -= 1
        elif X.hi <= two and J * X.lo > two:
            return X
        else:
            return None


def _fdiv(a: int, b: int, k: int) -> int:
    """``floor(a 2**k / b)``, ``b > 0``."""
    return (a << k) // b if k >= 0 else a // (b << -k)


def _pow_bounds(J: int, n: int, S: int) -> tuple[int, int, int, int]:
    """``(lo, le, hi, he)`` with ``lo 2**le <= J**n <= hi 2**he``, mantissas of ``S`` bits
    (square and multiply, each product rounded down for ``lo``, up for ``hi``)."""
    lo = hi = 1
    le = he = 0
    blo = bhi = J
    ble = bhe = 0
    while True:
        if n & 1:
            lo, le = _round(lo * blo, le + ble, S, False)
            hi, he = _round(hi * bhi, he + bhe, S, True)
        n >>= 1
        if not n:
            return lo, le, hi, he
        blo, ble = _round(blo * blo, 2 * ble, S, False)
        bhi, bhe = _round(bhi * bhi, 2 * bhe, S, True)


def _round(a: int, e: int, S: int, up: bool) -> tuple[int, int]:
    """``a 2**e`` to ``S`` bits of mantissa, rounded down or up."""
    sh = a.bit_length() - S
    if sh <= 0:
        return a, e
    return (-(-a >> sh) if up else a >> sh), e + sh


# --------------------------------------------------------------------------- the reference
def balanced_window_exact(name: str, window: Window, seed: int) -> np.ndarray:
    """:func:`balanced_window` cell by cell with exact integers (slow: the cross-check).

    Each row's ``x(y) = P / Q`` comes from the closed form on its own (no iteration of ``f``),
    each digit and carry from its definition (``floor(j x) = j P // Q``), each tile from a
    search of :attr:`Machine.tiles`. Rows within ``+-MAX_EXACT_ROW`` (an ``InvalidProblem``
    beyond).

    >>> from tilesolve.model.window import Window
    >>> w = Window(-3, -2, 5, 4)
    >>> bool((balanced_window_exact("kari-culik-13", w, 7) == balanced_window("kari-culik-13", w, 7)).all())
    True
    """
    m = machine(name)
    window = Window.of(window)
    _check_exact_rows(window)
    start = _start(m, seed)
    out = np.empty(window.shape, np.uint8)
    for row in range(window.height):
        y = window.cell(row, 0)[1]
        (P, Q), (Pb, Qb), (Pa, Qa) = (_row_value(m, start, y + d) for d in (0, -1, 1))
        kind = int(P > Q)
        p, r = m.steps[kind]
        primed_row = m.primed_colour is not None and Pa <= Qa
        for col in range(window.width):
            j = window.x0 + col
            a = (j + 1) * P // Q - j * P // Q
            b = (j + 1) * Pb // Qb - j * Pb // Qb
            s = p * (j * P // Q) - r * (j * Pb // Qb)
            out[row, col] = m.tiles.index((kind, int(primed_row and a == 0), a, b, s))
    return out


# --------------------------------------------------------------------------- the fast path
def _lut(m: Machine) -> tuple[np.ndarray, int]:
    """``lut[64 (2 kind + above) + 16 a + 4 b + s - smin]``: the tile of a transition in a row
    of ``kind`` whose row above has kind ``above`` (255 where none), and ``smin``."""
    smin = min(min(m.carries(0)), min(m.carries(1)))
    lut = np.full((4, 4, 4, 4), 255, np.uint8)
    for i, (kind, primed, a, b, s) in enumerate(m.tiles):
        for above in (0, 1):
            if int(m.primed_colour is not None and above == 0 and a == 0) == primed:
                lut[2 * kind + above, a, b, s - smin] = i
    return lut.ravel(), smin


def balanced_window(name: str, window: Window, seed: int) -> np.ndarray:
    """The window ``window`` of the tiling of built-in set ``name`` that ``seed`` fixes.

    Parameters
    ----------
    name : str
        ``"kari-14"`` or ``"kari-culik-13"`` (:data:`NAMES`).
    window : Window or (x0, y0, width, height)
        The cells, anywhere (coordinates within ``+-2**62``).
    seed : int
        Chooses ``x0`` (hence the tiling of the plane); the same seed gives the same tiling.

    Returns
    -------
    numpy.ndarray
        ``uint8`` of shape ``(height, width)``: the tile indices (the built-in file's order) of
        the cells ``window.cell(r, c)`` (row 0 is the top row when y grows upwards).

    Raises
    ------
    InvalidProblem
        An unknown name, a negative seed, or (about ``2**-3900`` of the seeds at a row beyond
        :data:`MAX_EXACT_ROW`) a floor that 4096 bits cannot decide.

    Notes
    -----
    Row by row downwards: bounds of ``x 2**PREC`` for the row above the window from the closed
    form, then ``x -> f(x)`` on the bounds, each row's kind and its first floors decided from
    them (sharper bounds, or exact rationals, where they do not agree). ``G[c] = floor(j x) -
    floor(x0 x)`` of the window's columns ``j = x0 + c`` is read in int64 fixed point from
    ``phi = floor(2**BITS frac(j x))`` and ``floor(2**BITS x)``, restarted every
    :data:`CHUNK` columns. The rounding error of ``phi + c x`` is below ``c + 1`` units, so a
    floor is decided unless the low bits lie within ``c + 1`` of the next unit; those few
    cells (about ``c / 2**BITS`` of them, and the column ``j = 0``) are decided from the
    line's bounds. The digits and carries are differences of ``G`` of two rows, and a table
    gives the tile. A few operations on integers of ``PREC`` bits a row, ``O(width)`` machine
    words; bands of rows run on threads.
    """
    return _window(name, window, seed, BITS)


def _window(name: str, window: Window, seed: int, bits: int) -> np.ndarray:
    """:func:`balanced_window` with ``bits`` fixed-point bits (tests lower it so that the
    exact fix-ups happen often)."""
    m = machine(name)
    window = Window.of(window)
    start = _start(m, seed)
    lut, smin = _lut(m)
    h, w = window.height, window.width
    kern = _k.KERNELS.pick(h * w)
    out = np.empty((h, w), np.uint8)
    block = CHUNK * _BLOCK_CHUNKS  # columns of one job
    band = max(1, min(_BAND_ROWS, _BAND_CELLS // (min(w, block) + 1)))  # rows of one job
    # Line i is the row y = y0 + h - i: i = 0 is the row above the window (its kind only),
    # lines 1..h the window's rows, line h + 1 the row below (its digits are row h's S edges).
    lines = _Lines(m, start, window.y0 + h, window.x0, w, bits)
    above = next(lines)[3]
    scratch = threading.local()

    def run(top: int, c0: int, band_lines: list, above: int) -> int:
        """The rows ``top ..`` of the band, columns ``c0 .. c0 + width - 1``; returns the rows
        with a cell that has no tile."""
        rows, width = len(band_lines) - 1, min(block, w - c0)
        q0, nq = c0 // CHUNK, -(-(width + 1) // CHUNK)
        phi = np.array([ln[0][q0:q0 + nq] for ln in band_lines], np.int64)
        off = np.array([ln[1][q0:q0 + nq] for ln in band_lines], np.int64)
        F = [ln[4] + ln[1][q0] for ln in band_lines]  # floor(j x) at the block's first column
        off -= off[:, :1]
        xt = np.array([ln[2] for ln in band_lines], np.int64)
        kinds = np.array([ln[3] for ln in band_lines], np.int64)
        zero = -(window.x0 + c0)  # the column of j = 0: floor(0 x) = 0 exactly, no rounding decides it
        size = (rows + 1) * (width + 1)
        if getattr(scratch, "G", np.empty(0)).size < size:  # one buffer a thread: no page faults a job
            scratch.G = np.empty(size, np.int32)
        G = scratch.G[:size].reshape(rows + 1, width + 1)
        where = np.empty(64, np.int64)
        n = kern.floors_kernel(phi, off, xt, bits, CHUNK, zero, G, where)
        if n > where.size:
            where = np.empty(n, np.int64)
            kern.floors_kernel(phi, off, xt, bits, CHUNK, zero, G, where)
        if 0 <= zero <= width:
            G[:, zero] = [-f for f in F]
        for k in where[:n].tolist():
            i, c = divmod(k, width + 1)
            j = window.x0 + c0 + c
            y = window.y0 + h - 1 - top - i
            G[i, c] = _decide(m, start, y, band_lines[i][5], lambda X: X.floor(j, 0))[0] - F[i]
        pr = np.array(m.steps, np.int64)[kinds[:-1]]
        code = 2 * kinds[:-1] + np.concatenate(([above], kinds[:-2]))
        s0 = np.array([p * F[i] - r * F[i + 1] - smin for i, (p, r) in enumerate(pr.tolist())], np.int64)
        return kern.tiles_kernel(G, s0, pr, code, lut, out[top:top + rows, c0:c0 + width])

    blocks = range(0, w, block)
    threads = min(_cores(), -(-h // band) * len(blocks)) if kern is not _k.KERNELS.plain() else 1
    with ThreadPoolExecutor(threads) as pool:
        jobs = []
        first = next(lines)
        for top in range(0, h, band):
            band_lines = [first] + [next(lines) for _ in range(min(band, h - top))]
            jobs += [pool.submit(run, top, c0, band_lines, above) for c0 in blocks]
            above, first = band_lines[-2][3], band_lines[-1]
        bad = sum(job.result() for job in jobs)
    if bad:
        raise InternalError(f"{name}: {bad} rows of window {window.describe()} have a cell with no tile (seed {seed})")
    return out if window.y_up else out[::-1].copy()


class _Lines:
    """The lines ``y, y - 1, ...`` of the orbit as the fast path reads them: per line
    ``(phi, off, xt, kind, F, X)`` with ``F = floor(j0 x)``, ``phi[q]`` and ``off[q]`` the
    fixed-point fraction ``floor(2**bits frac(j x))`` and ``floor(j x) - F`` at the start
    ``j = j0 + q CHUNK`` of column chunk ``q``, ``xt = floor(2**bits x)``, ``kind = x > 1``
    and ``X`` the line's :class:`_X`. Each is decided exactly (:func:`_decide`).
    """

    def __init__(self, m: Machine, start: tuple[int, int], y: int, j0: int, w: int, bits: int):
        self.m, self.start, self.y, self.bits = m, start, y, bits
        self.js = range(j0, j0 + w + 1, CHUNK)
        self.X = _row_bounds(m, start, y, PREC) or _sharpen(m, start, y, _X(0, 0, PREC))

    def __iter__(self):
        return self

    def __next__(self) -> tuple:
        bits = self.bits
        (kind, xt, Z), X = _decide(self.m, self.start, self.y, self.X, self._ask)
        F = Z[0] >> bits
        mask = (1 << bits) - 1
        line = ([z & mask for z in Z], [(z >> bits) - F for z in Z], xt, kind, F, X)
        self.X = X.step(*self.m.steps[kind])
        self.y -= 1
        return line

    def _ask(self, X: _X):
        kind, xt = X.kind(), X.floor(1, self.bits)
        Z = [X.floor(j, self.bits) for j in self.js]
        return None if kind is None or xt is None or None in Z else (kind, xt, Z)


