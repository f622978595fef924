"""Line-length statistics of brick walls (004 §5, Fig. 22; dappled paper §4).

A *line* of a brick wall is a maximal run of horizontal tiles (W_H: ``W = E``, a mortar line
runs across the cell) along a row, or of vertical tiles (W_V) up a column; its length is in
bricks (cells). 004 §5 compares the histograms of these lengths for the procedural wall (PD,
§4.3) and the non-procedural one built on Kaji's dappling (NPD, App. A) at ``n = 4`` and
``n = 10`` (Fig. 22), and reports a flaw of Kaji's algorithm: "the number of lines of length 4
is oddly equivalent to line of length 3 ... every lines over 4 of length will be clamped to 4".
:func:`clamp_numbers` states that as numbers: the share of lines at exactly ``n`` and at
``n - 1`` and their ratio (a run of independent fair choices gives a ratio near 1/2; lines cut
back to ``n`` push it towards 1 or above).

Three ways to count, one per kind of output, so that every line is counted once and whole:

* a finite wall (a rectangle, the ``wall`` route): every maximal run, those cut by the border
  included (they are the wall's lines);
* one period of a repeating wall (the torus, NPD): runs wrap around both seams
  (``cyclic=True``);
* a window of the infinite wall (PD): the window is computed with a margin of ``m >= n``
  cells on each side and a line is counted when its first cell (westmost, or topmost) lies in
  the window proper (``margin=m``); it is then whole inside the padded window.

Arrays are leg colours ``(rows, cols, 4)`` in tilesolve's order (N, E, S, W), row 0 at the top.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tilesolve.errors import InvalidProblem

__all__ = ["runs", "wall_lines", "histogram", "LineHistogram", "clamp_numbers"]


def runs(mask, *, cyclic: bool = False) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Maximal runs of ``True`` along each row of a 2-D boolean array.

    Returns ``(row, start, length)`` int64 arrays, one entry per run. With ``cyclic`` a run
    may wrap from the last column into the first (it is reported once, from its first cell);
    a row that is ``True`` throughout is one run of the row's length starting at 0.

    Examples
    --------
    >>> m = [[1, 1, 0, 1], [0, 1, 1, 0]]
    >>> [a.tolist() for a in runs(m)]
    [[0, 0, 1], [0, 3, 1], [2, 1, 2]]
    >>> [a.tolist() for a in runs(m, cyclic=True)]
    [[0, 1], [3, 1], [3, 2]]
    """
    m = np.asarray(mask, dtype=bool)
    if m.ndim != 2:
        raise InvalidProblem(f"runs are counted along the rows of a 2-D array, got {m.ndim}-D")
    rows, cols = m.shape
    if m.size == 0:
        e = np.zeros(0, np.int64)
        return e, e, e
    pad = np.zeros((rows, 1), dtype=np.int8)
    d = np.diff(np.concatenate([pad, m.astype(np.int8), pad], axis=1), axis=1)
    r0, s = np.nonzero(d == 1)
    _, e = np.nonzero(d == -1)
    length = (e - s).astype(np.int64)
    r0, s = r0.astype(np.int64), s.astype(np.int64)
    if not cyclic:
        return r0, s, length
    # join a run ending at the last column to the one starting at column 0 of the same row
    full = m.all(axis=1)
    wraps = m[:, 0] & m[:, -1] & ~full
    first = np.ones(r0.size, bool)
    first[1:] = r0[1:] != r0[:-1]
    last = np.ones(r0.size, bool)
    last[:-1] = r0[:-1] != r0[1:]
    head = first & wraps[r0]  # the run at column 0 of a wrapping row
    tail = last & wraps[r0]  # the run ending at the last column
    length[tail] += length[head]
    keep = ~head
    return r0[keep], s[keep], length[keep]


def wall_lines(legs, *, cyclic: bool = False, margin: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """Lengths of the horizontal and of the vertical lines of a wall, each counted once.

    Parameters
    ----------
    legs : array-like
        ``(rows, cols, 4)`` leg colours (N, E, S, W).
    cyclic : bool
        One period of a repeating wall: lines wrap around the seams.
    margin : int
        The array is a window padded by ``margin`` cells on each side: count the lines whose
        first cell (westmost for horizontal lines, topmost for vertical ones) is in the window
        proper. Whole when no line is longer than ``margin``.

    Returns
    -------
    tuple of numpy.ndarray
        ``(horizontal, vertical)`` int64 lengths.

    Examples
    --------
    >>> t = np.array([[[1, 0, 2, 0], [1, 1, 1, 0]], [[2, 1, 0, 1], [1, 2, 1, 1]]])
    >>> [a.tolist() for a in wall_lines(t)]
    [[1, 1], [2]]
    """
    t = np.asarray(legs)
    if t.ndim != 3 or t.shape[2] != 4:
        raise InvalidProblem(f"a wall is a (rows, cols, 4) array of leg colours, got shape {t.shape}")
    if cyclic and margin:
        raise InvalidProblem("a period of a repeating wall has no margin")
    hor = t[..., 3] == t[..., 1]  # W = E
    out = []
    for mask in (hor, ~hor.T):  # horizontal lines along rows; vertical lines down columns (rows of the transpose)
        line, start, length = runs(mask, cyclic=cyclic)
        if margin:
            n_lines, n_cells = mask.shape
            core = ((line >= margin) & (line < n_lines - margin) & (start >= margin) & (start < n_cells - margin))
            length = length[core]
        out.append(length)
    return out[0], out[1]


def histogram(lengths, top: int) -> np.ndarray:
    """Counts of the lengths ``1 .. top`` (index ``k - 1`` holds length ``k``).

    Raises
    ------
    InvalidProblem
        A length over ``top`` or under 1.

    Examples
    --------
    >>> histogram([1, 2, 2, 4], 4).tolist()
    [1, 2, 0, 1]
    """
    a = np.asarray(lengths, dtype=np.int64)
    if a.size and (int(a.min()) < 1 or int(a.max()) > top):
        raise InvalidProblem(f"line lengths must be 1..{top}, got {int(a.min())}..{int(a.max())}")
    return np.bincount(a, minlength=top + 1)[1:top + 1].astype(np.int64)


@dataclass(frozen=True)
class LineHistogram:
    """The line-length histograms of one generator at one limit ``n``.

    Attributes
    ----------
    method : str
        The generator (``procedural``, ``npd``, ``wall``).
    n : int
        The line limit.
    horizontal, vertical : numpy.ndarray
        Counts of the lengths ``1 .. n``.
    longest : tuple of int
        The longest horizontal and vertical line met (``<= n``: checked on every sample).
    samples : int
        How many walls were measured.
    cells : int
        Their total size in cells.
    """

    method: str
    n: int
    horizontal: np.ndarray
    vertical: np.ndarray
    longest: tuple[int, int]
    samples: int
    cells: int

    def counts(self, direction: str) -> np.ndarray:
        """``horizontal`` or ``vertical`` counts."""
        if direction not in ("horizontal", "vertical"):
            raise InvalidProblem(f"direction must be horizontal or vertical, got {direction!r}")
        return self.horizontal if direction == "horizontal" else self.vertical

    def shares(self, direction: str) -> np.ndarray:
        """The counts as fractions of the lines in that direction."""
        c = self.counts(direction)
        return c / max(1, int(c.sum()))

    def clamp(self, direction: str) -> dict[str, float]:
        """:func:`clamp_numbers` of the ``horizontal`` or ``vertical`` counts."""
        return clamp_numbers(self.counts(direction))


def clamp_numbers(counts) -> dict[str, float]:
    """The clamp test of 004 §5 on a histogram of lengths ``1 .. n``.

    Returns ``lines`` (their number), ``at_n`` and ``at_n_minus_1`` (shares of the lines),
    and ``ratio`` = count at ``n`` / count at ``n - 1`` (``nan`` when ``n = 1`` or there is no
    line of length ``n - 1``).

    Examples
    --------
    >>> clamp_numbers([8, 4, 2, 2])
    {'lines': 16, 'at_n': 0.125, 'at_n_minus_1': 0.125, 'ratio': 1.0}
    """
    c = np.asarray(counts, dtype=np.int64)
    total = int(c.sum())
    at_n = int(c[-1])
    before = int(c[-2]) if c.size > 1 else 0
    return {"lines": total, "at_n": at_n / total if total else float("nan"),
            "at_n_minus_1": before / total if total and c.size > 1 else float("nan"),
            "ratio": at_n / before if before else float("nan")}
