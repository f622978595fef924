"""Hash functions over the integer lattice (class notes §3.4; procedural walls 004 §4.2).

Every hash here comes in two forms that agree bit for bit: ``h(x, y)`` on numpy integer
arrays (any shape, broadcast; negative coordinates welcome) and ``h.scalar(x, y)`` on Python
ints, a line-by-line transcription that a GPU or C port can follow. ``%`` is the floor
modulo of Python and numpy (``-1 % 5 == 4``), which the notes' "modulo division" must mean
for the hashes to be defined on the whole lattice.

* :class:`PermutationHash`: eq. 3.1 ``P[x % N]``, eq. 3.3 ``P[(P[x % N] + y) % N]``,
  eq. 3.4 for three coordinates. Period ``N`` in each coordinate, range ``N``.
* :class:`LongPeriodHash`: eq. 3.5-3.7, the sum of ``M`` such hashes with tables of coprime
  sizes ``N_i``, reduced modulo one of the sizes ``N_j``. Period ``lcm(N_i)``, range ``N_j``.
  :func:`tiling_hash` is the design of §3.4.3 (tables 17, 19, 23, 24, 29, 31, 37, range 24,
  period 5,930,659,848); :func:`perlin_hash` the one of §3.4.4 (11, 13, 16, 17, 19).
* :class:`FnvXorshift`: the hash of the procedural walls (004 §4.2: "a FNV hash scheme ...
  to seed a xorshift random number generator from which we peek a value").

Tables are drawn from a seed, so the same seed gives the same hash; the tables themselves
(:attr:`PermutationHash.table`, :attr:`LongPeriodHash.tables`) are what a port needs. On a
grid of points, ``outer(xs, ys)`` evaluates the table hashes in compiled code, and
``row_tables`` hands the same tables to the compiled tilings (:mod:`._lattice_kernels`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from tilesolve._random import rng_from_seed
from tilesolve.constructive._lattice_kernels import (
    FNV_PRIME,
    XORSHIFT_STAR,
    fnv_xorshift_u64,
    outer_rows,
)
from tilesolve.errors import InvalidProblem

__all__ = [
    "MAX_WINDOW_CELLS",
    "LATTICE_BOUND",
    "check_int",
    "check_window",
    "permutation_table",
    "PermutationHash",
    "LongPeriodHash",
    "tiling_hash",
    "perlin_hash",
    "FnvXorshift",
    "fnv_xorshift_u64",
    "FNV_OFFSET",
    "FNV_PRIME",
    "MASK64",
    "XORSHIFT_STAR",
]

#: Largest window (cells) the lattice generators (stochastic tilings, procedural walls) build at once.
MAX_WINDOW_CELLS = 1 << 28
#: Coordinates addressed by the hashes stay below this in absolute value (lattice points up to
#: ``x0 + w + 1``, and twice that for the edge hash, must fit in 64 bits).
LATTICE_BOUND = (1 << 62) - 8


def check_int(v, name: str, lo: int | None = None) -> int:
    """``v`` as an int (numpy integers too), at least ``lo``; one-line errors otherwise."""
    if isinstance(v, bool) or not isinstance(v, (int, np.integer)):
        raise InvalidProblem(f"{name} must be an integer, got {v!r}")
    v = int(v)
    if lo is not None and v < lo:
        raise InvalidProblem(f"{name} must be >= {lo}, got {v}")
    return v


def check_window(x0, y0, w, h, *, what: str = "window") -> tuple[int, int, int, int]:
    """``(x0, y0, w, h)`` of a window ``[x0, x0 + w) x [y0, y0 + h)`` of the infinite lattice,
    checked: integers, positive sizes, inside :data:`LATTICE_BOUND`, at most
    :data:`MAX_WINDOW_CELLS` cells (the message gives the memory it would need)."""
    x0, y0 = check_int(x0, "x0"), check_int(y0, "y0")
    w, h = check_int(w, "width", 1), check_int(h, "height", 1)
    b = LATTICE_BOUND
    if not (-b <= x0 and x0 + w <= b and -b <= y0 and y0 + h <= b):
        raise InvalidProblem(f"{what} [{x0}, {x0 + w}) x [{y0}, {y0 + h}) leaves the 63-bit lattice the hashes address "
                             "(|coordinates| < 2**62)")
    if w * h > MAX_WINDOW_CELLS:
        raise InvalidProblem(f"a {what} of {w} x {h} = {w * h:,} cells needs about {w * h * 4 / 2**30:.1f} GiB; "
                             f"tilesolve builds at most {MAX_WINDOW_CELLS:,} cells at once: ask for smaller windows")
    return x0, y0, w, h

#: FNV-1a 64-bit offset basis (Fowler, Noll, Vo); the prime is ``FNV_PRIME``.
FNV_OFFSET = 0xCBF29CE484222325
MASK64 = (1 << 64) - 1
_MASK32 = (1 << 32) - 1


def _as_int64(a) -> np.ndarray:
    a = np.asarray(a)
    if a.dtype.kind not in "iu":
        raise InvalidProblem(f"lattice coordinates must be integers, got {a.dtype}")
    if a.dtype == np.uint64 and a.size and int(a.max()) > np.iinfo(np.int64).max:
        raise InvalidProblem("lattice coordinates must fit in 64-bit signed integers")
    return a.astype(np.int64, copy=False)


def _check_scalar(v) -> int:
    if isinstance(v, bool) or not isinstance(v, (int, np.integer)):
        raise InvalidProblem(f"lattice coordinates must be integers, got {v!r}")
    v = int(v)
    if not -(1 << 63) <= v < (1 << 63):
        raise InvalidProblem(f"lattice coordinate {v} does not fit in 64 bits")
    return v


def permutation_table(size: int, seed=None) -> np.ndarray:
    """A random permutation of ``0 .. size-1`` (§3.4.1), drawn from ``seed``."""
    if isinstance(size, bool) or not isinstance(size, (int, np.integer)) or size < 1:
        raise InvalidProblem(f"a permutation table needs a positive integer size, got {size!r}")
    return rng_from_seed(seed).permutation(int(size)).astype(np.int64)


@dataclass(frozen=True, eq=False)
class PermutationHash:
    """The traditional hash of one permutation table ``P`` of size ``N`` (§3.4.1, eq. 3.1-3.4).

    ``h(x) = P[x % N]``, ``h(x, y) = P[(P[x % N] + y) % N]`` and
    ``h(x, y, z) = P[(P[(P[x % N] + y) % N] + z) % N]``. Each step adds the next coordinate
    reduced ``% N`` first (the same value, and no overflow near ``±2**63``).

    Examples
    --------
    >>> h = PermutationHash(np.array([2, 0, 3, 1]))
    >>> int(h(5)), h.scalar(5), int(h(-3, 7)), h.scalar(-3, 7)   # P[1]; P[(P[1] + 7) % 4] = P[3]
    (0, 0, 1, 1)
    >>> h.period, h.range
    (4, 4)
    """

    table: np.ndarray

    def __post_init__(self) -> None:
        t = np.asarray(self.table, dtype=np.int64).reshape(-1)
        if not np.array_equal(np.sort(t), np.arange(t.size)):
            raise InvalidProblem("a permutation table must hold 0 .. N-1 once each")
        t.setflags(write=False)
        object.__setattr__(self, "table", t)

    @classmethod
    def from_seed(cls, size: int = 256, seed=None) -> "PermutationHash":
        """A hash with a random table of ``size`` entries (256 is the common size, §3.4.3)."""
        return cls(permutation_table(size, seed))

    @property
    def size(self) -> int:
        return int(self.table.size)

    @property
    def period(self) -> int:
        return self.size

    @property
    def range(self) -> int:
        return self.size

    def __call__(self, *coords) -> np.ndarray:
        if not 1 <= len(coords) <= 3:
            raise InvalidProblem("permutation hashes take 1, 2 or 3 coordinates (eq. 3.1-3.4)")
        n, p = self.size, self.table
        out = p[_as_int64(coords[0]) % n]
        for c in coords[1:]:
            out = p[(out + _as_int64(c) % n) % n]
        return out

    def outer(self, xs, ys, modulus: int | None = None) -> np.ndarray:
        """``h(x, y)`` for every ``y`` of ``ys`` (rows) and ``x`` of ``xs`` (columns), int32.

        Equal to ``self(xs[None, :], ys[:, None])`` (``% modulus`` when given). Eq. 3.3 is
        separable: ``P[x % N]`` is looked up once per column, ``y % N`` once per row, and the
        last ``% N`` becomes an index into the table written twice.
        """
        return _outer((self,), xs, ys, self.range, modulus)

    def row_tables(self, xs, modulus: int | None = None):
        """The tables that evaluate this hash a row at a time over the columns ``xs`` (compiled code)."""
        return _row_tables((self,), xs, self.range, modulus)

    def scalar(self, *coords) -> int:
        if not 1 <= len(coords) <= 3:
            raise InvalidProblem("permutation hashes take 1, 2 or 3 coordinates (eq. 3.1-3.4)")
        n = self.size
        out = int(self.table[_check_scalar(coords[0]) % n])
        for c in coords[1:]:
            out = int(self.table[(out + _check_scalar(c) % n) % n])
        return out


@dataclass(frozen=True, eq=False)
class LongPeriodHash:
    """A combined hash of several permutation tables (§3.4.2, eq. 3.5-3.7).

    ``h(x, y) = (sum_i P_i[(P_i[x % N_i] + y) % N_i]) % N_j`` (and likewise for one or three
    coordinates), where ``N_j`` is the size of table ``range_table``. Eq. 3.7 is garbled in
    the extraction (``N_i[x % N_i]``); it is read as the three-coordinate form of eq. 3.4
    inside the sum, the only reading consistent with eq. 3.5 and 3.6.

    The period is the least common multiple of the sizes (the product when they are
    pairwise coprime), the range is ``N_j``; the value is uniform on ``0 .. N_j - 1`` because
    table ``j`` is (Wichmann-Hill / L'Ecuyer, eq. 3.8).

    Examples
    --------
    >>> h = LongPeriodHash.from_sizes((3, 4), range_table=1, seed=0)
    >>> h.period, h.range
    (12, 4)
    >>> bool((h(np.arange(24), 5)[:12] == h(np.arange(12, 24), 5)).all())   # period 12 in x
    True
    """

    tables: tuple[np.ndarray, ...]
    range_table: int = 0
    _parts: tuple[PermutationHash, ...] = field(init=False, repr=False)

    def __post_init__(self) -> None:
        parts = tuple(PermutationHash(t) for t in self.tables)
        if not parts:
            raise InvalidProblem("a long-period hash needs at least one permutation table")
        if not 0 <= int(self.range_table) < len(parts):
            raise InvalidProblem(f"range_table must name one of the {len(parts)} tables, got {self.range_table}")
        object.__setattr__(self, "_parts", parts)
        object.__setattr__(self, "tables", tuple(p.table for p in parts))
        object.__setattr__(self, "range_table", int(self.range_table))

    @classmethod
    def from_sizes(cls, sizes, *, range_table: int = 0, seed=None) -> "LongPeriodHash":
        """Random tables of the given ``sizes``, all drawn from one ``seed``."""
        rng = rng_from_seed(seed)
        return cls(tuple(permutation_table(int(s), rng) for s in sizes), range_table)

    @property
    def sizes(self) -> tuple[int, ...]:
        return tuple(p.size for p in self._parts)

    @property
    def period(self) -> int:
        return math.lcm(*self.sizes)

    @property
    def range(self) -> int:
        return self.sizes[self.range_table]

    def __call__(self, *coords) -> np.ndarray:
        cs = [_as_int64(c) for c in coords]
        total = sum(p(*cs) for p in self._parts)
        return total % self.range

    def outer(self, xs, ys, modulus: int | None = None) -> np.ndarray:
        """``h(x, y)`` on the grid ``ys x xs``, int32 (see :meth:`PermutationHash.outer`)."""
        return _outer(self._parts, xs, ys, self.range, modulus)

    def row_tables(self, xs, modulus: int | None = None):
        """The tables that evaluate this hash a row at a time over the columns ``xs`` (compiled code)."""
        return _row_tables(self._parts, xs, self.range, modulus)

    def scalar(self, *coords) -> int:
        return sum(p.scalar(*coords) for p in self._parts) % self.range


def _row_tables(parts, xs, rng: int, modulus: int | None):
    """``(twice, sizes, px, red)`` for :mod:`._lattice_kernels` (see its docstring)."""
    xs = _as_int64(xs).reshape(-1)
    m, big = len(parts), 2 * max(p.size for p in parts)
    twice = np.zeros((m, big), dtype=np.int32)
    px = np.empty((m, xs.size), dtype=np.int32)
    for i, p in enumerate(parts):
        twice[i, : 2 * p.size] = np.concatenate([p.table, p.table])
        px[i] = p.table[xs % p.size]
    sizes = np.array([p.size for p in parts], dtype=np.int64)
    red = (np.arange(int(sizes.sum()), dtype=np.int64) % rng) % (rng if modulus is None else int(modulus))
    return twice, sizes, px, red.astype(np.int32)


def _outer(parts, xs, ys, rng: int, modulus: int | None) -> np.ndarray:
    """Evaluate the 2-D hash of the tables ``parts`` on the grid ``ys x xs`` (compiled loop)."""
    return outer_rows(*_row_tables(parts, xs, rng, modulus), _as_int64(ys).reshape(-1))


def _primes_around(r: int, below: int, above: int) -> list[int]:
    """``below`` primes under ``r`` and ``above`` primes over it, skipping divisors of ``r``."""
    def is_prime(n: int) -> bool:
        return n >= 2 and all(n % d for d in range(2, math.isqrt(n) + 1))

    lo, hi, out_lo, out_hi = r - 1, r + 1, [], []
    while len(out_lo) < below and lo >= 2:
        if is_prime(lo) and r % lo:
            out_lo.append(lo)
        lo -= 1
    while len(out_hi) < above:
        if is_prime(hi) and r % hi:
            out_hi.append(hi)
        hi += 1
    return sorted(out_lo + out_hi)


def tiling_hash(colors: int = 24, *, seed=None) -> LongPeriodHash:
    """The long-period hash for direct stochastic tilings (§3.4.3), with a range divisible by ``colors``.

    The notes fix the range at 24 (the lcm of the usual 2, 3, 4, 6, 8 colours) and add
    tables of the primes 17, 19, 23 and 29, 31, 37: period
    ``17 * 19 * 23 * 24 * 29 * 31 * 37 = 5,930,659,848``, 180 table entries. For ``colors``
    that do not divide 24 the range table becomes the smallest multiple of ``colors`` that is
    at least 24 (§3.4.2.4: "use a multiple of the range"), with the three primes below and
    the three above it that do not divide it; ``h % colors`` is then uniform.

    Examples
    --------
    >>> h = tiling_hash(seed=1)
    >>> h.sizes, h.range, f"{h.period:,}"
    ((17, 19, 23, 24, 29, 31, 37), 24, '5,930,659,848')
    >>> tiling_hash(5, seed=1).sizes
    (17, 19, 23, 25, 29, 31, 37)
    """
    if isinstance(colors, bool) or not isinstance(colors, (int, np.integer)) or colors < 1:
        raise InvalidProblem(f"colors must be a positive integer, got {colors!r}")
    r = 24 if 24 % colors == 0 else colors * -(-24 // colors)
    sizes = sorted(_primes_around(r, 3, 3) + [r])
    return LongPeriodHash.from_sizes(sizes, range_table=sizes.index(r), seed=seed)


def perlin_hash(*, seed=None) -> LongPeriodHash:
    """The long-period hash for Perlin noise (§3.4.4): tables 11, 13, 16, 17, 19, range 16, period 739,024."""
    return LongPeriodHash.from_sizes((11, 13, 16, 17, 19), range_table=2, seed=seed)


# --------------------------------------------------------------------------- FNV + xorshift
@dataclass(frozen=True)
class FnvXorshift:
    """The hash of the procedural walls (004 §4.2): FNV-1a seeds xorshift64*, one value is peeked.

    The paper names the scheme and nothing more. tilesolve's reading: FNV-1a (64-bit) over
    the 32-bit words of ``seed`` (low, high), ``stream`` and then ``x`` (low, high) and ``y``
    (low, high), the words treated as FNV's "octets"; the result seeds xorshift64*, whose
    first output is the hash (see :func:`fnv_xorshift_u64`, in ``_lattice_kernels`` with the
    compiled code that inlines it). ``stream`` separates independent hashes of one seed (the
    paper's ``ℋ`` and ``𝒱``). The *value* of the hash is its high 32 bits
    ``u`` (FNV's low bits mix poorly: bit 0 of FNV-1a is the parity of the inputs' bit 0), and
    :meth:`colour` reduces it to ``0 .. k-1`` as ``(u * k) >> 32``, the division-free range
    reduction (Lemire) that stands for the paper's ``ℋ(i, j) % k``: each colour gets
    ``floor(2**32 / k)`` or ``ceil(2**32 / k)`` of the values, as with ``%``.

    Examples
    --------
    >>> h = FnvXorshift(seed=7, stream=1)
    >>> int(h(np.int64(-5), np.int64(3))) == h.scalar(-5, 3)
    True
    """

    seed: int = 0
    stream: int = 0

    def __post_init__(self) -> None:
        for name in ("seed", "stream"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or not 0 <= v < (1 << 64):
                raise InvalidProblem(f"{name} must be an integer in 0 .. 2**64-1, got {v!r}")

    @property
    def basis(self) -> int:
        """FNV-1a state after the words ``seed`` (low, high) and ``stream`` (low 32 bits)."""
        h = FNV_OFFSET
        for w in (self.seed & _MASK32, self.seed >> 32, self.stream & _MASK32):
            h = ((h ^ w) * FNV_PRIME) & MASK64
        return h

    def __call__(self, x, y) -> np.ndarray:
        """``uint64`` hash of each lattice point (arrays broadcast)."""
        xu = _as_int64(x).view(np.uint64) if np.ndim(x) else np.int64(_as_int64(x)).view(np.uint64)
        yu = _as_int64(y).view(np.uint64) if np.ndim(y) else np.int64(_as_int64(y)).view(np.uint64)
        with np.errstate(over="ignore"):
            return fnv_xorshift_u64(np.uint64(self.basis), xu, yu)

    def scalar(self, x, y) -> int:
        x, y = _check_scalar(x) & MASK64, _check_scalar(y) & MASK64
        h = self.basis
        for w in (x & _MASK32, x >> 32, y & _MASK32, y >> 32):
            h = ((h ^ w) * FNV_PRIME) & MASK64
        h ^= h >> 12
        h ^= (h << 25) & MASK64
        h ^= h >> 27
        return (h * XORSHIFT_STAR) & MASK64

    def colour(self, x, y, k: int) -> np.ndarray:
        """``((hash >> 32) * k) >> 32`` as int64: a pseudo-random colour in ``0 .. k-1`` (``k < 2**31``)."""
        return (((self(x, y) >> np.uint64(32)) * np.uint64(k)) >> np.uint64(32)).astype(np.int64)

    def colour_scalar(self, x, y, k: int) -> int:
        return ((self.scalar(x, y) >> 32) * k) >> 32
