"""The family contract (tilesolve.family): a new family is its modules plus one registration.

A throw-away family, 1-D dappling ("no run of 1s longer than k in a row of n cells"), is
written as a separate package in a temporary folder and registered the way a real family is:
one entry point in the group ``tilesolve.families``. Nothing in tilesolve is edited, yet the
generic solve pipeline, ``tilesolve verify``, ``demo``, ``draw`` and ``export dimacs`` handle
it (run through the real console script, which finds the family on PYTHONPATH).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from tilesolve import family
from tilesolve.errors import InternalError, InvalidProblem
from clitools import SCRIPT

TOY = textwrap.dedent('''
    """1-D dappling: a row of n cells, tiles 0/1, no run of 1s longer than k."""
    from dataclasses import dataclass
    import time

    import numpy as np

    from tilesolve.encodings import ClauseSet
    from tilesolve.errors import InvalidProblem, MethodNotApplicable
    from tilesolve.family import Codec, Demo, Family, register
    from tilesolve.model.solution import Solution, Status


    @dataclass(frozen=True)
    class RunProblem:
        n: int
        k: int

        def describe(self):
            return f"row of {self.n} cells, runs of 1s <= {self.k}"


    class RunEncoding:
        """Variable i+1: cell i holds tile 1; one clause per window of k+1 cells."""
        restricted = False

        def __init__(self, p):
            self.n_vars = p.n
            self.hard = ClauseSet()
            w = np.arange(p.n - p.k)[:, None] + np.arange(p.k + 1)[None, :]
            self.hard.add_array(-(w + 1), "windows")

        def projection(self):
            return np.arange(1, self.n_vars + 1)

        def decode(self, model):
            m = np.asarray(model)
            return (m[np.abs(m) <= self.n_vars] > 0).astype(np.int8)

        def literals(self, tiling):
            return [(i + 1) if t else -(i + 1) for i, t in enumerate(tiling)]

        def header(self):
            return ["toy 1-D dappling", "variable i+1: cell i holds tile 1"]


    def greedy(p, run):
        rng = np.random.default_rng(run.seed)
        t = rng.integers(0, 2, p.n).astype(np.int8)
        count = 0
        for i in range(p.n):
            count = count + 1 if t[i] else 0
            if count > p.k:
                t[i], count = 0, 0
        return Solution(Status.SAT, t, "greedy", None, run.seed)


    def broken(p, run):
        return Solution(Status.SAT, np.ones(p.n, np.int8), "broken", None, run.seed)


    def sat(p, run):
        from tilesolve.engine.routes import sat_route
        return sat_route(RunEncoding(p), run, solver="cadical153", t0=time.perf_counter())


    def verify(p, tiling):
        bad, count = [], 0
        for i, t in enumerate(np.asarray(tiling).tolist()):
            count = count + 1 if t == 1 else 0
            if count > p.k:
                bad.append(f"run of 1s longer than {p.k} ending at cell {i}")
        return bad


    def read(doc, source):
        if not isinstance(doc.get("n"), int) or not isinstance(doc.get("k"), int):
            raise InvalidProblem(f"{source}: 'n' and 'k' must be integers")
        p = RunProblem(doc["n"], doc["k"])
        if "status" not in doc:
            return p, None
        tiling = None if doc.get("tiling") is None else np.asarray(doc["tiling"], np.int8)
        return p, Solution(Status(doc["status"]), tiling, doc.get("method", ""), None, doc.get("seed"))


    def write(p, sol):
        return {"format": "toy/runs", "version": 1, "n": p.n, "k": p.k, "status": sol.status.value,
                "method": sol.method, "seed": sol.seed,
                "tiling": None if sol.tiling is None else sol.tiling.tolist()}


    def draw(p, sol, path, fmt, **options):
        cells = "".join(f'<rect x="{10 * i}" width="10" height="10" fill="{"#000" if t else "#fff"}"/>'
                        for i, t in enumerate(sol.tiling.tolist()))
        Path(path).write_text(f'<svg xmlns="http://www.w3.org/2000/svg">{cells}</svg>')


    from pathlib import Path

    FAMILY = register(Family(
        name="runs", title="1-D dappling (a test family)", problem_type=RunProblem,
        routes={"greedy": greedy, "sat": sat, "broken": broken},
        auto=lambda p: "greedy", verify=verify, fallback="sat",
        encode=RunEncoding, codecs=(Codec("toy/runs", frozenset({1}), read, write),), draw=draw,
        demos=(Demo("runs", "a row of 40 cells, runs <= 2", lambda: RunProblem(40, 2)),),
    ))
''')


@pytest.fixture()
def plugin(tmp_path):
    """The toy family as an installed-looking package: module + dist-info with its entry point."""
    root = tmp_path / "site"
    (root / "toyruns").mkdir(parents=True)
    (root / "toyruns" / "__init__.py").write_text(TOY)
    info = root / "toyruns-0.1.dist-info"
    info.mkdir()
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: toyruns\nVersion: 0.1\n")
    (info / "entry_points.txt").write_text("[tilesolve.families]\nruns = toyruns:FAMILY\n")
    sys.path.insert(0, str(root))
    try:
        import toyruns

        yield root, toyruns
    finally:
        sys.path.remove(str(root))
        family.unregister("runs")
        sys.modules.pop("toyruns", None)


def _cli(root: Path, *args: str, cwd: Path) -> subprocess.CompletedProcess:
    env = dict(os.environ, PYTHONPATH=str(root) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    return subprocess.run([SCRIPT, *args], cwd=cwd, capture_output=True, text=True, env=env,
                          timeout=300)


def test_generic_solve_runs_the_pipeline(plugin):
    _, toy = plugin
    p = toy.RunProblem(30, 2)
    s = family.solve(p, seed=4)
    assert s.status.value == "sat" and s.method == "greedy" and s.seed == 4 and toy.verify(p, s.tiling) == []
    assert family.solve(p, seed=4).tiling.tolist() == s.tiling.tolist()  # same seed, same tiling
    drawn = family.solve(p)
    assert isinstance(drawn.seed, int)  # a seed is drawn and recorded when none is given
    assert family.solve(p, seed=drawn.seed).tiling.tolist() == drawn.tiling.tolist()
    s = family.solve(p, "sat", seed=1)
    assert s.status.value == "sat" and toy.verify(p, s.tiling) == []
    zeros = family.solve(toy.RunProblem(3, 0), "sat", seed=1)
    assert zeros.tiling.tolist() == [0, 0, 0]  # k = 0: only the all-zero row
    with pytest.raises(InternalError, match="fails verification"):
        family.solve(p, "broken")  # an explicit route whose answer fails its verifier is a bug
    with pytest.raises(InvalidProblem, match="unknown method"):
        family.solve(p, "magic")


def test_auto_falls_back_when_a_route_fails_verification(plugin, monkeypatch):
    _, toy = plugin
    monkeypatch.setitem(toy.FAMILY.routes, "greedy", toy.broken)
    s = family.solve(toy.RunProblem(30, 2), seed=2)
    assert s.status.value == "sat" and any("fell back to 'sat'" in n for n in s.notes)


@pytest.mark.slow
def test_cli_verify_demo_draw_and_export_handle_the_new_family(plugin, tmp_path):
    root, toy = plugin
    out = tmp_path / "demo"
    proc = _cli(root, "demo", "--family", "runs", "--out", str(out), cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert (out / "runs.json").exists() and (out / "runs.svg").exists()

    proc = _cli(root, "verify", str(out / "runs.json"), cwd=tmp_path)
    assert proc.returncode == 0 and proc.stdout.startswith("ok:"), proc.stdout + proc.stderr
    doc = json.loads((out / "runs.json").read_text())
    doc["tiling"] = [1] * len(doc["tiling"])
    (tmp_path / "bad.json").write_text(json.dumps(doc))
    proc = _cli(root, "verify", "bad.json", cwd=tmp_path)
    assert proc.returncode == 1 and "run of 1s longer than 2" in proc.stdout

    proc = _cli(root, "draw", str(out / "runs.json"), "-o", "again.svg", cwd=tmp_path)
    assert proc.returncode == 0 and (tmp_path / "again.svg").read_text().startswith("<svg"), proc.stderr

    proc = _cli(root, "export", "dimacs", str(out / "runs.json"), "-o", "runs.cnf", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    lines = (tmp_path / "runs.cnf").read_text().splitlines()
    assert "c toy 1-D dappling" in lines and "p cnf 40 38" in lines

    proc = _cli(root, "backends", cwd=tmp_path)
    assert "runs" in proc.stdout and "greedy" in proc.stdout


def test_registry_refuses_clashes(plugin):
    _, toy = plugin
    clash = family.Family(name="runs2", title="", problem_type=int, routes={}, auto=lambda p: "x",
                          verify=lambda p, t: [], codecs=toy.FAMILY.codecs)
    with pytest.raises(InvalidProblem, match="belongs to another family"):
        family.register(clash)
    with pytest.raises(InvalidProblem, match="registered already"):
        family.register(family.Family(name="runs", title="", problem_type=int, routes={}, auto=lambda p: "x",
                                      verify=lambda p, t: []))
    with pytest.raises(InvalidProblem, match="no tilesolve family"):
        family.solve(np.zeros(3))
