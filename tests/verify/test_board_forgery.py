"""Forged board-solution files, through the console script (issue 17, parts 3 and 4).

A board file describes its board (kind, grid, mask) and, for a board of at most 4096 cells,
lists its cells and edges too. ``tilesolve verify`` rebuilds the board from the description; every difference
between the list and that board is a violation with its position (exit 1), and
``tilesolve draw`` refuses the file (exit 2, one line, no picture). Absurd sizes and colour
counts are refused before anything is built: one line, exit 2, within a 1 GiB address space.
"""

from __future__ import annotations

import copy
import json
import subprocess
import sys

import pytest

from clitools import ENV, SCRIPT, one_line_error, run


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """Solutions written by tilesolve (version 3): a 60x40 rectangle, a mask board and a torus
    with their lists, and a 70x70 rectangle described only."""
    d = tmp_path_factory.mktemp("boards")
    (d / "m.txt").write_text("######\n##..##\n#.####\n")
    for name, spec in (("rect", "rect:60x40"), ("mask", "mask:m.txt"), ("torus", "torus:6x4"),
                       ("big", "rect:70x70")):
        proc = run("-q", "brick", "solve", "--board", spec, "--seed", "1", "-o", f"{name}.json", cwd=d)
        assert proc.returncode == 0, proc.stderr
    return d, {name: json.loads((d / f"{name}.json").read_text()) for name in ("rect", "mask", "torus", "big")}


def _verify_forged(folder, doc, name="forged.json"):
    (folder / name).write_text(json.dumps(doc))
    return run("verify", name, cwd=folder)


def _violations(proc) -> list[str]:
    assert proc.returncode == 1, (proc.stdout, proc.stderr)
    assert "Traceback" not in proc.stderr and not proc.stdout.startswith("ok")
    return [ln.strip() for ln in proc.stdout.splitlines()[1:]]


def test_files_as_written_verify_and_carry_their_grid(files):
    folder, docs = files
    assert docs["rect"]["version"] == 3 and docs["rect"]["grid"] == {"rows": 40, "cols": 60, "wrap_rows": None,
                                                                    "wrap_cols": None}
    assert docs["mask"]["mask"] == [[1] * 6, [1, 1, 0, 0, 1, 1], [1, 0, 1, 1, 1, 1]]
    assert docs["big"]["version"] == 3 and "cells" not in docs["big"]
    for name in docs:
        proc = run("verify", f"{name}.json", cwd=folder)
        assert proc.returncode == 0 and proc.stdout.startswith("ok:"), proc.stdout + proc.stderr


@pytest.mark.fast_cases(1)
@pytest.mark.parametrize("board", ["rect", "mask"])
@pytest.mark.parametrize("forge, listed", [
    (lambda cells: [-1, -1], "[-1, -1]"),
    (lambda cells: [5000, 5000], "[5000, 5000]"),
    (lambda cells: cells[1], "[0, 1]"),  # a duplicate of cell 1
])
def test_a_forged_cell_is_a_violation_at_its_place_and_is_not_drawn(files, board, forge, listed):
    folder, docs = files
    doc = copy.deepcopy(docs[board])
    doc["cells"][0] = forge(doc["cells"])
    lines = _violations(_verify_forged(folder, doc))
    assert f"(row 0, col 0) cell 0 is listed at {listed}; the board has it at [0, 0]" in lines
    pic = "forged.svg" if board == "rect" else "forged.png"
    err = one_line_error(run("draw", "forged.json", "-o", pic, cwd=folder))
    assert "not the board it describes" in err and "cell 0 is listed at" in err
    assert not (folder / pic).exists()


def test_moved_cells_are_reported_at_each_place(files):
    folder, docs = files
    doc = copy.deepcopy(docs["rect"])
    doc["cells"][61], doc["cells"][62] = doc["cells"][62], doc["cells"][61]  # two cells of row 1 swapped
    lines = _violations(_verify_forged(folder, doc))
    assert lines == ["(row 1, col 1) cell 61 is listed at [1, 2]; the board has it at [1, 1]",
                     "(row 1, col 2) cell 62 is listed at [1, 1]; the board has it at [1, 2]"]


def test_a_missing_or_extra_cell_is_a_violation(files):
    folder, docs = files
    doc = copy.deepcopy(docs["mask"])
    doc["cells"].append([2, 1])  # the hole at row 2, col 1
    lines = _violations(_verify_forged(folder, doc))
    assert "the file lists 16 cells; the board has 15" in lines


@pytest.mark.fast_cases(1)
@pytest.mark.parametrize("forge, expected", [
    # the first edge (leg N of cell [0, 0] on the wall, boundary leg 0) dropped
    (lambda e: e[1:], "the file does not list the edge where leg N of cell [0, 0] meets the wall (boundary leg 0)"),
    # listed twice
    (lambda e: e + [e[3]], "is listed twice"),
    # a join to another cell
    (lambda e: [[0, 2, 7, 0]] + e[1:], "edge 0 (cell 0 leg S, cell 7 leg N) is not an edge of the board"),
    # boundary legs renumbered
    (lambda e: [[0, 3, -1, 0]] + e[1:], "edge 0 (cell 0 leg W, the wall's boundary leg 0) is not an edge of the board"),
    # cells and legs that do not exist
    (lambda e: [[0, 7, -1, 0]] + e[1:], "names a cell, leg or boundary leg the board does not have"),
    (lambda e: [[0, 0, 5000, 1]] + e[1:], "names a cell, leg or boundary leg the board does not have"),
])
@pytest.mark.parametrize("board", ["rect", "mask"])
def test_forged_edges_are_violations(files, board, forge, expected):
    folder, docs = files
    doc = copy.deepcopy(docs[board])
    doc["edges"] = forge(doc["edges"])
    lines = _violations(_verify_forged(folder, doc))
    assert any(expected in ln for ln in lines), lines
    if board == "rect":
        assert "not the board it describes" in one_line_error(run("draw", "forged.json", "-o", "forged.svg",
                                                                 cwd=folder))


def test_edges_in_another_order_or_way_round_are_the_same_board(files):
    folder, docs = files
    doc = copy.deepcopy(docs["torus"])
    doc["edges"] = [[b, kb, a, ka] if b >= 0 else [a, ka, b, kb] for a, ka, b, kb in reversed(doc["edges"])]
    proc = _verify_forged(folder, doc)
    assert proc.returncode == 0 and proc.stdout.startswith("ok:"), proc.stdout + proc.stderr


def test_a_compact_file_that_lists_its_board_is_held_to_it(files):
    folder, docs = files
    from tilesolve.io.jsonio import encode_array
    from tilesolve.model.board import Board

    doc = copy.deepcopy(docs["big"])
    b = Board.rect(70, 70)
    cells = b.labels.copy()
    cells[4899] = [0, 0]
    edges = b.edge_array()  # legs N, E, S, W (0 = N, ..., 3 = W), as the file numbers them
    doc["cells"], doc["edges"] = encode_array(cells), encode_array(edges)
    lines = _violations(_verify_forged(folder, doc))
    assert lines == ["(row 69, col 69) cell 4899 is listed at [0, 0]; the board has it at [69, 69]"]


@pytest.mark.fast_cases(1)
@pytest.mark.parametrize("change, message", [
    (lambda d: d["grid"].update(wrap_cols="plain"), "a rect board has wrap_rows None and wrap_cols None"),
    (lambda d: d.update(board_kind="torus"), "a torus board has wrap_rows 'plain'"),
    (lambda d: d.update(board_kind="ring"), "not that of a ring board of 60x40: the ring board has no cell at [1, 1]"),
])
def test_a_description_that_contradicts_itself_is_refused(files, change, message):
    folder, docs = files
    doc = copy.deepcopy(docs["rect"])
    change(doc)
    assert message in one_line_error(_verify_forged(folder, doc))


def test_a_rect_kind_with_holes_is_refused(files):
    folder, docs = files
    doc = copy.deepcopy(docs["mask"])
    doc["board_kind"] = "rect"
    assert "not that of a rect board of 6x3" in one_line_error(_verify_forged(folder, doc))


@pytest.mark.fast_cases(1)
@pytest.mark.parametrize("name", ["rect", "big"])
def test_unknown_fields_are_refused(files, name):
    folder, docs = files
    doc = copy.deepcopy(docs[name])
    doc["shape"] = "anything"
    assert "unknown field 'shape'" in one_line_error(_verify_forged(folder, doc))


def _limited(args, cwd):
    """``tilesolve ARGS`` in a 1 GiB address space: a reader that allocates first fails."""
    def limit():
        import resource

        resource.setrlimit(resource.RLIMIT_AS, (1 << 30, 1 << 30))

    return subprocess.run([SCRIPT, *args], cwd=cwd, capture_output=True, text=True, env=ENV, timeout=300,
                          preexec_fn=limit, stdin=subprocess.DEVNULL)


@pytest.mark.fast_cases(1)
@pytest.mark.skipif(sys.platform != "linux", reason="address-space limits are set with Linux rlimits")
@pytest.mark.parametrize("name, change, message", [
    ("rect", lambda d: d.update(colors=10**9), "'colors' is 1000000000"),
    ("big", lambda d: d.update(colors=10**9), "'colors' is 1000000000"),
    ("rect", lambda d: d.update(colors=10**9, tileset=[[0, 1, 2, 1]]), "a list of tiles has 1 to 65536 colours"),
    ("big", lambda d: d["grid"].update(rows=10**9, cols=10**9), "'grid' is 1000000000x1000000000"),
    ("rect", lambda d: d["grid"].update(rows=10**9), "'grid' is 60x1000000000"),
    ("big", lambda d: d.update(mask={"dtype": "bits", "shape": [70, 70], "data": "AAAA"}), "'mask'"),
    ("big", lambda d: d.update(mask={"dtype": "bits", "shape": [10**9, 10**9], "data": ""}), "'mask'"),
    ("rect", lambda d: d.update(max_h=10**12), "'max_h' is 1000000000000"),
    ("rect", lambda d: d["boundary"].__setitem__(0, 2**70), "'boundary'"),
    ("rect", lambda d: d["tiles"].__setitem__(0, [2**70, 0, 0, 0]), "'tiles'"),
    ("rect", lambda d: d.update(leg_order=5), "leg_order 5"),
])
def test_absurd_sizes_and_colours_are_one_line_before_anything_is_built(files, name, change, message):
    folder, docs = files
    doc = copy.deepcopy(docs[name])
    change(doc)
    (folder / "absurd.json").write_text(json.dumps(doc))
    assert message in one_line_error(_limited(["verify", "absurd.json"], folder))


@pytest.mark.fast_cases(1)
@pytest.mark.skipif(sys.platform != "linux", reason="address-space limits are set with Linux rlimits")
@pytest.mark.parametrize("name", ["rect", "big"])
def test_absurd_colours_are_refused_by_every_reader_of_board_files(files, name):
    folder, docs = files
    doc = dict(docs[name], colors=10**9)
    (folder / "absurd.json").write_text(json.dumps(doc))
    for args in (["draw", "absurd.json", "-o", "absurd.png"], ["export", "dimacs", "absurd.json", "-o", "absurd.cnf"]):
        assert "'colors' is 1000000000" in one_line_error(_limited(args, folder))
        assert not (folder / args[-1]).exists()


def test_a_boundary_file_with_an_absurd_colour_is_one_line(tmp_path):
    (tmp_path / "b.json").write_text(json.dumps([2**70] + [0] * 11))
    err = one_line_error(run("brick", "solve", "--board", "rect:3x3", "--boundary", "b.json", cwd=tmp_path))
    assert "'boundary'" in err


@pytest.mark.slow
def test_a_file_written_before_grid_was_recorded_is_judged_by_the_grid_its_cells_span(files):
    folder, docs = files
    doc = copy.deepcopy(docs["mask"])
    del doc["grid"], doc["mask"]
    proc = _verify_forged(folder, doc)
    assert proc.returncode == 0 and "mask board, 15 cells in 6x3" in proc.stdout, proc.stdout + proc.stderr
    doc["cells"][0] = doc["cells"][1]  # the mask its cells span loses cell [0, 0]
    assert "the file lists 15 cells; the board has 14" in _violations(_verify_forged(folder, doc))
    rect = copy.deepcopy(docs["rect"])
    del rect["grid"], rect["mask"]
    rect["cells"][0] = [5000, 5000]
    assert "not that of a rect board of 5001x5001" in one_line_error(_verify_forged(folder, rect))


@pytest.mark.slow
def test_an_unsat_file_whose_list_is_not_its_board_is_refused(tmp_path):
    """Without a tiling no verifier judges the list, so the reader refuses it: the unsat claim
    is about the board described, never about the one listed."""
    (tmp_path / "t.json").write_text(json.dumps({"format": "tilesolve/wang-tileset", "version": 1, "colors": 4,
                                                 "tiles": [[0, 1, 2, 3]]}))
    proc = run("-q", "wang", "solve", "--tiles", "t.json", "--board", "rect:2x1", "--boundary", "free",
               "-o", "u.json", cwd=tmp_path)
    assert proc.returncode == 1, proc.stderr  # E and W of the one tile differ: unsat
    doc = json.loads((tmp_path / "u.json").read_text())
    assert doc["status"] == "unsat"
    doc["cells"][0] = [7, 7]
    (tmp_path / "f.json").write_text(json.dumps(doc))
    for args in (["verify", "f.json"], ["export", "dimacs", "f.json", "-o", "f.cnf"]):
        err = one_line_error(run(*args, cwd=tmp_path))
        assert "cells and edges are not the board it describes" in err and "cell 0 is listed at [7, 7]" in err


@pytest.mark.fast_cases(1)
@pytest.mark.parametrize("forge", [lambda t: t[:5], lambda t: [[10**12, 0, 0, 0]] + t[1:],
                                   lambda t: [[-5, 0, 0, 0]] + t[1:]])
def test_tiles_that_do_not_fit_the_board_are_violations_and_are_not_drawn(files, forge):
    folder, docs = files
    doc = copy.deepcopy(docs["rect"])
    doc["tiles"] = forge(doc["tiles"])
    first = _violations(_verify_forged(folder, doc))[0]
    assert first.startswith("tiling has shape (5, 4)") or "(row 0, col 0) leg N has colour" in first, first
    assert "tiles are not 4 colours in 0..2" in one_line_error(run("draw", "forged.json", "-o", "f.png", cwd=folder))
    assert not (folder / "f.png").exists()
