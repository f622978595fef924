"""The tilesolve/substitution-patch file (tilesolve.io.substitution_json): round trips, strict
fields, pictures."""

import numpy as np
import pytest

from tilesolve.errors import InvalidProblem
from tilesolve.families.substitution import solve
from tilesolve.io.jsonio import dumps, parse_json
from tilesolve.io.substitution_json import patch_from_dict, patch_to_dict, write_patch_png, write_patch_svg
from tilesolve.model.substitution import SubstitutionProblem


@pytest.mark.parametrize("problem", [SubstitutionProblem("p3", region=(-5, -5, 10, 10)),
                                     SubstitutionProblem("p2", steps=4), SubstitutionProblem("sphinx", steps=2),
                                     SubstitutionProblem("p3", region=(0, 0, 200, 200))])  # encoded arrays
def test_round_trip(problem):
    sol = solve(problem, seed=5)
    doc = parse_json(dumps(patch_to_dict(problem, sol)), "f.json")
    back, s2 = patch_from_dict(doc, "f.json")
    assert back == problem and s2.seed == 5 and s2.method == sol.method
    assert np.array_equal(s2.tiling.vertices, sol.tiling.vertices) and np.array_equal(s2.tiling.types, sol.tiling.types)


def _doc():
    p = SubstitutionProblem("chair", steps=1)
    return parse_json(dumps(patch_to_dict(p, solve(p, seed=1))), "f.json")


@pytest.mark.parametrize("change,message", [
    (lambda d: d.update(kind="hat"), "'kind'"),
    (lambda d: d.update(grid="zeta5"), "'grid'"),
    (lambda d: d.update(extra=1), "unknown field 'extra'"),
    (lambda d: d.update(region=[0, 0, 4, 4]), "either steps or a region"),
    (lambda d: d.update(vertices=[[[0, 0]]]), "'vertices'"),
    (lambda d: d.update(version=9), "version"),
])
def test_bad_fields_are_one_line(change, message):
    d = _doc()
    change(d)
    with pytest.raises(InvalidProblem, match=message):
        patch_from_dict(d, "f.json")


def test_pictures(tmp_path):
    sol = solve(SubstitutionProblem("p3", steps=3))
    write_patch_svg(tmp_path / "a.svg", sol.tiling, title="t")
    assert (tmp_path / "a.svg").read_text().count("<polygon") == sol.tiling.n_tiles
    write_patch_png(tmp_path / "a.png", sol.tiling, px=200)
    assert (tmp_path / "a.png").read_bytes()[:4] == b"\x89PNG"
    with pytest.raises(InvalidProblem, match="pixels"):
        write_patch_png(tmp_path / "b.png", sol.tiling, px=10**6)
