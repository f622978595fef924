"""The linear algorithm (§4): its verdict equals the SAT solver's, its tilings verify."""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from tilesolve.families import board as wang
from tilesolve.constructive.brick import cycle_corners, solve_linear
from tilesolve.constructive import _brick_kernels as K
from tilesolve.errors import MethodNotApplicable
from tilesolve.model.board import Board, BoardProblem, WangTileSet, random_boundary
from tilesolve.verify.board import board_violations


def _check_against_sat(board, k, seed, free_fraction=0.0):
    rng = np.random.default_rng(seed)
    beta = random_boundary(board, k, seed=seed)
    beta[rng.random(beta.size) < free_fraction] = -1
    p = BoardProblem(board, WangTileSet.brick(k), beta)
    try:
        lin = solve_linear(p, seed=seed)
    except MethodNotApplicable:
        assert board.kind in ("torus", "klein", "mobius", "cylinder"), "planar boards are always covered"
        return None
    sat = wang.solve(p, method="sat")
    assert lin.status == sat.status, (lin.reason, sat.reason)
    if lin.status.has_tiling:
        assert board_violations(p, lin.tiling) == []
    return lin


@pytest.mark.slow
@settings(max_examples=60)
@given(st.integers(1, 7), st.integers(1, 7), st.floats(0, 0.5), st.integers(0, 10**6), st.sampled_from([3, 4]),
       st.floats(0, 0.3))
def test_random_masks_agree_with_sat(rows, cols, holes, seed, k, free):
    _check_against_sat(Board.random_holes(cols, rows, holes, seed=seed), k, seed, free)


@pytest.mark.slow
@settings(max_examples=60)
@given(st.integers(1, 25), st.integers(0, 10**6), st.sampled_from([3, 4, 5]), st.floats(0, 0.3))
def test_random_trees_agree_with_sat(n, seed, k, free):
    """Trees are where the boundary decides (§4.2): many of these are unsolvable."""
    _check_against_sat(Board.random_tree(n, seed=seed), k, seed, free)


@settings(max_examples=40)
@given(st.sampled_from(["ring", "torus", "cylinder", "mobius", "klein"]), st.integers(2, 6), st.integers(2, 6),
       st.integers(0, 10**6))
def test_cycles_and_surfaces_agree_with_sat(kind, rows, cols, seed):
    _check_against_sat(getattr(Board, kind)(cols, rows), 3, seed)


def test_trees_decide_unsat_with_clash_cell():
    found = 0
    for seed in range(60):
        b = Board.random_tree(6, seed=seed)
        p = BoardProblem(b, WangTileSet.brick(3), random_boundary(b, 3, seed=seed))
        s = solve_linear(p, seed=seed)
        if s.status.value == "unsat":
            found += 1
            assert "clash" in s.reason and list(s.stats["clash_cell"]) in b.labels.tolist()
            assert wang.solve(p, method="sat").status.value == "unsat"
    assert found > 0


def test_theorem12_boards_with_a_cycle_are_always_solvable():
    for seed in range(20):
        b = Board.ring(4 + seed % 3, 3 + seed % 4)
        p = BoardProblem(b, WangTileSet.brick(3), random_boundary(b, 3, seed=seed))
        assert solve_linear(p, seed=seed).status.value == "sat"


def test_condition_propagation_figure2():
    # inputs on legs W, N, E; output on S (opposite N)
    def out(kw, vw, kn, vn, ke, ve):
        return K.out_cond(np.array([kw, kn, ke, K.ANY]), np.array([vw, vn, ve, -1]), 3)

    X, NOT, ANY = K.EXACT, K.NOT, K.ANY
    assert out(X, 1, X, 2, X, 1) == (NOT, 2)   # W = E: straight horizontal, S != N
    assert out(X, 0, X, 2, X, 1) == (X, 2)     # W != E: S = N
    assert out(X, 0, NOT, 2, X, 1) == (NOT, 2)  # forced S = N, N != 2
    assert out(X, 1, NOT, 2, X, 1) == (ANY, -1)
    assert out(ANY, -1, X, 2, X, 1) == (ANY, -1)
    assert out(NOT, 1, X, 2, X, 1) == (X, 2)     # W = E impossible: S = N
    assert out(NOT, 0, X, 2, X, 1) == (ANY, -1)


def test_corners_and_seeds():
    b = Board.rect(4, 4)
    assert cycle_corners(b.nbr_cell, np.array([2, 0, 1, 1]), np.array([3, 3, 0, 2])) == 4
    assert cycle_corners(b.nbr_cell, np.array([0, 1, 0]), np.array([2, 3, 1])) == 1
    p = BoardProblem(Board.rect(8, 8), WangTileSet.brick(3), random_boundary(Board.rect(8, 8), 3, seed=1))
    a, c = solve_linear(p, seed=3), solve_linear(p, seed=3)
    assert np.array_equal(a.tiling, c.tiling)


def test_auto_routes_uncovered_boards_to_sat():
    p = BoardProblem(Board.torus(1, 1), WangTileSet.brick(3))
    with pytest.raises(MethodNotApplicable, match="linear algorithm"):
        solve_linear(p)
    s = wang.solve(p)
    assert s.status.value == "unsat" and s.method == "sat" and any("not applicable" in n for n in s.notes)
    with pytest.raises(MethodNotApplicable):
        solve_linear(BoardProblem(Board.rect(2, 2), WangTileSet([[0, 0, 0, 0]], 1)))


@pytest.mark.slow
def test_crosscheck_all_routes():
    b = Board.random_holes(9, 9, 0.25, seed=7)
    p = BoardProblem(b, WangTileSet.brick(3), random_boundary(b, 3, seed=7))
    rep = wang.crosscheck(p, seed=1)
    assert rep.ok, rep.lines
