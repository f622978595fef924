"""The isohedral family's facade (tilesolve.families.isohedral): registration, the studio's
draw() call, and plain-value problems."""

from __future__ import annotations

import re

import numpy as np
import pytest

from tilesolve.errors import InvalidProblem
from tilesolve.families import isohedral as facade
from tilesolve.family import get


def test_registered_with_its_route_codec_and_command():
    fam = get("isohedral")
    assert fam is facade.FAMILY and fam.methods == ("auto", "template")
    assert fam.codecs[0].format == "tilesolve/isohedral-tiling"
    assert fam.commands == ("tilesolve.cli.isohedral:isohedral",)


def test_draw_gives_svg_text_of_a_verified_tiling():
    svg = facade.draw("IH28", params=[0.2, 0.5], edges={0: "bezier:0.3,0.2/0.7,-0.2"}, region=(0, 0, 4, 3), scale=20)
    w, h = (int(v) for v in re.search(r'<svg [^>]*width="(\d+)" height="(\d+)"', svg).groups())
    assert svg.startswith("<svg") and w >= 80 and h > 60 and svg.count("<use ") > 10  # 80x60 px, the caption under


def test_edges_by_class_or_in_order():
    by_class = facade.problem(41, edges={1: "line:0.5,0.1"})
    in_order = facade.problem(41, edges=["line", "line:0.5,0.1"])
    assert by_class == in_order
    with pytest.raises(InvalidProblem, match="edge class 2 does not exist"):
        facade.problem(41, edges={2: "line"})


def test_solve_refuses_other_problems():
    with pytest.raises(InvalidProblem, match="expected an IsohedralProblem"):
        facade.solve("IH41")


def test_the_forms_command_poses_the_forms_problem(tmp_path):
    from clitools import run

    from tilesolve.family import read_document

    form = facade.FORM
    values = form.values({"seed": 1, "type": "IH16", "params": "0.2", "edge0": "", "edge1": "line:0.5,0.1",
                          "region": "6x4", "scale": 20})
    built, _ = form.build(values)
    words, files = form.command(values)
    assert files == {} and form.time_limit is False
    assert run(*words, "-o", "t.json", cwd=tmp_path).returncode == 0
    fam, codec, doc = read_document(tmp_path / "t.json")
    assert fam is facade.FAMILY and codec.read(doc, "t.json")[0] == built
    # IH10 has one edge class: the second class's field does not apply (the studio hides it) and is ignored
    values = form.values({"seed": 1, "type": "IH10", "edge1": "line:0.5,0.3"})
    assert [f.name for f in form.fields if not f.applies(values)] == ["edge1", "edge2", "edge3", "edge4"]
    assert len(form.build(values)[0].edges) == 1 and "--edge 1=" not in " ".join(form.command(values)[0])


def test_the_forms_sketch_maps_each_class_onto_the_prototiles_sides():
    """The studio's edge editor draws the tile from the sketch: each side's map of its class's
    path, reversed where said, without its last point, is the prototile's outline, for every type."""
    from tilesolve.constructive.isohedral import edge_path, prototile
    from tilesolve.model.isohedral import TYPES, isohedral_type

    shaped = {"J": "line:0.3,0.05/0.6,-0.03", "U": "line:0.3,0.05/0.7,0.05", "S": "line:0.3,0.05/0.7,-0.05", "I": ""}
    form = facade.FORM
    for n in TYPES:
        kinds = isohedral_type(n).edge_kinds
        values = form.values({"seed": 1, "type": f"IH{n:02d}", **{f"edge{k}": "" for k in range(5)},
                              **{f"edge{k}": shaped[kind] for k, kind in enumerate(kinds)}})
        problem, _ = form.build(values)
        sketch = form.sketch(values)
        assert [e["kind"] for e in sketch["edges"]] == list(kinds)
        assert [e["field"] for e in sketch["edges"]] == [f"edge{k}" for k in range(len(kinds))]
        outline = []
        for side in sketch["sides"]:
            m = np.array(side["map"])
            pts = edge_path(problem.edges[side["edge"]]) @ m[:, :2].T + m[:, 2]
            outline.extend((pts[::-1] if side["reverse"] else pts)[:-1])
        want, _ = prototile(problem.template, problem.params, problem.edges)
        assert np.allclose(outline, want, atol=1e-9), problem.template.name


def test_a_marked_types_drawing_and_stats_are_the_marked_ones():
    svg = facade.draw("IH63", region=(0, 0, 3, 2))
    assert svg.count('xlink:href="#mark"') == 6  # one motif per tile
    sol = facade.solve(facade.problem("IH63", region=(0, 0, 3, 2)))
    assert sol.stats["aspects"] == 2 and sol.tiling.aspects.shape[0] == 1  # p4g: 2 aspects, the square's 1
