"""Kari's and Culik's tilings from balanced sequences (Kari 1996, Culik 1996; issue 20 §1):
the tiles are the machine's transitions, every window tiles, windows of a seed agree, the fast
path equals the exact cell-by-cell reference."""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest

from tilesolve.constructive import _balanced_kernels as K
from tilesolve.constructive import balanced as B
from tilesolve.errors import InvalidProblem
from tilesolve.io.builtin_tilesets import load
from tilesolve.model.window import Window

NAMES = list(B.NAMES)
#: (window, seed): near the origin, negative, far columns either way, far rows either way.
WINDOWS = [
    (Window(0, 0, 30, 20), 1),
    (Window(-17, -40, 25, 30), 2),
    (Window(2**61, -5, 20, 12), 3),
    (Window(-(2**62) + 5, 100, 20, 12), 4),
    (Window(3, 5000, 15, 5), 5),
    (Window(-9, -3000, 15, 5), 6),
]
#: Windows at the rows farthest from the seed's row (a few seconds each).
FAR = [(Window(-7, B.MAX_EXACT_ROW - 4, 12, 4), 7), (Window(2**62 - 20, -B.MAX_EXACT_ROW + 1, 12, 4), 8)]


def tiles_of(name):
    return np.asarray(load(name)[0].tiles)


def violations(name, grid):
    """Cells whose E edge differs from the W edge of the right neighbour, or whose S edge
    differs from the N edge of the cell below (N, E, S, W colours of the built-in file)."""
    t = tiles_of(name)[grid]
    return int((t[:, :-1, 1] != t[:, 1:, 3]).sum() + (t[:-1, :, 2] != t[1:, :, 0]).sum())


def digits(x, j0, n):
    """The balanced digits ``floor((j + 1) x) - floor(j x)``, ``j = j0 .. j0 + n - 1``."""
    return [math.floor((j + 1) * x) - math.floor(j * x) for j in range(j0, j0 + n)]


# --------------------------------------------------------------------------- the machines
@pytest.mark.parametrize("name", NAMES)
def test_tiles_are_the_machine_transitions(name):
    """The tiles rebuilt from the transitions are the built-in file's, in its order."""
    assert B.tile_colours(name) == tiles_of(name).tolist()


@pytest.mark.parametrize("name", NAMES)
def test_transitions_multiply(name):
    """Each tile is ``p a + s = r b + t`` with carries in ``1 - p .. r - 1``, and the tiles are
    every such transition whose digits a row of that kind reads and writes."""
    m = B.machine(name)
    lo = Fraction(2, m.jump)

    def span(a, b):  # the digits of the reals in (a, b]
        return set(range(math.floor(a), math.ceil(b) + 1))

    reads = (span(lo, 1), span(1, 2))
    writes = (span(2 * lo, 2), span(2 * lo / 2, 4 / Fraction(m.jump)))
    seen = set()
    for i in range(len(m.tiles)):
        kind, primed, a, b, s, t = m.transition(i)
        p, r = m.steps[kind]
        assert p * a + s == r * b + t
        assert s in m.carries(kind) and t in m.carries(kind)
        assert a in reads[kind] and b in writes[kind]
        seen.add((kind, primed, a, b, s))
    for kind in (0, 1):
        p, r = m.steps[kind]
        assert Fraction(p, r) == (2 if kind == 0 else Fraction(2, m.jump))
        for a in reads[kind]:
            for b in writes[kind]:
                for s in m.carries(kind):
                    if s + p * a - r * b in m.carries(kind):
                        assert (kind, 0, a, b, s) in seen
    primed = sorted(t for t in seen if t[1])
    # Culik: the one tile that reads a 0 written by a kind-0 row turns it into a 1
    assert primed == ([] if m.primed_colour is None else [(0, 1, 0, 1, 0)])


@pytest.mark.parametrize("name", NAMES)
def test_carry_colours_keep_kinds_apart(name):
    """The E/W colours of the two kinds are disjoint: a row is all of one kind."""
    m = B.machine(name)
    c0, c1 = set(m.carry_colours[0].values()), set(m.carry_colours[1].values())
    assert not c0 & c1


@pytest.mark.parametrize("name", NAMES)
def test_rows_run_down_the_orbit(name):
    """Row y carries x(y) in (2/J, 2] on its N edges and f(x(y)) = x(y - 1) on its S edges."""
    m = B.machine(name)
    start = B._start(m, 12)
    w = Window(-6, -4, 10, 8)
    grid = B.balanced_window(name, w, 12)
    t = tiles_of(name)[grid]
    for row in range(w.height):
        y = w.cell(row, 0)[1]
        x, below = Fraction(*B._row_value(m, start, y)), Fraction(*B._row_value(m, start, y - 1))
        assert Fraction(2, m.jump) < x <= 2
        assert below == (2 * x if x <= 1 else 2 * x / m.jump)
        north = [0 if c == m.primed_colour else c for c in t[row, :, 0]]
        south = [0 if c == m.primed_colour else c for c in t[row, :, 2]]
        assert north == digits(x, w.x0, w.width) and south == digits(below, w.x0, w.width)


@pytest.mark.parametrize("y", [-B.MAX_EXACT_ROW + 1, -77777, 54321, B.MAX_EXACT_ROW])
def test_closed_form_far_rows(y):
    """x(y) stays in (2/J, 2] and follows f far from the seed row, both ways (exact integer
    comparisons: a Fraction of a million bits costs a slow gcd)."""
    for name in NAMES:
        m = B.machine(name)
        start = B._start(m, 3)
        (P, Q), (Pb, Qb) = B._row_value(m, start, y), B._row_value(m, start, y - 1)
        assert 2 * Q < m.jump * P and P <= 2 * Q
        p, r = m.steps[int(P > Q)]
        assert Pb * Q * r == P * Qb * p


# --------------------------------------------------------------------------- windows
@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize("window,seed", WINDOWS, ids=[w.describe() for w, _ in WINDOWS])
def test_window_tiles_and_equals_reference(name, window, seed):
    grid = B.balanced_window(name, window, seed)
    assert grid.shape == window.shape and grid.dtype == np.uint8
    assert violations(name, grid) == 0
    assert np.array_equal(grid, B.balanced_window_exact(name, window, seed))


@pytest.mark.slow
@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize("window,seed", FAR, ids=[w.describe() for w, _ in FAR])
def test_far_rows_tile_and_equal_reference(name, window, seed):
    grid = B.balanced_window(name, window, seed)
    assert violations(name, grid) == 0
    assert np.array_equal(grid, B.balanced_window_exact(name, window, seed))


@pytest.mark.parametrize("name", NAMES)
def test_every_tile_is_used(name):
    grid = B.balanced_window(name, Window(-20, -20, 60, 60), 5)
    assert violations(name, grid) == 0
    assert set(np.unique(grid).tolist()) == set(range(len(tiles_of(name))))


@pytest.mark.parametrize("name", NAMES)
def test_overlapping_windows_agree(name):
    """One seed, one tiling: windows at different origins agree where they overlap, and a window
    is the union of its parts."""
    big = Window(-30, -25, 50, 40)
    whole = B.balanced_window(name, big, 8)
    for x0, y0, w, h in [(-30, -25, 50, 1), (-12, -3, 7, 11), (5, 14, 15, 1), (19, -25, 1, 40), (-40, -30, 20, 20)]:
        part = B.balanced_window(name, Window(x0, y0, w, h), 8)
        for r in range(h):
            for c in range(w):
                x, y = x0 + c, y0 + h - 1 - r
                if big.x0 <= x < big.x0 + big.width and big.y0 <= y < big.y0 + big.height:
                    assert part[r, c] == whole[big.y0 + big.height - 1 - y, x - big.x0]
    top, bottom = B.balanced_window(name, Window(-30, -5, 50, 20), 8), B.balanced_window(name, Window(-30, -25, 50, 20), 8)
    assert np.array_equal(np.vstack([top, bottom]), whole)


@pytest.mark.parametrize("name", NAMES)
def test_far_overlaps_agree(name):
    x0, y0 = 2**62 - 40, -2000
    a = B.balanced_window(name, Window(x0, y0, 30, 10), 4)
    b = B.balanced_window(name, Window(x0 + 10, y0 + 3, 30, 10), 4)
    assert np.array_equal(a[:7, 10:], b[3:, :20])


@pytest.mark.parametrize("name", NAMES)
def test_seeds_differ(name):
    w = Window(0, 0, 40, 10)
    assert not np.array_equal(B.balanced_window(name, w, 1), B.balanced_window(name, w, 2))
    assert np.array_equal(B.balanced_window(name, w, 1), B.balanced_window(name, w, 1))


@pytest.mark.parametrize("name", NAMES)
def test_exact_fixups(name, monkeypatch):
    """With 8 fixed-point bits and chunks of 5 columns most floors are decided exactly, across
    many chunk restarts: the window is still the reference's."""
    monkeypatch.setattr(B, "CHUNK", 5)
    for window, seed in WINDOWS[:4]:
        assert np.array_equal(B._window(name, window, seed, 8), B.balanced_window_exact(name, window, seed))


@pytest.mark.parametrize("name", NAMES)
def test_bands_and_blocks(name, monkeypatch):
    """Jobs of a few rows, and of a few columns, give the same window as one job."""
    w, seed = Window(-11, -7, 23, 17), 9
    whole = B.balanced_window(name, w, seed)
    assert np.array_equal(whole, B.balanced_window_exact(name, w, seed))
    monkeypatch.setattr(B, "_cores", lambda: 3)
    for chunk, block, cells in ((B.CHUNK, B._BLOCK_CHUNKS, 50), (2, 3, 50), (3, 1, 10**6)):
        monkeypatch.setattr(B, "CHUNK", chunk)
        monkeypatch.setattr(B, "_BLOCK_CHUNKS", block)
        monkeypatch.setattr(B, "_BAND_CELLS", cells)
        for mode in ("plain", "compiled"):  # compiled: jobs on threads
            monkeypatch.setattr(K.KERNELS, "mode", mode)
            assert np.array_equal(B.balanced_window(name, w, seed), whole)


@pytest.mark.parametrize("name", NAMES)
def test_plain_equals_compiled(name, monkeypatch):
    out = []
    for mode in ("plain", "compiled"):
        monkeypatch.setattr(K.KERNELS, "mode", mode)
        out.append([B._window(name, w, s, bits) for (w, s) in WINDOWS[:3] for bits in (8, B.BITS)])
    for a, b in zip(*out):
        assert np.array_equal(a, b)


def test_y_down_window_is_flipped():
    up = B.balanced_window("kari-14", Window(-4, 2, 9, 6), 3)
    down = B.balanced_window("kari-14", Window(-4, 2, 9, 6, y_up=False), 3)
    assert np.array_equal(down, up[::-1])


def test_kernel_reports_cells_without_tile():
    """Floors that give no digit, or a transition with no tile, are counted, never silent."""
    G = np.array([[0, 1, 5], [0, 2, 4]], np.int32)
    out = np.zeros((1, 2), np.uint8)
    lut = np.zeros(256, np.uint8)
    rows = (np.array([1]), np.array([[2, 1]]), np.array([0]))
    assert K.tiles_kernel(G, *rows, lut, out) == 1  # a = 4 is no digit
    G[0, 2] = 2  # both cells read 1, write 2, carry 1 in: key 16 + 8 + 1
    assert K.tiles_kernel(G, *rows, lut, out) == 0 and out.tolist() == [[0, 0]]
    lut[25] = 255
    assert K.tiles_kernel(G, *rows, lut, out) == 1 and out.tolist() == [[255, 255]]


def test_row_bounds_hold_the_row():
    """The closed form's bounds hold the exact x(y) 2**S, a few units apart."""
    for name in NAMES:
        m = B.machine(name)
        start = B._start(m, 5)
        for y in (-3001, -64, -1, 0, 1, 63, 2500):
            P, Q = B._row_value(m, start, y)
            for S in (64, 256):
                X = B._row_bounds(m, start, y, S)
                if X is not None:
                    assert X.lo * Q <= P << S <= X.hi * Q and X.hi - X.lo <= 4


@pytest.mark.parametrize("name", NAMES)
def test_far_rows(name):
    """Rows near +-2**62, beyond exact arithmetic: windows tile, agree where they overlap, and
    x(y) stepped down by f stays within the closed form's bounds."""
    for y0 in (-(2**62) + 1, 2**40, 2**62 - 30):
        a = B.balanced_window(name, Window(-(2**61), y0, 40, 12), 6)
        b = B.balanced_window(name, Window(-(2**61) + 10, y0 + 5, 40, 12), 6)
        assert violations(name, a) == 0 and violations(name, b) == 0
        assert np.array_equal(a[:7, 10:], b[5:, :30])
    m = B.machine(name)
    start = B._start(m, 6)
    lines = B._Lines(m, start, 2**61, 0, 1, B.BITS)
    for _ in range(300):
        X = next(lines)[-1]
    far = B._row_bounds(m, start, 2**61 - 299, B.PREC)
    assert X.lo <= far.hi and far.lo <= X.hi


@pytest.mark.parametrize("name", NAMES)
def test_sharper_bounds_and_exact_rows(name, monkeypatch):
    """With bounds of 64 bits most lines need sharper bounds, and without sharper ones exact
    rationals: the windows are still the reference's."""
    monkeypatch.setattr(B, "PREC", 64)
    for sharper in ((1024, 4096), ()):
        monkeypatch.setattr(B, "_SHARPER", sharper)
        for window, seed in WINDOWS[:4]:
            assert np.array_equal(B.balanced_window(name, window, seed), B.balanced_window_exact(name, window, seed))


def test_undecided_far_row_is_refused(monkeypatch):
    """Beyond exact arithmetic a floor the sharpest bounds cannot decide is refused, not guessed."""
    monkeypatch.setattr(B, "PREC", 60)
    monkeypatch.setattr(B, "_SHARPER", ())
    with pytest.raises(InvalidProblem, match="undecided"):
        B.balanced_window("kari-14", Window(2**60, 2**50, 30, 30), 1)


def test_bad_input():
    with pytest.raises(InvalidProblem, match="no balanced-sequence route"):
        B.balanced_window("jeandel-rao", Window(0, 0, 2, 2), 1)
    with pytest.raises(InvalidProblem, match="within"):
        B.balanced_window_exact("kari-14", Window(0, -B.MAX_EXACT_ROW, 2, 2), 1)
    with pytest.raises(InvalidProblem, match="seed"):
        B.balanced_window("kari-14", Window(0, 0, 2, 2), -1)
