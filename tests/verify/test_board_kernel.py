"""The fast passes of the board verifier agree with its join-array checks (tilesolve.verify.board).

:func:`board_violations` answers "no violation" from a fast pass over the grid (numpy, or
the numba kernel of :mod:`tilesolve.verify._board_kernel`) and names violations from the
board's join arrays (``_violations``, the checks it always made). Each fast pass must accept
exactly the tilings those checks accept, on valid and corrupted tilings of every kind of
grid board: rectangles, holes, rings, cylinders, tori, Möbius strips, Klein bottles and their
restrictions, with boundary colours, line limits and tile lists.
"""

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tilesolve.families import board as wang
from tilesolve.model.board import Board, BoardProblem, WangTileSet
from tilesolve.verify import _board_kernel
from tilesolve.verify import board as vb

SHAPES = ["rect", "torus", "cylinder", "mobius", "klein", "ring"]


def _board(kind: str, w: int, h: int, holes: int, seed: int) -> Board:
    """The ``kind`` board of ``w x h`` with about ``holes`` tenths of its cells removed: by
    restriction (odd seeds) or built from its grid and mask (even seeds)."""
    b = getattr(Board, kind)(w, h)
    if holes:
        keep = np.random.default_rng(seed).random(b.n_cells) >= holes / 10
        if keep.any():
            b = b.restrict(keep)
            if seed % 2 == 0:
                b = Board.from_grid_spec(b.grid_spec, b.mask_of(), kind=b.kind)
    return b


@pytest.fixture(scope="module")
def compiled():
    """The numba kernel, loaded whatever the board's size."""
    return _board_kernel.compiled(_board_kernel.COMPILED_FROM)


def _kernel_says(kernel, p: BoardProblem, t: np.ndarray) -> bool:
    """What the kernel (plain Python or compiled) says of ``t``, through the same arguments
    :func:`tilesolve.verify.board._compiled_clean` gives it."""
    return vb._compiled_clean(p, t, kernel)


def _agree(p: BoardProblem, t: np.ndarray, compiled) -> bool:
    """Every pass gives the join-array checks' answer; returns whether ``t`` is valid."""
    t = np.asarray(t)
    truth = not vb._violations(p, t.astype(np.int64))
    assert (vb._in_range(t, p.n_colors) and vb._grid_clean(p, t)) == truth
    spec = p.board.grid_spec
    if spec is not None and spec.wrap_rows is None and spec.wrap_cols is None:
        assert _kernel_says(_board_kernel.grid_clean, p, t) == truth
        assert _kernel_says(compiled, p, t) == truth
    assert (board_ok := vb.board_violations(p, t) == []) == truth
    return board_ok


def _edge_colouring(b: Board, k: int, rng) -> np.ndarray:
    """A tiling whose joined legs agree: a random colour on every edge of the board."""
    eid, n_edges = b.leg_edges()
    return rng.integers(0, k, n_edges)[eid]


def _corrupt(p: BoardProblem, t: np.ndarray, how: int, rng) -> np.ndarray:
    """One corruption of ``t``: a leg's colour, an edge recoloured on both its legs, a colour
    out of range, or two cells swapped."""
    t = t.copy()
    n, k = t.shape[0], p.n_colors
    a, leg = int(rng.integers(n)), int(rng.integers(4))
    if how == 0:
        t[a, leg] = (t[a, leg] + 1 + rng.integers(k - 1)) % k
    elif how == 1:
        eid, _ = p.board.leg_edges()
        t[eid == eid[a, leg]] = rng.integers(k)
    elif how == 2:
        t[a, leg] = rng.choice([-1, k, 255, -(2**40)])
    else:
        b = int(rng.integers(n))
        t[[a, b]] = t[[b, a]]
    return t


boards = st.tuples(st.sampled_from(SHAPES), st.integers(2, 7), st.integers(2, 7), st.integers(0, 4),
                   st.integers(0, 2**16))


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(boards, st.integers(2, 4), st.integers(0, 2**16), st.lists(st.integers(0, 3), max_size=3))
def test_tile_lists_on_every_grid_board(compiled, shape, k, seed, corruptions):
    """Random edge colourings are tilings by the tiles they use; some boundary legs fixed;
    then a few corruptions. The passes agree on each."""
    kind, w, h, holes, bseed = shape
    b = _board(kind, w, h, holes, bseed)
    rng = np.random.default_rng(seed)
    t = _edge_colouring(b, k, rng)
    tiles = np.unique(t, axis=0)  # each cell's legs N, E, S, W are its tile
    wall = b.nbr_cell < 0
    beta = np.full(b.n_boundary, -1)
    beta[b.nbr_leg[wall]] = np.where(rng.random(int(wall.sum())) < 0.5, t[wall], -1)
    p = BoardProblem(b, WangTileSet(tiles, k), beta)
    assert _agree(p, t, compiled)
    for how in corruptions:
        t = _corrupt(p, t, how, rng)
        _agree(p, t, compiled)
    small = t.clip(-128, 127).astype(np.int8)  # colours as a file reads them (int8), the large ones clipped
    assert _agree(p, small, compiled) == _agree(p, small.astype(np.int64), compiled)


@pytest.fixture(scope="module")
def brick_walls():
    """Brick tilings with line limits of small boards of every shape (SAT), with their problems."""
    out = []
    for kind, w, h, holes, lines in [("rect", 6, 5, 0, (2, 2)), ("rect", 5, 5, 3, (1, None)),
                                     ("ring", 5, 4, 0, (None, 2)), ("cylinder", 5, 4, 0, (2, 3)),
                                     ("torus", 4, 4, 0, (2, 2)), ("mobius", 5, 4, 0, (2, 2)),
                                     ("mobius", 6, 3, 2, (3, 1)), ("klein", 4, 4, 0, (2, 2)),
                                     ("torus", 5, 3, 0, (None, None)), ("mobius", 1, 3, 0, (3, 3))]:
        b = _board(kind, w, h, holes, 3)
        p = BoardProblem(b, WangTileSet.brick(3), None, max_h=lines[0], max_v=lines[1])
        s = wang.solve(p, method="sat", seed=1)
        if s.status.has_tiling:
            out.append((p, np.asarray(s.tiling)))
    assert len(out) >= 8
    return out


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.integers(0, 9), st.integers(0, 2**16), st.lists(st.integers(0, 3), max_size=3),
       st.sampled_from([None, 1, 2, 3, 5, 40]), st.sampled_from([None, 1, 2, 3, 5, 40]), st.booleans())
def test_brick_walls_on_every_grid_board(compiled, brick_walls, which, seed, corruptions, max_h, max_v, fix):
    """Valid brick walls (lines across the seams of tori, Möbius strips and Klein bottles
    included), under other line limits and boundary colours, then corrupted: the passes agree."""
    p, t = brick_walls[which % len(brick_walls)]
    rng = np.random.default_rng(seed)
    b = p.board
    wall = b.nbr_cell < 0
    beta = np.full(b.n_boundary, -1)
    if fix:
        beta[b.nbr_leg[wall]] = np.where(rng.random(int(wall.sum())) < 0.7, t[wall], rng.integers(0, 3, wall.sum()))
    _agree(p, t, compiled)
    q = BoardProblem(b, p.tileset, beta, max_h=max_h, max_v=max_v)
    _agree(q, t, compiled)
    for how in corruptions:
        t = _corrupt(q, t, how, rng)
        _agree(q, t, compiled)


def test_endless_lines_round_a_torus_and_a_mobius_strip(compiled):
    """A row of W_H tiles closed round a torus or a Möbius strip is an endless line: a violation
    of any limit, however long."""
    for kind in ("torus", "mobius", "klein"):
        b = getattr(Board, kind)(4, 3)
        t = np.zeros((b.n_cells, 4), np.int64)
        t[:, 1], t[:, 3] = 0, 1  # every tile W = E = 0, N = 0, S = 1: horizontal lines everywhere
        for lim in (1, 3, 4, 10**6):
            p = BoardProblem(b, WangTileSet.brick(3), None, max_h=lim)
            assert not _agree(p, t, compiled)


def test_the_grids_wall_legs_are_the_boards():
    """The wall legs the numpy pass finds from the grid are numbered as the board numbers them:
    fixing every boundary leg to its colour passes, any one changed fails."""
    rng = np.random.default_rng(7)
    for kind in SHAPES:
        b = _board(kind, 6, 5, 3, 1)
        t = _edge_colouring(b, 3, rng)
        wall = b.nbr_cell < 0
        beta = np.full(b.n_boundary, -1)
        beta[b.nbr_leg[wall]] = t[wall]
        p = BoardProblem(b, WangTileSet(np.unique(t, axis=0), 3), beta)
        assert vb._grid_clean(p, t)
        for j in range(b.n_boundary):
            wrong = beta.copy()
            wrong[j] = (wrong[j] + 1) % 3
            assert not vb._grid_clean(BoardProblem(b, p.tileset, wrong), t)


def test_the_kernel_is_loaded_once_the_numpy_checks_would_pay_for_it(monkeypatch):
    """A process checks boards with numpy until it has checked COMPILED_FROM cells (loading
    the compiled kernel costs more than one file's or one solve's numpy checks)."""
    monkeypatch.setattr(_board_kernel, "_COMPILED", None)
    monkeypatch.setattr(_board_kernel, "_numpy_cells", 0)
    assert _board_kernel.compiled(_board_kernel.COMPILED_FROM // 2) is None
    assert _board_kernel.compiled(_board_kernel.COMPILED_FROM // 2 - 1) is None
    assert _board_kernel.compiled(1) is not None
    assert _board_kernel.compiled(1) is not None
