"""Polyforms on the three grids: cells, neighbours, symmetries, parsing, holes, problem checks."""

from __future__ import annotations

import pytest

from tilesolve.errors import InvalidProblem
from tilesolve.model.shapes import GRIDS, Polyform, ShapesProblem, parse_ascii, parse_cells


@pytest.mark.parametrize("name, edge, corner", [("omino", 4, 8), ("hex", 6, 6), ("iamond", 3, 12)])
def test_each_cell_has_the_grid_s_neighbours(name, edge, corner):
    g = GRIDS[name]
    for c in ([(0, 0)] if name != "iamond" else [(1, 1), (2, 2)]):
        assert len(g.neighbours(c)) == edge and len(g.touching(c)) == corner
        assert all(c in g.neighbours(n) for n in g.neighbours(c))


@pytest.mark.parametrize("name, order", [("omino", 8), ("hex", 12), ("iamond", 12)])
def test_the_point_group_maps_cells_to_cells_and_keeps_adjacency(name, order):
    g = GRIDS[name]
    assert len(g.matrices) == order
    c = (0, 0) if name != "iamond" else (1, 1)
    for m in g.matrices:
        img = tuple(int(v) for v in m @ c)
        assert g.is_cell(img)
        assert sorted(tuple(int(v) for v in m @ n) for n in g.neighbours(c)) == sorted(g.neighbours(img))


def test_an_asymmetric_shape_has_a_full_orbit_and_a_symmetric_one_less():
    assert len(GRIDS["omino"].images(parse_ascii("##\n#.\n#.", "omino").cells)) == 8   # L tetromino
    assert len(GRIDS["omino"].images(parse_ascii("##\n##", "omino").cells)) == 1
    assert len(GRIDS["hex"].images(parse_ascii("##", "hex").cells)) == 3


def test_parsing_ascii_and_cells_agree():
    assert parse_ascii("##\n#.", "omino") == parse_cells("0,0 0,1 1,1", "omino")
    tri = parse_ascii("###", "iamond")  # up, down, up
    assert tri.size == 3 and {GRIDS["iamond"].cell_type(c) for c in tri.cells} == {(1, 1), (2, 2)}


def test_holes_are_found():
    assert parse_ascii("###\n#.#\n###", "omino").holes() == [((1, 1),)]
    assert parse_ascii("##.\n#.#\n.##", "hex").holes() == [((1, 0),)]
    assert parse_ascii("###\n#..", "omino").holes() == []


@pytest.mark.parametrize("make, message", [
    (lambda: parse_cells("0,0 2,0", "omino"), "edge-connected"),
    (lambda: parse_cells("0,0 0,0", "omino"), "distinct"),
    (lambda: parse_cells("0,0", "square"), "unknown grid"),
    (lambda: parse_cells("0,0", "iamond"), "not a cell"),
    (lambda: parse_cells("0,a", "omino"), "x,y"),
    (lambda: parse_ascii("#?", "omino"), "ASCII art"),
    (lambda: ShapesProblem("tile", (parse_cells("0,0", "omino"),)), "region or a torus"),
    (lambda: ShapesProblem("tile", (parse_cells("0,0", "omino"),), lattice=((1, 2), (2, 4))), "parallel"),
    (lambda: ShapesProblem("tile", (parse_cells("0,0", "omino"),), lattice=((1000, 0), (0, 1000))), "too large"),
    (lambda: ShapesProblem("classify", (parse_cells("0,0", "omino"),) * 2), "exactly one"),
    (lambda: ShapesProblem("paint", (parse_cells("0,0", "omino"),)), "unknown question"),
])
def test_bad_input_is_one_invalid_problem(make, message):
    with pytest.raises(InvalidProblem, match=message):
        make()


def test_a_polyform_is_normalised_by_translation():
    assert Polyform("omino", ((5, 5), (6, 5))).cells == ((0, 0), (1, 0))
    assert Polyform("iamond", ((7, 7), (8, 8))).cells == ((1, 1), (2, 2))
