"""The vectorised verifiers against the definitions read literally, cell by cell.

Dappled paper Def. 1.1, §3.1 (per-cell limits), §3.2 (cyclic runs); brick paper Def. 2.
Row blocks are made tiny here so that block edges and halos are crossed on small grids.
"""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from tilesolve.model.board import Board, BoardProblem, WangTileSet
from tilesolve.model.dappled import Condition, DappledProblem
from tilesolve.verify import dappled as vd
from tilesolve.verify.board import board_violations
from tilesolve.verify.dappled import dappled_violations, run_lengths


def literal_runs(member, axis, cyclic):
    """Run of True cells ending at each cell, walking left (H) / up (V) one cell at a time."""
    rows, cols = member.shape
    out = np.zeros((rows, cols), dtype=np.int64)
    for r in range(rows):
        for c in range(cols):
            n, rr, cc = 0, r, c
            while member[rr, cc]:
                n += 1
                if n > rows * cols:
                    n = np.iinfo(np.int64).max
                    break
                rr, cc = (rr, cc - 1) if axis == "H" else (rr - 1, cc)
                if cyclic:
                    rr, cc = rr % rows, cc % cols
                elif rr < 0 or cc < 0:
                    break
            out[r, c] = n
    return out


def literal_violations(tiling, cond, cyclic):
    member = np.isin(tiling, cond.tiles)
    run = literal_runs(member, cond.axis, cyclic)
    rows, cols = tiling.shape
    lim = cond.limit_array(rows, cols)
    return [(r, c, int(lim[r, c])) for r in range(rows) for c in range(cols) if lim[r, c] > 0 and run[r, c] > lim[r, c]]


@st.composite
def cases(draw):
    rows, cols = draw(st.integers(1, 7)), draw(st.integers(1, 7))
    tiling = np.array(draw(st.lists(st.lists(st.integers(0, 2), min_size=cols, max_size=cols),
                                    min_size=rows, max_size=rows)))
    conds = []
    for _ in range(draw(st.integers(1, 3))):
        tiles = tuple(sorted(draw(st.sets(st.integers(0, 2), min_size=1, max_size=2))))
        if draw(st.booleans()):
            limit = np.array(draw(st.lists(st.lists(st.integers(0, 9), min_size=cols, max_size=cols),
                                           min_size=rows, max_size=rows)))
            if not limit.any():
                limit[0, 0] = 1
        else:
            limit = draw(st.integers(1, 9))
        conds.append(Condition(draw(st.sampled_from("HV")), tiles, limit))
    return tiling, conds, draw(st.booleans())


@pytest.mark.slow
@settings(max_examples=300, deadline=None)
@given(case=cases(), block=st.sampled_from([1, 3, 8, 1 << 20]))
def test_condition_violations_match_the_literal_runs(case, block):
    tiling, conds, cyclic = case
    rows, cols = tiling.shape
    problem = DappledProblem(rows, cols, n_tiles=3, conditions=conds, cyclic=cyclic)
    saved = vd.BLOCK_CELLS
    vd.BLOCK_CELLS = block
    try:
        got = dappled_violations(problem, tiling.astype(np.int8))
    finally:
        vd.BLOCK_CELLS = saved
    want = []
    for cond in conds:
        want += [(r, c, f"^{lim}:") for r, c, lim in literal_violations(tiling, cond, cyclic)]
    assert [(v.row, v.col) for v in got] == [(r, c) for r, c, _ in want]
    assert all(m in v.message for v, (_, _, m) in zip(got, want))


@pytest.mark.slow
@settings(max_examples=200, deadline=None)
@given(case=cases())
def test_run_lengths_match_the_literal_runs(case):
    tiling, conds, cyclic = case
    member = tiling == 0
    for axis in "HV":
        assert np.array_equal(run_lengths(member, axis, cyclic), literal_runs(member, axis, cyclic))


def literal_board_violations(tiling, problem):
    """(kind, row, col) of the edge and boundary violations, leg by leg (Def. 2)."""
    b = problem.board
    out = []
    for a in range(b.n_cells):
        for k in range(4):
            nb, kb = int(b.nbr_cell[a, k]), int(b.nbr_leg[a, k])
            if nb >= 0 and (a, k) <= (nb, kb) and tiling[a, k] != tiling[nb, kb]:
                out.append(("edge", *b.labels[a].tolist()))
    for a in range(b.n_cells):
        for k in range(4):
            if b.nbr_cell[a, k] < 0:
                want = problem.boundary[b.nbr_leg[a, k]]
                if want >= 0 and tiling[a, k] != want:
                    out.append(("boundary", *b.labels[a].tolist()))
    return out


@pytest.mark.parametrize("board", [
    Board.rect(5, 4), Board.torus(4, 3), Board.klein(3, 3), Board.mobius(5, 4), Board.ring(4, 4),
    Board.random_holes(6, 6, 0.3, seed=1), Board.torus(1, 1), Board.mobius(1, 2),
])
def test_joins_and_boundary_match_the_literal_check(board):
    rng = np.random.default_rng(board.n_cells)
    problem = BoardProblem(board, WangTileSet.brick(3), rng.integers(-1, 3, board.n_boundary))
    for _ in range(20):
        tiling = rng.integers(0, 3, (board.n_cells, 4))
        got = [(v.kind, v.row, v.col) for v in board_violations(problem, tiling) if v.kind in ("edge", "boundary")]
        assert got == literal_board_violations(tiling, problem)
