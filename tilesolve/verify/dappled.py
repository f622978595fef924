"""Independent checker for dappled tilings.

Written from the definitions of the dappled paper (Def. 1.1, §3.1 non-uniform limits,
§3.2 cyclic runs, §6 items 2, 6, 7: subsets, counts, partial tilings) using numpy only.
It imports neither the constructive algorithms nor the encodings, so a bug there cannot
hide itself here.

How runs are checked
--------------------
A cell violates ``X_τ^k`` (Def. 1.1) when it ends a run of more than ``k`` cells of ``τ``
going left (``H``) or up (``V``), i.e. when the ``k + 1`` cells ending at it along the axis
all lie in ``τ``. For a uniform limit that is a sliding-window AND of ``k + 1`` shifted
copies of the membership array, built by doubling in ``O(log k)`` whole-array operations;
for per-cell limits (§3.1) the run length itself comes from a running maximum of the
positions of non-members (``run = index - last non-member at or before it``). Cyclic runs
(§3.2) see the line continued by its other end. The grid is processed in blocks of whole
rows (plus ``k`` halo rows above for vertical runs), so memory stays bounded by the block,
whatever the grid size.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tilesolve.model.dappled import Condition, DappledProblem

__all__ = ["Violation", "dappled_violations", "is_dappled", "run_lengths", "hamming_distance"]

#: Cells per block of rows in the condition check (bounds the temporary arrays).
BLOCK_CELLS = 1 << 20
_INF = np.iinfo(np.int64).max


@dataclass(frozen=True)
class Violation:
    """One reason a tiling fails its problem.

    ``kind`` is ``"shape"``, ``"tile"``, ``"condition"``, ``"fixed"`` or ``"count"``;
    ``row``/``col`` locate it (``None`` for global ones).
    """

    kind: str
    message: str
    row: int | None = None
    col: int | None = None

    def __str__(self) -> str:
        where = f"(row {self.row}, col {self.col}) " if self.row is not None else ""
        return f"{where}{self.message}"


def run_lengths(member: np.ndarray, axis: str, cyclic: bool) -> np.ndarray:
    """Length of the run of ``True`` cells ending at each cell, going left (H) or up (V).

    In cyclic mode runs wrap around; a line that is ``True`` everywhere has an unbounded
    run, reported as ``np.iinfo(np.int64).max``.

    Examples
    --------
    >>> run_lengths(np.array([[True, False, True, True]]), "H", False).tolist()
    [[1, 0, 1, 2]]
    >>> run_lengths(np.array([[True, False, True, True]]), "H", True).tolist()
    [[3, 0, 1, 2]]
    """
    m = np.asarray(member, dtype=bool)
    ax = 1 if axis == "H" else 0
    run = _runs_along(m, ax)
    if cyclic and m.size:
        n = m.shape[ax]
        last = np.take(run, [n - 1], axis=ax)  # run reaching the line's end: continues at its start
        head = np.arange(n).reshape((1, n) if ax == 1 else (n, 1)) + 1 == run  # cells still in the first run
        run = np.where(head, run + last, run)
        run = np.where(m.all(axis=ax, keepdims=True), _INF, run)
    return run


def _runs_along(m: np.ndarray, ax: int) -> np.ndarray:
    """Plain (non-cyclic) run lengths along axis ``ax``: index minus the last non-member."""
    n = m.shape[ax]
    idx = np.arange(n, dtype=np.int64).reshape((1, n) if ax == 1 else (n, 1))
    last_out = np.maximum.accumulate(np.where(m, np.int64(-1), idx), axis=ax)
    return idx - last_out


def _window_all(m: np.ndarray, width: int, ax: int) -> np.ndarray:
    """``out[i] = m[i - width + 1 .. i]`` all true along ``ax`` (false where the window
    starts before the array), by doubling: ``O(log width)`` shifted ANDs."""
    def shifted_and(a: np.ndarray, b: np.ndarray, s: int) -> np.ndarray:
        # a[i] & b[i - s], false for i < s
        out = np.zeros_like(a)
        n = a.shape[ax]
        if s < n:
            if ax == 1:
                np.logical_and(a[:, s:], b[:, : n - s], out=out[:, s:])
            else:
                np.logical_and(a[s:], b[: n - s], out=out[s:])
        return out

    acc, have = None, 0  # acc: windows of width `have` ending at each cell
    cur, span = m, 1  # cur: windows of width `span`
    while width:
        if width & 1:
            acc, have = (cur, span) if acc is None else (shifted_and(acc, cur, have), have + span)
        width >>= 1
        if width:
            cur, span = shifted_and(cur, cur, span), 2 * span
    return acc


def _member(block: np.ndarray, tiles: tuple[int, ...]) -> np.ndarray:
    if len(tiles) == 1:
        return block == tiles[0]
    return np.isin(block, tiles)


def _condition_cells(tiling: np.ndarray, cond: Condition, cyclic: bool) -> np.ndarray:
    """``(m, 2)`` positions (row-major order) of the cells that end too long a run."""
    rows, cols = tiling.shape
    per_cell = isinstance(cond.limit, np.ndarray)
    lim = cond.max_limit()
    if lim is None:
        return np.empty((0, 2), np.int64)
    ax = 1 if cond.axis == "H" else 0
    line = cols if ax == 1 else rows
    if not cyclic and not per_cell and lim >= line:
        return np.empty((0, 2), np.int64)  # no line holds lim + 1 cells
    # the lim cells before each cell along the axis (the halo), wrapped or padded as
    # non-members; no run reaches further back than a whole line
    halo = min(lim, line)
    ext = np.arange(-halo, line)
    valid = (ext >= 0) | cyclic
    ext = ext % line
    step = max(1, BLOCK_CELLS // max(cols, 1))
    found = []
    for r0 in range(0, rows, step):
        r1 = min(rows, r0 + step)
        if ax == 1:
            core = _member(tiling[r0:r1], cond.tiles)
            m = np.empty((r1 - r0, halo + cols), bool)
            m[:, halo:] = core
            m[:, :halo] = core[:, ext[:halo]] & valid[:halo]
        elif r0 >= halo:
            m = _member(tiling[r0 - halo : r1], cond.tiles)
        else:
            sel = np.arange(r0 - halo, r1)
            m = _member(tiling[sel % rows], cond.tiles)
            m[(sel < 0) & (not cyclic)] = False
        if per_cell:
            run = _runs_along(m, ax)
            run = run[:, halo:] if ax == 1 else run[halo:]
            if cyclic:  # a cyclic run as long as its line is the whole line: unbounded (§3.2)
                run = np.where(run >= line, _INF, run)
            limit = cond.limit[r0:r1]
            bad = (limit > 0) & (run > limit)
        else:
            # lim + 1 cells ending here; on a cyclic line shorter than that, the whole line
            win = _window_all(m, halo + 1, ax)
            bad = win[:, halo:] if ax == 1 else win[halo:]
        if bad.any():
            pos = np.argwhere(bad)
            pos[:, 0] += r0
            found.append(pos)
    return np.concatenate(found) if found else np.empty((0, 2), np.int64)


def _condition_violations(tiling: np.ndarray, cond: Condition, cyclic: bool) -> list[Violation]:
    out = []
    direction = "horizontal" if cond.axis == "H" else "vertical"
    for r, c in _condition_cells(tiling, cond, cyclic).tolist():
        lim = int(cond.limit[r, c]) if isinstance(cond.limit, np.ndarray) else int(cond.limit)
        out.append(
            Violation(
                "condition",
                f"violates {cond.axis}{_tiles(cond)}^{lim}: {direction} run of more than {lim} "
                f"tile{'s' if len(cond.tiles) > 1 else ''} {_tiles(cond)} ends here",
                int(r),
                int(c),
            )
        )
    return out


def _tiles(cond: Condition) -> str:
    return str(cond.tiles[0]) if len(cond.tiles) == 1 else "{" + ",".join(map(str, cond.tiles)) + "}"


def dappled_violations(problem: DappledProblem, tiling) -> list[Violation]:
    """Every way ``tiling`` fails ``problem``, with positions; empty when it is a solution.

    Checks the shape and tile range, every condition of ``L`` (plain or cyclic, uniform or
    per-cell, single tiles or subsets), the fixed cells and the global counts.

    Examples
    --------
    >>> from tilesolve.model import DappledProblem
    >>> p = DappledProblem.from_strings("3x1", ["H0=2"])
    >>> [str(v) for v in dappled_violations(p, [[0, 0, 0]])]
    ['(row 0, col 2) violates H0^2: horizontal run of more than 2 tile 0 ends here']
    """
    t = np.asarray(tiling)
    if t.shape != problem.shape:
        return [Violation("shape", f"tiling has shape {t.shape}, problem grid is {problem.shape}")]
    if t.size and not np.issubdtype(t.dtype, np.integer):
        return [Violation("tile", "tiling must hold integer tile numbers")]
    out: list[Violation] = []
    if t.size and (int(t.min()) < 0 or int(t.max()) >= problem.n_tiles):
        bad = (t < 0) | (t >= problem.n_tiles)
        for r, c in np.argwhere(bad):
            out.append(Violation("tile", f"tile {int(t[r, c])} is not in 0..{problem.n_tiles - 1}", int(r), int(c)))
        return out
    for cond in problem.conditions:
        out.extend(_condition_violations(t, cond, problem.cyclic))
    if problem.fixed is not None:
        mismatch = (problem.fixed >= 0) & (problem.fixed != t)
        for r, c in np.argwhere(mismatch):
            out.append(
                Violation("fixed", f"fixed tile {int(problem.fixed[r, c])} replaced by {int(t[r, c])}", int(r), int(c))
            )
    for k in problem.counts:
        n = int(np.count_nonzero(t == k.tile))
        if n < k.low or (k.high is not None and n > k.high):
            out.append(Violation("count", f"tile {k.tile} appears {n} times, required {k}"))
    return out


def is_dappled(problem: DappledProblem, tiling) -> bool:
    """True when ``tiling`` satisfies every requirement of ``problem``."""
    return not dappled_violations(problem, tiling)


def hamming_distance(a, b) -> int:
    """Number of cells where two tilings differ (dappled paper §6, item 3)."""
    return int(np.count_nonzero(np.asarray(a) != np.asarray(b)))
