"""All polyforms of a size: Redelmeier's algorithm (Redelmeier 1981, "Counting polyominoes:
yet another attack") for the fixed ones, reduced to free ones by the grid's point group.

A fixed polyform (one translation class) has one least cell in lexicographic order; translated
so that this cell is a start cell (the origin cell of each cell type of the grid), it is a
connected set of cells not less than the start. Redelmeier's untried-set recursion lists every
such set exactly once. A free polyform is kept when its fixed form equals its canonical form
(:meth:`tilesolve.model.shapes.Grid.canonical`), the least image under the point group.
"""

from __future__ import annotations

from typing import Iterator

from tilesolve.model.shapes import Grid, Polyform, grid

__all__ = ["fixed_polyforms", "free_polyforms"]


def _starts(g: Grid) -> list[tuple[int, int]]:
    return [(0, 0)] if g.period == 1 else [(1, 1), (2, 2)]


def fixed_polyforms(grid_name: str, n: int) -> Iterator[tuple[tuple[int, int], ...]]:
    """Every fixed polyform of ``n`` cells, as a sorted tuple of cells whose least cell is a
    start cell.

    Examples
    --------
    >>> sum(1 for _ in fixed_polyforms("omino", 4))
    19
    """
    g = grid(grid_name)
    for start in _starts(g):
        yield from _redelmeier(g, start, n)


def _redelmeier(g: Grid, start: tuple[int, int], n: int) -> Iterator[tuple[tuple[int, int], ...]]:
    cells: list[tuple[int, int]] = []
    seen = {start}  # cells ever put in an untried set on the current path (or the polyform)

    def grow(untried: list[tuple[int, int]]) -> Iterator[tuple[tuple[int, int], ...]]:
        untried = list(untried)
        while untried:
            c = untried.pop()
            cells.append(c)
            if len(cells) == n:
                yield tuple(sorted(cells))
            else:
                added = [d for d in g.neighbours(c) if d > start and d not in seen]
                seen.update(added)
                yield from grow(untried + added)
                seen.difference_update(added)
            cells.pop()

    yield from grow([start])


def free_polyforms(grid_name: str, n: int, *, holes: bool = True) -> list[Polyform]:
    """Every free polyform of ``n`` cells (congruent ones counted once), in canonical form;
    without ``holes`` those with a hole are left out.

    Examples
    --------
    >>> [len(free_polyforms("omino", k)) for k in range(1, 6)]
    [1, 1, 2, 5, 12]
    """
    g = grid(grid_name)
    out = []
    for cells in fixed_polyforms(grid_name, n):
        norm = g.normalise(cells)
        if norm == g.canonical(cells):
            p = Polyform(grid_name, norm)
            if holes or not p.holes():
                out.append(p)
    return out
