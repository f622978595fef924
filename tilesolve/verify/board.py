"""Independent checker for Wang tilings of boards.

Written from Def. 2 (valid tiling) and Def. 9 (brick Wang tiles) of Derouet-Jourdan,
Kaji, Mizoguchi, *A linear algorithm for brick Wang tiling*, and from §4 of the dappled
paper (brick walls without long lines), with numpy only. It reads the board's plain join
arrays and never imports the encodings or the constructive algorithms.

A tiling of a board is an ``(n_cells, 4)`` integer array: the colour of each cell's legs
in the board model's order N, E, S, W (see :mod:`tilesolve.model.board`), so each row is the
cell's tile; messages name each colour by its side, ``N=1 E=0 S=2 W=0``.

A tiling of a board cut from a grid (:attr:`Board.grid_spec`: rectangles, boards with holes,
rings, cylinders, tori, Möbius strips, Klein bottles and their restrictions) is first checked
in one pass over the grid, the joins re-derived from the grid's definition: by the compiled
loop of :mod:`tilesolve.verify._board_kernel` where no sides are identified and numba is at
hand, else by whole-array numpy operations. Only a tiling that fails it (or a board given by
its joins alone) is checked from the join arrays, which name every violation.

A file that lists its board's cells and edges besides describing the board (kind, grid,
mask) makes a second claim: that the list *is* that board. :func:`listing_violations`
checks it, so that a tiling is never judged on a board other than the one the file names.
"""

from __future__ import annotations

import numpy as np

from tilesolve.verify import _board_kernel
from tilesolve.verify.dappled import Violation

__all__ = ["board_violations", "is_valid_board_tiling", "line_runs", "listing_violations", "MAX_LISTED"]

_LEGS = ("N", "E", "S", "W")
#: Differences between a listed board and its description reported one by one, per kind
#: (cells, edges); one more violation counts the rest.
MAX_LISTED = 1000


def _where(labels: np.ndarray, a: int) -> tuple[int, int]:
    return int(labels[a, 0]), int(labels[a, 1])


def line_runs(nbr_cell: np.ndarray, nbr_leg: np.ndarray, member: np.ndarray, axis: str, cap: int) -> np.ndarray:
    """Length (capped at ``cap``) of the run of ``member`` cells ending at each cell.

    ``axis="H"``: a run goes from a cell out of its E leg into the W leg of the next;
    ``"V"``: out of the S leg into the N leg. Runs on a closed loop are capped.
    """
    into, out_of = (3, 1) if axis == "H" else (0, 2)  # (W, E) or (N, S)
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


def board_violations(problem, tiling) -> list[Violation]:
    """Every way ``tiling`` fails the board problem, with positions (``row``/``col`` = label).

    Checks (Def. 2): each cell's leg colours form a tile of ``W`` (for brick tiles, Def. 9
    directly; a tile with ``c1 = c3`` and ``c2 = c4`` is reported as a *cross*); legs that
    are joined carry the same colour; fixed boundary legs carry their colour; and for brick
    walls with limits, no horizontal run of W_H (``c1 = c3``) tiles longer than ``max_h``
    and no vertical run of W_V (``c2 = c4``) tiles longer than ``max_v``.

    Examples
    --------
    >>> from tilesolve.model.board import Board, BoardProblem, WangTileSet
    >>> p = BoardProblem(Board.rect(1, 1), WangTileSet.brick(3), [1, 0, 1, 0])  # boundary N, E, S, W
    >>> [v.kind for v in board_violations(p, [[1, 0, 1, 0]])]  # legs N, E, S, W
    ['cross']
    """
    n = problem.board.n_cells
    k = int(problem.tileset.n_colors)
    t = np.asarray(tiling)
    if t.shape != (n, 4):
        return [Violation("shape", f"tiling has shape {t.shape}, the board needs ({n}, 4): 4 leg colours per cell")]
    if t.size and not np.issubdtype(t.dtype, np.integer):
        return [Violation("colour", "leg colours must be integers")]
    if t.size == 0:
        return []
    clean = _compiled_clean(problem, t)
    if clean is None:  # no compiled pass for this board: whole-array checks
        clean = _in_range(t, k) and _grid_clean(problem, t)
    return [] if clean else _violations(problem, t.astype(np.int64, copy=False))


def _in_range(t: np.ndarray, k: int) -> bool:
    """Whether every entry of the integer array ``t`` is in ``0..k-1`` (one pass: a negative
    entry seen unsigned is larger than any ``k``)."""
    if t.dtype.kind == "i":
        t = t.view(np.dtype(f"u{t.dtype.itemsize}"))
    return int(t.max()) < k


def _violations(problem, t: np.ndarray) -> list[Violation]:
    """:func:`board_violations` from the board's join arrays, each violation named: ``t`` is an
    ``(n, 4)`` int64 array."""
    board = problem.board
    labels, nc, nl = board.labels, board.nbr_cell, board.nbr_leg
    n = labels.shape[0]
    k = int(problem.tileset.n_colors)
    out: list[Violation] = []
    if t.size and (int(t.min()) < 0 or int(t.max()) >= k):
        for a, leg in np.argwhere((t < 0) | (t >= k)):
            r, c = _where(labels, a)
            out.append(Violation("colour", f"leg {_LEGS[leg]} has colour {int(t[a, leg])}, outside C = 0..{k - 1}",
                                 r, c))
        return out
    # (1) tiles in W
    if problem.tileset.is_brick:
        h = t[:, 3] == t[:, 1]  # W = E
        v = t[:, 0] == t[:, 2]  # N = S
        for a in np.flatnonzero(h & v):
            r, c = _where(labels, a)
            out.append(Violation("cross", f"tile {_nesw(t[a])} is a cross (W = E and N = S), not a brick tile", r, c))
        for a in np.flatnonzero(~h & ~v):
            r, c = _where(labels, a)
            out.append(Violation("tile", f"tile {_nesw(t[a])} has no straight line (W != E and N != S)", r, c))
    else:
        ok = _rows_in(t, np.asarray(problem.tileset.tiles, dtype=np.int64), k)
        for a in np.flatnonzero(~ok):
            r, c = _where(labels, a)
            out.append(Violation("tile", f"tile {_nesw(t[a])} is not in the tile set", r, c))
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
    for axis, lim, member in (("H", getattr(problem, "max_h", None), t[:, 3] == t[:, 1]),
                              ("V", getattr(problem, "max_v", None), t[:, 0] == t[:, 2])):
        if lim is None:
            continue
        # no run off a loop is longer than the board: capping at n + 1 bounds the work, and a
        # run that reaches it goes round a loop (an endless line, longer than any limit)
        cap = min(int(lim), n) + 1
        run = line_runs(nc, nl, member, axis, cap)
        what = "horizontal run of W_H" if axis == "H" else "vertical run of W_V"
        for a in np.flatnonzero(run >= cap):
            r, c = _where(labels, a)
            out.append(Violation("line", f"{what} tiles longer than {lim} ends here", r, c))
    return out


def _compiled_clean(problem, t: np.ndarray, kernel=None) -> bool | None:
    """:func:`tilesolve.verify._board_kernel.grid_clean` of the tiling ``t``, by ``kernel`` or
    where it pays (:func:`tilesolve.verify._board_kernel.compiled`), on a board cut from a grid
    with no sides identified whose tiles it can look up; None elsewhere."""
    board, k = problem.board, int(problem.tileset.n_colors)
    spec = board.grid_spec
    if spec is None or spec[2] is not None or spec[3] is not None:
        return None
    brick = bool(problem.tileset.is_brick)
    if not brick and k**4 > 4 * board.n_cells + (1 << 16):
        return None
    kernel = kernel or _board_kernel.compiled(board.n_cells)
    if kernel is None:
        return None
    rows, cols = int(spec[0]), int(spec[1])
    full = board.n_cells == rows * cols
    known = np.zeros(0 if brick else k**4, bool)
    if not brick:
        legs = np.asarray(problem.tileset.tiles, dtype=np.int64)
        known[((legs[:, 0] * k + legs[:, 1]) * k + legs[:, 2]) * k + legs[:, 3]] = True
    present = np.zeros((0, 0), np.uint8) if full else board.mask_of().view(np.uint8)
    return bool(kernel(np.ascontiguousarray(t), present,
                       rows, cols, k, brick, known, problem.boundary, int(problem.max_h or 0),
                       int(problem.max_v or 0)))


def _grid_clean(problem, t: np.ndarray) -> bool:
    """True when ``t``, colours already in ``0..k-1``, is certainly a valid tiling of a board cut
    from a grid: every check of :func:`board_violations`, made with whole-array operations on
    the ``(rows, cols)`` grid of one small integer per leg.

    The joins are re-derived here from the grid's definition (:class:`~tilesolve.model.board.GridSpec`;
    the board-solution format): the legs N, E, S, W of the cell at ``(r, c)`` meet the S, W, N, E
    legs of the cells at ``(r-1, c)``, ``(r, c+1)``, ``(r+1, c)``, ``(r, c-1)``,
    across identified sides (``"twist"``: row ``r`` meets row ``rows-1-r``, column ``c`` meets
    ``cols-1-c``); a leg with no cell there meets the wall. The wall legs found so must be as
    many as the problem's boundary colours, each a wall leg of the board's join arrays too.

    False when any check fails or the board has no grid: :func:`board_violations` then names
    every violation from the board's join arrays.
    """
    board, k = problem.board, int(problem.tileset.n_colors)
    spec = board.grid_spec
    if spec is None or k > 1 << 16:
        return False
    rows, cols, wrap_rows, wrap_cols = int(spec[0]), int(spec[1]), spec[2], spec[3]
    n = t.shape[0]
    leg, word = (np.uint8, np.uint32) if k <= 256 else (np.uint16, np.uint64)
    words = np.ascontiguousarray(t, dtype=leg).view(word).reshape(n)  # a cell's 4 legs in one word
    if n == rows * cols:
        present = None
        g = words.view(leg).reshape(rows, cols, 4)
    else:
        present = board.mask_of()
        grid = np.zeros(rows * cols, word)
        grid[present.ravel()] = words
        g = grid.view(leg).reshape(rows, cols, 4)
    nn, e, s, w = (g[..., leg] for leg in range(4))

    def held(bad: np.ndarray, *where) -> bool:
        """Whether ``bad`` is false wherever the cells at the indices ``where`` are all present."""
        for ix in where if present is not None else ():
            bad = bad & present[ix]
        return not bad.any()

    everywhere = (slice(None), slice(None))
    # (1) tiles in W
    h, v = w == e, nn == s
    if problem.tileset.is_brick:
        if not held(h == v, everywhere):
            return False
    elif not _grid_tiles_in(g, present, np.asarray(problem.tileset.tiles, dtype=np.int64), k):
        return False
    # joined legs agree: E with the W of the next column, S with the N of the next row, and
    # across the identified sides
    if not (held(e[:, :-1] != w[:, 1:], (slice(None), slice(None, -1)), (slice(None), slice(1, None)))
            and held(s[:-1] != nn[1:], (slice(None, -1),), (slice(1, None),))):
        return False
    if wrap_cols is not None:
        across = slice(None, None, -1) if wrap_cols == "twist" else slice(None)
        if not held(e[:, -1] != w[across, 0], (slice(None), -1), (across, 0)):
            return False
    if wrap_rows is not None:
        across = slice(None, None, -1) if wrap_rows == "twist" else slice(None)
        if not held(s[-1] != nn[0, across], (-1, slice(None)), (0, across)):
            return False
    # (2) boundary constraints, on the wall legs the grid has
    if not _grid_boundary_holds(problem, t, present, rows, cols, wrap_rows, wrap_cols):
        return False
    # line lengths (dappled paper §4): runs go along the rows (columns), across identified sides
    for lim, member, wrap, down in ((problem.max_h, h, wrap_cols, False), (problem.max_v, v, wrap_rows, True)):
        if lim is not None:
            member = member if present is None else member & present
            if _long_run(member.T if down else member, int(lim), wrap):
                return False
    return True


def _grid_tiles_in(g: np.ndarray, present, table: np.ndarray, k: int) -> bool:
    """Whether every present cell of the grid ``g`` (legs N, E, S, W) holds a tile of ``table``."""
    n_keys = k**4
    if n_keys <= 4 * g.shape[0] * g.shape[1] + (1 << 16):  # a table of every key
        known = np.zeros(n_keys, bool)
        known[((table[:, 0] * k + table[:, 1]) * k + table[:, 2]) * k + table[:, 3]] = True
        key = g[..., 0].astype(np.int64)
        for leg in range(1, 4):
            key *= k
            key += g[..., leg]
        ok = known[key]
    else:
        ok = _rows_in(g.reshape(-1, 4).astype(np.int64), table, k).reshape(g.shape[:2])
    return bool(ok.all() if present is None else ok[present].all())


def _grid_boundary_holds(problem, t: np.ndarray, present, rows: int, cols: int, wrap_rows, wrap_cols) -> bool:
    """Whether the grid has as many wall legs as the problem has boundary colours, and each wall
    leg, numbered as the board model numbers them, carries its colour."""
    beta = problem.boundary
    fixed = bool((beta >= 0).any())
    if present is None:  # every cell: the wall legs are the sides not identified
        r, c = np.arange(rows), np.arange(cols)
        sides = [(None if wrap_rows else c, 0), (None if wrap_cols else r * cols + cols - 1, 1),
                 (None if wrap_rows else (rows - 1) * cols + c, 2), (None if wrap_cols else r * cols, 3)]
        walls = [(cells, leg) for cells, leg in sides if cells is not None]
    else:
        there = np.zeros((rows + 2, cols + 2), bool)  # the cells present, padded as the grid's sides meet
        there[1:-1, 1:-1] = present
        if wrap_cols is not None:
            across = slice(None, None, -1) if wrap_cols == "twist" else slice(None)
            there[1:-1, 0], there[1:-1, -1] = present[across, -1], present[across, 0]
        if wrap_rows is not None:
            across = slice(None, None, -1) if wrap_rows == "twist" else slice(None)
            there[0, 1:-1], there[-1, 1:-1] = present[-1, across], present[0, across]
        cell = np.full(rows * cols, -1, np.int64)
        if fixed:
            cell[present.ravel()] = np.arange(int(np.count_nonzero(present)))  # cells in row-major order
        walls = []
        for leg, (dr, dc) in enumerate(((-1, 0), (0, 1), (1, 0), (0, -1))):  # the cell across N, E, S, W
            spots = np.flatnonzero(present & ~there[1 + dr:rows + 1 + dr, 1 + dc:cols + 1 + dc])
            walls.append((cell[spots] if fixed else spots, leg))
    if sum(cells.size for cells, _ in walls) != beta.size:
        return False
    if not fixed:
        return True
    # wall legs are numbered in order of cell, then of leg N, E, S, W
    cells = np.concatenate([c for c, _ in walls]).astype(np.int64)
    legs = np.concatenate([np.full(c.size, leg) for c, leg in walls])
    number = np.empty(cells.size, np.int64)
    number[np.argsort(cells * 4 + legs, kind="stable")] = np.arange(cells.size)
    req = beta[number]
    return not ((req >= 0) & (t[cells, legs] != req)).any()


def _long_run(member: np.ndarray, lim: int, wrap) -> bool:
    """Whether some run of ``member`` cells along the rows of ``member`` is longer than ``lim``;
    ``wrap`` (``None``, ``"plain"`` or ``"twist"``) says how the end of a row continues."""
    if wrap is None:
        return _window_any(member, lim + 1)
    after = member[::-1] if wrap == "twist" else member  # the row each row runs on into
    whole = member.all(axis=1)
    if (whole & whole[::-1] if wrap == "twist" else whole).any():  # a closed line: endless
        return True
    cols = member.shape[1]
    more = min(lim, 2 * cols if wrap == "twist" else cols)  # beyond it, a run would close up
    chain = np.concatenate([member, after, member], axis=1)[:, :cols + more]
    return _window_any(chain, lim + 1)


def _window_any(m: np.ndarray, width: int) -> bool:
    """Whether some ``width`` consecutive entries of a row of ``m`` are all true (windows
    doubled, then joined with overlap: a logarithmic number of whole-array ands)."""
    if width > m.shape[1]:
        return False
    acc, span = m, 1  # acc[:, i]: m[:, i:i + span] all true
    while 2 * span <= width:
        acc = acc[:, :-span] & acc[:, span:]
        span *= 2
    rest = width - span
    if rest:
        acc = acc[:, :-rest] & acc[:, rest:]
    return bool(acc.any())


def _rows_in(rows: np.ndarray, table: np.ndarray, k: int) -> np.ndarray:
    """Which rows of ``rows`` (4 colours in ``0..k-1`` each) are rows of ``table``."""
    if k <= 55108:  # k**4 < 2**63: one int64 key per row
        key = lambda x: ((x[:, 0] * k + x[:, 1]) * k + x[:, 2]) * k + x[:, 3]  # noqa: E731
        return np.isin(key(rows), key(table))
    _, inv = np.unique(np.concatenate([table, rows]), axis=0, return_inverse=True)
    inv = inv.reshape(-1)
    return np.isin(inv[len(table):], inv[:len(table)])


def _nesw(legs: np.ndarray) -> str:
    """A cell's leg colours (N, E, S, W) as the tile a user reads, ``N=1 E=0 S=2 W=0``."""
    n, e, s, w = (int(v) for v in legs)
    return f"N={n} E={e} S={s} W={w}"


def _listed_edge_text(edge: np.ndarray) -> str:
    """A listed edge ``[a, ka, b, kb]`` in words, its legs by name (a file's leg numbers follow
    its own leg order; the names do not): ``cell 0 leg E, cell 1 leg W``."""
    a, ka, b, kb = (int(v) for v in edge)
    leg = lambda k: _LEGS[k] if 0 <= k < 4 else str(k)  # noqa: E731
    return f"cell {a} leg {leg(ka)}, " + (f"the wall's boundary leg {kb}" if b == -1 else f"cell {b} leg {leg(kb)}")


def _join_text(labels: np.ndarray, a: int, leg: int, b: int, kb: int) -> str:
    """``leg E of cell [r, c] meets leg W of cell [r', c']`` (``b = -1``: the wall)."""
    other = f"the wall (boundary leg {kb})" if b < 0 else f"leg {_LEGS[kb]} of cell {list(_where(labels, b))}"
    return f"leg {_LEGS[leg]} of cell {list(_where(labels, a))} meets {other}"


def listing_violations(board, cells, edges) -> list[Violation]:
    """Every way the ``cells`` and ``edges`` a file lists differ from ``board``, the board the
    file describes (rebuilt from its kind, grid and mask).

    ``cells`` must be the board's ``[row, col]`` labels in its order (a tiling gives the colours
    of cell ``i`` in its ``i``-th row). ``edges`` must hold each join once as ``[a, ka, b, kb]``
    (either way round) and each boundary leg once as ``[a, ka, -1, kb]`` with its number ``kb``,
    in any order. Each difference is a violation of kind ``"board"`` at the cell it concerns;
    past :data:`MAX_LISTED` of one kind, one more violation counts the rest.

    Examples
    --------
    >>> from tilesolve.model.board import Board
    >>> b = Board.rect(2, 1)
    >>> listing_violations(b, b.labels, b.edge_array())
    []
    >>> cells = b.labels.copy()
    >>> cells[0] = [5000, 5000]
    >>> [str(v) for v in listing_violations(b, cells, b.edge_array())]
    ['(row 0, col 0) cell 0 is listed at [5000, 5000]; the board has it at [0, 0]']
    """
    labels, nc, nl = board.labels, board.nbr_cell, board.nbr_leg
    n = labels.shape[0]
    out: list[Violation] = []
    c = np.asarray(cells)
    e = np.asarray(edges)
    if c.ndim != 2 or c.shape[1] != 2 or e.ndim != 2 or e.shape[1] != 4:
        return [Violation("board", f"the cells (shape {list(c.shape)}) and edges (shape {list(e.shape)}) are not "
                                   "lists of [row, col] and [a, ka, b, kb]")]
    c, e = c.astype(np.int64, copy=False), e.astype(np.int64, copy=False)
    # cells: the same labels in the same order
    if c.shape[0] != n:
        out.append(Violation("board", f"the file lists {c.shape[0]} cells; the board has {n}"))
    m = min(n, c.shape[0])
    moved = np.flatnonzero((c[:m] != labels[:m]).any(axis=1))
    for i in moved[:MAX_LISTED]:
        r, col = _where(labels, i)
        out.append(Violation("board", f"cell {i} is listed at {c[i].tolist()}; the board has it at [{r}, {col}]",
                             r, col))
    if moved.size > MAX_LISTED:
        out.append(Violation("board", f"... and {moved.size - MAX_LISTED} more cells listed at other places"))
    # edges: the same joins and numbered boundary legs. Each is keyed by its lower leg slot
    # (4 * cell + leg) and its other end (a slot, or 4n + the boundary-leg number).
    slot = np.arange(4 * n, dtype=np.int64)
    wall = nc.ravel() < 0
    nb = int(np.count_nonzero(wall))
    span = 4 * n + nb
    far = np.where(wall, 4 * n + nl.ravel(), nc.ravel() * 4 + nl.ravel())
    own = np.flatnonzero(wall | (far >= slot))
    if e.shape[0] == own.size and np.array_equal(e, np.stack(
            [own // 4, own % 4, nc.ravel()[own], nl.ravel()[own]], axis=1)):
        return out  # listed as tilesolve lists them: once each, from the lower slot, in slot order
    board_keys = own * span + far[own]  # ascending
    a, ka, b, kb = e.T
    ok = (a >= 0) & (a < n) & (ka >= 0) & (ka < 4) & np.where(
        b >= 0, (b < n) & (kb >= 0) & (kb < 4), (b == -1) & (kb >= 0) & (kb < nb))
    sa = a * 4 + ka
    sb = np.where(b >= 0, b * 4 + kb, 4 * n + kb)
    keys = np.where(ok, np.minimum(sa, sb) * span + np.maximum(sa, sb), -1)
    if ok.all() and np.array_equal(np.sort(keys), board_keys):  # in another order or orientation
        return out
    order = np.argsort(keys, kind="stable")
    repeat = np.zeros(keys.size, bool)
    repeat[order[1:]] = (keys[order[1:]] == keys[order[:-1]]) & ok[order[1:]]
    stray = ~ok | ~np.isin(keys, board_keys) | repeat
    bad = np.flatnonzero(stray)
    missing = board_keys[~np.isin(board_keys, keys)]
    for j in bad[:MAX_LISTED]:
        at = _where(labels, int(a[j])) if 0 <= a[j] < n else (None, None)
        why = ("is listed twice" if repeat[j] else "is not an edge of the board" if ok[j]
               else "names a cell, leg or boundary leg the board does not have")
        out.append(Violation("board", f"edge {int(j)} ({_listed_edge_text(e[j])}) {why}", *at))
    if bad.size > MAX_LISTED:
        out.append(Violation("board", f"... and {bad.size - MAX_LISTED} more listed edges the board does not have"))
    for key in missing[:MAX_LISTED]:
        lo, hi = divmod(int(key), span)
        a0, leg = divmod(lo, 4)
        b0, kb0 = (-1, hi - 4 * n) if hi >= 4 * n else divmod(hi, 4)
        r, col = _where(labels, a0)
        out.append(Violation("board", f"the file does not list the edge where {_join_text(labels, a0, leg, b0, kb0)}",
                             r, col))
    if missing.size > MAX_LISTED:
        out.append(Violation("board", f"... and {missing.size - MAX_LISTED} more edges of the board not listed"))
    return out


def is_valid_board_tiling(problem, tiling) -> bool:
    """True when ``tiling`` is a valid tiling of ``problem`` (no violations)."""
    return not board_violations(problem, tiling)
