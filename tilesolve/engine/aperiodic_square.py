"""A square's SAT search steered by a window of a known tiling (the square search ``"markov"``).

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

__all__ = ["METHOD", "window_phases"]

#: The method of a witness found by the window-phased run.
METHOD = "sat markov-phased"


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
