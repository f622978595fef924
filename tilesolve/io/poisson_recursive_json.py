"""Recursive Wang tile sets and their windows as files (Kopf et al. 2006; class notes Part V).

``tilesolve/recursive-wang-tiles`` (version 1), a set::

    {
      "format": "tilesolve/recursive-wang-tiles", "version": 1,
      "subdivision": 4, "seed": 1,
      "rules": [[[c, ...], ...], ...],   # C^4 tiles (eq. 2.5), each (n + 1) rows of n + 1
                                         # sub-lattice colours, row b = y b, south first
      "base": {...}                      # the corner tiles: a tilesolve/poisson-tiles document,
    }                                    # each region's points in progressive order

``tilesolve/recursive-wang-window`` (version 2), the points of a window::

    {
      "format": "tilesolve/recursive-wang-window", "version": 2,
      "colors": 2, "points": 16, "rho": 0.7, "lloyd": 0, "subdivision": 4,   # the set
      "distance": 0.047...,     # d of level 0 (2 rho r_max(N)); level l: d / n^l
      "window": {"x0": 0, "y0": 0, "width": 8, "height": 8, "y_up": true},
      "level": 2, "density": "level 2", "hash": "long", "seed": 1,
      "density_grid": null,     # or the density, points a unit area: rows (the top first) of
                                # numbers stretched over the window (a --density, --ramp, --image)
      "tileset": {...},         # the set: a tilesolve/recursive-wang-tiles document
      "local": [[x, y, level, rank], ...]   # relative to (x0, y0); coarsest level first
    }

A version 2 file holds everything its points are made from (the set, the density, the hash and
seed, the window): ``tilesolve verify`` re-derives them and compares
(:class:`SeededRecursiveWindow`). Version 1 files (without ``density_grid`` and ``tileset``)
are still read; only the spacing of their levels can be checked, and ``verify`` says so and
does not confirm them (exit 1).

Writes are deterministic: the same seed gives the same bytes. :func:`write_points` writes a
window as JSON, CSV (``x,y,level,rank``, plane coordinates) or NPY (an ``(n, 4)`` float64
array of the same columns), CSV and NPY for windows within ``+-2**31`` only.
"""

from __future__ import annotations

import io
import json
import math
import os
from dataclasses import dataclass

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.io.atomic import write_bytes_atomic, write_text_atomic
from tilesolve.io.jsonio import check_document
from tilesolve.io.poisson_json import check_point_output, embedded_set, read_problem, read_seed
from tilesolve.io.poisson_json import dump as dump_base
from tilesolve.io.poisson_json import tiles_from_dict, tiles_to_dict
from tilesolve.model.poisson_recursive import (
    MAX_CANDIDATES,
    RecursiveProblem,
    RecursiveTilesProblem,
    RecursiveTileSet,
    RecursiveWindow,
    RecursiveWindowProblem,
    check_level,
)
from tilesolve.model.solution import Solution, Status
from tilesolve.model.window import Window

__all__ = ["TILES_FORMAT", "WINDOW_FORMAT", "VERSIONS", "WINDOW_VERSIONS", "MAX_GRID",
           "SeededRecursiveWindow", "set_to_dict", "set_from_dict", "window_to_dict", "window_from_dict", "dump",
           "write_points"]

TILES_FORMAT = "tilesolve/recursive-wang-tiles"
WINDOW_FORMAT = "tilesolve/recursive-wang-window"
VERSIONS = frozenset({1})
#: Versions of window files read: 2 holds its set and density, 1 (spacing only) does not.
WINDOW_VERSIONS = frozenset({1, 2})
#: Most numbers a window file's density grid holds (as many as an image's pixels, ``--image``).
MAX_GRID = 1 << 22

_TILES_KEYS = {"format", "version", "subdivision", "seed", "rules", "base"}
_WINDOW_KEYS = {"format", "version", "colors", "points", "rho", "lloyd", "subdivision", "distance", "window", "level",
                "density", "hash", "seed", "local", "density_grid", "tileset"}
_V2_ONLY = {"density_grid", "tileset"}


@dataclass(frozen=True, eq=False)
class SeededRecursiveWindow(RecursiveWindow):
    """A window's points as a version 2 file states them, with the ``seed`` of the corner
    tiling they claim to come from: ``tilesolve verify`` re-derives them from it and the
    file's problem (a :class:`~tilesolve.model.poisson_recursive.RecursiveWindowProblem`, its
    set and density embedded)."""

    seed: int = 0


def _subdivision(doc: dict, source: str) -> int:
    n = doc.get("subdivision")
    if isinstance(n, bool) or not isinstance(n, int):
        raise InvalidProblem(f"{source}: 'subdivision' must be an integer, got {n!r}")
    return n


def set_to_dict(problem: RecursiveTilesProblem, solution: Solution) -> dict:
    """The document of a built set (``solution.tiling`` is the :class:`RecursiveTileSet`)."""
    ts = solution.tiling
    base = Solution(Status.SAT, ts.base, method=solution.method, seed=ts.base.seed,
                    stats={"short": ts.base.stats.get("short", 0)})
    return {"format": TILES_FORMAT, "version": 1, "subdivision": problem.subdivision, "seed": solution.seed,
            "rules": ts.rules.tolist(), "base": tiles_to_dict(problem.base, base)}


def set_from_dict(doc: dict, source: str = "<document>") -> tuple[RecursiveTilesProblem, Solution]:
    """Read :func:`set_to_dict`'s document; one-line errors naming ``source`` and the field."""
    check_document(doc, source, {TILES_FORMAT: VERSIONS}, fields=_TILES_KEYS, required=("rules", "base", "subdivision"))
    n = _subdivision(doc, source)
    _, base = tiles_from_dict(doc["base"], f"{source} (base)")
    b = base.tiling.problem
    try:
        problem = RecursiveTilesProblem(b.colors, b.points, b.rho, n, b.lloyd)
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: {exc}") from None
    rules = doc["rules"]
    shape = (problem.n_tiles, n + 1, n + 1)
    if not (isinstance(rules, list) and len(rules) == shape[0] and all(
            isinstance(r, list) and len(r) == n + 1 and all(
                isinstance(row, list) and len(row) == n + 1 and all(
                    isinstance(v, int) and not isinstance(v, bool) for v in row) for row in r) for r in rules)):
        raise InvalidProblem(f"{source}: 'rules' must be {shape[0]} rules of {n + 1} x {n + 1} integer colours")
    arr = np.array(rules, dtype=np.int64).reshape(shape)
    seed = read_seed(doc, source)
    ts = RecursiveTileSet(problem, base.tiling, arr, seed=seed)
    return problem, Solution(Status.SAT, ts, method=base.method, seed=seed, stats=dict(base.stats))


def window_to_dict(problem: RecursiveWindowProblem, solution: Solution) -> dict:
    """The version 2 document of a window (``solution.tiling`` is the :class:`RecursiveWindow`),
    its set and density embedded."""
    w, ts = solution.tiling, problem.tileset
    p = ts.problem
    built = Solution(Status.SAT, ts, method="build", seed=ts.seed)
    return {"format": WINDOW_FORMAT, "version": 2, "colors": p.colors, "points": p.points, "rho": p.rho,
            "lloyd": p.lloyd, "subdivision": p.subdivision, "distance": p.distance,
            "window": problem.window.to_dict(), "level": problem.level, "density": problem.label,
            "hash": problem.hash, "seed": solution.seed, "density_grid": problem.density,
            "tileset": set_to_dict(p, built), "local": np.column_stack([w.local, w.level, w.rank])}


def _grid(value, source: str):
    """A file's ``density_grid``: ``None``, or rows of non-negative numbers, as an array."""
    if value is None:
        return None
    if not (isinstance(value, list) and value and isinstance(value[0], list) and value[0]
            and len(value) * len(value[0]) <= MAX_GRID and all(
                isinstance(r, list) and len(r) == len(value[0]) and all(
                    isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) and v >= 0
                    for v in r) for r in value)):
        raise InvalidProblem(f"{source}: 'density_grid' must be null or equal rows of non-negative numbers, "
                             f"{MAX_GRID:,} at most")
    return np.array(value, dtype=np.float64)


def _local(rows, level: int, source: str) -> np.ndarray:
    """A file's ``local`` rows as an ``(n, 4)`` array, levels within ``0..level``."""
    if not isinstance(rows, list) or len(rows) > MAX_CANDIDATES:
        raise InvalidProblem(f"{source}: 'local' must be a list of at most {MAX_CANDIDATES:,} [x, y, level, rank] rows")
    for r in rows:
        if not (isinstance(r, list) and len(r) == 4 and all(
                isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in r)):
            raise InvalidProblem(f"{source}: 'local' holds {r!r}, not an [x, y, level, rank] row of numbers")
    arr = np.array(rows, dtype=np.float64).reshape(-1, 4)
    lv = arr[:, 2]
    if ((lv != np.round(lv)) | (lv < 0) | (lv > level)).any():
        raise InvalidProblem(f"{source}: a point's level must be an integer within 0..{level} (the window's level)")
    return arr


def window_from_dict(doc: dict, source: str = "<document>") -> tuple[RecursiveProblem, Solution]:
    """Read :func:`window_to_dict`'s document. Version 2: the window's problem (its set read
    from ``tileset``, its density from ``density_grid``) and a :class:`SeededRecursiveWindow`;
    version 1: the set's problem and the points (each level's spacing alone can be checked,
    :func:`tilesolve.verify.poisson_recursive.window_violations`)."""
    v2 = isinstance(doc, dict) and doc.get("version") == 2
    fields = _WINDOW_KEYS if v2 else _WINDOW_KEYS - _V2_ONLY
    check_document(doc, source, {WINDOW_FORMAT: WINDOW_VERSIONS}, fields=fields,
                   required=("window", "local", "level", "subdivision") + (("tileset", "seed") if v2 else ()))
    base = read_problem(doc, source)
    try:
        problem = RecursiveTilesProblem(base.colors, base.points, base.rho, _subdivision(doc, source), base.lloyd)
        level = check_level(doc["level"])
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: {exc}") from None
    window = Window.from_dict(doc["window"])
    arr = _local(doc["local"], level, source)
    seed = read_seed(doc, source)
    parts = (window, np.ascontiguousarray(arr[:, :2]), arr[:, 2].astype(np.int8), arr[:, 3].copy(), problem.distance,
             problem.subdivision)
    if not v2:
        return problem, Solution(Status.SAT, RecursiveWindow(*parts), method="window", seed=seed, window=window)
    tileset = embedded_set(doc, source, problem, set_from_dict)
    grid, label = _grid(doc.get("density_grid"), source), doc.get("density", "")
    if not isinstance(label, str) or len(label) > 1000:
        raise InvalidProblem(f"{source}: 'density' must be the density's label, a string (e.g. 'ramp 16,4096')")
    try:
        wp = RecursiveWindowProblem(tileset, window, None if grid is not None else level, grid, label,
                                    doc.get("hash", "long"))
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: {exc}") from None
    if wp.level != level:
        raise InvalidProblem(f"{source}: 'level' is {level}, but its density needs level {wp.level}")
    return wp, Solution(Status.SAT, SeededRecursiveWindow(*parts, seed=seed), method="window", seed=seed,
                        window=window)


def _rows(rows) -> str:
    return "[" + ", ".join("[" + ", ".join(str(v) for v in r) + "]" for r in rows) + "]"


def dump(doc: dict) -> str:
    """JSON text: one rule a line, the base set as :func:`tilesolve.io.poisson_json.dump` writes
    it, a window's one point a line (floats written to round-trip exactly)."""
    head = {k: v for k, v in doc.items() if k not in ("rules", "base", "density_grid", "tileset", "local")}
    text = json.dumps(head, indent=2)[:-2]
    if "density_grid" in doc:
        grid = doc["density_grid"]
        text += ',\n  "density_grid": ' + ("null" if grid is None else "[" + ",".join(
            "\n    [" + ", ".join(repr(v) for v in row) + "]" for row in np.asarray(grid).tolist()) + "\n  ]")
    if "tileset" in doc:
        text += ',\n  "tileset": ' + dump(doc["tileset"]).rstrip("\n").replace("\n", "\n  ")
    if "rules" in doc:
        text += ',\n  "rules": [' + ",".join(f"\n    {_rows(r)}" for r in doc["rules"]) + "\n  ]"
        text += ',\n  "base": ' + dump_base(doc["base"]).rstrip("\n").replace("\n", "\n  ")
    if "local" in doc:
        rows = np.asarray(doc["local"]).reshape(-1, 4).tolist()
        text += ',\n  "local": [' + ",".join(f"\n    [{x!r}, {y!r}, {int(lv)}, {u!r}]" for x, y, lv, u in rows)
        text += "\n  ]" if rows else "]"
    return text + "\n}\n"


def write_points(path: str | os.PathLike, problem: RecursiveWindowProblem, solution: Solution) -> None:
    """Write a window's points; the format follows the suffix: ``.json`` (:func:`window_to_dict`),
    ``.csv`` or ``.npy`` (plane coordinates, level and rank; windows within ``+-2**31`` only)."""
    suffix = check_point_output(path, problem.window)
    w = solution.tiling
    if suffix == "json":
        write_text_atomic(path, dump(window_to_dict(problem, solution)))
        return
    table = np.column_stack([w.absolute(), w.level.astype(np.float64), w.rank])
    if suffix == "npy":
        buf = io.BytesIO()
        np.save(buf, table)
        write_bytes_atomic(path, buf.getvalue())
    else:
        buf = io.StringIO()
        buf.write("x,y,level,rank\n")
        np.savetxt(buf, table, fmt=["%.17g", "%.17g", "%d", "%.17g"], delimiter=",")
        write_text_atomic(path, buf.getvalue())

