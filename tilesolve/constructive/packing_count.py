"""Enumerating and counting tile packings, with and without symmetry (class notes §5.5.3).

The notes publish, for ``C = 2``: **32** corner packings, which "reduce to a single
fundamental solution" under the symmetries of the problem, and **203,520** Wang packings.

Enumeration is a backtracking search (the notes' own method, §5.5.3) that places tiles in
row-major order and checks each tile against its west and north neighbours, and against
the east/south neighbours across the torus seam on the last column/row. Translation
symmetry is used exactly: every packing holds tile 0 at exactly one cell, so the packings
are the translates of those with tile 0 at the origin, and ``total = C**4 * anchored``.

The symmetry group (§5.5.3: translation, rotation, reflection, permutation of the colours)
acts on packings; :func:`packing_orbits` counts its orbits by reducing each anchored packing
to a canonical form (the lexicographically least image, translated back to tile 0 at the
origin). Rotating or reflecting a packing rotates or reflects each tile too: a Wang tile
turned a quarter clockwise has ``N' = W, E' = N, S' = E, W' = S``; a corner tile has
``NE' = NW, SE' = NE, SW' = SE, NW' = SW``.

Written by hand because no library enumerates exact covers with toroidal adjacency; the
search is tiny for ``C = 2`` (the 16-tile set).
"""

from __future__ import annotations

import itertools
import time
from typing import Iterator

import numpy as np

from tilesolve.deadline import NO_LIMIT, Deadline
from tilesolve.errors import InvalidProblem
from tilesolve.constructive.packing import apply_symmetry, symmetry_tile_map
from tilesolve.model.solution import CountResult, Status
from tilesolve.model.tiles import TileSet

__all__ = [
    "PUBLISHED_COUNTS",
    "enumerate_packings",
    "count_packings",
    "symmetry_maps",
    "apply_symmetry",
    "packing_orbits",
]

#: Published totals (class notes §5.5.3): (kind, C) -> (packings, fundamental solutions or None).
PUBLISHED_COUNTS: dict[tuple[str, int], tuple[int, int | None]] = {
    ("corner", 2): (32, 1),
    ("wang", 2): (203_520, None),
}

#: Enumeration is exhaustive only for small sets; C = 3 already has astronomically many packings.
MAX_ENUMERATE_TILES = 16


def _compat(ts: TileSet) -> tuple[np.ndarray, np.ndarray]:
    """``east[a, b]``: tile b may sit east of a; ``south[a, b]``: b may sit south of a."""
    tab = ts.table()
    a, b = tab[:, None, :], tab[None, :, :]
    if ts.kind == "wang":  # N E S W
        east = a[..., 1] == b[..., 3]
        south = a[..., 2] == b[..., 0]
    else:  # NE SE SW NW
        east = (a[..., 0] == b[..., 3]) & (a[..., 1] == b[..., 2])
        south = (a[..., 2] == b[..., 3]) & (a[..., 1] == b[..., 0])
    return east, south


def enumerate_packings(kind: str, colors: int, *, anchored: bool = True, deadline: Deadline = NO_LIMIT,
                       stats: dict | None = None) -> Iterator[np.ndarray]:
    """Yield every packing (``anchored``: every packing with tile 0 at cell (0, 0)).

    Stops early, without raising, when ``deadline`` expires (``stats["complete"]`` is then False).

    Examples
    --------
    >>> sum(1 for _ in enumerate_packings("corner", 2))
    2
    """
    ts = TileSet(kind, colors)
    n = ts.n_tiles
    if n > MAX_ENUMERATE_TILES:
        raise InvalidProblem(
            f"enumerating all packings of {n} tiles is out of reach (the notes call it hopeless for C=3); "
            "counting is supported for C=2"
        )
    side = colors * colors
    east, south = _compat(ts)
    east_l = [np.flatnonzero(east[t]).tolist() for t in range(n)]
    south_l = [np.flatnonzero(south[t]).tolist() for t in range(n)]
    grid = [-1] * n
    used = [False] * n
    stats = stats if stats is not None else {}
    stats["complete"] = False
    stats["nodes"] = 0
    cells = list(range(n))

    def candidates(p: int):
        r, c = divmod(p, side)
        if c > 0:
            cand = east_l[grid[p - 1]]
        elif r > 0:
            cand = south_l[grid[p - side]]
        else:
            cand = range(n)
        out = []
        for t in cand:
            if used[t]:
                continue
            if r > 0 and not south[grid[p - side], t]:
                continue
            if c == side - 1 and not east[t, grid[p - c]]:
                continue
            if r == side - 1 and not south[t, grid[c]]:
                continue
            out.append(t)
        return out

    stopped = [False]

    def rec(k: int) -> Iterator[np.ndarray]:
        if k == n:
            yield np.asarray(grid, dtype=np.int64).reshape(side, side)
            return
        stats["nodes"] += 1
        if stats["nodes"] % 4096 == 0 and deadline.expired():
            stopped[0] = True
            return
        p = cells[k]
        for t in candidates(p):
            grid[p] = t
            used[t] = True
            yield from rec(k + 1)
            used[t] = False
            grid[p] = -1
            if stopped[0]:
                return

    if anchored:
        grid[0], used[0] = 0, True
        yield from rec(1)
    else:
        yield from rec(0)
    stats["complete"] = not stopped[0]


def symmetry_maps(kind: str, colors: int) -> list[tuple[str, int, bool, np.ndarray]]:
    """The non-translation symmetries: ``(name, quarter turns, mirrored, tile map)``.

    The grid is first mirrored left-right (if ``mirrored``), then turned ``quarter turns``
    times clockwise; ``tile map[t]`` is the image of tile ``t`` (colours permuted as well).
    ``8 * C!`` entries.
    """
    out = []
    for perm in itertools.permutations(range(colors)):
        for mirrored in (False, True):
            for turns in range(4):
                img = symmetry_tile_map(kind, colors, perm, mirrored, turns)
                name = f"colours {perm}, {'mirror, ' if mirrored else ''}{90 * turns} deg"
                out.append((name, turns, mirrored, img))
    return out


def _keys(grids: np.ndarray, n_tiles: int) -> np.ndarray:
    """Lexicographic keys of anchored grids ``(N, R, C)``: base-``n_tiles`` numbers as uint64."""
    flat = grids.reshape(grids.shape[0], -1).astype(np.uint64)
    key = np.zeros(flat.shape[0], dtype=np.uint64)
    for k in range(flat.shape[1]):
        key = key * np.uint64(n_tiles) + flat[:, k]
    return key


def _anchor_all(g: np.ndarray) -> np.ndarray:
    """Translate each grid of ``(N, R, C)`` so that tile 0 is at (0, 0)."""
    n, rows, cols = g.shape
    where = np.argmax(g.reshape(n, -1) == 0, axis=1)
    r0, c0 = np.divmod(where, cols)
    ii = (np.arange(rows)[None, :, None] + r0[:, None, None]) % rows
    jj = (np.arange(cols)[None, None, :] + c0[:, None, None]) % cols
    return g[np.arange(n)[:, None, None], ii, jj]


def packing_orbits(anchored_packings, kind: str, colors: int) -> list[np.ndarray]:
    """One representative (canonical form) per orbit of the full symmetry group.

    The canonical form of a packing is its least image (row-major, lexicographic) among the
    ``8 * C!`` rotations/reflections/colour permutations, translated to tile 0 at (0, 0).
    """
    grids = np.asarray(list(anchored_packings), dtype=np.int64)
    if grids.size == 0:
        return []
    n_tiles = TileSet(kind, colors).n_tiles
    if n_tiles ** grids[0].size > 2**64:
        raise InvalidProblem("orbit computation supports C=2 only")
    best = None
    best_grid = None
    for _, turns, mirrored, m in symmetry_maps(kind, colors):
        g = grids[:, :, ::-1] if mirrored else grids
        g = np.rot90(g, k=-turns, axes=(1, 2))
        g = _anchor_all(m[g])
        key = _keys(g, n_tiles)
        if best is None:
            best, best_grid = key, g.copy()
        else:
            better = key < best
            best = np.where(better, key, best)
            best_grid[better] = g[better]
    _, first = np.unique(best, return_index=True)
    return [best_grid[i] for i in sorted(first)]


def count_packings(kind: str, colors: int, *, up_to_symmetry: bool = False,
                   deadline: Deadline = NO_LIMIT) -> CountResult:
    """Count all packings of the complete set over ``colors`` colours (C = 2).

    The value counts packings (or orbits, with ``up_to_symmetry``); ``stats`` holds
    ``anchored`` (packings with tile 0 at the origin) and ``nodes`` (search nodes). Status
    ``unknown`` with value ``None`` when the run's ``deadline`` stopped the enumeration.

    Examples
    --------
    >>> count_packings("corner", 2).value, count_packings("corner", 2, up_to_symmetry=True).value
    (32, 1)
    """
    t0 = time.perf_counter()
    stats: dict = {}
    anchored = list(enumerate_packings(kind, colors, deadline=deadline, stats=stats))
    figures = {"anchored": len(anchored), "nodes": stats["nodes"]}
    if not stats["complete"]:
        return CountResult(None, Status.UNKNOWN, "backtrack", time.perf_counter() - t0,
                           f"time limit of {deadline.time_limit:.3g} s reached", figures)
    n = TileSet(kind, colors).n_tiles
    value = len(packing_orbits(anchored, kind, colors)) if up_to_symmetry else n * len(anchored)
    return CountResult(value, Status.SAT, "backtrack", time.perf_counter() - t0, None, figures)
