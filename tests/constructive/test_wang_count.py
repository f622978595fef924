"""Counting Wang tilings of rectangles, cylinders and tori by the transfer method
(tilesolve.constructive.wang_count), checked against brute force and SAT enumeration."""

from __future__ import annotations

import itertools

import pytest
from clitools import one_line_error, run
from hypothesis import given, settings
from hypothesis import strategies as st

from tilesolve.constructive.wang_count import count_grid, transfer_applies
from tilesolve.errors import InvalidProblem
from tilesolve.io.builtin_tilesets import load
from tilesolve.model.board import Board, BoardProblem, WangTileSet


def brute_force(nesw, rows, cols, wrap_rows, wrap_cols) -> int:
    """Try every assignment of tiles to cells and check every inner edge."""
    total = 0
    for pick in itertools.product(range(len(nesw)), repeat=rows * cols):
        g = [[nesw[pick[r * cols + c]] for c in range(cols)] for r in range(rows)]
        ok = True
        for r in range(rows):
            for c in range(cols):
                n, e, s, w = g[r][c]
                if c + 1 < cols or wrap_cols:
                    ok &= e == g[r][(c + 1) % cols][3]
                if r + 1 < rows or wrap_rows:
                    ok &= s == g[(r + 1) % rows][c][0]
        total += ok
    return total


tilesets = st.integers(1, 3).flatmap(lambda k: st.lists(
    st.tuples(*[st.integers(0, k - 1)] * 4), min_size=1, max_size=4, unique=True).map(lambda t: (k, t)))


@settings(max_examples=60, deadline=None)
@given(tilesets, st.integers(1, 3), st.integers(1, 2), st.booleans(), st.booleans())
def test_transfer_matches_brute_force(kt, rows, cols, wrap_rows, wrap_cols):
    k, tiles = kt
    ts = WangTileSet(tiles, k)
    nesw = [tuple(t) for t in ts.tiles.tolist()]
    assert count_grid(ts, rows, cols, wrap_rows=wrap_rows, wrap_cols=wrap_cols) == \
        brute_force(nesw, rows, cols, wrap_rows, wrap_cols)


@pytest.mark.parametrize("spec", ["rect:3x2", "torus:2x3", "cylinder:3x2", "rect:1x4"])
def test_board_count_transfer_equals_enumeration(spec):
    from tilesolve.families import board as facade
    from tilesolve.io.mask import read_board_spec

    ts = WangTileSet([[0, 1, 1, 0], [1, 0, 0, 1], [0, 0, 1, 1], [1, 1, 0, 0], [0, 0, 0, 0]], 2)
    problem = BoardProblem(read_board_spec(spec), ts)
    fast = facade.count(problem, method="transfer")
    slow = facade.count(problem, method="enumerate")
    assert fast.method == "transfer" and slow.method != "transfer"
    assert fast.value == slow.value and fast.exact and fast.value > 0
    assert facade.count(problem).method == "transfer"  # auto picks it


def test_auto_falls_back_to_enumeration():
    from tilesolve.families import board as facade

    ts = WangTileSet([[0, 0, 0, 0], [1, 1, 1, 1], [0, 1, 0, 1]], 2)
    mobius = BoardProblem(Board.mobius(3, 2), ts)
    assert "twisted" in transfer_applies(mobius)
    res = facade.count(mobius)
    assert res.method != "transfer" and res.value == brute_force_board(mobius)
    fixed = BoardProblem(Board.rect(2, 2), ts, [0] * 8)
    assert transfer_applies(fixed) == "boundary colours are fixed"
    with pytest.raises(Exception, match="boundary colours are fixed"):
        facade.count(fixed, method="transfer")


def brute_force_board(problem) -> int:
    """Brute force on any board through its joins (legs N, E, S, W: a tile's columns)."""
    b, t = problem.board, problem.tileset.tiles.tolist()
    total = 0
    for pick in itertools.product(range(len(t)), repeat=b.n_cells):
        total += all(b.nbr_cell[a, leg] < 0 or t[pick[a]][leg] == t[pick[b.nbr_cell[a, leg]]][b.nbr_leg[a, leg]]
                     for a in range(b.n_cells) for leg in range(4))
    return total


def test_big_counts_are_exact():
    # all 16 tiles over 2 colours: every edge colour free, 2^(edges) tilings
    ts = WangTileSet(list(itertools.product(range(2), repeat=4)), 2)
    assert count_grid(ts, 6, 6) == 2 ** (6 * 7 * 2)
    assert count_grid(ts, 6, 6, wrap_rows=True, wrap_cols=True) == 2 ** (6 * 6 * 2)  # above 2^53: modular path
    assert count_grid(ts, 3, 7, wrap_rows=True) == 2 ** (3 * 7 + 3 * 8)


def test_jeandel_rao_has_no_small_torus_but_squares():
    jr, _ = load("jeandel-rao")
    assert count_grid(jr, 6, 6) > 0
    assert all(count_grid(jr, p, q, wrap_rows=True, wrap_cols=True) == 0 for p in range(1, 5) for q in range(1, 5))


def test_other_orientation_when_rows_explode(monkeypatch):
    import tilesolve.constructive.wang_count as wc

    # every tile meets every tile side by side (16 partial rows of width 2), but N/S colours
    # follow a 4-cycle (4 partial columns): refused one way, counted the other way
    ts = WangTileSet([(i, 0, (i + 1) % 4, 0) for i in range(4)], 4)
    nesw = [tuple(t) for t in ts.tiles.tolist()]
    expected = brute_force(nesw, 4, 2, True, False)
    assert expected > 0 and count_grid(ts, 4, 2, wrap_rows=True) == expected
    monkeypatch.setattr(wc, "MAX_STATES", 8)
    assert count_grid(ts, 4, 2, wrap_rows=True) == expected
    with pytest.raises(InvalidProblem, match="too many partial rows"):
        wc._rows(ts.tiles, 4, 2, False)


def test_refuses_absurd_rows():
    ts, _ = load("labbe-u19")
    with pytest.raises(InvalidProblem, match="too long for the transfer method"):
        count_grid(ts, 100, 100)
    with pytest.raises(InvalidProblem, match="at least one row"):
        count_grid(ts, 0, 3)


# ------------------------------------------------------------------ the commands
@pytest.mark.slow
def test_cli_wang_count_and_builtin_sets(tmp_path):
    proc = run("wang", "count", "--builtin", "jeandel-rao", "--board", "rect:3x2", cwd=tmp_path)
    assert proc.returncode == 0 and "by transfer" in proc.stderr
    jr, _ = load("jeandel-rao")
    assert int(proc.stdout.split()[-1]) == count_grid(jr, 2, 3)
    # an n s w e file of the same set gives the same count through --tiles
    (tmp_path / "jr.tiles").write_text("".join(f"{n} {s} {w} {e}\n" for n, e, s, w in jr.tiles.tolist()))
    again = run("wang", "count", "--tiles", "jr.tiles", "--board", "rect:3x2", cwd=tmp_path)
    assert again.returncode == 0 and again.stdout == proc.stdout
    listing = run("tiles", "--builtin", cwd=tmp_path)
    assert listing.returncode == 0 and "jeandel-rao " in listing.stdout and "aperiodic" in listing.stdout
    printed = run("tiles", "--builtin", "kari-14", "-o", "k.json", cwd=tmp_path)
    assert printed.returncode == 0 and len(printed.stdout.splitlines()) == 14
    solved = run("wang", "solve", "--tiles", "k.json", "--board", "rect:4x4", "--boundary", "free", cwd=tmp_path)
    assert solved.returncode == 0
    solved = run("wang", "solve", "--builtin", "jeandel-rao", "--board", "torus:2x2", "--boundary", "free",
                 cwd=tmp_path)
    assert solved.returncode == 1  # no 2x2 period
    assert "no built-in tile set" in one_line_error(run("wang", "count", "--builtin", "x", "--board", "rect:2x2",
                                                        cwd=tmp_path))
    assert "--tiles FILE or --builtin NAME" in one_line_error(
        run("wang", "count", "--builtin", "jeandel-rao", "--tiles", "jr.tiles", "--board", "rect:2x2", cwd=tmp_path))
    (tmp_path / "bad.tiles").write_text("0 1 2\n")
    assert "line 1: a tile needs 4 colours" in one_line_error(
        run("wang", "count", "--tiles", "bad.tiles", "--board", "rect:2x2", cwd=tmp_path))
    assert not (tmp_path / "x.json").exists()
