"""The ``tilesolve/shapes`` file (version 1): a polyform question and its answer.

::

    {
      "format": "tilesolve/shapes", "version": 1,
      "question": "tile",                # or "classify"
      "grid": "hex",                     # omino, hex, iamond (cell coordinates: tilesolve.model.shapes)
      "shapes": [[[0, 0], [1, 0]], ...], # cells of each shape
      "region": [[x, y], ...],           # tile: the cells to cover, or
      "lattice": [[a, b], [c, d]],       # tile: the torus's periods (translation units)
      "reflections": true, "max_level": 3, "max_copies": 2, "holes": false,
      "status": "sat", "method": "sat", "solver": "cadical153", "seed": 1, "time_s": 0.1,
      "reason": null, "notes": [], "stats": {},
      "tiling": [[piece, shape, x, y], ...],     # tile: one row per cell of each piece
      "report": {"verdict": "non-tiler", "heesch": 1, "copies": null, "lattice": null,
                 "tiling": [[piece, 0, x, y], ...], "patch": [[piece, level, x, y], ...],
                 "refutation": {...}, "holes": false}    # classify
    }

Readers reject unknown fields and malformed values with one line naming the file and field; the
tiling and report themselves are checked by :mod:`tilesolve.verify.shapes`.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.io.jsonio import check_document, provenance_to_dict, solution_from_provenance
from tilesolve.model.shapes import Polyform, ShapesProblem, ShapesReport
from tilesolve.model.solution import Solution

__all__ = ["SHAPES", "VERSIONS", "shapes_to_dict", "shapes_from_dict", "problem_to_dict"]

SHAPES = "tilesolve/shapes"
#: Versions of the shapes format this module reads and writes.
VERSIONS = frozenset({1})

_KEYS = {"format", "version", "question", "grid", "shapes", "region", "lattice", "reflections", "max_level",
         "max_copies", "holes", "status", "method", "solver", "seed", "time_s", "reason", "notes", "stats",
         "tiling", "report", "created_by", "comment"}
_REPORT_KEYS = {"verdict", "heesch", "copies", "lattice", "tiling", "patch", "refutation", "holes"}


def problem_to_dict(problem: ShapesProblem) -> dict:
    """The problem's fields of the document."""
    doc: dict[str, Any] = {"format": SHAPES, "version": 1, "question": problem.question,
                           "grid": problem.shapes[0].grid, "shapes": [[list(c) for c in s.cells] for s in problem.shapes]}
    if problem.region is not None:
        doc["region"] = [list(c) for c in problem.region]
    if problem.lattice is not None:
        doc["lattice"] = [list(v) for v in problem.lattice]
    doc.update(reflections=problem.reflections, max_level=problem.max_level, max_copies=problem.max_copies,
               holes=problem.holes)
    return doc


def _rows(a) -> list | None:
    return None if a is None else np.asarray(a, dtype=np.int64).tolist()


def shapes_to_dict(problem: ShapesProblem, solution: Solution) -> dict:
    """The JSON document of a polyform answer."""
    doc = problem_to_dict(problem)
    doc.update(provenance_to_dict(solution))
    doc["tiling"] = _rows(solution.tiling)
    r = solution.report
    if r is not None:
        doc["report"] = {"verdict": r.verdict, "heesch": r.heesch, "copies": r.copies,
                         "lattice": None if r.lattice is None else [list(v) for v in r.lattice],
                         "tiling": _rows(r.tiling), "patch": _rows(r.patch), "refutation": r.refutation,
                         "holes": r.holes}
    return doc


def _pairs(value, source, key) -> tuple:
    if not isinstance(value, list) or not all(isinstance(c, list) and len(c) == 2 and
                                              all(type(v) is int for v in c) for c in value):
        raise InvalidProblem(f"{source}: '{key}' must be a list of [x, y] integer pairs")
    return tuple(tuple(c) for c in value)


def _table(value, source, key):
    if value is None:
        return None
    if not isinstance(value, list) or not value or not all(
            isinstance(r, list) and len(r) == 4 and all(type(v) is int and abs(v) < 2**62 for v in r) for r in value):
        raise InvalidProblem(f"{source}: '{key}' must be a non-empty list of [piece, label, x, y] integer rows")
    return np.asarray(value, dtype=np.int64)


def _flag(doc, key, source, default):
    v = doc.get(key, default)
    if not isinstance(v, bool):
        raise InvalidProblem(f"{source}: '{key}' must be true or false")
    return v


def _int(doc, key, source, default):
    v = doc.get(key, default)
    if isinstance(v, bool) or not isinstance(v, int):
        raise InvalidProblem(f"{source}: '{key}' must be an integer")
    return v


def shapes_from_dict(doc: dict, source: Any = "<document>") -> tuple[ShapesProblem, Solution | None]:
    """Rebuild ``(problem, solution)`` from a ``tilesolve/shapes`` document (solution ``None``
    for a problem-only file, one without ``status``).

    Examples
    --------
    >>> doc = {"format": "tilesolve/shapes", "version": 1, "question": "tile", "grid": "omino",
    ...        "shapes": [[[0, 0], [1, 0]]], "region": [[0, 0], [1, 0]]}
    >>> p, s = shapes_from_dict(doc)
    >>> p.describe(), s
    ('tile a region of 2 cells with polyomino of 2 cells', None)
    """
    check_document(doc, source, {SHAPES: VERSIONS})
    extra = sorted(set(doc) - _KEYS)
    if extra:
        raise InvalidProblem(f"{source}: unknown field{'s' if len(extra) > 1 else ''} {', '.join(map(repr, extra))}")
    for key in ("question", "grid", "shapes"):
        if key not in doc:
            raise InvalidProblem(f"{source}: missing field '{key}'")
    if not isinstance(doc["shapes"], list) or not doc["shapes"]:
        raise InvalidProblem(f"{source}: 'shapes' must be a non-empty list of cell lists")
    if not isinstance(doc["grid"], str):
        raise InvalidProblem(f"{source}: 'grid' must be a string")
    try:
        shapes = tuple(Polyform(doc["grid"], _pairs(s, source, "shapes")) for s in doc["shapes"])
        region = None if doc.get("region") is None else _pairs(doc["region"], source, "region")
        lattice = None if doc.get("lattice") is None else _pairs(doc["lattice"], source, "lattice")
        problem = ShapesProblem(doc["question"], shapes, region, lattice, _flag(doc, "reflections", source, True),
                                _int(doc, "max_level", source, 3), _int(doc, "max_copies", source, 2),
                                _flag(doc, "holes", source, False))
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: {exc}") from None
    if "status" not in doc:
        return problem, None
    tiling = _table(doc.get("tiling"), source, "tiling")
    report = _report(doc.get("report"), source)
    sol = solution_from_provenance(doc, source, tiling if report is None else report)
    return problem, sol.replace(tiling=tiling, report=report)


def _report(value, source) -> ShapesReport | None:
    if value is None:
        return None
    if not isinstance(value, dict):
        raise InvalidProblem(f"{source}: 'report' must be an object")
    extra = sorted(set(value) - _REPORT_KEYS)
    if extra:
        raise InvalidProblem(f"{source}: unknown report field {extra[0]!r}")
    if not isinstance(value.get("verdict"), str):
        raise InvalidProblem(f"{source}: report 'verdict' must be a string")
    for key in ("heesch", "copies"):
        v = value.get(key)
        if v is not None and (isinstance(v, bool) or not isinstance(v, int)):
            raise InvalidProblem(f"{source}: report '{key}' must be an integer or null")
    ref = value.get("refutation")
    if ref is not None and not isinstance(ref, dict):
        raise InvalidProblem(f"{source}: report 'refutation' must be an object or null")
    lattice = value.get("lattice")
    lattice = None if lattice is None else _pairs(lattice, source, "report lattice")
    return ShapesReport(value["verdict"], value.get("heesch"), value.get("copies"), lattice,
                        _table(value.get("tiling"), source, "report tiling"),
                        _table(value.get("patch"), source, "report patch"), ref,
                        _flag(value, "holes", source, False))
