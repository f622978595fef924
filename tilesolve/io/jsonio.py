"""Versioned JSON files for problems and solutions, and plain-text tiling grids.

Every file carries ``"format": "tilesolve/<kind>"`` and ``"version"`` (DESIGN.md, "Files").
Readers accept only the formats and versions in :data:`FORMATS` and turn anything malformed
into one :class:`~tilesolve.errors.InvalidProblem` line naming the file and the field.
Writers go through :mod:`tilesolve.io.atomic`.

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
Solutions of grids of more than :data:`COMPACT_MIN_CELLS` cells are written as version 2
of ``tilesolve/dappled-solution``: the fields of version 1, with every grid (``tiling``,
``fixed``, ``closest_to`` and the ``limit`` of per-cell conditions) an *encoded array*
(below) instead of a list of rows. Readers take both versions.

Compact arrays
--------------
Large grids travel as *encoded arrays* (in ``tilesolve/board-solution`` version 2 and
``tilesolve/dappled-solution`` version 2)::

    {"dtype": "uint8", "shape": [4096, 4096], "data": "AAEBAAEAAQ..."}

``data`` is standard base64 (RFC 4648, with padding) of the array's values in row-major
(C) order. ``dtype`` is one of ``int8``, ``uint8``, ``int16``, ``uint16``, ``int32``,
``uint32``, ``int64`` (little-endian, ``itemsize`` bytes per value) or ``bits``: values 0/1
packed eight to a byte, the first value in the most significant bit, the last byte padded
with zeros (``numpy.packbits``). In Python::

    raw = base64.b64decode(a["data"])
    if a["dtype"] == "bits":
        v = numpy.unpackbits(numpy.frombuffer(raw, numpy.uint8), count=prod(a["shape"]))
    else:
        v = numpy.frombuffer(raw, "<" + numpy.dtype(a["dtype"]).str[1:])
    v = v.reshape(a["shape"])

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

import base64
import binascii
import json
import math
import os
import re
from typing import Any, Callable, Iterable, Mapping

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.inputs import read_input_text
from tilesolve.io.atomic import write_text_atomic
from tilesolve.model.dappled import Condition, DappledProblem, TileCount, parse_condition, parse_count, parse_size
from tilesolve.model.solution import Solution, Status

__all__ = [
    "DAPPLED_FORMATS",
    "DAPPLED_PROBLEM",
    "DAPPLED_SOLUTION",
    "load_document",
    "provenance_to_dict",
    "check_time_s",
    "solution_from_provenance",
    "read_json",
    "parse_json",
    "dumps",
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
    "encode_array",
    "decode_array",
    "ARRAY_DTYPES",
    "DAPPLED_SOLUTION_VERSIONS",
    "COMPACT_MIN_CELLS",
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
#: Dappled solutions of more cells than this are written as version 2 (encoded arrays).
COMPACT_MIN_CELLS = 1 << 16

_PROBLEM_KEYS = {"format", "version", "size", "n_tiles", "conditions", "cyclic", "fixed", "counts", "closest_to"}
_SOLUTION_KEYS = _PROBLEM_KEYS | {
    "status", "tiling", "method", "solver", "seed", "time_s", "objective", "reason", "notes", "stats",
}
_INFO_KEYS = {"created_by", "comment"}  # free text any file may carry


# ----------------------------------------------------------------------------- documents
def load_document(path: str | os.PathLike, formats: Mapping[str, Iterable[int]]) -> dict:
    """Read a tilesolve JSON file and check its ``format`` and ``version``.

    Parameters
    ----------
    path : path-like
    formats : mapping
        The formats accepted here and the versions of each (the reading module's own;
        :func:`tilesolve.family.read_document` finds any family's format in the registry).

    Raises
    ------
    InvalidProblem
        The file is missing, not JSON, not a tilesolve file, or of an unknown format/version.
    """
    return check_document(read_json(path), path, formats=formats)


def check_document(doc: Any, source: Any, formats: Mapping[str, Iterable[int]]) -> dict:
    """Check the ``format``/``version`` header of an already-parsed document against
    ``formats`` (format name -> versions read)."""
    if not isinstance(doc, dict):
        raise InvalidProblem(f"{source}: not a tilesolve file (expected a JSON object with a 'format' field)")
    fmt = doc.get("format")
    if not isinstance(fmt, str):
        raise InvalidProblem(f"{source}: not a tilesolve file (no 'format' field)")
    if fmt not in formats:
        raise InvalidProblem(f"{source}: a {fmt!r} file cannot be used here; expected {' or '.join(sorted(formats))}")
    version = doc.get("version")
    if isinstance(version, bool) or not isinstance(version, int):
        raise InvalidProblem(f"{source}: 'version' must be an integer, got {version!r}")
    if version not in formats[fmt]:
        known = ", ".join(map(str, sorted(formats[fmt])))
        raise InvalidProblem(
            f"{source}: {fmt} version {version} is not supported (this tilesolve reads version {known}); "
            "upgrade tilesolve?"
        )
    return doc


def read_json(path: str | os.PathLike) -> Any:
    """Parse any JSON file (no tilesolve header required), with one-line errors.

    The file is read through :func:`read_input_text` (so at most :func:`max_input_bytes`).

    Raises
    ------
    InvalidProblem
        The file is missing, unreadable, larger than the input limit or not JSON (``NaN`` and
        ``Infinity`` are not JSON, and nor is a number too large for a double).
    """
    return parse_json(read_input_text(path), path)


class _NotJson(ValueError):
    """A value Python's parser takes but JSON does not have (NaN, Infinity, 1e999)."""


def _no_constant(name: str) -> float:
    raise _NotJson(f"{name} is not a JSON number")


def _finite_float(text: str) -> float:
    value = float(text)
    if not math.isfinite(value):
        raise _NotJson(f"the number {text[:20]} is too large")
    return value


def parse_json(text: str, source: Any) -> Any:
    """Parse JSON text strictly, with one-line errors naming ``source``.

    >>> parse_json('{"seed": NaN}', "s.json")
    Traceback (most recent call last):
    ...
    tilesolve.errors.InvalidProblem: s.json: malformed JSON: NaN is not a JSON number
    """
    try:
        return json.loads(text, parse_constant=_no_constant, parse_float=_finite_float)
    except json.JSONDecodeError as exc:
        raise InvalidProblem(f"{source}: malformed JSON at line {exc.lineno}, column {exc.colno}: {exc.msg}") from None
    except _NotJson as exc:
        raise InvalidProblem(f"{source}: malformed JSON: {exc}") from None
    except ValueError:  # an integer of more digits than Python converts (sys.get_int_max_str_digits)
        raise InvalidProblem(f"{source}: malformed JSON: a number has too many digits") from None
    except RecursionError:
        raise InvalidProblem(f"{source}: malformed JSON (nested too deeply)") from None


def dumps(doc: Any) -> str:
    """JSON text with one line per grid row, so tilings stay readable and diffable.

    >>> print(dumps({"tiling": [[0, 1], [1, 0]], "n_tiles": 2}), end="")
    {
      "tiling": [
        [0, 1],
        [1, 0]
      ],
      "n_tiles": 2
    }
    """
    return _dump(_plain(doc), 0) + "\n"


def _dump(obj: Any, level: int) -> str:
    pad, inner = "  " * level, "  " * (level + 1)
    if isinstance(obj, np.ndarray):  # a 2-D integer grid (see _plain)
        if obj.size == 0:
            return json.dumps(obj.tolist())
        rows = _grid_rows(obj)
        return "[\n" + ",\n".join(inner + r for r in rows) + "\n" + pad + "]"
    if isinstance(obj, dict):
        if not obj:
            return "{}"
        items = [f"{inner}{json.dumps(str(k))}: {_dump(v, level + 1)}" for k, v in obj.items()]
        return "{\n" + ",\n".join(items) + "\n" + pad + "}"
    if isinstance(obj, list) and obj and any(isinstance(v, (dict, list, np.ndarray)) for v in obj):
        return "[\n" + ",\n".join(inner + _dump(v, level + 1) for v in obj) + "\n" + pad + "]"
    if isinstance(obj, list) and all(type(v) is int for v in obj):  # fast path for grid rows
        return "[" + ", ".join(map(str, obj)) + "]"
    return json.dumps(obj, separators=(", ", ": "), ensure_ascii=False, allow_nan=False)


def _grid_rows(a: np.ndarray) -> list[str]:
    """``"[0, 1, 1]"`` for each row; single-digit grids are formatted by numpy in bulk."""
    if a.min() >= 0 and a.max() <= 9:
        cells = np.empty((a.shape[0], a.shape[1], 3), dtype=np.uint8)
        cells[:, :, 0] = a.astype(np.uint8) + ord("0")
        cells[:, :, 1], cells[:, :, 2] = ord(","), ord(" ")
        text = cells.reshape(a.shape[0], -1)[:, :-2]
        return ["[" + line.decode("ascii") + "]" for line in map(bytes, text)]
    return ["[" + ", ".join(map(str, row)) + "]" for row in a.tolist()]


def _plain(obj: Any) -> Any:
    """Turn numpy values, enums, paths and tuples into JSON-ready Python values."""
    if isinstance(obj, dict):
        return {str(k): _plain(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        if all(type(v) is int for v in obj):  # fast path for grid rows
            return obj if isinstance(obj, list) else list(obj)
        return [_plain(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return obj if obj.ndim == 2 and np.issubdtype(obj.dtype, np.integer) else obj.tolist()
    if isinstance(obj, np.generic):
        return obj.item()
    if isinstance(obj, Status):
        return obj.value
    if isinstance(obj, os.PathLike):
        return os.fspath(obj)
    if isinstance(obj, float) and not math.isfinite(obj):
        return None if math.isnan(obj) else ("inf" if obj > 0 else "-inf")
    if obj is None or isinstance(obj, (bool, int, float, str)):
        return obj
    return str(obj)


# ----------------------------------------------------------------------------- compact arrays
#: The ``dtype`` names of encoded arrays (see the module docstring), smallest first.
ARRAY_DTYPES: dict[str, np.dtype] = {
    name: np.dtype(name).newbyteorder("<")
    for name in ("uint8", "int8", "uint16", "int16", "uint32", "int32", "int64")
}


_SIGNED = {"uint8": np.int16, "int8": np.int8, "uint16": np.int32, "int16": np.int16, "uint32": np.int64,
           "int32": np.int32, "int64": np.int64}


def encode_array(a) -> dict:
    """An integer array as an encoded array (module docstring), in the smallest ``dtype``
    that holds its values: ``bits`` for 0/1 values, else the narrowest integer type.

    >>> encode_array(np.array([[0, 1, 1], [1, 0, 0]]))
    {'dtype': 'bits', 'shape': [2, 3], 'data': 'cA=='}
    >>> encode_array([300, -1])["dtype"]
    'int16'
    """
    arr = np.asarray(a)
    if arr.dtype != bool and not np.issubdtype(arr.dtype, np.integer):
        raise TypeError(f"encode_array takes integer arrays, not {arr.dtype}")
    lo, hi = (int(arr.min()), int(arr.max())) if arr.size else (0, 0)
    if lo >= 0 and hi <= 1:
        name, raw = "bits", np.packbits(arr.astype(bool, copy=False), axis=None).tobytes()
    else:
        name = next(n for n, d in ARRAY_DTYPES.items()
                    if np.iinfo(d).min <= lo and hi <= np.iinfo(d).max)
        raw = np.ascontiguousarray(arr, dtype=ARRAY_DTYPES[name]).tobytes()
    return {"dtype": name, "shape": list(arr.shape), "data": base64.b64encode(raw).decode("ascii")}


def decode_array(value: Any, what: str, source: Any, *, ndim: int | None = None) -> np.ndarray:
    """The signed integer array of an encoded array (module docstring), or of plain JSON lists.

    An encoded array comes back in the narrowest signed type that holds its ``dtype``
    (``int8`` for ``bits`` and ``int8``, ``int16`` for ``uint8``, ...), so a large grid costs
    no more memory read than written; lists come back as ``int64``.

    Examples
    --------
    >>> decode_array({"dtype": "bits", "shape": [2, 3], "data": "cA=="}, "tiling", "t.json").tolist()
    [[0, 1, 1], [1, 0, 0]]
    >>> decode_array({"dtype": "uint8", "shape": [2], "data": "AAE"}, "tiling", "t.json")
    Traceback (most recent call last):
    ...
    tilesolve.errors.InvalidProblem: t.json: 'tiling': 'data' is not valid base64

    Raises
    ------
    InvalidProblem
        One line naming ``source`` and the field ``what``: not an encoded array or a
        rectangular list of integers, an unknown dtype, a bad shape, bad base64, a length
        that does not match the shape, or (for ``bits``) padding that is not zero.
    """
    def fail(why: str) -> InvalidProblem:
        return InvalidProblem(f"{source}: {what!r}: {why}")

    if isinstance(value, list):
        try:
            arr = np.array(value)
        except ValueError:
            raise fail("rows of different lengths") from None
        if arr.size and arr.dtype.kind not in "iu" or arr.dtype == object:
            raise fail("must hold integers only")
        arr = arr.astype(np.int64)
    elif isinstance(value, dict):
        if set(value) != {"dtype", "shape", "data"}:
            raise fail("an encoded array has exactly the fields 'dtype', 'shape' and 'data'")
        name, shape, data = value["dtype"], value["shape"], value["data"]
        if not isinstance(name, str) or name != "bits" and name not in ARRAY_DTYPES:
            raise fail(f"unknown dtype {name!r}; expected bits or {', '.join(ARRAY_DTYPES)}")
        if not isinstance(shape, list) or not all(type(d) is int and d >= 0 for d in shape):
            raise fail(f"'shape' must be a list of sizes, got {shape!r}")
        if not isinstance(data, str):
            raise fail("'data' must be a base64 string")
        try:
            raw = base64.b64decode(data, validate=True)
        except (binascii.Error, ValueError):
            raise fail("'data' is not valid base64") from None
        count = math.prod(shape)
        if name == "bits":
            if len(raw) != (count + 7) // 8:
                raise fail(f"'data' holds {len(raw)} bytes; {count} bits need {(count + 7) // 8}")
            bits = np.unpackbits(np.frombuffer(raw, np.uint8))
            if bits[count:].any():
                raise fail("'data' has bits set after the last value")
            arr = bits[:count].view(np.int8)
        else:
            dt = ARRAY_DTYPES[name]
            if len(raw) != count * dt.itemsize:
                raise fail(f"'data' holds {len(raw)} bytes; {count} {name} values need {count * dt.itemsize}")
            arr = np.frombuffer(raw, dt).astype(_SIGNED[name])
        arr = arr.reshape(shape)
    else:
        raise fail(f"expected an encoded array or a list, got {type(value).__name__}")
    if ndim is not None and arr.ndim != ndim and arr.size:
        raise fail(f"expected {ndim} dimensions, got shape {list(arr.shape)}")
    return arr


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
def provenance_to_dict(solution: Solution) -> dict:
    """The fields every solution file carries, whatever the family: status and provenance."""
    return {
        "status": solution.status.value,
        "method": solution.method,
        "solver": solution.solver,
        "seed": solution.seed,
        "time_s": round(float(solution.time_s), 6),
        "reason": solution.reason,
        "notes": list(solution.notes),
        "stats": dict(solution.stats),
    }


#: The largest ``time_s`` a solution file may record (about 31 years: no run lasts longer).
MAX_TIME_S = 1e9


def check_time_s(value: Any, source: Any, field: str = "time_s") -> float:
    """``value`` as a recorded duration: a finite number of seconds from 0 to :data:`MAX_TIME_S`
    (not a boolean), else a one-line error naming ``source`` and ``field``.

    >>> check_time_s(3, "f.json")
    3.0
    >>> check_time_s(-5, "f.json", "periods[0].time_s")
    Traceback (most recent call last):
    ...
    tilesolve.errors.InvalidProblem: f.json: 'periods[0].time_s' must be a number of seconds from 0 to 1e+09, got -5
    """
    if isinstance(value, bool) or not isinstance(value, (int, float)) \
            or not (math.isfinite(value) and 0 <= value <= MAX_TIME_S):
        raise InvalidProblem(f"{source}: {field!r} must be a number of seconds from 0 to {MAX_TIME_S:g}, "
                             f"got {value!r}")
    return float(value)


def solution_from_provenance(doc: dict, source: Any, tiling, *, what: str = "tiling",
                             default_status: str | None = None) -> Solution:
    """A :class:`Solution` from the fields :func:`provenance_to_dict` writes (checked
    strictly: wrong types are one-line errors), plus ``objective`` where present.

    ``tiling`` is the family's already-parsed grid (``None`` if the file has none); a
    status that promises a tiling without one is an error. ``default_status`` is used when
    the file has no ``status`` field. ``seed`` is a non-negative integer and ``time_s`` a
    finite number of seconds from 0 to :data:`MAX_TIME_S` (NaN never parses: :func:`parse_json`).
    """
    raw = doc.get("status", default_status)
    try:
        status = Status(raw)
    except ValueError:
        raise InvalidProblem(
            f"{source}: 'status' must be one of {', '.join(s.value for s in Status)}, got {raw!r}"
        ) from None
    if status.has_tiling and tiling is None:
        raise InvalidProblem(f"{source}: status is {status.value!r} but the file holds no {what!r}")

    def opt(name: str, kind: type | tuple, default: Any = None) -> Any:
        v = doc.get(name, default)
        if v is not None and (not isinstance(v, kind) or isinstance(v, bool) and kind is not bool):
            raise InvalidProblem(f"{source}: {name!r} has the wrong type ({type(v).__name__})")
        return v

    notes = opt("notes", list, []) or []
    if not all(isinstance(n, str) for n in notes):
        raise InvalidProblem(f"{source}: 'notes' must be a list of strings")
    seed, time_s = opt("seed", int), opt("time_s", (int, float), 0.0)
    if seed is not None and not 0 <= seed < 2**63:
        raise InvalidProblem(f"{source}: 'seed' must be an integer from 0 to 2**63 - 1, got {seed}")
    if time_s is not None:
        check_time_s(time_s, source)
    return Solution(
        status=status,
        tiling=tiling,
        method=opt("method", str, "") or "",
        solver=opt("solver", str),
        seed=seed,
        time_s=float(time_s or 0.0),
        objective=opt("objective", int),
        reason=opt("reason", str),
        notes=tuple(notes),
        stats=opt("stats", dict, {}) or {},
    )


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
