"""The ``tilesolve/aperiodic-window`` file (version 1): a window of a tiling of the plane by a
built-in aperiodic Wang tile set (:mod:`tilesolve.model.aperiodic_window`).

::

    {
      "format": "tilesolve/aperiodic-window", "version": 1,
      "tileset": {                        # the built-in set, so another tool can check the grid alone
        "name": "jeandel-rao",            # tilesolve tiles --builtin NAME
        "order": ["N", "E", "S", "W"],
        "colors": 5,
        "tiles": [[1, 1, 1, 3], ...]      # each tile's edge colours N, E, S, W, in the set's order
      },
      "window": {"x0": -4, "y0": 10, "width": 8, "height": 5, "y_up": true},
      "status": "sat",
      "method": "markov",                 # the constructive route
      "seed": 1,                          # which tiling of the plane (windows of one seed agree)
      "solver": null, "reason": null, "notes": [], "stats": {"tiles": 40},
      "grid": [[...], ...]                # height rows (top row first) of width tile indices
    }

``window`` is :meth:`tilesolve.model.window.Window.to_dict`: ``grid`` row ``r`` holds the tiles of
``y = y0 + height - 1 - r``, column ``c`` those of ``x = x0 + c``. The file records no time: it
is a function of the tile set, the window, the route and the seed, byte for byte. Grids of
more than :data:`~tilesolve.io.jsonio.COMPACT_MIN_CELLS` tiles are encoded arrays
(:func:`tilesolve.io.jsonio.encode_array`).

The reader re-derives the tile set from its name (:func:`tilesolve.io.builtin_tilesets.load`)
and refuses a file whose ``tileset`` is not that set, tile for tile in its order; it rejects
unknown fields and malformed values with one line naming the file and field. The grid itself
is checked by the family's verifier, not here, so ``tilesolve verify`` lists a bad grid's
violations.
"""

from __future__ import annotations

import json
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
from tilesolve.model.aperiodic_window import AperiodicWindowProblem
from tilesolve.model.solution import Solution
from tilesolve.model.window import Window

__all__ = ["APERIODIC_WINDOW", "VERSIONS", "VERSION", "window_to_dict", "window_from_dict"]

APERIODIC_WINDOW = "tilesolve/aperiodic-window"
#: Versions of the format this module reads; it writes :data:`VERSION`.
VERSIONS = frozenset({1})
VERSION = 1

_KEYS = {"format", "version", "tileset", "window", "status", "grid", "method", "solver", "seed", "reason", "notes",
         "stats", "created_by", "comment"}
_SET_KEYS = {"name", "order", "colors", "tiles"}
_ORDER = ["N", "E", "S", "W"]
_WINDOW_KEYS = ("x0", "y0", "width", "height", "y_up")


def window_to_dict(problem: AperiodicWindowProblem, solution: Solution) -> dict:
    """The JSON document of a window (the grid stays a numpy array, or an encoded array, for
    :func:`tilesolve.io.jsonio.dumps`)."""
    ts = problem.tileset
    prov = provenance_to_dict(solution)
    del prov["time_s"]  # the same seed gives the same file
    grid = None
    if solution.tiling is not None:
        g = np.asarray(solution.tiling)
        grid = encode_array(g) if g.size > COMPACT_MIN_CELLS else g.astype(np.int64)
    return {
        "format": APERIODIC_WINDOW,
        "version": VERSION,
        "tileset": {"name": problem.name, "order": list(_ORDER), "colors": int(ts.n_colors),
                    "tiles": ts.tiles.tolist()},
        "window": problem.window.to_dict(),
        **prov,
        "grid": grid,
    }


def window_from_dict(doc: dict, source: Any = "<document>") -> tuple[AperiodicWindowProblem, Solution]:
    """Rebuild ``(problem, solution)`` from a ``tilesolve/aperiodic-window`` document.

    Examples
    --------
    >>> from tilesolve.io.builtin_tilesets import load
    >>> tiles = load("jeandel-rao")[0].tiles.tolist()
    >>> doc = {"format": "tilesolve/aperiodic-window", "version": 1,
    ...        "tileset": {"name": "jeandel-rao", "order": ["N", "E", "S", "W"], "colors": 5, "tiles": tiles},
    ...        "window": {"x0": 3, "y0": -1, "width": 2, "height": 1, "y_up": True}, "grid": [[0, 1]]}
    >>> p, s = window_from_dict(doc)
    >>> p.name, p.window.x0, s.status.value, s.tiling.tolist()
    ('jeandel-rao', 3, 'sat', [[0, 1]])
    >>> window_from_dict(dict(doc, tileset=dict(doc["tileset"], tiles=tiles[::-1])))
    Traceback (most recent call last):
    ...
    tilesolve.errors.InvalidProblem: <document>: 'tileset.tiles' are not the tiles of the built-in set jeandel-rao (in its order)
    """
    check_document(doc, source, {APERIODIC_WINDOW: VERSIONS}, fields=_KEYS, required=("tileset", "window", "grid"))
    name, tileset = _tileset(doc["tileset"], source)
    window = _window(doc["window"], source)
    try:
        problem = AperiodicWindowProblem(name, tileset, window)
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: {exc}") from None
    grid = decode_array(doc["grid"], "grid", source, ndim=2)
    if grid.ndim != 2:  # decode_array lets an empty array of any shape through
        raise InvalidProblem(f"{source}: 'grid' is empty")
    sol = solution_from_provenance(doc, source, grid, what="grid", default_status="sat")
    return problem, sol.replace(window=problem.window)


def _tileset(value: Any, source: Any):
    """``(name, WangTileSet)``: the built-in set the file names, which its ``tileset`` must be."""
    from tilesolve.io.builtin_tilesets import load

    if not isinstance(value, dict) or set(value) != _SET_KEYS:
        raise InvalidProblem(f"{source}: 'tileset' must be an object with exactly the fields name, order, colors, "
                             "tiles")
    name = value["name"]
    if not isinstance(name, str):
        raise InvalidProblem(f"{source}: 'tileset.name' must be a string, got {name!r}")
    try:
        tileset, _ = load(name)
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: 'tileset.name': {exc}") from None
    if value["order"] != _ORDER:
        raise InvalidProblem(f"{source}: 'tileset.order' must be {_ORDER}, got {value['order']!r}")
    if type(value["colors"]) is not int or value["colors"] != tileset.n_colors:
        raise InvalidProblem(f"{source}: 'tileset.colors' must be {tileset.n_colors} for the built-in set {name}, "
                             f"got {value['colors']!r}")
    if json.dumps(value["tiles"]) != json.dumps(tileset.tiles.tolist()):  # 1.0 or true is not the colour 1
        raise InvalidProblem(f"{source}: 'tileset.tiles' are not the tiles of the built-in set {name} (in its order)")
    return name, tileset


def _window(win: Any, source: Any) -> Window:
    if not isinstance(win, dict) or set(win) != set(_WINDOW_KEYS):
        raise InvalidProblem(f"{source}: 'window' must be an object with exactly the fields {', '.join(_WINDOW_KEYS)}")
    try:
        return Window.from_dict(win)
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: 'window': {exc}") from None
