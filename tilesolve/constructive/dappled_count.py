"""Exact counting of dappled tilings by a transfer-matrix (profile) dynamic programme.

Kaji, Derouet-Jourdan and Ochiai, *Dappled tiling* (2016), Remark 1.4, note that the number of
``{H_0^2, V_1^2}``-dappled tilings with ``T = {0, 1}`` is tabulated (OEIS A206994) but that no
formula is known. This module counts the tilings of any :class:`DappledProblem` without global
counts or a target exactly, as a Python integer.

Method
------
*Tile classes.* Tiles that no condition and no fixed cell tells apart are merged into one class
whose weight is its size, so e.g. ``|T| = 5`` with conditions on tile 0 only runs with two classes.

*Per-column automaton.* Sweeping the grid row by row (top to bottom), the state of one column is
its class in the current row plus, for every ``V`` condition, the length of the vertical run of
member tiles that ends there (capped). The states reachable from the empty column are found by
breadth-first search and merged by partition refinement (Moore minimisation), so that only states
with different futures stay apart.

*Profile tensor.* The state of a whole row is a dense tensor with one axis of length ``s`` (the
number of column states) per column, ``s ** cols`` entries. Going to the next row is a product of
independent per-column transitions, applied as one linear pass per axis (tensor-product transform,
``cols * s ** cols`` additions per row); fixed cells and per-cell ``V`` limits just change the
per-axis map. A mask then zeroes the profiles whose row of classes breaks an ``H`` condition
(per-cell ``H`` limits give one mask per row; cyclic rows are checked around the wrap). The
passes run in place on one tensor, grouped so that each group of axes is applied to
cache-sized blocks gathered into scratch buffers (a row costs two or three sweeps over memory).

*Exact integers.* The programme runs modulo several primes just below ``2**62`` (numba, int64;
every transition weight is a small class size), and the residues are combined by the Chinese
remainder theorem. The number of primes comes from a rigorous bound: the count is at most the
product over rows of the number of admissible single rows (and likewise for columns), each
computed exactly by a one-dimensional programme, and, when that needs several primes, at most
the product of the exact counts of three horizontal strips (restricting a solution to a strip
gives a solution of the strip).

The sweep direction is chosen automatically: transposing a problem swaps rows and columns and
turns ``H`` conditions into ``V`` ones, and the orientation with the smaller tensor wins.
Problems with conditions along one axis only factor into independent lines and are counted by
the one-dimensional programme directly.

*Tori.* On a cyclic grid with conditions along both axes, runs wrap around the rows (handled
by the cyclic row masks, as for one axis) and down the columns. A column's automaton state
after the last row is exactly the state its first row continues from, so the count is the
trace of the row transfer operator to the power ``rows``: ``sum over profiles s of
(T^rows)[s, s]``, one sweep of the grid per start profile ``s`` (started from ``e_s`` with
the ordinary transitions in the first row, read back at ``s``). For a word in which every
``V`` condition resets, the state after it does not depend on where it started, so each
tiling is counted once; a column inside one ``V`` set throughout never returns to its start
state and is (rightly) never counted. Profiles whose row of classes breaks an ``H`` condition
are skipped, and when the problem is the same in every column the diagonal is constant on
the orbits of the column rotation, so one profile per orbit of the rotations and mirror images is swept (weighted by the
orbit's size). The cost is the start profiles times one sweep; :func:`plan_count` estimates it and
:func:`count_dappled` refuses above ``max_operations``.

Limits
------
Not supported (:class:`~tilesolve.errors.MethodNotApplicable`): global tile counts and a
target tiling (``closest_to``). Problems whose tensor would exceed ``max_memory`` bytes, and
tori whose trace would take more than ``max_operations`` additions, are refused before
anything large is allocated. Where only enumeration remains, :func:`enumeration_guard` says
so before it starts, with an estimate, and asks for a time limit or ``force``.
"""

from __future__ import annotations

import math
from collections import defaultdict
from dataclasses import dataclass
from functools import lru_cache
from typing import Callable

import numpy as np

from tilesolve._numba import numba as nb
from tilesolve.deadline import Deadline
from tilesolve.errors import InvalidProblem, MethodNotApplicable
from tilesolve.model.dappled import DappledProblem

__all__ = [
    "count_dappled",
    "plan_count",
    "CountPlan",
    "enumeration_guard",
    "ENUMERATION_RATE",
    "DEFAULT_MAX_MEMORY",
    "DEFAULT_MAX_OPERATIONS",
    "OPERATIONS_PER_SECOND",
]

#: Default ceiling on the working memory of one count (bytes).
DEFAULT_MAX_MEMORY = 2 * 2**30

#: Default ceiling on the estimated modular additions of a torus count (about a minute).
DEFAULT_MAX_OPERATIONS = 10**11

#: Modular additions per second assumed by time estimates (one laptop core, numba).
OPERATIONS_PER_SECOND = 2 * 10**9

#: Tilings per second assumed for a count by enumeration (a SAT call and a blocking clause each).
ENUMERATION_RATE = 1000

#: Enumerations estimated to finish within this many seconds start without being asked for.
ENUMERATION_FREE_S = 10.0

_PRIME_TOP = 2**62  # residues < p < 2**62, so a sum of two residues fits in int64


# =============================================================================== model prep
@dataclass
class _Cond:
    """One condition in a frame: ``member[k]`` says whether class ``k`` is in the tile set."""

    member: np.ndarray  # bool (K,)
    limit: np.ndarray  # int64 (rows, cols), 0 = no limit at that cell
    uniform: int | None  # the limit when it is the same finite number everywhere

    def transposed(self) -> "_Cond":
        return _Cond(self.member, np.ascontiguousarray(self.limit.T), self.uniform)

    @property
    def cap(self) -> int:
        """Largest finite limit + 1: longer runs behave alike (they break every limit)."""
        return int(self.limit.max()) + 1


@dataclass
class _Frame:
    """A problem over tile classes, swept row by row (``H`` along rows, ``V`` down columns)."""

    rows: int
    cols: int
    weights: np.ndarray  # int64 (K,) class sizes
    H: list[_Cond]
    V: list[_Cond]
    fixed: np.ndarray  # int64 (rows, cols) class index, -1 free
    cyclic: bool
    transposed: bool = False

    @property
    def K(self) -> int:
        return len(self.weights)

    def transpose(self) -> "_Frame":
        return _Frame(
            self.cols,
            self.rows,
            self.weights,
            [c.transposed() for c in self.V],
            [c.transposed() for c in self.H],
            np.ascontiguousarray(self.fixed.T),
            self.cyclic,
            not self.transposed,
        )


def _frame_of(problem: DappledProblem) -> _Frame:
    """Normalise ``problem``: drop conditions that cannot bite, merge interchangeable tiles."""
    if problem.counts:
        raise MethodNotApplicable(
            "exact counting does not support global tile counts; use method 'enumerate'"
        )
    if problem.closest_to is not None:
        raise MethodNotApplicable(
            "exact counting does not take a target tiling (closest_to); drop it to count all tilings"
        )
    rows, cols, cyclic = problem.rows, problem.cols, problem.cyclic
    kept: list[tuple[str, tuple[int, ...], np.ndarray, int | None]] = []
    r_idx = np.arange(rows)[:, None]
    c_idx = np.arange(cols)[None, :]
    for cond in problem.conditions:
        lim = cond.limit_array(rows, cols).astype(np.int64)
        uniform = cond.limit if cond.is_uniform else None
        if not cyclic:
            # A run ending at (r, c) is at most c+1 long (H) or r+1 long (V): larger limits never bite.
            reach = (c_idx + 1) if cond.axis == "H" else (r_idx + 1)
            if uniform is not None:
                if uniform >= (cols if cond.axis == "H" else rows):
                    continue
            else:
                lim = np.where(lim >= reach, 0, lim)
        if not lim.any():
            continue
        kept.append((cond.axis, cond.tiles, lim, uniform))

    fixed = problem.fixed
    fixed_tiles = set() if fixed is None else {int(t) for t in np.unique(fixed) if t >= 0}
    signature = {}
    for t in range(problem.n_tiles):
        key = (tuple(t in tiles for _, tiles, _, _ in kept), t if t in fixed_tiles else -1)
        signature.setdefault(key, []).append(t)
    classes = list(signature.values())
    cls_of_tile = np.empty(problem.n_tiles, dtype=np.int64)
    for k, members in enumerate(classes):
        cls_of_tile[members] = k
    weights = np.array([len(m) for m in classes], dtype=np.int64)

    H: list[_Cond] = []
    V: list[_Cond] = []
    for axis, tiles, lim, uniform in kept:
        member = np.zeros(len(classes), dtype=bool)
        member[cls_of_tile[list(tiles)]] = True
        (H if axis == "H" else V).append(_Cond(member, lim, uniform))
    fixed_cls = np.full((rows, cols), -1, dtype=np.int64)
    if fixed is not None:
        pinned = fixed >= 0
        fixed_cls[pinned] = cls_of_tile[fixed[pinned].astype(np.int64)]
    return _Frame(rows, cols, weights, H, V, fixed_cls, cyclic)


# ===================================================================== one-dimensional lines
def _line_count(weights, conds, limits, fixed_line, max_states: int | None = None) -> int | None:
    """Exact number of weighted fillings of one (non-cyclic) line.

    ``conds`` are ``(member, cap)`` pairs, ``limits[j]`` the per-position limits (0 = none),
    ``fixed_line`` the class per position (-1 free). Returns None when more than ``max_states``
    run-states appear (callers then fall back to a cruder bound).
    """
    K = len(weights)
    m = len(conds)
    states: dict[tuple[int, ...], int] = {(0,) * m: 1}
    for pos in range(len(fixed_line)):
        f = int(fixed_line[pos])
        allowed = range(K) if f < 0 else (f,)
        lim_here = [int(limits[j][pos]) for j in range(m)]
        new: dict[tuple[int, ...], int] = defaultdict(int)
        for runs, cnt in states.items():
            for cl in allowed:
                nxt = []
                for j, (member, cap) in enumerate(conds):
                    r = min(runs[j] + 1, cap) if member[cl] else 0
                    if lim_here[j] and r > lim_here[j]:
                        break
                    nxt.append(r)
                else:
                    new[tuple(nxt)] += cnt * int(weights[cl])
        states = new
        if max_states is not None and len(states) > max_states:
            return None
        if not states:
            return 0
    return sum(states.values())


def _lines_product(fr: _Frame, axis: str, max_states: int | None = None) -> int | None:
    """Product over all rows (``axis='H'``) or columns (``'V'``) of their single-line counts."""
    conds = fr.H if axis == "H" else fr.V
    n_lines = fr.rows if axis == "H" else fr.cols
    caps = [(c.member, c.cap) for c in conds]
    cache: dict[bytes, int | None] = {}
    total = 1
    for i in range(n_lines):
        if axis == "H":
            lims = [c.limit[i, :] for c in conds]
            fx = fr.fixed[i, :]
        else:
            lims = [c.limit[:, i] for c in conds]
            fx = fr.fixed[:, i]
        key = b"".join(np.ascontiguousarray(a).tobytes() for a in lims) + np.ascontiguousarray(fx).tobytes()
        if key not in cache:
            cache[key] = _line_count(fr.weights, caps, lims, fx, max_states)
        n = cache[key]
        if n is None:
            return None
        total *= n
    return total


def _count_bound(fr: _Frame) -> int:
    """A rigorous upper bound on the count: rows (and columns) are each admissible on their own."""
    free = fr.fixed < 0
    trivial = int(fr.weights.sum()) ** int(free.sum())
    best = trivial
    for axis in "HV":
        b = _lines_product(fr, axis, max_states=4096)
        if b is not None:
            best = min(best, b)
    return best


# ===================================================================== per-column automaton
@dataclass
class _Automaton:
    s: int  # number of column states
    state_cls: np.ndarray  # int64 (s,)
    trans: np.ndarray  # int64 (n_keys, s, K): next state or -1
    start: np.ndarray  # int64 (n_keys, K): first-row state or -1
    key_of_cell: np.ndarray  # int64 (rows, cols)


def _column_automaton(fr: _Frame, max_states: int = 1 << 16) -> _Automaton:
    """Reachable, minimised states of one column under the frame's ``V`` conditions."""
    K, V = fr.K, fr.V
    m = len(V)
    if m:
        stacked = np.stack([c.limit for c in V], axis=-1).reshape(-1, m)
        keys, inverse = np.unique(stacked, axis=0, return_inverse=True)
        key_of_cell = inverse.reshape(fr.rows, fr.cols).astype(np.int64)
    else:
        keys = np.zeros((1, 0), dtype=np.int64)
        key_of_cell = np.zeros((fr.rows, fr.cols), dtype=np.int64)
    n_keys = len(keys)
    members = [c.member for c in V]
    caps = [c.cap for c in V]

    start = (-1, (0,) * m)
    index = {start: 0}
    order = [start]
    edges: list[list[int]] = []  # per state: flattened (key, cls) -> target
    i = 0
    while i < len(order):
        cl0, runs = order[i]
        row = []
        for k in range(n_keys):
            lim = keys[k]
            for cl in range(K):
                nxt = []
                for j in range(m):
                    r = min(runs[j] + 1, caps[j]) if members[j][cl] else 0
                    if lim[j] and r > lim[j]:
                        break
                    nxt.append(r)
                else:
                    st = (cl, tuple(nxt))
                    if st not in index:
                        index[st] = len(order)
                        order.append(st)
                        if len(order) > max_states:
                            raise MethodNotApplicable(
                                f"one column has more than {max_states:,} run states; exact counting is "
                                "infeasible, use method 'enumerate'"
                            )
                    row.append(index[st])
                    continue
                row.append(-1)
        edges.append(row)
        i += 1
    E = np.array(edges, dtype=np.int64)  # (n, n_keys*K)
    cls = np.array([st[0] for st in order], dtype=np.int64)

    # Moore partition refinement; blocks start from the class (start state alone: class -1).
    _, block = np.unique(cls, return_inverse=True)
    n_blocks = block.max() + 1
    while True:
        tgt = np.where(E >= 0, block[np.maximum(E, 0)], -1)
        sig = np.concatenate([block[:, None], tgt], axis=1)
        _, new_block = np.unique(sig, axis=0, return_inverse=True)
        new_block = new_block.ravel()
        if new_block.max() + 1 == n_blocks:
            block = new_block
            break
        block, n_blocks = new_block, new_block.max() + 1
    # Renumber real states 0..s-1 (the start state keeps its own block, dropped).
    start_block = block[0]
    real = sorted({int(b) for b in block} - {int(start_block)})
    renum = np.full(n_blocks, -1, dtype=np.int64)
    renum[real] = np.arange(len(real))
    s = len(real)
    rep = {}
    for st, b in enumerate(block):
        rep.setdefault(int(b), st)
    state_cls = np.array([cls[rep[b]] for b in real], dtype=np.int64)
    trans = np.full((n_keys, s, K), -1, dtype=np.int64)
    for b in real:
        row = E[rep[b]].reshape(n_keys, K)
        trans[:, renum[b], :] = np.where(row >= 0, renum[block[np.maximum(row, 0)]], -1)
    srow = E[0].reshape(n_keys, K)
    start_tr = np.where(srow >= 0, renum[block[np.maximum(srow, 0)]], -1)
    return _Automaton(s, state_cls, trans, start_tr, key_of_cell)


# ========================================================================= planning / sizes
@dataclass(frozen=True)
class CountPlan:
    """How :func:`count_dappled` would count a problem (no large allocation happens here).

    Attributes
    ----------
    route : str
        ``"trivial"`` (no condition left), ``"lines"`` (conditions along one axis only: a product
        of independent lines), ``"transfer"`` (the profile tensor) or ``"torus"`` (the trace of
        the transfer operator, cyclic problems with conditions along both axes).
    transposed : bool
        The sweep runs over the columns of the original problem.
    rows, cols : int
        Shape in the sweep frame (the tensor has one axis per ``cols``).
    n_classes : int
        Tile classes after merging interchangeable tiles.
    column_states : int
        States of one column (``s``); the tensor has ``s ** cols`` entries.
    tensor_states : int
    n_primes : int
        Residue computations combined by the Chinese remainder theorem.
    bound_bits : int
        Bits of the rigorous upper bound behind ``n_primes`` (the product of the single lines'
        counts, or of narrow column strips' when that is smaller).
    memory_bytes : int
        Estimated peak working memory of the tensor route.
    operations : int
        Estimated modular additions.
    start_profiles : int
        Sweeps per prime of the ``"torus"`` route (1 otherwise).
    halves : bool
        The ``"transfer"`` sweep meets in the middle: the problem reads the same upside down,
        so only the lower half of the rows is swept (then one join sweep per prime).
    """

    route: str
    transposed: bool
    rows: int
    cols: int
    n_classes: int
    column_states: int
    tensor_states: int
    n_primes: int
    bound_bits: int
    memory_bytes: int
    operations: int
    start_profiles: int = 1
    halves: bool = False

    @property
    def seconds(self) -> float:
        """Rough time estimate (:data:`OPERATIONS_PER_SECOND`)."""
        return self.operations / OPERATIONS_PER_SECOND

    def describe(self) -> str:
        """The work in words, e.g. ``"3^16 = 43,046,721 states x 8 of 16 rows, 3 primes"``."""
        if self.route not in ("transfer", "torus"):
            return f"route {self.route}"
        starts = f", {self.start_profiles:,} start profiles" if self.route == "torus" else ""
        rows = f"{self.rows - self.rows // 2} of {self.rows} rows" if self.halves else f"{self.rows} rows"
        return (f"{self.column_states}^{self.cols} = {self.tensor_states:,} states x {rows}{starts}, "
                f"{self.n_primes} prime{'s' if self.n_primes != 1 else ''}")


def _tensor_size(fr: _Frame, torus: bool = False) -> tuple[_Automaton, int, int, int]:
    aut = _column_automaton(fr)
    n = aut.s ** fr.cols
    n_rows = len({b"".join(c.limit[r].tobytes() for c in fr.H) for r in range(fr.rows)}) if fr.H else 0
    pat_bytes = (4 if fr.K**fr.cols < 2**31 else 8) if n_rows > 1 else 0
    meet = not torus and _meets_in_middle(fr, aut)
    # int64 tensors (two to meet in the middle) + uint8 mask (+ class-pattern index when rows
    # differ) + row-validity tables
    mem = n * (8 * (2 if meet else 1) + (1 if fr.H else 0) + pat_bytes) + n_rows * fr.K**fr.cols + 32 * _CHUNK
    nnz = int((aut.trans >= 0).sum()) / max(1, aut.trans.shape[0])
    sweeps = fr.rows - fr.rows // 2 + 1 if meet else fr.rows  # the bottom half, one join, one dot product
    ops = int(sweeps * fr.cols * n * max(1.0, nnz / max(aut.s, 1)))
    return aut, n, mem, ops


@lru_cache(maxsize=None)
def _is_prime(n: int) -> bool:
    if n < 2:
        return False
    for q in (2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37):
        if n % q == 0:
            return n == q
    d, r = n - 1, 0
    while d % 2 == 0:
        d //= 2
        r += 1
    for a in (2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37):  # deterministic below 3.3e24
        x = pow(a, d, n)
        if x in (1, n - 1):
            continue
        for _ in range(r - 1):
            x = x * x % n
            if x == n - 1:
                break
        else:
            return False
    return True


_PRIMES: list[int] = []


def _primes(k: int) -> list[int]:
    """The ``k`` largest primes below ``2**62``."""
    c = (_PRIMES[-1] if _PRIMES else _PRIME_TOP) - 1
    while len(_PRIMES) < k:
        if c % 2 and _is_prime(c):
            _PRIMES.append(c)
        c -= 1
    return _PRIMES[:k]


def _n_primes(bound: int) -> int:
    """Fewest primes whose product exceeds ``bound`` (so residues pin the count down)."""
    k, prod = 0, 1
    while prod <= bound:
        k += 1
        prod *= _primes(k)[-1]
    return max(k, 1)


def _plan(
    problem: DappledProblem, orientation: str | None, max_memory: int = DEFAULT_MAX_MEMORY
) -> tuple[CountPlan, _Frame, _Automaton | None, int]:
    fr = _frame_of(problem)
    if orientation not in (None, "rows", "cols"):
        raise InvalidProblem(f"orientation must be None, 'rows' or 'cols', got {orientation!r}")
    if fr.cyclic and fr.H and fr.V:
        return _plan_torus(fr, orientation, max_memory)
    if not fr.H and not fr.V:
        free = int((fr.fixed < 0).sum())
        bound = int(fr.weights.sum()) ** free
        return CountPlan("trivial", False, fr.rows, fr.cols, fr.K, 1, 1, 0, bound.bit_length(), 0, 0), fr, None, bound
    if not fr.cyclic and (not fr.H or not fr.V) and orientation is None:
        bound = _lines_product(fr, "H" if fr.H else "V")
        return CountPlan("lines", False, fr.rows, fr.cols, fr.K, 0, 0, 0, bound.bit_length(), 0, 0), fr, None, bound

    candidates = []
    if fr.cyclic:
        # Runs wrap along the rows of the sweep by the row masks: put every condition on the
        # H side. Sweeping the other way, they wrap down the columns: the torus trace.
        want = "cols" if fr.V else "rows"
        if orientation not in (None, want):
            return _plan_torus(fr, orientation, max_memory)
        candidates.append(fr.transpose() if fr.V else fr)
    else:
        if orientation in (None, "rows"):
            candidates.append(fr)
        if orientation in (None, "cols"):
            candidates.append(fr.transpose())
    sized = []
    for cand in candidates:
        try:
            sized.append((cand, *_tensor_size(cand)))
        except MethodNotApplicable:
            if len(candidates) == 1:
                raise
    if not sized:
        raise MethodNotApplicable("exact counting: the column run states are too many in both orientations")
    sized.sort(key=lambda t: (t[3] > max_memory, t[4], t[3]))  # fits, then fewest operations
    cand, aut, n, mem, ops = sized[0]
    bound = _tight_bound(cand, aut)
    k = _n_primes(bound) if bound > 0 else 0
    plan = CountPlan(
        "transfer",
        cand.transposed,
        cand.rows,
        cand.cols,
        cand.K,
        aut.s,
        n,
        k,
        bound.bit_length(),
        mem,
        ops * max(k, 1),
        halves=_meets_in_middle(cand, aut),
    )
    return plan, cand, aut, bound


def _shift_invariant(fr: _Frame) -> bool:
    """True when every column of the frame is alike (per-cell limits and fixed cells)."""
    arrays = [c.limit for c in fr.H + fr.V] + [fr.fixed]
    return all(bool((a == a[:, :1]).all()) for a in arrays)


def _torus_starts(fr: _Frame, aut: _Automaton) -> tuple[np.ndarray, np.ndarray]:
    """Start profiles of the trace and their weights (orbit sizes under column rotation and
    mirroring when every column is alike)."""
    s, W = aut.s, fr.cols
    n = s**W
    idx = np.arange(n, dtype=np.int64)
    if fr.H:
        member = np.array([c.member for c in fr.H], dtype=np.bool_)
        lims = np.ascontiguousarray(np.stack([c.limit[fr.rows - 1] for c in fr.H]))
        ok = _row_valid(fr.K, W, member, lims, True)[_class_patterns(aut.state_cls, fr.K, W)].astype(bool)
    else:
        ok = np.ones(n, dtype=bool)
    if not _shift_invariant(fr) or W == 1:
        return idx[ok], np.ones(int(ok.sum()), dtype=np.int64)
    # Alike columns: the problem is also the same read right to left (uniform rows), so the
    # orbits are those of the dihedral group (rotations of the profile and of its mirror).
    top = s ** (W - 1)
    mirror = np.zeros(n, dtype=np.int64)
    rest = idx.copy()
    for _ in range(W):
        mirror = mirror * s + rest % s
        rest //= s
    canon = np.minimum(idx, mirror)
    for start in (idx, mirror):
        rot = start.copy()
        for _ in range(W - 1):
            rot = (rot % top) * s + rot // top  # the profile shifted by one column
            np.minimum(canon, rot, out=canon)
    reps, sizes = np.unique(canon[ok], return_counts=True)
    return reps, sizes.astype(np.int64)


def _plan_torus(fr: _Frame, orientation: str | None, max_memory: int):
    """Plan the trace count of a torus (conditions along both axes, see the module doc)."""
    candidates = []
    if orientation in (None, "rows"):
        candidates.append(fr)
    if orientation in (None, "cols"):
        candidates.append(fr.transpose())
    sized = []
    for cand in candidates:
        try:
            aut, n, mem, ops = _tensor_size(cand, torus=True)
        except MethodNotApplicable:
            if len(candidates) == 1:
                raise
            continue
        if n > 1 << 24:  # start profiles are listed explicitly: refuse before allocating them
            sized.append((cand, aut, n, mem + 16 * n, ops * n, None))
            continue
        starts = _torus_starts(cand, aut)
        sized.append((cand, aut, n, mem + 16 * n, ops * max(1, len(starts[0])), starts))
    if not sized:
        raise MethodNotApplicable("exact counting: the column run states are too many in both orientations")
    sized.sort(key=lambda t: (t[3] > max_memory, t[4]))
    cand, aut, n, mem, ops, starts = sized[0]
    bound = _tight_bound(cand, aut)
    k = _n_primes(bound) if bound > 0 else 0
    n_starts = n if starts is None else len(starts[0])
    plan = CountPlan("torus", cand.transposed, cand.rows, cand.cols, cand.K, aut.s, n, k, bound.bit_length(), mem,
                     ops * max(k, 1), n_starts)
    return plan, cand, aut, bound


def plan_count(
    problem: DappledProblem, *, orientation: str | None = None, max_memory: int = DEFAULT_MAX_MEMORY
) -> CountPlan:
    """Describe how :func:`count_dappled` would count ``problem``, without counting.

    Raises the same :class:`~tilesolve.errors.MethodNotApplicable` as :func:`count_dappled` for
    unsupported problems; ``max_memory`` only steers the choice of orientation here (compare
    :attr:`CountPlan.memory_bytes` with it to see whether the count would be refused).

    Examples
    --------
    >>> from tilesolve.model.dappled import DappledProblem
    >>> p = DappledProblem.from_strings("12x12", ["H0=2", "V1=2"])
    >>> pl = plan_count(p)
    >>> pl.route, pl.column_states, pl.tensor_states, pl.n_primes
    ('transfer', 3, 531441, 2)
    >>> plan_count(DappledProblem.from_strings("4x4", ["H0=2", "V1=2"], cyclic=True)).route
    'torus'
    """
    return _plan(problem, orientation, max_memory)[0]


# ============================================================================ numba kernels
@nb.njit(cache=True, inline="always")
def _mul_small(x, w, p):
    r = np.int64(0)
    while w:
        if w & 1:
            r += x
            if r >= p:
                r -= p
        x += x
        if x >= p:
            x -= p
        w >>= 1
    return r


@nb.njit(cache=True)
def _axis_pass(src, dst, pre, s, post, indptr, indices, weights, p):
    """dst[a, j, b] = w_j * sum_{i in pred(j)} src[a, i, b]  (mod p), tensor viewed (pre, s, post)."""
    blk = s * post
    if post < 16:
        # Short lanes: flat scalar loops (slicing views would cost more than they save).
        for a in range(pre):
            base = a * blk
            for j in range(s):
                lo = indptr[j]
                hi = indptr[j + 1]
                w = weights[j]
                for b in range(post):
                    acc = np.int64(0)
                    for k in range(lo, hi):
                        acc += src[base + indices[k] * post + b]
                        if acc >= p:
                            acc -= p
                    if w != 1 and acc != 0:
                        acc = _mul_small(acc, w, p)
                    dst[base + j * post + b] = acc
        return
    # Long lanes: contiguous views, so that LLVM vectorises the modular additions.
    for a in range(pre):
        sa = src[a * blk : (a + 1) * blk]
        da = dst[a * blk : (a + 1) * blk]
        for j in range(s):
            d = da[j * post : (j + 1) * post]
            lo = indptr[j]
            hi = indptr[j + 1]
            if lo == hi:
                d[:] = 0
                continue
            x0 = sa[indices[lo] * post : (indices[lo] + 1) * post]
            if hi - lo == 1:
                for b in range(post):
                    d[b] = x0[b]
            else:
                x1 = sa[indices[lo + 1] * post : (indices[lo + 1] + 1) * post]
                for b in range(post):
                    x = x0[b] + x1[b]
                    d[b] = x - p if x >= p else x
                for k in range(lo + 2, hi):
                    xk = sa[indices[k] * post : (indices[k] + 1) * post]
                    for b in range(post):
                        x = d[b] + xk[b]
                        d[b] = x - p if x >= p else x
            w = weights[j]
            if w != 1:
                for b in range(post):
                    d[b] = _mul_small(d[b], w, p)


@nb.njit(cache=True)
def _sweep_row(t, s, bounds, map_ids, indptr, indices, weights, p, mask, use_mask, sc1, sc2, chunk):
    """One row, in place: apply every column's map to its tensor axis, then the row's H mask.

    The axes are split into groups (``bounds``) whose joint extent fits in cache; for each group
    the tensor is walked once, gathering ``extent x chunk`` sub-blocks into the scratch buffers,
    applying the group's axis passes there and scattering back. The mask is applied while
    scattering the last group, so a row costs a few sweeps over memory, not one per column.
    """
    N = t.shape[0]
    W = bounds[bounds.shape[0] - 1]
    for g in range(bounds.shape[0] - 2, -1, -1):
        c0 = bounds[g]
        c1 = bounds[g + 1]
        S = 1
        for _ in range(c0, c1):
            S *= s
        post = 1
        for _ in range(c1, W):
            post *= s
        pre = N // (S * post)
        # sub-block: bp consecutive "pre" indices x S x bw consecutive "post" indices, stored
        # as (S, bp, bw) so that every axis pass below runs over at least bp * bw lanes.
        bw = min(post, max(1, chunk // S))
        bp = min(pre, max(1, chunk // (S * bw)))
        masked = use_mask and g == 0
        for a0 in range(0, pre, bp):
            na = min(bp, pre - a0)
            for b0 in range(0, post, bw):
                nb_ = min(bw, post - b0)
                ln = na * nb_
                _gather(t, sc1, a0 * S * post + b0, na, S, post, nb_)
                src = sc1
                dst = sc2
                ppre = 1
                ppost = S * ln
                for c in range(c0, c1):
                    ppost //= s
                    m = map_ids[c]
                    _axis_pass(src, dst, ppre, s, ppost, indptr[m], indices[m], weights[m], p)
                    src, dst = dst, src
                    ppre *= s
                _scatter(src, t, a0 * S * post + b0, na, S, post, nb_, mask, masked)


@nb.njit(cache=True)
def _gather(t, sc, start, na, S, post, nb):
    """sc[(i * na + q) * nb + b] = t[start + (q * S + i) * post + b]: copy a (na, S, nb) block of
    the tensor into scratch as (S, na, nb). Unsigned indices let LLVM drop negative-index checks."""
    start = np.uint64(start)
    na = np.uint64(na)
    S = np.uint64(S)
    post = np.uint64(post)
    nb = np.uint64(nb)
    if nb == 1:
        for i in range(S):
            for q in range(na):
                sc[i * na + q] = t[start + (q * S + i) * post]
    else:
        for q in range(na):
            for i in range(S):
                src = start + (q * S + i) * post
                dst = (i * na + q) * nb
                for b in range(nb):
                    sc[dst + b] = t[src + b]


@nb.njit(cache=True)
def _scatter(sc, t, start, na, S, post, nb, mask, masked):
    """Inverse of :func:`_gather`, zeroing the entries whose mask is 0 when ``masked``."""
    start = np.uint64(start)
    na = np.uint64(na)
    S = np.uint64(S)
    post = np.uint64(post)
    nb = np.uint64(nb)
    for q in range(na):
        for i in range(S):
            dst = start + (q * S + i) * post
            src = (i * na + q) * nb
            if masked:
                for b in range(nb):
                    t[dst + b] = sc[src + b] if mask[dst + b] else 0
            else:
                for b in range(nb):
                    t[dst + b] = sc[src + b]


@nb.njit(cache=True)
def _sum_mod(buf, p):
    acc = np.int64(0)
    for i in range(buf.shape[0]):
        acc += buf[i]
        if acc >= p:
            acc -= p
    return acc


@nb.njit(cache=True)
def _dot_parts(a, b):
    """``a . b`` for entries below ``2**62``, exactly, as three 128-bit sums ``(high, low)``.

    With ``x = x1 * 2**31 + x0``: ``x * y = x1*y1 * 2**62 + (x1*y0 + x0*y1) * 2**31 + x0*y0``.
    Every half product is below ``2**62`` (the cross pair below ``2**63``); each sum is kept
    as a high word counting the carries out of a wrapping 64-bit low word (no branches, so
    the loop vectorises).
    """
    lo = np.uint64((1 << 31) - 1)
    h2 = np.uint64(0)
    l2 = np.uint64(0)
    h1 = np.uint64(0)
    l1 = np.uint64(0)
    h0 = np.uint64(0)
    l0 = np.uint64(0)
    sh = np.uint64(31)
    for i in range(a.shape[0]):
        x = np.uint64(a[i])
        y = np.uint64(b[i])
        x1 = x >> sh
        x0 = x & lo
        y1 = y >> sh
        y0 = y & lo
        v = x1 * y1
        l2 += v
        h2 += np.uint64(l2 < v)
        v = x1 * y0 + x0 * y1
        l1 += v
        h1 += np.uint64(l1 < v)
        v = x0 * y0
        l0 += v
        h0 += np.uint64(l0 < v)
    return h2, l2, h1, l1, h0, l0


@nb.njit(cache=True)
def _row_valid(K, W, member, limits, cyclic):
    """Whether each class pattern (column 0 most significant) satisfies the H conditions."""
    n = K**W
    out = np.ones(n, dtype=np.uint8)
    digits = np.zeros(W, dtype=np.int64)
    nH = member.shape[0]
    for idx in range(n):
        ok = True
        for h in range(nH):
            run = 0
            if cyclic:
                full = True
                for c in range(W):
                    if not member[h, digits[c]]:
                        full = False
                        break
                if full:
                    for c in range(W):
                        if limits[h, c] > 0:
                            ok = False
                            break
                    if not ok:
                        break
                    continue
                for c in range(2 * W):
                    cc = c % W
                    run = run + 1 if member[h, digits[cc]] else 0
                    if c >= W and limits[h, cc] > 0 and run > limits[h, cc]:
                        ok = False
                        break
            else:
                for c in range(W):
                    run = run + 1 if member[h, digits[c]] else 0
                    if limits[h, c] > 0 and run > limits[h, c]:
                        ok = False
                        break
            if not ok:
                break
        out[idx] = 1 if ok else 0
        # odometer: last column least significant
        c = W - 1
        while c >= 0:
            digits[c] += 1
            if digits[c] < K:
                break
            digits[c] = 0
            c -= 1
    return out


# ================================================================================= counting
def _build_maps(fr: _Frame, aut: _Automaton, torus: bool = False):
    """Per-cell axis maps in CSR form, deduplicated: (map_id (rows, cols), indptr, indices, weights).

    With ``torus`` the first row continues from the start profile's states (ordinary
    transitions) instead of from the empty column."""
    s = aut.s
    table: dict[tuple[int, int, bool], int] = {}
    ptrs, idxs, wts = [], [], []
    map_id = np.empty((fr.rows, fr.cols), dtype=np.int64)
    for r in range(fr.rows):
        for c in range(fr.cols):
            key = (int(aut.key_of_cell[r, c]), int(fr.fixed[r, c]), r == 0 and not torus)
            if key not in table:
                k, f, first = key
                indptr = [0]
                ind: list[int] = []
                w = np.ones(s, dtype=np.int64)
                for j in range(s):
                    cj = int(aut.state_cls[j])
                    if f < 0 or cj == f:
                        w[j] = fr.weights[cj]
                        if first:
                            if aut.start[k, cj] == j:
                                ind.append(0)
                        else:
                            ind.extend(np.nonzero(aut.trans[k, :, cj] == j)[0].tolist())
                    indptr.append(len(ind))
                table[key] = len(ptrs)
                ptrs.append(indptr)
                idxs.append(ind)
                wts.append(w)
            map_id[r, c] = table[key]
    width = max(1, max(len(x) for x in idxs))
    indices = np.zeros((len(idxs), width), dtype=np.int64)
    for m, ind in enumerate(idxs):
        indices[m, : len(ind)] = ind
    return map_id, np.array(ptrs, dtype=np.int64), indices, np.array(wts, dtype=np.int64)


def _class_patterns(state_cls: np.ndarray, K: int, W: int) -> np.ndarray:
    """For every tensor index, the index of its row of classes (column 0 most significant)."""
    dtype = np.int32 if K**W < 2**31 else np.int64
    sc = state_cls.astype(dtype)
    pat = sc.copy()
    for _ in range(1, W):
        pat = (pat[:, None] * dtype(K) + sc[None, :]).ravel()
    return pat


def _crt(residues: list[int], primes: list[int]) -> int:
    x, m = 0, 1
    for r, p in zip(residues, primes):
        t = ((r - x) * pow(m, -1, p)) % p
        x += m * t
        m *= p
    return x


def count_dappled(
    problem: DappledProblem,
    *,
    progress: Callable[[int, int], object] | None = None,
    max_memory: int = DEFAULT_MAX_MEMORY,
    orientation: str | None = None,
    max_operations: int | None = DEFAULT_MAX_OPERATIONS,
    deadline: Deadline | None = None,
) -> int:
    """Exact number of tilings that satisfy ``problem`` (dappled paper, Def. 1.1 and Remark 1.4).

    Parameters
    ----------
    problem : DappledProblem
        Any number of tiles; conditions on single tiles or subsets (§6 item 2), uniform or
        per-cell (§3.1) limits; fixed cells (partial tiling, §6 item 7); cyclic problems (§3.2),
        tori with conditions along both axes by the trace of the transfer operator.
    progress : callable, optional
        Called as ``progress(done, total)`` after each row of each residue computation (the
        facade passes a :mod:`tilesolve.progress` task's ``set``; constructive code never
        writes to the terminal itself).
    max_memory : int
        Refuse (before allocating) when the estimated working memory exceeds this many bytes.
    orientation : {None, 'rows', 'cols'}
        Force the sweep over rows (as given) or over columns (transposed); ``None`` picks the
        cheaper one and counts one-axis problems as a product of lines.
    max_operations : int or None
        Refuse a torus count whose estimated modular additions exceed this (the message gives
        the estimate); ``None`` for no ceiling.
    deadline : Deadline, optional
        Checked after every row sweep; raises :class:`~tilesolve.deadline.TimeLimitReached`.

    Returns
    -------
    int
        The number of tilings (a Python integer of any size).

    Raises
    ------
    MethodNotApplicable
        Global counts, a target tiling, a state space larger than ``max_memory`` allows, or a
        torus above ``max_operations`` (the message gives the estimate).
    TimeLimitReached
        The deadline passed (the message says how far the count got).

    Examples
    --------
    >>> from tilesolve.model.dappled import DappledProblem
    >>> count_dappled(DappledProblem.from_strings("3x3", ["H0=2", "V1=2"]))  # OEIS A206994: T(3,3)
    174
    >>> count_dappled(DappledProblem.from_strings("4x4", ["H0=2", "V1=2"], cyclic=True))  # a torus
    90
    """
    if not callable(progress):
        progress = None
    plan, fr, aut, bound = _plan(problem, orientation, max_memory)
    if plan.route in ("trivial", "lines"):
        if progress is not None:
            progress(1, 1)
        return bound
    if bound == 0:
        if progress is not None:
            progress(1, 1)
        return 0
    if plan.memory_bytes > max_memory:
        raise MethodNotApplicable(
            f"exact counting would need a tensor of {aut.s}^{fr.cols} = {plan.tensor_states:,} states "
            f"(~{plan.memory_bytes / 2**30:.2f} GiB, limit {max_memory / 2**30:.2f} GiB; ~{_duration(plan.seconds)} "
            "of work); try a smaller grid"
        )
    assert aut is not None
    if plan.route == "torus":
        if max_operations is not None and plan.operations > max_operations:
            raise MethodNotApplicable(
                f"exact counting of this torus sweeps the grid once per start profile: {plan.start_profiles:,} "
                f"sweeps of a {aut.s}^{fr.cols} = {plan.tensor_states:,}-state tensor, about {plan.operations:.2g} "
                f"additions (~{_duration(plan.seconds)}; limit {max_operations:.2g})"
            )
        if deadline is not None:
            deadline.check("planning the count")
        starts = _torus_starts(fr, aut)
        return _transfer_count(fr, aut, plan.n_primes, progress, deadline, starts)
    if deadline is not None:
        deadline.check("planning the count")
    return _transfer_count(fr, aut, plan.n_primes, progress, deadline)


def _duration(seconds: float) -> str:
    """``"3 s"``, ``"2.5 h"``, ``"4e+03 years"``: a rough duration for estimates."""
    for unit, size in (("years", 3.15e7), ("days", 86400), ("h", 3600), ("min", 60)):
        if seconds >= 2 * size:
            return f"{seconds / size:.2g} {unit}"
    return f"{seconds:.2g} s"


def _column_strip(fr: _Frame, c0: int, c1: int) -> _Frame:
    """Columns ``c0 .. c1-1`` of a frame, as a problem of its own whose rows do not wrap."""
    sub = lambda c: _Cond(c.member, np.ascontiguousarray(c.limit[:, c0:c1]), c.uniform)  # noqa: E731
    return _Frame(
        fr.rows, c1 - c0, fr.weights, [sub(c) for c in fr.H], [sub(c) for c in fr.V],
        np.ascontiguousarray(fr.fixed[:, c0:c1]), False, fr.transposed,
    )  # fmt: skip


#: Largest tensor (entries) of one column strip of :func:`_strip_bound`.
_STRIP_STATES = 1 << 15


def _tight_bound(fr: _Frame, aut: _Automaton) -> int:
    """The single lines' bound on the count, tightened by the column strips' (:func:`_strip_bound`)
    when it needs several primes."""
    bound = _count_bound(fr)
    if _STRIP_BOUND and bound > 0 and _n_primes(bound) >= 2 and fr.cols >= 2:
        bound = min(bound, _strip_bound(fr, aut.s))
    return bound


def _strip_bound(fr: _Frame, s: int) -> int:
    """Product of the exact counts of vertical strips of at most :data:`_STRIP_STATES` profiles.

    Restricting a solution to a strip of columns gives a solution of the strip (conditions only
    forbid runs; a strip's rows do not wrap and its columns are counted without wrapping, which
    only drops conditions), so the product bounds the count. The strips are narrow, so their
    counts cost next to nothing beside the count itself, and the bound is far tighter than the
    single lines' (16x16 {H0^2, V1^2}: 173 bits, the count has 168, the single rows give 229).
    """
    per = max(1, int(math.log(_STRIP_STATES) / math.log(s) + 1e-9)) if s > 1 else fr.cols
    n_strips = max(2, -(-fr.cols // per))
    edges = [round(i * fr.cols / n_strips) for i in range(n_strips + 1)]
    cache: dict[bytes, int] = {}
    total = 1
    for c0, c1 in zip(edges, edges[1:]):
        sub = _column_strip(fr, c0, c1)
        key = b"".join(c.limit.tobytes() for c in sub.H + sub.V) + sub.fixed.tobytes() + bytes([sub.cols])
        if key not in cache:
            b = _count_bound(sub)
            cache[key] = 0 if b == 0 else _transfer_count(sub, _column_automaton(sub), _n_primes(b), None)
        total *= cache[key]
    return total


def _transfer_count(fr: _Frame, aut: _Automaton, n_primes: int, progress, deadline: Deadline | None = None,
                    starts: tuple[np.ndarray, np.ndarray] | None = None) -> int:
    """The profile-tensor programme, modulo ``n_primes`` primes, combined by CRT.

    With ``starts`` (start profiles and weights), the torus trace: one sweep per start
    profile, from it and back to it (module doc). A problem that reads the same upside down
    meets in the middle (:func:`_meets_in_middle`): the top half is swept, and the bottom half,
    read upwards, is the same tensor; the count is the top tensor against the bottom one seen
    through the join of the two halves, one map per column (:func:`_join_map`)."""
    s, W, R = aut.s, fr.cols, fr.rows
    torus = starts is not None
    map_id, indptr, indices, weights = _build_maps(fr, aut, torus)
    meet = not torus and _meets_in_middle(fr, aut)
    if meet:
        join_row, indptr, indices, weights = _with_map(indptr, indices, weights, *_join_map(fr, aut), W)

    # H masks: one per distinct row of limits; with several, rebuilt from the class patterns.
    row_key: list[bytes] = []
    valid: dict[bytes, np.ndarray] = {}
    single_mask = pat = None
    if fr.H:
        member = np.array([c.member for c in fr.H], dtype=np.bool_)
        lims = np.stack([c.limit for c in fr.H])  # (nH, R, W)
        row_key = [lims[:, r, :].tobytes() for r in range(R)]
        for r, key in enumerate(row_key):
            if key not in valid:
                valid[key] = _row_valid(fr.K, W, member, np.ascontiguousarray(lims[:, r, :]), fr.cyclic)
        pat = _class_patterns(aut.state_cls, fr.K, W)
        if len(valid) == 1:
            single_mask = valid[row_key[0]][pat]
            pat = None

    primes = _primes(n_primes)
    bounds = _axis_groups(s, W)
    chunk = _CHUNK
    sc1 = np.empty(max(2 * chunk, s ** int(np.diff(bounds).max())), dtype=np.int64)
    sc2 = np.empty_like(sc1)
    t = np.empty(s**W, dtype=np.int64)
    no_mask = np.ones(1, dtype=np.uint8)
    residues = []
    profiles, mult = starts if torus else (np.zeros(1, dtype=np.int64), np.ones(1, dtype=np.int64))
    half = R // 2
    n_rows = R - half if meet else R  # meeting: the bottom half (the longer one), then the join
    total = len(primes) * (n_rows + meet) * len(profiles)
    done = 0
    cur_key, cur_mask = None, None
    for p in primes:
        acc = 0
        for sigma, w in zip(profiles.tolist(), mult.tolist()):
            t[:] = 0
            t[sigma] = 1
            top = None
            for r in range(n_rows):
                if meet and r == half:
                    top = t.copy()  # odd height: the top half is one row shorter
                mask = no_mask
                if fr.H:
                    if single_mask is not None:
                        mask = single_mask
                    else:
                        if cur_key != row_key[r]:
                            cur_key, cur_mask = row_key[r], valid[row_key[r]][pat]
                        mask = cur_mask
                _sweep_row(
                    t, s, bounds, map_id[r], indptr, indices, weights, np.int64(p), mask, bool(fr.H), sc1, sc2, chunk
                )
                done += 1
                if progress is not None:
                    progress(done, total)
                if deadline is not None:
                    deadline.check(f"counting ({done:,} of {total:,} row sweeps)")
            if meet:
                if top is None:
                    top = t.copy()
                _sweep_row(t, s, bounds, join_row, indptr, indices, weights, np.int64(p), no_mask, False, sc1, sc2,
                           chunk)
                acc += _dot_mod(top, t, p)
                del top
                done += 1
                if progress is not None:
                    progress(done, total)
            else:
                acc += w * (int(t[sigma]) if torus else int(_sum_mod(t, np.int64(p))))
        residues.append(acc % p)
    return _crt(residues, primes)


#: Meet in the middle when the problem reads the same upside down (see :func:`_transfer_count`).
_MEET_IN_MIDDLE = True
#: Most column states for which the join of the two halves is built (``states ** 2`` words).
_MEET_MAX_STATES = 64


def _meets_in_middle(fr: _Frame, aut: _Automaton) -> bool:
    """Whether the frame reads the same upside down, so its two halves give the same tensor.

    Rows reversed, the fixed cells and the ``H`` limits must stay the same, and every ``V``
    limit must be uniform (a run's limit then does not depend on the cell where it ends,
    hence not on the direction it is read in).
    """
    if not _MEET_IN_MIDDLE or fr.rows < 4 or aut.s > _MEET_MAX_STATES:
        return False
    if not (fr.fixed == fr.fixed[::-1]).all():
        return False
    if not all((c.limit == c.limit[::-1]).all() for c in fr.H):
        return False
    return all((c.limit == c.limit.flat[0]).all() for c in fr.V)


def _join_map(fr: _Frame, aut: _Automaton) -> tuple[list[int], list[int]]:
    """Which column states of the top half may meet which of the bottom half (CSR, symmetric).

    A state stands for every column word that reaches it, and words in one state have the same
    futures; so two states meet when the word of one, followed by the word of the other read
    backwards, breaks no ``V`` condition. One shortest word per state is enough.
    """
    K = fr.K
    word: dict[int, tuple[int, ...]] = {}
    frontier = []
    for cl in range(K):
        st = int(aut.start[0, cl])
        if st >= 0 and st not in word:
            word[st] = (cl,)
            frontier.append(st)
    while frontier:
        nxt = []
        for st in frontier:
            for cl in range(K):
                to = int(aut.trans[0, st, cl])
                if to >= 0 and to not in word:
                    word[to] = word[st] + (cl,)
                    nxt.append(to)
        frontier = nxt
    conds = [(c.member, int(c.limit.flat[0])) for c in fr.V if c.limit.flat[0] > 0]

    def ok(cells) -> bool:
        for member, lim in conds:
            run = 0
            for cl in cells:
                run = run + 1 if member[cl] else 0
                if run > lim:
                    return False
        return True

    indptr, ind = [0], []
    for j in range(aut.s):
        ind.extend(i for i in range(aut.s) if i in word and j in word and ok(word[j] + word[i][::-1]))
        indptr.append(len(ind))
    return indptr, ind


def _with_map(indptr, indices, weights, ptr, ind, W):
    """The CSR map tables with one more map (weights 1) and a row of ``W`` columns using it."""
    m = indptr.shape[0]
    width = max(indices.shape[1], len(ind))
    grown = np.zeros((m + 1, width), dtype=np.int64)
    grown[:m, : indices.shape[1]] = indices
    grown[m, : len(ind)] = ind
    return (np.full(W, m, dtype=np.int64), np.vstack([indptr, np.array(ptr, dtype=np.int64)]), grown,
            np.vstack([weights, np.ones(weights.shape[1], dtype=np.int64)]))


def _dot_mod(a: np.ndarray, b: np.ndarray, p: int) -> int:
    """``sum(a * b) mod p`` for residues below ``p < 2**62`` (exact; see :func:`_dot_parts`)."""
    h2, l2, h1, l1, h0, l0 = (int(v) for v in _dot_parts(a, b))
    return ((h2 << 64 | l2) * 2**62 + (h1 << 64 | l1) * 2**31 + (h0 << 64 | l0)) % p


#: Tighten the prime count with strip counts (see :func:`_strip_bound`).
_STRIP_BOUND = True
#: Scratch block (entries) for one group of axes: two such int64 blocks should sit in L2.
_CHUNK = 1 << 15
#: Largest extent of one group of axes (entries).
_GROUP = 1 << 10


def _axis_groups(s: int, W: int) -> np.ndarray:
    """Split the ``W`` tensor axes into consecutive groups of extent at most ``_GROUP``."""
    if s <= 1:
        return np.array([0, W], dtype=np.int64)
    per = max(1, int(math.log(_GROUP) / math.log(s) + 1e-9))
    n_groups = -(-W // per)
    edges = [round(i * W / n_groups) for i in range(n_groups + 1)]
    return np.array(edges, dtype=np.int64)


def _big(n: int) -> str:
    return f"{n:,}" if n < 10**6 else (f"{float(n):.2g}" if n.bit_length() < 1000 else f"2^{n.bit_length() - 1}")


def enumeration_guard(problem: DappledProblem, *, time_limit: float | None = None, force: bool = False,
                      why: str | None = None) -> None:
    """Say before it starts when a count can only enumerate, and how long that may take.

    Counting by enumeration finds the tilings one at a time (a SAT call and a blocking clause
    each, about :data:`ENUMERATION_RATE` a second), so its time grows with the count itself.
    The estimate uses the rigorous upper bound of the transfer-matrix planner (the product of
    the single-line counts, global counts and targets left out). Enumerations estimated at
    more than :data:`ENUMERATION_FREE_S` seconds start only with a time limit (the run then
    ends ``unknown`` with the tilings found so far) or with ``force``.

    Parameters
    ----------
    problem : DappledProblem
    time_limit : float, optional
    force : bool
    why : str, optional
        Why the transfer matrix does not apply (starts the message).

    Raises
    ------
    MethodNotApplicable
        Without a time limit or ``force``, when the estimate is above the threshold.

    Examples
    --------
    >>> from tilesolve.model.dappled import DappledProblem
    >>> p = DappledProblem.from_strings("12x12", ["H0=2", "V1=2"], counts=["1=70"])
    >>> enumeration_guard(p, time_limit=5)
    >>> enumeration_guard(p)
    Traceback (most recent call last):
    ...
    tilesolve.errors.MethodNotApplicable: only enumeration can count this problem, one tiling at a time: up to 6e+38 tilings (~1.9e+28 years at about 1000 a second); give a time limit (--time-limit) or force it (force=True, --force)
    """
    if time_limit is not None or force:
        return
    import dataclasses

    relaxed = dataclasses.replace(problem, counts=(), closest_to=None)
    bound = _count_bound(_frame_of(relaxed))
    seconds = bound / ENUMERATION_RATE
    if seconds <= ENUMERATION_FREE_S:
        return
    head = f"{why}; " if why else ""
    raise MethodNotApplicable(
        f"{head}only enumeration can count this problem, one tiling at a time: up to {_big(bound)} tilings "
        f"(~{_duration(seconds)} at about {ENUMERATION_RATE} a second); give a time limit (--time-limit) or force "
        "it (force=True, --force)"
    )
