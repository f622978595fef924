"""Wang tilings of boards end to end: the ``board`` family (linear algorithm, solvers, walls).

Every question about Wang tilings of boards (Derouet-Jourdan, Kaji, Mizoguchi, *A linear
algorithm for brick Wang tiling*, 2016) goes through :func:`solve`, :func:`count` or
:func:`crosscheck`, as for dappled tilings (:mod:`tilesolve.families.dappled`):

``solve``
    the generic pipeline (:func:`tilesolve.family.solve`) over :data:`SOLVERS`: every
    tiling is checked with the independent verifier
    :func:`tilesolve.verify.board.board_violations`.
``count`` / ``enumerate_tilings``
    all valid tilings of small boards by solver enumeration with blocking clauses (the
    paper's future work, §5).
``crosscheck``
    runs the linear algorithm, SAT and CP-SAT on one problem and confirms they agree.

Examples
--------
>>> from tilesolve.model.board import Board, BoardProblem, WangTileSet
>>> p = BoardProblem(Board.rect(4, 4), WangTileSet.brick(3), [1] * 16)
>>> s = solve(p, seed=1)
>>> s.status.value, s.method
('sat', 'linear')
>>> count(BoardProblem(Board.rect(1, 1), WangTileSet.brick(3))).value
36
"""

from __future__ import annotations

import time
from typing import Any, Iterator

import numpy as np

from tilesolve.errors import InvalidProblem, MethodNotApplicable
from tilesolve.family import Codec, Demo, Family, Field, Form, RunOptions, form_size, raise_if_interrupted, register
from tilesolve.family import run_deadline
from tilesolve.family import solve as _solve
from tilesolve.io.board_json import BOARD_SOLUTION, VERSIONS
from tilesolve.model.board import BoardProblem
from tilesolve.model.solution import CountResult, CrosscheckReport, Solution, Status
from tilesolve.progress import Progress, as_progress
from tilesolve.verify.board import board_violations

__all__ = [
    "FAMILY", "SOLVERS", "METHODS", "linear", "sat", "cpsat", "theorem7", "wall", "procedural", "npd", "solve",
    "enumerate_tilings", "count", "CountResult", "crosscheck", "CrosscheckReport",
]


def linear(problem: BoardProblem, run: RunOptions) -> Solution:
    """The linear algorithm of §4 (brick Wang tiles, no line limits)."""
    from tilesolve.constructive.brick import solve_linear

    return solve_linear(problem, seed=run.seed)


def sat(problem: BoardProblem, run: RunOptions) -> Solution:
    """SAT on :func:`tilesolve.encodings.wang.encode_wang` (any tile set, line limits);
    unsat answers carry a checked DRAT proof."""
    from tilesolve.encodings.registry import encode
    from tilesolve.engine.routes import sat_route
    from tilesolve.engine.sat import DEFAULT_SAT_SOLVER

    t0 = time.perf_counter()
    enc = encode("wang-board-cnf", problem, deadline=run.deadline)
    return sat_route(enc, run, solver=run.solver or DEFAULT_SAT_SOLVER, t0=t0)


def cpsat(problem: BoardProblem, run: RunOptions) -> Solution:
    """OR-tools CP-SAT: an integer colour per edge, a table constraint per cell."""
    from tilesolve.encodings.wang import build_cpsat_wang
    from tilesolve.engine.cpsat import DEFAULT_CPSAT_WORKERS, solve_cp_model

    t0 = time.perf_counter()
    cp = build_cpsat_wang(problem, deadline=run.deadline)
    r = solve_cp_model(cp.model, cp.bools, deadline=run.deadline, seed=run.seed,
                       num_workers=run.workers or DEFAULT_CPSAT_WORKERS)
    tiling = cp.decode(r.model) if r.status.has_tiling else None
    return Solution(Status.SAT if tiling is not None else r.status, tiling, "cpsat", "cp-sat", run.seed,
                    time.perf_counter() - t0, reason=None if tiling is not None else r.reason, stats=dict(r.stats))


def theorem7(problem: BoardProblem, run: RunOptions) -> Solution:
    """Theorem 7: tile outside a small core leaves first, solve the core by SAT (any
    three-boundary tile set; ``unknown`` when the core fails)."""
    from tilesolve.constructive.wang import theorem7_solve

    return theorem7_solve(problem, run, core_solver=sat)


def wall(problem: BoardProblem, run: RunOptions) -> Solution:
    """A brick wall without long lines from a dappled tiling (dappled paper §4;
    :mod:`tilesolve.families.walls`): brick tiles on a rectangle, free boundary, line limits."""
    from tilesolve.families.walls import wall_route

    return wall_route(problem, run)


def procedural(problem: BoardProblem, run: RunOptions) -> Solution:
    """A window of the infinite procedural brick wall (004 §3-4, App. B; :mod:`tilesolve.families.walls`):
    brick tiles on a rectangle, free boundary, ``max_h == max_v``; family option ``origin``."""
    from tilesolve.families.walls import procedural_route

    return procedural_route(problem, run)


def npd(problem: BoardProblem, run: RunOptions) -> Solution:
    """The repeatable non-procedural wall NPD (004 App. A; :mod:`tilesolve.families.walls`): brick
    tiles on a torus (one period) or a rectangle (a window of the repeating wall), both line
    limits; family options ``period`` and ``origin``."""
    from tilesolve.families.walls import npd_route

    return npd_route(problem, run)


#: Solving routes by name. ``"auto"`` is not an entry: it picks one (:func:`auto_method`).
SOLVERS = {"linear": linear, "sat": sat, "cpsat": cpsat, "theorem7": theorem7, "wall": wall,
           "procedural": procedural, "npd": npd}
METHODS: tuple[str, ...] = ("auto",) + tuple(SOLVERS)


def auto_method(problem: BoardProblem) -> str:
    """``wall`` for brick walls with line limits on a free rectangle, else ``linear`` (falls
    back to ``sat`` where it does not apply)."""
    from tilesolve.families.walls import is_free_wall

    return "wall" if is_free_wall(problem) else "linear"


def solve(problem: BoardProblem, *, method: str | Any = "auto", seed: int | None = None,
          time_limit: float | None = None, progress: Progress | bool = False) -> Solution:
    """Find a valid tiling of a board problem (or prove none exists), verified independently.

    Parameters
    ----------
    problem : BoardProblem
    method : {"auto", "linear", "sat", "cpsat", "theorem7", "wall", "procedural", "npd"} or callable
        ``"linear"`` is the linear algorithm of §4 (brick Wang tiles, no line limits);
        ``"theorem7"`` tiles outside a small core leaves first and solves the core by SAT
        (any three-boundary tile set); ``"wall"`` makes a brick wall without long lines from
        a dappled tiling; ``"procedural"`` cuts a window at (0, 0) from the infinite procedural
        wall (``tilesolve.family.solve`` with ``options={"origin": (x0, y0)}`` moves it);
        ``"npd"`` makes a wall that repeats (004 App. A) on a torus or a rectangle;
        ``"auto"`` uses ``wall`` or ``linear`` where they apply and falls back to SAT, saying
        why in ``Solution.notes``. A callable is a route ``(problem, run)``.
    seed : int, optional
        Drawn and recorded when not given.
    time_limit : float, optional
        Seconds for the whole run; expiry gives ``unknown``.

    Returns
    -------
    Solution
        ``tiling`` is an ``(n_cells, 4)`` array of leg colours in the board model's leg order
        N, E, S, W (the columns of ``Board.nbr_cell``): each row is the cell's tile, as files
        and printed text give it.
    """
    if not isinstance(problem, BoardProblem):
        raise InvalidProblem(f"expected a BoardProblem, got {type(problem).__name__}")
    return _solve(problem, method, seed=seed, time_limit=time_limit, progress=progress)


def enumerate_tilings(problem: BoardProblem, *, limit: int | None = None,
                      time_limit: float | None = None) -> Iterator[np.ndarray]:
    """Yield every valid tiling (``(n_cells, 4)`` arrays), each once, by SAT enumeration."""
    from tilesolve.encodings.wang import encode_wang
    from tilesolve.engine.sat import ModelEnumerator

    enc = encode_wang(problem)
    for model in ModelEnumerator(enc.clauses, enc.projection(), limit=limit, deadline=run_deadline(time_limit)):
        yield enc.decode(model)


def count(problem: BoardProblem, *, method: str = "auto", time_limit: float | None = None,
          progress: Progress | bool = False, force: bool = False) -> CountResult:
    """Count the valid tilings of a (small) board problem exactly.

    ``method``: ``"transfer"`` (a transfer matrix over row words, :mod:`tilesolve.constructive.
    wang_count`: free rectangles, cylinders and tori, any tile set), ``"enumerate"`` (SAT
    enumeration, any board) or ``"auto"`` (transfer where it applies, else enumeration).
    ``progress`` (:func:`tilesolve.progress.as_progress`) shows the transfer's columns and rows,
    or the tilings enumerated so far.
    """
    from tilesolve.encodings.wang import encode_wang
    from tilesolve.engine.sat import count_models

    if method not in ("auto", "enumerate", "transfer"):
        raise InvalidProblem(f"unknown count method {method!r}; choose auto, transfer or enumerate")
    progress = as_progress(progress)
    t0 = time.perf_counter()
    deadline = run_deadline(time_limit)
    if method != "enumerate":
        from tilesolve.constructive.wang_count import count_problem, transfer_applies
        from tilesolve.deadline import TimeLimitReached

        if method == "transfer" or transfer_applies(problem) is None:
            try:
                value = count_problem(problem, deadline, progress)
            except TimeLimitReached as exc:
                return CountResult(None, Status.UNKNOWN, "transfer", time.perf_counter() - t0, note=str(exc))
            return CountResult(value, Status.SAT, "transfer", time.perf_counter() - t0)
    enc = encode_wang(problem)
    with progress.task("counting by enumeration", unit="tiling") as bar:
        res = count_models(enc.clauses, enc.projection(), deadline=deadline, on_model=bar.set)
    return res.replace(time_s=time.perf_counter() - t0)


def crosscheck(problem: BoardProblem, *, seed: int | None = None, time_limit: float | None = None,
               methods=("linear", "sat", "cpsat")) -> CrosscheckReport:
    """Run several routes on ``problem``: verdicts must agree and every tiling must verify.

    The linear algorithm's tiling must also satisfy the CNF encoding. Ctrl-C stops it.
    """
    from tilesolve.encodings.wang import encode_wang
    from tilesolve.engine.sat import solve_cnf
    from tilesolve.family import draw_seed

    seed = draw_seed() if seed is None else seed
    rep = CrosscheckReport()
    for name in methods:
        try:
            sol = raise_if_interrupted(SOLVERS[name](problem, RunOptions(seed, run_deadline(time_limit))))
        except MethodNotApplicable as exc:
            rep.lines.append(f"skip {name}: {exc}")
            continue
        if sol.status.has_tiling:
            bad = board_violations(problem, sol.tiling)
            rep.add(not bad, f"{name}: sat, tiling verifies ({len(bad)} violations)")
            if name == "linear" and not bad:
                enc = encode_wang(problem)
                # Ctrl-C inside this check is the interruption, not a failed check
                r = raise_if_interrupted(solve_cnf(enc.clauses, assumptions=enc.literals(sol.tiling)))
                rep.add(r.status is Status.SAT, "linear tiling satisfies the CNF encoding")
        else:
            rep.lines.append(f"     {name}: {sol.status.value}" + (f" ({sol.reason})" if sol.reason else ""))
        if sol.status is not Status.UNKNOWN:
            rep.verdicts[name] = Status.SAT if sol.status.has_tiling else Status.UNSAT
    rep.add_agreement()
    return rep


# ----------------------------------------------------------------------------- the family record
def _listing(problem: BoardProblem) -> list:
    """Where the cells and edges a file lists differ from the board it describes."""
    from tilesolve.io.board_json import ListedBoardProblem
    from tilesolve.verify.board import listing_violations

    if not isinstance(problem, ListedBoardProblem):
        return []
    return listing_violations(problem.board, problem.listed_cells, problem.listed_edges)


def _refuse_false_listing(problem: BoardProblem, what: str) -> None:
    """Refuse a problem whose file lists cells and edges other than its board (``what``: where)."""
    wrong = _listing(problem)
    if wrong:
        n = len(wrong)
        raise InvalidProblem(f"{what}the file's cells and edges are not the board it describes "
                             f"({problem.board.describe()}): {n} difference{'s' if n != 1 else ''}, the first: "
                             f"{wrong[0]}")


def _verify(problem: BoardProblem, tiling) -> list:
    return _listing(problem) + board_violations(problem, tiling)


def _encode(problem: BoardProblem):
    from tilesolve.encodings.registry import encode

    return encode("wang-board-cnf", problem)


def _read_solution(doc: dict, source: str):
    """The file's problem and solution. Without a tiling, no verifier judges the file's list of
    cells and edges (an unsat claim is about the board described): a false list is refused here."""
    from tilesolve.io.board_json import board_solution_from_dict

    problem, sol = board_solution_from_dict(doc, source)
    if sol.tiling is None:
        _refuse_false_listing(problem, f"{source}: ")
    return problem, sol


def _write_solution(problem: BoardProblem, sol: Solution) -> dict:
    from tilesolve.io.board_json import board_solution_to_dict

    return board_solution_to_dict(problem, sol)


def _draw(problem: BoardProblem, sol: Solution, path, fmt: str, *, title: str | None = None, notes=(),
          **_ignored) -> None:
    """SVG of a board tiling: bricks merged from the edge structure, seams of tori and
    Möbius strips marked; PNG for large boards. A file whose listed cells and edges are not
    the board it describes is refused."""
    _refuse_false_listing(problem, "nothing drawn: ")
    t, n, k = np.asarray(sol.tiling), problem.board.n_cells, problem.n_colors
    if t.shape != (n, 4) or t.size and (t.min() < 0 or t.max() >= k):
        raise InvalidProblem(f"nothing drawn: the file's tiles are not 4 colours in 0..{k - 1} for each of the "
                             f"{n} cells (tilesolve verify tells where)")
    legend = [f"{sol.status.value} by {sol.method}" + (f", seed {sol.seed}" if sol.seed is not None else "")]
    if fmt == "png":
        from tilesolve.io.png import write_board_png

        caption = [title or problem.board.describe()] + ([sol.window.caption()] if sol.window is not None else [])
        write_board_png(path, problem, sol.tiling, window=sol.window, caption=caption + legend + list(notes))
        return
    from tilesolve.io.svg_board import write_board_svg

    write_board_svg(path, problem, sol.tiling, title=title or problem.board.describe(), window=sol.window,
                    notes=legend + list(notes))


def _brick_wall_demo() -> BoardProblem:
    from tilesolve.families.walls import wall_problem

    return wall_problem(32, 20, 3)


def _mobius_demo() -> BoardProblem:
    """A Möbius strip (Example 5) with a hole, brick tiles, a random boundary."""
    from tilesolve.model.board import Board, WangTileSet, random_boundary

    m = Board.mobius(40, 14)
    keep = np.ones(m.n_cells, bool)
    lab = m.labels
    keep[(lab[:, 0] >= 5) & (lab[:, 0] <= 8) & (lab[:, 1] >= 17) & (lab[:, 1] <= 22)] = False
    b = m.restrict(keep)
    return BoardProblem(b, WangTileSet.brick(3), random_boundary(b, 3, seed=1))


DEMOS = (
    Demo("brick-wall", "a 32x20 brick wall, no line through more than 3 cells (dappled §4)", _brick_wall_demo),
    Demo("brick-mobius", "a Möbius strip 40x14 with a hole, random boundary (brick paper §4, Example 5)",
         _mobius_demo),
)

#: Board shapes the studio's form offers (``--board KIND:WxH``; ``mask``: a rectangle with painted holes).
FORM_BOARDS = ("rect", "torus", "cylinder", "mobius", "klein", "ring", "mask")


def _form_holes(values):
    grid = values.get("mask")
    if values["board"] != "mask":
        return None
    rows, cols = form_size(values["size"])
    keep = np.ones((rows, cols), dtype=bool) if grid is None else np.array(grid, dtype=np.int64) != 0
    return keep


#: Grid steps (row, col) out of the legs N, E, S, W.
_LEG_STEP = np.array([[-1, 0], [0, 1], [1, 0], [0, -1]])


def _form_boundary(values, board):
    from tilesolve.model.board import random_boundary

    spec = values["boundary"].strip()
    if spec == "random":
        colours = random_boundary(board, values["colors"], seed=values["seed"])
    elif spec == "free":
        colours = None
    else:
        legs = [v.strip() for v in spec.split(",")]
        if len(legs) != board.n_boundary:
            raise InvalidProblem(f"boundary colours: the board has {board.n_boundary} boundary legs, "
                                 f"{len(legs)} colours given (or write random or free)")
        try:
            colours = np.array([-1 if v in ("-", "") else int(v) for v in legs], dtype=np.int64)
        except ValueError:
            raise InvalidProblem("boundary colours: a comma-separated colour per boundary leg, - for free") from None
    painted = values.get("edge")
    if painted is None or all(v < 0 for row in painted for v in row):
        return colours
    # a boundary leg facing a painted cell of the frame (or of a hole) takes its colour
    grid = np.array(painted, dtype=np.int64)
    legs = board.boundary_legs
    at = board.labels[legs[:, 0]] + _LEG_STEP[legs[:, 1]] + 1
    inside = (at[:, 0] >= 0) & (at[:, 0] < grid.shape[0]) & (at[:, 1] >= 0) & (at[:, 1] < grid.shape[1])
    paint = np.full(len(legs), -1, dtype=np.int64)
    paint[inside] = grid[at[inside, 0], at[inside, 1]]
    out = np.full(len(legs), -1, dtype=np.int64) if colours is None else np.array(colours, dtype=np.int64)
    return np.where(paint >= 0, paint, out)


def _form_build(values) -> tuple[BoardProblem, dict]:
    """The studio form's brick board (the ``brick solve`` options; painted holes make a mask board)."""
    from tilesolve.model.board import Board, WangTileSet, parse_board_spec

    if not 3 <= values["colors"]:
        raise InvalidProblem(f"brick Wang tiles need #C >= 3 colours (Def. 9), got {values['colors']}")
    keep = _form_holes(values)
    board = Board.mask(keep) if keep is not None else parse_board_spec(f"{values['board']}:{values['size']}")
    return BoardProblem(board, WangTileSet.brick(values["colors"]), _form_boundary(values, board),
                        max_h=values["max_h"], max_v=values["max_v"]), {}


def _form_command(values) -> tuple[list[str], dict[str, str]]:
    import json

    files = {}
    keep = _form_holes(values)
    if keep is not None:
        files["mask.txt"] = "".join("".join("#" if k else "." for k in row) + "\n" for row in keep.tolist())
        spec = "mask:mask.txt"
    else:
        spec = f"{values['board']}:{values['size']}"
    words = ["brick", "solve", "--board", spec, "--colors", str(values["colors"])]
    boundary = values["boundary"].strip()
    painted = values.get("edge") is not None and any(v >= 0 for row in values["edge"] for v in row)
    if boundary in ("random", "free") and not painted:
        words += ["--boundary", boundary]
    else:
        colours = _form_build(values)[0].boundary
        files["boundary.json"] = json.dumps([None if v < 0 else int(v) for v in colours.tolist()])
        words += ["--boundary", "boundary.json"]
    for name in ("max_h", "max_v"):
        if values[name] is not None:
            words += [f"--{name.replace('_', '-')}", str(values[name])]
    return words, files


def _form_window(values, window):
    """One window of the infinite procedural brick wall (004 §4) with the form's line limit."""
    from tilesolve.families.walls import wall_problem

    line = values["max_h"] or values["max_v"] or 3
    problem = wall_problem(window.width, window.height, line, n_colors=values["colors"])
    return problem, "procedural", {"origin": (window.x0, window.y0)}


def _mask_extent(values) -> tuple[int, int, int, int]:
    rows, cols = form_size(values["size"])
    return rows, cols, 0, 1


def _edge_extent(values) -> tuple[int, int, int, int]:
    rows, cols = form_size(values["size"])
    return rows + 2, cols + 2, 0, values["colors"] - 1


FORM = Form(
    fields=(
        Field("board", "choice", "board", "rect", "the board's shape; mask: a rectangle with painted holes",
              choices=FORM_BOARDS, option="--board"),
        Field("size", "size", "size (WxH)", "24x16", "W columns by H rows", high=1 << 20, option="--board"),
        Field("colors", "int", "colours #C", 3, "edge colours of the brick tiles (Def. 9)", low=3, high=8,
              option="--colors"),
        Field("boundary", "text", "boundary colours", "free", "free, random, or a colour per boundary leg "
              "(comma-separated, - = free; legs numbered by cell, then N E S W)", option="--boundary"),
        Field("max_h", "int", "longest horizontal line", None, "no horizontal line through more cells (SAT route)",
              low=1, high=1 << 20, option="--max-h"),
        Field("max_v", "int", "longest vertical line", None, "no vertical line through more cells (SAT route)",
              low=1, high=1 << 20, option="--max-v"),
        Field("mask", "cells", "holes (mask boards)", None, "click cells to make holes (0) or cells (1)",
              option="--board", extent=_mask_extent, when=({"board": ("mask",)},)),
        Field("edge", "cells", "boundary colours (painted)", None, "paint the frame around the board (or a "
              "hole): every boundary leg facing a painted cell takes its colour", option="--boundary",
              extent=_edge_extent),
    ),
    build=_form_build,
    command=_form_command,
    window=_form_window,
)


def _warm() -> None:
    """Compile the linear algorithm's kernels now (the studio's long-lived server)."""
    from tilesolve.constructive.brick import compile_kernels

    compile_kernels()


FAMILY = register(Family(
    name="board",
    title="Wang tilings of boards: brick Wang tiles, the linear algorithm, any tile set by SAT "
          "(Derouet-Jourdan, Kaji, Mizoguchi 2016)",
    problem_type=BoardProblem,
    routes=SOLVERS,
    auto=auto_method,
    verify=_verify,
    fallback="sat",
    count=count,
    encode=_encode,
    codecs=(Codec(BOARD_SOLUTION, VERSIONS, _read_solution, _write_solution),),
    draw=_draw,
    demos=DEMOS,
    commands=("tilesolve.cli.brick:brick", "tilesolve.cli.wang:wang", "tilesolve.cli.wall:wall"),
    form=FORM,
    warm=_warm,
    route_help={
        "linear": "the linear algorithm of §4 (numba)",
        "sat": "CNF + PySAT, any tile set, line limits; unsat with a checked DRAT proof",
        "cpsat": "OR-tools CP-SAT table constraints",
        "theorem7": "Theorem 7: leaves first, the core by SAT",
        "wall": "brick walls without long lines from a dappled tiling (dappled §4)",
        "procedural": "a window of the infinite procedural brick wall (004 §4; one line limit; option origin)",
        "npd": "a repeatable wall on a torus or a window of one (004 App. A; options period, origin)",
    },
))
