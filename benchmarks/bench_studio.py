"""The studio's answer time against the same work done in-process, measured in the same run.

Each row solves one problem of the issue's speed goal (``tilesolve studio``: a 64x64 dappled
tiling or a 100x100 brick board shown <= 0.5 s after Solve; issue 22: a 2048x2048 dappled
tiling, 16.5 s from Solve to picture before) two ways:

* baseline: in this process, warm, what the page needs: :func:`tilesolve.family.solve`, the
  solution file, its verification and the picture (:func:`tilesolve.studio.worker.solve_request`);
* studio: through a real server (uvicorn on a free port, httpx): ``POST /api/solve``, then
  ``GET /api/jobs/ID?wait=`` until the answer is there (a worker process, the JSON transfer).

The last row is one 32x32-cell window of the infinite procedural wall (``GET /api/view``),
against the same window solved and drawn in-process. The browser's own times (click to
picture, pan frame rate) are printed by ``tests/studio/test_browser.py -k speed``.

Usage::

    python benchmarks/bench_studio.py [--repeat 5]
"""

from __future__ import annotations

import argparse
import json
import threading
import time

import httpx
import uvicorn

from _measure import best
from tilesolve import family
from tilesolve.model.window import Window
from tilesolve.studio import worker
from tilesolve.studio.app import create_app

#: ``(family, values, at most this many repeats)``.
ROWS = [("dappled", {"size": "64x64", "seed": 1}, 99), ("board", {"size": "100x100", "seed": 1}, 99),
        ("dappled", {"size": "2048x2048", "seed": 1}, 2)]


def serve():
    srv = uvicorn.Server(uvicorn.Config(create_app(), host="127.0.0.1", port=0, log_level="warning"))
    threading.Thread(target=srv.run, daemon=True).start()
    while not srv.started:
        time.sleep(0.05)
    return srv, f"http://127.0.0.1:{srv.servers[0].sockets[0].getsockname()[1]}"


def studio_solve(client, name, values):
    job = client.post("/api/solve", json={"family": name, "values": values}).json()["id"]
    while (state := client.get(f"/api/jobs/{job}?wait=5").json())["state"] == "running":
        pass
    assert state["state"] == "done", state
    return state["result"]


def local_view(values, n):
    fam, vals, _, _ = worker.pose("board", values)
    problem, method, options = fam.form.window(vals, Window(0, 0, n, n))
    sol = family.solve(problem, method, seed=vals["seed"], options=options)
    return family.render(problem, sol, "png")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args()
    srv, url = serve()
    worker.warm_families()
    client = httpx.Client(base_url=url, timeout=120, headers={"origin": url})  # as the studio's own page posts
    time.sleep(1.0)
    rows = []
    for name, values, most in ROWS:
        repeat = min(args.repeat, most)
        worker.solve_request(name, values, "auto", None)  # warm this process
        studio_solve(client, name, values)               # warm the server's workers
        base, _, _ = best(lambda: worker.solve_request(name, values, "auto", None), repeat)
        wall, _, res = best(lambda: studio_solve(client, name, values), repeat)
        rows.append((f"{name} {values['size']}", base, wall, f"{res['picture']['format']}"))
    n, values = 32, {"seed": 3, "max_h": 3}
    local_view(values, n)
    base, _, _ = best(lambda: local_view(values, n), args.repeat)
    windows = iter(range(1, 10**6))  # a new window each time: no cache hit

    def fetch():
        r = client.get(f"/api/view/board.png?x={next(windows) * n}&y=0&n={n}&values={json.dumps(values)}")
        assert r.status_code == 200

    fetch()
    wall, _, _ = best(fetch, args.repeat)
    rows.append((f"wall view {n}x{n}", base, wall, "png"))
    print(f"{'problem':<20} {'picture':>7} {'in-process ms':>14} {'studio ms':>10} {'ratio':>6}")
    for what, base, wall, fmt in rows:
        print(f"{what:<20} {fmt:>7} {base * 1e3:14.1f} {wall * 1e3:10.1f} {wall / base:6.2f}")
    print("goal: a 64x64 dappled tiling or a 100x100 brick board <= 500 ms after Solve (browser: "
          "python -m pytest -s tests/studio/test_browser.py -k speed)")
    client.close()
    srv.should_exit = True


if __name__ == "__main__":
    main()
