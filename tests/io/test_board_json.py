"""Board solution files, versions 1, 2 and 3: round trips, old files, other readers, bad input
(the forgeries, through the console script: tests/verify/test_board_forgery.py)."""

import base64
import json
import shutil
from pathlib import Path

import numpy as np
import pytest

from tilesolve.errors import InvalidProblem
from tilesolve.io import jsonio
from tilesolve.io.board_json import (
    COMPACT_MIN_CELLS, ListedBoardProblem, board_solution_to_dict, read_board_solution, write_board_solution,
)
from tilesolve.model.aperiodic import Lattice
from tilesolve.model.board import Board, BoardProblem, WangTileSet
from tilesolve.model.solution import Solution, Status
from tilesolve.verify.board import listing_violations

from clitools import run

#: Files written by tilesolve before version 3 (versions 1 and 2, legs W, N, E, S), with the
#: DRAT proofs of the unsat ones and the tile set they were solved for.
OLD = Path(__file__).parents[1] / "data" / "board_solution"
#: Where a leg of a version 1 or 2 file (W, N, E, S) stands in N, E, S, W, written out by hand.
NESW_INDEX = {0: 3, 1: 0, 2: 1, 3: 2}


def _boards():
    mob = Board.mobius(7, 5)
    keep = np.ones(mob.n_cells, bool)
    keep[[8, 9, 16, 34]] = False  # the last row loses a cell: the grid keeps its 5 rows
    ring = Board.ring(5, 4)
    return {
        "rect": Board.rect(4, 3), "torus": Board.torus(4, 3), "cylinder": Board.cylinder(5, 2),
        "mobius": Board.mobius(3, 4), "klein": Board.klein(3, 3), "ring": ring,
        "mask": Board.random_holes(6, 6, 0.3, seed=2), "mobius|U": mob.restrict(keep),
        "tree": Board.random_tree(12, seed=1),
        "grid": Board.grid(np.arange(20).reshape(4, 5) % 7 != 3, wrap_rows="twist", wrap_cols="plain"),
        "edges only": Board.from_edges(ring.labels, ring.edge_array(), kind="ring"),
    }


def _problem_and_solution(board, seed=0, tiling=True):
    rng = np.random.default_rng(seed)
    beta = rng.integers(-1, 3, board.n_boundary)
    p = BoardProblem(board, WangTileSet.brick(3), beta, max_h=3 if seed % 2 else None)
    tiles = rng.integers(0, 3, (board.n_cells, 4)) if tiling else None
    status = Status.SAT if tiling else Status.UNSAT
    return p, Solution(status, tiles, method="linear", seed=seed, time_s=0.5, stats={"cycles": 2})


def _same(p, s, q, t):
    if isinstance(q, ListedBoardProblem):  # what tilesolve lists is the board it describes
        assert listing_violations(q.board, q.listed_cells, q.listed_edges) == []
    for name in ("labels", "nbr_cell", "nbr_leg"):
        assert np.array_equal(getattr(p.board, name), getattr(q.board, name)), name
    assert p.board.kind == q.board.kind
    assert np.array_equal(p.boundary, q.boundary)
    assert (p.n_colors, p.tileset.is_brick, p.max_h, p.max_v) == (q.n_colors, q.tileset.is_brick, q.max_h, q.max_v)
    assert t.status == s.status and (t.method, t.seed, t.time_s, t.stats) == (s.method, s.seed, s.time_s, s.stats)
    assert (s.tiling is None and t.tiling is None) or np.array_equal(s.tiling, t.tiling)


@pytest.mark.parametrize("compact", [False, True])
@pytest.mark.parametrize("name", list(_boards()))
def test_round_trip_gives_the_same_problem_and_tiling(tmp_path, name, compact):
    board = _boards()[name]
    for seed, tiling in ((0, True), (1, True), (2, False)):
        p, s = _problem_and_solution(board, seed, tiling)
        path = tmp_path / "s.json"
        write_board_solution(path, p, s, compact=compact)
        doc = json.loads(path.read_text())
        assert doc["version"] == 3 and doc["leg_order"] == ["N", "E", "S", "W"]
        if compact:
            assert ("grid" in doc) == (board.grid_spec is not None) and ("edges" in doc) == (board.grid_spec is None)
        _same(p, s, *read_board_solution(path))


def test_large_boards_are_written_compactly_and_small_ones_as_lists():
    small = Board.rect(64, 64)
    big = Board.with_holes(70, 70, 8, 5, seed=1)
    assert small.n_cells <= COMPACT_MIN_CELLS < big.n_cells
    assert isinstance(board_solution_to_dict(*_problem_and_solution(small))["boundary"], list)
    doc = board_solution_to_dict(*_problem_and_solution(big))
    assert doc["version"] == 3 and doc["mask"]["dtype"] == "bits" and doc["tiles"]["dtype"] == "uint8"
    assert board_solution_to_dict(*_problem_and_solution(Board.rect(80, 80)))["mask"] is None


@pytest.mark.parametrize("rows, cols, colours", [(3, 5, 3), (70, 90, 3), (70, 90, 2), (33, 301, 4)])
def test_a_rectangle_streamed_is_the_same_file(tmp_path, monkeypatch, rows, cols, colours):
    """write_rect_solution writes the bytes write_board_solution writes, in pieces (here of 6
    and 12 cells too), whatever dtype the tiles take (``bits`` for colours 0 and 1)."""
    from tilesolve.io import board_json
    from tilesolve.model.window import Window

    legs = np.random.default_rng(rows).integers(0, colours, (rows, cols, 4))
    sol = Solution(Status.SAT, legs.reshape(-1, 4), "procedural", None, 5, 0.25, notes=("a note",),
                   window=Window(-3, 8, cols, rows))
    problem = BoardProblem(Board.rect(cols, rows), WangTileSet.brick(3), None, max_h=2, max_v=3)
    write_board_solution(tmp_path / "whole.json", problem, sol)
    for piece in (6, 12, board_json.STREAM_CELLS):
        monkeypatch.setattr(board_json, "STREAM_CELLS", piece)
        board_json.write_rect_solution(tmp_path / "streamed.json", legs.astype(np.int8), WangTileSet.brick(3), sol,
                                       max_h=2, max_v=3)
        assert (tmp_path / "streamed.json").read_bytes() == (tmp_path / "whole.json").read_bytes()
    tiles = json.loads((tmp_path / "whole.json").read_text())["tiles"]
    if rows * cols > COMPACT_MIN_CELLS:
        assert tiles["dtype"] == ("bits" if colours == 2 else "uint8")
    else:
        assert isinstance(tiles, list)


def test_version_3_reads_with_base64_and_numpy_alone(tmp_path):
    """What the module docstring tells another tool, done by hand."""
    board = Board.mobius(6, 4).restrict(np.arange(24) != 7)
    p, s = _problem_and_solution(board, 3)
    path = tmp_path / "s.json"
    write_board_solution(path, p, s, compact=True)
    doc = json.loads(path.read_text())
    g = doc["grid"]
    assert (g["rows"], g["cols"], g["wrap_rows"], g["wrap_cols"]) == (4, 6, None, "twist")
    mask = np.unpackbits(np.frombuffer(base64.b64decode(doc["mask"]["data"]), np.uint8), count=24).reshape(4, 6)
    assert mask.sum() == 23 and mask[1, 1] == 0
    tiles = np.frombuffer(base64.b64decode(doc["tiles"]["data"]), "<u1").reshape(doc["tiles"]["shape"])
    assert np.array_equal(tiles, s.tiling)  # the tiling's rows as they are: legs N, E, S, W
    beta = np.frombuffer(base64.b64decode(doc["boundary"]["data"]), "<i1")
    assert np.array_equal(beta, p.boundary)


def test_reads_a_version_1_file_written_by_hand(tmp_path):
    doc = {
        "format": "tilesolve/board-solution", "version": 1, "board_kind": "rect",
        "leg_order": ["W", "N", "E", "S"], "colors": 3, "tileset": "brick", "max_h": None, "max_v": None,
        "status": "sat", "method": "linear", "solver": None, "seed": 4, "time_s": 0.1, "reason": None,
        "notes": [], "stats": {},
        "cells": [[0, 0], [0, 1]],
        "edges": [[0, 0, -1, 0], [0, 1, -1, 1], [0, 2, 1, 0], [0, 3, -1, 2],
                  [1, 1, -1, 3], [1, 2, -1, 4], [1, 3, -1, 5]],
        "boundary": [1, None, None, 0, None, None],
        "tiles": [[1, 0, 2, 1], [2, 0, 2, 2]],
    }
    path = tmp_path / "v1.json"
    path.write_text(json.dumps(doc))
    q, t = read_board_solution(path)
    b = Board.rect(2, 1)
    assert np.array_equal(q.board.nbr_cell, b.nbr_cell) and np.array_equal(q.board.nbr_leg, b.nbr_leg)
    # boundary legs renumbered by cell, then N, E, S, W: W of cell 0 (was 0) is now 2, N of cell 1 stays 3;
    # the tiling's legs are N, E, S, W in memory
    assert q.boundary.tolist() == [-1, -1, 1, 0, -1, -1] and t.tiling.tolist() == [[0, 2, 1, 1], [0, 2, 2, 2]]
    # the same file in version 3: tiles and leg numbers in N, E, S, W; boundary legs numbered alike
    v3 = _as_version_3(doc)
    assert v3["tiles"] == [[0, 2, 1, 1], [0, 2, 2, 2]] and v3["edges"][:3] == [[0, 3, -1, 2], [0, 0, -1, 0], [0, 1, 1, 3]]
    assert v3["boundary"] == [None, None, 1, 0, None, None]
    path.write_text(json.dumps(v3))
    q3, t3 = read_board_solution(path)
    assert np.array_equal(q3.board.nbr_cell, b.nbr_cell) and np.array_equal(q3.board.nbr_leg, b.nbr_leg)
    assert q3.boundary.tolist() == q.boundary.tolist() and t3.tiling.tolist() == v3["tiles"]


def _as_version_3(doc: dict) -> dict:
    """A version 1 document (plain lists, legs W, N, E, S) in version 3's leg order, by hand."""
    out = dict(doc, version=3, leg_order=["N", "E", "S", "W"])
    out["tiles"] = [[w_n_e_s[i] for i in (1, 2, 3, 0)] for w_n_e_s in doc["tiles"]]
    out["edges"] = [[a, NESW_INDEX[ka], b, kb if b < 0 else NESW_INDEX[kb]] for a, ka, b, kb in doc["edges"]]
    if isinstance(doc["tileset"], list):
        out["tileset"] = [[w_n_e_s[i] for i in (1, 2, 3, 0)] for w_n_e_s in doc["tileset"]]
    return _walls_renumbered(out)


def _walls_renumbered(doc: dict) -> dict:
    """``doc`` with its wall legs numbered 0, 1, ... by cell, then by leg number (in the
    document's own leg order), the boundary colours moved along."""
    walls = sorted((a, ka, kb) for a, ka, b, kb in doc["edges"] if b < 0)
    new = {kb: i for i, (_, _, kb) in enumerate(walls)}
    doc["edges"] = [[a, ka, b, new[kb] if b < 0 else kb] for a, ka, b, kb in doc["edges"]]
    boundary = [None] * len(new)
    for old, i in new.items():
        boundary[i] = doc["boundary"][old]
    doc["boundary"] = boundary
    return doc


def _as_version_1(doc: dict) -> dict:
    """A version 3 document with plain lists back in version 1's leg order, by hand."""
    back = {v: k for k, v in NESW_INDEX.items()}
    out = json.loads(jsonio.dumps(doc))
    out.update(version=1, leg_order=["W", "N", "E", "S"])
    out["tiles"] = [[n_e_s_w[i] for i in (3, 0, 1, 2)] for n_e_s_w in out["tiles"]]
    out["edges"] = [[a, back[ka], b, kb if b < 0 else back[kb]] for a, ka, b, kb in out["edges"]]
    return _walls_renumbered(out)


def test_versions_1_and_3_of_one_solution_read_the_same(tmp_path):
    for board in (Board.mobius(4, 3).restrict(np.arange(12) != 5), Lattice(3, 4, 1).board()):
        p, s = _problem_and_solution(board, 1)
        v3 = board_solution_to_dict(p, s, compact=False)
        (tmp_path / "v3.json").write_text(jsonio.dumps(v3))
        (tmp_path / "v1.json").write_text(json.dumps(_as_version_1(v3)))
        _same(p, s, *read_board_solution(tmp_path / "v3.json"))
        _same(p, s, *read_board_solution(tmp_path / "v1.json"))


def test_a_window_of_the_plane_is_data_in_version_3_only(tmp_path):
    from dataclasses import replace

    from tilesolve.model.window import Window

    p, s = _problem_and_solution(Board.rect(4, 3))
    s = replace(s, window=Window(-2, 5, 4, 3))
    write_board_solution(tmp_path / "w.json", p, s)
    doc = json.loads((tmp_path / "w.json").read_text())
    assert doc["window"] == {"x0": -2, "y0": 5, "width": 4, "height": 3, "y_up": True}
    assert read_board_solution(tmp_path / "w.json")[1].window == Window(-2, 5, 4, 3)
    assert "window" not in board_solution_to_dict(*_problem_and_solution(Board.rect(4, 3)))
    doc["window"]["width"] = 0
    assert "'window': window size must be positive" in _read_error(tmp_path, doc)
    assert "'window' needs version 3" in _read_error(tmp_path, dict(_as_version_1(doc), window=doc["window"]))


def test_a_window_that_is_not_the_boards_grid_is_refused(tmp_path):
    p, s = _problem_and_solution(Board.rect(4, 3))
    doc = json.loads(jsonio.dumps(board_solution_to_dict(p, s)))
    rows, cols = p.board.grid_spec.rows, p.board.grid_spec.cols
    for width, height in ((cols, rows + 1), (cols - 1, rows), (rows, cols)):  # the last one transposed
        window = {"x0": 0, "y0": 0, "width": width, "height": height, "y_up": True}
        message = f"'window' is {width}x{height} cells (WxH), but the board has the grid {cols}x{rows}"
        assert message in _read_error(tmp_path, dict(doc, window=window))


def _v2_doc():
    """A compact document (encoded arrays); version 3 has version 2's encodings."""
    return board_solution_to_dict(*_problem_and_solution(Board.with_holes(9, 7, 2, 2, seed=3)), compact=True)


def _set(path, value):
    def change(d):
        *head, last = path
        for k in head:
            d = d[k]
        d[last] = value
    return change


@pytest.mark.parametrize("change, field, message", [
    (_set(["tiles", "data"], "not base64!"), "tiles", "not valid base64"),
    (_set(["tiles", "data"], base64.b64encode(b"\0" * 7).decode()), "tiles", "holds 7 bytes"),
    (_set(["tiles", "dtype"], "float32"), "tiles", "unknown dtype 'float32'"),
    (_set(["tiles", "shape"], "63x4"), "tiles", "'shape' must be a list"),
    (_set(["tiles", "data"], 12), "tiles", "'data' must be a base64 string"),
    (_set(["tiles"], "brick"), "tiles", "expected an encoded array"),
    (_set(["tiles", "extra"], 1), "tiles", "exactly the fields"),
    (_set(["mask", "shape"], [9, 7]), "mask", "0/1 values of shape [7, 9]"),
    (_set(["mask", "dtype"], "uint8"), "mask", "holds"),
    (_set(["mask", "data"], base64.b64encode(b"\xff" * 8).decode()), "mask", "bits set after the last value"),
    (_set(["boundary", "data"], "AAAA"), "boundary", "bytes"),
    (_set(["grid", "wrap_cols"], "spiral"), "grid", "wrap_cols"),
    (_set(["grid", "rows"], "7"), "grid", "'rows' must be an integer"),
    (_set(["grid", "rows"], 0), "grid", "positive"),
    (lambda d: d.pop("grid"), "grid", "needs 'grid' or 'cells' and 'edges'"),
])
def test_malformed_version_2_is_one_line_naming_file_and_field(tmp_path, change, field, message):
    doc = _v2_doc()
    change(doc)
    text = _read_error(tmp_path, doc)
    assert message in text and field in text


def _read_error(tmp_path, doc) -> str:
    """The one-line error of reading ``doc`` from a file, which it names."""
    path = tmp_path / "bad.json"
    path.write_text(jsonio.dumps(doc))
    with pytest.raises(InvalidProblem) as err:
        read_board_solution(path)
    text = str(err.value)
    assert str(path) in text and "\n" not in text
    return text


def test_unknown_versions_are_still_refused(tmp_path):
    doc = _v2_doc()
    doc["version"] = 4
    path = tmp_path / "v4.json"
    path.write_text(json.dumps(doc))
    with pytest.raises(InvalidProblem, match="version 4 is not supported"):
        read_board_solution(path)


@pytest.mark.parametrize("values", [[0, 1, 1, 0], [[3, 200], [0, 5]], [-1, 40000], [2**40, -3]])
def test_encoded_arrays_round_trip_in_the_narrowest_dtype(values):
    a = np.array(values)
    enc = jsonio.encode_array(a)
    assert np.array_equal(jsonio.decode_array(json.loads(json.dumps(enc)), "x", "f"), a)
    width = {"bits": 1 / 8, "uint8": 1, "int16": 2, "int32": 4, "int64": 8}[enc["dtype"]]
    lo, hi = a.min(), a.max()
    assert width == (1 / 8 if lo >= 0 and hi <= 1 else 1 if lo >= 0 and hi < 256 else
                     2 if -2**15 <= lo and hi < 2**15 else 4 if -2**31 <= lo and hi < 2**31 else 8)


def test_lists_record_the_grid_and_mask_besides_the_list():
    board = Board.mobius(4, 3).restrict(np.arange(12) != 5)
    doc = board_solution_to_dict(*_problem_and_solution(board), compact=False)
    assert doc["grid"] == {"rows": 3, "cols": 4, "wrap_rows": None, "wrap_cols": "twist"}
    assert doc["mask"].tolist() == [[1, 1, 1, 1], [1, 0, 1, 1], [1, 1, 1, 1]]
    assert doc["cells"].shape == (11, 2) and doc["edges"].shape == (board.n_edges, 4)


def test_a_listed_grid_board_keeps_its_list_for_the_verifier(tmp_path):
    p, s = _problem_and_solution(Board.ring(5, 4))
    path = tmp_path / "s.json"
    write_board_solution(path, p, s, compact=False)
    q, _ = read_board_solution(path)
    assert isinstance(q, ListedBoardProblem) and q.board.grid_spec == p.board.grid_spec
    assert np.array_equal(q.listed_cells, p.board.labels) and np.array_equal(q.listed_edges, p.board.edge_array())
    write_board_solution(path, p, s, compact=True)
    assert type(read_board_solution(path)[0]) is BoardProblem  # described only: nothing else to check


def _v1_doc():
    return _as_version_1(board_solution_to_dict(*_problem_and_solution(Board.rect(3, 2)), compact=False))


@pytest.mark.parametrize("make, change, message", [
    (_v1_doc, _set(["extra"], 1), "unknown field 'extra'"),
    (_v2_doc, _set(["board"], "rect"), "unknown field 'board'"),
    (_v1_doc, _set(["colors"], 64), "'colors' is 64; brick Wang tiles have 3 to 63"),
    (_v1_doc, _set(["colors"], 2), "'colors' is 2"),
    (_v1_doc, lambda d: d.update(tileset=[[0, 1, 0, 1]], colors=1 << 17), "a list of tiles has 1 to 65536"),
    (_v1_doc, _set(["tileset"], {"tiles": []}), "'tileset' must be \"brick\" or a list of tiles"),
    (_v1_doc, _set(["grid", "cols"], 1 << 27), "'grid' is 134217728x2"),
    (_v1_doc, _set(["max_h"], 2**31), "'max_h' is 2147483648"),
    (_v1_doc, _set(["leg_order"], 5), "leg_order 5"),
    (_v1_doc, _set(["leg_order"], ["N", "E", "S", "W"]), "is not that of version 1, ['W', 'N', 'E', 'S']"),
    (_v2_doc, _set(["leg_order"], ["W", "N", "E", "S"]), "is not that of version 3, ['N', 'E', 'S', 'W']"),
    (_v1_doc, _set(["cells"], {"dtype": "uint8", "shape": [6, 2], "data": ""}), "encoded arrays need version 2"),
    (_v1_doc, lambda d: d.pop("edges"), "'cells' and 'edges' together"),
    (_v1_doc, lambda d: (d.pop("edges"), d.pop("cells")), "lists 'cells' and 'edges'"),
    (_v1_doc, _set(["cells"], [[0, 0, 0]] * 6), "2 integers per entry"),
    (_v1_doc, _set(["boundary", 0], 2**70), "'boundary': must hold integers only"),
    (_v1_doc, _set(["board_kind"], "torus"), "a torus board has wrap_rows 'plain'"),
    (_v2_doc, _set(["board_kind"], "rect"), "not that of a rect board of 9x7"),
])
def test_malformed_or_absurd_fields_are_one_line(tmp_path, make, change, message):
    doc = make()
    change(doc)
    assert message in _read_error(tmp_path, doc)


def test_a_board_given_by_its_joins_alone_needs_distinct_labels(tmp_path):
    p, s = _problem_and_solution(Lattice(3, 4, 1).board())
    path = tmp_path / "s.json"
    for compact in (False, True):
        write_board_solution(path, p, s, compact=compact)
        q, _ = read_board_solution(path)
        assert q.board.kind == "sheared torus" and type(q) is BoardProblem  # its list is its description
        doc = json.loads(path.read_text())
        cells = jsonio.decode_array(doc["cells"], "cells", path)
        cells[0] = cells[1]
        doc["cells"] = cells.tolist() if not compact else jsonio.encode_array(cells)
        path.write_text(json.dumps(doc))
        with pytest.raises(InvalidProblem, match=r"cells 0 and 1 have the same label \[0, 1\]"):
            read_board_solution(path)


@pytest.mark.parametrize("name", sorted(p.name for p in OLD.glob("v[12]-*.json")))
def test_files_of_versions_1_and_2_still_read_and_verify(tmp_path, name):
    """Files tilesolve wrote before version 3 (legs W, N, E, S): the unsat ones' proofs are
    re-checked against the CNF re-derived from the file, so its tile set reads in the order
    written."""
    shutil.copytree(OLD, tmp_path / "old")
    proc = run("verify", name, "--proof-dir", "proofs", cwd=tmp_path / "old")
    assert proc.returncode == 0, proc.stderr
    out = proc.stdout + proc.stderr
    assert out.startswith(f"ok: {name}") and ("unsat re-checked" in out) == ("unsat" in name)
    q, t = read_board_solution(OLD / name)
    doc = json.loads((OLD / name).read_text())
    assert doc["version"] == int(name[1]) and doc["leg_order"] == ["W", "N", "E", "S"]
    if isinstance(doc["tileset"], list):  # written as legs W, N, E, S; read as tiles N, E, S, W
        assert q.tileset.tiles.tolist() == [[n, e, s, w] for w, n, e, s in doc["tileset"]]
    if doc.get("tiles") is not None:  # each cell's legs W, N, E, S in the file: N, E, S, W in memory
        written = jsonio.decode_array(doc["tiles"], "tiles", name)
        assert np.array_equal(t.tiling, written[:, [1, 2, 3, 0]])
    # written again, as version 3, it reads to the same problem and tiling
    write_board_solution(tmp_path / "v3.json", q, t)
    _same(q, t, *read_board_solution(tmp_path / "v3.json"))


def test_a_large_grid_board_is_read_and_verified_without_its_joins(tmp_path):
    """A compact file of a grid board is read and verified from its grid: the board's labels
    and join arrays (8 bytes a leg) are never built."""
    from tilesolve.families import board as wang

    b = Board.rect(80, 60)
    p = BoardProblem(b, WangTileSet.brick(3))
    s = wang.solve(p, seed=1)
    write_board_solution(tmp_path / "b.json", p, s)
    q, t = read_board_solution(tmp_path / "b.json")
    assert wang.FAMILY.verify(q, t.tiling) == [] and q.describe() == p.describe()
    assert "nbr_cell" not in vars(q.board) and "labels" not in vars(q.board)
