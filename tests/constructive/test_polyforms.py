"""Free polyforms by Redelmeier's algorithm, counted against OEIS A000105 (polyominoes),
A000228 (polyhexes) and A000577 (polyiamonds)."""

from __future__ import annotations

import pytest

from tilesolve.constructive.polyforms import fixed_polyforms, free_polyforms

OMINOES = [1, 1, 2, 5, 12, 35, 108, 369, 1285, 4655]
HEXES = [1, 1, 3, 7, 22, 82, 333, 1448]
IAMONDS = [1, 1, 1, 3, 4, 12, 24, 66, 160, 448]


@pytest.mark.parametrize("grid, counts, fast", [("omino", OMINOES, 7), ("hex", HEXES, 6), ("iamond", IAMONDS, 8)])
def test_free_counts_match_oeis_small_sizes(grid, counts, fast):
    assert [len(free_polyforms(grid, n)) for n in range(1, fast + 1)] == counts[:fast]


@pytest.mark.slow
@pytest.mark.parametrize("grid, counts, fast", [("omino", OMINOES, 7), ("hex", HEXES, 6), ("iamond", IAMONDS, 8)])
def test_free_counts_match_oeis_large_sizes(grid, counts, fast):
    assert [len(free_polyforms(grid, n)) for n in range(fast + 1, len(counts) + 1)] == counts[fast:]


def test_fixed_counts():
    # A001168 fixed polyominoes, A001207 fixed polyhexes, A001420 fixed polyiamonds
    assert [sum(1 for _ in fixed_polyforms("omino", n)) for n in range(1, 7)] == [1, 2, 6, 19, 63, 216]
    assert [sum(1 for _ in fixed_polyforms("hex", n)) for n in range(1, 5)] == [1, 3, 11, 44]
    assert [sum(1 for _ in fixed_polyforms("iamond", n)) for n in range(1, 6)] == [2, 3, 6, 14, 36]


def test_holes_filter():
    assert len(free_polyforms("hex", 6, holes=False)) == 81
    assert len(free_polyforms("omino", 7, holes=False)) == 107  # the one 7-omino with a hole is left out
    assert all(not p.holes() for p in free_polyforms("iamond", 6, holes=False))


def test_every_free_polyform_is_distinct_and_connected():
    forms = free_polyforms("iamond", 7)
    assert len({p.cells for p in forms}) == len(forms)
    assert all(p.size == 7 for p in forms)
