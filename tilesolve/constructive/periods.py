"""Periodic tilings found by lattice index: the few cells of one period, smallest first.

A periodic tiling repeats under a lattice of periods; the lattice's *index* is the number of
cells of one period (its fundamental domain). Every lattice of index ``n`` is one sheared
torus :class:`~tilesolve.model.aperiodic.Lattice` ``(p, q, s)`` with ``p * q = n`` and
``0 <= s < p`` (Hermite normal form, :mod:`tilesolve.model.aperiodic`), so the lattices of
index ``n`` number ``sigma(n)`` (the sum of the divisors of ``n``) and are only ``n`` cells
each. :func:`search` tries them for ``n = 1, 2, ...`` by backtracking with arc consistency
(:mod:`._period_kernels`), each within a budget of fixed tiles, and stops at the first one
tiled.

A tile set whose period is long in both directions may still have a lattice of small index:
``periodic-10-35`` tiles the 35 x 35 torus and no smaller rectangle, but its rows repeat with
a shift, so one row of 35 tiles is a whole period (the sheared torus 35 x 1, shear 8, index
35). The transducer route reaches its 35 x 35 torus at ``k = 35`` only through ``T_15``'s 2.5
million transitions, and the SAT sweep of the tori up to 35 x 35 found it in none of the times
tried; this search tries the 981 lattices of index at most 35 (benchmarks/bench_aperiodic_lattice.py).

The search only finds witnesses. A lattice left at the budget is not known to be untileable,
and one that the search exhausts is not reported as refuted either: refutations come from the
SAT route with checked proofs. A witness is checked like any other, by the family's verifier
on its board; :func:`rectangle` turns it into the plain torus it repeats to.

Examples
--------
>>> from tilesolve.model.board import WangTileSet
>>> ws = WangTileSet([[0, 0, 1, 0], [1, 0, 0, 0]], 2)  # N, E, S, W: rows alternate
>>> found = search(ws, 4)
>>> found.lattice, found.tiling.tolist(), found.tried
(Lattice(rows=2, cols=1, shear=0), [[0], [1]], 3)
>>> rectangle(Lattice(2, 1, 1), np.array([[0], [1]])).tolist()  # one column, shifted: 2 x 2
[[0, 1], [1, 0]]
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Iterator

import numpy as np

from tilesolve.deadline import NO_LIMIT, Deadline
from tilesolve.errors import InvalidProblem
from tilesolve.model.aperiodic import Lattice
from tilesolve.model.board import WangTileSet

__all__ = ["LatticeSearch", "lattices_by_index", "search", "rectangle", "NODE_BUDGET"]

#: Tiles the search of one lattice may fix before it leaves the lattice. The lattices that the
#: built-in periodic sets tile are found after 2-21 fixed tiles, 114 for periodic-10-127's; some
#: untileable ones of index above 60 need tens of thousands, so a larger budget costs far more
#: time on them and, on the built-in sets, finds no other witness.
NODE_BUDGET = 256


@dataclass(frozen=True)
class LatticeSearch:
    """What :func:`search` found.

    Attributes
    ----------
    lattice : Lattice or None
        The first lattice tiled (``None``: none).
    tiling : numpy.ndarray or None
        ``(rows, cols)`` tile indices of ``lattice`` (row 0 at the top).
    tried : int
        Lattices searched, the one tiled included.
    over_budget : int
        Lattices left at the node budget (neither tiled nor exhausted).
    index : int
        The index of the last lattice searched (0 when none).
    reason : str
        Why the search stopped, in words.
    seconds : float
        Wall-clock time of the search.
    """

    lattice: Lattice | None
    tiling: np.ndarray | None
    tried: int
    over_budget: int
    index: int
    reason: str
    seconds: float


def lattices_by_index(max_index: int) -> Iterator[Lattice]:
    """Every lattice of periods of index ``1 .. max_index``, by index, then rows, then shear.

    Examples
    --------
    >>> [lat.name() for lat in lattices_by_index(2)]
    ['torus 1x1', 'torus 1x2', 'torus 2x1', 'torus 2x1 shear 1']
    >>> sum(1 for _ in lattices_by_index(35))  # sigma(1) + ... + sigma(35)
    1007
    """
    for n in range(1, int(max_index) + 1):
        for p in range(1, n + 1):
            if n % p == 0:
                for s in range(p):
                    yield Lattice(p, n // p, s)


def search(tileset: WangTileSet, max_index: int, *, node_budget: int = NODE_BUDGET,
           deadline: Deadline = NO_LIMIT) -> LatticeSearch:
    """The first lattice of :func:`lattices_by_index` that ``tileset`` tiles (module docstring).

    Parameters
    ----------
    tileset : WangTileSet
    max_index : int
        The largest index (cells of one period) tried.
    node_budget : int
        Tiles the search of one lattice may fix before it moves on (:data:`NODE_BUDGET`).
    deadline : Deadline, optional
        Checked before every lattice; when it has passed the search stops without a witness.

    Returns
    -------
    LatticeSearch
    """
    from tilesolve.constructive._period_kernels import KERNELS

    if int(max_index) < 1 or int(node_budget) < 1:
        raise InvalidProblem(f"the lattice search needs an index and a node budget of at least 1, got "
                             f"{max_index} and {node_budget}")
    t0 = time.perf_counter()
    col = np.ascontiguousarray(tileset.tiles, dtype=np.int64)
    tried = over = index = 0
    for lat in lattices_by_index(max_index):
        if deadline.expired():
            return LatticeSearch(None, None, tried, over, index, f"time limit reached after {tried:,} lattices "
                                 f"(index up to {index})", time.perf_counter() - t0)
        n = lat.rows * lat.cols
        out = np.zeros(n, np.int64)
        found = KERNELS.pick(n).lattice_tiling(col, lat.rows, lat.cols, lat.shear, int(node_budget), out)
        tried, index = tried + 1, n
        if found == 1:
            return LatticeSearch(lat, out.reshape(lat.rows, lat.cols), tried, over, index,
                                 f"the {lat.name()} is tiled", time.perf_counter() - t0)
        over += found == -1
    return LatticeSearch(None, None, tried, over, index, f"no lattice of index at most {max_index} tiled "
                         f"({over:,} of {tried:,} left at the node budget of {node_budget})",
                         time.perf_counter() - t0)


def rectangle(lattice: Lattice, tiling) -> np.ndarray:
    """The tiling of ``lattice`` repeated to the plain torus it lies in: ``rows`` x
    ``cols * rows / gcd(rows, shear)`` (moving ``cols`` columns east moves ``shear`` rows south,
    so the rows repeat after ``rows / gcd(rows, shear)`` such steps)."""
    t = np.asarray(tiling, dtype=np.int64)
    p, s = int(lattice.rows), int(lattice.shear)
    laps = p // math.gcd(p, s)
    return np.concatenate([t[(np.arange(p) + k * s) % p] for k in range(laps)], axis=1)
