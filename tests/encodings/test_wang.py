"""SAT / CP-SAT on any board: agreement, counting against brute force, proofs."""

import itertools

import numpy as np
import pytest

from tilesolve.families import board as wang
from tilesolve.encodings.wang import encode_wang, line_windows
from tilesolve.errors import InvalidProblem, MethodNotApplicable
from tilesolve.model.board import Board, BoardProblem, WangTileSet, random_boundary
from tilesolve.verify.board import board_violations


def brute_count(problem):
    """Count valid tilings by trying every colouring of the edges (tiny boards only)."""
    board = problem.board
    eid, ne = board.leg_edges()
    k = problem.n_colors
    fixed = np.full(ne, -1)
    bl = board.boundary_legs
    fixed[eid[bl[:, 0], bl[:, 1]]] = problem.boundary
    free = np.flatnonzero(fixed < 0)
    n = 0
    for cols in itertools.product(range(k), repeat=free.size):
        c = fixed.copy()
        c[free] = cols
        n += not board_violations(problem, c[eid])
    return n


@pytest.mark.fast_cases(1)
@pytest.mark.parametrize("board", [Board.rect(2, 1), Board.rect(2, 2), Board.torus(2, 1), Board.mobius(2, 2), Board.cylinder(2, 2)])
def test_count_matches_brute_force(board):
    b = random_boundary(board, 3, seed=1)
    b[::2] = -1  # half the boundary free
    p = BoardProblem(board, WangTileSet.brick(3), b)
    c = wang.count(p)
    assert c.status.value == "sat" and c.value == brute_count(p)


def test_count_single_cell_and_generic_tiles():
    assert wang.count(BoardProblem(Board.rect(1, 1), WangTileSet.brick(4))).value == 2 * 16 * 3
    # generic tiles: 2 colours, tiles that copy W->E and N->S: horizontal/vertical stripes
    ts = WangTileSet([[a, b, a, b] for a in range(2) for b in range(2)], 2)
    p = BoardProblem(Board.rect(4, 3), ts)
    assert wang.count(p).value == 2 ** 3 * 2 ** 4
    tilings = list(wang.enumerate_tilings(p, limit=5))
    assert len(tilings) == 5 and all(not board_violations(p, t) for t in tilings)


@pytest.mark.parametrize("kind", ["rect", "torus", "cylinder", "mobius", "klein"])
def test_sat_and_cpsat_agree_and_verify(kind):
    b = getattr(Board, kind)(5, 4)
    for seed in range(3):
        p = BoardProblem(b, WangTileSet.brick(3), random_boundary(b, 3, seed=seed))
        rep = wang.crosscheck(p, seed=seed, methods=("sat", "cpsat"))
        assert rep.ok, rep.lines


def test_unsat_has_checked_proof():
    # one cell, W = E and N = S forced: a cross, not a brick tile
    p = BoardProblem(Board.rect(1, 1), WangTileSet.brick(3), [0, 1, 0, 1])
    for m in ("sat", "cpsat"):
        s = wang.solve(p, method=m)
        assert s.status.value == "unsat"
    s = wang.solve(p, method="sat")
    assert "checked" in s.reason
    # the 1x1 torus joins W to E and N to S: only crosses fit
    assert wang.solve(BoardProblem(Board.torus(1, 1), WangTileSet.brick(3)), method="sat").status.value == "unsat"


def test_generic_tileset_on_mobius():
    # tiles copying W->E and N->S; on a Möbius strip the twist flips N/S roles: still solvable
    ts = WangTileSet([[b, a, c, a] for a in range(2) for b in range(2) for c in range(2)], 2)  # N, E, S, W
    p = BoardProblem(Board.mobius(4, 3), ts)
    s = wang.solve(p, method="auto")
    assert s.status.value == "sat" and s.method == "sat" and any("not applicable" in n for n in s.notes)


def test_methods_and_errors():
    p = BoardProblem(Board.rect(2, 2), WangTileSet.brick(3))
    with pytest.raises(InvalidProblem, match="unknown method"):
        wang.solve(p, method="magic")
    with pytest.raises(MethodNotApplicable):
        wang.solve(BoardProblem(Board.rect(2, 2), WangTileSet.brick(3), max_h=1), method="cpsat")
    assert set(wang.METHODS) == {"auto", "linear", "sat", "cpsat", "theorem7", "wall", "procedural", "npd"}


def test_line_windows_and_limits():
    b = Board.rect(4, 2)
    w = line_windows(b.nbr_cell, b.nbr_leg, "H", 3)
    assert w.shape == (4, 3)
    t = line_windows(Board.torus(3, 2).nbr_cell, Board.torus(3, 2).nbr_leg, "V", 3)
    assert t.shape == (6, 3)
    for lim in (1, 2):
        p = BoardProblem(Board.rect(6, 6), WangTileSet.brick(3), random_boundary(b := Board.rect(6, 6), 3, seed=2),
                         max_h=lim, max_v=lim)
        s = wang.solve(p, method="auto", seed=0)
        assert s.status.value in ("sat", "unsat")
        if s.status.value == "sat":
            assert not board_violations(p, s.tiling)


def test_encoding_accepts_exactly_valid_tilings():
    p = BoardProblem(Board.rect(3, 3), WangTileSet.brick(3), random_boundary(Board.rect(3, 3), 3, seed=3))
    enc = encode_wang(p)
    s = wang.solve(p, method="linear", seed=2)
    from tilesolve.engine.sat import solve_cnf

    assert solve_cnf(enc.clauses, assumptions=enc.literals(s.tiling)).status.value == "sat"
    eid, ne = p.board.leg_edges()
    col = np.zeros(ne, np.int64)
    col[eid.ravel()] = np.asarray(s.tiling).ravel()
    for e in range(ne):  # recolour one edge: the CNF and the verifier must agree
        c2 = col.copy()
        c2[e] = (c2[e] + 1) % 3
        t = c2[eid]
        cnf = solve_cnf(enc.clauses, assumptions=enc.literals(t)).status.value
        assert (cnf == "sat") == (not board_violations(p, t))
