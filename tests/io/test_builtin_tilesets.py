"""Built-in tile sets: every file loads, carries its source and verdict, and where a second
public source lists the same set, both transcriptions are isomorphic tile sets."""

from __future__ import annotations

import networkx as nx
import numpy as np
import pytest
from networkx.algorithms.isomorphism import DiGraphMatcher

from tilesolve.errors import InvalidProblem
from tilesolve.io.builtin_tilesets import VERDICTS, load, names

# a source's order -> the positions of N, E, S, W in its tuples
_ORDERS = {"n s w e": (0, 3, 1, 2), "right top left bottom": (1, 0, 3, 2), "north east south west": (0, 1, 2, 3)}


def _nesw(raw, order: str, turned: int = 0) -> list[tuple]:
    """A source's tiles as N, E, S, W tuples; ``turned``: the source draws the set rotated
    by that many degrees clockwise (its N side is our E side for 90)."""
    idx = _ORDERS[order]
    k = turned // 90
    return [tuple(str(t[idx[(i - k) % 4]]) for i in range(4)) for t in raw]


def _graph(tiles) -> nx.DiGraph:
    """Tiles and colours as a graph: tile -> colour edges labelled by the sides that carry it;
    horizontal-edge colours (N/S) and vertical-edge colours (E/W) are separate node kinds, so
    an isomorphism relabels the colours of each axis on its own."""
    g = nx.DiGraph()
    for i, t in enumerate(tiles):
        g.add_node(("t", i), kind="tile")
        for side, axis, colour in zip("NESW", "hvhv", t):
            node = (axis, str(colour))
            g.add_node(node, kind=axis)
            sides = g.edges[("t", i), node]["sides"] if g.has_edge(("t", i), node) else ""
            g.add_edge(("t", i), node, sides="".join(sorted(sides + side)))
    return g


def isomorphic(a, b) -> bool:
    """Are two tile sets (lists of N, E, S, W tuples) the same up to tile order and a
    relabelling of colours per axis?"""
    if len(set(a)) != len(set(b)):
        return False
    return DiGraphMatcher(_graph(sorted(set(a))), _graph(sorted(set(b))),
                          node_match=lambda x, y: x["kind"] == y["kind"],
                          edge_match=lambda x, y: x["sides"] == y["sides"]).is_isomorphic()


def test_isomorphism_test_can_fail():
    jr, _ = load("jeandel-rao")
    tiles = [tuple(t) for t in jr.tiles.tolist()]
    rotated = [(w, n, e, s) for n, e, s, w in tiles]  # N moved to E: not a relabelling
    relabelled = [(4 - n, (e + 1) % 4 if e < 4 else e, 4 - s, (w + 1) % 4 if w < 4 else w) for n, e, s, w in tiles]
    assert isomorphic(tiles, relabelled[::-1])
    assert not isomorphic(tiles, rotated)
    broken = list(tiles)
    broken[0] = (broken[0][0], broken[0][1], broken[0][2], (broken[0][3] + 1) % 4)
    assert not isomorphic(tiles, broken)


def test_names_and_info():
    got = names()
    for must in ("jeandel-rao", "jeandel-rao-4", "jeandel-rao-fig10", "kari-culik-13", "kari-14",
                 "ammann-16", "labbe-u19"):
        assert must in got
    assert any(n.startswith("finite-") for n in got) and any(n.startswith("periodic-") for n in got)
    for name in got:
        ts, info = load(name)
        assert info["verdict"] in VERDICTS
        assert info["n_tiles"] == len(ts) and info["title"] and info["reference"]
        src = info["sources"][0]
        assert src["repo"] and src["path"] and len(src["commit"]) == 40
        if info["verdict"] == "periodic":
            assert info["period"] >= 1


@pytest.mark.parametrize("name,n_tiles,h_colors,v_colors", [
    ("jeandel-rao", 11, 5, 4), ("jeandel-rao-4", 11, 4, 4), ("kari-culik-13", 13, 4, 5),
    ("kari-14", 14, 3, 6), ("ammann-16", 16, 6, 6), ("labbe-u19", 19, 6, 10),
])
def test_sizes_from_the_literature(name, n_tiles, h_colors, v_colors):
    ts, _ = load(name)
    t = ts.tiles
    assert len(ts) == n_tiles
    assert np.unique(t[:, [0, 2]]).size == h_colors and np.unique(t[:, [1, 3]]).size == v_colors


def test_turning_is_a_rotation():
    assert _nesw([("a", "b", "c", "d")], "north east south west", 90) == [("d", "a", "b", "c")]
    assert _nesw([("a", "b", "c", "d")], "north east south west", 180) == [("c", "d", "a", "b")]


def test_second_sources_agree():
    checked = 0
    for name in names():
        ts, info = load(name)
        ours = [tuple(map(str, t)) for t in ts.tiles.tolist()]
        for src in info["sources"][1:]:
            assert isomorphic(ours, _nesw(src["tiles"], src["order"], src.get("turned", 0))), (name, src["path"])
            checked += 1
    assert checked >= 5


def test_first_sources_are_the_test_data_copies_of_the_cited_files():
    """The meyerphi/tiling files the built-in sets cite are kept in tests/data/transducer: each
    set is its cited file's tiles, in the file's order and colours."""
    from pathlib import Path

    from tilesolve.io.tileset_formats import read_tileset_file

    copies = Path(__file__).resolve().parents[1] / "data" / "transducer"
    checked = 0
    for name in names():
        ts, info = load(name)
        src = info["sources"][0]
        assert (src["repo"], src["order"]) == ("meyerphi/tiling", "n s w e") and src["path"].startswith("tilesets/")
        copy, _ = read_tileset_file(copies / src["path"].removeprefix("tilesets/"), "nswe")
        assert np.array_equal(copy.tiles, ts.tiles) and copy.n_colors == ts.n_colors, name
        checked += 1
    assert checked == len(names())


def test_tiles_quoted_from_a_program_name_their_lines():
    """A source file that holds more than the tiles (a program; its tiles are recorded) names
    the lines that hold them, so the citation can be checked by eye: jeandel-rao once cited a
    file of slabbe's that holds a polygon partition and no tile list."""
    quoted = 0
    for name in names():
        for src in load(name)[1]["sources"]:
            if src["path"].endswith(".py"):
                first, last = map(int, src["lines"].split("-"))
                assert src["tiles"] and 1 <= first <= last < first + len(src["tiles"]), (name, src["path"])
                quoted += 1
    assert quoted == 3
    jr = load("jeandel-rao")[1]["sources"]
    assert [s["path"] for s in jr[1:]] == ["slabbe/jeandel_rao.py", "slabbe/wang_tiles.py"]


def test_unknown_name():
    with pytest.raises(InvalidProblem, match="no built-in tile set 'nope'"):
        load("nope")
