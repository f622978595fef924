"""Cross-checks of the random-access generators against the solver route, on random windows.

The design card's rule for every family (DESIGN.md, "Cross-checks"): a constructive output
must satisfy the family's encoding, and the SAT route must agree on solvability. For the
generators of issue 10 a *window* is the problem:

procedural walls (004 §3-4, App. B)
    the window ``[x0, x0 + w) x [y0, y0 + h)`` of :func:`tilesolve.constructive.walls.wall_window`,
    with its own boundary (the colours of its outer legs) and the line limit ``n`` it was built
    with, is a board problem (brick tiles, ``max_h = max_v = n``). The window (1) verifies with
    the board verifier, (2) as an assignment (edge colours, and each cell's straight-line
    auxiliaries) falsifies no clause of the board CNF (:func:`tilesolve.encodings.wang.encode_wang`,
    line-limit clauses included), and (3) the SAT route solves the same window and boundary,
    its tiling verified.
stochastic tilings (class notes ch. 3)
    a window of a scanline or direct tiling is a grid tiling with the window's own boundary.
    Its Wang images (corner tiles become Wang tiles over ``C**2`` colours, §2.9) form a board
    problem with the set's tiles; the window (1) verifies with the grid verifier, (2) as an
    assignment (edge colours and tile selectors) falsifies no clause of the board CNF, and
    (3) the SAT route solves the same window and boundary, its tiling verified.

Each check returns a :class:`~tilesolve.model.solution.CrosscheckReport` (``ok`` false on any
disagreement); :func:`random_wall_window` and :func:`random_tiling_window` draw the windows of
a sweep from a seed. Ctrl-C during a SAT call raises :class:`KeyboardInterrupt`.

Examples
--------
>>> rep = crosscheck_wall_window((-7, 12, 4, 3), colors=3, max_line=2, seed=5)
>>> rep.ok, len(rep.lines)
(True, 4)
>>> from tilesolve.model.stochastic import StochasticProblem
>>> crosscheck_tiling_window(StochasticProblem("corner", 2, (3, -4, 3, 3)), seed=1).ok
True
"""

from __future__ import annotations

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.model.board import Board, BoardProblem, WangTileSet
from tilesolve.model.solution import CrosscheckReport, Status
from tilesolve.model.stochastic import StochasticProblem

__all__ = ["crosscheck_wall_window", "crosscheck_tiling_window", "random_wall_window", "random_tiling_window",
           "window_problem", "cnf_falsified"]


def window_problem(legs, tileset: WangTileSet, *, max_line: int | None = None) -> BoardProblem:
    """The board problem of a window: a ``rows x cols`` rectangle whose boundary legs carry the
    window's own outer colours (``legs``: ``(rows, cols, 4)`` N, E, S, W)."""
    t = np.asarray(legs, dtype=np.int64)
    rows, cols = t.shape[:2]
    board = Board.rect(cols, rows)
    flat = t.reshape(-1, 4)
    bl = board.boundary_legs
    return BoardProblem(board, tileset, flat[bl[:, 0], bl[:, 1]], max_h=max_line, max_v=max_line)


def cnf_falsified(problem: BoardProblem, legs) -> tuple[int, int]:
    """``(clauses, falsified)``: the board CNF of ``problem`` evaluated on the assignment that
    ``legs`` spells (one colour per edge; for brick tiles ``h = (W == E)``, ``v = (N == S)``;
    otherwise the selector of each cell's tile). A tile outside the set counts as falsifying."""
    from tilesolve.encodings.wang import encode_wang

    enc = encode_wang(problem)
    t = np.asarray(legs, dtype=np.int64).reshape(-1, 4)
    vals = np.zeros(enc.n_vars + 1, dtype=bool)
    colour = np.zeros(enc.n_edges, dtype=np.int64)
    colour[enc.edge_of_leg.ravel()] = t.ravel()
    vals[enc.var(np.arange(enc.n_edges), colour)] = True
    missing = 0
    if problem.tileset.is_brick:
        vals[enc.h_var] = t[:, 3] == t[:, 1]
        vals[enc.v_var] = t[:, 0] == t[:, 2]
    else:
        k = enc.n_colors
        tiles = problem.tileset.tiles.astype(np.int64)
        codes = ((tiles[:, 0] * k + tiles[:, 1]) * k + tiles[:, 2]) * k + tiles[:, 3]
        order = np.argsort(codes)
        mine = ((t[:, 0] * k + t[:, 1]) * k + t[:, 2]) * k + t[:, 3]
        pos = np.minimum(np.searchsorted(codes[order], mine), len(codes) - 1)
        found = codes[order][pos] == mine
        missing = int((~found).sum())
        m = len(codes)
        base = enc.n_vars - t.shape[0] * m  # the selectors are the last n_cells * m variables
        cells = np.flatnonzero(found)
        vals[base + 1 + cells * m + order[pos[cells]]] = True
    bad = sum(len(rows) for _, rows in enc.clauses.falsified(vals))
    return len(enc.clauses), bad + missing


def _sat_check(rep: CrosscheckReport, problem: BoardProblem, seed: int, time_limit: float | None,
               verify) -> None:
    """Run the board family's SAT route on ``problem``; record its verdict and verify its tiling."""
    from tilesolve.family import raise_if_interrupted, solve

    sol = raise_if_interrupted(solve(problem, "sat", seed=seed, time_limit=time_limit))
    if sol.status.has_tiling:
        bad = verify(sol.tiling)
        rep.add(not bad, f"sat route: sat, its tiling verifies ({len(bad)} violations), {sol.time_s:.2f} s")
        rep.verdicts["sat"] = Status.SAT
    elif sol.status is Status.UNSAT:
        rep.add(False, "sat route: unsat, but the generator's window is a tiling of it")
        rep.verdicts["sat"] = Status.UNSAT
    else:
        rep.lines.append(f"     sat route: {sol.status.value} ({sol.reason})")


def crosscheck_wall_window(window: tuple[int, int, int, int], *, colors: int = 3, max_line: int | None = None,
                           seed: int = 0, time_limit: float | None = None) -> CrosscheckReport:
    """Cross-check one window of the procedural wall (module docstring)."""
    from tilesolve.constructive.walls import wall_window
    from tilesolve.verify.board import board_violations

    x0, y0, w, h = window
    legs = wall_window(x0, y0, w, h, colors=colors, max_line=max_line, seed=seed)
    problem = window_problem(legs, WangTileSet.brick(colors), max_line=max_line)
    rep = CrosscheckReport()
    bad = board_violations(problem, legs.reshape(-1, 4))
    rep.add(not bad, f"procedural window verifies ({len(bad)} violations)" + (f": {bad[0]}" if bad else ""))
    n_clauses, falsified = cnf_falsified(problem, legs)
    rep.add(falsified == 0, f"procedural window satisfies the board CNF ({n_clauses:,} clauses, "
                            f"{falsified} falsified)")
    rep.verdicts["procedural"] = Status.SAT
    _sat_check(rep, problem, seed, time_limit, lambda t: board_violations(problem, t))
    rep.add_agreement()
    return rep


def _wang_images(problem: StochasticProblem, grid) -> tuple[np.ndarray, WangTileSet]:
    """The window's legs ``(rows, cols, 4)`` (N, E, S, W) and the set, as Wang tiles (§2.9)."""
    from tilesolve.model.tiles import TileSet, corner_to_wang

    ts = problem.tiles
    g = np.asarray(grid, dtype=np.int64)
    if problem.kind == "wang":
        wang, images, indices = ts, g, np.array(ts.indices)
    else:
        c = problem.colors
        wang, images, indices = TileSet("wang", c * c), corner_to_wang(g, colors=c), ts.wang_images()
    legs = np.stack(wang.colors_of(images.ravel()), axis=1).reshape(g.shape + (4,))
    tiles = WangTileSet(np.stack(wang.colors_of(indices), axis=1), max(wang.colors, wang.cv))
    return legs, tiles


def crosscheck_tiling_window(problem: StochasticProblem, *, method: str = "auto", seed: int = 0,
                             time_limit: float | None = None) -> CrosscheckReport:
    """Cross-check one window of a stochastic tiling (module docstring)."""
    from tilesolve.families.stochastic import solve, stochastic_violations
    from tilesolve.verify.board import board_violations

    sol = solve(problem, method=method, seed=seed)
    rep = CrosscheckReport()
    if not sol.status.has_tiling:
        rep.add(False, f"{method} route: {sol.status.value} ({sol.reason})")
        return rep
    bad = stochastic_violations(problem, sol.tiling)
    rep.add(not bad, f"{sol.method} window verifies with the grid verifier ({len(bad)} violations)")
    legs, tiles = _wang_images(problem, sol.tiling)
    board_problem = window_problem(legs, tiles)
    n_clauses, falsified = cnf_falsified(board_problem, legs)
    rep.add(falsified == 0, f"{sol.method} window satisfies the grid-tiling CNF of its Wang images "
                            f"({n_clauses:,} clauses, {falsified} falsified)")
    rep.verdicts[sol.method] = Status.SAT
    _sat_check(rep, board_problem, seed, time_limit, lambda t: board_violations(board_problem, t))
    rep.add_agreement()
    return rep


# ----------------------------------------------------------------------------- random windows
_FAR = 1 << 40


def _coordinate(rng: np.random.Generator) -> int:
    """Near the origin, far away, or near the edge of the hashes' lattice (both signs)."""
    scale = rng.choice([64, _FAR, 1 << 61])
    return int(rng.integers(-scale, scale))


def random_wall_window(rng: np.random.Generator, *, max_side: int = 8, max_line: int | None = None,
                       colors: int | None = None) -> dict:
    """Parameters of one random procedural-wall window: ``window``, ``colors`` (3 to 5 unless
    given), ``max_line`` (1 to 10, or no limit, unless given)."""
    if max_side < 1:
        raise InvalidProblem(f"the largest window side must be >= 1, got {max_side}")
    w, h = (int(v) for v in rng.integers(1, max_side + 1, size=2))
    n = max_line if max_line is not None else [None, *range(1, 11)][int(rng.integers(0, 11))]
    return {"window": (_coordinate(rng), _coordinate(rng), w, h),
            "colors": int(colors if colors is not None else rng.integers(3, 6)), "max_line": n}


#: (kind, variant, route) combinations the stochastic family serves.
TILING_ROUTES = (("wang", "complete", "direct"), ("wang", "complete", "scanline"), ("wang", "compact", "scanline"),
                 ("wang", "sums", "direct"), ("corner", "complete", "direct"), ("corner", "complete", "scanline"),
                 ("corner", "compact", "scanline"))


def random_tiling_window(rng: np.random.Generator, *, max_side: int = 6, kind: str | None = None,
                         method: str | None = None, colors: int | None = None) -> tuple[StochasticProblem, str]:
    """One random stochastic-tiling window and the route to run: ``(problem, method)``."""
    if max_side < 1:
        raise InvalidProblem(f"the largest window side must be >= 1, got {max_side}")
    combos = [c for c in TILING_ROUTES if (kind is None or c[0] == kind) and (method is None or c[2] == method)]
    k, variant, route = combos[int(rng.integers(0, len(combos)))]
    c = int(colors if colors is not None else rng.integers(2, 4))
    w, h = (int(v) for v in rng.integers(1, max_side + 1, size=2))
    far = int(rng.choice([64, _FAR]))
    window = (int(rng.integers(-far, far)), int(rng.integers(-far, far)), w, h)
    algorithm = str(rng.choice(["edges", "two"]))
    return StochasticProblem(k, c, window, variant, str(rng.choice(["long", "table"])), algorithm), route
