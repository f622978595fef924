"""Boards (Def. 1, 4, Example 5), tile sets (Def. 6, 9) and board problems (Def. 2)."""

import networkx as nx
import numpy as np
import pytest

from tilesolve.errors import InvalidProblem
from tilesolve.model.board import (
    E, N, S, W, Board, BoardProblem, WangTileSet, parse_board_spec, parse_mask_text, read_mask,
    wang_from_nesw, wang_to_nesw,
)


def test_rect_joins_and_counts():
    b = Board.rect(3, 4)
    assert b.n_cells == 12 and b.n_boundary == 2 * (3 + 4)
    idx = b.index_of()
    a = idx[(1, 1)]
    assert b.nbr_cell[a, E] == idx[(1, 2)] and b.nbr_leg[a, E] == W
    assert b.nbr_cell[a, S] == idx[(2, 1)] and b.nbr_leg[a, S] == N
    assert b.nbr_cell[idx[(0, 0)], N] == -1
    # l1/l3 and l2/l4 are opposite: a join always meets the opposite leg on a grid
    inner = b.nbr_cell >= 0
    assert (b.nbr_leg[inner] == (np.nonzero(inner)[1] + 2) % 4).all()
    eid, ne = b.leg_edges()
    assert ne == b.n_edges == (3 * 3 + 2 * 4) + 14


@pytest.mark.parametrize("kind,boundary", [("torus", 0), ("klein", 0), ("cylinder", 2 * 5), ("mobius", 2 * 5)])
def test_surfaces(kind, boundary):
    b = getattr(Board, kind)(4, 5)
    assert b.n_cells == 20 and b.n_boundary == boundary
    assert (b.degree_in_cells() == 4 - (b.nbr_cell < 0).sum(axis=1)).all()


def test_mobius_example5_identification():
    n = 5
    b = Board.mobius(n, n)
    idx = b.index_of()
    # paper: j = 1 joined to j' = N where i + i' = N + 1 (1-based); here col 0 and col n-1
    for r in range(n):
        a = idx[(r, n - 1)]
        assert b.nbr_cell[a, E] == idx[(n - 1 - r, 0)] and b.nbr_leg[a, E] == W
    # boundary B: the rows i = 1 and i = N
    rows = b.labels[b.boundary_legs[:, 0], 0]
    assert set(rows.tolist()) == {0, n - 1}
    assert nx.is_connected(b.cell_graph())


def test_restriction_def4_and_networkx():
    b = Board.rect(5, 5)
    keep = np.ones(25, bool)
    keep[[6, 7, 8, 11, 12, 13, 16, 17, 18]] = False  # dig a 3x3 hole
    r = b.restrict(keep)
    assert r.n_cells == 16 and r.n_boundary == 20 + 12
    g = r.to_networkx()
    assert g.degree("wall") == r.n_boundary
    assert all(g.degree(v) == 4 for v in range(r.n_cells))
    assert len(nx.cycle_basis(nx.Graph(r.cell_graph()))) == 1


def test_from_edges_round_trip_and_bad_edges():
    b = Board.klein(3, 4)
    b2 = Board.from_edges(b.labels.tolist(), b.edge_list())
    assert np.array_equal(b.nbr_cell, b2.nbr_cell) and np.array_equal(b.nbr_leg, b2.nbr_leg)
    with pytest.raises(InvalidProblem, match="not joined"):
        Board.from_edges([[0, 0]], [[0, 0, -1, 0]])
    with pytest.raises(InvalidProblem, match="joined twice"):
        Board.from_edges([[0, 0]], [[0, 0, -1, 0], [0, 0, -1, 1], [0, 1, -1, 2], [0, 2, -1, 3]])


def test_tree_and_ring_builders():
    t = Board.random_tree(30, seed=4)
    g = nx.Graph(t.cell_graph())
    assert nx.is_tree(g) and t.n_cells == 30
    ring = Board.ring(4, 6)
    assert len(nx.cycle_basis(nx.Graph(ring.cell_graph()))) == 1


def test_masks(tmp_path):
    m = parse_mask_text("###\n#.#\n###\n")
    assert m.sum() == 8
    with pytest.raises(InvalidProblem, match="not '#'"):
        parse_mask_text("#x#")
    with pytest.raises(InvalidProblem, match="no '#'"):
        parse_mask_text("...")
    from PIL import Image

    img = np.zeros((3, 4, 4), np.uint8)
    img[1, 1:3, 3] = 255
    Image.fromarray(img, "RGBA").save(tmp_path / "m.png")
    pm = read_mask(tmp_path / "m.png")
    assert pm.sum() == 2 and pm[1, 1] and pm[1, 2]
    (tmp_path / "m.txt").write_text("#.\n##\n")
    b = parse_board_spec(f"mask:{tmp_path / 'm.txt'}")
    assert b.n_cells == 3
    with pytest.raises(InvalidProblem, match="cannot read mask"):
        parse_board_spec(f"mask:{tmp_path / 'missing.txt'}")
    with pytest.raises(InvalidProblem, match="cannot read board"):
        parse_board_spec("hexagon:3x3")


def test_brick_tiles_def9_and_three_boundary():
    for k in (3, 4, 5):
        wb = WangTileSet.brick(k)
        # (c1 = c3, c2 != c4) or (c1 != c3, c2 = c4): 2 * k * k * (k - 1) tiles
        assert len(wb) == 2 * k * k * (k - 1)
        assert wb.three_boundary()
        t = wb.tiles
        assert (((t[:, 0] == t[:, 2]) ^ (t[:, 1] == t[:, 3]))).all()
    assert not WangTileSet([[0, 0, 0, 0]], 2).three_boundary()
    with pytest.raises(InvalidProblem, match="#C >= 3"):
        WangTileSet.brick(2)
    with pytest.raises(InvalidProblem, match="empty"):
        WangTileSet([], 3)
    with pytest.raises(InvalidProblem, match="outside C"):
        WangTileSet([[0, 1, 2, 3]], 3)
    assert np.array_equal(wang_to_nesw(wang_from_nesw([[1, 2, 3, 4]])), [[1, 2, 3, 4]])
    assert wang_from_nesw([[1, 2, 3, 4]]).tolist() == [[4, 1, 2, 3]]


def test_problem_validation():
    b = Board.rect(2, 2)
    wb = WangTileSet.brick(3)
    p = BoardProblem(b, wb)
    assert (p.boundary == -1).all()
    with pytest.raises(InvalidProblem, match="outside C"):
        BoardProblem(b, wb, [3] * 8)
    with pytest.raises(InvalidProblem, match="not on the boundary"):
        BoardProblem(b, wb, [0] * 9)
    with pytest.raises(InvalidProblem, match="not on the boundary"):
        BoardProblem.from_boundary_legs(b, wb, {(0, E): 1})
    q = BoardProblem.from_boundary_legs(b, wb, {(0, W): 1, (0, N): 2})
    assert sorted(q.boundary[q.boundary >= 0].tolist()) == [1, 2]
    with pytest.raises(InvalidProblem, match="brick"):
        BoardProblem(b, WangTileSet([[0, 0, 0, 0]], 1), max_h=2)
