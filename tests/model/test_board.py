"""Boards (Def. 1, 4, Example 5), tile sets (Def. 6, 9) and board problems (Def. 2)."""

import networkx as nx
import numpy as np
import pytest

from tilesolve.errors import InvalidProblem
from tilesolve.model.board import (
    E, LEG_NAMES, N, PAPER_LEGS, S, W, Board, BoardProblem, GridSpec, WangTileSet, parse_board_spec,
    parse_mask_text,
)
from tilesolve.io.mask import read_board_spec, read_mask


def test_rect_joins_and_counts():
    b = Board.rect(4, 3)
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
    b = getattr(Board, kind)(5, 4)  # 5 columns, 4 rows
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
    b = Board.klein(4, 3)
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
    ring = Board.ring(6, 4)
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
    b = read_board_spec(f"mask:{tmp_path / 'm.txt'}")
    assert b.n_cells == 3 and b.grid_spec == GridSpec(2, 2) and b.mask_of().tolist() == [[True, False], [True, True]]
    with pytest.raises(InvalidProblem, match="cannot read mask"):
        read_board_spec(f"mask:{tmp_path / 'missing.txt'}")
    with pytest.raises(InvalidProblem, match="cannot read board"):
        read_board_spec("hexagon:3x3")
    with pytest.raises(InvalidProblem, match="mask file"):
        parse_board_spec(f"mask:{tmp_path / 'm.txt'}")  # the model reads no files


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
    # W_B is listed in lexicographic order of the paper's legs l1..l4 = W, N, E, S
    paper = WangTileSet.brick(3).tiles[:, PAPER_LEGS]
    assert np.array_equal(paper, np.unique(paper, axis=0))


def test_legs_are_numbered_n_e_s_w_as_tiles_are():
    """Leg k of a cell is column k of its tile (N, E, S, W); the paper's l1..l4 are W, N, E, S."""
    assert (N, E, S, W) == (0, 1, 2, 3) and LEG_NAMES == ("N", "E", "S", "W")
    assert PAPER_LEGS.tolist() == [W, N, E, S]
    b = Board.rect(3, 3)
    centre = b.index_of()[(1, 1)]
    across = {N: (0, 1), E: (1, 2), S: (2, 1), W: (1, 0)}
    for k, (r, c) in across.items():
        assert b.nbr_cell[centre, k] == b.index_of()[(r, c)] and b.nbr_leg[centre, k] == (k + 2) % 4
    # boundary legs by cell, then leg N, E, S, W: the corner (0, 0) has N = 0 and W = 1
    assert b.nbr_leg[0, N] == 0 and b.nbr_leg[0, W] == 1 and b.nbr_cell[0, E] == 1
    ts = WangTileSet([[2, 0, 1, 0]], 3)
    assert ts.contains([[2, 0, 1, 0]]).all() and not ts.contains([[0, 2, 0, 1]]).any()


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


def _literal_grid(mask, wrap_rows, wrap_cols):
    """Joins of Board.grid read off the definition cell by cell (brick paper Def. 1, Example 5)."""
    H, Wd = mask.shape
    cells = [(r, c) for r in range(H) for c in range(Wd) if mask[r, c]]
    index = {rc: i for i, rc in enumerate(cells)}
    nc = np.full((len(cells), 4), -1)
    for i, (r, c) in enumerate(cells):
        for k, (dr, dc) in enumerate([(-1, 0), (0, 1), (1, 0), (0, -1)]):  # across N, E, S, W
            r2, c2 = r + dr, c + dc
            if not 0 <= c2 < Wd and wrap_cols:
                r2, c2 = (H - 1 - r2 if wrap_cols == "twist" else r2), c2 % Wd
            if not 0 <= r2 < H and wrap_rows:
                r2, c2 = r2 % H, (Wd - 1 - c2 if wrap_rows == "twist" else c2)
            nc[i, k] = index.get((r2, c2), -1)
    return np.array(cells).reshape(-1, 2), nc


@pytest.mark.parametrize("wrap_rows", [None, "plain", "twist"])
@pytest.mark.parametrize("wrap_cols", [None, "plain", "twist"])
def test_grid_builder_matches_the_definition_and_restrictions_keep_their_grid(wrap_rows, wrap_cols):
    rng = np.random.default_rng(5)
    for H, Wd in [(1, 1), (1, 4), (3, 1), (4, 5)]:
        mask = rng.random((H, Wd)) > 0.25
        mask[0, 0] = True
        b = Board.grid(mask, wrap_rows=wrap_rows, wrap_cols=wrap_cols)
        labels, nc = _literal_grid(mask, wrap_rows, wrap_cols)
        assert np.array_equal(b.labels, labels) and np.array_equal(b.nbr_cell, nc)
        Board(b.labels, b.nbr_cell, b.nbr_leg)  # the checked constructor accepts the joins
        assert b.grid_spec == GridSpec(H, Wd, wrap_rows, wrap_cols)
        keep = rng.random(b.n_cells) > 0.3
        keep[0] = True
        r = b.restrict(keep)
        g = Board.from_grid_spec(r.grid_spec, r.mask_of())
        for name in ("labels", "nbr_cell", "nbr_leg"):
            assert np.array_equal(getattr(r, name), getattr(g, name))
        e = b.edge_array()
        again = Board.from_edges(b.labels, e)
        assert np.array_equal(again.nbr_cell, b.nbr_cell) and np.array_equal(again.nbr_leg, b.nbr_leg)


def test_grid_spec_given_by_hand_is_checked():
    b = Board.mobius(4, 3)
    assert Board(b.labels, b.nbr_cell, b.nbr_leg, grid_spec=GridSpec(3, 4, None, "twist")).grid_spec == b.grid_spec
    with pytest.raises(InvalidProblem, match="not those of the grid"):
        Board(b.labels, b.nbr_cell, b.nbr_leg, grid_spec=GridSpec(3, 4, None, "plain"))
    with pytest.raises(InvalidProblem, match="do not fit"):
        Board(b.labels, b.nbr_cell, b.nbr_leg, grid_spec=GridSpec(2, 4))
    with pytest.raises(InvalidProblem, match="wrap must be"):
        Board.from_grid_spec(GridSpec(2, 2, "spiral"), np.ones((2, 2), bool))
    with pytest.raises(InvalidProblem, match="does not fit"):
        Board.from_grid_spec(GridSpec(2, 2), np.ones((3, 2), bool))
    assert Board.from_edges(b.labels, b.edge_array()).grid_spec is None


def test_from_edges_reports_bad_cells_and_legs():
    with pytest.raises(InvalidProblem, match="cell 5 leg 0, which does not exist"):
        Board.from_edges([[0, 0]], [[5, 0, -1, 0]])
    with pytest.raises(InvalidProblem, match="cell 0 leg 7, which does not exist"):
        Board.from_edges([[0, 0], [0, 1]], [[1, 0, 0, 7]])


@pytest.mark.parametrize("kind", ["rect", "torus", "cylinder", "mobius", "klein", "ring"])
def test_a_grid_boards_joins_are_made_on_first_use(kind):
    """A board built from its grid counts its cells and boundary legs on the grid, before its
    labels (of a full grid) and joins exist, as many as they then hold; a copy made by pickling
    keeps working."""
    import pickle

    rng = np.random.default_rng(3)
    for w, h in ((2, 2), (5, 4), (3, 7)):
        b = getattr(Board, kind)(w, h)
        keep = rng.random(b.n_cells) > 0.3
        keep[0] = True
        for board in (b, Board.from_grid_spec(b.grid_spec, b.restrict(keep).mask_of())):
            fresh = Board.from_grid_spec(board.grid_spec, board.mask_of(), kind=board.kind)
            n_boundary, n_cells, said = fresh.n_boundary, fresh.n_cells, fresh.describe()
            assert "nbr_cell" not in vars(fresh)
            assert n_cells == board.n_cells and said == board.describe()
            copy = pickle.loads(pickle.dumps(fresh))
            assert n_boundary == int((fresh.nbr_cell < 0).sum()) == board.n_boundary
            for name in ("labels", "nbr_cell", "nbr_leg"):
                assert np.array_equal(getattr(fresh, name), getattr(board, name))
                assert np.array_equal(getattr(copy, name), getattr(board, name))
    with pytest.raises(AttributeError):
        Board.rect(2, 2).no_such_thing  # noqa: B018
