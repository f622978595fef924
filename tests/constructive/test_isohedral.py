"""Isohedral tilings from their templates (tilesolve.constructive.isohedral)."""

from __future__ import annotations

import numpy as np
import pytest

from tilesolve.constructive.isohedral import edge_path, layout, prototile, symmetries
from tilesolve.errors import InvalidProblem
from tilesolve.model.isohedral import MARKINGS, BEZIER_CHORDS, EdgeShape, IsohedralProblem, isohedral_type


def test_edge_paths_run_from_0_0_to_1_0():
    path = edge_path(EdgeShape.parse("bezier:0.3,0.2/0.7,-0.2/0.8,0/0.9,0.1/0.95,0.1"))
    assert len(path) == 2 * BEZIER_CHORDS + 1
    assert path[0].tolist() == [0, 0] and path[-1].tolist() == [1, 0]
    s = edge_path(EdgeShape.parse("bezier:0.3,0.2/0.7,-0.2"))  # S-symmetric control points: an S-symmetric path
    r = s[::-1]
    assert np.allclose(s, np.column_stack([1 - r[:, 0], -r[:, 1]]), atol=1e-12)


def test_the_prototile_passes_through_the_tiling_vertices():
    t = isohedral_type(16)
    outline, corners = prototile(t, t.default_params, (EdgeShape("line"), EdgeShape.parse("line:0.5,0.1")))
    verts = t.vertex_coeffs @ np.array((*t.default_params, 1.0))
    assert np.allclose(outline[list(corners)], verts)
    assert len(outline) == 6 + 4  # one extra point on each of the four J edges


def test_a_tile_that_crosses_itself_is_refused():
    wild = EdgeShape.parse("line:0.5,1.5/0.6,-1.5")
    with pytest.raises(InvalidProblem, match="IH41 tile crosses itself"):
        layout(IsohedralProblem(41, edges=(wild, wild)))


def test_parameters_that_collapse_an_edge_are_refused():
    with pytest.raises(InvalidProblem, match="vanish|crosses itself|parallel"):
        layout(IsohedralProblem(41, params=(-0.1 / 3.9, 0.5)))


def test_too_large_a_region_is_refused():
    with pytest.raises(InvalidProblem, match="at most 200,000"):
        layout(IsohedralProblem(41, region=(0, 0, 1000, 1000)))


def test_the_tiles_meet_the_region_and_are_coloured():
    p = IsohedralProblem(7, region=(2, -3, 6, 4))
    t = layout(p)
    assert len({tuple(r) for r in t.placements.tolist()}) == t.n_tiles
    for k in range(t.n_tiles):
        poly = t.tile(k)
        assert poly[:, 0].max() > 2 and poly[:, 0].min() < 8 and poly[:, 1].max() > -3 and poly[:, 1].min() < 1
    assert set(t.colours.tolist()) == {0, 1, 2}


@pytest.mark.parametrize("n", sorted(MARKINGS), ids=lambda n: f"IH{n:02d}")
def test_a_marked_types_tiles_carry_the_motif_moved_onto_them(n):
    t = layout(IsohedralProblem(n, region=(-2, -2, 6, 5)))
    verts = t.outline[list(t.corners)]
    assert len(t.symmetries) == len(symmetries(verts)) and np.allclose(t.symmetries[0], np.eye(2, 3))
    for k in range(t.n_tiles):
        m = t.mark_motion(k)
        assert _rows(t.outline @ m[:, :2].T + m[:, 2]) == _rows(t.tile(k))  # a motion onto the tile
    # The marks take every coset of the stabilizer that the type's aspects need.
    assert len(set(t.marks.tolist())) * t.aspects.shape[0] >= MARKINGS[n].aspects


def _rows(points) -> list:
    return sorted(np.round(points, 9).tolist())
