"""Line-length statistics of brick walls (004 §5, Fig. 22): run counting against brute force,
the line limit on random windows (PD) and tori (NPD), histogram sums, the clamp numbers, and
the ``tilesolve wall-lines`` command."""

from __future__ import annotations

import csv
import json

import numpy as np
import pytest

from clitools import one_line_error, run
from tilesolve.constructive.wall_stats import clamp_numbers, histogram, runs, wall_lines
from tilesolve.constructive.walls import wall_window
from tilesolve.errors import InvalidProblem
from tilesolve.families.walls import line_statistics


def brute_runs(row: list[bool], cyclic: bool) -> list[tuple[int, int]]:
    """``(start, length)`` of the maximal runs of one row, walking cell by cell."""
    n = len(row)
    if cyclic and all(row):
        return [(0, n)]
    out = []
    for i in range(n):
        prev = row[i - 1] if (i > 0 or cyclic) else False
        if row[i] and not prev:
            k = 0
            while k < n and row[(i + k) % n] and (cyclic or i + k < n):
                k += 1
            out.append((i, k))
    return out


@pytest.mark.parametrize("cyclic", [False, True])
def test_runs_against_brute_force(cyclic):
    rng = np.random.default_rng(1)
    for _ in range(200):
        m = rng.random((int(rng.integers(1, 5)), int(rng.integers(1, 9)))) < rng.random()
        line, start, length = runs(m, cyclic=cyclic)
        got = sorted(zip(line.tolist(), start.tolist(), length.tolist()))
        want = sorted((r, s, k) for r in range(m.shape[0]) for s, k in brute_runs(m[r].tolist(), cyclic))
        assert got == want
        assert int(length.sum()) == int(m.sum())  # every member cell in exactly one run


def test_window_lines_are_counted_once_and_whole():
    """Lines of a padded window, counted by first cell, are the lines of a far larger window
    that start in the window proper."""
    n, x0, y0, w, h = 4, -7, 11, 30, 20
    padded = wall_window(x0 - n, y0 - n, w + 2 * n, h + 2 * n, colors=3, max_line=n, seed=3)
    big_pad = 3 * n
    big = wall_window(x0 - big_pad, y0 - big_pad, w + 2 * big_pad, h + 2 * big_pad, colors=3, max_line=n, seed=3)
    hor = big[..., 3] == big[..., 1]  # W = E
    want_h, want_v = [], []
    for mask, out in ((hor, want_h), (~hor.T, want_v)):
        line, start, length = runs(mask)
        keep = ((line >= big_pad) & (line < mask.shape[0] - big_pad)
                & (start >= big_pad) & (start < mask.shape[1] - big_pad))
        out.extend(sorted(length[keep].tolist()))
    got_h, got_v = wall_lines(padded, margin=n)
    assert sorted(got_h.tolist()) == want_h and sorted(got_v.tolist()) == want_v


@pytest.mark.parametrize("n", range(1, 11))
def test_procedural_lines_never_exceed_n_on_random_windows(n):
    rng = np.random.default_rng(n)
    for _ in range(4):
        x0, y0 = (int(v) for v in rng.integers(-10**12, 10**12, size=2))
        w, h = (int(v) for v in rng.integers(1, 60, size=2))
        legs = wall_window(x0 - n, y0 - n, w + 2 * n, h + 2 * n, colors=int(rng.integers(3, 6)), max_line=n,
                           seed=int(rng.integers(0, 2**32)))
        for lengths in wall_lines(legs):  # every run of the padded window, cut or whole
            assert lengths.max() <= n


@pytest.mark.parametrize("n", range(1, 11))
def test_npd_lines_never_exceed_n_across_the_seams(n):
    size = max(4, n + 3) + n % 3
    size += size % 2  # even heights, odd widths (even for n = 1: no cyclic 1-dappling of an odd side here)
    h = line_statistics("npd", n, width=size + (2 if n == 1 else 1), height=size, samples=2, seed=n)
    assert max(h.longest) <= n


@pytest.mark.parametrize("method", ["procedural", "npd", "wall"])
def test_histogram_sums_are_the_line_counts(method):
    h = line_statistics(method, 4, width=24, height=20, samples=2, seed=5)
    assert h.samples == 2 and h.cells == 2 * 24 * 20
    for d in ("horizontal", "vertical"):
        assert h.counts(d).shape == (4,)
        assert np.isclose(h.shares(d).sum(), 1.0)
    if method == "npd":  # on the torus the lines cover every cell of their kind exactly once
        assert int((h.horizontal * np.arange(1, 5)).sum() + (h.vertical * np.arange(1, 5)).sum()) == h.cells
    lengths = np.array([1, 1, 2, 3, 3, 3])
    assert int(histogram(lengths, 3).sum()) == lengths.size


def test_kaji_dappling_clamps_lines_at_n_and_pd_does_not():
    """004 §5: with Kaji's dappling there are about as many lines at n = 4 as at 3; the
    procedural wall has about half as many (the numbers are in benchmarks/bench_wall_lines.py)."""
    for method in ("npd", "wall"):
        h = line_statistics(method, 4, width=96, height=96, samples=2, seed=0)
        assert clamp_numbers(h.vertical + h.horizontal)["ratio"] > 0.8
    pd = line_statistics("procedural", 4, width=96, height=96, samples=2, seed=0)
    assert clamp_numbers(pd.vertical + pd.horizontal)["ratio"] < 0.65


def test_clamp_numbers_and_histogram_refuse_out_of_range():
    assert clamp_numbers([3, 1])["ratio"] == pytest.approx(1 / 3)
    assert np.isnan(clamp_numbers([5])["ratio"])
    with pytest.raises(InvalidProblem, match="1..3"):
        histogram([1, 4], 3)


@pytest.mark.parametrize(("kwargs", "words"), [
    ({"method": "magic", "n": 4}, "unknown wall generator"),
    ({"method": "npd", "n": 0}, "1..256"),
    ({"method": "procedural", "n": 10**30}, "1..256"),
    ({"method": "npd", "n": 4, "width": 2}, "at least 3x3"),
    ({"method": "wall", "n": 4, "colors": 2}, "3..127"),
    ({"method": "procedural", "n": 4, "width": 10**30}, "cells measured"),
    ({"method": "procedural", "n": 4, "samples": 0}, "samples"),
])
def test_line_statistics_bad_input(kwargs, words):
    method, n = kwargs.pop("method"), kwargs.pop("n")
    with pytest.raises(InvalidProblem, match=words):
        line_statistics(method, n, **kwargs)


def test_command_writes_a_small_table(tmp_path):
    """The fast tier's wall-lines: one generator on a small wall (both, with pictures: below, slow)."""
    proc = run("wall-lines", "--method", "procedural", "--max-line", "3", "--size", "12x8", "--samples", "1",
               "--seed", "2", "-o", "t.csv", "--svg", "h.svg", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    rows = list(csv.DictReader((tmp_path / "t.csv").open()))
    assert [(r["method"], r["direction"]) for r in rows] == [("procedural", "vertical"), ("procedural", "horizontal")]
    for r in rows:
        assert int(r["lines"]) == sum(int(r[f"length_{k}"]) for k in (1, 2, 3)) and int(r["longest"]) <= 3
    assert (tmp_path / "h.svg").read_text().startswith("<?xml")


@pytest.mark.slow
def test_command_writes_table_and_pictures(tmp_path):
    proc = run("wall-lines", "--method", "procedural", "--method", "npd", "--max-line", "3", "--size", "24x16",
               "--samples", "1", "--seed", "2", "-o", "t.csv", "--svg", "h.svg", "--png", "h.png", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    rows = list(csv.DictReader((tmp_path / "t.csv").open()))
    assert [(r["method"], r["direction"]) for r in rows] == [
        ("procedural", "vertical"), ("procedural", "horizontal"), ("npd", "vertical"), ("npd", "horizontal")]
    for r in rows:
        assert int(r["lines"]) == sum(int(r[f"length_{k}"]) for k in (1, 2, 3)) and int(r["longest"]) <= 3
    assert "procedural   3 vertical" in proc.stdout
    assert (tmp_path / "h.svg").read_text().startswith("<?xml")
    assert (tmp_path / "h.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    again = run("wall-lines", "--method", "npd", "--max-line", "3", "--size", "24x16", "--samples", "1",
                "--seed", "2", "-o", "-", cwd=tmp_path)
    doc = json.loads(again.stdout)
    assert doc["format"] == "tilesolve-wall-lines" and doc["rows"][0]["counts"] == [
        int(rows[2][f"length_{k}"]) for k in (1, 2, 3)]  # same seed, same table


@pytest.mark.slow
def test_command_refuses_in_one_line(tmp_path):
    (tmp_path / "keep.json").write_text("{}\n")
    one_line_error(run("wall-lines", "--size", "2x2", "--method", "npd", "-o", "keep.json", cwd=tmp_path))
    assert (tmp_path / "keep.json").read_text() == "{}\n"
