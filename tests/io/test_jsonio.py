"""Files: atomic writes, versioned JSON, text grids, SVG and PNG pictures."""

from __future__ import annotations

import json
import os
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from tilesolve.errors import InvalidProblem
from tilesolve.io import jsonio
from tilesolve.io.atomic import atomic_write, write_text_atomic
from tilesolve.io.png import tiling_image, write_png
from tilesolve.io.svg import MAX_SVG_CELLS, PALETTE, svg_string, tile_colour, write_svg
from tilesolve.model.dappled import Condition, DappledProblem, TileCount, parse_condition
from tilesolve.model.solution import Solution, Status

SVG_NS = "{http://www.w3.org/2000/svg}"

# A 4x3 tiling satisfying H0=2 and V1=2 (checked in test_fixture_is_dappled).
TILING = np.array([[0, 0, 1, 0], [1, 0, 0, 1], [0, 1, 1, 0]])


def _problem(**kw) -> DappledProblem:
    return DappledProblem.from_strings("4x3", ["H0=2", "V1=2"], **kw)


def test_fixture_is_dappled():
    from tilesolve.verify.dappled import is_dappled

    assert is_dappled(_problem(), TILING)


# ----------------------------------------------------------------------------- atomic
def test_atomic_write_replaces_file(tmp_path):
    path = tmp_path / "a.txt"
    path.write_text("old")
    write_text_atomic(path, "new")
    assert path.read_text() == "new"
    assert os.listdir(tmp_path) == ["a.txt"]


@pytest.mark.parametrize("exc", [RuntimeError, KeyboardInterrupt])
def test_atomic_write_leaves_nothing_on_failure(tmp_path, exc):
    path = tmp_path / "a.txt"
    path.write_text("old")
    with pytest.raises(exc):
        with atomic_write(path) as f:
            f.write("half")
            raise exc()
    assert path.read_text() == "old"
    assert os.listdir(tmp_path) == ["a.txt"]
    with pytest.raises(exc):
        with atomic_write(tmp_path / "b.txt", "wb") as f:
            f.write(b"half")
            raise exc()
    assert os.listdir(tmp_path) == ["a.txt"]


def test_atomic_write_uses_umask_permissions(tmp_path):
    old = os.umask(0o022)
    try:
        write_text_atomic(tmp_path / "p.txt", "x")
    finally:
        os.umask(old)
    assert (tmp_path / "p.txt").stat().st_mode & 0o777 == 0o644


def test_atomic_write_missing_directory(tmp_path):
    with pytest.raises(OSError):
        write_text_atomic(tmp_path / "nope" / "a.txt", "x")


# ----------------------------------------------------------------------------- json
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
    jsonio.write_problem(path, p)
    doc = json.loads(path.read_text())
    assert doc["format"] == "tilesolve/dappled-problem" and doc["version"] == 1
    assert doc["size"] == {"rows": 3, "cols": 4}
    assert doc["conditions"][:3] == ["H0=2", "V{0,2}=3", "H1=inf"]
    assert doc["conditions"][3]["axis"] == "V" and doc["conditions"][3]["limit"][0] == [0, 1, 2, 0]
    q = jsonio.read_problem(path)
    assert (q.rows, q.cols, q.n_tiles, q.cyclic) == (3, 4, 3, True)
    assert list(q.conditions) == list(p.conditions)
    assert np.array_equal(q.fixed, p.fixed) and np.array_equal(q.closest_to, p.closest_to)
    assert q.counts == p.counts


def test_solution_round_trip(tmp_path):
    p = _problem()
    sol = Solution(Status.SAT, TILING, method="constructive", solver=None, seed=7, time_s=0.25,
                   notes=("a note",), stats={"vars": np.int64(12)})
    path = tmp_path / "s.json"
    jsonio.write_solution(path, p, sol)
    text = path.read_text()
    assert '    [0, 0, 1, 0],' in text  # one line per row
    q, s = jsonio.read_solution(path)
    assert q.describe() == p.describe()
    assert s.status == Status.SAT and np.array_equal(s.tiling, TILING)
    assert (s.method, s.seed, s.time_s, s.notes, s.stats) == ("constructive", 7, 0.25, ("a note",), {"vars": 12})
    # A solution file is also a problem source.
    assert jsonio.read_problem(path).describe() == p.describe()


@pytest.mark.parametrize("low, high", [(0, 2), (0, 10), (-1, 3), (0, 130)])
def test_dumps_writes_numpy_grids_like_lists(low, high):
    t = np.random.default_rng(1).integers(low, high, (6, 9))
    doc = json.loads(jsonio.dumps({"tiling": t, "nested": [t], "empty": np.zeros((0, 0), int)}))
    assert doc == {"tiling": t.tolist(), "nested": [t.tolist()], "empty": []}


def test_unsat_solution_without_tiling(tmp_path):
    path = tmp_path / "u.json"
    jsonio.write_solution(path, _problem(), Solution(Status.UNSAT, None, method="sat", reason="refuted"))
    _, s = jsonio.read_solution(path)
    assert s.status == Status.UNSAT and s.tiling is None and s.reason == "refuted"


def _doc() -> dict:
    return jsonio.solution_to_dict(_problem(), Solution(Status.SAT, TILING, method="sat"))


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
        jsonio.read_solution(path)
    text = str(err.value)
    assert message in text and str(path) in text and "\n" not in text


def test_reader_rejects_bad_json_and_missing_file(tmp_path):
    path = tmp_path / "bad.json"
    path.write_text('{"format": ')
    with pytest.raises(InvalidProblem, match="malformed JSON at line 1"):
        jsonio.load_document(path, jsonio.DAPPLED_FORMATS)
    with pytest.raises(InvalidProblem, match="no such file"):
        jsonio.load_document(tmp_path / "missing.json", jsonio.DAPPLED_FORMATS)
    path.write_text("[1, 2]")
    with pytest.raises(InvalidProblem, match="not a tilesolve file"):
        jsonio.load_document(path, jsonio.DAPPLED_FORMATS)


def test_corrupted_tiling_is_read_for_the_verifier(tmp_path):
    """Out-of-range tiles and wrong shapes are the verifier's findings, not read errors."""
    doc = _doc()
    doc["tiling"] = [[0, 5, 1, 0], [1, 0, 0, 1], [0, 1, 1, 0]]
    _, s = jsonio.solution_from_dict(doc)
    assert s.tiling[0, 1] == 5
    doc["tiling"] = [[0, 1], [1, 0]]
    _, s = jsonio.solution_from_dict(doc)
    assert s.tiling.shape == (2, 2)


def test_text_grids(tmp_path):
    assert jsonio.parse_text_grid("# c\n01?\n\n1.0\n", allow_free=True).tolist() == [[0, 1, -1], [1, -1, 0]]
    assert jsonio.parse_text_grid("10, 2\n0 11").tolist() == [[10, 2], [0, 11]]
    with pytest.raises(InvalidProblem, match="free cell"):
        jsonio.parse_text_grid("0?1")
    with pytest.raises(InvalidProblem, match="line 2: row has 2 cells"):
        jsonio.parse_text_grid("011\n01")
    with pytest.raises(InvalidProblem, match="cannot read cell 'x'"):
        jsonio.parse_text_grid("0x1", allow_free=True)
    with pytest.raises(InvalidProblem, match="empty"):
        jsonio.parse_text_grid("# nothing\n")
    assert jsonio.format_text_grid(np.array([[0, 1], [-1, 0]])) == "01\n?0\n"
    assert jsonio.format_text_grid(np.array([[10, 1]])) == "10 1\n"


def test_read_tiling_sources(tmp_path):
    grid = tmp_path / "g.txt"
    grid.write_text("0?\n10\n")
    assert jsonio.read_tiling(grid, allow_free=True).tolist() == [[0, -1], [1, 0]]
    with pytest.raises(InvalidProblem, match=r"g\.txt: line 1"):
        jsonio.read_tiling(grid)
    arr = tmp_path / "a.json"
    arr.write_text("[[0, 1], [1, 0]]")
    assert jsonio.read_tiling(arr).tolist() == [[0, 1], [1, 0]]
    sol = tmp_path / "s.json"
    jsonio.write_solution(sol, _problem(), Solution(Status.SAT, TILING, method="sat"))
    assert np.array_equal(jsonio.read_tiling(sol), TILING)
    prob = tmp_path / "p.json"
    fixed = np.full((3, 4), -1)
    fixed[1, 2] = 1
    jsonio.write_problem(prob, _problem(fixed=fixed))
    assert np.array_equal(jsonio.read_tiling(prob, allow_free=True), fixed)
    with pytest.raises(InvalidProblem, match="problem file holds no"):
        jsonio.read_tiling(prob)
    unsat = tmp_path / "u.json"
    jsonio.write_solution(unsat, _problem(), Solution(Status.UNSAT, None, method="sat"))
    with pytest.raises(InvalidProblem, match="holds no tiling"):
        jsonio.read_tiling(unsat)


# ----------------------------------------------------------------------------- svg
def _parse(text: str) -> ET.Element:
    return ET.fromstring(text)


def test_svg_is_valid_xml_with_legend():
    root = _parse(svg_string(TILING, problem=_problem(), notes=["sat by test"]))
    assert root.tag == SVG_NS + "svg"
    texts = [t.text for t in root.iter(SVG_NS + "text")]
    assert "tile 0" in texts and "tile 1" in texts
    assert any("4x3 grid" in t for t in texts) and any("H0=2, V1=2" in t for t in texts)
    assert "sat by test" in texts
    fills = {e.get("fill") for e in root.iter() if e.get("fill")}
    assert {PALETTE[0], PALETTE[1]} <= fills


def test_svg_legend_shows_per_cell_ranges():
    lim = np.array([[2, 3, 0, 5]] * 3, dtype=np.int32)
    p = DappledProblem(3, 4, conditions=(Condition("H", (0,), lim), parse_condition("V1=2")))
    texts = [t.text for t in _parse(svg_string(TILING, problem=p)).iter(SVG_NS + "text")]
    assert any("H0=2..5 per cell, V1=2" in t for t in texts)


def test_svg_cells_are_drawn_exactly():
    """Rebuild the tiling from the drawn rectangles (background = most common tile)."""
    t = np.array([[0, 1, 1, 2], [2, 2, 2, 0], [1, 0, 1, 1]])
    root = _parse(svg_string(t, cell=10, legend=False, grid=False))
    block = next(g for g in root.iter(SVG_NS + "g") if g.get("id") == "block")
    back = block.find(SVG_NS + "rect")
    colour_to_tile = {tile_colour(k): k for k in range(3)}
    out = np.full(t.shape, colour_to_tile[back.get("fill")])
    for g in block.findall(SVG_NS + "g"):
        tile = colour_to_tile[g.get("fill")]
        for r in g.findall(SVG_NS + "rect"):
            x, y, w = (int(float(r.get(k))) // 10 for k in ("x", "y", "width"))
            out[y, x : x + w] = tile
    assert np.array_equal(out, t)


def test_svg_repeat_and_grid():
    root = _parse(svg_string(TILING, repeat=3, grid=True))
    uses = list(root.iter(SVG_NS + "use"))
    assert len(uses) == 9
    dashed = [p for p in root.iter(SVG_NS + "path") if p.get("stroke-dasharray")]
    assert len(dashed) == 1  # the seams
    root = _parse(svg_string(TILING, grid=False))
    assert not list(root.iter(SVG_NS + "path"))


def test_svg_refuses_huge_tilings_and_bad_input(tmp_path):
    side = int(MAX_SVG_CELLS**0.5) + 1
    with pytest.raises(InvalidProblem, match="PNG"):
        svg_string(np.zeros((side, side), dtype=np.int8))
    with pytest.raises(InvalidProblem):
        svg_string(np.zeros(5, dtype=int))
    with pytest.raises(InvalidProblem, match="repeat"):
        svg_string(TILING, repeat=0)
    write_svg(tmp_path / "t.svg", TILING)
    assert (tmp_path / "t.svg").read_text().startswith("<?xml")


def test_palette_is_distinct():
    colours = [tile_colour(k) for k in range(40)]
    assert len(set(colours)) == 40
    assert tile_colour(-1) not in colours


# ----------------------------------------------------------------------------- png
def test_png_pixels_match_tiles(tmp_path):
    path = tmp_path / "t.png"
    write_png(path, TILING, scale=2, repeat=2, grid=False)
    from PIL import Image

    with Image.open(path) as img:
        assert img.size == (4 * 2 * 2, 3 * 2 * 2)
        rgb = np.asarray(img.convert("RGB"))
    for r in range(6):
        for c in range(8):
            want = tile_colour(int(TILING[r % 3, c % 4]))
            got = "#{:02X}{:02X}{:02X}".format(*rgb[2 * r, 2 * c])
            assert got == want


def test_png_default_scale_and_limits():
    img = tiling_image(np.zeros((2000, 1000), dtype=np.int8))
    assert img.size == (1000, 2000) and img.mode == "P"
    assert tiling_image(TILING).size == (4 * 16, 3 * 16)
    with pytest.raises(InvalidProblem, match="scale"):
        tiling_image(TILING, scale=0)


# ----------------------------------------------------------------------------- docs
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def test_readme_json_example_is_a_valid_solution():
    import re

    from tilesolve.verify.dappled import dappled_violations

    with open(os.path.join(ROOT, "README.md"), encoding="utf-8") as f:
        readme = f.read()
    block = re.search(r"```json\n(.*?)```", readme, re.S).group(1)
    problem, sol = jsonio.solution_from_dict(json.loads(block), "README.md")
    assert sol.status == Status.SAT and not dappled_violations(problem, sol.tiling)


def test_readme_install_command():
    """The quick start's install command (the test command: tests/test_readme.py)."""
    with open(os.path.join(ROOT, "README.md"), encoding="utf-8") as f:
        readme = f.read()
    assert "pip install . && tilesolve demo" in readme


def test_compact_solution_round_trip_version_2(tmp_path):
    p = _rich_problem()
    tiling = np.array([[1, 2, 0, 2], [2, 1, 1, 0], [0, 2, 1, 2]])
    sol = Solution(Status.SAT, tiling, method="sat", seed=3, objective=7)
    path = tmp_path / "s.json"
    jsonio.write_solution(path, p, sol, compact=True)
    doc = json.loads(path.read_text())
    assert doc["version"] == 2 and doc["tiling"]["dtype"] == "uint8" and doc["fixed"]["dtype"] == "int8"
    assert doc["conditions"][3]["limit"]["shape"] == [3, 4] and doc["closest_to"]["dtype"] == "bits"
    q, s = jsonio.read_solution(path)
    assert q.describe() == p.describe() and list(q.conditions) == list(p.conditions)
    assert np.array_equal(q.fixed, p.fixed) and np.array_equal(q.closest_to, p.closest_to)
    assert np.array_equal(s.tiling, tiling) and s.tiling.dtype == np.int16 and s.objective == 7  # uint8 read signed
    assert np.array_equal(jsonio.read_tiling(path), tiling)
    assert jsonio.read_problem(path).describe() == p.describe()


def test_large_solutions_are_written_compactly():
    rows, cols = 300, 220
    assert rows * cols > jsonio.COMPACT_MIN_CELLS
    p = DappledProblem.from_strings(f"{cols}x{rows}", ["H0=2"])
    t = np.indices((rows, cols)).sum(axis=0) % 2
    doc = jsonio.solution_to_dict(p, Solution(Status.SAT, t, method="constructive"), arrays=True)
    assert doc["version"] == 2 and doc["tiling"]["dtype"] == "bits"
    assert len(doc["tiling"]["data"]) == 4 * ((rows * cols // 8 + 2) // 3)  # one bit a cell, base64
    _, s = jsonio.solution_from_dict(json.loads(jsonio.dumps(doc)))
    assert np.array_equal(s.tiling, t)
    small = jsonio.solution_to_dict(_problem(), Solution(Status.SAT, TILING, method="sat"))
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
    doc = jsonio.solution_to_dict(_problem(n_tiles=3), Solution(Status.SAT, TILING * 2 % 3, method="sat"),
                                  compact=True)
    change(doc["tiling"])
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(doc))
    with pytest.raises(InvalidProblem) as err:
        jsonio.read_solution(path)
    text = str(err.value)
    assert message in text and text.startswith(str(path)) and "\n" not in text


def test_encoded_arrays_need_version_2(tmp_path):
    doc = jsonio.solution_to_dict(_problem(), Solution(Status.SAT, TILING, method="sat"), compact=True)
    doc["version"] = 1
    with pytest.raises(InvalidProblem, match="encoded arrays need version 2"):
        jsonio.solution_from_dict(doc, "f.json")
    with pytest.raises(ValueError):
        jsonio.problem_to_dict(_problem(), compact=True)


def test_list_grids_read_fast_keep_their_messages():
    doc = _doc()
    doc["tiling"] = [[0, 1, 1, 0], [1, 0, 0, True], [0, 1, 1, 0]]
    with pytest.raises(InvalidProblem, match=r"'tiling': row 1, col 3 holds True, not a tile number"):
        jsonio.solution_from_dict(doc)
    doc["tiling"] = [[0, 1, 1, 0], [1, 0, 0, -2], [0, 1, 1, 0]]
    with pytest.raises(InvalidProblem, match=r"'tiling': row 1, col 3 holds -2, not a tile number"):
        jsonio.solution_from_dict(doc)
    doc["tiling"] = [[0, 1, 1, 0], [1, 0, 0, 1.5], [0, 1, 1, 0]]
    with pytest.raises(InvalidProblem, match=r"'tiling': row 1, col 3 holds 1.5, not a tile number"):
        jsonio.solution_from_dict(doc)
