"""Tile-set importers (tilesolve.io.tileset_formats): the orders of other tools, format
detection, and one-line errors."""

from __future__ import annotations

import numpy as np
import pytest

from tilesolve.errors import InvalidProblem
from tilesolve.io.builtin_tilesets import load
from tilesolve.io.tileset_formats import detect_format, parse_tileset_text, read_tileset_file
from tilesolve.io.tileset_json import write_tileset


def _same(a, b) -> bool:
    return a.n_colors == b.n_colors and np.array_equal(a.tiles, b.tiles)


def _jr_lines(order: str, shift: int = 0) -> str:
    jr, _ = load("jeandel-rao")
    pos = {"nswe": (0, 2, 3, 1), "tilesat": (0, 1, 2, 3), "rtlb": (1, 0, 3, 2)}[order]
    return "\n".join(" ".join(str(t[i] + shift) for i in pos) for t in jr.tiles.tolist()) + "\n"


def test_nswe_file_is_the_builtin(tmp_path):
    p = tmp_path / "jr.tiles"
    p.write_text("# Jeandel-Rao, n s w e\n" + _jr_lines("nswe"))
    ts, notes = read_tileset_file(p)
    assert _same(ts, load("jeandel-rao")[0]) and notes == []


def test_tilesat_file_is_the_builtin(tmp_path):
    p = tmp_path / "jr11"
    p.write_text("11 5 20 20\n" + _jr_lines("tilesat", shift=1))
    assert detect_format(p, p.read_text()) == "tilesat"
    ts, _ = read_tileset_file(p)
    assert _same(ts, load("jeandel-rao")[0])


def test_rtlb_literal_and_lines_are_the_builtin(tmp_path):
    jr = load("jeandel-rao")[0]
    lines = _jr_lines("rtlb")
    literal = "tiles = [" + ", ".join("(" + ", ".join(row.split()) + ")" for row in lines.splitlines()) + "]\n"
    p = tmp_path / "jr.sage"
    p.write_text(literal)
    assert detect_format(p, literal) == "rtlb"
    assert _same(read_tileset_file(p)[0], jr)
    q = tmp_path / "jr.txt"
    q.write_text(lines)
    assert detect_format(q, lines) == "nswe"  # plain lines: nswe unless told
    assert _same(read_tileset_file(q, "rtlb")[0], jr)


def test_json_through_the_same_reader(tmp_path):
    jr = load("jeandel-rao")[0]
    p = tmp_path / "jr.json"
    write_tileset(p, jr)
    assert _same(read_tileset_file(p)[0], jr)
    assert _same(parse_tileset_text(p.read_text(), "json")[0], jr)


def test_orders_differ():
    a = parse_tileset_text("0 1 2 3\n", "nswe")[0].tiles.tolist()
    b = parse_tileset_text("0 1 2 3\n", "rtlb")[0].tiles.tolist()
    c = parse_tileset_text("1 4 1 1\n1 2 3 4\n", "tilesat")[0]
    assert a == [[0, 3, 1, 2]] and b == [[1, 0, 3, 2]] and c.tiles.tolist() == [[0, 1, 2, 3]]


def test_duplicates_dropped_with_a_note():
    ts, notes = parse_tileset_text("0 1 0 1\n0 1 0 1\n1 0 1 0\n", "nswe", "d.tiles")
    assert len(ts) == 2 and notes == ["d.tiles: 1 duplicate tile(s) dropped"]


@pytest.mark.parametrize("text,fmt,message", [
    ("0 1 2\n", "nswe", "line 1: a tile needs 4 colours (north south west east), got 3"),
    ("0 1 2 3\n0 1 x 3\n", "nswe", "line 2: colour 'x' is not an integer"),
    ("0 1 2.5 3\n", "nswe", "colour '2.5' is not an integer"),
    ("0 1 -2 3\n", "nswe", "colour -2 is negative"),
    ("# only a comment\n", "nswe", "the tile set is empty"),
    ("", "rtlb", "the tile set is empty"),
    ("[(0, 1, 2)]", "rtlb", "a tile needs 4 colours (right top left bottom), got 3"),
    ("2 3 5 5\n1 2 3 4\n1 1 1 1\n", "tilesat", "line 2: colour 4 is outside 1..3"),
    ("2 3 5 5\n1 2 3 3\n", "tilesat", "header announces 2 tiles, the file has 1"),
    ("2 3 5\n1 2 3 3\n", "tilesat", "the TileSAT header must be 4 integers"),
    ("", "tilesat", "empty file"),
    ("{", "json", "malformed JSON"),
    ("0 1 2 3\n", "svg", "unknown tile-set format 'svg'"),
])
def test_one_line_errors(text, fmt, message):
    with pytest.raises(InvalidProblem) as exc:
        parse_tileset_text(text, fmt, "f")
    assert message in str(exc.value) and "\n" not in str(exc.value)
