"""Poisson sphere tile sets and boxes of points as files (class notes §4.4).

``tilesolve/poisson-sphere-tiles`` (version 1), a tile set::

    {
      "format": "tilesolve/poisson-sphere-tiles", "version": 1,
      "colors": 2, "points": 128, "rho": 0.65,   # the problem (C, N, rho)
      "distance": 0.14...,        # 2 rho r_max(N) (eq. 4.5-4.6), for people: readers recompute it
      "method": "dart", "seed": 1, "stats": {"short": 0},
      "tiles": {"corner": [[[x, y, z], ...], ...], "xedge": [...], "yedge": [...], "zedge": [...],
                "xface": [...], "yface": [...], "zface": [...], "interior": [...]}
    }

(tile order as in :class:`tilesolve.model.poisson_sphere.PoissonSphereTileSet`).

``tilesolve/poisson-sphere-window`` (version 2), the points of a box::

    {
      "format": "tilesolve/poisson-sphere-window", "version": 2,
      "colors": 2, "points": 128, "rho": 0.65, "distance": 0.14...,
      "box": {"x0": 0, "y0": 0, "z0": 0, "width": 4, "height": 4, "depth": 4},
      "hash": "long", "seed": 1,
      "tileset": {...},           # the set: a tilesolve/poisson-sphere-tiles document
      "local": [[x, y, z], ...]   # relative to (x0, y0, z0)
    }

A version 2 file binds its points to the seed: it holds everything they are made from (the set,
the hash and its seed, the box), so that ``tilesolve verify`` re-derives them and compares
(:class:`SeededBox`). Version 1 files (the same without ``tileset``) are still read; their
points can only be checked for their spacing, and ``verify`` says so and does not confirm them
(exit 1): sample the box again to write version 2.

Writes are deterministic (no timings): the same seed gives the same bytes. :func:`write_points3`
also writes a box as CSV (``x,y,z`` header) or NPY (an ``(n, 3)`` float64 array) of coordinates
of space, for boxes within ``+-2**31``; the JSON form keeps any box exact.
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
from tilesolve.io.poisson_json import FLOAT_RANGE, POINT_FORMATS, built_set, embedded_set, read_points, read_seed
from tilesolve.model.poisson_sphere import (
    KINDS,
    MAX_WINDOW_POINTS,
    Box,
    PoissonSphereProblem,
    PoissonSphereTilesProblem,
    PoissonSphereTileSet,
    PoissonSphereWindow,
    PoissonSphereWindowProblem,
)
from tilesolve.model.solution import Solution, Status

__all__ = ["TILES_FORMAT", "WINDOW_FORMAT", "VERSIONS", "WINDOW_VERSIONS", "SeededBox", "tiles_to_dict",
           "tiles_from_dict", "window_to_dict", "window_from_dict", "dump", "write_points3", "check_point_output3"]

TILES_FORMAT = "tilesolve/poisson-sphere-tiles"
WINDOW_FORMAT = "tilesolve/poisson-sphere-window"
VERSIONS = frozenset({1})
#: Versions of box files read: 2 holds its tile set, 1 (spacing only) does not.
WINDOW_VERSIONS = frozenset({1, 2})

_PROBLEM = ("colors", "points", "rho")
_TILES_KEYS = {"format", "version", *_PROBLEM, "distance", "method", "seed", "stats", "tiles"}
_WINDOW_KEYS = {"format", "version", *_PROBLEM, "distance", "box", "hash", "seed", "local", "tileset"}


@dataclass(frozen=True, eq=False)
class SeededBox(PoissonSphereWindow):
    """A box's points as a version 2 file states them, with the ``seed`` of the lattice hash
    they claim to come from: ``tilesolve verify`` re-derives them from it and the file's
    problem (:class:`~tilesolve.model.poisson_sphere.PoissonSphereWindowProblem`, its set
    embedded)."""

    seed: int = 0


def _problem(p: PoissonSphereTilesProblem) -> dict:
    return {"colors": p.colors, "points": p.points, "rho": p.rho, "distance": p.distance}


def tiles_to_dict(problem: PoissonSphereTilesProblem, solution: Solution) -> dict:
    """The document of a built set (``solution.tiling`` is the :class:`PoissonSphereTileSet`)."""
    ts = solution.tiling
    return {"format": TILES_FORMAT, "version": 1, **_problem(problem), "method": solution.method,
            "seed": solution.seed, "stats": {"short": int(ts.stats.get("short", 0))},
            "tiles": {k: [a.tolist() for a in ts.tiles[k]] for k in KINDS}}


def _read_problem(doc: dict, source: str) -> PoissonSphereTilesProblem:
    missing = [k for k in _PROBLEM if k not in doc]
    if missing:
        raise InvalidProblem(f"{source}: missing field {missing[0]!r}")
    try:
        problem = PoissonSphereTilesProblem(doc["colors"], doc["points"], doc["rho"])
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: {exc}") from None
    stated = doc.get("distance", problem.distance)  # recomputed; another stated distance is refused
    if isinstance(stated, bool) or not isinstance(stated, (int, float)) or not math.isclose(
            stated, problem.distance, rel_tol=1e-12):
        raise InvalidProblem(f"{source}: 'distance' is {stated!r}, but its problem's is {problem.distance!r} "
                             "(2 rho r_max(N))")
    return problem


def tiles_from_dict(doc: dict, source: str = "<document>") -> tuple[PoissonSphereTilesProblem, Solution]:
    """Read :func:`tiles_to_dict`'s document; one-line errors naming ``source`` and the field."""
    check_document(doc, source, {TILES_FORMAT: VERSIONS}, fields=_TILES_KEYS, required=("tiles",))
    problem = _read_problem(doc, source)
    tiles = doc["tiles"]
    if not isinstance(tiles, dict) or set(tiles) != set(KINDS):
        raise InvalidProblem(f"{source}: 'tiles' must have the fields {', '.join(KINDS)}")
    arrays = {}
    for kind, n in problem.counts().items():
        if not isinstance(tiles[kind], list) or len(tiles[kind]) != n:
            raise InvalidProblem(f"{source}: a set over {problem.colors} colours has {n} {kind} tiles")
        arrays[kind] = [read_points(t, f"tiles.{kind}[{i}]", source, 4 * problem.points + 16, 3)
                        for i, t in enumerate(tiles[kind])]
    return problem, built_set(doc, source,
                              lambda seed, stats: PoissonSphereTileSet(problem, arrays, seed=seed, stats=stats))


def window_to_dict(problem: PoissonSphereWindowProblem, solution: Solution) -> dict:
    """The version 2 document of a box (``solution.tiling`` is the :class:`PoissonSphereWindow`),
    its set embedded."""
    ts = problem.tileset
    return {"format": WINDOW_FORMAT, "version": 2, **_problem(ts.problem),
            "box": problem.box.to_dict(), "hash": problem.hash, "seed": solution.seed,
            "tileset": tiles_to_dict(ts.problem, Solution(Status.SAT, ts, method="dart", seed=ts.seed)),
            "local": solution.tiling.local}


def window_from_dict(doc: dict, source: str = "<document>") -> tuple[PoissonSphereProblem, Solution]:
    """Read :func:`window_to_dict`'s document. Version 2: the box's problem (its set read from
    ``tileset``) and a :class:`SeededBox`; version 1: the set's problem and the points (spacing
    alone can be checked, :func:`tilesolve.verify.poisson_sphere.point_violations3`)."""
    v2 = isinstance(doc, dict) and doc.get("version") == 2
    fields = _WINDOW_KEYS if v2 else _WINDOW_KEYS - {"tileset"}
    check_document(doc, source, {WINDOW_FORMAT: WINDOW_VERSIONS}, fields=fields,
                   required=("box", "local", "tileset", "seed") if v2 else ("box", "local"))
    problem = _read_problem(doc, source)
    box = Box.from_dict(doc["box"])
    local = read_points(doc["local"], "local", source, MAX_WINDOW_POINTS, 3)
    seed = read_seed(doc, source)
    if not v2:
        return problem, Solution(Status.SAT, PoissonSphereWindow(box, local, problem.distance), method="window",
                                 seed=seed)
    tileset = embedded_set(doc, source, problem, tiles_from_dict)
    try:
        wp = PoissonSphereWindowProblem(tileset, box, doc.get("hash", "long"))
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: {exc}") from None
    return wp, Solution(Status.SAT, SeededBox(box, local, problem.distance, seed), method="window", seed=seed)


def dump(doc: dict) -> str:
    """JSON text: a tile's points on one line, a box's one point a line, its embedded set as a
    set is written (floats round-trip)."""
    def line(rows) -> str:
        return "[" + ", ".join(f"[{x!r}, {y!r}, {z!r}]" for x, y, z in rows) + "]"

    head = {k: v for k, v in doc.items() if k not in ("tiles", "tileset", "local")}
    text = json.dumps(head, indent=2)[:-2]
    if "tileset" in doc:
        text += ',\n  "tileset": ' + dump(doc["tileset"]).rstrip("\n").replace("\n", "\n  ")
    if "tiles" in doc:
        kinds = [f'    "{k}": [\n' + ",\n".join("      " + line(t) for t in doc["tiles"][k]) + "\n    ]"
                 for k in KINDS]
        text += ',\n  "tiles": {\n' + ",\n".join(kinds) + "\n  }"
    if "local" in doc:
        rows = np.asarray(doc["local"]).tolist()
        text += ',\n  "local": [' + ",".join(f"\n    [{x!r}, {y!r}, {z!r}]" for x, y, z in rows)
        text += "\n  ]" if rows else "]"
    return text + "\n}\n"


def check_point_output3(path: str | os.PathLike, box: Box) -> str:
    """The format of a points file, from its suffix; refuses CSV and NPY for a box beyond
    ``+-2**31`` (before any work is done)."""
    suffix = os.fspath(path).rsplit(".", 1)[-1].lower()
    if suffix not in POINT_FORMATS:
        raise InvalidProblem(f"cannot tell the format of {os.fspath(path)!r}: use .json, .csv or .npy")
    far = max(max(abs(lo), abs(lo + n)) for lo, n in zip(box.origin, box.size))
    if suffix != "json" and far > FLOAT_RANGE:
        raise InvalidProblem(f"the box lies beyond +-2**31, where {suffix.upper()} coordinates lose precision: "
                             "write .json (points relative to the box's corner)")
    return suffix


def write_points3(path: str | os.PathLike, problem: PoissonSphereWindowProblem, solution: Solution) -> None:
    """Write a box's points: ``.json`` (:func:`window_to_dict`), ``.csv`` or ``.npy``."""
    suffix = check_point_output3(path, problem.box)
    if suffix == "json":
        write_text_atomic(path, dump(window_to_dict(problem, solution)))
        return
    pts = solution.tiling.absolute()
    if suffix == "npy":
        buf = io.BytesIO()
        np.save(buf, pts)
        write_bytes_atomic(path, buf.getvalue())
    else:
        buf = io.StringIO()
        buf.write("x,y,z\n")
        np.savetxt(buf, pts, fmt="%.17g", delimiter=",")
        write_text_atomic(path, buf.getvalue())
