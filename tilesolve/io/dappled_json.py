"""The dappled codec: ``tilesolve/dappled-problem`` and ``tilesolve/dappled-solution`` files
(through the shared helpers of :mod:`tilesolve.io.jsonio`), and plain-text tiling grids.

Dappled formats, version 1
--------------------------
``tilesolve/dappled-problem``::

    {
      "format": "tilesolve/dappled-problem", "version": 1,
      "size": {"rows": 4, "cols": 6},          # or "6x4" (W x H)
      "n_tiles": 2,
      "conditions": ["H0=2", "V1=3", "H{0,2}=3", "V1=inf",
                     {"axis": "H", "tiles": [0], "limit": [[2, 2, 3], ...]}],  # per-cell, 0 = none
      "cyclic": false,
      "fixed": [[0, -1, 1], ...],              # optional partial tiling, -1 = free
      "counts": ["1=8", "0=4..10"],            # optional global tile counts
      "closest_to": [[0, 1, 1], ...]           # optional target tiling
    }

``tilesolve/dappled-solution`` has every problem field plus ``"status"`` (sat, unsat,
optimal, unknown), ``"tiling"`` (rows top to bottom, or null), ``"method"``, ``"solver"``,
``"seed"``, ``"time_s"``, ``"objective"``, ``"reason"``, ``"notes"`` and ``"stats"``.
Tilings are ``tiling[row][col]`` with row 0 at the top.

Dappled solutions, version 2
----------------------------
Solutions of grids of more than :data:`~tilesolve.io.jsonio.COMPACT_MIN_CELLS` cells are written as version 2
of ``tilesolve/dappled-solution``: the fields of version 1, with every grid (``tiling``,
``fixed``, ``closest_to`` and the ``limit`` of per-cell conditions) an *encoded array*
(:mod:`tilesolve.io.jsonio`) instead of a list of rows. Readers take both versions.

Text grids
----------
One row per line, top row first; a cell is a digit, or ``?`` / ``.`` for a free cell in a
partial tiling. Rows may instead be whitespace- or comma-separated numbers (for 10 or more
tiles). Blank lines and lines starting with ``#`` are ignored::

    # a 4x3 partial tiling
    01?1
    ?..0
    1100
"""

from __future__ import annotations

import os
import re
from typing import Any, Callable

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.inputs import read_input_text
from tilesolve.io.atomic import write_text_atomic
from tilesolve.io.jsonio import (
    COMPACT_MIN_CELLS,
    check_document,
    decode_array,
    dumps,
    encode_array,
    parse_json,
    provenance_to_dict,
    read_json,
    solution_from_provenance,
)
from tilesolve.model.dappled import Condition, DappledProblem, TileCount, parse_condition, parse_count, parse_size
from tilesolve.model.solution import Solution

__all__ = [
    "DAPPLED_FORMATS",
    "DAPPLED_PROBLEM",
    "DAPPLED_SOLUTION",
    "DAPPLED_SOLUTION_VERSIONS",
    "problem_to_dict",
    "problem_from_dict",
    "solution_to_dict",
    "solution_from_dict",
    "write_problem",
    "write_solution",
    "read_problem",
    "read_solution",
    "read_tiling",
    "parse_text_grid",
    "format_text_grid",
]

DAPPLED_PROBLEM = "tilesolve/dappled-problem"
DAPPLED_SOLUTION = "tilesolve/dappled-solution"

#: Versions of ``tilesolve/dappled-solution`` this module reads (problems are version 1).
DAPPLED_SOLUTION_VERSIONS = frozenset({1, 2})
#: The dappled formats and the versions this module reads (each io module checks its own).
DAPPLED_FORMATS: dict[str, frozenset[int]] = {
    DAPPLED_PROBLEM: frozenset({1}),
    DAPPLED_SOLUTION: DAPPLED_SOLUTION_VERSIONS,
}

_PROBLEM_KEYS = {"format", "version", "size", "n_tiles", "conditions", "cyclic", "fixed", "counts", "closest_to"}
_SOLUTION_KEYS = _PROBLEM_KEYS | {
    "status", "tiling", "method", "solver", "seed", "time_s", "objective", "reason", "notes", "stats",
}
_INFO_KEYS = {"created_by", "comment"}  # free text any file may carry


# ----------------------------------------------------------------------------- problems
def _condition_to_json(cond: Condition, grid: Callable[[np.ndarray], Any]) -> Any:
    if cond.is_uniform:
        return str(cond)
    return {"axis": cond.axis, "tiles": list(cond.tiles), "limit": grid(cond.limit)}


def problem_to_dict(problem: DappledProblem, *, format: str = DAPPLED_PROBLEM, arrays: bool = False,
                    compact: bool = False) -> dict:
    """The JSON document of ``problem`` (format ``tilesolve/dappled-problem``, version 1).

    With ``arrays=True`` grids stay numpy arrays (for :func:`dumps`, which writes them fast);
    with ``compact=True`` (solutions only) they are encoded arrays, in version 2.
    """
    if compact and format != DAPPLED_SOLUTION:
        raise ValueError("only solution documents have a compact version")
    grid: Callable[[np.ndarray], Any]
    grid = encode_array if compact else (lambda a: a) if arrays else (lambda a: a.tolist())  # noqa: E731
    from tilesolve import __version__

    doc: dict[str, Any] = {
        "format": format,
        "version": 2 if compact else 1,
        "created_by": f"tilesolve {__version__}",
        "size": {"rows": problem.rows, "cols": problem.cols},
        "n_tiles": problem.n_tiles,
        "conditions": [_condition_to_json(c, grid) for c in problem.conditions],
        "cyclic": problem.cyclic,
    }
    if problem.fixed is not None:
        doc["fixed"] = grid(problem.fixed)
    if problem.counts:
        doc["counts"] = [str(k) for k in problem.counts]
    if problem.closest_to is not None:
        doc["closest_to"] = grid(problem.closest_to)
    return doc


def problem_from_dict(doc: dict, source: Any = "<document>") -> DappledProblem:
    """Rebuild a :class:`DappledProblem` from a problem or solution document.

    Raises
    ------
    InvalidProblem
        On a missing or malformed field, with the field's name.
    """
    version = _dappled_header(doc, source, (DAPPLED_PROBLEM, DAPPLED_SOLUTION))
    allowed = (_SOLUTION_KEYS if doc["format"] == DAPPLED_SOLUTION else _PROBLEM_KEYS) | _INFO_KEYS
    unknown = sorted(set(doc) - allowed)
    if unknown:
        raise InvalidProblem(f"{source}: unknown field {unknown[0]!r} in a {doc['format']} file")
    rows, cols = _size(doc, source)
    n_tiles = _int(doc.get("n_tiles", 2), "n_tiles", source)
    conditions = doc.get("conditions", [])
    if not isinstance(conditions, list):
        raise InvalidProblem(f"{source}: 'conditions' must be a list, e.g. [\"H0=2\", \"V1=3\"]")
    conds = tuple(_condition(c, i, source, version) for i, c in enumerate(conditions))
    cyclic = doc.get("cyclic", False)
    if not isinstance(cyclic, bool):
        raise InvalidProblem(f"{source}: 'cyclic' must be true or false, got {cyclic!r}")
    counts = doc.get("counts", [])
    if not isinstance(counts, list):
        raise InvalidProblem(f"{source}: 'counts' must be a list, e.g. [\"1=8\", \"0=4..10\"]")
    fixed = _opt_grid(doc.get("fixed"), "fixed", source, allow_free=True, version=version)
    closest = _opt_grid(doc.get("closest_to"), "closest_to", source, allow_free=False, version=version)
    try:
        return DappledProblem(
            rows,
            cols,
            n_tiles=n_tiles,
            conditions=conds,
            cyclic=cyclic,
            fixed=fixed,
            counts=tuple(_count(k, source) for k in counts),
            closest_to=closest,
        )
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: {exc}") from None


def _dappled_header(doc: Any, source: Any, formats: tuple[str, ...]) -> int:
    """The document's version, once its header is one of ``formats`` (dappled formats)."""
    return check_document(doc, source, {f: DAPPLED_FORMATS[f] for f in formats})["version"]


def _size(doc: dict, source: Any) -> tuple[int, int]:
    size = doc.get("size")
    if isinstance(size, str):
        try:
            return parse_size(size)
        except InvalidProblem as exc:
            raise InvalidProblem(f"{source}: 'size': {exc}") from None
    if not isinstance(size, dict) or set(size) != {"rows", "cols"}:
        raise InvalidProblem(f"{source}: 'size' must be {{\"rows\": R, \"cols\": C}} or \"WxH\", got {size!r}")
    return _int(size["rows"], "size.rows", source), _int(size["cols"], "size.cols", source)


def _int(value: Any, name: str, source: Any) -> int:
    if isinstance(value, bool) or not isinstance(value, int):
        raise InvalidProblem(f"{source}: {name!r} must be an integer, got {value!r}")
    return value


def _condition(c: Any, i: int, source: Any, version: int = 1) -> Condition:
    try:
        if isinstance(c, str):
            return parse_condition(c)
        if isinstance(c, dict):
            if not {"axis", "tiles", "limit"} <= set(c) or set(c) - {"axis", "tiles", "limit"}:
                raise InvalidProblem("expected a string like \"H0=2\" or {\"axis\", \"tiles\", \"limit\"}")
            tiles = c["tiles"]
            tiles = [tiles] if isinstance(tiles, int) and not isinstance(tiles, bool) else tiles
            if not isinstance(tiles, list) or not all(isinstance(t, int) and not isinstance(t, bool) for t in tiles):
                raise InvalidProblem(f"'tiles' must be a tile number or a list of them, got {c['tiles']!r}")
            limit = c["limit"]
            if isinstance(limit, list) or (version >= 2 and isinstance(limit, dict)):
                limit = _grid(limit, "limit", allow_free=False)
            elif limit in ("inf", "∞", None):
                limit = None
            elif isinstance(limit, bool) or not isinstance(limit, int):
                raise InvalidProblem(f"'limit' must be an integer, \"inf\" or a grid of integers, got {limit!r}")
            return Condition(str(c["axis"]), tuple(tiles), limit)
        raise InvalidProblem(f"expected a string like \"H0=2\", got {c!r}")
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: conditions[{i}]: {exc}") from None


def _count(k: Any, source: Any) -> TileCount:
    try:
        if isinstance(k, str):
            return parse_count(k)
        if isinstance(k, dict) and "tile" in k and not set(k) - {"tile", "low", "high"}:
            vals = [k["tile"], k.get("low", 0), k.get("high")]
            if all((isinstance(v, int) and not isinstance(v, bool)) or (v is None and j == 2) for j, v in enumerate(vals)):
                return TileCount(*vals)
        raise InvalidProblem(f"expected a string like \"1=8\" or \"1=4..10\", got {k!r}")
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: counts: {exc}") from None


def _grid(value: Any, what: str, *, allow_free: bool) -> np.ndarray:
    """A rectangular list of lists of ints, or an encoded array, as an int64 array
    (``-1`` allowed if ``allow_free``)."""
    if isinstance(value, dict):
        arr = decode_array(value, what, "", ndim=2)
        if arr.size == 0:
            raise InvalidProblem(f"{what!r} must be a non-empty grid")
    else:
        if not isinstance(value, list) or not value or not all(isinstance(r, list) for r in value):
            raise InvalidProblem(f"{what!r} must be a non-empty list of rows (lists of tile numbers)")
        types: set[type] = set()
        for row in value:
            types.update(map(type, row))
        try:
            arr = np.array(value) if types == {int} else None
        except (ValueError, OverflowError):
            arr = None
        if arr is None or arr.ndim != 2 or not arr.size:
            _grid_error(value, what)
    low = -1 if allow_free else 0
    if arr.min() < low or arr.max() > 2**31:
        r, c = np.argwhere((arr < low) | (arr > 2**31))[0]
        raise InvalidProblem(f"{what!r}: row {r}, col {c} holds {arr[r, c]}, not a tile number")
    return arr


def _grid_error(value: list, what: str) -> None:
    """Raise the one-line error for the first thing wrong in a list of rows."""
    width = len(value[0])
    for r, row in enumerate(value):
        if len(row) != width or not row:
            raise InvalidProblem(f"{what!r}: row {r} has {len(row)} cells, row 0 has {width}")
        for c, v in enumerate(row):
            if isinstance(v, bool) or not isinstance(v, int):
                raise InvalidProblem(f"{what!r}: row {r}, col {c} holds {v!r}, not a tile number")
    raise InvalidProblem(f"{what!r} must be a grid of tile numbers")


def _opt_grid(value: Any, what: str, source: Any, *, allow_free: bool, version: int = 1) -> np.ndarray | None:
    if value is None:
        return None
    if isinstance(value, dict) and version < 2:
        raise InvalidProblem(f"{source}: {what!r} must be a list of rows (encoded arrays need version 2)")
    try:
        return _grid(value, what, allow_free=allow_free)
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: {str(exc).removeprefix(': ')}") from None


# ----------------------------------------------------------------------------- solutions
def solution_to_dict(problem: DappledProblem, solution: Solution, *, arrays: bool = False,
                     compact: bool | None = None) -> dict:
    """The JSON document of a solution, carrying its whole problem (``tilesolve/dappled-solution``).

    With ``arrays=True`` grids stay numpy arrays (for :func:`dumps`, which writes them fast).
    ``compact`` writes version 2 (grids as encoded arrays); by default, for grids of more
    than :data:`COMPACT_MIN_CELLS` cells.
    """
    if compact is None:
        compact = problem.rows * problem.cols > COMPACT_MIN_CELLS
    doc = problem_to_dict(problem, format=DAPPLED_SOLUTION, arrays=arrays, compact=compact)
    tiling = None if solution.tiling is None else np.asarray(solution.tiling)
    doc.update(provenance_to_dict(solution))
    doc["objective"] = solution.objective
    if tiling is not None:
        tiling = encode_array(tiling) if compact else tiling if arrays else tiling.tolist()
    doc["tiling"] = tiling
    return doc


def solution_from_dict(doc: dict, source: Any = "<document>") -> tuple[DappledProblem, Solution]:
    """Rebuild ``(problem, solution)`` from a solution document.

    The tiling is read as written (any rectangular grid of integers): checking it against
    the problem is the verifier's job, so a corrupted tiling is reported there, with positions.
    """
    version = _dappled_header(doc, source, (DAPPLED_SOLUTION,))
    problem = problem_from_dict(doc, source)
    tiling = _opt_grid(doc.get("tiling"), "tiling", source, allow_free=True, version=version)
    return problem, solution_from_provenance(doc, source, tiling)


# ----------------------------------------------------------------------------- files
def write_problem(path: str | os.PathLike, problem: DappledProblem) -> None:
    """Write a ``tilesolve/dappled-problem`` file atomically."""
    write_text_atomic(path, dumps(problem_to_dict(problem, arrays=True)))


def write_solution(path: str | os.PathLike, problem: DappledProblem, solution: Solution, *,
                   compact: bool | None = None) -> None:
    """Write a ``tilesolve/dappled-solution`` file atomically (``compact`` as in :func:`solution_to_dict`)."""
    write_text_atomic(path, dumps(solution_to_dict(problem, solution, arrays=True, compact=compact)))


def read_problem(path: str | os.PathLike) -> DappledProblem:
    """Read the problem of a problem *or* solution file."""
    return problem_from_dict(read_json(path), path)


def read_solution(path: str | os.PathLike) -> tuple[DappledProblem, Solution]:
    """Read a solution file (version 1 or 2) as ``(problem, solution)``."""
    return solution_from_dict(read_json(path), path)


def read_tiling(path: str | os.PathLike, *, allow_free: bool = False, what: str = "tiling") -> np.ndarray:
    """Read a tiling from a solution file, a problem file, a JSON grid or a text grid.

    Parameters
    ----------
    path : path-like
        A ``tilesolve/dappled-solution`` file (its ``tiling``), a ``tilesolve/dappled-problem``
        file (its ``fixed`` cells, when ``allow_free``), a JSON list of rows, or a text grid.
    allow_free : bool
        Accept free cells (``?``, ``.`` or ``-1``), returned as ``-1``: a partial tiling.
    what : str
        How error messages name the tiling.

    Returns
    -------
    numpy.ndarray
        int64 array ``[row, col]``; tile range and shape are checked by the problem.
    """
    text = read_input_text(path)
    stripped = text.lstrip()
    if stripped.startswith(("{", "[")):
        doc = parse_json(text, path)
        if isinstance(doc, list):
            return _opt_grid(doc, what, path, allow_free=allow_free)
        _dappled_header(doc, path, (DAPPLED_PROBLEM, DAPPLED_SOLUTION))
        if doc["format"] == DAPPLED_SOLUTION:
            _, sol = solution_from_dict(doc, path)
            if sol.tiling is None:
                raise InvalidProblem(f"{path}: this solution (status {sol.status.value}) holds no tiling")
            if (sol.tiling < 0).any():
                raise InvalidProblem(f"{path}: 'tiling' has free cells (-1)")
            return sol.tiling
        problem = problem_from_dict(doc, path)
        if allow_free and problem.fixed is not None:
            return problem.fixed.astype(np.int64)
        raise InvalidProblem(
            f"{path}: a problem file holds no {what}; give a solution file or a text grid"
        )
    try:
        return parse_text_grid(text, allow_free=allow_free, what=what)
    except InvalidProblem as exc:
        raise InvalidProblem(f"{path}: {exc}") from None


_FREE = {"?", ".", "-1"}
_SPLIT = re.compile(r"[\s,]+")


def parse_text_grid(text: str, *, allow_free: bool = False, what: str = "tiling") -> np.ndarray:
    """Parse a text grid (see the module docstring); free cells become ``-1``.

    >>> parse_text_grid("01?\\n110", allow_free=True).tolist()
    [[0, 1, -1], [1, 1, 0]]
    >>> parse_text_grid("10 11\\n0 2").tolist()
    [[10, 11], [0, 2]]
    """
    rows: list[list[int]] = []
    for lineno, raw in enumerate(text.splitlines(), start=1):
        line = raw.strip()
        if not line or line.startswith("#"):
            continue
        tokens = [t for t in _SPLIT.split(line) if t] if _SPLIT.search(line) else list(line)
        row = []
        for tok in tokens:
            if tok in _FREE:
                if not allow_free:
                    raise InvalidProblem(f"line {lineno}: free cell {tok!r} in a {what}, which must be complete")
                row.append(-1)
            elif tok.isdigit() and tok.isascii() and len(tok) <= 18:
                row.append(int(tok))
            else:
                free = ", '?' or '.' for a free cell" if allow_free else ""
                raise InvalidProblem(f"line {lineno}: cannot read cell {tok[:20]!r}: expected a tile number{free}")
        if rows and len(row) != len(rows[0]):
            raise InvalidProblem(f"line {lineno}: row has {len(row)} cells, the first row has {len(rows[0])}")
        rows.append(row)
    if not rows:
        raise InvalidProblem(f"the {what} is empty: expected one row of tile numbers per line")
    return np.array(rows, dtype=np.int64)


def format_text_grid(tiling: np.ndarray) -> str:
    """The tiling as a text grid: digits when every tile is below 10, else space-separated.

    >>> print(format_text_grid(np.array([[0, 1], [-1, 0]])), end="")
    01
    ?0
    """
    t = np.asarray(tiling)
    wide = t.size and int(t.max()) >= 10
    sym: Callable[[int], str] = lambda v: "?" if v < 0 else str(v)  # noqa: E731
    sep = " " if wide else ""
    return "".join(sep.join(sym(int(v)) for v in row) + "\n" for row in t)
