"""The studio's HTTP API (tilesolve.studio.app): every endpoint with valid, invalid,
oversized and concurrent requests, through Starlette's TestClient."""

from __future__ import annotations

import base64
import json
import subprocess
import threading
import time

import numpy as np
import pytest
from starlette.testclient import TestClient

from tests.clitools import SCRIPT
from tilesolve import family  # noqa: E402
from tilesolve.constructive.hashes import FnvXorshift
from tilesolve.studio.app import MAX_BODY, create_app  # noqa: E402
from tilesolve.studio import jobs as jobs_module  # noqa: E402

#: A search that runs for minutes: a corner packing with C = 4 by plain SAT (class notes §5.5).
LONG = {"family": "packing", "values": {"kind": "corner", "colors": 4, "seed": 1}, "method": "sat"}


def tiling_of(doc):
    """(status, tiling) of a solution document, read by its family's codec."""
    _, codec = family.codec_of(doc["format"])
    _, sol = codec.read(doc, "solution.json")
    return sol.status, np.asarray(sol.tiling)


@pytest.fixture(scope="module")
def client():
    # the studio's own page: TestClient's host, and an Origin header as a browser sends it
    with TestClient(create_app(warm=False), headers={"origin": "http://testserver"}) as c:
        yield c


def solve(client, body, wait=60.0):
    r = client.post("/api/solve", json=body)
    assert r.status_code == 200, r.text
    job = r.json()["id"]
    t0 = time.perf_counter()
    while True:
        state = client.get(f"/api/jobs/{job}?wait=2").json()
        if state["state"] != "running" or time.perf_counter() - t0 > wait:
            return state


def test_the_page_and_its_scripts_are_served(client):
    r = client.get("/")
    assert r.status_code == 200 and "tilesolve studio" in r.text
    assert client.get("/static/studio.js").status_code == 200


def test_every_family_with_a_form_is_listed(client):
    listed = {f["name"]: f for f in client.get("/api/families").json()["families"]}
    assert set(listed) == {f.name for f in family.families() if f.form is not None}
    assert {"dappled", "board", "packing", "stochastic"} <= set(listed)
    assert listed["dappled"]["methods"][0] == "auto"
    assert any(f["kind"] == "cells" for f in listed["dappled"]["fields"])
    assert listed["board"]["view"] and listed["stochastic"]["view"] and not listed["dappled"]["view"]
    assert all(f["pictures"] == ["svg", "png"] for f in listed.values())


def test_a_family_that_draws_only_svg_is_listed_so(client):
    """The page offers the picture exports its family draws (Family.pictures)."""
    form = family.Form(fields=(), build=lambda values: (None, {}), command=lambda values: ([], {}))
    fam = family.register(family.Family(name="toy-svg", title="toy", problem_type=type("Toy", (), {}), routes={},
                                        auto=lambda p: "x", verify=lambda p, t: [], pictures=("svg",), form=form))
    try:
        listed = {f["name"]: f for f in client.get("/api/families").json()["families"]}
        assert listed["toy-svg"]["pictures"] == ["svg"]
    finally:
        family.unregister(fam.name)


def test_check_describes_the_problem_and_the_painted_grids(client):
    r = client.post("/api/check", json={"family": "dappled", "values": {"size": "7x5", "tiles": 3, "seed": 4}})
    assert r.status_code == 200
    doc = r.json()
    assert doc["describe"].startswith("7x5 grid, |T|=3")
    assert doc["cells"]["fixed"] == [5, 7, 0, 2]
    assert doc["command"].endswith("--seed 4 -o solution.json")
    assert doc["sketch"] is None  # no tile edges to shape


def test_check_gives_the_tiles_sides_to_the_edge_editor(client):
    r = client.post("/api/check", json={"family": "isohedral", "values": {"type": "IH12", "edge0": "line:0.3,0.2/0.7,0.2",
                                                                        "edge1": "line", "seed": 1}})
    assert r.status_code == 200, r.text
    sketch = r.json()["sketch"]
    assert sketch["edges"] == [{"field": "edge0", "kind": "U"}, {"field": "edge1", "kind": "J"}]
    assert {s["edge"] for s in sketch["sides"]} == {0, 1} and sketch["chords"] == 16
    assert all(np.shape(s["map"]) == (2, 3) and isinstance(s["reverse"], bool) for s in sketch["sides"])
    # a U edge that is not mirror-symmetric is refused with the model's message
    r = client.post("/api/check", json={"family": "isohedral", "values": {"type": "IH12", "edge0": "line:0.3,0.2", "seed": 1}})
    assert r.status_code == 400 and "U edge" in r.json()["error"]


def test_fields_say_when_they_apply(client):
    fields = {f["name"]: f for f in next(f for f in client.get("/api/families").json()["families"]
                                          if f["name"] == "shapes")["fields"]}
    assert fields["holes"]["when"] == [{"question": ["heesch"]}] and fields["shape"]["when"] == []


@pytest.mark.parametrize("body, message", [
    ({"family": "nope"}, "unknown family 'nope'"),
    ({"family": "dappled", "values": {"cond": "H0=x"}}, "cannot read condition"),
    ({"family": "dappled", "values": {"size": "0x3"}}, "must be at least 1x1"),
    ({"family": "dappled", "values": {"tiles": 2.5}}, "must be a whole number"),
    ({"family": "dappled", "values": {"path": "/etc/passwd"}}, "unknown field 'path'"),
    ({"family": "dappled", "values": {"fixed": [[0, 1]]}}, "the grid must be 16x12"),
    ({"family": "dappled", "values": {"size": "2x1", "fixed": [[0, 7]]}}, "cell value 7 is outside 0..1"),
    ({"family": "dappled", "method": "magic"}, "unknown method 'magic'"),
    ({"family": "dappled", "time_limit": -1}, "time limit must be"),
    ({"family": "board", "values": {"colors": 2}}, "must be in 3..8"),
    ({"family": "board", "values": {"boundary": "1,2"}}, "boundary legs"),
    ({"family": "stochastic", "values": {"kind": "hex"}}, "must be one of wang, corner"),
])
def test_bad_input_is_one_line_400(client, body, message):
    for path in ("/api/check", "/api/solve"):
        r = client.post(path, json=body)
        assert r.status_code == 400, (path, r.text)
        error = r.json()["error"]
        assert message in error and "\n" not in error


def test_the_messages_are_the_clis(client):
    from tilesolve.errors import InvalidProblem
    from tilesolve.model.dappled import parse_condition

    with pytest.raises(InvalidProblem) as exc:
        parse_condition("H0=x")
    r = client.post("/api/check", json={"family": "dappled", "values": {"cond": "H0=x"}})
    assert r.json()["error"] == str(exc.value)


def test_sizes_are_refused_before_allocation(client):
    r = client.post("/api/check", json={"family": "dappled", "values": {"size": "100000x100000"}})
    assert r.status_code == 400 and "at most 4,194,304 here" in r.json()["error"]
    r = client.post("/api/check", content=b"{" + b" " * (MAX_BODY + 1) + b"}",
                    headers={"content-type": "application/json"})
    assert r.status_code == 413 and "request too large" in r.json()["error"]
    assert client.post("/api/check", content=b"[1, 2", headers={"content-type": "application/json"}).status_code == 400
    r = client.get("/api/view/board.png?x=0&y=0&n=100000")
    assert r.status_code == 400 and "1..128 cells" in r.json()["error"]


@pytest.mark.slow
@pytest.mark.parametrize("name", [f.name for f in family.families() if f.form is not None])
def test_each_family_solves_verifies_and_exports(client, name):
    state = solve(client, {"family": name, "values": {"seed": 3}})
    assert state["state"] == "done", state
    res = state["result"]
    assert res["status"] == "sat" and res["seed"] == 3
    assert res["verdict"][0].startswith("ok: solution.json is a valid ")
    assert (res["report"] is not None) == (name == "aperiodic")
    assert family.verify_document(json.loads(res["json"])).ok
    assert res["picture"]["format"] in ("svg", "png")
    job = state["id"]
    assert client.get(f"/api/jobs/{job}/solution.json").text == res["json"]
    svg = client.get(f"/api/jobs/{job}/picture.svg")
    assert svg.status_code == 200 and "<svg" in svg.text[:400]
    png = client.get(f"/api/jobs/{job}/picture.png")
    assert png.status_code == 200 and png.content[:8] == b"\x89PNG\r\n\x1a\n"
    assert client.get(f"/api/jobs/{job}/secret.txt").status_code == 400
    assert client.get("/api/jobs/j999999").status_code == 400


@pytest.mark.slow
def test_large_tilings_come_as_png(client):
    state = solve(client, {"family": "dappled", "values": {"size": "64x64", "seed": 1}})
    assert state["result"]["picture"]["format"] == "png"
    assert base64.b64decode(state["result"]["picture"]["data"])[:4] == b"\x89PNG"


def test_fixed_cells_are_kept(client):
    fixed = [[-1] * 8 for _ in range(6)]
    fixed[2][3], fixed[4][5] = 1, 0
    state = solve(client, {"family": "dappled", "values": {"size": "8x6", "fixed": fixed, "seed": 2}})
    cells = unpack(state["result"]["cells"])
    assert cells.shape == (6, 8) and cells[2, 3] == 1 and cells[4, 5] == 0


def unpack(packed):
    """A grid packed by the worker (``tilesolve.studio.worker.packed_cells``) as an array."""
    data = np.frombuffer(base64.b64decode(packed["data"]), dtype={"int8": "<i1", "int16": "<i2", "int32": "<i4"}[packed["dtype"]])
    return data.reshape(packed["rows"], packed["cols"])


@pytest.mark.parametrize("grid, dtype", [([[0, -1], [5, 127]], "int8"), ([[300, -1]], "int16"), ([[-70000]], "int32")])
def test_grids_are_packed_in_the_narrowest_type(grid, dtype):
    from tilesolve.studio.worker import packed_cells

    packed = packed_cells(np.array(grid))
    assert packed["dtype"] == dtype and unpack(packed).tolist() == grid


def test_the_command_keeps_the_time_limit_where_the_cli_takes_one(client):
    r = client.post("/api/check", json={"family": "dappled", "values": {"seed": 3}, "time_limit": 2.5})
    assert r.status_code == 200 and "--time-limit 2.5 --seed 3" in r.json()["command"]
    r = client.post("/api/check", json={"family": "stochastic", "values": {"seed": 3}, "time_limit": 2.5})
    assert r.status_code == 200 and "--time-limit" not in r.json()["command"]


def test_each_form_knows_whether_its_command_takes_a_time_limit():
    import click

    from tilesolve.cli.group import main_group

    for fam in family.families():
        if fam.form is None:
            continue
        words, _ = fam.form.command(fam.form.values({"seed": 1}))
        ctx = main_group.make_context("tilesolve", list(words), resilient_parsing=True)
        cmd = main_group
        for word in words:
            if not isinstance(cmd, click.Group) or word.startswith("-"):
                break
            cmd = cmd.get_command(ctx, word)
        takes = any("--time-limit" in p.opts for p in cmd.params)
        assert fam.form.time_limit == takes, fam.name


def test_the_palette_is_the_pictures(client):
    from tilesolve.io.svg import FREE_COLOUR, tile_colour

    palette = client.get("/api/families").json()["palette"]
    assert palette["tiles"][:12] == [tile_colour(k) for k in range(12)] and palette["free"] == FREE_COLOUR


def test_closest_tiling_of_a_painted_target(client):
    target = [[0] * 6 for _ in range(4)]  # all tile 0: breaks H0=2 and V0=2 everywhere
    state = solve(client, {"family": "dappled", "values": {"size": "6x4", "cond": "H0=2,V0=2", "target": target,
                                                           "seed": 1}})
    res = state["result"]
    assert res["status"] == "optimal" and res["objective"] > 0 and res["method"] == "maxsat"


def test_painted_boundary_colours_hold(client):
    edge = [[-1] * 6 for _ in range(5)]
    edge[0][1], edge[2][5] = 2, 1  # the N leg of cell (0, 0), the E leg of cell (1, 3)
    res = solve(client, {"family": "board", "values": {"size": "4x3", "boundary": "free", "edge": edge,
                                                       "seed": 1}})["result"]
    cells = json.loads(res["json"])["tiles"]
    assert cells[0][0] == 2 and cells[4 + 3][1] == 1  # N, E, S, W


def test_unsat_shows_the_reason(client):
    state = solve(client, {"family": "dappled", "values": {"size": "3x1", "cond": "H0=1,H1=1", "tiles": 2,
                                                           "fixed": [[0, 1, 1]], "seed": 1}})
    res = state["result"]
    assert res["status"] == "unsat" and res["reason"] and res["picture"] is None
    assert client.get(f"/api/jobs/{state['id']}/picture.png").status_code == 400


@pytest.mark.slow
def test_clashing_pins_are_unsat_not_an_error(client):
    state = solve(client, {"family": "packing", "values": {"pins": [[5] * 9] * 9, "seed": 1}})
    assert state["result"]["status"] == "unsat" and "pinned at" in state["result"]["reason"]


def test_cancel_a_long_search_and_the_server_goes_on(client):
    job = client.post("/api/solve", json=LONG).json()["id"]
    time.sleep(0.5)
    assert client.get(f"/api/jobs/{job}").json()["state"] == "running"
    # a small solve is not blocked by the long one
    small = solve(client, {"family": "dappled", "values": {"size": "8x8", "seed": 1}}, wait=30)
    assert small["state"] == "done"
    state = client.post(f"/api/jobs/{job}/cancel", json={}).json()
    assert state["state"] == "cancelled"
    assert client.get(f"/api/jobs/{job}/solution.json").status_code == 400
    assert solve(client, {"family": "dappled", "values": {"size": "8x8", "seed": 1}})["state"] == "done"


def test_progress_is_streamed_as_server_sent_events(client):
    """The solve's progress tasks come as events (the page's bar and status line) until the job
    ends; the last event is the job's final state, without its result."""
    job = client.post("/api/solve", json=LONG).json()["id"]
    seen = []

    def cancel_once_progress_shows():
        while True:
            state = client.get(f"/api/jobs/{job}?wait=0.5").json()
            if state["progress"] or state["state"] != "running":
                seen.append(state)
                client.post(f"/api/jobs/{job}/cancel", json={})
                return

    canceller = threading.Thread(target=cancel_once_progress_shows)
    canceller.start()
    r = client.get(f"/api/jobs/{job}/events")  # TestClient returns once the stream has ended
    canceller.join()
    assert r.status_code == 200 and r.headers["content-type"].startswith("text/event-stream")
    events = [json.loads(line[len("data: "):]) for line in r.text.splitlines() if line.startswith("data: ")]
    assert r.text.endswith("\n\n") and len(events) >= 2
    assert seen[0]["progress"][0]["label"] == "packing: solving with 'sat'" and seen[0]["progress"][0]["unit"] is None
    assert any(e["progress"] and e["progress"][0]["label"] == "packing: solving with 'sat'" for e in events)
    assert all(e["state"] == "running" for e in events[:-1])
    assert events[-1]["state"] == "cancelled" and events[-1]["progress"] == [] and "result" not in events[-1]


def test_the_events_of_an_ended_job_are_its_final_state(client):
    state = solve(client, {"family": "dappled", "values": {"size": "4x4", "seed": 1}})
    assert state["state"] == "done" and state["progress"] == []
    r = client.get(f"/api/jobs/{state['id']}/events")
    assert [json.loads(line[6:])["state"] for line in r.text.splitlines() if line.startswith("data: ")] == ["done"]


def test_a_time_limit_gives_unknown(client):
    state = solve(client, dict(LONG, time_limit=1))
    assert state["result"]["status"] == "unknown"


def test_too_many_solves_are_refused_not_queued(client, monkeypatch):
    monkeypatch.setattr(jobs_module, "MAX_RUNNING", 1)
    jobs = [client.post("/api/solve", json=LONG).json()["id"]]
    try:
        r = client.post("/api/solve", json=LONG)
        assert r.status_code == 429 and "at most 1 solves run at once" in r.json()["error"]
    finally:
        for job in jobs:
            client.post(f"/api/jobs/{job}/cancel", json={})
    assert solve(client, {"family": "dappled", "values": {"size": "4x4", "seed": 1}})["state"] == "done"


@pytest.mark.slow
def test_concurrent_requests(client):
    out = []

    def one(i):
        r = client.post("/api/check", json={"family": "dappled", "values": {"size": f"{4 + i}x4"}})
        out.append(r.status_code)
        out.append(solve(client, {"family": "stochastic", "values": {"seed": i}})["state"])

    threads = [threading.Thread(target=one, args=(i,)) for i in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert sorted(map(str, out)) == ["200"] * 4 + ["done"] * 4


@pytest.mark.slow
def test_view_tiles_agree_where_windows_overlap(client):
    from PIL import Image
    import io

    values = json.dumps({"seed": 5, "max_h": 3})
    a = client.get(f"/api/view/board.png?x=0&y=0&n=8&values={values}")
    assert a.status_code == 200 and a.headers["content-type"] == "image/png"
    b = client.get(f"/api/view/board.png?x=4&y=0&n=8&values={values}")
    ia, ib = (Image.open(io.BytesIO(r.content)).convert("RGB") for r in (a, b))
    w = ia.width // 8
    assert ia.crop((4 * w, 0, 8 * w, ia.height)).tobytes() == ib.crop((0, 0, 4 * w, ib.height)).tobytes()
    for fam in family.families():  # a tile is its window's pixels only (no caption): the page draws them edge to edge
        if fam.form is not None and fam.form.window is not None:
            tile = Image.open(io.BytesIO(client.get(f"/api/view/{fam.name}.png?x=3&y=-9&n=16").content))
            assert tile.width == tile.height and tile.width % 16 == 0, fam.name
    assert client.get(f"/api/view/stochastic.png?x=-1000&y=77&n=16&values={json.dumps({'seed': 1})}").status_code == 200
    unseeded = [client.get("/api/view/stochastic.png?x=0&y=0&n=8").content for _ in range(2)]
    assert unseeded[0] == unseeded[1]  # windows of a view without a seed share seed 0
    r = client.get("/api/view/dappled.png?x=0&y=0&n=8")
    assert r.status_code == 400 and "no infinite view" in r.json()["error"]
    assert client.get("/api/view/board.png?x=a").status_code == 400
    assert client.get("/api/view/board.png?values=%7B").status_code == 400


@pytest.mark.slow
@pytest.mark.parametrize("body", [
    {"family": "dappled", "values": {"size": "9x7", "cond": "H0=2, V1=3", "tiles": 3, "seed": 11,
                                     "fixed": [[0] + [-1] * 8] + [[-1] * 9] * 6}},
    {"family": "board", "values": {"board": "mask", "size": "6x5", "seed": 2, "boundary": "free", "max_h": 3,
                                   "max_v": 3, "mask": [[1, 1, 1, 1, 1, 1]] * 4 + [[1, 0, 0, 1, 1, 1]]},
     "method": "sat"},
    {"family": "board", "values": {"seed": 4}},
    {"family": "board", "values": {"size": "4x3", "boundary": "free", "seed": 1, "edge": [[-1, 0, 1, 2, 0, -1]] +
                                   [[1, -1, -1, -1, -1, 2]] * 3 + [[-1, 0, 0, 0, 0, -1]]}},
    {"family": "packing", "values": {"kind": "wang", "colors": 2, "seed": 1, "pins": [[3, -1, -1, -1]] + [[-1] * 4] * 3},
     "method": "sat"},
    {"family": "stochastic", "values": {"kind": "wang", "set": "compact", "colors": 2, "x0": -3, "y0": 2,
                                        "seed": 9}},
    {"family": "shapes", "values": {"grid": "hex", "shape": "XX", "size": "4x3", "seed": 2}, "time_limit": 60},
    {"family": "shapes", "values": {"where": "region", "size": "5x2", "paint": [[-1] * 8] * 5 + [[0, 1, 1] + [0] * 5] * 2 +
                                    [[0, 1, 0] + [0] * 5], "seed": 2}},
    {"family": "aperiodic-window", "values": {"builtin": "kari-culik-13", "x0": -5, "y0": 7, "size": "12x6", "seed": 4}},
])
def test_the_cli_command_reproduces_the_tiling(client, body, tmp_path):
    res = solve(client, body)["result"]
    exe = SCRIPT
    line = res["command"].replace("tilesolve ", exe + " ", 1) if "&&" not in res["command"] else \
        res["command"].replace("&& tilesolve ", f"&& {exe} ")
    run = subprocess.run(["bash", "-c", line], cwd=tmp_path, capture_output=True, text=True)
    assert run.returncode == 0, (line, run.stderr)
    ours, theirs = (tiling_of(json.loads(text)) for text in (res["json"], (tmp_path / "solution.json").read_text()))
    assert ours[0] == theirs[0] and np.array_equal(ours[1], theirs[1])
    verify = subprocess.run([exe, "verify", "solution.json"], cwd=tmp_path, capture_output=True, text=True)
    assert verify.returncode == 0, verify.stderr


@pytest.mark.slow
def test_a_window_of_the_plane_is_shown_from_its_data(client):
    res = solve(client, {"family": "stochastic", "values": {"x0": -3, "y0": 2, "size": "5x4", "seed": 1}})["result"]
    assert res["window"] == {"x0": -3, "y0": 2, "width": 5, "height": 4, "y_up": True}
    assert json.loads(res["json"])["window"] == res["window"]
    assert "window x -3..1, y 2..5 (y grows upwards)" in res["picture"]["data"]  # the SVG's caption
    assert solve(client, {"family": "board", "values": {"seed": 4}})["result"]["window"] is None
    assert "function windowCaption" in client.get("/static/studio.js").text


def test_a_report_without_a_witness_is_shown_without_a_picture(client):
    state = solve(client, {"family": "aperiodic", "values": {"tileset": "periodic-7-30", "max_square": 0,
                                                             "max_period": 1, "seed": 1}})
    res = state["result"]
    assert res["status"] == "sat" and res["picture"] is None
    assert "no picture: this report has no witness tiling to draw" in res["notes"]
    # the report in its own words: a verdict and a conclusion, not "a valid tiling"
    assert res["report"]["title"] == "aperiodicity report" and res["report"]["verdict"] == "open"
    assert res["report"]["conclusion"].startswith("No periodic tiling with these periods")
    assert res["verdict"][0].startswith("ok: solution.json is a valid aperiodicity report (")
    assert res["verdict"][0].endswith("verdict open; the CNFs of 1 refutation(s) re-derived from the problem match "
                                      "their digests, but their proofs were NOT re-checked (give --proof-dir DIR)")
    doc = json.loads(res["json"])
    assert (doc["version"], doc["verdict"], doc["status"]) == (2, "open", "sat")


def test_the_window_form_offers_every_set_with_a_constructive_route():
    from tilesolve.families.aperiodic_window import _routes_by_set
    from tilesolve.families.aperiodic_window_form import BUILTINS

    assert set(BUILTINS) == set(_routes_by_set())


def test_the_wall_view_sends_its_shaders_for_webgl2(client):
    from tilesolve.io.board_png import picture_palette

    r = client.get(f"/api/webgl/board?values={json.dumps({'seed': 7, 'colors': 4, 'max_h': 2})}")
    assert r.status_code == 200
    doc = r.json()
    assert doc["kind"] == "wall" and doc["uniforms"]["u_nc"] == 4
    assert doc["uniforms"]["u_basis"] == [w for k in range(4) for w in divmod(FnvXorshift(7, k).basis, 1 << 32)[::-1]]
    assert all(doc[k].startswith("#version 300 es\n") for k in ("vertex", "cells", "colour", "data"))
    assert doc["palette"] == [list(rgb) for rgb in picture_palette()]  # the view tiles' colours
    assert client.get("/api/webgl/stochastic").json() == {"kind": None}  # its view is the server's tiles
    r = client.get("/api/webgl/dappled")
    assert r.status_code == 400 and "no infinite view" in r.json()["error"]
    assert client.get("/api/webgl/board?values={\"colors\": 2}").status_code == 400


def test_a_chosen_palette_colours_the_wall_views_tiles_and_shaders(client):
    import io

    from PIL import Image

    from tilesolve.io.board_png import picture_palette
    from tilesolve.io.wall_png import MORTAR, N_BRICK_COLOURS

    values = json.dumps({"seed": 3, "colors": 4})
    chosen = [(0x44, 0x01, 0x54), (0x21, 0x90, 0x8C), (0xFD, 0xE7, 0x25)]
    param = ",".join(f"{r:02X}{g:02X}{b:02X}" for r, g, b in chosen)
    own = client.get(f"/api/view/board.png?values={values}&x=-8&y=4&n=16")
    mine = client.get(f"/api/view/board.png?values={values}&x=-8&y=4&n=16&palette={param}")
    assert own.status_code == mine.status_code == 200
    a, b = Image.open(io.BytesIO(own.content)), Image.open(io.BytesIO(mine.content))
    # the same pixels (palette indices), the bricks in the chosen colours taken in turn, mortar kept
    assert np.array_equal(np.asarray(a), np.asarray(b))
    used = set(np.unique(np.asarray(b)).tolist())
    assert MORTAR in used and len(used - {MORTAR}) > 10
    rgb = {tuple(c) for c in np.asarray(b.convert("RGB")).reshape(-1, 3).tolist()}
    assert rgb == set(chosen) | {picture_palette()[MORTAR]}
    # the shaders' palette texture is the tiles' palette
    doc = client.get(f"/api/webgl/board?values={values}&palette={param}").json()
    assert doc["palette"][:N_BRICK_COLOURS] == [list(chosen[i % 3]) for i in range(N_BRICK_COLOURS)]
    assert doc["palette"] == [list(c) for c in picture_palette(chosen)]
    for bad in ("12345", "GG0000", ",".join(["000000"] * 257)):
        r = client.get(f"/api/view/board.png?values={values}&x=0&y=0&n=8&palette={bad}")
        assert r.status_code == 400 and "palette" in r.json()["error"]


def test_the_texture_look_of_a_corner_tilings_view(client):
    import io

    from PIL import Image

    from tilesolve.gpu.texture import Atlas, texture_window
    from tilesolve.studio.views import TEXTURE_TILE, texture_example

    assert {f["name"]: f["texture"] for f in client.get("/api/families").json()["families"]}["stochastic"] is True
    values = json.dumps({"seed": 5, "kind": "corner", "colors": 2})
    r = client.get(f"/api/view/stochastic.png?values={values}&x=-40&y=7&n=32&look=texture")
    assert r.status_code == 200
    img = np.asarray(Image.open(io.BytesIO(r.content)).convert("RGBA"))
    at = Atlas.from_example(texture_example(), 2, tile=TEXTURE_TILE, seed=5)
    assert np.array_equal(img, texture_window(at, -40, 7, 32, 32, seed=5))  # one texel a pixel
    r = client.get(f"/api/view/stochastic.png?values={values}&x=0&y=0&n=128&look=texture")
    assert Image.open(io.BytesIO(r.content)).size == (1024, 1024)  # 8 px a tile when zoomed out
    doc = client.get(f"/api/webgl/stochastic?values={values}&look=texture").json()
    assert doc["kind"] == "texture" and doc["tile"] == TEXTURE_TILE and doc["colour"].startswith("#version 300 es\n")
    for name, vals, message in [("board", {}, "texture look"), ("stochastic", {"kind": "wang"}, "texture look"),
                                ("stochastic", {"kind": "corner", "colors": 6}, "at most 4 colours")]:
        r = client.get(f"/api/view/{name}.png?values={json.dumps(vals)}&x=0&y=0&n=8&look=texture")
        assert r.status_code == 400 and message in r.json()["error"]
    r = client.get(f"/api/webgl/stochastic?values={values}&look=photo")
    assert r.status_code == 400 and "look must be one of picture, texture" in r.json()["error"]
