"""Independent checker for dappled tilings.

Written from the definitions of the dappled paper (Def. 1.1, §3.1 non-uniform limits,
§3.2 cyclic runs, §6 items 2, 6, 7: subsets, counts, partial tilings) using numpy only.
It imports neither the constructive algorithms nor the encodings, so a bug there cannot
hide itself here.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tilesolve.model.dappled import Condition, DappledProblem

__all__ = ["Violation", "dappled_violations", "is_dappled", "run_lengths", "hamming_distance"]


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
    """
    m = member if axis == "H" else member.T
    rows, cols = m.shape
    width = 2 * cols if cyclic else cols
    src = np.concatenate([m, m], axis=1) if cyclic else m
    run = np.zeros((rows, width), dtype=np.int64)
    prev = np.zeros(rows, dtype=np.int64)
    for c in range(width):
        prev = np.where(src[:, c], prev + 1, 0)
        run[:, c] = prev
    out = run[:, cols:] if cyclic else run
    if cyclic:
        full = m.all(axis=1)
        out = np.where(full[:, None], np.iinfo(np.int64).max, out)
    return out if axis == "H" else out.T


def _condition_violations(tiling: np.ndarray, cond: Condition, cyclic: bool) -> list[Violation]:
    member = np.isin(tiling, cond.tiles)
    run = run_lengths(member, cond.axis, cyclic)
    rows, cols = tiling.shape
    limit = cond.limit_array(rows, cols).astype(np.int64)
    bad = (limit > 0) & (run > limit)
    out = []
    direction = "horizontal" if cond.axis == "H" else "vertical"
    for r, c in np.argwhere(bad):
        lim = int(limit[r, c])
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


def dappled_violations(tiling, problem: DappledProblem) -> list[Violation]:
    """Every way ``tiling`` fails ``problem``, with positions; empty when it is a solution.

    Checks the shape and tile range, every condition of ``L`` (plain or cyclic, uniform or
    per-cell, single tiles or subsets), the fixed cells and the global counts.

    Examples
    --------
    >>> from tilesolve.model import DappledProblem
    >>> p = DappledProblem.from_strings("3x1", ["H0=2"])
    >>> [str(v) for v in dappled_violations([[0, 0, 0]], p)]
    ['(row 0, col 2) violates H0^2: horizontal run of more than 2 tile 0 ends here']
    """
    t = np.asarray(tiling)
    if t.shape != problem.shape:
        return [Violation("shape", f"tiling has shape {t.shape}, problem grid is {problem.shape}")]
    if t.size and not np.issubdtype(t.dtype, np.integer):
        return [Violation("tile", "tiling must hold integer tile numbers")]
    out: list[Violation] = []
    bad = (t < 0) | (t >= problem.n_tiles)
    for r, c in np.argwhere(bad):
        out.append(Violation("tile", f"tile {int(t[r, c])} is not in 0..{problem.n_tiles - 1}", int(r), int(c)))
    if out:
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
        n = int((t == k.tile).sum())
        if n < k.low or (k.high is not None and n > k.high):
            out.append(Violation("count", f"tile {k.tile} appears {n} times, required {k}"))
    return out


def is_dappled(tiling, problem: DappledProblem) -> bool:
    """True when ``tiling`` satisfies every requirement of ``problem``."""
    return not dappled_violations(tiling, problem)


def hamming_distance(a, b) -> int:
    """Number of cells where two tilings differ (dappled paper §6, item 3)."""
    return int((np.asarray(a) != np.asarray(b)).sum())
