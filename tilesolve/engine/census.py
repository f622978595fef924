"""The engine of the census of small Wang tile sets (issue 20 §4): the sets up to symmetry,
and the runs that classify them on local cores or a Dask cluster.

Sets up to symmetry
    A tile ``(N, E, S, W)`` takes its N and S colours from the horizontal edges' palette and
    its E and W colours from the vertical edges' one, each ``0 .. K-1``; it is numbered
    ``((N * K + E) * K + S) * K + W``. Two sets are the same question (they tile the same
    squares and tori, turned) when one is the other with the colours of each axis relabelled,
    or turned or mirrored as a whole (the dihedral group of the square; a quarter turn moves
    the horizontal colours onto vertical edges, so it swaps the two palettes).
    :func:`symmetries` lists that group as permutations of the tiles (``8 * K!^2`` of them for
    ``K >= 2``; one for ``K = 1``, whose one tile all fix); a set's *canonical* form is the
    least, in lexicographic order, of its images' sorted tile numbers, and
    :func:`canonical_sets` keeps exactly the sets that are their own canonical form: one a class.

Runs (:func:`run_jobs`)
    The sets are cut into jobs of :data:`CHUNK`, run on local worker processes or as Dask
    futures by the machinery of the period sweep (:mod:`tilesolve.engine.aperiodic`), and each
    job's records are handed to the caller as it ends (who appends them to the census file): a
    stopped run loses at most the jobs under way. What a record holds and how it is certified is
    the caller's (:mod:`tilesolve.families.aperiodic_census`).

Examples
--------
>>> [len(canonical_sets(n, 2)) for n in (1, 2, 3)]
[3, 13, 36]
"""

from __future__ import annotations

import functools
import itertools
from typing import Callable

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.model.run import RunOptions

__all__ = ["symmetries", "canonical_sets", "tiles_of", "run_jobs", "CHUNK", "MAX_SETS"]

#: Sets a job classifies (one task of a worker; a killed worker loses at most one job's work).
CHUNK = 8
#: Most candidate sets (before symmetry) one census enumerates: C(K^4, N).
MAX_SETS = 5_000_000


def _tiles(k: int) -> np.ndarray:
    """``(K^4, 4)`` the tiles ``(N, E, S, W)`` by number."""
    return np.stack(np.unravel_index(np.arange(k ** 4), (k,) * 4), axis=1).astype(np.int64)


def symmetries(k: int) -> np.ndarray:
    """The symmetry group of sets of tiles over ``k`` colours per axis, as ``(G, K^4)``
    permutations of the tile numbers (distinct rows): a relabelling of each axis's colours,
    then a mirror (E and W swapped) or not, then 0 to 3 quarter turns clockwise (the W colour
    becomes the N colour).

    >>> symmetries(2).shape, symmetries(3).shape
    ((32, 16), (288, 81))
    """
    if int(k) < 1:
        raise InvalidProblem(f"colours per axis must be at least 1, got {k}")
    t = _tiles(k)
    out = []
    for h in itertools.permutations(range(k)):
        for v in itertools.permutations(range(k)):
            rh, rv = np.array(h), np.array(v)
            image = np.stack([rh[t[:, 0]], rv[t[:, 1]], rh[t[:, 2]], rv[t[:, 3]]], axis=1)
            for mirrored in (image, image[:, [0, 3, 2, 1]]):
                x = mirrored
                for _ in range(4):
                    out.append(np.ravel_multi_index(tuple(x.T), (k,) * 4))
                    x = x[:, [3, 0, 1, 2]]  # a quarter turn clockwise: N <- W, E <- N, S <- E, W <- S
    return np.unique(np.array(out, dtype=np.int64), axis=0)


def canonical_sets(n_tiles: int, k: int) -> np.ndarray:
    """``(M, n_tiles)`` sorted tile numbers of one set per symmetry class (its canonical form,
    module docstring), in lexicographic order.

    Every set of ``n_tiles`` distinct tiles is compared with its images under each symmetry in
    turn, and dropped at the first image that is smaller (most fall within a few).
    """
    n_tiles, k = int(n_tiles), int(k)
    if n_tiles < 1:
        raise InvalidProblem(f"a census needs at least 1 tile a set, got {n_tiles}")
    m = k ** 4
    from math import comb

    if comb(m, n_tiles) > MAX_SETS:
        raise InvalidProblem(f"{comb(m, n_tiles):,} sets of {n_tiles} tiles over {k} colours per axis are more "
                             f"than {MAX_SETS:,} to enumerate")
    sets = np.fromiter(itertools.chain.from_iterable(itertools.combinations(range(m), n_tiles)), np.int64)
    sets = sets.reshape(-1, n_tiles)
    weight = np.int64(m) ** np.arange(n_tiles - 1, -1, -1, dtype=np.int64)
    key = sets @ weight
    for perm in symmetries(k):
        least = key <= np.sort(perm[sets], axis=1) @ weight
        sets, key = sets[least], key[least]
    return sets


def tiles_of(numbers, k: int) -> np.ndarray:
    """``(n, 4)`` the tiles ``(N, E, S, W)`` with these numbers."""
    return _tiles(int(k))[np.asarray(numbers, dtype=np.int64)]




def _chunk(job: Callable[[list], list], chunks: list, *, seed: int) -> list:
    """Job ``seed`` of a run: ``job`` on its chunk of sets."""
    return job(chunks[seed])


def run_jobs(sets: list, job: Callable[[list], list], run: RunOptions, take: Callable[[list], None],
             show: Callable[[], None] = lambda: None) -> bool:
    """Run ``job`` (picklable: it goes to worker processes) on every chunk of :data:`CHUNK`
    ``sets``; ``take(records)`` receives each job's records in the calling process as the job
    ends, ``show()`` is called as they come. ``run.cluster`` (a Dask scheduler address or client)
    runs them as Dask futures, else ``run.workers`` local processes (default 2; 1 runs here)
    (:func:`tilesolve.engine.aperiodic.dispatch`); ``run.deadline`` stops giving out jobs.
    Returns True when Ctrl-C stopped the run.
    """
    from tilesolve.engine.aperiodic import dispatch

    chunks = [sets[i:i + CHUNK] for i in range(0, len(sets), CHUNK)]

    def taken(i: int, records: list) -> bool:
        take(records)
        return False

    try:
        return dispatch(functools.partial(_chunk, job, chunks), len(chunks), run, taken, show)
    except KeyboardInterrupt:
        return True
