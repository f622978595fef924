"""How large a problem's CNF will be, estimated from its dimensions before anything is encoded.

``tilesolve export dimacs`` refuses a problem whose DIMACS text would exceed its limit with
this estimate, instead of encoding gigabytes first (:func:`tilesolve.family.cnf_estimate`).
"""

from __future__ import annotations

from tilesolve.encodings.dappled import CardEncoding, card_clauses
from tilesolve.model.board import BoardProblem
from tilesolve.model.dappled import DappledProblem
from tilesolve.model.packing import PackingProblem

__all__ = ["cnf_estimate"]


def cnf_estimate(problem) -> tuple[int, int, int] | None:
    """``(variables, clauses, literals)`` the CNF of ``problem`` is estimated to hold, from its
    dimensions alone (nothing is encoded), or None for a family without a model here.

    Dappled problems (:mod:`tilesolve.encodings.dappled`): per cell, with ``|T| > 2`` tiles,
    one "some tile" clause of ``|T|`` literals and the at-most-one clauses (pairwise up to 6
    tiles, else a sequential counter of ``3|T| - 4`` binary clauses), and per condition one window
    clause of ``(p + 1)`` cells times the tiles outside the condition. Board problems
    (:mod:`tilesolve.encodings.wang`): per edge (about two per cell) an exactly-one over the
    colours, per cell a "some tile" clause and four binary clauses per tile. Counts add their
    cardinality encodings (:func:`tilesolve.encodings.dappled.card_clauses`); packings of
    ``n`` tiles hold about ``8 n^2`` clauses of ``21 n^2`` literals (measured). Fixed cells
    and the brick encoding's run limits are left out.

    >>> cnf_estimate(DappledProblem.from_strings("2048x2048", ["H0=2"], n_tiles=10))[2]
    373293056
    """
    if isinstance(problem, DappledProblem):
        cells, t = problem.rows * problem.cols, problem.n_tiles
        n_vars, clauses, lits = cells * (1 if t <= 2 else t if t <= 6 else 2 * t - 1), 0, 0
        if t > 2:
            amo = (t * (t - 1) // 2, t * (t - 1)) if t <= 6 else (3 * t - 4, 6 * t - 8)
            clauses, lits = cells * (1 + amo[0]), cells * (t + amo[1])
        for cond in problem.conditions:
            limit = cond.limit if cond.limit is None or isinstance(cond.limit, int) else int(cond.limit.min())
            if not limit:
                continue
            run = min(limit + 1, problem.cols if cond.axis == "H" else problem.rows)
            clauses += cells
            lits += cells * run * (max(1, t - len(cond.tiles)) if t > 2 else 1)
        for k in problem.counts:  # a counter over every cell (the tile's literals), at least and at most
            card = CardEncoding.AUTO
            bounds = ([cells - k.low] if k.low > 0 else []) + ([k.high] if k.high is not None and k.high < cells else [])
            extra = int(sum(card_clauses(cells, b, card.enctype(cells, b)) for b in bounds))
            clauses, lits, n_vars = clauses + extra, lits + 3 * extra, n_vars + extra
        return n_vars, clauses, lits
    if isinstance(problem, PackingProblem):  # measured: C = 2, 3 (Wang), 3, 4 (corner) packings
        placements = problem.tiles.n_tiles ** 2
        return 2 * placements, 8 * placements, 21 * placements
    if isinstance(problem, BoardProblem):
        cells, k, m = problem.board.n_cells, problem.n_colors, len(problem.tileset)
        edges = 2 * cells
        clauses = edges * (1 + k * (k - 1) // 2) + cells * (1 + 4 * m)
        return edges * k + cells * m, clauses, edges * (k + k * (k - 1)) + cells * 9 * m
    return None
