"""Brick walls without long lines (dappled paper §4): the home of the wall facade.

A brick wall is a brick Wang tiling (brick paper, Def. 9) of a rectangle with a free boundary
in which no horizontal line runs through more than ``max_h`` cells and no vertical one through
more than ``max_v``. The dappled paper (§4) builds one from an L-dappled tiling with
``T = {0, 1}`` (0 = W_H, a horizontal line crosses the cell; 1 = W_V) and
``L = {H_0^max_h, V_1^max_v}``: :func:`tilesolve.constructive.brick.wall_from_dappled` turns
the classes into leg colours. Walls are board problems (:mod:`tilesolve.families.board`): this module
provides two routes of the board family:

``wall``
    the finite wall of the dappled paper (§4), from a dappled tiling of the whole rectangle;
``procedural``
    a window of the infinite procedural wall of Derouet-Jourdan, Salvati and Jonchier
    (004 §3-4, App. B; :func:`tilesolve.constructive.walls.wall_window`): every cell's tile is a
    function of its absolute coordinates and the seed, so two windows of the same seed agree
    on the cells they share. It needs one line limit ``n = max_h = max_v`` (004 §4.3);
``npd``
    the repeatable non-procedural wall NPD (004 App. A; :func:`npd_route`): a cyclic dappling
    (dappled paper §3.2) with the border constraint, then the Wang tiling on top, so that the
    wall tiles the torus (one period) or any window of the plane it repeats over.

Examples
--------
>>> from tilesolve.verify.board import board_violations
>>> p, s = brick_wall(9, 6, 2, seed=1)
>>> board_violations(p, s.tiling), s.method
([], 'wall')
>>> from tilesolve.family import solve
>>> q = wall_problem(6, 4, 3)
>>> s = solve(q, "procedural", seed=5, options={"origin": (-100, 40)})
>>> board_violations(q, s.tiling), s.method
([], 'procedural')
>>> t = npd_problem(12, 8, 4)
>>> s = solve(t, "npd", seed=2)
>>> t.board.kind, board_violations(t, s.tiling), s.method
('torus', [], 'npd')
"""

from __future__ import annotations

import time

import numpy as np

from tilesolve.errors import InvalidProblem, MethodNotApplicable
from tilesolve.model.board import Board, BoardProblem, WangTileSet
from tilesolve.model.run import RunOptions
from tilesolve.model.solution import Solution, Status
from tilesolve.model.window import Window

__all__ = ["wall_problem", "npd_problem", "is_free_wall", "wall_route", "procedural_route", "npd_route",
           "brick_wall", "write_procedural_wall", "BandChecker", "CHECK_CELLS", "LINE_METHODS", "line_statistics"]

#: Cells the board verifier checks at a time when a wall is checked band by band
#: (:class:`BandChecker`; the verifier's board and arrays take about 150 bytes a cell).
CHECK_CELLS = 1 << 16


def wall_problem(width: int, height: int, max_line: int, *, max_v: int | None = None,
                 n_colors: int = 3) -> BoardProblem:
    """The board problem of a ``width x height`` brick wall (width first, as ``--size WxH``)
    with lines of at most ``max_line`` cells across and ``max_v`` (default ``max_line``) down."""
    return BoardProblem(Board.rect(width, height), WangTileSet.brick(n_colors), None, max_h=int(max_line),
                        max_v=int(max_line if max_v is None else max_v))


def npd_problem(width: int, height: int, max_line: int, *, max_v: int | None = None,
                n_colors: int = 3) -> BoardProblem:
    """The board problem of one period of a repeatable wall: brick tiles on the
    ``width x height`` torus (:meth:`Board.torus`), lines of at most ``max_line`` cells across
    and ``max_v`` (default ``max_line``) down, across the seams too (004 App. A)."""
    return BoardProblem(Board.torus(width, height), WangTileSet.brick(n_colors), None, max_h=int(max_line),
                        max_v=int(max_line if max_v is None else max_v))


def is_free_wall(problem: BoardProblem) -> bool:
    """True when the ``wall`` route applies: brick tiles on a rectangle, every boundary leg
    free, both line limits set."""
    return (problem.board.kind == "rect" and problem.tileset.is_brick and problem.max_h is not None
            and problem.max_v is not None and bool((problem.boundary < 0).all()))


def _dappled(problem, run: RunOptions) -> Solution:
    """The dappled family's pipeline on ``problem`` (its routes, verified there) as a part of
    this run: the run's seed and deadline, none of its options."""
    from dataclasses import replace

    from tilesolve.family import get, run_route

    return run_route(get("dappled"), problem, "auto", replace(run, options={}))


def wall_route(problem: BoardProblem, run: RunOptions) -> Solution:
    """Solve a free wall problem through a dappled tiling (dappled §4).

    The dappled problem goes through the dappled family's own pipeline (Algorithm 1 where it
    applies, SAT otherwise, e.g. for limit 1), so it is verified there too; its seed and its
    deadline are the run's.
    """
    from tilesolve.constructive.brick import wall_from_dappled
    from tilesolve.model.dappled import DappledProblem, parse_condition

    if not is_free_wall(problem):
        raise MethodNotApplicable("the wall route needs brick tiles on a rectangle with a free boundary and "
                                  "both line limits; use method 'sat'")
    t0 = time.perf_counter()
    rows, cols = (int(v) + 1 for v in problem.board.labels.max(axis=0))
    dp = DappledProblem(rows, cols, 2, (parse_condition(f"H0={problem.max_h}"), parse_condition(f"V1={problem.max_v}")))
    ds = _dappled(dp, run)
    notes = tuple(f"dappled: {n}" for n in ds.notes) + (f"dappled classes by {ds.method!r}",)
    if not ds.status.has_tiling:
        return Solution(ds.status, None, "wall", ds.solver, run.seed, time.perf_counter() - t0, reason=ds.reason,
                        notes=notes)
    tiling = wall_from_dappled(ds.tiling, problem.n_colors, seed=run.seed)
    return Solution(Status.SAT, tiling, "wall", ds.solver, run.seed, time.perf_counter() - t0, notes=notes)


def _origin(value) -> tuple[int, int]:
    """The ``origin`` option: two integers ``(x0, y0)``."""
    try:
        x0, y0 = value
    except (TypeError, ValueError):
        raise InvalidProblem(f"the wall's origin must be two integers (x0, y0), got {value!r}") from None
    for v in (x0, y0):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)):
            raise InvalidProblem(f"the wall's origin must be two integers (x0, y0), got {value!r}")
    return int(x0), int(y0)


def procedural_route(problem: BoardProblem, run: RunOptions) -> Solution:
    """A window of the infinite procedural brick wall (004 §3-4, App. B).

    The tiles come from :func:`tilesolve.constructive.walls.wall_window`: 2x2 blocks whose
    outer edges are hashes of their coordinates, filled by the base-case solver of App. B,
    with procedural dappling (§4.3) so that no line runs through more than ``n`` bricks.
    ``W`` of the paper's tiles (§3.1) is the brick set ``W_B`` of ``problem.n_colors >= 3``
    colours.

    Parameters
    ----------
    problem : BoardProblem
        Brick tiles on a ``rows x cols`` rectangle, free boundary, ``max_h == max_v == n``.
    run : RunOptions
        ``run.seed`` seeds the hashes; ``run.option("origin", (0, 0))`` is the window's
        bottom-left cell ``(x0, y0)`` in the paper's coordinates (``i`` east, ``j`` north):
        board cell ``(r, c)`` is wall cell ``(x0 + c, y0 + rows - 1 - r)``.

    Returns
    -------
    Solution
        ``sat`` with the ``(rows * cols, 4)`` int8 leg colours (N, E, S, W) of the board's
        cells, row-major; its ``window`` is the window of the plane
        (:class:`~tilesolve.model.window.Window`, y growing upwards), and a note names it too.

    Raises
    ------
    MethodNotApplicable
        The problem is not a free brick wall with one line limit (names ``wall`` or ``sat``).
    """
    from tilesolve.constructive.walls import wall_window

    if not is_free_wall(problem):
        raise MethodNotApplicable("the procedural route needs brick tiles on a rectangle with a free boundary "
                                  "and a line limit; use method 'sat'")
    if problem.max_h != problem.max_v:
        raise MethodNotApplicable(f"the procedural route limits lines to one n in both directions (004 §4.3), "
                                  f"got max_h {problem.max_h} and max_v {problem.max_v}; use method 'wall' or 'sat'")
    x0, y0 = _origin(run.option("origin", (0, 0)))
    t0 = time.perf_counter()
    rows, cols = (int(v) + 1 for v in problem.board.labels.max(axis=0))
    window = Window(x0, y0, cols, rows)
    legs = wall_window(x0, y0, cols, rows, colors=problem.n_colors, max_line=problem.max_h, seed=run.seed)
    return Solution(Status.SAT, legs.reshape(rows * cols, 4), "procedural", None, run.seed,
                    time.perf_counter() - t0, notes=(_window_note(window, run.seed),), window=window)


def _window_note(window: Window, seed: int) -> str:
    return f"window {window.describe()} of the infinite wall of seed {seed}"


def write_procedural_wall(path, region: tuple[int, int, int, int], *, colors: int = 3, max_line: int,
                          seed: int) -> Solution:
    """Write the window ``region = (x0, y0, w, h)`` of the infinite procedural wall as a
    ``tilesolve/board-solution`` file, checked band by band and streamed (``tilesolve wall -o``).

    The file is the one :func:`tilesolve.family.solve` with :func:`procedural_route` and
    :func:`tilesolve.io.board_json.write_board_solution` give (the same wall, provenance and
    bytes; only ``time_s`` differs), and the wall passes the same board verifier
    (:func:`tilesolve.verify.board.board_violations`, line limits included), but neither the
    board of the whole window nor the file's text is built: the legs are computed once (4
    bytes a cell, as :func:`tilesolve.constructive.walls.wall_window` gives them), checked
    :data:`CHECK_CELLS` cells at a time by a :class:`BandChecker` (each band grown by the
    ``max_line`` rows above it, so that every join and line is seen whole), and the tiles are
    written a piece at a time (:func:`tilesolve.io.board_json.write_rect_solution`).

    Returns
    -------
    Solution
        ``sat``, method ``procedural``, the window's legs ``(w * h, 4)`` (N, E, S, W), its
        ``window`` and ``time_s`` (generation and check, as :func:`tilesolve.family.solve`
        times a route and its verification).

    Raises
    ------
    InvalidProblem
        A bad region, colour count, line limit or seed (:func:`wall_window`'s checks).
    InternalError
        The wall fails the board verifier (a bug); nothing is written.
    """
    from tilesolve.constructive.walls import wall_window
    from tilesolve.io.board_json import write_rect_solution

    x0, y0, w, h = (int(v) for v in region)
    t0 = time.perf_counter()
    window = Window(x0, y0, w, h)
    legs = wall_window(x0, y0, w, h, colors=colors, max_line=max_line, seed=seed)
    checker = BandChecker(colors, max_line)
    band = max(1, CHECK_CELLS // w)
    for top in range(0, h, band):
        part = legs[top:top + band]
        checker.check(part, f"the procedural wall of seed {seed}", window.cell(top, 0), last=top + band >= h)
    sol = Solution(Status.SAT, legs.reshape(w * h, 4), "procedural", None, seed, time.perf_counter() - t0,
                   notes=(_window_note(window, seed),), window=window)
    write_rect_solution(path, legs, WangTileSet.brick(colors), sol, max_h=max_line, max_v=max_line)
    return sol


class BandChecker:
    """Board-verifies a wall given as consecutive bands of rows, top to bottom, each grown by
    the ``max_line`` rows above it (kept from the band before), so that no join between
    bands and no vertical line across a band border escapes the board verifier
    (:func:`tilesolve.verify.board.board_violations`, line limits included).

    Examples
    --------
    >>> from tilesolve.constructive.walls import wall_window
    >>> legs = wall_window(0, 0, 8, 9, colors=3, max_line=2, seed=1)
    >>> c = BandChecker(3, 2)
    >>> [c.check(legs[r:r + 3], "a wall", (0, 8 - r), last=r == 6) for r in (0, 3, 6)]
    [24, 24, 24]
    """

    def __init__(self, colors: int, max_line: int | None) -> None:
        self.colors, self.n = colors, max_line
        self.keep = 0 if max_line is None else int(max_line)
        self.above: np.ndarray | None = None
        self._problems: dict[tuple[int, int], BoardProblem] = {}

    def _problem(self, rows: int, cols: int) -> BoardProblem:
        key = (rows, cols)
        if key not in self._problems:  # bands share one shape (the first and last may differ)
            self._problems = {key: BoardProblem(Board.rect(cols, rows), WangTileSet.brick(self.colors), None,
                                                max_h=self.n, max_v=self.n)}
        return self._problems[key]

    def check(self, legs: np.ndarray, what: str, at: tuple[int, int], *, last: bool) -> int:
        """Check the next band, ``(rows, cols, 4)`` legs whose top-left cell is the wall's
        cell ``at = (x, y)`` (for the message); the number of its cells.

        Raises
        ------
        InternalError
            The band, with the rows kept above it, fails the board verifier.
        """
        from tilesolve.errors import InternalError
        from tilesolve.verify.board import board_violations

        hh, w = legs.shape[:2]
        part = legs if self.above is None or self.keep == 0 else np.concatenate([self.above, legs])
        bad = board_violations(self._problem(part.shape[0], w), part.reshape(-1, 4))
        if bad:
            x, y = at
            raise InternalError(f"{what} fails the board verifier in the band of rows y {y - hh + 1}..{y}, "
                                f"x {x}..{x + w - 1}: {bad[0]}")
        if self.keep and not last:
            self.above = part[-self.keep:].copy()
        return hh * w


def _period(value, default: tuple[int, int]) -> tuple[int, int]:
    """The ``period`` option: two integers ``(width, height)`` in cells."""
    if value is None:
        return default
    try:
        w, h = value
    except (TypeError, ValueError):
        raise InvalidProblem(f"the wall's period must be two integers (width, height), got {value!r}") from None
    for v in (w, h):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < 1:
            raise InvalidProblem(f"the wall's period must be two positive integers (width, height), got {value!r}")
    return int(w), int(h)


def npd_route(problem: BoardProblem, run: RunOptions) -> Solution:
    """The repeatable non-procedural wall NPD (004 App. A) on a torus, or a window of it.

    A cyclic dappling of one period (dappled paper §3.2: Algorithm 2 or Remark 3.4 where they
    apply, SAT otherwise, through the dappled family's own verified pipeline) with the limits of
    :func:`tilesolve.constructive.npd.cyclic_limits` (the border constraint: two vertical tiles
    in every row, two horizontal ones in every column), then App. A's Algorithm 1
    (:func:`tilesolve.constructive.npd.npd_legs`) colours the edges row by row and column by
    column so that the period closes on itself. ``run.seed`` seeds both steps: the same seed
    gives the same wall.

    Parameters
    ----------
    problem : BoardProblem
        Brick tiles (``problem.n_colors >= 3``), both line limits ``max_h``/``max_v`` (they may
        differ), no fixed boundary leg, on either

        * a torus ``Board.torus(cols, rows)`` (:func:`npd_problem`): the period itself; the
          limits hold across the seams; or
        * a rectangle ``Board.rect(cols, rows)`` (:func:`wall_problem`): a window of the plane
          tiled by repeating one period.
    run : RunOptions
        ``run.seed``; ``run.deadline`` bounds the dappling; family options:

        ``period``: ``(width, height)`` of the repeating period in cells; default the board's
        ``(cols, rows)``; on a torus it must be the board's.
        ``origin``: ``(x0, y0)``, default ``(0, 0)``, as in :func:`procedural_route`: board
        cell ``(r, c)`` is wall cell ``(x0 + c, y0 + rows - 1 - r)`` (``y`` grows upwards),
        i.e. cell ``(height - 1 - y mod height, x mod width)`` of the period. The window at
        ``(0, 0)`` of the period's size is the period itself.

    Returns
    -------
    Solution
        ``sat``: ``(n_cells, 4)`` leg colours (N, E, S, W) in the board's cell order, method
        ``"npd"``, ``solver`` the dappling's solver, ``window`` the window of the plane the
        period repeats over (:class:`~tilesolve.model.window.Window`, y growing upwards), notes
        naming the period and the dappling's route. On a torus an ``unsat`` dappling gives
        ``unsat`` (a brick wall of the torus with
        these limits exists exactly when the cyclic dappling does; the dappled route's proof
        is checked there), a time limit ``unknown``.

    Raises
    ------
    InvalidProblem
        A period under 3x3 cells (no repeatable wall with line limits exists), a malformed
        ``period``/``origin``, or a torus whose ``period`` is not the board's.
    MethodNotApplicable
        Not brick tiles on a free torus or rectangle with both limits; or, on a rectangle, no
        wall repeats with that period (the cyclic dappling is unsatisfiable: choose another
        period or method ``wall``).
    """
    from tilesolve.constructive.npd import cyclic_limits, npd_legs, periodic_window
    from tilesolve.model.dappled import DappledProblem, parse_condition

    kind = problem.board.kind
    if not (kind in ("torus", "rect") and problem.tileset.is_brick and problem.max_h is not None
            and problem.max_v is not None and bool((problem.boundary < 0).all())):
        raise MethodNotApplicable("the npd route needs brick tiles on a torus or a rectangle with a free boundary "
                                  "and both line limits; use method 'sat'")
    rows, cols = (int(v) + 1 for v in problem.board.labels.max(axis=0))
    pw, ph = _period(run.option("period"), (cols, rows))
    if kind == "torus" and (pw, ph) != (cols, rows):
        raise InvalidProblem(f"on a torus the period is the board ({cols}x{rows}), got period {pw}x{ph}")
    window = Window(*_origin(run.option("origin", (0, 0))), cols, rows)
    p, q = cyclic_limits(ph, pw, problem.max_h, problem.max_v)
    t0 = time.perf_counter()
    dp = DappledProblem(ph, pw, 2, (parse_condition(f"H0={p}"), parse_condition(f"V1={q}")), cyclic=True)
    ds = _dappled(dp, run)
    notes = tuple(f"dappled: {n}" for n in ds.notes) + (
        f"period {pw}x{ph}: cyclic dappling H0={p}, V1={q} by {ds.method!r}",)
    if not ds.status.has_tiling:
        if ds.status is Status.UNSAT and kind == "rect":
            raise MethodNotApplicable(f"no wall with lines <= {problem.max_h} across and {problem.max_v} down "
                                      f"repeats with period {pw}x{ph} (the cyclic dappling is unsatisfiable); "
                                      f"choose another period or use method 'wall'")
        if ds.status is Status.UNSAT:
            notes += ("the unsat proof is the cyclic dappling's: a brick wall of this torus with these limits "
                      "colours its cells as such a dappling, two vertical tiles in a row and two horizontal in a "
                      "column (004 App. A)",)
        return Solution(ds.status, None, "npd", ds.solver, run.seed, time.perf_counter() - t0, reason=ds.reason,
                        notes=notes)
    period = npd_legs(ds.tiling, problem.n_colors, seed=run.seed)
    legs = periodic_window(period, window.x0, window.y0, cols, rows)
    lab = problem.board.labels
    tiling = legs[lab[:, 0], lab[:, 1]].astype(np.int8)
    return Solution(Status.SAT, tiling, "npd", ds.solver, run.seed, time.perf_counter() - t0, notes=notes,
                    window=window)


def brick_wall(width: int, height: int, max_line: int, *, max_v: int | None = None, n_colors: int = 3,
               seed: int | None = None) -> tuple[BoardProblem, Solution]:
    """A verified ``width x height`` brick wall: ``(problem, solution)`` (see the module docstring)."""
    from tilesolve.family import solve

    problem = wall_problem(width, height, max_line, max_v=max_v, n_colors=n_colors)
    return problem, solve(problem, method="wall", seed=seed)


#: The generators :func:`line_statistics` measures: the procedural wall (PD, 004 §4.3), the
#: repeatable wall on Kaji's cyclic dappling (NPD, 004 App. A) and the finite wall on Kaji's
#: dappling (the ``wall`` route, dappled paper §4, Algorithm 1).
LINE_METHODS = ("procedural", "npd", "wall")

#: At most this many cells per measured wall (the whole run holds one wall at a time).
MAX_STATS_CELLS = 1 << 22
#: The longest line limit measured (the histograms have one bin per length).
MAX_STATS_LINE = 256


def line_statistics(method: str, n: int, *, width: int = 128, height: int = 128, samples: int = 4, seed: int = 0,
                    colors: int = 3):
    """Line-length histograms of ``samples`` walls of one generator (004 §5, Fig. 22).

    Sample ``k`` uses seed ``seed + k``. ``procedural``: the window at ``(0, 0)`` of
    ``width x height`` cells of the infinite wall, computed with a margin of ``n`` cells and
    counted by first cell (:func:`tilesolve.constructive.wall_stats.wall_lines`); ``npd``: the
    ``width x height`` torus (one period), lines wrapping the seams; ``wall``: the finite
    ``width x height`` rectangle, every line. The ``npd`` and ``wall`` walls come through
    :func:`tilesolve.family.solve`, so the board verifier checks them (line limit included);
    every sample's longest line is checked against ``n`` here as well.

    Returns
    -------
    tilesolve.constructive.wall_stats.LineHistogram

    Raises
    ------
    InvalidProblem
        Unknown method, ``n`` outside ``1 ..`` :data:`MAX_STATS_LINE`, ``colors < 3``, sizes
        under 1 (3 for ``npd``), ``samples < 1``, more than :data:`MAX_STATS_CELLS` cells in all.
    InternalError
        A wall with a line longer than ``n`` (a bug).

    Examples
    --------
    >>> h = line_statistics("npd", 4, width=16, height=16, samples=1)
    >>> h.longest[0] <= 4 and h.longest[1] <= 4, int(h.horizontal.sum()) > 0
    (True, True)
    """
    from tilesolve.constructive.hashes import check_int
    from tilesolve.constructive.wall_stats import LineHistogram, histogram, wall_lines
    from tilesolve.constructive.walls import wall_window
    from tilesolve.errors import InternalError
    from tilesolve.family import solve

    if method not in LINE_METHODS:
        raise InvalidProblem(f"unknown wall generator {method!r}; choose one of {', '.join(LINE_METHODS)}")
    n = check_int(n, "max_line")
    if not 1 <= n <= MAX_STATS_LINE:
        raise InvalidProblem(f"the maximum line length must be 1..{MAX_STATS_LINE} bricks here, got {n}")
    w, h, k, s0 = (check_int(v, name) for v, name in ((width, "width"), (height, "height"), (samples, "samples"),
                                                      (seed, "seed")))
    nc = check_int(colors, "colors")
    if not 3 <= nc <= 127:
        raise InvalidProblem(f"brick walls take 3..127 colours here (004 §3.1), got {nc}")
    if min(w, h) < 1 or k < 1 or s0 < 0:
        raise InvalidProblem(f"need width, height, samples >= 1 and seed >= 0, got {w}, {h}, {k}, {s0}")
    if w * h > MAX_STATS_CELLS or k > MAX_STATS_CELLS // (w * h):
        raise InvalidProblem(f"{k} walls of {w}x{h} cells are over the {MAX_STATS_CELLS:,} cells measured in "
                             f"one run; take fewer or smaller samples")
    hor = np.zeros(n, np.int64)
    ver = np.zeros(n, np.int64)
    longest = [0, 0]
    for seed_k in range(s0, s0 + k):
        if method == "procedural":
            legs = wall_window(-n, -n, w + 2 * n, h + 2 * n, colors=nc, max_line=n, seed=seed_k)
            lines = wall_lines(legs, margin=n)
        else:
            make = npd_problem if method == "npd" else wall_problem
            problem = make(w, h, n, n_colors=nc)
            sol = solve(problem, method, seed=seed_k)
            if not sol.status.has_tiling:
                raise InvalidProblem(f"no {method} wall of {w}x{h} cells with lines <= {n} ({sol.status.value}); "
                                     f"try another size")
            lab = problem.board.labels
            legs = np.empty((h, w, 4), np.int64)
            legs[lab[:, 0], lab[:, 1]] = sol.tiling
            lines = wall_lines(legs, cyclic=method == "npd")
        for d, (a, into) in enumerate(zip(lines, (hor, ver))):
            top = int(a.max()) if a.size else 0
            if top > n:
                raise InternalError(f"{method} wall of seed {seed_k} has a line of {top} bricks, over n = {n}")
            longest[d] = max(longest[d], top)
            into += histogram(a, n)
    return LineHistogram(method, n, hor, ver, (longest[0], longest[1]), k, k * w * h)
