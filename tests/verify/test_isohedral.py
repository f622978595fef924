"""The independent verifier of isohedral tilings (tilesolve.verify.isohedral): every one of the 93
types draws and verifies, with straight and with curved edges; forged tilings are caught."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from tilesolve.constructive.isohedral import layout
from tilesolve.model.isohedral import MARKINGS, TYPES, EdgeShape, IsohedralProblem, isohedral_type
from tilesolve.verify import isohedral as verifier
from tilesolve.verify.isohedral import tiling_violations

#: A shape of each kind that keeps its constraint (§7.3.1).
SHAPES = {"J": "bezier:0.3,0.12/0.7,-0.08", "U": "bezier:0.3,0.12/0.7,0.12", "S": "bezier:0.3,0.12/0.7,-0.12",
          "I": "line"}


def curved(n: int, region=(-1.5, -1, 5, 4)) -> IsohedralProblem:
    t = isohedral_type(n)
    return IsohedralProblem(n, edges=tuple(EdgeShape.parse(SHAPES[k]) for k in t.edge_kinds), region=region)


@pytest.mark.parametrize("n", TYPES, ids=lambda n: f"IH{n:02d}")
def test_every_type_draws_and_verifies(n):
    for problem in (IsohedralProblem(n, region=(0, 0, 4, 3)), curved(n)):
        tiling = layout(problem)
        assert tiling.n_tiles >= 4
        assert tiling_violations(problem, tiling) == []


def kinds(violations) -> set[str]:
    return {v.kind for v in violations}


@pytest.fixture(scope="module")
def good():
    problem = curved(28)
    return problem, layout(problem)


def test_a_moved_outline_point_breaks_the_template(good):
    problem, tiling = good
    outline = tiling.outline.copy()
    outline[3] += 0.01
    assert "template" in kinds(tiling_violations(problem, dataclasses.replace(tiling, outline=outline)))


def test_other_edge_shapes_or_parameters_are_not_this_tiling(good):
    problem, tiling = good
    other = dataclasses.replace(problem, edges=(EdgeShape.parse("bezier:0.3,0.1/0.7,-0.1"),) + problem.edges[1:])
    assert "template" in kinds(tiling_violations(other, tiling))
    moved = dataclasses.replace(problem, params=(0.21, 0.5))
    assert "template" in kinds(tiling_violations(moved, tiling))


def test_forged_motions_are_caught(good):
    problem, tiling = good
    aspects = tiling.aspects.copy()
    aspects[1, :, :2] *= 1.01  # not an isometry, not the table's
    found = kinds(tiling_violations(problem, dataclasses.replace(tiling, aspects=aspects)))
    assert {"template", "congruence"} <= found
    trans = tiling.translations * 1.1
    assert "template" in kinds(tiling_violations(problem, dataclasses.replace(tiling, translations=trans)))


def test_a_crossing_tile_is_caught(good):
    problem, tiling = good
    outline = tiling.outline.copy()
    outline[[2, 6]] = outline[[6, 2]]
    assert "simple" in kinds(verifier._crossings(outline, 1e-9))


def test_the_torus_check_finds_gaps_and_overlaps(good, monkeypatch):
    # Past a template check that is told to pass: wrong translations leave chords unmatched
    # and the areas wrong; a missing aspect leaves a gap.
    problem, tiling = good
    monkeypatch.setattr(verifier, "_template", lambda *a: [])
    wide = dataclasses.replace(tiling, translations=tiling.translations * np.array([[1.25], [1.0]]))
    assert "torus" in kinds(tiling_violations(problem, wide))
    one = dataclasses.replace(tiling, aspects=tiling.aspects[:1].repeat(len(tiling.aspects), axis=0))
    assert "torus" in kinds(tiling_violations(problem, one))


def test_the_drawing_is_checked(good):
    problem, tiling = good
    placed, colours = tiling.placements, tiling.colours
    drop = dataclasses.replace(tiling, placements=placed[5:], colours=colours[5:])
    assert "drawing" in kinds(tiling_violations(problem, drop))
    twice = dataclasses.replace(tiling, placements=np.vstack([placed, placed[:1]]), colours=np.append(colours, colours[0]))
    assert "drawing" in kinds(tiling_violations(problem, twice))
    far = placed.copy()
    far[0, :2] += 1000
    assert "drawing" in kinds(tiling_violations(problem, dataclasses.replace(tiling, placements=far)))
    same = np.zeros_like(colours)
    assert "colour" in kinds(tiling_violations(problem, dataclasses.replace(tiling, colours=same)))


def test_another_types_tiling_is_refused(good):
    problem, tiling = good
    assert kinds(tiling_violations(IsohedralProblem(41), tiling)) == {"shape"}


def test_any_parameters_are_refused_in_one_line_or_draw_a_verified_tiling():
    # Parameters far from the defaults: the generator refuses (a vanished edge, a tile that
    # crosses itself, parallel translations) or its tiling verifies; never a tiling that fails.
    from tilesolve.errors import InvalidProblem

    rng = np.random.default_rng(4)
    free = [n for n in TYPES if isohedral_type(n).n_params]
    outcomes = set()
    for n in rng.choice(free, 30, replace=False):
        t = isohedral_type(int(n))
        params = tuple(float(p) for p in np.asarray(t.default_params) + rng.uniform(-0.6, 0.6, t.n_params))
        try:
            problem = curved(int(n), region=(0, 0, 4, 3))
            problem = dataclasses.replace(problem, params=params)
            tiling = layout(problem)
        except InvalidProblem:
            outcomes.add("refused")
            continue
        assert tiling_violations(problem, tiling) == [], (n, params)
        outcomes.add("verified")
    assert outcomes == {"refused", "verified"}


@pytest.mark.parametrize("n", sorted(MARKINGS), ids=lambda n: f"IH{n:02d}")
def test_every_marked_type_draws_its_markings_and_a_flipped_one_is_caught(n):
    problem = IsohedralProblem(n, region=(-1, -1, 5, 4))
    tiling = layout(problem)
    assert tiling.marks is not None and len(tiling.motif) == len(MARKINGS[n].stabilizer)
    assert tiling_violations(problem, tiling) == []
    # Flip the marking of a tile in the middle: after a reflection of the prototile outside the
    # stabilizer the tile's motif is the mirror image of the right one.
    keep = {tuple(h) for h in MARKINGS[n].stabilizer}
    verts = tiling.outline[list(tiling.corners)]
    flips = [s for s, m in enumerate(tiling.symmetries) if np.linalg.det(m[:, :2]) < 0 and
             not any(np.allclose(m, _vertex_map(verts, h)) for h in keep)]
    centre = np.array([1.5, 1.0])
    k = int(np.argmin([np.abs(tiling.tile(k).mean(axis=0) - centre).max() for k in range(tiling.n_tiles)]))
    s, r = tiling.symmetries[tiling.marks[k]], tiling.symmetries[flips[0]]
    flipped = np.hstack([s[:, :2] @ r[:, :2], s[:, :2] @ r[:, 2:] + s[:, 2:]])
    marks = tiling.marks.copy()
    marks[k] = next(i for i, m in enumerate(tiling.symmetries) if np.allclose(m, flipped))
    forged = dataclasses.replace(tiling, marks=marks)
    assert not np.allclose(_mark_points(forged, k), _mark_points(tiling, k))
    assert kinds(tiling_violations(problem, forged)) == {"marking"}


def _vertex_map(verts, h):
    """The motion of the vertex map (k, reflected), fitted here for the test."""
    k, reflected = h
    n = len(verts)
    target = verts[[(k - i if reflected else k + i) % n for i in range(n)]]
    return np.linalg.lstsq(np.hstack([verts, np.ones((n, 1))]), target, rcond=None)[0].T


def _mark_points(tiling, k):
    m = tiling.mark_motion(k)
    pts = np.round(np.concatenate([p @ m[:, :2].T + m[:, 2] for p in tiling.motif]), 9)
    return pts[np.lexsort(pts.T[::-1])]


def test_the_motif_must_keep_exactly_the_stabilizer_and_unmarked_types_carry_none():
    problem = IsohedralProblem(65, region=(0, 0, 3, 2))
    tiling = layout(problem)
    one_flag = dataclasses.replace(tiling, motif=tiling.motif[:1])  # H = 1's motif: IH48's, not IH65's
    assert "keep its motif are [(0, False)]" in tiling_violations(problem, one_flag)[0].message
    unmarked = dataclasses.replace(tiling, marks=None, symmetries=None, motif=())
    assert "must carry markings" in tiling_violations(problem, unmarked)[0].message
    square = IsohedralProblem(72, region=(0, 0, 3, 2))
    plain = layout(square)
    marked = dataclasses.replace(plain, motif=tiling.motif, symmetries=tiling.symmetries, marks=np.zeros(plain.n_tiles, int))
    assert kinds(tiling_violations(square, marked)) == {"marking"}
    outside = dataclasses.replace(tiling, motif=tuple(p + 5 for p in tiling.motif))
    assert "leaves the prototile" in tiling_violations(problem, outside)[0].message


def test_the_point_group_must_be_the_stated_groups(monkeypatch):
    problem = IsohedralProblem(89, region=(0, 0, 3, 2))
    tiling = layout(problem)
    t = isohedral_type(89)
    for group, aspects, message in (("p6m", 2, "p6m's has 12"), ("p31m", 4, "4 aspects of a stabilizer of 3 need 12")):
        wrong = dataclasses.replace(t, marking=dataclasses.replace(t.marking, group=group, aspects=aspects))
        monkeypatch.setattr(verifier, "isohedral_type", lambda n, wrong=wrong: wrong)
        assert message in tiling_violations(problem, tiling)[0].message
