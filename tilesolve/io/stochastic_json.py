"""The ``tilesolve/stochastic-tiling`` file (version 2; version 1 is read): a window of a stochastic tiling.

::

    {
      "format": "tilesolve/stochastic-tiling", "version": 2,
      "kind": "wang",                    # or "corner"
      "colors": 3,                       # C
      "set": "compact",                  # complete, compact or sums (class notes §2.7, §3.2, §3.3.2.2)
      "window": {"x0": -4, "y0": 10, "width": 8, "height": 5, "y_up": true},
      "hash": "long",                    # long or table (§3.4)
      "algorithm": "edges",              # direct Wang route on the complete set: edges or two
      "tile_set": {                      # the set, so another tool can check the grid alone
        "sides": ["N", "E", "S", "W"],   # or ["NE", "SE", "SW", "NW"]
        "numbers": [0, 4, ...],          # the tiles' eq. 2.1 / 2.5 numbers
        "colours": [[0, 0, 0, 0], ...]   # each tile's four colours, in "sides" order
      },
      "status": "sat",
      "grid": [[...], ...],              # height rows (top row first) of width tile numbers
      "method": "scanline", "seed": 1, "time_s": 0.01, "solver": null,
      "reason": null, "notes": [], "stats": {}
    }

``window`` is :meth:`tilesolve.model.window.Window.to_dict`: the bottom-left tile ``(x0, y0)``
(tiles are named by their SW corner, §2.7), ``width`` columns by ``height`` rows, and the
direction of the y axis. ``y_up`` is true: y points north, so ``grid`` row ``r`` holds the tiles
of ``y = y0 + height - 1 - r`` (a window whose y grows downwards is refused). Version 1 wrote
the window without ``y_up`` and meant the same thing: y pointing north.

Grids of more than :data:`~tilesolve.io.jsonio.COMPACT_MIN_CELLS` cells, and tile sets of
more than that many tiles, are written as encoded arrays
(:func:`tilesolve.io.jsonio.encode_array`). Readers reject unknown fields and malformed values
with one line naming the file and field, and a ``tile_set`` that is not the set the header
names; the grid itself is checked by the family's verifier, not here, so ``tilesolve verify``
lists a bad file's violations.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.io.jsonio import (
    COMPACT_MIN_CELLS,
    check_document,
    decode_array,
    encode_array,
    provenance_to_dict,
    solution_from_provenance,
)
from tilesolve.model.solution import Solution
from tilesolve.model.stochastic import StochasticProblem
from tilesolve.model.window import Window

__all__ = ["STOCHASTIC_TILING", "VERSIONS", "VERSION", "stochastic_to_dict", "stochastic_from_dict"]

STOCHASTIC_TILING = "tilesolve/stochastic-tiling"
#: Versions of the format this module reads; it writes :data:`VERSION`.
VERSIONS = frozenset({1, 2})
#: The version written: 2 records the window's y direction (``window.y_up``).
VERSION = 2

_KEYS = {"format", "version", "kind", "colors", "set", "window", "hash", "algorithm", "tile_set", "status", "grid",
         "method", "solver", "seed", "time_s", "reason", "notes", "stats", "created_by", "comment"}
_V1_WINDOW_KEYS = {"x0", "y0", "width", "height"}
_SET_KEYS = {"sides", "numbers", "colours"}


def _array(a: np.ndarray):
    return encode_array(a) if a.size > COMPACT_MIN_CELLS else np.asarray(a, dtype=np.int64)


def stochastic_to_dict(problem: StochasticProblem, solution: Solution) -> dict:
    """The JSON document of a window (arrays stay numpy arrays or encoded arrays for
    :func:`tilesolve.io.jsonio.dumps`)."""
    ts = problem.tiles
    table = ts.table()
    return {
        "format": STOCHASTIC_TILING,
        "version": VERSION,
        "kind": problem.kind,
        "colors": problem.colors,
        "set": problem.variant,
        "window": problem.window.to_dict(),
        "hash": problem.hash,
        "algorithm": problem.algorithm,
        "tile_set": {
            "sides": list(ts.sides),
            "numbers": encode_array(ts.indices) if ts.n_tiles > COMPACT_MIN_CELLS else ts.indices.tolist(),
            "colours": _array(table),
        },
        **provenance_to_dict(solution),
        "grid": None if solution.tiling is None else _array(np.asarray(solution.tiling)),
    }


def _field(doc: dict, key: str, source: Any):
    if key not in doc:
        raise InvalidProblem(f"{source}: missing field {key!r}")
    return doc[key]


def _int(v: Any, key: str, source: Any) -> int:
    if isinstance(v, bool) or not isinstance(v, int):
        raise InvalidProblem(f"{source}: {key!r} must be an integer, got {v!r}")
    return v


def _str(v: Any, key: str, source: Any) -> str:
    if not isinstance(v, str):
        raise InvalidProblem(f"{source}: {key!r} must be a string, got {v!r}")
    return v


def stochastic_from_dict(doc: dict, source: Any = "<document>") -> tuple[StochasticProblem, Solution]:
    """Rebuild ``(problem, solution)`` from a ``tilesolve/stochastic-tiling`` document.

    Examples
    --------
    >>> doc = {"format": "tilesolve/stochastic-tiling", "version": 2, "kind": "wang", "colors": 2,
    ...        "set": "complete", "window": {"x0": 0, "y0": 0, "width": 2, "height": 1, "y_up": True},
    ...        "grid": [[0, 0]]}
    >>> p, s = stochastic_from_dict(doc)
    >>> p.window, s.status.value, s.tiling.tolist()
    (Window(x0=0, y0=0, width=2, height=1, y_up=True), 'sat', [[0, 0]])
    >>> s.window == p.window
    True

    A version 1 window has no ``y_up``; its y points north:

    >>> v1 = dict(doc, version=1, window={"x0": 0, "y0": 0, "width": 2, "height": 1})
    >>> stochastic_from_dict(v1)[0].window == p.window
    True
    """
    version = check_document(doc, source, {STOCHASTIC_TILING: VERSIONS}, fields=_KEYS)["version"]
    kind = _str(_field(doc, "kind", source), "kind", source)
    colors = _int(_field(doc, "colors", source), "colors", source)
    variant = _str(doc.get("set", "complete"), "set", source)
    window = _window(_field(doc, "window", source), version, source)
    hash_ = _str(doc.get("hash", "long"), "hash", source)
    algorithm = _str(doc.get("algorithm", "edges"), "algorithm", source)
    try:
        problem = StochasticProblem(kind, colors, window, variant, hash_, algorithm)  # type: ignore[arg-type]
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: {exc}") from None
    if "tile_set" in doc:
        _check_tile_set(doc["tile_set"], problem, source)
    grid = doc.get("grid")
    if grid is not None:
        grid = decode_array(grid, "grid", source, ndim=2)
        if grid.size == 0:
            raise InvalidProblem(f"{source}: 'grid' is empty")
    sol = solution_from_provenance(doc, source, grid, what="grid",
                                   default_status="sat" if grid is not None else "unknown")
    return problem, sol.replace(window=problem.window)


def _window(win: Any, version: int, source: Any) -> Window:
    """The ``window`` field: :meth:`Window.to_dict`'s five fields (version 2) or, in version 1,
    ``x0, y0, width, height`` with y pointing north."""
    fields = _V1_WINDOW_KEYS if version == 1 else _V1_WINDOW_KEYS | {"y_up"}
    if not isinstance(win, dict) or set(win) != fields:
        raise InvalidProblem(f"{source}: 'window' must be an object with exactly the fields "
                             f"{', '.join(sorted(fields, key=('x0', 'y0', 'width', 'height', 'y_up').index))} "
                             f"in version {version}")
    try:
        return Window.from_dict(win)
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: 'window': {exc}") from None


def _check_tile_set(value: Any, problem: StochasticProblem, source: Any) -> None:
    """The file's ``tile_set`` must be the set its header names (a file that says one thing
    and holds another would let other tools check a different set)."""
    if not isinstance(value, dict) or set(value) != _SET_KEYS:
        raise InvalidProblem(f"{source}: 'tile_set' must be an object with exactly the fields "
                             "sides, numbers, colours")
    ts = problem.tiles
    if value["sides"] != list(ts.sides):
        raise InvalidProblem(f"{source}: 'tile_set.sides' must be {list(ts.sides)} for {problem.kind} tiles, "
                             f"got {value['sides']!r}")
    numbers = decode_array(value["numbers"], "tile_set.numbers", source, ndim=1)
    colours = decode_array(value["colours"], "tile_set.colours", source, ndim=2)
    if not np.array_equal(numbers, ts.indices):
        raise InvalidProblem(f"{source}: 'tile_set.numbers' are not the tiles of the {ts.describe()}")
    if not np.array_equal(colours, ts.table()):
        raise InvalidProblem(f"{source}: 'tile_set.colours' are not the colours of the {ts.describe()} "
                             "(eq. 2.1 / 2.5)")
