"""The independent polyform checker catches every kind of corruption."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from tilesolve.engine.shapes import classify
from tilesolve.families.shapes import solve
from tilesolve.model.shapes import ShapesProblem, parse_ascii, parse_cells
from tilesolve.verify.shapes import shapes_violations

RECT = tuple((x, y) for x in range(5) for y in range(2))


@pytest.fixture(scope="module")
def region_tiling():
    p = ShapesProblem("tile", (parse_ascii("##\n##\n#.", "omino"),), region=RECT)
    return p, solve(p, seed=3).tiling


def test_a_valid_tiling_has_no_violation(region_tiling):
    p, t = region_tiling
    assert shapes_violations(p, t) == []


@pytest.mark.parametrize("corrupt, message", [
    (lambda t: _moved(t), "congruent|covered"),
    (lambda t: t[1:], "congruent"),
    (lambda t: np.concatenate([t, t[t[:, 0] == 0] + [7, 0, 0, 0]]), "covered by pieces"),
    (lambda t: t + [0, 1, 0, 0], "names shape"),
    (lambda t: t[:, :3], "rows"),
])
def test_single_corruptions_are_caught(region_tiling, corrupt, message):
    p, t = region_tiling
    bad = shapes_violations(p, corrupt(t.copy()))
    assert bad and any(__import__("re").search(message, b) for b in bad), bad


def _moved(t):
    t[0, 2] += 7
    return t


def test_a_piece_outside_the_region_and_a_missing_cell():
    p = ShapesProblem("tile", (parse_ascii("##", "omino"),), region=((0, 0), (1, 0), (0, 1), (1, 1)))
    t = np.array([[0, 0, 0, 0], [0, 0, 1, 0], [1, 0, 0, 1], [1, 0, 0, 2]])
    bad = shapes_violations(p, t)
    assert any("outside the region" in b for b in bad) and any("not covered" in b for b in bad)


def test_mirror_images_are_refused_without_reflections():
    s = parse_ascii("##\n#.\n#.", "omino")
    p = ShapesProblem("tile", (s,), region=s.cells, reflections=False)
    mirrored = [(0, 0, -x, y) for x, y in s.cells]
    assert shapes_violations(p, np.array(mirrored)) == ["piece 0 is not a congruent copy of shape 0"]
    assert shapes_violations(replace(p, reflections=True), np.array(mirrored)) != []  # not in the region either


def test_a_periodic_tiling_claimed_isohedral_is_caught():
    p = ShapesProblem("classify", (parse_cells("0,0 0,1 1,-3 1,-1 2,-3 2,-2", "hex"),))
    r = classify(p, seed=1).report
    assert r.verdict == "periodic"
    assert any("not isohedral" in b for b in shapes_violations(p, replace(r, verdict="isohedral")))


def test_corona_corruptions_are_caught():
    p = ShapesProblem("classify", (parse_cells("0,0 0,1 0,2 0,3 1,-1 1,3", "hex"),))
    r = classify(p, seed=1).report
    patch = r.patch
    assert any("does not surround" in b for b in shapes_violations(p, replace(r, patch=patch[patch[:, 0] != 2])))
    relabelled = patch.copy()
    relabelled[relabelled[:, 0] == 1, 1] = 2
    assert any("distance" in b for b in shapes_violations(p, replace(r, patch=relabelled)))
    assert any("coronas" in b for b in shapes_violations(p, replace(r, heesch=2)))
    assert any("refutation" in b for b in shapes_violations(p, replace(r, refutation=None)))
    overlap = np.concatenate([patch, patch[patch[:, 0] == 1] + [100, 0, 0, 0]])
    assert any("covered by patch pieces" in b for b in shapes_violations(p, replace(r, patch=overlap)))


def test_a_patch_with_a_hole_is_refused_for_h_c():
    from tilesolve.verify.shapes import _hole_errors
    from tilesolve.model.shapes import GRIDS

    ring = set(parse_ascii("###\n#.#\n###", "omino").cells)
    assert _hole_errors(GRIDS["omino"], ring) and not _hole_errors(GRIDS["omino"], ring | {(1, 1)})
