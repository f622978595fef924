"""The studio serves only its own page (tilesolve.studio.origin, sizing, jobs): forged ``Host``
and ``Origin`` headers, cross-site and ``text/plain`` posts, oversized problems and bodies are
refused; a solve past the memory cap is stopped with a clear error; API errors name no Python
class; and through the console script, the solver processes die with a server killed by SIGKILL."""

from __future__ import annotations

import gc
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import httpx
import pytest
from starlette.testclient import TestClient

from tests.clitools import ENV, SCRIPT
from tilesolve.studio import jobs as jobs_module
from tilesolve.studio import worker
from tilesolve.studio.app import MAX_BODY, create_app

OWN = "http://testserver"
#: A search that runs for minutes: a corner packing with C = 4 by plain SAT (class notes §5.5).
LONG = {"family": "packing", "values": {"kind": "corner", "colors": 4, "seed": 1}, "method": "sat"}
SMALL = {"family": "dappled", "values": {"size": "6x4", "seed": 1}}
#: How long processes may take to end after their server is killed (a bound, not a goal).
BOUND_S = 60.0
#: A Python class name in a message (``ValueError``, ``KeyError``, ``JSONDecodeError``...).
CLASS_NAME = re.compile(r"\b[A-Z][A-Za-z]*(Error|Exception|Warning)\b|Traceback")


@pytest.fixture(scope="module")
def app():
    return create_app(warm=False)


@pytest.fixture(scope="module")
def client(app):
    with TestClient(app) as c:  # no Origin header unless a test sends one
        yield c


def post(client, path: str, body: dict, **headers):
    """A POST as the studio's page sends it (its origin, JSON), plus ``headers``."""
    return client.post(path, json=body, headers={"origin": OWN, **headers})


def jobs_started(app) -> int:
    return len(app.state.jobs._jobs)


def solve(client, body: dict) -> str:
    r = post(client, "/api/solve", body)
    assert r.status_code == 200, r.text
    return r.json()["id"]


def finish(client, job: str) -> dict:
    while True:
        state = client.get(f"/api/jobs/{job}?wait=2").json()
        if state["state"] != "running":
            return state


@pytest.mark.parametrize("host", ["evil.example", "evil.example:80", "testserver:8765", "127.0.0.1.evil.example",
                                  "localhost:80", ""])
def test_a_forged_host_is_refused(client, app, host):
    # DNS rebinding: another site's name pointed at the studio's address; its page sends its name
    job = solve(client, SMALL)
    started = jobs_started(app)
    for method, path in (("GET", "/api/families"), ("GET", f"/api/jobs/{job}"), ("GET", f"/api/jobs/{job}/solution.json"),
                         ("GET", "/"), ("POST", "/api/solve"), ("POST", "/api/check")):
        r = client.request(method, path, headers={"host": host, "origin": f"http://{host}"}, json=SMALL)
        assert r.status_code == 403, (method, path, r.text)
        assert r.json()["error"].startswith("refused: this server answers requests for testserver or testserver:80, not")
    assert jobs_started(app) == started
    assert finish(client, job)["state"] == "done"


@pytest.mark.parametrize("headers, why", [
    ({"origin": "http://evil.example"}, "not from 'http://evil.example'"),
    ({"origin": "null"}, "not from 'null'"),
    ({"origin": "http://testserver:8080"}, "not from 'http://testserver:8080'"),
    ({"origin": "https://testserver"}, "not from 'https://testserver'"),
    ({}, "not from a request without an Origin header"),
    ({"origin": OWN, "sec-fetch-site": "cross-site"}, "not from 'http://testserver'"),
    ({"origin": OWN, "sec-fetch-site": "same-site"}, "not from 'http://testserver'"),
    ({"origin": OWN, "content-type": "text/plain"}, "must be sent as JSON"),
    ({"origin": OWN, "content-type": "application/x-www-form-urlencoded"}, "must be sent as JSON"),
    ({"origin": OWN, "content-type": "multipart/form-data; boundary=x"}, "must be sent as JSON"),
])
def test_a_change_from_another_page_is_refused(client, app, headers, why):
    started = jobs_started(app)
    for path in ("/api/solve", "/api/check", "/api/jobs/j1/cancel"):
        r = client.post(path, content=b'{"family": "dappled"}', headers={"content-type": "application/json", **headers})
        assert r.status_code == 403, (path, r.text)
        assert why in r.json()["error"], r.json()
    assert jobs_started(app) == started


def test_the_own_page_may_post_json_with_a_charset(client):
    r = client.post("/api/check", content=b'{"family": "dappled"}', headers={
        "origin": OWN, "content-type": "application/json; charset=utf-8", "sec-fetch-site": "same-origin"})
    assert r.status_code == 200, r.text


def test_other_sites_cannot_read_the_api_but_may_link_the_page(client):
    for site in ("cross-site", "same-site"):
        r = client.get("/api/view/board.png?x=0&y=0&n=8", headers={"sec-fetch-site": site})
        assert r.status_code == 403 and "answers its own page only" in r.json()["error"]
        assert client.get("/api/families", headers={"sec-fetch-site": site}).status_code == 403
        assert client.get("/", headers={"sec-fetch-site": site}).status_code == 200
    assert client.get("/api/families", headers={"sec-fetch-site": "same-origin"}).status_code == 200


@pytest.mark.parametrize("method", ["sat", "maxsat", "cpsat"])
def test_an_oversized_problem_is_refused_with_its_estimate(client, app, method):
    started = jobs_started(app)
    body = {"family": "dappled", "values": {"size": "2048x2048", "tiles": 10}, "method": method}
    for path in ("/api/check", "/api/solve"):
        r = post(client, path, body)
        assert r.status_code == 400, r.text
        error = r.json()["error"]
        assert error.startswith(f"too large for the studio: method '{method}' would need about ")
        assert "(41,943,040 placements (cell, tile)); a solve here may use 2.0 GiB" in error
    assert jobs_started(app) == started
    # the same size by the constructive route is no encoding: it is accepted
    assert post(client, "/api/check", {"family": "dappled", "values": {"size": "2048x2048", "tiles": 10}}
                ).status_code == 200


def test_bodies_are_limited_while_they_are_read(client):
    # no Content-Length (chunked): refused once more than MAX_BODY bytes have come
    chunks = iter([b'{"family": "dappled", "pad": "'] + [b"x" * 65536] * (MAX_BODY // 65536 + 1) + [b'"}'])
    r = client.post("/api/check", content=chunks, headers={"origin": OWN, "content-type": "application/json"})
    assert r.status_code == 413 and r.json()["error"] == f"request too large (at most {MAX_BODY:,} bytes)"
    r = client.post("/api/check", content=b"{}", headers={"origin": OWN, "content-type": "application/json",
                                                           "content-length": str(MAX_BODY + 1)})
    assert r.status_code == 413


@pytest.mark.slow
def test_a_refused_large_request_leaves_nothing_behind(client):
    # its error's traceback held the parsed grid in a reference cycle, until a full collection
    rows = [[100_000] * 1024] * 1000  # one row object 1000 times; the parsed grid has 1000 rows
    r = post(client, "/api/check", {"family": "dappled", "values": {"size": "1024x1024", "fixed": rows}})
    assert r.status_code == 400 and "the grid must be 1024x1024" in r.json()["error"]
    parsed = [o for o in gc.get_objects() if isinstance(o, list) and len(o) == 1000 and isinstance(o[0], list)
              and len(o[0]) == 1024 and o[0] is not o[1]]
    assert parsed == []


@pytest.mark.parametrize("body", [
    b"[" * 100_000 + b"]" * 100_000,
    b'{"family": "dappled", "values": {"tiles": 1e999}}',
    b'{"family": "dappled", "values": {"size": "99999999999999999999x3"}}',
    b'{"family": "dappled", "time_limit": NaN}',
    b'{"family": "dappled", "values": {"cond": "H0=2=3"}}',
    b'{"family": "board", "values": {"boundary": "\\u0000"}}',
    b'{"family": ["dappled"]}',
    b'{"family": "dappled", "values": [1, 2]}',
    b"\xff\xfe",
    b'{"family": "dappled", "values": {"fixed": [[0, 1], 7]}}',
])
def test_api_errors_name_no_python_class(client, body):
    r = client.post("/api/check", content=body, headers={"origin": OWN, "content-type": "application/json"})
    assert r.status_code == 400, r.text
    assert not CLASS_NAME.search(r.json()["error"]), r.json()


def test_a_bug_is_one_line_without_a_class_name(client, monkeypatch, capsys):
    def broken(*args):
        raise KeyError("values")

    monkeypatch.setattr(worker, "pose", broken)
    r = post(client, "/api/check", SMALL)
    assert r.status_code == 500
    assert r.json()["error"] == "internal error in the studio server (a bug; its log has the details)"
    assert "KeyError" in capsys.readouterr().err  # the traceback is in the server's log


def test_a_solve_past_the_memory_cap_is_stopped_and_the_server_goes_on(client, monkeypatch):
    # the watch ends the process once its resident memory has grown by more than the cap: a
    # 16 MiB cap instead of 2 GiB stops the long packing search while it builds its encoding
    monkeypatch.setattr(jobs_module, "SOLVE_MEMORY", 16 << 20)
    state = finish(client, solve(client, LONG))
    assert state["state"] == "error"
    assert state["error"] == ("stopped: the solve needed more than 16 MiB of memory, the studio's limit per solve; "
                              "try a smaller problem (the tilesolve command has no such limit)")
    monkeypatch.undo()
    assert finish(client, solve(client, SMALL))["state"] == "done"


# ------------------------------------------------- through the console script: a real server


def start_server() -> tuple[subprocess.Popen, str]:
    """``tilesolve studio --no-browser --port 0`` and its URL (read from its announcement)."""
    proc = subprocess.Popen([SCRIPT, "studio", "--no-browser", "--port", "0"], stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True, env=ENV)
    line = proc.stderr.readline()
    match = re.search(r"http://127\.0\.0\.1:\d+", line)
    assert match, line
    return proc, match.group(0)


def _stat(pid: int) -> list[str] | None:
    try:
        return (Path("/proc") / str(pid) / "stat").read_text().rsplit(")", 1)[1].split()
    except OSError:
        return None


def descendants(pid: int) -> set[int]:
    """Live (non-zombie) descendants of ``pid``, from /proc."""
    parents = {}
    for entry in Path("/proc").iterdir():
        fields = _stat(int(entry.name)) if entry.name.isdigit() else None
        if fields is not None and fields[0] != "Z":
            parents[int(entry.name)] = int(fields[1])
    out, todo = set(), [pid]
    while todo:
        p = todo.pop()
        kids = [c for c, pp in parents.items() if pp == p]
        out.update(kids)
        todo.extend(kids)
    return out


def alive(pid: int) -> bool:
    fields = _stat(pid)
    return fields is not None and fields[0] != "Z"


@pytest.mark.slow
def test_forged_headers_are_refused_by_the_real_server():
    proc, url = start_server()
    try:
        port = url.rsplit(":", 1)[1]
        with httpx.Client(base_url=url, timeout=60) as http:
            assert http.get("/api/families").status_code == 200
            assert http.get("/api/families", headers={"host": f"localhost:{port}"}).status_code == 200
            r = http.get("/api/families", headers={"host": f"rebound.example:{port}"})
            assert r.status_code == 403 and "answers requests for 127.0.0.1:" in r.json()["error"]
            r = http.post("/api/solve", content=b'{"family": "dappled"}', headers={"content-type": "text/plain"})
            assert r.status_code == 403
            r = http.post("/api/solve", json=SMALL, headers={"origin": "http://evil.example"})
            assert r.status_code == 403
            r = http.post("/api/check", json=SMALL, headers={"origin": url})
            assert r.status_code == 200, r.text
    finally:
        proc.terminate()
        proc.wait()


@pytest.mark.slow
@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_solver_processes_die_with_a_killed_server():
    proc, url = start_server()
    try:
        with httpx.Client(base_url=url, timeout=120, headers={"origin": url}) as http:
            job = http.post("/api/solve", json=LONG).json()["id"]
            # the forkserver warms itself (a solve of every family), then forks the worker
            t0 = time.perf_counter()
            while not any(len(descendants(c)) for c in descendants(proc.pid)):
                assert time.perf_counter() - t0 < 600, "no worker process started"
                time.sleep(0.5)
            assert http.get(f"/api/jobs/{job}").json()["state"] == "running"
        family = descendants(proc.pid)
        assert len(family) >= 3  # the forkserver, the solving worker, a spare (and the resource tracker)
    finally:
        os.kill(proc.pid, signal.SIGKILL)
        proc.wait()
    t0 = time.perf_counter()
    while any(alive(p) for p in family) and time.perf_counter() - t0 < BOUND_S:
        time.sleep(0.1)
    assert not [p for p in family if alive(p)], "processes outlived their server"
