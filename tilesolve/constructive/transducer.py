"""Wang tile sets as transducers: the constructive route to "no tiling" and "periodic".

Jeandel and Rao, *An aperiodic set of 11 Wang tiles* (arXiv:1506.06492; Advances in
Combinatorics, 2021), §2-3; class notes Part II §8.2 for Wang's procedure this route decides in
part. meyerphi/tiling implements the same search (without minimisation) in C++; its test sets
are this module's test data.

A Wang tile ``(N, E, S, W)`` is a transition from state ``W`` to state ``E`` that reads ``N``
and writes ``S``: the tile set is a transducer ``T`` whose states are the horizontal (W/E)
colours (Jeandel and Rao read the bottom colour and write the top one; the direction only
decides which way rows are stacked). A bi-infinite path of ``T`` is a bi-infinite row of tiles; its input word is the row's
top colours and its output word the bottom colours. Composing ``T`` with itself ``k`` times
stacks rows: a transition of ``T^k`` is a column of ``k`` tiles that match vertically, reading
the top colour of the column and writing its bottom colour. So

* ``T^k`` has a bi-infinite path iff a bi-infinite strip of height ``k`` can be tiled; with no
  such strip the set tiles no plane;
* a cycle of ``T^k`` whose transitions each write what they read is a ``k x p`` block whose
  bottom matches its top and whose right side matches its left: a torus, so a periodic tiling.

Each step keeps what can lie on a bi-infinite path and merges what behaves alike
(Jeandel-Rao §3):

* *simplify*: only transitions on cycles (both ends in one strongly connected component) can
  lie on a bi-infinite path of a finite transducer, and a limit of shifts of any strip tiling
  uses only those (compactness);
* *minimise*: states with the same future (forward bisimilar: the same labels lead to
  equivalent states) are merged; bisimulation is a congruence for composition, so
  ``T_k = min(scc(T_{k-1} ∘ T_1))`` realises the same strips as the full ``T^k``.

Merged states would break a witness read off one column per transition, so every level keeps
the transitions it merged (:class:`Level`) and :func:`unfold` turns a periodic cycle of the
minimised ``T_k`` back into tiles: from any state of a class, bisimulation gives a transition
with the same label into the next class; following the cycle lap after lap until the state
at the start of a lap repeats gives a cycle of the unminimised level, whose upper part is a
cycle of ``T_{k-1}`` to unfold in turn (its length may grow by whole laps).

Verdicts
--------
``"empty"`` at ``k``: ``T_k`` has no transition. Every cycle of the full ``T^k`` projects to a
cycle of ``T_k`` (each row of a cyclic strip is a cyclic row, by induction on ``k``), so the
full ``T^k`` is acyclic: no ``k x w`` rectangle can be tiled for ``w`` one more than its
longest path. :func:`strip_width` computes that ``w`` (minimised, not simplified: forward
bisimulation keeps the longest path from every state); the certificate is that rectangle,
refuted independently (the aperiodicity family refutes it by SAT with a checked proof).

``"periodic"`` at ``k``: a tiling of a ``k x p`` torus as tile indices, checked independently
(:func:`torus_tiling` gives the leg colours for the board verifier).

``"undecided"``: neither up to the largest ``k`` reached (the ``k`` limit, the time limit or the
size limit stopped the search). Aperiodic sets stay undecided for every ``k``.

Examples
--------
>>> from tilesolve.model.board import WangTileSet
>>> ts = WangTileSet([[0, 0, 0, 0]], 1)  # one tile, all sides colour 0
>>> v = decide(ts, max_k=3)
>>> v.verdict, v.k, v.torus.tolist()
('periodic', 1, [[0]])
>>> stack = WangTileSet([[0, 0, 1, 0]], 2)  # N=0, S=1: rows never stack
>>> v = decide(stack, max_k=3)
>>> v.verdict, v.k, strip_width(stack, v.k)
('empty', 2, 1)
>>> stairs = WangTileSet([[0, 0, 1, 0], [1, 0, 0, 0]], 2)  # S=1 under N=1 and back
>>> v = decide(stairs, max_k=3)
>>> v.verdict, v.torus.tolist()
('periodic', [[0], [1]])
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from tilesolve.deadline import NO_LIMIT, Deadline, TimeLimitReached
from tilesolve.errors import InternalError, InvalidProblem
from tilesolve.model.board import WangTileSet

__all__ = [
    "Transducer", "Level", "TransducerVerdict", "tile_transducer", "compose", "simplify", "minimize",
    "periodic_cycle", "build_level", "unfold", "decide", "strip_width", "torus_tiling",
    "transducer_report", "DEFAULT_MAX_TRANSITIONS",
]

#: Largest number of candidate transitions one composition may build before the search stops
#: undecided (about 50 bytes each while it is built).
DEFAULT_MAX_TRANSITIONS = 20_000_000


@dataclass(frozen=True, eq=False)
class Transducer:
    """A letter-to-letter transducer: labelled transitions between numbered states.

    Attributes
    ----------
    n_states : int
        States are ``0 .. n_states-1``.
    src, dst, north, south : numpy.ndarray
        ``(n_transitions,)`` int64: a transition goes from ``src`` to ``dst`` reading the top
        colour ``north`` and writing the bottom colour ``south``.
    """

    n_states: int
    src: np.ndarray
    dst: np.ndarray
    north: np.ndarray
    south: np.ndarray

    @property
    def n_transitions(self) -> int:
        return int(self.src.size)

    def is_empty(self) -> bool:
        return self.src.size == 0

    def to_networkx(self):
        """The transitions as a :class:`networkx.MultiDiGraph` (``north``, ``south`` and the
        transition's ``index`` on each edge)."""
        import networkx as nx

        g = nx.MultiDiGraph()
        g.add_nodes_from(range(self.n_states))
        for i, (a, b, n, s) in enumerate(zip(self.src.tolist(), self.dst.tolist(), self.north.tolist(),
                                             self.south.tolist())):
            g.add_edge(a, b, north=n, south=s, index=i)
        return g


def _i64(a) -> np.ndarray:
    return np.ascontiguousarray(a, dtype=np.int64)


def tile_transducer(tileset: WangTileSet) -> Transducer:
    """``T``: one transition ``W -> E`` reading ``N``, writing ``S`` per tile (Jeandel-Rao §2);
    transition ``i`` is tile ``i`` of ``tileset.tiles``.

    Examples
    --------
    >>> t = tile_transducer(WangTileSet([[0, 1, 0, 1], [0, 0, 0, 0]], 2))  # N, E, S, W
    >>> t.n_states, t.src.tolist(), t.dst.tolist(), t.north.tolist(), t.south.tolist()
    (2, [1, 0], [1, 0], [0, 0], [0, 0])
    """
    t = _i64(tileset.tiles)  # N, E, S, W
    return Transducer(int(tileset.n_colors), _i64(t[:, 3]), _i64(t[:, 1]), _i64(t[:, 0]), _i64(t[:, 2]))


def _row_keys(rows: np.ndarray, sizes) -> np.ndarray | None:
    """One int64 key per row of non-negative ``rows`` whose column ``c`` is below ``sizes[c]``
    (mixed radix), or ``None`` when the keys could overflow."""
    total = 1
    for m in sizes:
        total *= max(int(m), 1)
    if total >= 2**62:
        return None
    key = np.zeros(rows.shape[0], np.int64)
    for c, m in enumerate(sizes):
        key = key * np.int64(max(int(m), 1)) + rows[:, c]
    return key


def _first_of_each(rows: np.ndarray, sizes) -> np.ndarray:
    """Sorted indices of the first occurrence of each distinct row."""
    key = _row_keys(rows, sizes)
    if key is None:
        _, first = np.unique(rows, axis=0, return_index=True)
    else:
        _, first = np.unique(key, return_index=True)
    return np.sort(first)


def _unique_rows(rows: np.ndarray, sizes) -> np.ndarray:
    """The distinct rows in lexicographic order (the mixed-radix key keeps that order)."""
    key = _row_keys(rows, sizes)
    if key is None:
        return np.unique(rows, axis=0)
    _, first = np.unique(key, return_index=True)
    return rows[first]


def _renumber(src: np.ndarray, dst: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Dense numbers for the states transitions touch: ``(src, dst, old number of each)``."""
    used, inv = np.unique(np.concatenate([src, dst]), return_inverse=True)
    inv = inv.astype(np.int64).ravel()
    return inv[: src.size], inv[src.size:], used


def compose(top: Transducer, bottom: Transducer, *, max_transitions: int = DEFAULT_MAX_TRANSITIONS,
            deadline: Deadline = NO_LIMIT) -> tuple[Transducer, np.ndarray, np.ndarray]:
    """``top ∘ bottom``: ``bottom``'s rows under ``top``'s, where ``top`` writes what ``bottom``
    reads. States are the pairs that transitions touch; transitions that agree on source,
    target, input and output are merged. ``deadline`` is checked between the passes over the
    candidate transitions (each a sort or a few array operations).

    Returns
    -------
    (Transducer, numpy.ndarray, numpy.ndarray)
        The composition, and for each of its transitions the ``top`` and ``bottom``
        transitions it is made of (the first such pair).

    Raises
    ------
    InvalidProblem
        When more than ``max_transitions`` candidate transitions would be built.
    TimeLimitReached
        When ``deadline`` passes.

    Examples
    --------
    >>> t = tile_transducer(WangTileSet([[0, 0, 0, 0]], 1))
    >>> c, i, j = compose(t, t)
    >>> c.n_states, c.n_transitions, i.tolist(), j.tolist()
    (1, 1, [0], [0])
    """
    n_colours = int(max(top.south.max(initial=-1), bottom.north.max(initial=-1), top.north.max(initial=-1),
                        bottom.south.max(initial=-1))) + 1
    order = np.argsort(bottom.north, kind="stable")
    counts = np.bincount(bottom.north, minlength=n_colours)
    starts = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
    per_top = counts[top.south].astype(np.int64)
    total = int(per_top.sum())
    if total > max_transitions:
        raise InvalidProblem(f"a composition would have {total:,} candidate transitions, "
                             f"more than the limit of {max_transitions:,}")
    doing = f"composing ({total:,} candidate transitions)"
    deadline.check(doing)
    i = np.repeat(np.arange(top.src.size, dtype=np.int64), per_top)
    offset = np.arange(total, dtype=np.int64) - np.repeat(np.cumsum(per_top) - per_top, per_top)
    j = order[starts[top.south[i]] + offset]
    nb = np.int64(bottom.n_states)
    deadline.check(doing)
    src, dst, _ = _renumber(top.src[i] * nb + bottom.src[j], top.dst[i] * nb + bottom.dst[j])
    n = np.int64(max(int(src.max(initial=-1)), int(dst.max(initial=-1))) + 1)
    north, south = top.north[i], bottom.south[j]
    nv = np.int64(max(n_colours, 1))
    deadline.check(doing)
    first = _first_of_each(np.stack([src, dst, north, south], axis=1), [n, n, nv, nv])
    deadline.check(doing)
    src, dst, used = _renumber(src[first], dst[first])
    return Transducer(int(used.size), src, dst, north[first], south[first]), i[first], j[first]


def _out_edges(src: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Compressed rows of the edges ``src -> ...`` over ``n`` states: ``(indptr, order)``, the
    edges out of state ``v`` being ``order[indptr[v]:indptr[v + 1]]`` (in their given order)."""
    indptr = np.zeros(n + 1, np.int64)
    np.cumsum(np.bincount(src, minlength=n), out=indptr[1:])
    return indptr, np.argsort(src, kind="stable")


def _components(src: np.ndarray, dst: np.ndarray, n: int) -> np.ndarray:
    """The strongly connected component of each of ``n`` states of the graph of edges
    ``src -> dst`` (Tarjan's algorithm, compiled for large graphs: :mod:`._transducer_kernels`)."""
    from tilesolve.constructive._transducer_kernels import KERNELS

    indptr, order = _out_edges(src, n)
    return KERNELS.pick(n + src.size).scc_labels(indptr, _i64(dst[order]), n)


def simplify(t: Transducer) -> np.ndarray:
    """Indices of the transitions of ``t`` that lie on a cycle: both ends in one strongly
    connected component (Jeandel-Rao's simplification).

    Examples
    --------
    >>> ts = WangTileSet([[0, 0, 0, 0], [0, 1, 0, 0]], 2)  # the second goes from 0 to 1
    >>> simplify(tile_transducer(ts)).tolist()
    [0]
    """
    label = _components(t.src, t.dst, t.n_states)
    return np.flatnonzero(label[t.src] == label[t.dst])


def _is_stable(cls: np.ndarray, src: np.ndarray, label: np.ndarray, dst: np.ndarray, n_labels: int) -> bool:
    """Exact check that the partition ``cls`` is a forward bisimulation: every state has the
    same set of ``(label, class of target)`` as its class as a whole."""
    n, m = cls.size, int(cls.max(initial=-1)) + 1
    per_state = _unique_rows(np.stack([src, label, cls[dst]], axis=1), [n, n_labels, m])
    per_class = _unique_rows(np.stack([cls[per_state[:, 0]], per_state[:, 1], per_state[:, 2]], axis=1),
                             [m, n_labels, m])
    n_state = np.bincount(per_state[:, 0], minlength=n)
    n_class = np.bincount(per_class[:, 0], minlength=m)
    return bool(np.array_equal(n_state, n_class[cls]))


def _refine(cls: np.ndarray, sig: np.ndarray) -> np.ndarray:
    """Classes of the pairs ``(cls, sig)``, numbered in their lexicographic order (as
    ``numpy.unique(..., axis=0)`` numbers them, by two sorts of integers instead of one of
    rows): ``sig`` replaced by its rank, each pair is one mixed-radix key."""
    ranks, rank = np.unique(sig, return_inverse=True)
    _, new = np.unique(cls * np.int64(ranks.size) + rank.ravel(), return_inverse=True)
    return new.astype(np.int64).ravel()


def minimize(t: Transducer, *, deadline: Deadline = NO_LIMIT) -> np.ndarray:
    """The coarsest forward bisimulation of ``t`` (Jeandel-Rao §3): ``(n_states,)`` class of
    each state, numbered ``0 .. m-1``. States with the same future (for every transition of one,
    a transition of the other with the same input and output into an equivalent state) share
    a class.

    Partition refinement: each round splits classes by a 64-bit signature of the set of
    ``(label, class of target)`` of each state; the final partition is checked exactly (a
    signature collision would merge unequal states) and refined again with fresh
    multipliers if the check fails. ``deadline`` is checked before every round
    (:class:`~tilesolve.deadline.TimeLimitReached`).

    Examples
    --------
    >>> t = tile_transducer(WangTileSet([[0, 0, 0, 0], [0, 1, 0, 1]], 2))
    >>> minimize(t).tolist()  # colours 0 and 1 both loop reading and writing 0
    [0, 0]
    """
    n = t.n_states
    if n == 0:
        return np.zeros(0, np.int64)
    nv = int(max(t.north.max(initial=0), t.south.max(initial=0))) + 1
    label = t.north * np.int64(nv) + t.south
    salt = 0
    while True:
        mult = np.random.default_rng(0x7A45 + salt).integers(1, 2**62, size=2, dtype=np.int64) | 1
        cls = np.zeros(n, np.int64)
        n_cls = 1
        while True:
            deadline.check(f"minimising {t.n_transitions:,} transitions ({n_cls:,} classes of {n:,} states)")
            pairs = _unique_rows(np.stack([t.src, label, cls[t.dst]], axis=1), [n, nv * nv, n_cls])
            with np.errstate(over="ignore"):
                x = (pairs[:, 1] * mult[0] + pairs[:, 2] + 1) * mult[1]
                x ^= x >> np.int64(29)
                x *= mult[0]
            sig = np.zeros(n, np.int64)
            if pairs.size:  # rows are grouped by state: one sum per state that has transitions
                starts = np.flatnonzero(np.r_[True, pairs[1:, 0] != pairs[:-1, 0]])
                with np.errstate(over="ignore"):
                    sig[pairs[starts, 0]] = np.add.reduceat(x, starts)
            cls = _refine(cls, sig)
            m = int(cls.max()) + 1
            if m == n_cls:
                break
            n_cls = m
        deadline.check(f"minimising {t.n_transitions:,} transitions (checking {n_cls:,} classes)")
        if _is_stable(cls, t.src, label, t.dst, nv * nv):
            return cls
        salt += 1


def periodic_cycle(t: Transducer) -> np.ndarray | None:
    """Indices of the transitions of a cycle of ``t`` each of which writes what it reads, in
    order along the cycle, or ``None``. A loop if there is one; else each strongly connected
    part of those transitions gives a shortest cycle through its least state (one breadth-first
    search from all of these states at once, each staying in its part), and the shortest of
    these is returned (ties: the least start state).

    Examples
    --------
    >>> t = Transducer(3, *(np.array(a) for a in ([0, 1, 2, 1], [1, 2, 0, 0], [0, 0, 0, 1], [0, 0, 0, 0])))
    >>> periodic_cycle(t).tolist()  # 0 -> 1 -> 2 -> 0; the shortcut 1 -> 0 reads 1, writes 0
    [0, 1, 2]
    """
    same = np.flatnonzero(t.north == t.south)
    loops = same[t.src[same] == t.dst[same]]
    if loops.size:
        return loops[:1]
    n = t.n_states
    label = _components(t.src[same], t.dst[same], n)
    same = same[label[t.src[same]] == label[t.dst[same]]]  # the transitions inside the parts
    if same.size == 0:
        return None
    src, dst = t.src[same], t.dst[same]
    start = np.full(n, n, np.int64)
    np.minimum.at(start, label[src], src)  # the least state of each part, by the part's label
    sources = np.unique(start[label[src]])
    indptr, order = _out_edges(src, n)
    dist = np.full(n, -1, np.int64)
    parent = np.full(n, -1, np.int64)  # the edge (into ``same``) that first reached each state
    dist[sources] = 0
    frontier, d = sources, 0
    while frontier.size:
        lo, count = indptr[frontier], indptr[frontier + 1] - indptr[frontier]
        at = np.repeat(lo - np.cumsum(count) + count, count) + np.arange(int(count.sum()), dtype=np.int64)
        e = order[at]
        e = e[dist[dst[e]] == -1]
        frontier, first = np.unique(dst[e], return_index=True)
        d += 1
        dist[frontier], parent[frontier] = d, e[first]
    closing = np.flatnonzero(dst == start[label[dst]])  # edges back into a part's least state
    best = closing[np.lexsort((src[closing], dst[closing], dist[src[closing]]))[0]]
    path = [int(best)]
    x = int(src[best])
    while dist[x] > 0:
        path.append(int(parent[x]))
        x = int(src[parent[x]])
    return same[np.asarray(path[::-1], np.int64)]


@dataclass(frozen=True, eq=False)
class Level:
    """One step of the search: ``T_k`` and what it was made of.

    Attributes
    ----------
    k : int
        Rows stacked.
    full : Transducer
        The simplified, unminimised level: ``scc(T_{k-1} ∘ T_1)`` (for ``k = 1``, ``scc(T)``).
    upper : numpy.ndarray
        For each transition of ``full``, the transition of the previous level's :attr:`quotient`
        above it (``-1`` for ``k = 1``).
    tile : numpy.ndarray
        For each transition of ``full``, the tile of its bottom row.
    cls : numpy.ndarray
        The class (state of :attr:`quotient`) of each state of ``full``.
    quotient : Transducer
        ``T_k``: ``full`` with the classes of :attr:`cls` merged (the minimised level).
    """

    k: int
    full: Transducer
    upper: np.ndarray
    tile: np.ndarray
    cls: np.ndarray
    quotient: Transducer


def _level(k: int, full: Transducer, upper: np.ndarray, tile: np.ndarray, minimise: bool,
           deadline: Deadline) -> Level:
    deadline.check(f"simplifying T_{k} ({full.n_transitions:,} transitions)")
    keep = simplify(full)
    deadline.check(f"simplifying T_{k} ({keep.size:,} of {full.n_transitions:,} transitions on cycles)")
    src, dst, _ = _renumber(full.src[keep], full.dst[keep])
    n = int(max(src.max(initial=-1), dst.max(initial=-1))) + 1
    full = Transducer(n, src, dst, full.north[keep], full.south[keep])
    upper, tile = upper[keep], tile[keep]
    deadline.check(f"minimising T_{k} ({full.n_transitions:,} transitions)")
    cls = minimize(full, deadline=deadline) if minimise else np.arange(n, dtype=np.int64)
    m = int(cls.max(initial=-1)) + 1
    nv = int(max(full.north.max(initial=0), full.south.max(initial=0))) + 1
    q = _unique_rows(np.stack([cls[full.src], cls[full.dst], full.north, full.south], axis=1), [m, m, nv, nv])
    return Level(k, full, upper, tile, cls, Transducer(m, _i64(q[:, 0]), _i64(q[:, 1]), _i64(q[:, 2]),
                                                       _i64(q[:, 3])))


def build_level(tileset: WangTileSet, previous: Level | None, *, minimise: bool = True,
                max_transitions: int = DEFAULT_MAX_TRANSITIONS, deadline: Deadline = NO_LIMIT) -> Level:
    """``T_1`` (``previous=None``) or ``T_{k+1}`` from ``T_k``: compose with ``T``, simplify, and
    minimise (or not: ``minimise=False`` keeps every state, for cross-checks). ``deadline`` is
    checked between the steps and within them (:class:`~tilesolve.deadline.TimeLimitReached`): no
    step runs longer than one sort of the level's transitions without a look at it."""
    base = tile_transducer(tileset)
    if previous is None:
        return _level(1, base, np.full(base.n_transitions, -1, np.int64), np.arange(base.n_transitions,
                                                                                    dtype=np.int64), minimise,
                      deadline)
    comp, i, j = compose(previous.quotient, base, max_transitions=max_transitions, deadline=deadline)
    return _level(previous.k + 1, comp, i, j, minimise, deadline)


def _unfold_one(level: Level, cycle: np.ndarray) -> np.ndarray:
    """A cycle of ``level.full`` whose image in the quotient is ``cycle`` (transitions of
    ``level.quotient``) repeated a whole number of times."""
    full, q, cls = level.full, level.quotient, level.cls
    lookup: dict[tuple[int, int, int, int], int] = {}
    for e, (a, b, n, s) in enumerate(zip(full.src.tolist(), cls[full.dst].tolist(), full.north.tolist(),
                                         full.south.tolist())):
        lookup.setdefault((a, n, s, b), e)
    want = [(int(q.north[e]), int(q.south[e]), int(q.dst[e])) for e in cycle.tolist()]
    x = int(np.flatnonzero(cls == q.src[cycle[0]])[0])
    seen: dict[int, int] = {}
    path: list[int] = []
    while x not in seen:
        seen[x] = len(path)
        for n, s, b in want:
            e = lookup.get((x, n, s, b))
            if e is None:
                raise InternalError(f"level {level.k}: the minimised transducer is not a bisimulation quotient")
            path.append(e)
            x = int(full.dst[e])
    return np.asarray(path[seen[x]:], np.int64)


def unfold(levels: list[Level], cycle: np.ndarray) -> np.ndarray:
    """Tiles ``(k, p)`` (row 0 at the top) of the torus given by a periodic ``cycle`` of the
    last level's quotient: unfold level by level (:class:`Level`), then repeat each row up to
    the width of the widest."""
    rows: list[np.ndarray] = []
    cyc = np.asarray(cycle, np.int64)
    for level in reversed(levels):
        path = _unfold_one(level, cyc)
        rows.append(level.tile[path])
        cyc = level.upper[path]
    rows.reverse()
    width = max(r.size for r in rows)
    return np.stack([np.tile(r, width // r.size) for r in rows])


@dataclass(frozen=True)
class TransducerVerdict:
    """What the transducer search decided (Jeandel-Rao §3), with its certificate.

    Attributes
    ----------
    verdict : str
        ``"empty"`` (``T_k`` has no transition: the set tiles no plane), ``"periodic"`` (a
        torus) or ``"undecided"``.
    k : int
        The ``k`` of the verdict; for ``"undecided"``, the largest ``k`` whose ``T_k`` was built
        (0 when not even ``T_1`` was).
    torus : numpy.ndarray or None
        ``"periodic"`` only: ``(k, p)`` tile indices of a tiling of the ``k x p`` torus (row 0
        at the top), to be checked on ``Board.torus(p, k)``.
    reason : str
        Why the search stopped, in words.
    sizes : list of tuple
        ``(k, states, transitions)`` of each (minimised) ``T_k`` built.
    seconds : float
        Wall-clock time of the search.
    """

    verdict: str
    k: int
    torus: np.ndarray | None = None
    reason: str = ""
    sizes: list = field(default_factory=list)
    seconds: float = 0.0


def decide(tileset: WangTileSet, *, max_k: int = 30, deadline: Deadline = NO_LIMIT, minimise: bool = True,
           max_transitions: int = DEFAULT_MAX_TRANSITIONS) -> TransducerVerdict:
    """Search ``k = 1 .. max_k`` for an empty ``T_k`` or a periodic cycle (Jeandel-Rao §3).

    Parameters
    ----------
    tileset : WangTileSet
    max_k : int
        Largest number of stacked rows tried.
    deadline : Deadline, optional
        Checked between the steps of each level; when it has passed the verdict is
        ``"undecided"`` with the last ``k`` completed.
    minimise : bool
        Merge bisimilar states at every level (default); ``False`` keeps them (slower, the
        same verdicts).
    max_transitions : int
        Size limit of one composition (see :func:`compose`); reaching it ends the search
        undecided.

    Returns
    -------
    TransducerVerdict
    """
    if int(max_k) < 1:
        raise InvalidProblem(f"the largest k must be at least 1, got {max_k}")
    t0 = time.perf_counter()
    levels: list[Level] = []
    sizes: list[tuple[int, int, int]] = []

    def stop(verdict: str, reason: str, torus=None) -> TransducerVerdict:
        return TransducerVerdict(verdict, levels[-1].k if levels else 0, torus, reason, sizes,
                                 time.perf_counter() - t0)

    while True:
        try:
            deadline.check(f"building T_{len(levels) + 1}")
            level = build_level(tileset, levels[-1] if levels else None, minimise=minimise,
                                max_transitions=max_transitions, deadline=deadline)
        except (TimeLimitReached, InvalidProblem) as e:
            return stop("undecided", str(e))
        levels.append(level)
        q = level.quotient
        sizes.append((level.k, q.n_states, q.n_transitions))
        if q.is_empty():
            return stop("empty", f"T_{level.k} has no transition")
        cyc = periodic_cycle(q)
        if cyc is not None:
            torus = unfold(levels, cyc)
            return stop("periodic", f"T_{level.k} has a cycle that writes what it reads: a "
                                    f"{torus.shape[0]} x {torus.shape[1]} torus", torus)
        if level.k >= int(max_k):
            return stop("undecided", f"k limit {max_k} reached")


def strip_width(tileset: WangTileSet, k: int, *, max_transitions: int = DEFAULT_MAX_TRANSITIONS,
                deadline: Deadline = NO_LIMIT) -> int | None:
    """The least ``w`` such that no ``k x w`` rectangle can be tiled, or ``None`` when
    rectangles of height ``k`` and every width can (the full ``T^k`` has a cycle).

    The full ``T^k`` is built minimised but not simplified (forward bisimulation keeps the
    set of finite label sequences from each state, so the longest path); ``w`` is its
    longest path plus one. Raises :class:`InvalidProblem` past ``max_transitions`` and
    :class:`~tilesolve.deadline.TimeLimitReached` when ``deadline`` passes.

    Examples
    --------
    >>> strip_width(WangTileSet([[0, 1, 0, 0]], 2), 1)  # E=1 never meets W=0
    2
    """
    import networkx as nx

    if int(k) < 1:
        raise InvalidProblem(f"k must be at least 1, got {k}")
    base = tile_transducer(tileset)

    def quotient(t: Transducer) -> Transducer:
        cls = minimize(t, deadline=deadline)
        m = int(cls.max(initial=-1)) + 1
        nv = int(max(t.north.max(initial=0), t.south.max(initial=0))) + 1
        q = _unique_rows(np.stack([cls[t.src], cls[t.dst], t.north, t.south], axis=1), [m, m, nv, nv])
        return Transducer(m, _i64(q[:, 0]), _i64(q[:, 1]), _i64(q[:, 2]), _i64(q[:, 3]))

    t = quotient(base)
    for _ in range(int(k) - 1):
        if t.is_empty():
            return 1
        t = quotient(compose(t, base, max_transitions=max_transitions, deadline=deadline)[0])
    if t.is_empty():
        return 1
    g = nx.DiGraph()
    g.add_edges_from(zip(t.src.tolist(), t.dst.tolist()))
    if not nx.is_directed_acyclic_graph(g):
        return None
    return int(nx.dag_longest_path_length(g)) + 1


def torus_tiling(tileset: WangTileSet, torus) -> np.ndarray:
    """Leg colours ``(k * p, 4)`` (N, E, S, W, cells in row-major order) of the ``(k, p)`` tile
    indices ``torus``: the tiling of ``Board.torus(p, k)`` for the board verifier."""
    idx = np.asarray(torus, dtype=np.int64)
    return np.asarray(tileset.tiles, dtype=np.int64)[idx.ravel()]


#: How the conclusions of the transducer's reports without a certificate begin (an undecided
#: search, or an empty ``T_k`` with no rectangle to certify it): they claim nothing checkable.
UNDECIDED_OPENINGS = ("Undecided by the transducer up to k = ", "T_")


def transducer_report(problem, run, *, refute) -> tuple[str, object]:
    """The aperiodicity family's ``transducer`` route, given the SAT route to certify with.

    Searches ``k = 1 .. max_k`` (the run option ``max_k``; default the problem's
    ``max_period``, or ``max_square`` when no periods are asked) with :func:`decide`, then
    turns the verdict into certificates (:mod:`tilesolve.model.aperiodic`):

    * ``"periodic"``: the ``k x p`` torus witness (``periods``; the family's verifier checks
      it on the board);
    * ``"empty"``: the ``k x w`` rectangle of :func:`strip_width`, refuted by ``refute`` (the
      SAT route with a checked DRAT proof); the certificate keeps the proof's evidence and
      adds the transducer's (``transducer_k``, ``strip_width``). A rectangle that SAT tiles
      would contradict the transducer: :class:`InternalError`. When the full ``T^k`` is over
      the size limit there is no rectangle to certify: the verdict is returned as
      ``"undecided"`` and the conclusion says why;
    * ``"undecided"``: no certificate, the conclusion says up to which ``k``.

    Parameters
    ----------
    problem : AperiodicProblem
    run : RunOptions
    refute : callable
        ``refute(board_name, run) -> Certificate`` deciding a board by SAT (e.g.
        :func:`tilesolve.engine.aperiodic.decide` with the tile set bound).

    Returns
    -------
    (str, AperiodicReport)
        The verdict and the report.
    """
    from tilesolve.model.aperiodic import AperiodicReport, Certificate, rectangle_name

    ts = problem.tileset
    max_k = int(run.option("max_k", problem.max_period or problem.max_square))
    v = decide(ts, max_k=max_k, deadline=run.deadline)
    sizes = [list(map(int, s)) for s in v.sizes]
    ev = {"transducer_k": v.k, "reason": v.reason, "sizes": sizes, "transducer_s": round(v.seconds, 6)}
    literature = (problem.info or {}).get("literature")
    if v.verdict == "periodic":
        k, p = v.torus.shape
        cert = Certificate(f"torus {k}x{p}", "tiles", v.torus, "transducer", ev, round(v.seconds, 6))
        return v.verdict, AperiodicReport(periods=(cert,), conclusion=(
            f"The set tiles the {k}x{p} torus (found as a cycle of T_{v.k} that writes what it reads, "
            f"Jeandel-Rao): it tiles the plane periodically, so it is not aperiodic."), literature=literature)
    if v.verdict == "empty":
        try:
            w = strip_width(ts, v.k, deadline=run.deadline)
        except (InvalidProblem, TimeLimitReached) as exc:  # over the size or time limit: no rectangle to certify
            return "undecided", AperiodicReport(conclusion=(
                f"T_{v.k} is empty (Jeandel-Rao): no strip of height {v.k} can be tiled; the rectangle to "
                f"certify it could not be computed ({exc})."), literature=literature)
        if w is None:
            raise InternalError(f"T_{v.k} is empty but the full T^{v.k} has a cycle")
        name = rectangle_name(v.k, w)
        sat = refute(name, run)
        if sat.status == "tiles":
            raise InternalError(f"the transducer says no {v.k}x{w} rectangle can be tiled, SAT tiled one")
        cert = Certificate(name, sat.status, None, "sat+transducer", {**sat.evidence, **ev, "strip_width": w},
                           round(v.seconds + sat.time_s, 6))
        if sat.status == "refuted":
            text = (f"T_{v.k} is empty (Jeandel-Rao): no strip of height {v.k} can be tiled, and the "
                    f"{v.k}x{w} rectangle is refuted with a checked proof, so the set tiles no plane.")
        else:
            text = (f"T_{v.k} is empty (Jeandel-Rao): no strip of height {v.k} can be tiled; the SAT "
                    f"refutation of the {v.k}x{w} rectangle is undecided ({sat.evidence.get('why', '')}).")
        return v.verdict, AperiodicReport(squares=(cert,), conclusion=text, literature=literature)
    return v.verdict, AperiodicReport(conclusion=(
        f"Undecided by the transducer up to k = {v.k} ({v.reason}): T_k is not empty and has no cycle that "
        f"writes what it reads, so the set tiles strips of every height up to {v.k} and no torus of "
        f"height at most {v.k}."), literature=literature)
