"""SAT, MaxSAT and CP-SAT encodings of dappled tiling problems.

The dappled paper (Kaji, Derouet-Jourdan, Ochiai 2016) asks in §6 item 8 for an
"interpretation as a SAT problem"; this module is that formalisation, for every variant
:class:`~tilesolve.model.dappled.DappledProblem` can state: conditions ``H_tau^p`` /
``V_tau^q`` on single tiles or subsets (§6 item 2), uniform or per-cell limits (§3.1),
plain or cyclic grids (§3.2), partial tilings (§6 item 7), global counts (§6 item 6) and
the closest tiling as a weighted MaxSAT problem (§6 item 3).

Variables
---------
``|T| = 2``
    one variable ``x[r, c]`` per cell, true iff the cell holds tile 1 (variable
    ``1 + r * cols + c``).
``|T| >= 3``
    one-hot variables ``y[r, c, t]``, true iff cell ``(r, c)`` holds tile ``t`` (variable
    ``1 + (r * cols + c) * |T| + t``), with an exactly-one constraint per cell.

Grid variables are numbered by arithmetic, not through :class:`pysat.formula.IDPool`,
because the clauses are generated as numpy arrays (a 1024x1024 grid has a million cells;
an ``IDPool`` call per cell alone costs about a second). Auxiliary variables of the
cardinality encodings come from an ``IDPool`` that starts after the grid block, and
:meth:`DappledEncoding.describe_var` names every variable.

Clauses
-------
A condition ``H_tau^p`` is violated at ``(r, c)`` when the ``p + 1`` cells
``(r, c-p) .. (r, c)`` all hold tiles of ``tau`` (Def. 1.1). The encoding forbids each such
window with one clause "some cell of the window holds a tile outside ``tau``"::

    OR_{k=0..p} OR_{t not in tau} [cell (r, c-k) holds t]

which for ``|T| = 2`` is a clause of ``p + 1`` literals and needs no auxiliary variables.
Per-cell limits give each window its own length; with ``cyclic=True`` column indices wrap,
and a window at least as long as the row is the whole row ("not every cell of the row is
in ``tau``"), which matches the torus semantics of §3.2.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, field
from typing import Any, Iterable, Iterator, Sequence

import numpy as np
from pysat.card import EncType
from pysat.formula import CNF, WCNF, IDPool

from tilesolve.deadline import Deadline, TimeLimitReached
from tilesolve.encodings import ClauseSet, cardinality
from tilesolve.errors import InvalidProblem
from tilesolve.model.dappled import Condition, DappledProblem

__all__ = [
    "CardEncoding",
    "DappledEncoding",
    "encode_cnf",
    "encode_wcnf",
    "naive_clauses",
    "card_clauses",
    "CpSatDappled",
    "build_cpsat",
]


class CardEncoding(str, enum.Enum):
    """Cardinality encodings offered for global counts (names of :class:`pysat.card.EncType`).

    ``AUTO`` picks a sequential counter for small products ``cells * bound`` and a
    cardinality network (``O(n log^2 n)`` clauses) otherwise.
    """

    AUTO = "auto"
    SEQCOUNTER = "seqcounter"
    SORTNETWRK = "sortnetwrk"
    CARDNETWRK = "cardnetwrk"
    TOTALIZER = "totalizer"
    MTOTALIZER = "mtotalizer"
    KMTOTALIZER = "kmtotalizer"

    def enctype(self, n: int, bound: int) -> int:
        if self is CardEncoding.AUTO:
            return EncType.seqcounter if n * max(1, bound) <= 50_000 else EncType.cardnetwrk
        return getattr(EncType, self.value)


#: One-hot cells use pairwise at-most-one up to this many tiles, a sequential counter above.
PAIRWISE_AMO_MAX = 6


@dataclass
class DappledEncoding:
    """Clauses of a dappled problem plus the map between models and tilings.

    Attributes
    ----------
    problem : DappledProblem
    hard : ClauseSet
        The clauses every tiling must satisfy.
    n_vars : int
        Largest variable number in use (grid and auxiliary).
    n_grid_vars : int
        Grid variables are ``1 .. n_grid_vars``.
    one_hot : bool
        ``True`` for ``|T| >= 3``.
    soft : numpy.ndarray or None
        For :func:`encode_wcnf`: one literal per soft unit clause (weight 1 each), true
        when a cell keeps its target tile. ``None`` for a plain CNF encoding.
    pool : pysat.formula.IDPool
        Pool of the auxiliary variables of the cardinality encodings (it starts after
        the grid block).
    aux_ranges : list of (int, int, str)
        Auxiliary variable ranges and what they encode (:meth:`describe_var`, DIMACS header).

    Examples
    --------
    >>> from tilesolve.model import DappledProblem
    >>> enc = encode_cnf(DappledProblem.from_strings("3x1", ["H0=2"]))
    >>> list(enc.hard)
    [[1, 2, 3]]
    >>> enc.decode([-1, 2, -3]).tolist()
    [[0, 1, 0]]
    >>> enc.literals([[1, 0, 0]])
    [1, -2, -3]
    """

    problem: DappledProblem
    hard: ClauseSet
    n_vars: int
    n_grid_vars: int
    one_hot: bool
    soft: np.ndarray | None = None
    pool: IDPool | None = None
    aux_ranges: list = field(default_factory=list)

    #: The formula is the whole problem: an unsat answer is a refutation.
    restricted = False

    # ------------------------------------------------------------------ literals
    def grid_vars(self) -> np.ndarray:
        """Variable numbers, shape ``(rows, cols)`` (``|T| = 2``) or ``(rows, cols, |T|)``."""
        return _grid_vars(self.problem)

    def tile_literals(self, tile: int) -> np.ndarray:
        """``(rows, cols)`` array of the literal "this cell holds ``tile``"."""
        return _tile_lits(self.problem, tile)

    def projection(self) -> np.ndarray:
        """The grid variables (a model restricted to them determines the tiling)."""
        return np.arange(1, self.n_grid_vars + 1, dtype=np.int64)

    def literals(self, tiling) -> list[int]:
        """Literals that fix every grid variable to ``tiling`` (assumptions for a solver).

        The formula plus these assumptions is satisfiable iff ``tiling`` satisfies the
        problem, which lets tests check a tiling (e.g. a constructive one) against the
        encoding.
        """
        return self._literal_array(tiling).tolist()

    def _literal_array(self, tiling) -> np.ndarray:
        """:meth:`literals` as an int64 array (no Python list of millions of ints)."""
        t = np.asarray(tiling)
        p = self.problem
        if t.shape != p.shape:
            raise InvalidProblem(f"tiling has shape {t.shape}, grid is {p.shape}")
        if ((t < 0) | (t >= p.n_tiles)).any():
            raise InvalidProblem(f"tiling holds tiles outside 0..{p.n_tiles - 1}")
        gv = self.grid_vars()
        if not self.one_hot:
            return np.where(t == 1, gv, -gv).ravel()
        onehot = t[:, :, None] == np.arange(p.n_tiles)[None, None, :]
        return np.where(onehot, gv, -gv).ravel()

    def decode(self, model: Sequence[int] | np.ndarray) -> np.ndarray:
        """Turn a solver model (signed DIMACS literals) into ``tiling[row, col]`` (int8).

        Grid variables missing from the model (a solver may omit variables that occur
        in no clause) count as false.
        """
        val = self.values(model)
        gv = self.grid_vars()
        if not self.one_hot:
            return val[gv].astype(np.int8)
        return np.argmax(val[gv], axis=2).astype(np.int8)

    def values(self, model: Sequence[int] | np.ndarray) -> np.ndarray:
        """Boolean array ``v[var]`` (index 0 unused) of a model's grid and aux variables."""
        m = np.asarray(model, dtype=np.int64).ravel()
        val = np.zeros(max(self.n_vars, self.n_grid_vars) + 1, dtype=bool)
        m = m[(m != 0) & (np.abs(m) <= self.n_vars)]
        val[np.abs(m)] = m > 0
        return val

    def target_values(self, tiling) -> np.ndarray:
        """Boolean grid assignment (``v[var]``) of a tiling; auxiliary variables false."""
        val = np.zeros(self.n_vars + 1, dtype=bool)
        lits = self._literal_array(tiling)
        val[np.abs(lits)] = lits > 0
        return val

    def describe_var(self, var: int) -> str:
        """Meaning of a variable, e.g. ``"x[2,5]: cell (row 2, col 5) holds tile 1"``."""
        p = self.problem
        if 1 <= var <= self.n_grid_vars:
            i = var - 1
            if not self.one_hot:
                r, c = divmod(i, p.cols)
                return f"x[{r},{c}]: cell (row {r}, col {c}) holds tile 1 (false: tile 0)"
            cell, t = divmod(i, p.n_tiles)
            r, c = divmod(cell, p.cols)
            return f"y[{r},{c},{t}]: cell (row {r}, col {c}) holds tile {t}"
        for lo, hi, what in self.aux_ranges:
            if lo <= var <= hi:
                return f"auxiliary variable of {what}"
        if self.pool is not None and var <= self.n_vars:
            return "auxiliary variable"
        raise KeyError(var)

    def header(self) -> list[str]:
        """Comment lines describing the problem and the variable numbering (DIMACS header)."""
        p = self.problem
        lines = [
            "tilesolve dappled tiling encoding (Kaji, Derouet-Jourdan, Ochiai 2016, section 6 item 8)",
            f"problem: {p.describe()}",
            "cells are (row, col), row 0 at the top",
        ]
        if self.one_hot:
            lines.append(
                f"variables 1..{self.n_grid_vars}: y[r,c,t] = 1 + (r*{p.cols} + c)*{p.n_tiles} + t, "
                "true iff cell (r,c) holds tile t"
            )
        else:
            lines.append(
                f"variables 1..{self.n_grid_vars}: x[r,c] = 1 + r*{p.cols} + c, true iff cell (r,c) holds tile 1"
            )
        for lo, hi, what in self.aux_ranges:
            lines.append(f"variables {lo}..{hi}: auxiliary, {what}")
        counts: dict[str, int] = {}
        for b in self.hard.blocks:
            counts[b.label] = counts.get(b.label, 0) + len(b)
        for label, n in counts.items():
            lines.append(f"{n} clauses: {label}")
        if self.soft is not None:
            lines.append(f"{len(self.soft)} soft unit clauses (weight 1): cell keeps its target tile")
        return lines

    # ------------------------------------------------------------------ pysat objects
    def cnf(self) -> CNF:
        """The hard clauses as a :class:`pysat.formula.CNF`."""
        cnf = CNF(from_clauses=self.hard.to_lists())
        cnf.nv = max(cnf.nv, self.n_vars)
        cnf.comments = ["c " + line for line in self.header()]
        return cnf

    def wcnf(self) -> WCNF:
        """Hard clauses plus unit soft clauses of weight 1 (requires :func:`encode_wcnf`)."""
        if self.soft is None:
            raise InvalidProblem("this encoding has no soft clauses; build it with encode_wcnf")
        w = WCNF()
        for ch in self.hard.chunks():
            for c in ch:
                w.append(c)
        for lit in self.soft.tolist():
            w.append([lit], weight=1)
        w.nv = max(w.nv, self.n_vars)
        w.comments = ["c " + line for line in self.header()]
        return w


# ---------------------------------------------------------------------- helpers


def _millions(n: int) -> str:
    return f"{n / 1e6:.1f} M" if n >= 100_000 else f"{n:,}"


def _grid_vars(p: DappledProblem) -> np.ndarray:
    if p.n_tiles == 2:
        return np.arange(1, p.size + 1, dtype=np.int64).reshape(p.rows, p.cols)
    return np.arange(1, p.size * p.n_tiles + 1, dtype=np.int64).reshape(p.rows, p.cols, p.n_tiles)


def _tile_lits(p: DappledProblem, tile: int) -> np.ndarray:
    gv = _grid_vars(p)
    if p.n_tiles == 2:
        return gv if tile == 1 else -gv
    return gv[:, :, tile]


def _outside_lits(p: DappledProblem, tiles: Sequence[int]) -> np.ndarray:
    """``(rows, cols, k)`` literals "cell holds a tile outside ``tiles``" (``k = |T| - |tau|``)."""
    others = [t for t in range(p.n_tiles) if t not in set(tiles)]
    if not others:
        return np.zeros((p.rows, p.cols, 0), dtype=np.int64)
    if p.n_tiles == 2:
        return _tile_lits(p, others[0])[:, :, None]
    return _grid_vars(p)[:, :, others]


#: Cells per strip of window clauses (the encoder checks its deadline between strips).
STRIP_CELLS = 1 << 18


def _uniform_windows(out: np.ndarray, p: int, cyclic: bool) -> Iterator[np.ndarray]:
    """:func:`_window_clauses` for one limit ``p`` at every cell, by shifted slices.

    Same clauses in the same order (row-major over the window's last cell, literals from
    cell ``c-p`` to ``c``), without the index arrays of the per-cell path (4x faster on a
    2048x2048 grid), yielded in strips of about :data:`STRIP_CELLS` cells.
    """
    rows, cols, k = out.shape
    if cyclic and p + 1 >= cols:
        yield out.reshape(rows, cols * k)
        return
    if not cyclic and p >= cols:
        return
    n_end = cols if cyclic else cols - p
    strip = max(1, STRIP_CELLS // cols)
    for r0 in range(0, rows, strip):
        o = out[r0 : r0 + strip]
        if cyclic:
            parts = [np.roll(o, j, axis=1) for j in range(p, -1, -1)]  # cell c-j at column c
        else:
            parts = [o[:, p - j : p - j + n_end] for j in range(p, -1, -1)]
        win = np.stack(parts, axis=2)  # (strip, n_end, p + 1, k)
        yield win.reshape(win.shape[0] * n_end, (p + 1) * k)


def _window_clauses(out: np.ndarray, limit: np.ndarray | int, cyclic: bool) -> Iterable[np.ndarray]:
    """Forbid horizontal windows (along axis 1) of ``limit + 1`` cells all inside ``tau``.

    ``out[r, c, :]`` are the literals "cell (r, c) is outside tau"; ``limit[r, c]`` is the
    limit for runs ending at ``(r, c)`` (0 = none), or one int for every cell. Returns
    clause arrays.
    """
    if not isinstance(limit, np.ndarray):
        return _uniform_windows(out, int(limit), cyclic) if limit else iter(())
    rows, cols, k = out.shape
    blocks = []
    for p in np.unique(limit[limit > 0]).tolist():
        rr, cc = np.nonzero(limit == p)
        if cyclic and p + 1 >= cols:
            # The window covers the whole (wrapped) row: "not every cell of the row in tau".
            rr = np.unique(rr)
            blocks.append(out[rr].reshape(len(rr), cols * k))
            continue
        if not cyclic:
            keep = cc >= p
            rr, cc = rr[keep], cc[keep]
            if rr.size == 0:
                continue
        offs = np.arange(p, -1, -1, dtype=np.int64)  # cells c-p .. c
        win = cc[:, None] - offs[None, :]
        if cyclic:
            win %= cols
        blocks.append(out[rr[:, None], win].reshape(len(rr), (p + 1) * k))
    return blocks


def _condition_blocks(p: DappledProblem, cond: Condition) -> Iterable[np.ndarray]:
    out = _outside_lits(p, cond.tiles)
    limit = cond.limit_array(p.rows, p.cols) if not cond.is_uniform else (cond.limit or 0)
    if cond.axis == "H":
        return _window_clauses(out, limit, p.cyclic)
    return _window_clauses(out.transpose(1, 0, 2), limit.T if isinstance(limit, np.ndarray) else limit, p.cyclic)


def _exactly_one_blocks(p: DappledProblem) -> list[tuple[np.ndarray, str]]:
    """Exactly-one constraints of the one-hot cells (vectorised over all cells)."""
    gv = _grid_vars(p).reshape(p.size, p.n_tiles)
    T = p.n_tiles
    blocks = [(gv, "one tile per cell: at least one")]
    if T <= PAIRWISE_AMO_MAX:
        i, j = np.triu_indices(T, 1)
        amo = np.stack([-gv[:, i], -gv[:, j]], axis=2).reshape(-1, 2)
        blocks.append((amo, "one tile per cell: at most one (pairwise)"))
    return blocks


def _sequential_amo(p: DappledProblem, first_aux: int) -> tuple[np.ndarray, int]:
    """Sinz's sequential-counter at-most-one for every cell, vectorised.

    Hand-written because :class:`pysat.card.CardEnc` works one constraint at a time, which
    would cost a Python call per cell. For ``x_1..x_n`` with auxiliaries ``s_1..s_{n-1}``:
    ``-x_i | s_i``, ``-s_{i-1} | s_i``, ``-x_i | -s_{i-1}``.
    """
    T = p.n_tiles
    gv = _grid_vars(p).reshape(p.size, T)
    s = first_aux + np.arange(p.size * (T - 1), dtype=np.int64).reshape(p.size, T - 1)
    parts = [np.stack([-gv[:, : T - 1], s], axis=2).reshape(-1, 2)]
    parts.append(np.stack([-s[:, :-1], s[:, 1:]], axis=2).reshape(-1, 2))
    parts.append(np.stack([-gv[:, 1:], -s], axis=2).reshape(-1, 2))
    return np.concatenate(parts), int(s.max())


def encode_cnf(
    problem: DappledProblem,
    *,
    card_encoding: CardEncoding | str = CardEncoding.AUTO,
    deadline: Deadline | None = None,
) -> DappledEncoding:
    """Encode a dappled problem as CNF (dappled paper §6 item 8).

    Every condition (plain or cyclic, any limit ``>= 1``, single tiles and subsets,
    uniform or per-cell), fixed cells (unit clauses) and global counts (cardinality
    encodings from :mod:`pysat.card`) are encoded; ``closest_to`` is ignored here (see
    :func:`encode_wcnf`). No solver is called.

    Parameters
    ----------
    problem : DappledProblem
    card_encoding : CardEncoding or str
        Cardinality encoding for ``problem.counts``.
    deadline : Deadline, optional
        Checked between blocks of clauses.

    Returns
    -------
    DappledEncoding

    Raises
    ------
    TimeLimitReached
        The deadline passed while encoding (the message says how far it got).

    Examples
    --------
    >>> from tilesolve.model import DappledProblem
    >>> enc = encode_cnf(DappledProblem.from_strings("4x4", ["H0=2", "V1=2"], cyclic=True))
    >>> enc.n_vars, len(enc.hard)
    (16, 32)
    """
    p = problem
    card = CardEncoding(card_encoding)
    hard = ClauseSet()

    def check() -> None:
        if deadline is not None:
            deadline.check(f"encoding ({_millions(len(hard))} clauses built)")

    one_hot = p.n_tiles > 2
    n_grid = p.size * (p.n_tiles if one_hot else 1)
    top = n_grid
    aux_ranges: list[tuple[int, int, str]] = []
    if one_hot:
        for arr, label in _exactly_one_blocks(p):
            hard.add_array(arr, label)
        if p.n_tiles > PAIRWISE_AMO_MAX:
            arr, new_top = _sequential_amo(p, top + 1)
            hard.add_array(arr, "one tile per cell: at most one (sequential counter)", grid_only=False)
            aux_ranges.append((top + 1, new_top, "at-most-one sequential counters"))
            top = new_top
    for cond in p.conditions:
        check()
        for arr in _condition_blocks(p, cond):
            hard.add_array(arr, f"{cond} windows" + (" (cyclic)" if p.cyclic else ""))
            check()
    if p.fixed is not None:
        rr, cc = np.nonzero(p.fixed >= 0)
        if rr.size:
            gv = _grid_vars(p)
            t = p.fixed[rr, cc].astype(np.int64)
            lits = gv[rr, cc] * np.where(t == 1, 1, -1) if not one_hot else gv[rr, cc, t]
            hard.add_array(lits[:, None], "fixed cells")
    pool = IDPool(start_from=top + 1)
    for k in p.counts:
        check()
        lits = _tile_lits(p, k.tile).ravel().tolist()
        n = len(lits)
        if deadline is not None and deadline.time_limit is not None:
            _card_fits(k, n, card, deadline)
        before = pool.top
        clauses: list[list[int]] = []
        if k.low > 0:
            clauses += cardinality("atleast", lits, k.low, vpool=pool, encoding=card.enctype(n, n - k.low))
        if k.high is not None and k.high < n:
            clauses += cardinality("atmost", lits, k.high, vpool=pool, encoding=card.enctype(n, k.high))
        hard.add_lists(clauses, f"count {k}", grid_only=False)
        if pool.top > before:
            aux_ranges.append((before + 1, pool.top, f"cardinality encoding of count {k}"))
    check()
    return DappledEncoding(
        problem=p,
        hard=hard,
        n_vars=max(pool.top, top),
        n_grid_vars=n_grid,
        one_hot=one_hot,
        pool=pool,
        aux_ranges=aux_ranges,
    )


#: Seconds per clause assumed for PySAT's cardinality encodings (one uninterruptible call each;
#: 3-15 µs were measured on a busy laptop core), to refuse one that cannot fit the time left.
CARD_SECONDS_PER_CLAUSE = 3e-6


def card_clauses(n: int, bound: int, enctype: int) -> float:
    """Rough clause count of one cardinality constraint over ``n`` literals (measured shapes)."""
    if enctype == EncType.seqcounter:
        return 2.0 * n * max(1, bound)
    if enctype in (EncType.cardnetwrk, EncType.sortnetwrk):
        return 0.7 * n * max(1.0, np.log2(max(n, 2))) ** 2
    return float(n)  # others: too varied to model; only their size in literals is certain


def _card_fits(k, n: int, card: CardEncoding, deadline: Deadline) -> None:
    """Raise :class:`TimeLimitReached` before a cardinality encoding that cannot fit the time left."""
    est = 0.0
    if k.low > 0:
        est += card_clauses(n, n - k.low, card.enctype(n, n - k.low))
    if k.high is not None and k.high < n:
        est += card_clauses(n, k.high, card.enctype(n, k.high))
    need = est * CARD_SECONDS_PER_CLAUSE
    left = deadline.remaining()
    if left is not None and need > left:
        raise TimeLimitReached(
            f"time limit of {deadline.time_limit:.3g} s reached while encoding: the cardinality encoding of count "
            f"{k} (~{_millions(int(est))} clauses, ~{need:.2g} s) cannot fit in the {left:.2g} s left"
        )


def encode_wcnf(
    problem: DappledProblem,
    target=None,
    *,
    card_encoding: CardEncoding | str = CardEncoding.AUTO,
    deadline: Deadline | None = None,
) -> DappledEncoding:
    """Encode the closest-tiling problem as weighted partial MaxSAT (§6 item 3, Example 6.1).

    Hard clauses are those of :func:`encode_cnf`; each cell adds a soft unit clause of
    weight 1 "the cell keeps its target tile", so the cost of a model is the Hamming
    distance ``d(f1, f2)`` of the paper.

    Parameters
    ----------
    problem : DappledProblem
    target : array-like, optional
        The tiling to stay close to; defaults to ``problem.closest_to``.
    deadline : Deadline, optional
        As for :func:`encode_cnf`.

    Raises
    ------
    InvalidProblem
        When neither ``target`` nor ``problem.closest_to`` is given.

    Examples
    --------
    >>> import numpy as np
    >>> from tilesolve.model import DappledProblem
    >>> p = DappledProblem.from_strings("3x1", ["H0=2"], closest_to=np.zeros((1, 3), int))
    >>> encode_wcnf(p).soft.tolist()
    [-1, -2, -3]
    """
    if target is None:
        target = problem.closest_to
    if target is None:
        raise InvalidProblem("a closest-tiling encoding needs a target tiling (closest_to)")
    enc = encode_cnf(problem, card_encoding=card_encoding, deadline=deadline)
    enc.soft = enc._literal_array(target)
    if enc.one_hot:
        enc.soft = enc.soft[enc.soft > 0]
    return enc


def naive_clauses(problem: DappledProblem) -> list[list[int]]:
    """Reference encoding of uniform binary conditions, one clause at a time in Python.

    The obvious loop over cells and windows, kept as a benchmark baseline and as an
    independent cross-check of :func:`encode_cnf` (same variable numbering, ``|T| = 2``,
    uniform limits, no counts). Not used by any solver route.
    """
    p = problem
    if p.n_tiles != 2 or not p.is_uniform:
        raise InvalidProblem("naive_clauses covers |T| = 2 with uniform limits only")
    clauses: list[list[int]] = []
    var = lambda r, c: 1 + r * p.cols + c  # noqa: E731
    for cond in p.conditions:
        if cond.limit is None:
            continue
        lim = cond.limit
        inside = set(cond.tiles)
        sign = 1 if 0 in inside else -1  # "cell outside tau" literal
        everything = inside == {0, 1}  # no cell is outside tau: every window is an empty clause
        n_line, n_along = (p.rows, p.cols) if cond.axis == "H" else (p.cols, p.rows)
        for a in range(n_line):
            seen = set()
            for b in range(n_along):
                if not p.cyclic and b < lim:
                    continue
                cells = sorted({(b - k) % n_along for k in range(lim + 1)}) if p.cyclic else range(b - lim, b + 1)
                key = tuple(cells)
                if key in seen:
                    continue
                seen.add(key)
                if everything:
                    clauses.append([])
                elif cond.axis == "H":
                    clauses.append([sign * var(a, j) for j in cells])
                else:
                    clauses.append([sign * var(j, a) for j in cells])
    if p.fixed is not None:
        for r in range(p.rows):
            for c in range(p.cols):
                t = int(p.fixed[r, c])
                if t >= 0:
                    clauses.append([var(r, c) if t == 1 else -var(r, c)])
    return clauses


# ---------------------------------------------------------------------- CP-SAT


@dataclass
class CpSatDappled:
    """An OR-tools CP-SAT model of a dappled problem (built, not solved).

    Attributes
    ----------
    model : ortools.sat.python.cp_model.CpModel
    variables : list
        ``variables[v - 1]`` is the Boolean variable of grid variable ``v`` of the CNF
        encoding (same numbering as :func:`encode_cnf`).
    encoding : DappledEncoding
        The CNF encoding whose grid clauses the model shares.
    objective : bool
        True when the model minimises the Hamming distance to ``closest_to``.
    """

    model: Any
    variables: list
    encoding: DappledEncoding
    objective: bool = False

    def decode(self, values: Sequence[bool]) -> np.ndarray:
        """Tiling from the values of :attr:`variables` (in order)."""
        v = np.asarray(values, dtype=bool)
        lits = np.where(v, np.arange(1, len(v) + 1), -np.arange(1, len(v) + 1))
        return self.encoding.decode(lits)

    def add_hint(self, tiling) -> None:
        """Hint every grid variable with ``tiling`` (CP-SAT solution hint)."""
        for lit in self.encoding.literals(tiling):
            self.model.add_hint(self.variables[abs(lit) - 1], lit > 0)


#: Variables or clauses added to a CP-SAT model between two deadline checks.
CPSAT_BUILD_CHUNK = 1 << 14


def build_cpsat(problem: DappledProblem, *, deadline: Deadline | None = None) -> CpSatDappled:
    """Build a CP-SAT model with the same semantics as :func:`encode_cnf`.

    The clauses of the CNF encoding (windows, fixed cells, exactly-one) become ``BoolOr``
    constraints; counts become native linear constraints; ``closest_to`` becomes the
    objective "minimise the number of cells that differ" (§6 item 3).

    The clauses go into the model's protocol buffer directly (CP-SAT literal ``v - 1`` for
    variable ``v``, ``-v`` for its negation), a few times faster than one
    ``add_bool_or`` call per clause; building is still about 10 µs a clause, so a
    ``deadline`` is checked every :data:`CPSAT_BUILD_CHUNK` variables or clauses.

    Raises
    ------
    TimeLimitReached
        The deadline passed while building (the message says how far it got).

    Examples
    --------
    >>> from tilesolve.model import DappledProblem
    >>> m = build_cpsat(DappledProblem.from_strings("3x3", ["H0=2", "V1=2"]))
    >>> len(m.variables)
    9
    """
    from ortools.sat.python import cp_model

    # Counts are linear constraints in CP-SAT: leave them out of the clause encoding.
    p_nocount = DappledProblem(
        problem.rows,
        problem.cols,
        n_tiles=problem.n_tiles,
        conditions=problem.conditions,
        cyclic=problem.cyclic,
        fixed=problem.fixed,
    )
    enc = encode_cnf(p_nocount, deadline=deadline)
    enc.problem = problem  # same grid and variables; decode/literals need only those
    model = cp_model.CpModel()
    chunk = CPSAT_BUILD_CHUNK
    n_vars = enc.n_vars  # grid variables, then the sequential-counter auxiliaries
    n_clauses = len(enc.hard)
    every: list = []
    for lo in range(0, n_vars, chunk):
        if deadline is not None:
            deadline.check(f"building the CP-SAT model ({_millions(lo)} of {_millions(n_vars)} variables created)")
        every.extend(model.new_bool_var(f"v{v}") for v in range(lo + 1, min(n_vars, lo + chunk) + 1))
    xs = every[: enc.n_grid_vars]
    constraints = model.proto.constraints
    done = 0
    for block in enc.hard.blocks:
        lits = block.lits if block.lits is not None else None
        rows = block.ragged if lits is None else None
        n = len(block)
        for lo in range(0, n, chunk):
            if deadline is not None:
                deadline.check(f"building the CP-SAT model ({_millions(done)} of {_millions(n_clauses)} clauses added)")
            if lits is not None:
                part = lits[lo : lo + chunk]
                part = np.where(part > 0, part - 1, part).tolist()  # CP-SAT: v - 1, negation -v
            else:
                part = [[v - 1 if v > 0 else v for v in c] for c in rows[lo : lo + chunk]]
            for clause in part:
                constraints.add().bool_or.literals.extend(clause)
            done += len(part)
    for k in problem.counts:
        tl = _tile_lits(problem, k.tile).ravel().tolist()
        terms = [xs[v - 1] if v > 0 else 1 - xs[-v - 1] for v in tl]
        s = cp_model.LinearExpr.sum(terms)
        if k.low > 0:
            model.add(s >= k.low)
        if k.high is not None:
            model.add(s <= k.high)
    has_obj = problem.closest_to is not None
    if has_obj:
        keep = enc.literals(problem.closest_to)
        if enc.one_hot:
            keep = [v for v in keep if v > 0]
        # cost of a cell = 1 - [cell keeps its target tile]
        model.minimize(cp_model.LinearExpr.sum([(1 - xs[v - 1]) if v > 0 else xs[-v - 1] for v in keep]))
    return CpSatDappled(model=model, variables=xs, encoding=enc, objective=has_obj)
