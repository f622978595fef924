"""Compact tile sets (class notes §3.2-3.3) and the `tilesolve tiles` command."""

from __future__ import annotations

import itertools
import xml.etree.ElementTree as ET
from collections import Counter

import numpy as np
import pytest
from click.testing import CliRunner
from hypothesis import given, strategies as st

from tilesolve.cli.main import main_group
from tilesolve.errors import InvalidProblem
from tilesolve.io.svg_tileset import tileset_svg_string
from tilesolve.model.tiles import TileSet, corner_colors, wang_colors, wang_index

SVG = "{http://www.w3.org/2000/svg}"
colours = st.integers(min_value=2, max_value=8)


def compact(kind: str, c: int) -> TileSet:
    return TileSet(kind, c, variant="compact")


# ----------------------------------------------------------------------------- published numbers
def test_published_compact_wang_set_over_two_colours():
    # §3.2.1, Fig. 3.2 and the slides: "0 3 5 6 9 10 12 15 a compact Wang tile set over 2 colors"
    assert compact("wang", 2).indices.tolist() == [0, 3, 5, 6, 9, 10, 12, 15]


def test_compact_corner_set_over_two_colours_is_the_complete_set():
    # §3.2.2: "the complete corner tile set over two colors and the compact corner tile set
    # over two colors are identical"
    assert compact("corner", 2).indices.tolist() == TileSet("corner", 2).indices.tolist() == list(range(16))


def test_sizes_match_the_notes_table():
    # §3.2.1 and §3.2.2 list the sizes for C = 2..8. Our copy of the notes lost the C = 6 entry
    # (72 = 2 * 6**2) of the Wang list: "8, 18, 32, 50, 98, 128"; it is put back here.
    wang = [8, 18, 32, 50, 72, 98, 128]
    corner = [16, 54, 128, 250, 432, 686, 1024]
    for c, w, k in zip(range(2, 9), wang, corner):
        assert compact("wang", c).n_tiles == len(compact("wang", c).indices) == w
        assert compact("corner", c).n_tiles == len(compact("corner", c).indices) == k


# ----------------------------------------------------------------------------- the defining properties
@given(colours)
def test_compact_wang_has_two_tiles_per_north_west(c):
    n, e, s, w = wang_colors(np.array(compact("wang", c).indices), colors=c)
    assert Counter(zip(n.tolist(), w.tolist())) == {nw: 2 for nw in itertools.product(range(c), repeat=2)}
    # the two tiles of each (N, W) differ in E and in S: a scanline tiling always has two choices
    assert len(set(zip(n.tolist(), w.tolist(), e.tolist()))) == len(set(zip(n.tolist(), w.tolist(), s.tolist()))) == 2 * c * c


@given(colours)
def test_compact_wang_follows_tilesolves_rule(c):
    n, e, s, w = wang_colors(np.array(compact("wang", c).indices), colors=c)
    k = (e - n) % c
    assert np.all((k == 0) | (k == 1))
    assert np.all(s == (w + k) % c)


@given(colours)
def test_compact_corner_has_two_tiles_per_ne_nw_sw(c):
    ne, se, sw, nw = corner_colors(np.array(compact("corner", c).indices), colors=c)
    keys = list(zip(ne.tolist(), nw.tolist(), sw.tolist()))
    assert Counter(keys) == {k: 2 for k in itertools.product(range(c), repeat=3)}
    x = (ne + nw + sw) % c
    assert np.all((se == x) | (se == (x + 1) % c))


@pytest.mark.parametrize("c", range(2, 7))
def test_sums_set_is_every_corner_colouring_summed(c):
    # §3.3.2.2, straight from the definition over all C**4 corner colourings
    got = set()
    for ne, se, sw, nw in itertools.product(range(c), repeat=4):
        got.add(int(wang_index((nw + ne) % c, (ne + se) % c, (se + sw) % c, (sw + nw) % c, colors=c)))
    ts = TileSet("wang", c, variant="sums")
    assert ts.indices.tolist() == sorted(got)
    assert ts.n_tiles == len(got) == c**3  # "a compact set of C^3 Wang tiles over C colors"
    n, e, s, w = ts.table().T
    assert np.all((n + s - e - w) % c == 0)


def test_sums_set_equals_the_scanline_compact_set_only_for_two_colours():
    # §3.3.2.2: "except for two colors, these compact Wang tile sets are different"
    assert TileSet("wang", 2, variant="sums").indices.tolist() == compact("wang", 2).indices.tolist()
    for c in range(3, 6):
        assert TileSet("wang", c, variant="sums").indices.tolist() != compact("wang", c).indices.tolist()


def test_table_lists_the_tiles_of_the_set():
    ts = compact("corner", 3)
    tab = ts.table()
    assert tab.shape == (54, 4)
    assert ts.index(*tab.T).tolist() == ts.indices.tolist()
    assert ts.wang_images().shape == (54,)
    assert not ts.indices.flags.writeable


def test_complete_set_is_the_default_and_unchanged():
    ts = TileSet("wang", 3)
    assert ts.variant == "complete" and ts == TileSet("wang", 3, variant="complete")
    assert ts.indices.tolist() == list(range(81))
    assert "complete" in ts.describe() and "compact" in compact("wang", 3).describe()


@pytest.mark.parametrize("kwargs,words", [
    (dict(kind="corner", colors=3, variant="sums"), "only for Wang"),
    (dict(kind="wang", colors=2, colors_v=3, variant="compact"), "complete Wang"),
    (dict(kind="wang", colors=3, variant="minimal"), "unknown tile set"),
    (dict(kind="wang", colors=1, variant="compact"), "at least 2"),
])
def test_invalid_combinations_are_rejected(kwargs, words):
    with pytest.raises(InvalidProblem, match=words) as info:
        TileSet(**kwargs)
    assert "\n" not in str(info.value)


# ----------------------------------------------------------------------------- CLI and SVG
def invoke(*args: str):
    return CliRunner().invoke(main_group, list(args))


@pytest.mark.parametrize("args,expected", [
    (("--kind", "wang", "--colors", "2", "--set", "compact"), "0 3 5 6 9 10 12 15"),
    (("--kind", "corner", "--colors", "2", "--set", "compact"), " ".join(map(str, range(16)))),
    (("--kind", "wang", "--colors", "2", "--set", "sums"), "0 3 5 6 9 10 12 15"),
    (("--kind", "wang", "--colors", "2"), " ".join(map(str, range(16)))),
])
def test_cli_prints_the_indices_on_the_last_line(args, expected):
    result = invoke("tiles", *args)
    assert result.exit_code == 0, result.output
    assert result.stdout.strip().splitlines()[-1] == expected


def test_cli_compact_corner_three_colours():
    result = invoke("tiles", "--kind", "corner", "--colors", "3", "--set", "compact")
    assert result.exit_code == 0
    assert result.stdout.split() == [str(i) for i in compact("corner", 3).indices.tolist()]
    assert "54 tiles" in result.stderr


@pytest.mark.parametrize("args,words", [
    (("--kind", "wang", "--colors", "1"), "--colors must be at least 2"),
    (("--kind", "wang", "--colors", "0", "--set", "compact"), "--colors must be at least 2"),
    (("--kind", "corner", "--colors", "3", "--set", "sums"), "only for Wang"),
])
def test_cli_bad_input_is_one_line_and_exit_2(tmp_path, args, words):
    result = invoke("tiles", *args, "--svg", str(tmp_path / "t.svg"))
    assert result.exit_code == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("tilesolve: error: ") and words in lines[0]
    assert result.stdout == "" and not (tmp_path / "t.svg").exists()


def test_cli_unknown_set_is_a_usage_error():
    result = invoke("tiles", "--kind", "wang", "--colors", "3", "--set", "minimal")
    assert result.exit_code == 2 and "--set" in result.stderr and result.stdout == ""


def test_cli_missing_directory_for_svg(tmp_path):
    result = invoke("tiles", "--kind", "wang", "--colors", "2", "--svg", str(tmp_path / "no" / "t.svg"))
    assert result.exit_code == 2 and "does not exist" in result.stderr


def test_cli_help_lists_the_sets():
    result = invoke("tiles", "--help")
    assert result.exit_code == 0
    for word in ("--kind", "--colors", "--set", "compact", "sums", "§3.2.1", "Exit codes"):
        assert word in result.stdout
    assert "tiles" in invoke("--help").stdout


@pytest.mark.parametrize("kind,variant,c", [("wang", "compact", 2), ("corner", "compact", 3), ("wang", "sums", 3)])
def test_cli_writes_a_parseable_svg(tmp_path, kind, variant, c):
    out = tmp_path / "t.svg"
    result = invoke("tiles", "--kind", kind, "--colors", str(c), "--set", variant, "--svg", str(out))
    assert result.exit_code == 0, result.output
    root = ET.parse(out).getroot()
    assert root.tag == f"{SVG}svg"
    ts = TileSet(kind, c, variant=variant)
    assert len(root.findall(f".//{SVG}polygon")) == 4 * ts.n_tiles
    assert len(root.findall(f".//{SVG}rect")) == ts.n_tiles + 1  # and the background
    labels = [t.text for t in root.iter(f"{SVG}text")][1:]  # the first text is the title
    assert labels == [str(i) for i in ts.indices.tolist()]
    assert [p.name for p in tmp_path.iterdir()] == ["t.svg"]  # no temporary file left


def test_svg_colours_follow_the_tiles():
    from tilesolve.io.svg_packing import colour_of

    ts = compact("wang", 2)
    root = ET.fromstring(tileset_svg_string(ts, labels=False, title=""))
    fills = [p.get("fill") for p in root.iter(f"{SVG}polygon")]
    assert fills == [colour_of(k) for row in ts.table().tolist() for k in row]
    assert root.find(f".//{SVG}text") is None


@given(colours)
def test_compact_wang_uses_every_colour_on_every_edge(c):
    sides = wang_colors(np.array(compact("wang", c).indices), colors=c)
    for side in sides:
        assert set(side.tolist()) == set(range(c))
