"""The ``tilesolve/packing`` file (version 1): a tile packing and its provenance.

::

    {
      "format": "tilesolve/packing", "version": 1,
      "kind": "corner",                 # or "wang"
      "colors": 3,                      # C (C_h for Wang tiles with "colors_v")
      "colors_v": 4,                    # optional, Wang tiles only
      "fixed": [[0, 0, 40]],            # optional pinned tiles: [row, col, tile]
      "status": "sat",                  # sat, unsat, unknown
      "grid": [[...], ...],             # C**2 rows (top to bottom; row r-1 north of row r) of
                                        # C**2 tile indices (eq. 2.1 Wang N E S W, eq. 2.5 corner
                                        # NE SE SW NW); the torus wraps both ways; null without one
      "method": "sat", "solver": "glucose42", "seed": 1, "time_s": 0.1,
      "reason": null, "notes": [], "stats": {}
    }

Readers reject unknown fields and malformed values with one line naming the file and field;
the grid itself is *not* checked here (that is :func:`tilesolve.verify.packing.packing_violations`'
job, so ``tilesolve verify`` can list a bad file's violations).
"""

from __future__ import annotations

import os
from typing import Any

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.io.atomic import write_text_atomic
from tilesolve.io.jsonio import check_document, dumps, load_document, provenance_to_dict, solution_from_provenance
from tilesolve.model.packing import PackingProblem
from tilesolve.model.solution import Solution

__all__ = ["PACKING", "packing_to_dict", "packing_from_dict", "write_packing", "read_packing"]

PACKING = "tilesolve/packing"
#: Versions of the packing format this module reads and writes.
VERSIONS = frozenset({1})

_KEYS = {"format", "version", "kind", "colors", "colors_v", "fixed", "status", "grid", "method", "solver", "seed",
         "time_s", "reason", "notes", "stats", "created_by", "comment"}


def packing_to_dict(problem: PackingProblem, solution: Solution) -> dict:
    """The JSON document of a packing solution (grids stay numpy arrays for :func:`dumps`)."""
    doc: dict[str, Any] = {"format": PACKING, "version": 1, "kind": problem.kind, "colors": problem.colors}
    if problem.colors_v is not None:
        doc["colors_v"] = problem.colors_v
    if problem.fixed:
        doc["fixed"] = [list(f) for f in problem.fixed]
    doc.update({
        **provenance_to_dict(solution),
        "grid": None if solution.tiling is None else np.asarray(solution.tiling, dtype=np.int64),
    })
    return doc


def _int(doc: dict, key: str, source: Any, default=None):
    v = doc.get(key, default)
    if v is default:
        return v
    if isinstance(v, bool) or not isinstance(v, int):
        raise InvalidProblem(f"{source}: '{key}' must be an integer, got {v!r}")
    return v


def packing_from_dict(doc: dict, source: Any = "<document>") -> tuple[PackingProblem, Solution]:
    """Rebuild ``(problem, solution)`` from a ``tilesolve/packing`` document.

    Examples
    --------
    >>> doc = {"format": "tilesolve/packing", "version": 1, "kind": "wang", "colors": 2,
    ...        "grid": [[0] * 4] * 4}
    >>> p, s = packing_from_dict(doc)
    >>> p.kind, s.status.value, s.tiling.shape
    ('wang', 'sat', (4, 4))
    """
    check_document(doc, source, {PACKING: VERSIONS}, fields=_KEYS, required=("kind", "colors"))
    kind = doc["kind"]
    colors = _int(doc, "colors", source)
    colors_v = _int(doc, "colors_v", source)
    fixed = doc.get("fixed") or []
    if not isinstance(fixed, list) or not all(isinstance(f, list) and len(f) == 3 for f in fixed):
        raise InvalidProblem(f"{source}: 'fixed' must be a list of [row, col, tile]")
    try:
        problem = PackingProblem(kind, colors, colors_v, tuple(tuple(f) for f in fixed))
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: {exc}") from None
    grid = doc.get("grid")
    if grid is not None:
        if not isinstance(grid, list) or not all(isinstance(r, list) for r in grid) or \
                not all(type(v) is int and -2**63 <= v < 2**63 for r in grid for v in r):
            raise InvalidProblem(f"{source}: 'grid' must be a list of rows of integer tile indices")
        if len({len(r) for r in grid}) > 1:
            raise InvalidProblem(f"{source}: 'grid' rows have different lengths")
        grid = np.asarray(grid, dtype=np.int64)
        if grid.size == 0:
            raise InvalidProblem(f"{source}: 'grid' is empty")
    sol = solution_from_provenance(doc, source, grid, what="grid",
                                   default_status="sat" if grid is not None else "unknown")
    return problem, sol


def write_packing(path: str | os.PathLike, problem: PackingProblem, solution: Solution) -> None:
    """Write a packing file atomically ('-' writes to stdout)."""
    write_text_atomic(path, dumps(packing_to_dict(problem, solution)))


def read_packing(path: str | os.PathLike) -> tuple[PackingProblem, Solution]:
    """Read a ``tilesolve/packing`` file."""
    return packing_from_dict(load_document(path, {PACKING: VERSIONS}), path)
