"""Classification of polyforms: tori, isohedral tilings, Heesch numbers."""

from __future__ import annotations

import numpy as np
import pytest

from tilesolve.engine.shapes import classify, is_isohedral, lattices
from tilesolve.errors import InvalidProblem
from tilesolve.model.shapes import GRIDS, ShapesProblem, ShapesReport, parse_ascii, parse_cells
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


#: Three 7-ominoes that tile isohedrally only with 4 copies per period (no 1- or 2-copy torus
#: tiling of them is isohedral; heesch-sat calls them isohedral too).
FOUR_COPY_7_OMINOES = ["0,0 0,1 1,-1 1,0 2,0 3,0 3,1", "0,0 0,1 0,2 1,-1 1,0 1,2 1,3",
                       "0,0 0,1 0,2 0,3 0,4 1,0 1,3"]


@pytest.mark.parametrize("cells", FOUR_COPY_7_OMINOES)
def test_a_7_omino_with_4_copies_a_period_is_isohedral_with_a_verified_witness(cells):
    from tilesolve.deadline import NO_LIMIT
    from tilesolve.engine.shapes import _torus_search

    p = ShapesProblem("classify", (parse_cells(cells, "omino"),), max_copies=2)
    found, _ = _torus_search(p, NO_LIMIT, "cadical153", 0, range(1, 3))
    assert found is None or found[0] == "periodic"  # the torus search up to 2 copies finds no isohedral tiling
    sol = classify(p, seed=0)
    r = sol.report
    assert (r.verdict, r.copies, sol.status) == ("isohedral", 4, Status.SAT)
    assert sol.stats["surrounds"] >= 1
    assert shapes_violations(p, r) == []


def test_a_closed_surround_is_found_for_a_tiler_and_none_for_a_non_tiler():
    from tilesolve.deadline import NO_LIMIT
    from tilesolve.engine.shapes import _surround_search

    tiler = ShapesProblem("classify", (parse_ascii("###\n.###", "hex"),))
    found, tried = _surround_search(tiler, NO_LIMIT, "cadical153", 0)
    assert found is not None and found[0] == "isohedral" and tried >= 1
    assert shapes_violations(tiler, ShapesReport("isohedral", copies=found[1], lattice=found[2],
                                                 tiling=found[3])) == []
    non_tiler = ShapesProblem("classify", (parse_cells(HEESCH1, "hex"),))
    assert _surround_search(non_tiler, NO_LIMIT, "cadical153", 0) == (None, 0)


def test_the_anisohedral_hex_has_no_closed_surround_that_tiles():
    from tilesolve.deadline import NO_LIMIT
    from tilesolve.engine.shapes import _surround_search

    p = ShapesProblem("classify", (parse_cells(ANISOHEDRAL, "hex"),))
    assert _surround_search(p, NO_LIMIT, "cadical153", 0)[0] is None


def test_a_surround_whose_group_spans_a_line_gives_no_tiling():
    from tilesolve.encodings.shapes import encode_surround
    from tilesolve.engine.shapes import surround_tiling

    enc = encode_surround(ShapesProblem("classify", (parse_ascii("##", "omino"),)))
    right = [i for i in range(enc.n_vars) if enc.m[i] == 0 and tuple(enc.t[i]) in ((2, 0), (-2, 0))]
    assert len(right) == 2 and surround_tiling(enc, right) is None
    up = [i for i in range(enc.n_vars) if enc.m[i] == 0 and tuple(enc.t[i]) in ((0, 1), (0, -1))]
    copies, lattice, tiling = surround_tiling(enc, right + up)
    assert (copies, lattice) == (1, ((2, 0), (0, 1)))

