"""Independent checker for Wang tilings of boards.

Written from Def. 2 (valid tiling) and Def. 9 (brick Wang tiles) of Derouet-Jourdan,
Kaji, Mizoguchi, *A linear algorithm for brick Wang tiling*, and from §4 of the dappled
paper (brick walls without long lines), with numpy only. It reads the board's plain join
arrays and never imports the encodings or the constructive algorithms.

A tiling of a board is an ``(n_cells, 4)`` integer array: the colour of each cell's legs
in the order W, N, E, S (see :mod:`tilesolve.model.board`).
"""

from __future__ import annotations

import numpy as np

from tilesolve.verify.dappled import Violation

__all__ = ["board_violations", "is_valid_board_tiling", "line_runs"]

_LEGS = ("W", "N", "E", "S")


def _where(labels: np.ndarray, a: int) -> tuple[int, int]:
    return int(labels[a, 0]), int(labels[a, 1])


def line_runs(nbr_cell: np.ndarray, nbr_leg: np.ndarray, member: np.ndarray, axis: str, cap: int) -> np.ndarray:
    """Length (capped at ``cap``) of the run of ``member`` cells ending at each cell.

    ``axis="H"``: a run goes from a cell out of its E leg into the W leg of the next;
    ``"V"``: out of the S leg into the N leg. Runs on a closed loop are capped.
    """
    into, out_of = (0, 2) if axis == "H" else (1, 3)
    pred = nbr_cell[:, into]
    ok = (pred >= 0) & (nbr_leg[:, into] == out_of)
    pred_safe = np.where(ok, pred, 0)
    run = member.astype(np.int64)
    for _ in range(cap):
        new = np.where(member, 1 + np.where(ok, run[pred_safe], 0), 0)
        new = np.minimum(new, cap)
        if np.array_equal(new, run):
            break
        run = new
    return run


def board_violations(tiling, problem) -> list[Violation]:
    """Every way ``tiling`` fails the board problem, with positions (``row``/``col`` = label).

    Checks (Def. 2): each cell's leg colours form a tile of ``W`` (for brick tiles, Def. 9
    directly; a tile with ``c1 = c3`` and ``c2 = c4`` is reported as a *cross*); legs that
    are joined carry the same colour; fixed boundary legs carry their colour; and for brick
    walls with limits, no horizontal run of W_H (``c1 = c3``) tiles longer than ``max_h``
    and no vertical run of W_V (``c2 = c4``) tiles longer than ``max_v``.

    Examples
    --------
    >>> from tilesolve.model.board import Board, BoardProblem, WangTileSet
    >>> p = BoardProblem(Board.rect(1, 1), WangTileSet.brick(3), [0, 1, 0, 1])
    >>> [v.kind for v in board_violations([[0, 1, 0, 1]], p)]
    ['cross']
    """
    board = problem.board
    labels, nc, nl = board.labels, board.nbr_cell, board.nbr_leg
    n = labels.shape[0]
    k = int(problem.tileset.n_colors)
    t = np.asarray(tiling)
    if t.shape != (n, 4):
        return [Violation("shape", f"tiling has shape {t.shape}, the board needs ({n}, 4): 4 leg colours per cell")]
    if t.size and not np.issubdtype(t.dtype, np.integer):
        return [Violation("colour", "leg colours must be integers")]
    t = t.astype(np.int64, copy=False)
    out: list[Violation] = []
    if t.size and (int(t.min()) < 0 or int(t.max()) >= k):
        for a, leg in np.argwhere((t < 0) | (t >= k)):
            r, c = _where(labels, a)
            out.append(Violation("colour", f"leg {_LEGS[leg]} has colour {int(t[a, leg])}, outside C = 0..{k - 1}",
                                 r, c))
        return out
    # (1) tiles in W
    if problem.tileset.is_brick:
        h = t[:, 0] == t[:, 2]
        v = t[:, 1] == t[:, 3]
        for a in np.flatnonzero(h & v):
            r, c = _where(labels, a)
            out.append(Violation("cross", f"tile {t[a].tolist()} is a cross (c1 = c3 and c2 = c4), not a brick tile", r, c))
        for a in np.flatnonzero(~h & ~v):
            r, c = _where(labels, a)
            out.append(Violation("tile", f"tile {t[a].tolist()} has no straight line (c1 != c3 and c2 != c4)", r, c))
    else:
        ts = np.asarray(problem.tileset.tiles, dtype=np.int64)
        key = lambda x: ((x[:, 0] * k + x[:, 1]) * k + x[:, 2]) * k + x[:, 3]  # noqa: E731
        ok = np.isin(key(t), key(ts))
        for a in np.flatnonzero(~ok):
            r, c = _where(labels, a)
            out.append(Violation("tile", f"tile {t[a].tolist()} (W, N, E, S) is not in the tile set", r, c))
    # joined legs agree: leg slot a*4+k meets slot b*4+kb (flat arrays, one gather)
    slot = np.arange(4 * n, dtype=np.int64)
    ncf = nc.ravel()
    other = np.where(ncf >= 0, ncf * 4 + nl.ravel(), slot)
    tf = t.ravel()
    mism = (tf != tf[other]) & (slot <= other)  # each join once, from its smaller slot
    for i in np.flatnonzero(mism):
        a, leg, b, bl = int(i) // 4, int(i) % 4, int(other[i]) // 4, int(other[i]) % 4
        r, c = _where(labels, a)
        out.append(Violation(
            "edge",
            f"leg {_LEGS[leg]} has colour {int(t[a, leg])} but the leg {_LEGS[bl]} of cell "
            f"{list(_where(labels, b))} it meets has colour {int(t[b, bl])}", r, c,
        ))
    # (2) boundary constraints
    beta = np.asarray(problem.boundary, dtype=np.int64)
    wa, wl = np.nonzero(nc < 0)
    req = beta[nl[wa, wl]]
    badb = (req >= 0) & (t[wa, wl] != req)
    for i in np.flatnonzero(badb):
        a, leg = int(wa[i]), int(wl[i])
        r, c = _where(labels, a)
        out.append(Violation(
            "boundary",
            f"boundary leg {int(nl[a, leg])} ({_LEGS[leg]}) has colour {int(t[a, leg])}, required {int(req[i])}", r, c,
        ))
    # line lengths (dappled paper §4)
    for axis, lim, member in (("H", getattr(problem, "max_h", None), t[:, 0] == t[:, 2]),
                              ("V", getattr(problem, "max_v", None), t[:, 1] == t[:, 3])):
        if lim is None:
            continue
        run = line_runs(nc, nl, member, axis, int(lim) + 1)
        what = "horizontal run of W_H" if axis == "H" else "vertical run of W_V"
        for a in np.flatnonzero(run > lim):
            r, c = _where(labels, a)
            out.append(Violation("line", f"{what} tiles longer than {lim} ends here", r, c))
    return out


def is_valid_board_tiling(tiling, problem) -> bool:
    """True when ``tiling`` is a valid tiling of ``problem`` (no violations)."""
    return not board_violations(tiling, problem)
