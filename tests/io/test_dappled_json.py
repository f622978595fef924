"""The dappled codec (:mod:`tilesolve.io.dappled_json`): problem and solution files of
versions 1 and 2, their one-line errors, text grids and tilings read from any source."""

from __future__ import annotations

import json
import os

import numpy as np
import pytest

from tilesolve.errors import InvalidProblem
from tilesolve.io import dappled_json, jsonio
from tilesolve.model.dappled import Condition, DappledProblem, TileCount, parse_condition
from tilesolve.model.solution import Solution, Status

# A 4x3 tiling satisfying H0=2 and V1=2 (checked in tests/io/test_jsonio.py).
TILING = np.array([[0, 0, 1, 0], [1, 0, 0, 1], [0, 1, 1, 0]])
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def _problem(**kw) -> DappledProblem:
    return DappledProblem.from_strings("4x3", ["H0=2", "V1=2"], **kw)


def _rich_problem() -> DappledProblem:
    lim = np.arange(12, dtype=np.int32).reshape(3, 4) % 3
    fixed = np.full((3, 4), -1)
    fixed[0, 0] = 2
    return DappledProblem(
        3, 4, n_tiles=3,
        conditions=(parse_condition("H0=2"), parse_condition("V{0,2}=3"), parse_condition("H1=inf"),
                    Condition("V", (1,), lim)),
        cyclic=True, fixed=fixed, counts=(TileCount(1, 2, 5), TileCount(2, 3, 3), TileCount(0, 1, None)),
        closest_to=np.zeros((3, 4), dtype=int),
    )


def test_problem_round_trip(tmp_path):
    p = _rich_problem()
    path = tmp_path / "p.json"
    dappled_json.write_problem(path, p)
    doc = json.loads(path.read_text())
    assert doc["format"] == "tilesolve/dappled-problem" and doc["version"] == 1
    assert doc["size"] == {"rows": 3, "cols": 4}
    assert doc["conditions"][:3] == ["H0=2", "V{0,2}=3", "H1=inf"]
    assert doc["conditions"][3]["axis"] == "V" and doc["conditions"][3]["limit"][0] == [0, 1, 2, 0]
    q = dappled_json.read_problem(path)
    assert (q.rows, q.cols, q.n_tiles, q.cyclic) == (3, 4, 3, True)
    assert list(q.conditions) == list(p.conditions)
    assert np.array_equal(q.fixed, p.fixed) and np.array_equal(q.closest_to, p.closest_to)
    assert q.counts == p.counts


def test_solution_round_trip(tmp_path):
    p = _problem()
    sol = Solution(Status.SAT, TILING, method="constructive", solver=None, seed=7, time_s=0.25,
                   notes=("a note",), stats={"vars": np.int64(12)})
    path = tmp_path / "s.json"
    dappled_json.write_solution(path, p, sol)
    text = path.read_text()
    assert '    [0, 0, 1, 0],' in text  # one line per row
    q, s = dappled_json.read_solution(path)
    assert q.describe() == p.describe()
    assert s.status == Status.SAT and np.array_equal(s.tiling, TILING)
    assert (s.method, s.seed, s.time_s, s.notes, s.stats) == ("constructive", 7, 0.25, ("a note",), {"vars": 12})
    # A solution file is also a problem source.
    assert dappled_json.read_problem(path).describe() == p.describe()


def test_unsat_solution_without_tiling(tmp_path):
    path = tmp_path / "u.json"
    dappled_json.write_solution(path, _problem(), Solution(Status.UNSAT, None, method="sat", reason="refuted"))
    _, s = dappled_json.read_solution(path)
    assert s.status == Status.UNSAT and s.tiling is None and s.reason == "refuted"


def _doc() -> dict:
    return dappled_json.solution_to_dict(_problem(), Solution(Status.SAT, TILING, method="sat"))


@pytest.mark.parametrize(
    "change, message",
    [
        (lambda d: d.update(format="tilesolve/teapot"), "a 'tilesolve/teapot' file cannot be used here"),
        (lambda d: d.pop("format"), "no 'format'"),
        (lambda d: d.update(version=3), "version 3 is not supported"),
        (lambda d: d.update(version="1"), "'version' must be an integer"),
        (lambda d: d.update(size={"rows": 3}), "'size'"),
        (lambda d: d.update(size={"rows": 0, "cols": 4}), "positive"),
        (lambda d: d.update(conditions=["Q0=2"]), "conditions[0]"),
        (lambda d: d.update(conditions="H0=2"), "must be a list"),
        (lambda d: d.update(cyclic="yes"), "'cyclic'"),
        (lambda d: d.update(status="maybe"), "'status'"),
        (lambda d: d.update(tiling=[[0, 1], [1]]), "row 1 has 1 cells"),
        (lambda d: d.update(tiling=[[0, "a", 1, 0]] * 3), "not a tile number"),
        (lambda d: d.update(tiling=None), "holds no 'tiling'"),
        (lambda d: d.update(cylic=True), "unknown field 'cylic'"),
        (lambda d: d.update(counts=["1=x"]), "counts"),
        (lambda d: d.update(n_tiles=1), "at least 2 tiles"),
        (lambda d: d.update(fixed=[[0, 0], [0, 0]]), "partial tiling"),
    ],
)
def test_readers_reject_malformed(tmp_path, change, message):
    doc = _doc()
    change(doc)
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(doc))
    with pytest.raises(InvalidProblem) as err:
        dappled_json.read_solution(path)
    text = str(err.value)
    assert message in text and str(path) in text and "\n" not in text


def test_corrupted_tiling_is_read_for_the_verifier(tmp_path):
    """Out-of-range tiles and wrong shapes are the verifier's findings, not read errors."""
    doc = _doc()
    doc["tiling"] = [[0, 5, 1, 0], [1, 0, 0, 1], [0, 1, 1, 0]]
    _, s = dappled_json.solution_from_dict(doc)
    assert s.tiling[0, 1] == 5
    doc["tiling"] = [[0, 1], [1, 0]]
    _, s = dappled_json.solution_from_dict(doc)
    assert s.tiling.shape == (2, 2)


def test_text_grids(tmp_path):
    assert dappled_json.parse_text_grid("# c\n01?\n\n1.0\n", allow_free=True).tolist() == [[0, 1, -1], [1, -1, 0]]
    assert dappled_json.parse_text_grid("10, 2\n0 11").tolist() == [[10, 2], [0, 11]]
    with pytest.raises(InvalidProblem, match="free cell"):
        dappled_json.parse_text_grid("0?1")
    with pytest.raises(InvalidProblem, match="line 2: row has 2 cells"):
        dappled_json.parse_text_grid("011\n01")
    with pytest.raises(InvalidProblem, match="cannot read cell 'x'"):
        dappled_json.parse_text_grid("0x1", allow_free=True)
    with pytest.raises(InvalidProblem, match="empty"):
        dappled_json.parse_text_grid("# nothing\n")
    assert dappled_json.format_text_grid(np.array([[0, 1], [-1, 0]])) == "01\n?0\n"
    assert dappled_json.format_text_grid(np.array([[10, 1]])) == "10 1\n"


def test_read_tiling_sources(tmp_path):
    grid = tmp_path / "g.txt"
    grid.write_text("0?\n10\n")
    assert dappled_json.read_tiling(grid, allow_free=True).tolist() == [[0, -1], [1, 0]]
    with pytest.raises(InvalidProblem, match=r"g\.txt: line 1"):
        dappled_json.read_tiling(grid)
    arr = tmp_path / "a.json"
    arr.write_text("[[0, 1], [1, 0]]")
    assert dappled_json.read_tiling(arr).tolist() == [[0, 1], [1, 0]]
    sol = tmp_path / "s.json"
    dappled_json.write_solution(sol, _problem(), Solution(Status.SAT, TILING, method="sat"))
    assert np.array_equal(dappled_json.read_tiling(sol), TILING)
    prob = tmp_path / "p.json"
    fixed = np.full((3, 4), -1)
    fixed[1, 2] = 1
    dappled_json.write_problem(prob, _problem(fixed=fixed))
    assert np.array_equal(dappled_json.read_tiling(prob, allow_free=True), fixed)
    with pytest.raises(InvalidProblem, match="problem file holds no"):
        dappled_json.read_tiling(prob)
    unsat = tmp_path / "u.json"
    dappled_json.write_solution(unsat, _problem(), Solution(Status.UNSAT, None, method="sat"))
    with pytest.raises(InvalidProblem, match="holds no tiling"):
        dappled_json.read_tiling(unsat)


def test_readme_json_example_is_a_valid_solution():
    import re

    from tilesolve.verify.dappled import dappled_violations

    with open(os.path.join(ROOT, "README.md"), encoding="utf-8") as f:
        readme = f.read()
    block = re.search(r"```json\n(.*?)```", readme, re.S).group(1)
    problem, sol = dappled_json.solution_from_dict(json.loads(block), "README.md")
    assert sol.status == Status.SAT and not dappled_violations(problem, sol.tiling)


def test_compact_solution_round_trip_version_2(tmp_path):
    p = _rich_problem()
    tiling = np.array([[1, 2, 0, 2], [2, 1, 1, 0], [0, 2, 1, 2]])
    sol = Solution(Status.SAT, tiling, method="sat", seed=3, objective=7)
    path = tmp_path / "s.json"
    dappled_json.write_solution(path, p, sol, compact=True)
    doc = json.loads(path.read_text())
    assert doc["version"] == 2 and doc["tiling"]["dtype"] == "uint8" and doc["fixed"]["dtype"] == "int8"
    assert doc["conditions"][3]["limit"]["shape"] == [3, 4] and doc["closest_to"]["dtype"] == "bits"
    q, s = dappled_json.read_solution(path)
    assert q.describe() == p.describe() and list(q.conditions) == list(p.conditions)
    assert np.array_equal(q.fixed, p.fixed) and np.array_equal(q.closest_to, p.closest_to)
    assert np.array_equal(s.tiling, tiling) and s.tiling.dtype == np.int16 and s.objective == 7  # uint8 read signed
    assert np.array_equal(dappled_json.read_tiling(path), tiling)
    assert dappled_json.read_problem(path).describe() == p.describe()


def test_large_solutions_are_written_compactly():
    rows, cols = 300, 220
    assert rows * cols > jsonio.COMPACT_MIN_CELLS
    p = DappledProblem.from_strings(f"{cols}x{rows}", ["H0=2"])
    t = np.indices((rows, cols)).sum(axis=0) % 2
    doc = dappled_json.solution_to_dict(p, Solution(Status.SAT, t, method="constructive"), arrays=True)
    assert doc["version"] == 2 and doc["tiling"]["dtype"] == "bits"
    assert len(doc["tiling"]["data"]) == 4 * ((rows * cols // 8 + 2) // 3)  # one bit a cell, base64
    _, s = dappled_json.solution_from_dict(json.loads(jsonio.dumps(doc)))
    assert np.array_equal(s.tiling, t)
    small = dappled_json.solution_to_dict(_problem(), Solution(Status.SAT, TILING, method="sat"))
    assert small["version"] == 1 and small["tiling"] == TILING.tolist()


@pytest.mark.parametrize("change, message", [
    (lambda t: t.update(data="%%%"), "'tiling': 'data' is not valid base64"),
    (lambda t: t.update(data="AAAA"), "'tiling': 'data' holds 3 bytes; 12 uint8 values need 12"),
    (lambda t: t.update(dtype="float64"), "'tiling': unknown dtype 'float64'"),
    (lambda t: t.update(shape=[12]), "'tiling': expected 2 dimensions"),
    (lambda t: t.update(shape=[3, -4]), "'tiling': 'shape' must be a list of sizes"),
    (lambda t: t.pop("dtype"), "'tiling': an encoded array has exactly the fields"),
])
def test_malformed_compact_tiling_is_one_line(tmp_path, change, message):
    doc = dappled_json.solution_to_dict(_problem(n_tiles=3), Solution(Status.SAT, TILING * 2 % 3, method="sat"),
                                  compact=True)
    change(doc["tiling"])
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(doc))
    with pytest.raises(InvalidProblem) as err:
        dappled_json.read_solution(path)
    text = str(err.value)
    assert message in text and text.startswith(str(path)) and "\n" not in text


def test_encoded_arrays_need_version_2(tmp_path):
    doc = dappled_json.solution_to_dict(_problem(), Solution(Status.SAT, TILING, method="sat"), compact=True)
    doc["version"] = 1
    with pytest.raises(InvalidProblem, match="encoded arrays need version 2"):
        dappled_json.solution_from_dict(doc, "f.json")
    with pytest.raises(ValueError):
        dappled_json.problem_to_dict(_problem(), compact=True)


def test_list_grids_read_fast_keep_their_messages():
    doc = _doc()
    doc["tiling"] = [[0, 1, 1, 0], [1, 0, 0, True], [0, 1, 1, 0]]
    with pytest.raises(InvalidProblem, match=r"'tiling': row 1, col 3 holds True, not a tile number"):
        dappled_json.solution_from_dict(doc)
    doc["tiling"] = [[0, 1, 1, 0], [1, 0, 0, -2], [0, 1, 1, 0]]
    with pytest.raises(InvalidProblem, match=r"'tiling': row 1, col 3 holds -2, not a tile number"):
        dappled_json.solution_from_dict(doc)
    doc["tiling"] = [[0, 1, 1, 0], [1, 0, 0, 1.5], [0, 1, 1, 0]]
    with pytest.raises(InvalidProblem, match=r"'tiling': row 1, col 3 holds 1.5, not a tile number"):
        dappled_json.solution_from_dict(doc)
