"""Classification of polyforms: tori, isohedral tilings, Heesch numbers."""

from __future__ import annotations

import numpy as np
import pytest

from tilesolve.engine.shapes import classify, is_isohedral, lattices
from tilesolve.errors import InvalidProblem
from tilesolve.model.shapes import GRIDS, ShapesProblem, parse_ascii, parse_cells
from tilesolve.model.solution import Status
from tilesolve.verify.shapes import shapes_violations

#: The 2-anisohedral 6-hex (tiles only with two transitivity classes) and a 6-hex with Heesch number 1.
ANISOHEDRAL = "0,0 0,1 1,-3 1,-1 2,-3 2,-2"
HEESCH1 = "0,0 0,1 0,2 0,3 1,-1 1,3"


def test_lattices_are_counted_by_sigma():
    assert [len(list(lattices(n))) for n in (1, 2, 6, 12)] == [1, 3, 12, 28]


@pytest.mark.parametrize("grid, art", [("omino", "##\n#."), ("hex", "###"), ("iamond", "###"), ("omino", "#")])
def test_simple_shapes_tile_isohedrally_with_a_verified_witness(grid, art):
    p = ShapesProblem("classify", (parse_ascii(art, grid),))
    sol = classify(p, seed=1)
    assert sol.report.verdict == "isohedral" and sol.status is Status.SAT
    assert shapes_violations(p, sol.report) == []


def test_a_non_tiler_gets_its_heesch_number_with_a_checked_refutation():
    p = ShapesProblem("classify", (parse_cells(HEESCH1, "hex"),))
    sol = classify(p, seed=1)
    r = sol.report
    assert (r.verdict, r.heesch) == ("non-tiler", 1)
    assert r.refutation["proof_status"] == "verified" and r.refutation["level"] == 2
    assert shapes_violations(p, r) == []


def test_the_two_anisohedral_hex_tiles_with_two_copies_but_not_isohedrally():
    p = ShapesProblem("classify", (parse_cells(ANISOHEDRAL, "hex"),), max_copies=2)
    r = classify(p, seed=1).report
    assert (r.verdict, r.copies) == ("periodic", 2)
    pieces = [[tuple(c) for c in r.tiling[r.tiling[:, 0] == k][:, 2:].tolist()] for k in np.unique(r.tiling[:, 0])]
    assert not is_isohedral(GRIDS["hex"], pieces, r.lattice)
    assert shapes_violations(p, r) == []


def test_a_lattice_tiling_is_isohedral():
    g = GRIDS["omino"]
    assert is_isohedral(g, [[(0, 0), (1, 0)]], ((2, 0), (0, 1)))


def test_with_one_level_a_tiler_search_that_finds_no_torus_is_inconclusive():
    p = ShapesProblem("classify", (parse_cells(ANISOHEDRAL, "hex"),), max_copies=1, max_level=1)
    sol = classify(p, seed=1)
    assert sol.report.verdict == "inconclusive" and sol.status is Status.UNKNOWN
    assert shapes_violations(p, sol.report) == []


def test_absurd_tilings_are_refused_with_an_estimate():
    from tilesolve.engine.shapes import check_size

    p = ShapesProblem("tile", (parse_ascii("#" * 19 + "\n#", "omino"),), lattice=((140, 0), (0, 140)))
    with pytest.raises(InvalidProblem, match="about .* literals"):
        check_size(p)
