"""The isohedral types' templates, edge shapes and problems (tilesolve.model.isohedral)."""

from __future__ import annotations

import numpy as np
import pytest

from tilesolve.errors import InvalidProblem
from tilesolve.model.isohedral import (
    GS_TABLE_5_2_3,
    MARKED,
    MARKINGS,
    TYPES,
    EdgeShape,
    IsohedralProblem,
    isohedral_type,
    parse_type,
)


def test_93_types_81_with_tables_and_12_marked_outline_twins():
    assert TYPES == tuple(range(1, 94))
    assert sorted(MARKED) == [19, 35, 48, 60, 63, 65, 70, 75, 80, 87, 89, 92]
    for n, twin in MARKED.items():
        t, u = isohedral_type(n), isohedral_type(twin)
        assert twin not in MARKED and t.outline_of == twin and u.outline_of is None
        assert set(t.edge_kinds) == {"I"}  # a marked type's edges cannot be modified
        assert (t.n_vertices, t.n_aspects, t.edge_kinds) == (u.n_vertices, u.n_aspects, u.edge_kinds)
    assert sum(isohedral_type(n).outline_of is None for n in TYPES) == 81


@pytest.mark.parametrize("n", TYPES)
def test_every_template_is_consistent(n):
    t = isohedral_type(n)
    assert len(t.edge_classes) == len(t.orientations) == t.n_vertices >= 3
    assert sorted(set(t.edge_classes)) == list(range(len(t.edge_kinds)))
    assert len(t.default_params) == t.n_params
    assert t.vertex_coeffs.shape == (t.n_vertices, 2, t.n_params + 1)
    assert t.aspect_coeffs.shape == (t.n_aspects, 2, 3, t.n_params + 1)
    c = t.colouring
    assert len(c) == 19 and 2 <= t.n_colours <= 4
    assert all(0 <= c[a] < t.n_colours for a in range(t.n_aspects))
    for perm in (c[12:12 + t.n_colours], c[15:15 + t.n_colours]):  # the translations permute the colours
        assert sorted(perm) == list(range(t.n_colours))
    a0 = t.aspect_coeffs[0] @ np.array((*t.default_params, 1.0))
    assert np.allclose(a0, [[1, 0, 0], [0, 1, 0]])  # aspect 0 is the prototile itself


def test_ih16_is_the_notes_example():
    # §7.4.1, Fig. 19: IH16 has 3 aspects and edges a (I) and b, c (one J shape); Fig. 22: one parameter.
    t = isohedral_type("IH16")
    assert (t.n_params, t.n_aspects, t.edge_kinds, t.edge_classes) == (1, 3, ("I", "J"), (0, 1, 1, 1, 1, 0))


@pytest.mark.parametrize("text, n", [("IH41", 41), ("ih7", 7), ("IH07", 7), (" 93 ", 93), (1, 1)])
def test_type_names(text, n):
    assert parse_type(text) == n


@pytest.mark.parametrize("text", ["IH0", "IH94", "H41", "41x", "", True, -3])
def test_unknown_types_are_refused(text):
    with pytest.raises(InvalidProblem, match="unknown isohedral type"):
        parse_type(text)


@pytest.mark.parametrize("text", ["line", "line:0.5,0.2", "bezier:0.3,0.2/0.7,-0.2",
                                  "bezier:0.2,0.1/0.3,0.2/0.5,0/0.7,-0.2/0.8,-0.1", "line:1e-3,-2.5E-1/0.5,0"])
def test_edge_shapes_round_trip(text):
    shape = EdgeShape.parse(text)
    assert EdgeShape.parse(shape.text()) == shape


@pytest.mark.parametrize("text, message", [
    ("curve:0,1", "cannot read edge shape"),
    ("line:0.5", "cannot read point"),
    ("line:0.5,x", "cannot read point"),
    ("bezier:0.3,0.2", "3k-1 points"),
    ("line:9,0", "within"),
])
def test_bad_edge_shapes_are_refused(text, message):
    with pytest.raises(InvalidProblem, match=message):
        EdgeShape.parse(text)


@pytest.mark.parametrize("kind, good, bad", [
    ("U", "bezier:0.3,0.2/0.7,0.2", "bezier:0.3,0.2/0.7,-0.2"),
    ("S", "bezier:0.3,0.2/0.7,-0.2", "bezier:0.3,0.2/0.7,0.2"),
    ("I", "line:0.5,0", "line:0.5,0.01"),
    ("J", "line:0.2,0.3/0.9,-0.1", None),
])
def test_edge_constraints(kind, good, bad):
    EdgeShape.parse(good).check(kind, "edge 0")
    if bad is not None:
        with pytest.raises(InvalidProblem, match=f"edge 0 is an? {kind} edge"):
            EdgeShape.parse(bad).check(kind, "edge 0")


def test_problem_defaults_and_refusals():
    p = IsohedralProblem(41)
    assert p.params == isohedral_type(41).default_params and len(p.edges) == 2
    assert p.describe() == "IH41 in the region 0,0,8x6"
    with pytest.raises(InvalidProblem, match="IH41 takes 2 parameters, got 1"):
        IsohedralProblem(41, params=(0.2,))
    with pytest.raises(InvalidProblem, match="2 edge classes, got 1"):
        IsohedralProblem(41, edges=(EdgeShape("line"),))
    with pytest.raises(InvalidProblem, match="IH16's edge 0 is an I edge"):
        IsohedralProblem(16, edges=(EdgeShape.parse("line:0.5,0.1"), EdgeShape("line")))
    with pytest.raises(InvalidProblem, match="positive sizes"):
        IsohedralProblem(41, region=(0, 0, 0, 5))
    with pytest.raises(InvalidProblem, match="finite"):
        IsohedralProblem(41, params=(float("nan"), 0.5))


def test_the_12_marked_types_markings():
    """Each marked type keeps a subgroup H of its twin's prototile symmetries; its group's point
    group has H's order times its aspects; the three that force the square take no parameter."""
    order = {"p3m1": 6, "p31m": 6, "pmm": 4, "cmm": 4, "p4m": 8, "p4g": 8, "p6m": 12}
    assert sorted(MARKINGS) == sorted(MARKED)
    for n, m in MARKINGS.items():
        t = isohedral_type(n)
        assert t.marking is m and len(set(m.stabilizer)) == len(m.stabilizer) and (0, False) in m.stabilizer
        assert order[m.group] == m.aspects * len(m.stabilizer)
        assert t.n_params == (0 if m.square or isohedral_type(m.twin).n_params == 0 else 1)
    assert sorted(n for n, m in MARKINGS.items() if m.square) == [63, 70, 75]
    assert [MARKINGS[n].group for n in (87, 89, 92)] == ["p3m1", "p31m", "p6m"]


def _induced(stabilizer):
    """H's name in G&S's notation: c_n (rotations only) or d_n (n rotations and n reflections)."""
    rotations = sum(1 for _, flip in stabilizer if not flip)
    return f"{'d' if len(stabilizer) > rotations else 'c'}{rotations}"


def test_the_marked_types_numbers_agree_with_gs_table_5_2_3():
    """Every marked type's tiling group and tile stabilizer H are its row of Grünbaum and Shephard's
    Table 5.2.3 (S(P), S(P|M)); in 4^4 the d1 through edge midpoints is pmm (IH65), the diagonal
    one p4m (IH70)."""
    assert sorted(GS_TABLE_5_2_3) == sorted(MARKINGS)
    for n, m in MARKINGS.items():
        assert (m.group, _induced(m.stabilizer)) == GS_TABLE_5_2_3[n], f"IH{n}"
    # the two 4^4 mirrors: i -> 1 - i swaps the ends of edge 0 (midpoints), i -> -i fixes vertex 0 (diagonal)
    assert (1, True) in MARKINGS[65].stabilizer and (0, True) in MARKINGS[70].stabilizer
    # within a topological type (one outline twin) no two marked types share a row
    for twin in set(MARKED.values()):
        rows = [GS_TABLE_5_2_3[n] for n, t in MARKED.items() if t == twin]
        assert len(rows) == len(set(rows))
