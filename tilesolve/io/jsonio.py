"""The shared JSON helpers of every family's codec: versioned documents, strict parsing,
readable writing, compact arrays and the provenance every solution file carries.

Every file carries ``"format": "tilesolve/<kind>"`` and ``"version"`` (DESIGN.md, "Files").
Each codec reads only its own formats and versions (:func:`load_document`,
:func:`check_document`) and turns anything malformed into one
:class:`~tilesolve.errors.InvalidProblem` line naming the file and the field
(:func:`parse_json`, :func:`decode_array`, :func:`solution_from_provenance`).
Writers go through :mod:`tilesolve.io.atomic` with :func:`dumps`.

The codecs: :mod:`tilesolve.io.dappled_json`, :mod:`tilesolve.io.board_json`,
:mod:`tilesolve.io.packing_json`, :mod:`tilesolve.io.stochastic_json`,
:mod:`tilesolve.io.aperiodic_json`, :mod:`tilesolve.io.tileset_json`.

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
"""

from __future__ import annotations

import base64
import binascii
import json
import math
import os
from typing import Any, Iterable, Mapping

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.inputs import read_input_text
from tilesolve.model.solution import Solution, Status

__all__ = [
    "load_document",
    "check_document",
    "read_json",
    "parse_json",
    "dumps",
    "encode_array",
    "encoded_dtype",
    "encoded_text",
    "decode_array",
    "ARRAY_DTYPES",
    "COMPACT_MIN_CELLS",
    "provenance_to_dict",
    "check_time_s",
    "solution_from_provenance",
    "MAX_TIME_S",
]

#: Grids of more cells than this are written as encoded arrays (dappled solutions version 2,
#: stochastic tilings).
COMPACT_MIN_CELLS = 1 << 16


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


def check_document(doc: Any, source: Any, formats: Mapping[str, Iterable[int]], *,
                   fields: Iterable[str] | None = None, required: Iterable[str] = ()) -> dict:
    """Check the ``format``/``version`` header of an already-parsed document against
    ``formats`` (format name -> versions read); with ``fields``, refuse a field not among them,
    and refuse a document without one of the ``required`` fields.

    >>> check_document({"format": "f", "version": 1, "x": 0}, "d.json", {"f": {1}}, fields={"format", "version"})
    Traceback (most recent call last):
    ...
    tilesolve.errors.InvalidProblem: d.json: unknown field 'x'
    """
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
    extra = sorted(set(doc) - set(fields)) if fields is not None else []
    if extra:
        raise InvalidProblem(f"{source}: unknown field{'s' if len(extra) > 1 else ''} {', '.join(map(repr, extra))}")
    for key in required:
        if key not in doc:
            raise InvalidProblem(f"{source}: missing field {key!r}")
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
    name = encoded_dtype(*((int(arr.min()), int(arr.max())) if arr.size else (0, 0)))
    return {"dtype": name, "shape": list(arr.shape), "data": encoded_text(arr, name)}


def encoded_dtype(lo: int, hi: int) -> str:
    """The ``dtype`` name :func:`encode_array` gives an array whose values span ``lo .. hi``.

    >>> encoded_dtype(0, 1), encoded_dtype(0, 2), encoded_dtype(-1, 2)
    ('bits', 'uint8', 'int8')
    """
    if lo >= 0 and hi <= 1:
        return "bits"
    return next(n for n, d in ARRAY_DTYPES.items() if np.iinfo(d).min <= lo and hi <= np.iinfo(d).max)


def encoded_text(arr: np.ndarray, name: str) -> str:
    """The base64 ``data`` of ``arr``'s values (row-major) as ``dtype`` ``name``.

    Pieces of an array concatenate to the whole's text when every piece but the last holds
    a multiple of 24 values (3 bytes of ``bits``, a multiple of 3 bytes of any integer type):
    a writer can stream a large array's text piece by piece.
    """
    if name == "bits":
        raw = np.packbits(np.asarray(arr).astype(bool, copy=False), axis=None).tobytes()
    else:
        raw = np.ascontiguousarray(arr, dtype=ARRAY_DTYPES[name]).tobytes()
    return base64.b64encode(raw).decode("ascii")


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


# ----------------------------------------------------------------------------- provenance
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
