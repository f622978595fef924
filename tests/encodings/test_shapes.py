"""The polyform CNFs: exact cover of regions and tori, coronas."""

from __future__ import annotations

import pytest
from pysat.solvers import Solver

from tilesolve.encodings.shapes import (encode_coronas, encode_surround, encode_tiling, lattice_basis, point_group,
                                        sequential_at_most_one, torus_reducer)
from tilesolve.model.shapes import GRIDS, ShapesProblem, parse_ascii, parse_cells


def _sat(enc) -> bool:
    with Solver(name="cadical153", bootstrap_with=enc.hard.to_lists()) as s:
        return s.solve()


@pytest.mark.parametrize("lattice", [((3, 0), (0, 4)), ((2, 1), (-1, 3)), ((6, 0), (1, 1))])
@pytest.mark.parametrize("grid", ["omino", "hex", "iamond"])
def test_the_torus_reducer_has_one_representative_per_class(grid, lattice):
    g = GRIDS[grid]
    reduce, reps = torus_reducer(g, lattice)
    (a, b), (c, d) = lattice
    assert len(reps) == abs(a * d - b * c) * (2 if grid == "iamond" else 1)
    assert sorted(map(reduce, reps)) == sorted(reps)
    p = g.period
    for cell in reps:
        for k, l in ((1, 0), (0, 1), (2, -3)):
            moved = (cell[0] + p * (k * a + l * c), cell[1] + p * (k * b + l * d))
            assert reduce(moved) == cell


def test_dominoes_on_a_rectangle_and_a_decoded_tiling():
    p = ShapesProblem("tile", (parse_ascii("##", "omino"),), region=tuple((x, y) for x in range(3) for y in range(2)))
    enc = encode_tiling(p)
    with Solver(name="cadical153", bootstrap_with=enc.hard.to_lists()) as s:
        assert s.solve()
        t = enc.decode(s.get_model())
    assert t.shape == (6, 4) and len(set(t[:, 0].tolist())) == 3
    assert all(v > 0 for v in enc.literals(t) if abs(v) in {abs(x) for x in enc.literals(t) if x > 0})


def test_an_odd_region_has_no_domino_tiling():
    p = ShapesProblem("tile", (parse_ascii("##", "omino"),), region=tuple((x, 0) for x in range(3)))
    assert not _sat(encode_tiling(p))


def test_a_placement_that_overlaps_itself_on_a_small_torus_is_left_out():
    p = ShapesProblem("tile", (parse_ascii("###", "omino"),), lattice=((2, 0), (0, 3)))
    enc = encode_tiling(p)
    assert all(len({c[1] for c in cells}) == 3 for _, cells in enc.placements)  # only the vertical bar fits
    assert _sat(enc)


def test_coronas_of_a_square_exist_and_of_a_non_tiler_stop():
    square = ShapesProblem("classify", (parse_ascii("#", "omino"),))
    assert _sat(encode_coronas(square, 2))
    hexes = ShapesProblem("classify", (parse_cells("0,0 0,1 0,2 0,3 1,-1 1,3", "hex"),))
    assert _sat(encode_coronas(hexes, 1)) and not _sat(encode_coronas(hexes, 2))


@pytest.mark.parametrize("grid, reflections", [("omino", True), ("omino", False), ("hex", True), ("iamond", False)])
def test_the_point_group_table_is_a_group_of_the_grids_matrices(grid, reflections):
    import numpy as np

    mats, product, inverse = point_group(GRIDS[grid], reflections)
    assert len(mats) == GRIDS[grid].order * (2 if reflections else 1) and (mats[0] == np.eye(2)).all()
    for a in range(len(mats)):
        assert product[a, inverse[a]] == 0 and product[inverse[a], a] == 0
        for b in range(len(mats)):
            assert (mats[product[a, b]] == mats[a] @ mats[b]).all()


@pytest.mark.parametrize("grid, art", [("omino", "#"), ("hex", "##"), ("iamond", "##")])
def test_every_surround_candidate_shares_an_edge_with_the_shape_without_overlapping_it(grid, art):
    p = ShapesProblem("classify", (parse_ascii(art, grid),))
    enc = encode_surround(p)
    g = GRIDS[grid]
    shape = set(enc.shape)
    around = {n for c in shape for n in g.neighbours(c)} - shape
    for m, t in zip(enc.m.tolist(), enc.t.tolist()):
        cells = {tuple(int(v) for v in enc.mats[m] @ c + t) for c in enc.shape}
        assert cells.isdisjoint(shape) and cells & around and all(g.is_cell(c) for c in cells)
    with Solver(name="cadical153", bootstrap_with=enc.clauses) as s:
        assert s.solve()


@pytest.mark.parametrize("vectors, basis", [([(3, 0), (0, 2)], ((3, 0), (0, 2))), ([(1, 2), (2, 1)], ((3, 0), (2, 1))),
                                            ([(0, 0), (5, 0)], None), ([(-2, -1), (4, 0)], ((4, 0), (2, 1)))])
def test_lattice_basis_is_the_hermite_form(vectors, basis):
    assert lattice_basis(vectors) == basis


@pytest.mark.parametrize("n", [3, 4, 9, 10, 17, 40])
def test_the_sequential_counter_is_pysats_clause_for_clause(n):
    import random

    from pysat.card import CardEnc

    rnd = random.Random(n)
    lits = [v * rnd.choice((1, -1)) for v in rnd.sample(range(1, 200), n)]
    top = 200 + rnd.randrange(50)
    assert sequential_at_most_one(lits, top).tolist() == CardEnc.atmost(lits, bound=1, top_id=top, encoding=1).clauses


def test_the_half_turn_surround_holds_only_translations_and_half_turns():
    p = ShapesProblem("classify", (parse_ascii("###\n#..", "omino"),))
    full, half = encode_surround(p), encode_surround(p, half_turns=True)
    kept = {(m, tuple(t)) for m, t in zip(full.m.tolist(), full.t.tolist()) if m in (0, 2)}  # I and the half-turn
    assert {(m, tuple(t)) for m, t in zip(half.m.tolist(), half.t.tolist())} == kept
    assert (full.mats[2] == -full.mats[0]).all()
