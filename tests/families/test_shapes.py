"""The shapes family through the pipeline, the census, and heesch-sat's 6-hex table (Kaplan's
README: of the 81 holeless free 6-hexes, 76 tile isohedrally, 4 are non-tilers (three with
Heesch number 1, one with 2), and one, the 2-anisohedral 6-hex, is inconclusive for heesch-sat)."""

from __future__ import annotations

from collections import Counter

import pytest

from tilesolve.families.shapes import FAMILY, census, polyforms, solve
from tilesolve.errors import InvalidProblem
from tilesolve.model.shapes import ShapesProblem, parse_ascii
from tilesolve.model.solution import Status

ANISOHEDRAL = ((0, 0), (0, 1), (1, -3), (1, -1), (2, -3), (2, -2))


def test_unsat_region_with_a_checked_proof_and_a_named_encoding():
    p = ShapesProblem("tile", (parse_ascii("###\n.#.", "omino"),), region=tuple((x, y) for x in range(4) for y in range(3)))
    sol = solve(p, seed=1)
    assert sol.status is Status.UNSAT and sol.stats["proof_status"] == "verified"
    assert sol.stats["encoding"]["name"] == "shapes-tile-cnf"


def test_pentominoes_tile_a_rectangle_together():
    shapes = (parse_ascii("#####", "omino"), parse_ascii("##\n##\n#.", "omino"))
    p = ShapesProblem("tile", shapes, region=tuple((x, y) for x in range(5) for y in range(3)))
    assert solve(p, seed=1).status is Status.SAT  # the pipeline verified it


def test_the_census_of_tetrominoes():
    rows, n = census("omino", 4, workers=1)
    assert n == 5 and all(r.verdict == "isohedral" and not r.problems for r in rows)


def test_listing_refuses_sizes_that_take_too_long():
    with pytest.raises(InvalidProblem, match="sizes 1..9"):
        polyforms("hex", 10)


def test_the_family_is_registered():
    from tilesolve import family

    assert family.get("shapes") is FAMILY and FAMILY in family.families()


@pytest.mark.slow
def test_heesch_sat_s_six_hex_table():
    rows, n = census("hex", 6, holes=False, max_level=3, max_copies=2, workers=2)
    assert n == 81 and not [r for r in rows if r.problems]
    kinds = Counter(r.verdict for r in rows)
    assert kinds == {"isohedral": 76, "non-tiler": 4, "periodic": 1}
    assert sorted(r.heesch for r in rows if r.verdict == "non-tiler") == [1, 1, 1, 2]
    (aniso,) = [r for r in rows if r.verdict == "periodic"]
    assert aniso.copies == 2 and aniso.cells == tuple(sorted(ANISOHEDRAL))


#: Holeless polyforms whose Heesch number is 0 without holes and 1 with holes in the outer
#: corona: heesch-sat (``sat -isohedral -hh``) reports ``~ 0 1`` (H_c = 0, H_h = 1) for both
#: (its triangle cells are these minus (1, 1)).
HH_OMINO = ((1, -2), (1, -1), (0, 0), (1, 0), (2, 0), (3, 0), (1, 1))
HH_IAMOND = ((2, -1), (1, 1), (4, 1), (-1, 2), (2, 2), (1, 4), (2, 5), (1, 7), (-1, 8))


@pytest.mark.parametrize("grid_name, cells", [("omino", HH_OMINO),
                                              pytest.param("iamond", HH_IAMOND, marks=pytest.mark.slow)])
def test_holes_in_the_outer_corona_raise_the_heesch_number(grid_name, cells):
    from tilesolve.model.shapes import Polyform, enclosed, grid

    shape = Polyform(grid_name, cells)
    hc = solve(ShapesProblem("classify", (shape,)), seed=0)
    hh = solve(ShapesProblem("classify", (shape,), holes=True), seed=0)
    assert (hc.report.verdict, hc.report.heesch, hc.report.holes) == ("non-tiler", 0, False)
    assert (hh.report.verdict, hh.report.heesch, hh.report.holes) == ("non-tiler", 1, True)
    # the H_h patch really has a hole (else H_c would be 1 too), and each next level is refuted
    assert enclosed(grid(grid_name), {tuple(c) for c in hh.report.patch[:, 2:].tolist()})
    assert hc.report.refutation["proof_status"] == hh.report.refutation["proof_status"] == "verified"
    assert hh.report.refutation["level"] == 2
