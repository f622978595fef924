"""Poisson disk tile sets and windows as files (class notes §4.3).

``tilesolve/poisson-tiles`` (version 1), a tile set::

    {
      "format": "tilesolve/poisson-tiles", "version": 1,
      "colors": 2, "points": 64, "rho": 0.75, "lloyd": 0,   # the problem (C, N, rho, Lloyd steps)
      "distance": 0.1007...,      # 2 rho r_max(N), for people: readers recompute it
      "method": "dart", "seed": 1, "stats": {"short": 12},
      "tiles": {"corner": [[[x, y], ...], ...],   # by colour
                "hedge": [...],                   # by west * C + east
                "vedge": [...],                   # by south * C + north
                "interior": [...]}                # by eq. 2.5 (NE, SE, SW, NW)
    }

``tilesolve/poisson-window`` (version 2), the points of a window::

    {
      "format": "tilesolve/poisson-window", "version": 2,
      "colors": 2, "points": 64, "rho": 0.75, "lloyd": 0,   # the set the tiling used
      "window": {"x0": 0, "y0": 0, "width": 8, "height": 8, "y_up": true},
      "tiling": "direct", "set": "complete", "hash": "long", "seed": 1,
      "distance": 0.1007...,
      "tileset": {...},           # that set: a tilesolve/poisson-tiles document
      "local": [[x, y], ...]      # points relative to (x0, y0): x0 + x, y0 + y in the plane
    }

A version 2 file binds its points to the seed: it holds everything they are made from (the set,
the corner tiling, its hash and seed, the window), so that ``tilesolve verify`` re-derives them
and compares (:class:`SeededWindow`). Version 1 files (the same without ``tileset``) are still
read; their points can only be checked for their spacing, and ``verify`` says so and does not
confirm them (exit 1): sample the window again to write version 2.

Coordinates are tile units, y north. Writes are deterministic (no timings): the same seed
gives the same bytes. :func:`write_points` also writes a window as CSV (``x,y`` header) or NPY
(an ``(n, 2)`` float64 array) of plane coordinates, for windows within ``+-2**31`` where
float64 keeps them to 1e-6 of a tile; the JSON form keeps any window exact.
"""

from __future__ import annotations

import io
import json
import math
import os
from dataclasses import dataclass
from typing import Any

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.io.atomic import write_bytes_atomic, write_text_atomic
from tilesolve.io.jsonio import check_document
from tilesolve.model.poisson import (
    KINDS,
    MAX_WINDOW_POINTS,
    PoissonProblem,
    PoissonTilesProblem,
    PoissonTileSet,
    PoissonWindow,
    PoissonWindowProblem,
)
from tilesolve.model.solution import Solution, Status
from tilesolve.model.window import Window

__all__ = ["TILES_FORMAT", "WINDOW_FORMAT", "VERSIONS", "WINDOW_VERSIONS", "UNBOUND", "SeededWindow", "tiles_to_dict",
           "tiles_from_dict", "window_to_dict", "window_from_dict", "embedded_set", "read_problem", "read_seed",
           "read_points", "built_set", "dump", "write_points", "check_point_output", "POINT_FORMATS", "FLOAT_RANGE"]

TILES_FORMAT = "tilesolve/poisson-tiles"
WINDOW_FORMAT = "tilesolve/poisson-window"
VERSIONS = frozenset({1})
#: Versions of window files read: 2 holds its tile set, 1 (spacing only) does not.
WINDOW_VERSIONS = frozenset({1, 2})
#: Output formats of a window's points, by file suffix.
POINT_FORMATS = ("json", "csv", "npy")
#: CSV and NPY hold plane coordinates: windows within this bound only.
FLOAT_RANGE = 1 << 31

_PROBLEM = ("colors", "points", "rho", "lloyd")
_TILES_KEYS = {"format", "version", *_PROBLEM, "distance", "method", "seed", "stats", "tiles"}
#: What ``verify`` says of a version 1 window file (``what``: the kind of set it does not hold).
UNBOUND = ("a version 1 window file holds no {what}, so its points cannot be re-derived from its seed: only their "
           "spacing was checked, and it is NOT confirmed that they are the window of the set and seed it names; "
           "sample the window again to write version 2")
_WINDOW_KEYS = {"format", "version", *_PROBLEM, "window", "tiling", "set", "hash", "seed", "distance", "local",
                "tileset"}


@dataclass(frozen=True, eq=False)
class SeededWindow(PoissonWindow):
    """A window's points as a version 2 file states them, with the ``seed`` of the corner
    tiling they claim to come from: ``tilesolve verify`` re-derives them from it and the
    file's problem (:class:`~tilesolve.model.poisson.PoissonWindowProblem`, its set embedded)."""

    seed: int = 0


def _problem(p: PoissonTilesProblem) -> dict:
    return {"colors": p.colors, "points": p.points, "rho": p.rho, "lloyd": p.lloyd, "distance": p.distance}


def tiles_to_dict(problem: PoissonTilesProblem, solution: Solution) -> dict:
    """The document of a built set (``solution.tiling`` is the :class:`PoissonTileSet`)."""
    ts = solution.tiling
    return {"format": TILES_FORMAT, "version": 1, **_problem(problem), "method": solution.method,
            "seed": solution.seed, "stats": {k: v for k, v in solution.stats.items() if k == "short"},
            "tiles": {k: [a.tolist() for a in ts.tiles[k]] for k in KINDS}}


def read_points(value: Any, what: str, source: str, limit: int, dim: int = 2) -> np.ndarray:
    """Field ``what`` of a document: a list of at most ``limit`` points of ``dim`` (2 or 3) finite
    numbers, as an ``(n, dim)`` float64 array; one-line errors naming ``source`` and the field."""
    shape, noun = ("[x, y]", "pair") if dim == 2 else ("[x, y, z]", "triple")
    if not isinstance(value, list) or len(value) > limit:
        raise InvalidProblem(f"{source}: {what!r} must be a list of at most {limit:,} {shape} points")
    for p in value:
        if not (isinstance(p, list) and len(p) == dim and all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                                               and math.isfinite(v) for v in p)):
            raise InvalidProblem(f"{source}: {what!r} holds {p!r}, not an {shape} {noun} of numbers")
    return np.array(value, dtype=np.float64).reshape(-1, dim)


def read_problem(doc: dict, source: str) -> PoissonTilesProblem:
    """The problem a document states (``colors``, ``points``, ``rho``, ``lloyd``); a stated
    ``distance`` other than the problem's is refused."""
    for key in _PROBLEM:
        if key not in doc:
            raise InvalidProblem(f"{source}: missing field {key!r}")
    try:
        problem = PoissonTilesProblem(doc["colors"], doc["points"], doc["rho"], doc["lloyd"])
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: {exc}") from None
    # The distance is recomputed from the problem; a file that states another one is refused,
    # so that the verdict can never be read as a promise about the stated distance.
    stated = doc.get("distance", problem.distance)
    if isinstance(stated, bool) or not isinstance(stated, (int, float)) or not math.isclose(
            stated, problem.distance, rel_tol=1e-12):
        raise InvalidProblem(f"{source}: 'distance' is {stated!r}, but its problem's is {problem.distance!r} "
                             "(2 rho r_max(N))")
    return problem


def read_seed(doc: dict, source: str):
    """A document's ``seed``: ``None`` or an integer within ``0..2**63 - 1``."""
    seed = doc.get("seed")
    if seed is not None and (isinstance(seed, bool) or not isinstance(seed, int) or not 0 <= seed < 2**63):
        raise InvalidProblem(f"{source}: 'seed' must be an integer from 0 to 2**63 - 1, got {seed!r}")
    return seed


def tiles_from_dict(doc: dict, source: str = "<document>") -> tuple[PoissonTilesProblem, Solution]:
    """Read :func:`tiles_to_dict`'s document; one-line errors naming ``source`` and the field."""
    check_document(doc, source, {TILES_FORMAT: VERSIONS}, fields=_TILES_KEYS, required=("tiles",))
    problem = read_problem(doc, source)
    tiles = doc["tiles"]
    if not isinstance(tiles, dict) or set(tiles) != set(KINDS):
        raise InvalidProblem(f"{source}: 'tiles' must have the fields {', '.join(KINDS)}")
    c, n = problem.colors, problem.points
    want = {"corner": c, "hedge": c * c, "vedge": c * c, "interior": c**4}
    arrays = {}
    for kind in KINDS:
        if not isinstance(tiles[kind], list) or len(tiles[kind]) != want[kind]:
            raise InvalidProblem(f"{source}: a set over {c} colours has {want[kind]} {kind} tiles")
        arrays[kind] = [read_points(t, f"tiles.{kind}[{i}]", source, 4 * n + 16) for i, t in enumerate(tiles[kind])]
    return problem, built_set(doc, source, lambda seed, stats: PoissonTileSet(problem, arrays, seed=seed, stats=stats))


def built_set(doc: dict, source: str, make) -> Solution:
    """The solution of a built tile set's document (2-D or 3-D): its ``stats``, seed and method
    read from ``doc``, the set made by ``make(seed, stats)``."""
    stats = doc.get("stats", {})
    if not isinstance(stats, dict):
        raise InvalidProblem(f"{source}: 'stats' must be an object")
    seed = read_seed(doc, source)
    method = doc.get("method", "dart")
    return Solution(Status.SAT, make(seed, dict(stats)), method=method if isinstance(method, str) else "dart",
                    seed=seed, stats=dict(stats))


def _set_solution(ts: PoissonTileSet) -> Solution:
    """A built set as the solution :func:`tiles_to_dict` writes (its seed and shortfall)."""
    return Solution(Status.SAT, ts, method="dart", seed=ts.seed, stats={"short": ts.stats.get("short", 0)})


def window_to_dict(problem: PoissonWindowProblem, solution: Solution) -> dict:
    """The version 2 document of a window (``solution.tiling`` is the :class:`PoissonWindow`),
    its set embedded."""
    w, ts = solution.tiling, problem.tileset
    return {"format": WINDOW_FORMAT, "version": 2, **_problem(ts.problem),
            "window": problem.window.to_dict(), "tiling": problem.tiling, "set": problem.variant,
            "hash": problem.hash, "seed": solution.seed, "tileset": tiles_to_dict(ts.problem, _set_solution(ts)),
            "local": w.local}


def window_from_dict(doc: dict, source: str = "<document>") -> tuple[PoissonProblem, Solution]:
    """Read :func:`window_to_dict`'s document. Version 2: the window's problem (its set read
    from ``tileset``) and a :class:`SeededWindow`; version 1: the set's problem and the points
    (spacing alone can be checked, :func:`tilesolve.verify.poisson.point_violations`)."""
    v2 = isinstance(doc, dict) and doc.get("version") == 2
    fields = _WINDOW_KEYS if v2 else _WINDOW_KEYS - {"tileset"}
    check_document(doc, source, {WINDOW_FORMAT: WINDOW_VERSIONS}, fields=fields,
                   required=("window", "local", "tileset", "seed") if v2 else ("window", "local"))
    problem = read_problem(doc, source)
    window = Window.from_dict(doc["window"])
    local = read_points(doc["local"], "local", source, MAX_WINDOW_POINTS)
    seed = read_seed(doc, source)
    if not v2:
        return problem, Solution(Status.SAT, PoissonWindow(window, local, problem.distance),
                                 method=str(doc.get("tiling", "direct")), seed=seed, window=window)
    tileset = embedded_set(doc, source, problem, tiles_from_dict)
    try:
        wp = PoissonWindowProblem(tileset, window, doc.get("tiling", "direct"), doc.get("set", "complete"),
                                  doc.get("hash", "long"))
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: {exc}") from None
    return wp, Solution(Status.SAT, SeededWindow(window, local, problem.distance, seed), method="window", seed=seed,
                        window=window)


def embedded_set(doc: dict, source: str, problem, read):
    """The tile set a version 2 window file embeds (``read(doc["tileset"], ...)``, a set's
    reader), which must be of the window's ``problem``; the file's seed must be stated."""
    if doc.get("seed") is None:
        raise InvalidProblem(f"{source}: a version 2 window file states the seed of its tiling, not null")
    set_problem, built = read(doc["tileset"], f"{source} (tileset)")
    if set_problem != problem:
        raise InvalidProblem(f"{source}: the window states {problem.describe()}, but its tileset is "
                             f"{set_problem.describe()}")
    return built.tiling


def _line(rows) -> str:
    return "[" + ", ".join(f"[{x!r}, {y!r}]" for x, y in rows) + "]"


def dump(doc: dict) -> str:
    """JSON text: a tile's points on one line, a window's one point a line, its embedded set as
    a set is written (floats written to round-trip exactly)."""
    head = {k: v for k, v in doc.items() if k not in ("tiles", "tileset", "local")}
    text = json.dumps(head, indent=2)[:-2]
    if "tileset" in doc:
        text += ',\n  "tileset": ' + dump(doc["tileset"]).rstrip("\n").replace("\n", "\n  ")
    if "tiles" in doc:
        kinds = [f'    "{k}": [\n' + ",\n".join("      " + _line(t) for t in doc["tiles"][k]) + "\n    ]"
                 for k in KINDS]
        text += ',\n  "tiles": {\n' + ",\n".join(kinds) + "\n  }"
    if "local" in doc:
        rows = np.asarray(doc["local"]).tolist()
        text += ',\n  "local": [' + ",".join(f"\n    [{x!r}, {y!r}]" for x, y in rows) + ("\n  ]" if rows else "]")
    return text + "\n}\n"


def check_point_output(path: str | os.PathLike, window: Window) -> str:
    """The format of a points file, from its suffix; refuses CSV and NPY for a window beyond
    :data:`FLOAT_RANGE` (before any work is done)."""
    suffix = os.fspath(path).rsplit(".", 1)[-1].lower()
    if suffix not in POINT_FORMATS:
        raise InvalidProblem(f"cannot tell the format of {os.fspath(path)!r}: use .json, .csv or .npy")
    far = max(abs(window.x0), abs(window.y0), abs(window.x0 + window.width), abs(window.y0 + window.height))
    if suffix != "json" and far > FLOAT_RANGE:
        raise InvalidProblem(f"the window lies beyond +-2**31, where {suffix.upper()} plane coordinates lose "
                             "precision: write .json (points relative to the window's corner)")
    return suffix


def write_points(path: str | os.PathLike, problem: PoissonWindowProblem, solution: Solution) -> None:
    """Write a window's points; the format follows the suffix: ``.json`` (:func:`window_to_dict`),
    ``.csv`` or ``.npy`` (plane coordinates, windows within :data:`FLOAT_RANGE` only)."""
    suffix = check_point_output(path, problem.window)
    w = solution.tiling
    if suffix == "json":
        write_text_atomic(path, dump(window_to_dict(problem, solution)))
        return
    pts = w.absolute()
    if suffix == "npy":
        buf = io.BytesIO()
        np.save(buf, pts)
        write_bytes_atomic(path, buf.getvalue())
    else:
        buf = io.StringIO()
        buf.write("x,y\n")
        np.savetxt(buf, pts, fmt="%.17g", delimiter=",")
        write_text_atomic(path, buf.getvalue())
