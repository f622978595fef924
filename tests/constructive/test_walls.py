"""Procedural stochastic walls (004 §3-4, App. B): the tile set, the 2x2 base case against SAT,
dappling line limits, random access, and the SAT encoding of the same windows."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st
from pysat.solvers import Solver

from tilesolve.constructive.walls import (
    APPENDIX_B,
    SOURCES,
    block_fillings,
    brick_tile_set,
    dappling_period,
    line_lengths,
    orientation,
    wall_tile_scalar,
    wall_window,
)
from tilesolve.encodings.wang import encode_wang
from tilesolve.errors import InvalidProblem
from tilesolve.model.board import Board, BoardProblem, WangTileSet
from tilesolve.verify.board import board_violations

COORD = st.one_of(st.integers(-40, 40), st.integers(2**61, 2**61 + 50), st.integers(-(2**61) - 50, -(2**61)))


def window_problem(legs: np.ndarray, n_colors: int, max_line):
    """The board problem of a window: its own boundary, the wall's line limits."""
    h, w, _ = legs.shape
    board = Board.rect(w, h)
    t = legs.reshape(-1, 4).astype(np.int64)
    bl = board.boundary_legs
    return BoardProblem(board, WangTileSet.brick(n_colors), t[bl[:, 0], bl[:, 1]], max_h=max_line, max_v=max_line), t


def pin(enc, legs) -> list[int]:
    """Unit literals fixing every edge of the encoded board to the colours of ``legs`` ((n, 4))."""
    t = np.asarray(legs, dtype=np.int64).reshape(-1, 4)
    return [int(v) for v in enc.var(enc.edge_of_leg.ravel(), t.ravel())]


def block_legs(outer, inner) -> np.ndarray:
    """(N, E, S, W) legs of the 2x2 block, rows top first, from its 8 outer and 4 inner colours."""
    vt0, vt2, hl0, hl2, vb0, vb2, hr0, hr2 = outer
    vt1, hl1, vb1, hr1 = inner
    return np.array([[[hl2, vt1, hl1, vt0], [hr2, vt2, hr1, vt1]],
                     [[hl1, vb1, hl0, vb0], [hr1, vb2, hr0, vb1]]])


def is_brick_block(legs: np.ndarray) -> bool:
    """Every cell is a horizontal (W = E, N != S) or vertical (N = S, W != E) tile (eq. 1-2)."""
    n, e, s, w = (legs[..., k] for k in range(4))
    return bool((((w == e) & (n != s)) | ((n == s) & (w != e))).all())


# ------------------------------------------------------------------------------ tile set
@pytest.mark.parametrize("nc", [3, 4, 5, 6])
def test_the_wall_tile_set_is_the_brick_wang_set(nc):
    ts = brick_tile_set(nc)
    assert len(ts) == 2 * nc**2 * (nc - 1)
    assert np.array_equal(ts.tiles, WangTileSet.brick(nc).tiles)
    assert len(brick_tile_set(3)) == 36


# ------------------------------------------------------------------------------ App. B
def _raws_for(nc: int) -> list[tuple[int, int, int, int]]:
    """Hash values reaching every choice of m (0 .. nc-2) in the four different-colour helpers."""
    vals = sorted({(m * 2**32 + nc - 2) // (nc - 1) for m in range(nc - 1)} |
                  {(m * 2**32 + nc - 3) // max(nc - 2, 1) for m in range(max(nc - 2, 1))} | {0, 2**32 - 1})
    return [(a, b, c, d) for a, b, c, d in zip(vals, vals[1:] + vals[:1], vals[2:] + vals[:2], vals[3:] + vals[:3])]


@pytest.mark.slow
def test_appendix_b_fills_every_boundary_of_a_2x2_block_and_sat_agrees():
    """nc = 3, every one of the 3**8 boundaries: SAT finds a tiling, and every App. B filling
    (with every choice the different-colour helpers can make) is one the CNF accepts."""
    nc = 3
    board = Board.rect(2, 2)
    enc = encode_wang(BoardProblem(board, WangTileSet.brick(nc)))
    bl = board.boundary_legs
    edge_of = enc.edge_of_leg
    # boundary leg -> SOURCES name (board labels: row 0 = top; legs N, E, S, W)
    name = {(0, 3): "VT0", (0, 0): "HL2", (1, 0): "HR2", (1, 1): "VT2",
            (2, 3): "VB0", (2, 2): "HL0", (3, 1): "VB2", (3, 2): "HR0"}
    order = [SOURCES.index(name[(int(a), int(k))]) for a, k in bl]
    raws = _raws_for(nc)
    with Solver(name="cd15", bootstrap_with=list(enc.clauses)) as sat:
        for outer in itertools.product(range(nc), repeat=8):
            boundary = [outer[i] for i in order]
            lits = [int(enc.var(edge_of[a, k], c)) for (a, k), c in zip(bl, boundary)]
            assert sat.solve(assumptions=lits), outer  # the SAT route: every boundary has a tiling
            for r in raws:
                for inner in block_fillings(outer, nc, r):
                    legs = block_legs(outer, inner)
                    assert is_brick_block(legs), (outer, inner)
                    assert sat.solve(assumptions=pin(enc, legs)), (outer, inner)


@pytest.mark.slow
def test_appendix_b_fills_every_boundary_with_four_colours():
    nc = 4

    def brick(w, n, e, s):
        return (w == e) != (n == s)  # exactly one straight line: eq. 1 or eq. 2

    for outer in itertools.product(range(nc), repeat=8):
        vt0, vt2, hl0, hl2, vb0, vb2, hr0, hr2 = outer
        for r in ((0, 0, 0, 0), (2**32 - 1,) * 4):
            for vt1, hl1, vb1, hr1 in block_fillings(outer, nc, r):
                assert (brick(vt0, hl2, vt1, hl1) and brick(vt1, hr2, vt2, hr1) and brick(vb0, hl1, vb1, hl0)
                        and brick(vb1, hr1, vb2, hr0)), (outer, (vt1, hl1, vb1, hr1))


@pytest.mark.slow
def test_appendix_b_bit_order_is_the_only_consistent_one():
    """The 16 case names read b1 b2 b3 b4 = (HL2 = HL0, HR0 = HR2, VT0 = VT2, VB0 = VB2)."""
    nc = 3
    eqs = [("HL2", "HL0"), ("HR0", "HR2"), ("VT0", "VT2"), ("VB0", "VB2")]
    idx = {s: i for i, s in enumerate(SOURCES)}
    consistent = []
    for perm in itertools.permutations(range(4)):
        ok = True
        for outer in itertools.product(range(nc), repeat=8):
            bits = [outer[idx[a]] == outer[idx[b]] for a, b in eqs]
            key = "".join("1" if bits[perm[k]] else "0" for k in range(4))
            vals = list(outer) + [0, 0, 0, 0]
            # helpers: the smallest colour unlike their inputs
            for slot, (a, b) in zip(range(8, 12), [("VT0", "VT2"), ("HL2", "HL0"), ("VB0", "VB2"), ("HR0", "HR2")]):
                vals[slot] = min({0, 1, 2} - {outer[idx[a]], outer[idx[b]]})
            for fill in APPENDIX_B[key]:
                if not is_brick_block(block_legs(outer, [vals[idx[s]] for s in fill])):
                    ok = False
                    break
            if not ok:
                break
        consistent.append(ok)
    assert consistent == [True] + [False] * 23


def test_all_different_boundary_gives_the_two_checkerboards():
    fills = block_fillings([0, 1, 0, 1, 0, 1, 0, 1], 3)
    kinds = [orientation(block_legs([0, 1, 0, 1, 0, 1, 0, 1], f)).tolist() for f in fills]
    assert kinds == [[[True, False], [False, True]], [[False, True], [True, False]]]


# ------------------------------------------------------------------------------ windows
@settings(max_examples=60)
@given(n=st.one_of(st.none(), st.integers(1, 10)), nc=st.integers(3, 5), x0=COORD, y0=COORD,
       w=st.integers(1, 30), h=st.integers(1, 30), seed=st.integers(0, 2**64 - 1))
def test_every_window_is_a_brick_tiling_with_lines_of_at_most_n(n, nc, x0, y0, w, h, seed):
    legs = wall_window(x0, y0, w, h, colors=nc, max_line=n, seed=seed)
    assert legs.shape == (h, w, 4)
    problem, t = window_problem(legs, nc, n)
    assert board_violations(problem, t) == []
    if n is not None:
        hor, ver = line_lengths(legs)
        assert max(hor.max(initial=0), ver.max(initial=0)) <= n


@pytest.mark.parametrize("n", list(range(1, 11)))
def test_line_limit_is_reached_and_kept_on_a_large_window(n):
    legs = wall_window(-517, 311, 240, 200, colors=3, max_line=n, seed=n)
    hor, ver = line_lengths(legs)
    assert max(hor.max(), ver.max()) == n  # the limit holds and is used
    problem, t = window_problem(legs, 3, n)
    assert board_violations(problem, t) == []


def test_without_dappling_lines_grow_longer():
    hor, ver = line_lengths(wall_window(0, 0, 300, 300, colors=3, seed=2))
    assert max(hor.max(), ver.max()) > 6


@settings(max_examples=60)
@given(n=st.one_of(st.none(), st.integers(1, 10)), nc=st.integers(3, 6), x0=COORD, y0=COORD,
       seed=st.integers(0, 2**64 - 1), dx=st.integers(0, 14), dy=st.integers(0, 14))
def test_random_access_windows_and_single_cells_agree(n, nc, x0, y0, seed, dx, dy):
    big = wall_window(x0, y0, 16, 16, colors=nc, max_line=n, seed=seed)
    small = wall_window(x0 + dx, y0 + dy, 2, 2, colors=nc, max_line=n, seed=seed)
    assert np.array_equal(small, big[14 - dy: 16 - dy, dx: dx + 2])
    cell = wall_tile_scalar(x0 + dx, y0 + dy, colors=nc, max_line=n, seed=seed)
    assert cell == tuple(int(v) for v in big[15 - dy, dx])


def test_windows_built_in_strips_match_single_cells():
    # 3 x 70001 cells are built in several strips of rows; cells on both sides of every strip
    # boundary must be those of the per-cell form.
    x0, y0, w, h = -2, -35001, 3, 70001
    legs = wall_window(x0, y0, w, h, colors=3, max_line=2, seed=4)
    problem, t = window_problem(legs[:40], 3, 2)
    assert board_violations(problem, t) == []
    strip = (1 << 16) // w
    for r in sorted({0, h - 1} | {k * strip + d for k in range(1, h // strip + 1) for d in (-1, 0)} - {h}):
        for c in range(w):
            assert tuple(int(v) for v in legs[r, c]) == wall_tile_scalar(x0 + c, y0 + h - 1 - r, colors=3,
                                                                           max_line=2, seed=4), (r, c)
    hor, ver = line_lengths(legs)
    assert max(hor.max(), ver.max()) <= 2


@pytest.mark.parametrize("n", [None, 1, 2, 3, 4])
def test_windows_satisfy_the_sat_encoding_and_sat_solves_them_too(n):
    legs = wall_window(-5, 9, 8, 7, colors=3, max_line=n, seed=11)
    problem, t = window_problem(legs, 3, n)
    enc = encode_wang(problem)
    with Solver(name="cd15", bootstrap_with=list(enc.clauses)) as sat:
        assert sat.solve(assumptions=pin(enc, t))  # the procedural window is a model
        assert sat.solve()  # and the SAT route tiles the same window and boundary
        other = enc.decode(sat.get_model())
    assert board_violations(problem, other) == []


def test_same_seed_same_wall():
    a = wall_window(3, 4, 20, 20, colors=4, max_line=3, seed=1)
    assert np.array_equal(a, wall_window(3, 4, 20, 20, colors=4, max_line=3, seed=1))
    assert not np.array_equal(a, wall_window(3, 4, 20, 20, colors=4, max_line=3, seed=2))


def test_dappling_period_and_bad_input():
    assert [dappling_period(n) for n in (None, 1, 2, 3, 4, 9)] == [0, 2, 2, 4, 4, 10]
    with pytest.raises(InvalidProblem, match="at least 3 colours"):
        wall_window(0, 0, 2, 2, colors=2)
    with pytest.raises(InvalidProblem, match=">= 1"):
        wall_window(0, 0, 2, 2, max_line=0)
    with pytest.raises(InvalidProblem, match="GiB"):
        wall_window(0, 0, 1 << 15, 1 << 14)
    with pytest.raises(InvalidProblem, match="2\\*\\*62"):
        wall_window(2**62, 0, 2, 2)
    with pytest.raises(InvalidProblem, match="2\\*\\*62"):
        wall_tile_scalar(0, -(2**62) - 1)
    with pytest.raises(InvalidProblem):
        wall_window(0, 0, 2, 2, seed=-1)
    with pytest.raises(InvalidProblem):
        brick_tile_set(2)


def test_appendix_b_helpers_sit_in_their_own_slot():
    # the compiled solver relies on it: vd2T only fills V[i+1, j+1], hd2L only H[i, j+1], ...
    for fills in APPENDIX_B.values():
        for fill in fills:
            for slot, name in enumerate(fill):
                assert name not in ("vd2T", "hd2L", "vd2B", "hd2R") or name == ("vd2T", "hd2L", "vd2B", "hd2R")[slot]


def test_line_lengths_counts_runs_by_hand():
    h_tile, v_tile = [1, 0, 2, 0], [1, 2, 1, 0]  # (N, E, S, W): W = E horizontal; N = S vertical
    legs = np.array([[h_tile, h_tile, v_tile, h_tile],
                     [v_tile, h_tile, v_tile, v_tile],
                     [v_tile, v_tile, v_tile, h_tile]])
    assert orientation(legs).tolist() == [[True, True, False, True], [False, True, False, False],
                                          [False, False, False, True]]
    hor, ver = line_lengths(legs)
    assert sorted(hor.tolist()) == [1, 1, 1, 2]  # rows: HH.H / .H.. / ...H
    assert sorted(ver.tolist()) == [1, 1, 2, 3]  # columns, top down: HVV / HHV / VVV / HVH
