"""The substitution family (tilesolve.families.substitution): routes, auto, verification through
the pipeline, and the family record's files."""

import pytest

from tilesolve import family
from tilesolve.errors import MethodNotApplicable
from tilesolve.families.substitution import FAMILY, patch_violations, solve
from tilesolve.model.substitution import Patch, SubstitutionProblem


def test_registered_with_its_commands():
    assert family.get("substitution") is FAMILY
    assert FAMILY.methods == ("auto", "substitution", "pentagrid")


@pytest.mark.parametrize("problem,method", [(SubstitutionProblem("p3", region=(-4, -4, 8, 8)), "pentagrid"),
                                            (SubstitutionProblem("p2", steps=3), "substitution"),
                                            (SubstitutionProblem("l-tetromino", steps=2), "substitution")])
def test_auto_route_and_verification(problem, method):
    s = solve(problem, seed=2)
    assert s.status.value == "sat" and s.method == method and patch_violations(problem, s.tiling) == []
    assert s.stats["tiles"] == s.tiling.n_tiles


def test_substitution_on_a_region_keeps_the_tiles_inside():
    p = SubstitutionProblem("p2", region=(3, -2, 9, 7))
    s = solve(p, method="substitution", seed=1)
    assert s.tiling.n_tiles > 10 and patch_violations(p, s.tiling) == []


def test_pentagrid_needs_a_region():
    with pytest.raises(MethodNotApplicable, match="give a region"):
        solve(SubstitutionProblem("p3", steps=3), method="pentagrid")


def test_a_patch_of_another_window_or_kind_fails():
    s = solve(SubstitutionProblem("p3", region=(0, 0, 10, 10)), seed=1)
    assert patch_violations(SubstitutionProblem("p3", region=(0, 0, 5, 5)), s.tiling)[0].kind == "window"
    assert patch_violations(SubstitutionProblem("p2", region=(0, 0, 10, 10)), s.tiling)[0].kind == "shape"
    other = Patch("chair", s.tiling.types, s.tiling.vertices)
    assert patch_violations(SubstitutionProblem("chair", steps=1), other)


def test_the_same_seed_gives_the_same_window():
    p = SubstitutionProblem("p3", region=(-5, 0, 10, 10))
    a, b = solve(p, seed=9).tiling, solve(p, seed=9).tiling
    assert (a.vertices == b.vertices).all()


def test_demos_build():
    for demo in FAMILY.demos:
        assert solve(demo.make(), method=demo.method, seed=1).status.value == "sat"


@pytest.mark.parametrize("values", [{}, {"kind": "p2", "patch": "steps", "steps": 4},
                                    {"kind": "sphinx", "patch": "steps", "steps": 2},
                                    {"x0": -1000, "y0": 50, "size": "12x8"}])
def test_the_form_and_its_command_pose_the_same_problem(tmp_path, values):
    import json

    from clitools import run

    from tilesolve.families.substitution import FORM

    full = {f.name: f.default for f in FORM.fields} | values
    problem, _ = FORM.build(full)
    words, files = FORM.command(full)
    assert files == {}
    proc = run(*words, "--seed", "6", "-o", "s.json", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    doc = json.loads((tmp_path / "s.json").read_text())
    ours = solve(problem, seed=6).tiling
    assert doc["kind"] == problem.kind and (doc["steps"], doc["region"]) == (
        problem.steps, list(problem.region) if problem.region else None)
    assert len(doc["types"]) == ours.n_tiles


def test_a_rep_tile_grows_by_steps_whatever_the_window_fields_say():
    from tilesolve.families.substitution import FORM

    vals = FORM.values({"kind": "chair", "patch": "window", "steps": 3, "seed": 1})
    problem, _ = FORM.build(vals)
    assert (problem.kind, problem.steps, problem.region) == ("chair", 3, None)
    applies = {f.name: f.applies(vals) for f in FORM.fields}  # the studio hides the others
    assert applies == {"kind": True, "patch": False, "x0": False, "y0": False, "size": False, "steps": True}


@pytest.mark.slow
def test_the_studio_solves_the_family_and_its_command_reproduces_it(tmp_path):
    import json
    import os
    import subprocess
    import sys
    import time

    from starlette.testclient import TestClient

    from tilesolve.studio.app import create_app

    with TestClient(create_app(warm=False), headers={"origin": "http://testserver"}) as client:
        job = client.post("/api/solve", json={"family": "substitution", "values": {"seed": 3}}).json()["id"]
        t0 = time.perf_counter()
        while (state := client.get(f"/api/jobs/{job}?wait=2").json())["state"] == "running":
            assert time.perf_counter() - t0 < 300
    res = state["result"]
    assert res["status"] == "sat" and res["verdict"][0].startswith("ok: solution.json is a valid tiling")
    assert res["picture"]["format"] == "svg" and "<polygon" in res["picture"]["data"]  # about 1,200 tiles
    exe = os.path.join(os.path.dirname(sys.executable), "tilesolve")
    run = subprocess.run(["bash", "-c", res["command"].replace("tilesolve ", exe + " ", 1)], cwd=tmp_path,
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert json.loads((tmp_path / "solution.json").read_text())["vertices"] == json.loads(res["json"])["vertices"]
