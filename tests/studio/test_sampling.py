"""The studio's forms of the sampling families (tilesolve.families.sampling_forms): the poisson,
poisson-sphere, recursive-wang and stipple pages solve, verify and export; their copied commands
(the set's build, then the window; the stipple command) reproduce the file through the console
script; a window's set is
bounded while the form is checked; the Poisson disk preset of the page's gallery."""

from __future__ import annotations

import json
import subprocess

import pytest
from starlette.testclient import TestClient

from tests.clitools import SCRIPT
from tests.studio.browsing import fill, pick, solve as solve_on_page
from tests.studio.test_app import solve
from tests.studio.test_screenshots import compare, open_link
from tilesolve.families.sampling_forms import POISSON_FORM, RECURSIVE_FORM, SET_BUDGETS, SPHERE_FORM
from tilesolve.errors import InvalidProblem
from tilesolve.studio.app import create_app

@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(warm=False), headers={"origin": "http://testserver"}) as c:
        yield c


def test_a_windows_command_builds_its_set_first():
    vals = SPHERE_FORM.values({"seed": 4, "x0": -3, "z0": 2, "depth": 2, "set_seed": 9})
    words, files = SPHERE_FORM.command(vals)
    assert words == ["sample", "poisson-spheres", "window", "set.json", "--region=-3,0,2,6x6x2"]
    assert files == {"set.json": ["sample", "poisson-spheres", "build", "-C", "2", "-N", "64", "--rho", "0.6",
                                  "--seed", "9", "-o", "set.json"]}
    # the set question is the build alone, its seed the run's
    assert SPHERE_FORM.command(SPHERE_FORM.values({"seed": 4, "show": "set"})) == (
        ["sample", "poisson-spheres", "build", "-C", "2", "-N", "64", "--rho", "0.6"], {})


def test_a_windows_set_and_points_are_bounded_before_anything_is_built():
    with pytest.raises(InvalidProblem, match=f"at most {SET_BUDGETS['poisson']:,} points over its tiles here, this one has "
                                             "3,264 .102 tiles x 32.; build it with show = set"):
        POISSON_FORM.build(POISSON_FORM.values({"colors": 3, "seed": 1}))
    with pytest.raises(InvalidProblem, match="about 1,048,576 points; the studio shows at most 20,000"):
        RECURSIVE_FORM.build(RECURSIVE_FORM.values({"level": 3, "seed": 1}))
    # a large set is a solve of its own (cancellable), not built while the form is checked
    problem, _ = POISSON_FORM.build(POISSON_FORM.values({"colors": 3, "show": "set", "seed": 1}))
    assert problem.n_tiles == 102


def test_the_check_says_why_a_window_is_refused(client):
    r = client.post("/api/check", json={"family": "poisson", "values": {"colors": 4, "points": 64, "seed": 1}})
    assert r.status_code == 400 and "a window's set is built while the form is checked" in r.json()["error"]


@pytest.mark.slow
@pytest.mark.parametrize("body", [
    {"family": "poisson", "values": {"x0": -7, "y0": 1 << 39, "size": "5x3", "tiling": "scanline", "seed": 3}},
    {"family": "poisson", "values": {"show": "set", "colors": 1, "points": 24, "rho": 0.7, "lloyd": 2, "seed": 5}},
    {"family": "poisson-sphere", "values": {"x0": 1000000, "y0": -5, "z0": 7, "size": "3x2", "depth": 2,
                                            "set_seed": 2, "seed": 4}},
    {"family": "poisson-sphere", "values": {"show": "set", "seed": 6}},
    {"family": "recursive-wang", "values": {"x0": -2, "y0": 3, "size": "2x2", "level": 2, "seed": 8}},
    {"family": "recursive-wang", "values": {"by": "density", "density": 300.5, "size": "3x2", "seed": 8}},
    {"family": "recursive-wang", "values": {"show": "set", "colors": 1, "subdivision": 2, "seed": 9}},
    {"family": "stipple", "values": {"image": "gradient", "method": "polyomino", "tile": "chair", "points": 1500,
                                     "lloyd": 0, "jitter": False, "seed": 2}},
], ids=lambda b: f"{b['family']}-{b['values'].get('show', 'window')}-{b['values']['seed']}")
def test_the_copied_command_reproduces_the_file(client, body, tmp_path):
    state = solve(client, body, wait=300)
    res = state["result"]
    assert res["status"] == "sat", state
    assert res["verdict"][0].startswith("ok: solution.json is a valid "), res["verdict"]
    line = res["command"].replace("tilesolve ", SCRIPT + " ")
    windows = body["family"] != "stipple" and body["values"].get("show") != "set"
    assert line.count(SCRIPT) == (2 if windows else 1)
    run = subprocess.run(["bash", "-c", line], cwd=tmp_path, capture_output=True, text=True)
    assert run.returncode == 0, (line, run.stderr)
    # the files hold no timings: the same document, point for point
    assert json.loads(res["json"]) == json.loads((tmp_path / "solution.json").read_text())
    verify = subprocess.run([SCRIPT, "verify", "solution.json"], cwd=tmp_path, capture_output=True, text=True)
    assert verify.returncode == 0, verify.stdout + verify.stderr


# ----------------------------------------------------------------------------- in the browser
@pytest.mark.slow
def test_the_poisson_preset_shows_a_verified_window(page, tmp_path):
    page.click("#presets button[data-preset='Poisson disk tiles C = 2']")
    page.wait_for_function("studio.result !== null && document.getElementById('solve').disabled === false "
                           "&& studio.job === null", timeout=120_000)
    res = page.evaluate("studio.result")
    assert res["family"] == "poisson" and res["status"] == "sat" and res["seed"] == 1
    assert "ok: solution.json is a valid point set of Poisson disk window x 0..7, y 0..7" in page.text_content("#verdict")
    assert page.locator("#picture svg").count() == 1
    command = page.text_content("#command")
    assert command.startswith("tilesolve sample poisson-tiles build -C 2 -N 32 --rho 0.75 --lloyd 0 --seed 1 "
                              "-o set.json && tilesolve sample poisson-tiles window set.json --region=0,0,8x8 ")
    with page.expect_download() as dl:
        page.click("#export-json")
    dl.value.save_as(tmp_path / "solution.json")
    run = subprocess.run([SCRIPT, "verify", "solution.json"], cwd=tmp_path, capture_output=True, text=True)
    assert run.returncode == 0, run.stdout + run.stderr


@pytest.mark.slow
def test_the_window_fields_hide_for_the_set_and_the_level_for_a_density(page):
    pick(page, "recursive-wang")
    visible = lambda name: page.locator(f"#field-{name}").is_visible()  # noqa: E731
    assert visible("x0") and visible("level") and not visible("density")
    page.select_option("#field-by", "density")
    page.dispatch_event("#field-by", "change")
    page.wait_for_function("document.getElementById('describe').textContent.includes('density')")
    assert visible("density") and not visible("level")
    page.select_option("#field-show", "set")
    page.dispatch_event("#field-show", "change")
    page.wait_for_function("document.getElementById('describe').textContent.startsWith('recursive Wang tiles')")
    assert not any(visible(n) for n in ("x0", "y0", "size", "set_seed", "by", "density"))
    assert visible("subdivision")
    page.fill("#seed", "2")
    res = solve_on_page(page)
    assert res["status"] == "sat" and page.text_content("#command").startswith("tilesolve sample recursive-wang build ")


@pytest.mark.slow
def test_a_window_that_is_too_dense_is_refused_on_the_page(page):
    pick(page, "poisson-sphere")
    fill(page, "depth", 16)
    fill(page, "size", "16x16")
    page.wait_for_function("document.getElementById('describe').dataset.state === 'invalid'")
    assert "the studio shows at most 20,000" in page.text_content("#describe") + page.text_content("#error")


@pytest.mark.slow
@pytest.mark.parametrize("values", [{"show": "window", "size": "6x4", "x0": -3, "y0": 1000},
                                    {"by": "density", "density": 900, "size": "4x2"}],
                         ids=["poisson-window", "recursive-wang-density"])
def test_sampling_pictures_on_the_page(page, server, values):
    fam = "poisson" if "x0" in values else "recursive-wang"
    res = open_link(page, server, fam, values, seed=2)
    assert res["status"] == "sat" and res["seed"] == 2
    compare(f"sampling-{fam}", page.locator("#stage").screenshot(animations="disabled"))
