"""Dappled tiling problems (Kaji, Derouet-Jourdan, Ochiai, *Dappled tiling*, 2016).

Conventions
-----------
A tiling is a numpy array ``tiling[row, col]`` with row 0 at the top and tiles numbered
``0 .. n_tiles-1``. The paper writes ``f(i, j)`` with ``i`` horizontal, so its ``(i, j)``
is our ``[j, i]`` (``row = j``, ``col = i``).

A condition ``H_tau^p`` (paper Def. 1.1; subset form: future work 2) forbids a horizontal
run of more than ``p`` consecutive cells whose tiles all lie in ``tau``; ``V_tau^q`` is the
vertical analogue. ``p = None`` stands for the paper's ``p = infinity`` (never violated).
Per-cell ("non-uniform", §3.1) limits are arrays of shape ``(rows, cols)``: the limit at
``(r, c)`` applies to runs that *end* at ``(r, c)`` (the paper's "violates at (i, j)"),
going left for ``H`` and up for ``V``; an entry ``0`` means "no limit at this cell".

With ``cyclic=True`` runs wrap around both edges (the torus of §3.2).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Iterable

import numpy as np

from tilesolve.errors import InvalidProblem

__all__ = [
    "Condition",
    "TileCount",
    "DappledProblem",
    "parse_condition",
    "parse_count",
    "parse_size",
    "MAX_CELLS",
]

#: Largest grid any dappled route accepts (cells). A tiling of this size is 1 GiB of int8.
MAX_CELLS = 1 << 30

_COND_RE = re.compile(r"^\s*([HhVv])\s*(\{[\d,\s]*\}|\d+)\s*=\s*(\d+|inf|∞)\s*$")


@dataclass(frozen=True, eq=False)
class Condition:
    """One condition ``H_tau^p`` or ``V_tau^q``.

    Parameters
    ----------
    axis : {"H", "V"}
        ``"H"`` limits horizontal runs (along a row), ``"V"`` vertical runs.
    tiles : tuple of int
        The subset ``tau``; a single tile ``t`` gives the paper's ``H_t^p``.
    limit : int, None or numpy.ndarray
        The longest allowed run (``p >= 1``); ``None`` is infinity; an array gives a
        per-cell limit (0 = unlimited at that cell), as in §3.1.

    Examples
    --------
    >>> parse_condition("H0=2")
    Condition('H0=2')
    >>> str(Condition("V", (0, 2), 3))
    'V{0,2}=3'
    """

    axis: str
    tiles: tuple[int, ...]
    limit: int | None | np.ndarray

    def __post_init__(self) -> None:
        axis = str(self.axis).upper()
        if axis not in ("H", "V"):
            raise InvalidProblem(f"condition axis must be 'H' or 'V', got {self.axis!r}")
        object.__setattr__(self, "axis", axis)
        tiles = tuple(sorted({int(t) for t in self.tiles}))
        if not tiles:
            raise InvalidProblem("a condition needs at least one tile")
        object.__setattr__(self, "tiles", tiles)
        limit = self.limit
        if isinstance(limit, np.ndarray):
            if limit.ndim != 2 or not np.issubdtype(limit.dtype, np.integer):
                raise InvalidProblem("a per-cell condition limit must be a 2-D integer array")
            if (limit < 0).any():
                raise InvalidProblem("per-cell condition limits must be >= 0 (0 = unlimited)")
            limit = np.ascontiguousarray(limit, dtype=np.int32)
            limit.setflags(write=False)
        elif limit is not None:
            if isinstance(limit, float) and math.isinf(limit):
                limit = None
            else:
                if int(limit) != limit or int(limit) < 1:
                    raise InvalidProblem(f"condition limit must be an integer >= 1, got {limit!r}")
                limit = int(limit)
        object.__setattr__(self, "limit", limit)

    @property
    def is_uniform(self) -> bool:
        return not isinstance(self.limit, np.ndarray)

    @property
    def is_single_tile(self) -> bool:
        return len(self.tiles) == 1

    def limit_array(self, rows: int, cols: int) -> np.ndarray:
        """The limit as an int32 ``(rows, cols)`` array, 0 meaning unlimited."""
        if isinstance(self.limit, np.ndarray):
            return self.limit
        return np.full((rows, cols), 0 if self.limit is None else self.limit, dtype=np.int32)

    def max_limit(self) -> int | None:
        """Largest finite limit (None when the condition never bites)."""
        if isinstance(self.limit, np.ndarray):
            finite = self.limit[self.limit > 0]
            return int(finite.max()) if finite.size else None
        return self.limit

    def __str__(self) -> str:
        tiles = str(self.tiles[0]) if len(self.tiles) == 1 else "{" + ",".join(map(str, self.tiles)) + "}"
        if isinstance(self.limit, np.ndarray):
            lim = "per-cell"
        else:
            lim = "inf" if self.limit is None else str(self.limit)
        return f"{self.axis}{tiles}={lim}"

    def __repr__(self) -> str:
        return f"Condition({str(self)!r})"

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Condition):
            return NotImplemented
        if (self.axis, self.tiles) != (other.axis, other.tiles):
            return False
        a, b = self.limit, other.limit
        if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
            return isinstance(a, np.ndarray) and isinstance(b, np.ndarray) and np.array_equal(a, b)
        return a == b

    __hash__ = None  # type: ignore[assignment]


def parse_condition(text: str) -> Condition:
    """Parse ``"H0=2"``, ``"V1=3"``, ``"H{0,2}=3"`` or ``"V1=inf"`` into a :class:`Condition`.

    Raises
    ------
    InvalidProblem
        On any other syntax.
    """
    m = _COND_RE.match(text)
    if not m:
        raise InvalidProblem(
            f"cannot read condition {text!r}: expected e.g. H0=2 (no horizontal run of tile 0 "
            "longer than 2), V1=3, H{0,2}=3 for a subset of tiles, or V1=inf"
        )
    axis, tiles, lim = m.groups()
    tile_list = [int(t) for t in tiles.strip("{}").split(",") if t.strip()]
    limit = None if lim in ("inf", "∞") else int(lim)
    return Condition(axis, tuple(tile_list), limit)


@dataclass(frozen=True)
class TileCount:
    """A global constraint (future work 6): ``low <= #{cells with tile} <= high``.

    ``high=None`` means no upper bound.
    """

    tile: int
    low: int = 0
    high: int | None = None

    def __post_init__(self) -> None:
        if self.low < 0 or (self.high is not None and self.high < self.low):
            raise InvalidProblem(f"tile count bounds for tile {self.tile} are empty: {self.low}..{self.high}")

    def __str__(self) -> str:
        if self.high == self.low:
            return f"{self.tile}={self.low}"
        return f"{self.tile}={self.low}..{'' if self.high is None else self.high}"


_COUNT_RE = re.compile(r"^\s*(\d+)\s*=\s*(\d*)\s*(\.\.\s*(\d*))?\s*$")


def parse_count(text: str) -> TileCount:
    """Parse ``"1=8"`` (exactly 8 cells of tile 1), ``"1=4..10"``, ``"1=..10"`` or ``"1=4.."``."""
    m = _COUNT_RE.match(text)
    if not m or (m.group(2) == "" and m.group(3) is None):
        raise InvalidProblem(
            f"cannot read count {text!r}: expected TILE=N (exactly N), TILE=LO..HI, TILE=..HI or TILE=LO.."
        )
    tile, low, dots, high = m.groups()
    lo = int(low) if low else 0
    if dots is None:
        return TileCount(int(tile), lo, lo)
    return TileCount(int(tile), lo, int(high) if high else None)


def parse_size(text: str) -> tuple[int, int]:
    """Parse ``"WxH"`` (W columns, H rows) and return ``(rows, cols)``."""
    m = re.match(r"^\s*(-?\d+)\s*[xX×]\s*(-?\d+)\s*$", str(text))
    if not m:
        raise InvalidProblem(f"cannot read size {text!r}: expected WxH, e.g. 64x48 (64 columns, 48 rows)")
    w, h = int(m.group(1)), int(m.group(2))
    _check_shape(h, w)
    return h, w


def _check_shape(rows: int, cols: int) -> None:
    if rows <= 0 or cols <= 0:
        raise InvalidProblem(f"grid size must be positive, got {cols}x{rows} (WxH)")
    cells = rows * cols
    if cells > MAX_CELLS:
        raise InvalidProblem(
            f"grid {cols}x{rows} has {cells:,} cells; tilesolve refuses more than {MAX_CELLS:,} "
            f"(the tiling alone would need {cells / 2**30:.1f} GiB)"
        )


@dataclass(frozen=True, eq=False)
class DappledProblem:
    """An L-dappled tiling question on an ``rows x cols`` grid.

    Parameters
    ----------
    rows, cols : int
        Grid shape (the paper's ``G_{m,n}`` has ``m = cols``, ``n = rows``).
    n_tiles : int
        ``|T| >= 2``; tiles are ``0 .. n_tiles-1``.
    conditions : sequence of Condition
        The set ``L``.
    cyclic : bool
        Runs wrap around both edges (§3.2).
    fixed : numpy.ndarray, optional
        Partial tiling (future work 7): ``fixed[r, c] = t`` pins tile ``t``, ``-1`` is free.
    counts : sequence of TileCount
        Global tile counts (future work 6).
    closest_to : numpy.ndarray, optional
        Ask for a dappled tiling at minimum Hamming distance from this one (future work 3).

    Examples
    --------
    >>> p = DappledProblem(4, 6, conditions=[parse_condition("H0=2"), parse_condition("V1=2")])
    >>> p.shape, [str(c) for c in p.conditions]
    ((4, 6), ['H0=2', 'V1=2'])
    """

    rows: int
    cols: int
    n_tiles: int = 2
    conditions: tuple[Condition, ...] = ()
    cyclic: bool = False
    fixed: np.ndarray | None = None
    counts: tuple[TileCount, ...] = ()
    closest_to: np.ndarray | None = None

    def __post_init__(self) -> None:
        rows, cols = int(self.rows), int(self.cols)
        _check_shape(rows, cols)
        object.__setattr__(self, "rows", rows)
        object.__setattr__(self, "cols", cols)
        if int(self.n_tiles) < 2:
            raise InvalidProblem(f"a tile set needs at least 2 tiles (|T| >= 2), got {self.n_tiles}")
        if int(self.n_tiles) > 127:
            raise InvalidProblem(f"at most 127 tile kinds are supported, got {self.n_tiles}")
        object.__setattr__(self, "n_tiles", int(self.n_tiles))
        conds = tuple(self.conditions)
        for c in conds:
            if not isinstance(c, Condition):
                raise InvalidProblem(f"expected a Condition, got {c!r}")
            bad = [t for t in c.tiles if not 0 <= t < self.n_tiles]
            if bad:
                raise InvalidProblem(f"condition {c} names tile {bad[0]}, but tiles are 0..{self.n_tiles - 1}")
            if not c.is_uniform and c.limit.shape != (rows, cols):
                raise InvalidProblem(
                    f"per-cell limits of {c.axis}{list(c.tiles)} have shape {c.limit.shape}, grid is {(rows, cols)}"
                )
        object.__setattr__(self, "conditions", conds)
        object.__setattr__(self, "fixed", self._grid_arg(self.fixed, "partial tiling", allow_free=True))
        object.__setattr__(self, "closest_to", self._grid_arg(self.closest_to, "target tiling", allow_free=False))
        counts = tuple(self.counts)
        for k in counts:
            if not 0 <= k.tile < self.n_tiles:
                raise InvalidProblem(f"count constraint names tile {k.tile}, but tiles are 0..{self.n_tiles - 1}")
            if k.low > rows * cols:
                raise InvalidProblem(f"count {k} asks for more cells than the {rows * cols} the grid has")
        object.__setattr__(self, "counts", counts)

    def _grid_arg(self, arr, what: str, allow_free: bool) -> np.ndarray | None:
        if arr is None:
            return None
        a = np.asarray(arr)
        if a.shape != (self.rows, self.cols):
            raise InvalidProblem(
                f"{what} is {a.shape[1] if a.ndim == 2 else '?'}x{a.shape[0] if a.ndim else '?'} (WxH), "
                f"but the grid is {self.cols}x{self.rows}"
            )
        if not np.issubdtype(a.dtype, np.integer):
            raise InvalidProblem(f"{what} must hold integer tile numbers")
        lo = -1 if allow_free else 0
        bad = (a < lo) | (a >= self.n_tiles)
        if bad.any():
            r, c = map(int, np.argwhere(bad)[0])
            raise InvalidProblem(
                f"{what} names tile {int(a[r, c])} at row {r}, col {c}; tiles are 0..{self.n_tiles - 1}"
                + (" (-1 = free)" if allow_free else "")
            )
        out = np.array(a, dtype=np.int8)
        out.setflags(write=False)
        return out

    # ------------------------------------------------------------------ helpers
    @property
    def shape(self) -> tuple[int, int]:
        return (self.rows, self.cols)

    @property
    def size(self) -> int:
        return self.rows * self.cols

    @property
    def is_uniform(self) -> bool:
        """True when no condition has per-cell limits."""
        return all(c.is_uniform for c in self.conditions)

    @property
    def is_plain(self) -> bool:
        """True when the problem is just ``L`` on a grid: no fixed cells, counts or target."""
        return self.fixed is None and not self.counts and self.closest_to is None

    def single_tile_limits(self) -> tuple[np.ndarray, np.ndarray] | None:
        """``(p, q)`` as int32 arrays of shape ``(n_tiles, rows, cols)`` (0 = unlimited).

        Several conditions on the same tile and axis combine to the tightest limit.
        Returns ``None`` when some condition names a subset of two or more tiles, which
        the paper's algorithms do not cover.
        """
        if any(not c.is_single_tile for c in self.conditions):
            return None
        big = np.iinfo(np.int32).max
        lim = {ax: np.full((self.n_tiles, self.rows, self.cols), big, dtype=np.int32) for ax in "HV"}
        for c in self.conditions:
            arr = c.limit_array(self.rows, self.cols)
            arr = np.where(arr == 0, big, arr)
            t = c.tiles[0]
            np.minimum(lim[c.axis][t], arr, out=lim[c.axis][t])
        for a in lim.values():
            a[a == big] = 0
        return lim["H"], lim["V"]

    def describe(self) -> str:
        conds = ", ".join(str(c) for c in self.conditions) or "no conditions"
        extra = []
        if self.cyclic:
            extra.append("cyclic")
        if self.fixed is not None:
            extra.append(f"{int((self.fixed >= 0).sum())} fixed cells")
        if self.counts:
            extra.append("counts " + ", ".join(map(str, self.counts)))
        if self.closest_to is not None:
            extra.append("closest to a target")
        tail = f" ({'; '.join(extra)})" if extra else ""
        return f"{self.cols}x{self.rows} grid, |T|={self.n_tiles}, L={{{conds}}}{tail}"

    @classmethod
    def from_strings(
        cls,
        size: str,
        conditions: Iterable[str],
        *,
        n_tiles: int = 2,
        cyclic: bool = False,
        counts: Iterable[str] = (),
        fixed: np.ndarray | None = None,
        closest_to: np.ndarray | None = None,
    ) -> "DappledProblem":
        """Build a problem from CLI-style strings.

        >>> DappledProblem.from_strings("6x4", ["H0=2", "V1=2"]).describe()
        '6x4 grid, |T|=2, L={H0=2, V1=2}'
        """
        rows, cols = parse_size(size)
        return cls(
            rows,
            cols,
            n_tiles=n_tiles,
            conditions=tuple(parse_condition(c) for c in conditions),
            cyclic=cyclic,
            counts=tuple(parse_count(k) for k in counts),
            fixed=fixed,
            closest_to=closest_to,
        )
