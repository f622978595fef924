"""The Markov-partition codings of Jeandel-Rao and U19 (tilesolve/constructive/markov.py).

Every window is checked against the built-in tile set's colours directly (numpy, nothing shared
with the coding); the labels of the transcribed partitions are checked against slabbe's tile
lists kept in the data files; the float path is checked against the exact path cell by cell.
"""

from __future__ import annotations

import json
import math
from decimal import Decimal, getcontext
from fractions import Fraction
from importlib import resources

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from tilesolve.constructive import markov
from tilesolve.constructive._markov_kernels import KERNELS
from tilesolve.constructive.markov import NAMES, QPhi, markov_window, orbit_window, partition
from tilesolve.errors import InvalidProblem
from tilesolve.model.window import Window

DATA = resources.files("tilesolve") / "data"
PHI = QPhi(0, 1)


def tileset(name: str) -> tuple[dict, np.ndarray]:
    """The built-in tile set file and its tiles as an ``(n, 4)`` array in N, E, S, W order."""
    doc = json.loads((DATA / "tilesets" / f"{name}.json").read_text(encoding="utf-8"))
    cols = [doc["order"].index(side) for side in "NESW"]
    return doc, np.array(doc["tiles"])[:, cols]


def markov_doc(name: str) -> dict:
    return json.loads((DATA / "markov" / f"{name}.json").read_text(encoding="utf-8"))


def mismatches(name: str, grid: np.ndarray) -> int:
    """Edges of ``grid`` (row 0 at the top) whose two colours differ."""
    t = tileset(name)[1][grid]
    return int((t[:, :-1, 1] != t[:, 1:, 3]).sum() + (t[:-1, :, 2] != t[1:, :, 0]).sum())


# --------------------------------------------------------------------------- the data
def test_jeandel_rao_labels_are_slabbes_tiles():
    doc, tiles = tileset("jeandel-rao")
    src = next(s for s in doc["about"]["sources"] if s["path"] == "slabbe/jeandel_rao.py")
    assert src["order"] == "right top left bottom"
    tile_of = markov_doc("jeandel-rao")["tile_of_label"]
    assert sorted(tile_of) == list(range(11))
    for label, (right, top, left, bottom) in enumerate(src["tiles"]):
        assert tiles[tile_of[label]].tolist() == [int(top), int(right), int(bottom), int(left)]


def test_u19_labels_are_labbes_tiles_up_to_colour_names():
    doc = markov_doc("labbe-u19")
    _, tiles = tileset("labbe-u19")
    slabbe = doc["about"]["slabbe_tiles"]
    assert slabbe["order"] == "right top left bottom"
    tile_of = doc["tile_of_label"]
    assert sorted(tile_of) == list(range(19))
    vertical, horizontal = {}, {}
    for label, (right, top, left, bottom) in enumerate(slabbe["tiles"]):
        n, e, s, w = tiles[tile_of[label]].tolist()
        for names, letter, colour in ((horizontal, top, n), (horizontal, bottom, s),
                                      (vertical, right, e), (vertical, left, w)):
            assert names.setdefault(letter, colour) == colour
    for names in (vertical, horizontal):  # a bijection on each axis
        assert len(set(names.values())) == len(names)


@pytest.mark.parametrize("name, area", [("jeandel-rao", 4 * PHI + 1), ("labbe-u19", QPhi(1))])
def test_polygons_fill_the_fundamental_domain(name, area):
    part = partition(name)
    assert part.lx * part.ly == area  # the covolume of the lattice
    total = QPhi(0)
    for _, vs, _ in part.atoms:
        for a, b in zip(vs, vs[1:] + vs[:1]):
            total = total + (a[0] * b[1] - a[1] * b[0]) * Fraction(1, 2)
    assert total == area
    assert len(part.atoms) == {"jeandel-rao": 24, "labbe-u19": 19}[name]


def test_unknown_partition_is_refused():
    with pytest.raises(InvalidProblem, match="no Markov partition"):
        markov_window("kari-14", Window(0, 0, 2, 2), 1)


# --------------------------------------------------------------------------- Q(phi)
getcontext().prec = 200
SQRT5 = Decimal(5).sqrt()


def decimal(q: QPhi) -> Decimal:
    dec = lambda f: Decimal(f.numerator) / Decimal(f.denominator)  # noqa: E731
    return dec(q.a) + dec(q.b) * (1 + SQRT5) / 2


big = st.fractions(max_denominator=1 << 40) | st.integers(-(1 << 70), 1 << 70).map(Fraction)


@settings(max_examples=100, deadline=None)
@given(big, big)
def test_qphi_sign_floor_float_are_exact(a, b):
    q = QPhi(a, b)
    d = decimal(q)
    assert q.sign() == (d > 0) - (d < 0)
    assert q.floor() == math.floor(d)
    assert abs(Decimal(float(q)) - d) <= abs(d) * Decimal(2) ** -52 + Decimal(2) ** -63


def test_qphi_arithmetic():
    assert PHI * PHI == PHI + 1
    assert (1 / PHI) == PHI - 1
    assert (PHI + 3) * ((4 - PHI) / 11) == 1
    assert (2 - PHI) < (PHI - 1) < 1 < PHI


# --------------------------------------------------------------------------- the windows
ORIGINS = [(0, 0), (-37, 12), (-1_000_003, -999_983), (2**61 + 5, -(2**61) - 17), (2**62 - 30, 2**62 - 20)]


@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize("origin", ORIGINS)
@pytest.mark.parametrize("seed", [0, 1, 123456789])
def test_windows_are_valid_tilings(name, origin, seed):
    grid = markov_window(name, Window(*origin, 30, 20), seed)
    assert grid.shape == (20, 30) and grid.dtype == np.uint8
    assert int(grid.max()) < len(tileset(name)[1])
    assert mismatches(name, grid) == 0


@pytest.mark.parametrize("name", NAMES)
def test_every_tile_occurs(name):
    grid = markov_window(name, Window(-60, -60, 120, 120), 5)
    assert set(np.unique(grid).tolist()) == set(range(len(tileset(name)[1])))


@pytest.mark.parametrize("name", NAMES)
def test_windows_agree_where_they_overlap(name):
    a = markov_window(name, Window(-10, -7, 30, 25), 42)
    b = markov_window(name, Window(5, 3, 30, 25), 42)
    # overlap x 5..19, y 3..17: a's row r holds y = 17 - r, column c x = c - 10;
    # b's row r holds y = 27 - r, column c x = c + 5
    assert np.array_equal(a[0:15, 15:30], b[10:25, 0:15])
    assert not np.array_equal(markov_window(name, Window(-10, -7, 30, 25), 43), a)


@pytest.mark.parametrize("name", NAMES)
def test_blocks_agree_with_one_block(name, monkeypatch):
    window = Window(-13, 8, 23, 17)
    whole = markov_window(name, window, 9)
    monkeypatch.setattr(markov, "BLOCK", 5)
    assert np.array_equal(markov_window(name, window, 9), whole)


@pytest.mark.parametrize("name", NAMES)
def test_y_down_window_is_the_y_up_window_upside_down(name):
    up = markov_window(name, Window(3, -4, 9, 7), 2)
    down = markov_window(name, Window(3, -4, 9, 7, y_up=False), 2)
    assert np.array_equal(down, up[::-1])


@pytest.mark.parametrize("name", NAMES)
def test_float_path_agrees_with_exact_path(name):
    window = Window(-6, 11, 14, 12)
    start = markov.start_point(name, 77)
    part = partition(name)
    grid = orbit_window(name, window, start)
    for r in range(window.height):
        for c in range(window.width):
            x, y = window.cell(r, c)
            assert grid[r, c] == part.label_at(start[0] + x * part.hx, start[1] + y * part.hy)


@pytest.mark.slow
@pytest.mark.parametrize("name", NAMES)
def test_float_path_agrees_with_exact_path_across_blocks(name):
    """Full-size blocks, where the float error is largest (a 4500 x 4300 window)."""
    window = Window(-(2**50) - 4000, 2**55 + 17, 4500, 4300)  # two blocks each way
    grid = markov_window(name, window, 8)
    start = markov.start_point(name, 8)
    part = partition(name)
    rng = np.random.default_rng(0)
    edges = [0, 1, 4095, 4096, 4097]
    cells = [(r, c) for r in edges + [4299] for c in edges + [4499]] + list(zip(rng.integers(0, 4300, 100),
                                                                          rng.integers(0, 4500, 100)))
    for r, c in cells:
        x, y = window.cell(int(r), int(c))
        assert grid[r, c] == part.label_at(start[0] + x * part.hx, start[1] + y * part.hy)
    assert mismatches(name, grid[4090:4102, 4090:4102]) == 0


@pytest.mark.parametrize("name", NAMES)
def test_plain_and_compiled_kernels_agree(name, monkeypatch):
    out = {}
    for mode in ("plain", "compiled"):
        monkeypatch.setattr(KERNELS, "mode", mode)
        out[mode] = markov_window(name, Window(-40, 25, 50, 40), 3)
    assert np.array_equal(out["plain"], out["compiled"])


# --------------------------------------------------------------------------- points on edges
def edge_points(name):
    """A vertex and the midpoint of an edge of each kind (vertical, horizontal, slanted)."""
    part = partition(name)
    found = {}
    for _, vs, _ in part.atoms:
        for a, b in zip(vs, vs[1:] + vs[:1]):
            kind = "vertical" if a[0] == b[0] else "horizontal" if a[1] == b[1] else "slanted"
            found.setdefault(kind, ((a[0] + b[0]) * Fraction(1, 2), (a[1] + b[1]) * Fraction(1, 2)))
            found.setdefault("vertex", a)
    return found


@pytest.mark.parametrize("name", NAMES)
def test_orbits_through_edges_and_vertices_are_valid(name, monkeypatch):
    part = partition(name)
    calls = []
    exact = type(part).label_at
    monkeypatch.setattr(type(part), "label_at", lambda self, x, y: calls.append(1) or exact(self, x, y))
    for kind, start in edge_points(name).items():
        calls.clear()
        grid = orbit_window(name, Window(-4, -3, 12, 10), start)
        assert calls, f"{kind}: the exact path was not taken"
        assert mismatches(name, grid) == 0, kind


@pytest.mark.parametrize("name", NAMES)
def test_a_point_on_an_edge_takes_the_label_of_its_infinitesimal_move(name):
    part = partition(name)
    vx, vy = markov.PERTURBATION
    delta = Fraction(1, 10**12)
    for start in edge_points(name).values():
        for n in range(-3, 4):
            x, y = start[0] + n * part.hx, start[1] - n * part.hy
            assert part.label_at(x, y) == part.label_at(x + delta * vx, y + delta * vy)


def test_origins_beyond_the_window_lattice_are_refused():
    with pytest.raises(InvalidProblem, match="2\\*\\*62"):
        markov_window("jeandel-rao", Window(2**62 - 2, 0, 4, 4), 1)


# --------------------------------------------------------------------------- the GPU tables
@pytest.mark.parametrize("name", NAMES)
def test_cell_point_codes_like_the_window(name):
    part = markov.partition(name)
    lx, sx, ly, hx, hy = (float(v) for v in (part.lx, part.sx, part.ly, part.hx, part.hy))
    window = Window(2**40 + 3, -(2**45), 16, 12)
    grid = markov_window(name, window, 11)
    ax, ay = markov.cell_point(name, 11, window.x0, window.y0)
    compared = 0
    for r in range(window.height):
        for c in range(window.width):
            x, y = window.cell(r, c)
            px, py = ax + (x - window.x0) * hx, ay + (y - window.y0) * hy
            ell = math.floor(py / ly)
            py, px = py - ell * ly, px - ell * sx
            px -= math.floor(px / lx) * lx
            clear = []
            for tile, atom, _ in part.atoms:
                vs = np.array([[float(x), float(y)] for x, y in atom])
                d = np.roll(vs, -1, axis=0) - vs
                cross = d[:, 0] * (py - vs[:, 1]) - d[:, 1] * (px - vs[:, 0])
                if (cross > 1e-5).all():
                    clear.append(tile)
            if clear:
                compared += 1
                assert clear == [grid[r, c]]
    assert compared >= 0.9 * grid.size
