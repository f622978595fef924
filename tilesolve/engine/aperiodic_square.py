"""Squares' SAT searches steered by a tiling: a window of a known tiling (search ``"markov"``) or
the short rows and columns of a smaller witness (search ``"grams"``).

For a tile set that has a Markov partition (Jeandel-Rao and Labbé's U19; the window comes from
the constructive route, :mod:`tilesolve.families.aperiodic_square`, above this layer), the
square's *full* formula (the named encoding ``wang-tiles-cnf``, nothing removed) is solved with
the preferred phases of the window (:func:`window_phases`): every cell's window tile true, its
other tiles false. The phases only steer the solver's first choices; the answer is the
solver's, a witness is verified like any other, and an ``unsat`` answer would carry its DRAT
proof checked against the formula, so no verdict depends on the window. The window is a valid
tiling, so the solver meets no conflict on Jeandel-Rao squares
(benchmarks/bench_aperiodic_sat.py).

:func:`tilesolve.engine.aperiodic.square_scan` races this run against the unguided phase search,
and a witness records which run found it: its method is :data:`METHOD` or ``"sat"``.
"""

from __future__ import annotations

import numpy as np

__all__ = ["METHOD", "GRAMS_METHOD", "GRAM_SIDE", "GRAM_LENGTH", "window_phases", "grams", "gram_encoding"]

#: The method of a witness found by the window-phased run.
METHOD = "sat markov-phased"
#: The method of a witness found by the gram-guided run.
GRAMS_METHOD = "sat gram-guided"
#: Side of the square whose witness (found by the unguided phase search) gives the grams.
GRAM_SIDE = 100
#: The longest gram: runs of at most this many cells along a row or a column (3 leaves
#: Jeandel-Rao's 200x200 square untiled in 60 s CPU; 4 tiles it with a few hundred conflicts).
GRAM_LENGTH = 4


def window_phases(enc, grid) -> list[int]:
    """Preferred literals for ``enc``, a tile-selection CNF
    (:func:`tilesolve.encodings.wang_tiles.encode_tiles`): the tile ``grid`` holds at each
    cell true, every other tile false (one literal for every variable).

    >>> from tilesolve.encodings.wang_tiles import encode_tiles
    >>> from tilesolve.model.board import Board, WangTileSet
    >>> enc = encode_tiles(Board.rect(2, 2), WangTileSet([[0, 0, 0, 0], [1, 1, 1, 1]], 2))
    >>> window_phases(enc, [[1, 1], [1, 0]])
    [-1, 2, -3, 4, -5, 6, 7, -8]
    """
    on = np.zeros(enc.n_vars + 1, dtype=bool)
    on[enc.literals(grid)] = True
    v = np.arange(1, enc.n_vars + 1, dtype=np.int64)
    return np.where(on[1:], v, -v).tolist()


def grams(grid, length: int = GRAM_LENGTH) -> list[tuple[bool, dict[tuple[int, ...], list[int]]]]:
    """The runs of ``2 .. length`` cells along the rows and the columns of ``grid`` (a tiling),
    as ``(along columns, {first tiles: the tiles that follow})`` for each run length ``>= 3``
    (pairs are the colour constraints' business), the rows' first.

    >>> g = grams([[0, 1, 0, 1], [1, 0, 1, 0]], 3)
    >>> g[0]
    (False, {(0, 1): [0], (1, 0): [1]})
    """
    from numpy.lib.stride_tricks import sliding_window_view

    g = np.asarray(grid, dtype=np.int64)
    out = []
    for down, a in ((False, g), (True, g.T)):
        for k in range(3, length + 1):
            runs = sliding_window_view(a, k, axis=1).reshape(-1, k) if a.shape[1] >= k else np.zeros((0, k), int)
            follow: dict[tuple[int, ...], list[int]] = {}
            for run in sorted(set(map(tuple, runs.tolist()))):
                follow.setdefault(run[:-1], []).append(run[-1])
            out.append((down, follow))
    return out


def gram_encoding(enc, gram_sets):
    """``enc`` (a square's tile-selection CNF) restricted to tilings whose every run along a row or
    a column has its first tiles' follower among ``gram_sets`` (:func:`grams`): for each place
    and each allowed start, a clause "this start here implies one of its followers next". A
    restricted formula: a model is a tiling of the square (verified like any witness), an
    ``unsat`` proves nothing.

    >>> from tilesolve.encodings.wang_tiles import encode_tiles
    >>> from tilesolve.model.board import Board, WangTileSet
    >>> enc = encode_tiles(Board.rect(3, 3), WangTileSet([[0, 0, 0, 0]], 1))
    >>> r = gram_encoding(enc, grams([[0, 0, 0]]))
    >>> r.restricted, len(r.hard) - len(enc.hard)
    (True, 3)
    """
    from tilesolve.encodings import ClauseSet
    from tilesolve.encodings.wang_tiles import TileEncoding

    m = enc.n_tiles
    rows, cols = enc.labels[:, 0], enc.labels[:, 1]
    cell = np.full((int(rows.max()) + 1, int(cols.max()) + 1), -1, dtype=np.int64)
    cell[rows, cols] = np.arange(enc.n_cells)
    cs = ClauseSet()
    for b in enc.hard.blocks:
        cs.add_array(b.lits, b.label)
    for down, follow in gram_sets:
        a = cell.T if down else cell
        for start, nexts in follow.items():
            k = len(start) + 1
            if a.shape[1] < k:
                continue
            places = [a[:, i:a.shape[1] - k + 1 + i].ravel() for i in range(k)]
            ok = np.all([p >= 0 for p in places], axis=0)
            places = [p[ok] for p in places]
            lits = [-(1 + places[i] * m + t) for i, t in enumerate(start)]
            lits += [1 + places[-1] * m + t for t in nexts]
            cs.add_array(np.stack(lits, axis=1), f"runs of {k} along {'columns' if down else 'rows'}")
    return TileEncoding(cs, enc.n_cells, m, enc.labels, restricted=True)
