"""Independent checker for rectangular Wang and corner tilings (class notes §2.7).

A *grid tiling* is an array ``grid[row, col]`` of tile numbers, row 0 at the top (row
``r - 1`` lies north of row ``r``), over a tile set given by the colours of its tiles:

* Wang tiles (§2.7): ``tiles[k] = (c_N, c_E, c_S, c_W)``; the E edge of a cell must equal the
  W edge of its eastern neighbour and the S edge must equal the N edge of the cell below.
* corner tiles (§2.7): ``tiles[k] = (c_NE, c_SE, c_SW, c_NW)``, the order of eq. 2.5 and of
  :class:`tilesolve.model.tiles.TileSet`; each corner is shared by up to four cells, and it
  suffices to check the two corners along each shared edge: NE/SE of a cell against NW/SW
  of its eastern neighbour, SW/SE against NW/NE of the cell below.

``toroidal=True`` also compares the last column with the first and the last row with the
first (a tiling of the torus). Written from the definitions with numpy only; it imports
neither the tile models nor the generators it checks.
"""

from __future__ import annotations

import numpy as np

from tilesolve.verify.dappled import Violation

__all__ = ["grid_violations", "is_grid_tiling", "count_mismatches"]

# (own side, neighbour side, side names) for each neighbour direction; side = column of ``tiles``.
_WANG_EAST = ((1, 3, "E", "W"),)
_WANG_SOUTH = ((2, 0, "S", "N"),)
_CORNER_EAST = ((0, 3, "NE", "NW"), (1, 2, "SE", "SW"))
_CORNER_SOUTH = ((2, 3, "SW", "NW"), (1, 0, "SE", "NE"))


def _prepare(grid, tiles, kind: str, labels):
    """``(numbers, colours, problems)``: grid as row numbers of ``tiles``, or a shape/tile problem."""
    if kind not in ("wang", "corner"):
        return None, None, [Violation("shape", f"unknown tile kind {kind!r}; choose wang or corner")]
    t = np.asarray(tiles)
    if t.ndim != 2 or t.shape[1] != 4 or not np.issubdtype(t.dtype, np.integer):
        return None, None, [Violation("shape", "tile colours must be an (n_tiles, 4) integer array, "
                                               f"got shape {t.shape}")]
    g = np.asarray(grid)
    if g.ndim != 2:
        return None, None, [Violation("shape", f"grid must be 2-D, got shape {g.shape}")]
    if g.size and not np.issubdtype(g.dtype, np.integer):
        return None, None, [Violation("tile", "grid must hold integer tile numbers")]
    n = t.shape[0]
    if labels is None:
        bad = (g < 0) | (g >= n)
        k = np.where(bad, 0, g) if bad.any() else g
        what = f"0..{n - 1}"
    else:
        lab = np.asarray(labels, dtype=np.int64).reshape(-1)
        if lab.shape[0] != n:
            return None, None, [Violation("shape", f"{lab.shape[0]} labels for {n} tiles")]
        order = np.argsort(lab, kind="stable")
        pos = np.searchsorted(lab[order], g.astype(np.int64, copy=False)).clip(0, max(n - 1, 0))
        k = order[pos] if n else np.zeros_like(g)
        bad = (lab[k] != g) if n else np.ones(g.shape, dtype=bool)
        what = "the tile set"
    problems = [Violation("tile", f"tile {int(g[r, c])} is not in {what}", int(r), int(c))
                for r, c in np.argwhere(bad)]
    # The smallest integer type that holds the colours keeps big grids cheap to check.
    dt = np.min_scalar_type(int(t.max())) if t.size and int(t.min()) >= 0 else np.int64
    return k, t.astype(dt, copy=False), problems


def _mismatch_masks(k: np.ndarray, t: np.ndarray, kind: str, toroidal: bool):
    """Yield ``(mask, own, other, names, direction)`` for each side pair that must agree."""
    col = t[k] if k.size else np.zeros(k.shape + (4,), dtype=np.int64)
    east_pairs, south_pairs = (_WANG_EAST, _WANG_SOUTH) if kind == "wang" else (_CORNER_EAST, _CORNER_SOUTH)
    if toroidal:
        east = np.roll(col, -1, axis=1)
        south = np.roll(col, -1, axis=0)
        here_e = here_s = col
    else:
        east, here_e = col[:, 1:], col[:, :-1]
        south, here_s = col[1:, :], col[:-1, :]
    for own, other, pairs, direction in ((here_e, east, east_pairs, "east"), (here_s, south, south_pairs, "south")):
        for a, b, na, nb in pairs:
            yield own[..., a] != other[..., b], own[..., a], other[..., b], (na, nb), direction


def grid_violations(tiles, grid, *, kind: str = "wang", toroidal: bool = False, labels=None,
                    limit: int | None = None) -> list[Violation]:
    """Every way ``grid`` fails to be a tiling, with positions; empty when it is one.

    Parameters
    ----------
    grid : array-like of int
        ``grid[row, col]``, row 0 at the top: the number of the tile at each cell.
    tiles : array-like of int, shape (n_tiles, 4)
        Colours of each tile: ``(N, E, S, W)`` edges for Wang tiles, ``(NE, SE, SW, NW)``
        corners for corner tiles (eq. 2.1 / 2.5 digit order).
    kind : {"wang", "corner"}
    toroidal : bool
        Also match the last column against the first and the last row against the first.
    labels : array-like of int, optional
        Tile ``k`` appears in ``grid`` as ``labels[k]`` (e.g. the eq. 2.1 indices of a compact
        set, :attr:`TileSet.indices`) instead of as ``k``.
    limit : int, optional
        Stop after this many violations (a corrupt gigantic grid would list millions).

    Returns
    -------
    list of Violation
        kinds ``"shape"``, ``"tile"`` (number outside the set) and ``"match"`` (the western
        or northern cell of a pair whose shared edge or corner colours differ).

    Examples
    --------
    >>> tiles = [[0, 0, 0, 0], [0, 1, 0, 1]]         # N, E, S, W
    >>> grid_violations(tiles, [[0, 0], [0, 1]])      # tile 1 (W = 1) east of tile 0 (E = 0)
    [Violation(kind='match', message='E colour 0 meets W colour 1 of the cell to the east', row=1, col=0)]
    >>> grid_violations(tiles, [[1, 1]], toroidal=True)
    []
    """
    k, t, problems = _prepare(grid, tiles, kind, labels)
    if k is None or problems:
        return problems[:limit] if limit is not None else problems
    out: list[Violation] = []
    for bad, a, b, (na, nb), direction in _mismatch_masks(k, t, kind, toroidal):
        where = "the cell to the east" if direction == "east" else "the cell below"
        for r, c in np.argwhere(bad)[:limit]:
            out.append(Violation("match", f"{na} colour {int(a[r, c])} meets {nb} colour {int(b[r, c])} of {where}",
                                 int(r), int(c)))
    out.sort(key=lambda v: (v.row, v.col))
    return out[:limit]


def count_mismatches(tiles, grid, *, kind: str = "wang", toroidal: bool = False, labels=None) -> int:
    """Number of violations :func:`grid_violations` would list, without building them (-1 on a shape error)."""
    k, t, problems = _prepare(grid, tiles, kind, labels)
    if k is None:
        return -1
    if problems:
        return len(problems)
    return int(sum(int(bad.sum()) for bad, *_ in _mismatch_masks(k, t, kind, toroidal)))


def is_grid_tiling(tiles, grid, *, kind: str = "wang", toroidal: bool = False, labels=None) -> bool:
    """True when ``grid`` is a valid tiling (see :func:`grid_violations`)."""
    return count_mismatches(tiles, grid, kind=kind, toroidal=toroidal, labels=labels) == 0
