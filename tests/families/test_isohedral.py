"""The isohedral family's facade (tilesolve.families.isohedral): registration, the studio's
draw() call, and plain-value problems."""

from __future__ import annotations

import re

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
    with pytest.raises(InvalidProblem, match="edge class 1 does not exist"):
        form.build(form.values({"seed": 1, "type": "IH10"}))  # IH10 has one edge class; the default fills two
