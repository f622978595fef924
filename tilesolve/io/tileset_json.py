"""Wang tile-set files: ``"format": "tilesolve/wang-tileset"``, version 1.

Tiles are written in tilesolve's public edge order N, E, S, W (class notes §2.7)::

    {
      "format": "tilesolve/wang-tileset", "version": 1,
      "order": ["N", "E", "S", "W"],
      "colors": 3,                       # colours are 0 .. colors-1
      "tiles": [[0, 1, 2, 0], ...],      # one [N, E, S, W] per tile
      "name": "optional name", "comment": "optional text",
      "about": {...}                     # optional: where the set comes from, what is known
    }

``about`` (an object) is kept as it is; the built-in sets (:mod:`tilesolve.io.builtin_tilesets`)
use it for their title, sources and literature verdict.

Files without a header are read as before the format existed: a JSON list of tiles, or
``{"colors": K, "tiles": [...], "order": "WNES" | "NESW"}`` (order default W, N, E, S, the
brick paper's legs l1..l4). Duplicate tiles are dropped (a set), with a note returned. A set's
colours are the colours its tiles use, relabelled ``0 .. k-1`` in order when they are not
already (:func:`compact_tileset`, with a note).
"""

from __future__ import annotations

import os
from typing import Any

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.io.atomic import write_text_atomic
from tilesolve.io.jsonio import check_document, dumps, read_json
from tilesolve.model.board import WangTileSet, colour_rows

__all__ = ["WANG_TILESET", "VERSIONS", "tileset_to_dict", "tileset_from_data", "compact_tileset", "read_tileset",
           "write_tileset"]

WANG_TILESET = "tilesolve/wang-tileset"
#: Versions of the tile-set format this module reads and writes.
VERSIONS = frozenset({1})
_KEYS = {"format", "version", "order", "colors", "tiles", "name", "comment", "created_by", "about"}


def tileset_to_dict(tileset: WangTileSet, *, name: str | None = None, about: dict | None = None) -> dict:
    """The JSON document of a tile set (tiles in N, E, S, W order)."""
    doc: dict[str, Any] = {"format": WANG_TILESET, "version": 1, "order": ["N", "E", "S", "W"],
                           "colors": tileset.n_colors, "tiles": tileset.tiles.tolist()}
    if name:
        doc["name"] = name
    if about:
        doc["about"] = about
    return doc


def _tiles(value: Any, source: str) -> list[list[int]]:
    if not isinstance(value, list) or not value:
        raise InvalidProblem(f"{source}: 'tiles' must be a non-empty list of tiles")
    for i, t in enumerate(value):
        if not (isinstance(t, list) and len(t) == 4
                and all(isinstance(c, int) and not isinstance(c, bool) and 0 <= c < 2**63 for c in t)):
            raise InvalidProblem(f"{source}: tile {i} must be a list of 4 integer colours (from 0), "
                                 f"got {str(t)[:60]}")
    return value


def compact_tileset(tiles_nesw: Any, source: str, colors: int | None = None) -> tuple[WangTileSet, list[str]]:
    """The tile set of ``tiles_nesw`` (rows N, E, S, W of colours from 0), its colours
    relabelled compactly, and notes for the user.

    Every reader of tile-set files ends here, so a set's palette is the colours its tiles use:
    when they are not ``0 .. k-1`` they are renumbered in order (a note lists the first few),
    so one colour numbered 99,999,992 costs what colour 3 costs. ``colors``, where a file
    declares it, must hold every colour used.

    Examples
    --------
    >>> ts, notes = compact_tileset([[0, 5, 0, 99999992], [5, 0, 5, 0]], "t.tiles")
    >>> ts.n_colors, ts.tiles.tolist()
    (3, [[0, 1, 0, 2], [1, 0, 1, 0]])
    >>> notes
    ['t.tiles: colours relabelled 0..2 in order (5 -> 1, 99999992 -> 2)']

    Raises
    ------
    InvalidProblem
        Colours that are not integers from 0, rows that are not four colours, no tiles, or a
        colour at or above ``colors``.
    """
    try:
        t = colour_rows(tiles_nesw)
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: {exc}") from None
    if t.size == 0:
        raise InvalidProblem(f"{source}: the tile set is empty")
    if t.min() < 0:
        raise InvalidProblem(f"{source}: colour {int(t.min())} is negative")
    if colors is not None and colors < 1:
        raise InvalidProblem(f"{source}: 'colors' must be at least 1, got {colors}")
    if colors is not None and t.max() >= colors:
        raise InvalidProblem(f"{source}: colour {int(t.max())} is outside C = 0..{colors - 1} ('colors' is {colors})")
    used, inverse = np.unique(t, return_inverse=True)
    notes = []
    if int(used[-1]) != len(used) - 1:
        moved = [f"{int(c)} -> {i}" for i, c in enumerate(used) if c != i]
        shown = ", ".join(moved[:4]) + (f", ... ({len(moved)} colours)" if len(moved) > 4 else "")
        notes.append(f"{source}: colours relabelled 0..{len(used) - 1} in order ({shown})")
        t = inverse.reshape(t.shape)
    ts = WangTileSet(t, len(used))
    if len(ts) < len(t):
        notes.append(f"{source}: {len(t) - len(ts)} duplicate tile(s) dropped")
    return ts, notes


def tileset_from_data(data: Any, source: str = "<tile set>") -> tuple[WangTileSet, list[str]]:
    """A tile set from a parsed document (versioned or legacy) and notes for the user
    (:func:`compact_tileset` relabels its colours compactly)."""
    if isinstance(data, dict) and "format" in data:
        check_document(data, source, {WANG_TILESET: VERSIONS})
        extra = set(data) - _KEYS
        if extra:
            raise InvalidProblem(f"{source}: unknown field {sorted(extra)[0]!r}")
        if "about" in data and not isinstance(data["about"], dict):
            raise InvalidProblem(f"{source}: 'about' must be an object")
        if data.get("order", ["N", "E", "S", "W"]) != ["N", "E", "S", "W"]:
            raise InvalidProblem(f"{source}: 'order' must be [\"N\", \"E\", \"S\", \"W\"]")
        nesw = _tiles(data.get("tiles"), source)
    else:
        if isinstance(data, list):
            data = {"tiles": data}
        if not isinstance(data, dict):
            raise InvalidProblem(f"{source}: expected a tilesolve/wang-tileset document or a list of tiles")
        tiles = _tiles(data.get("tiles"), source)
        order = data.get("order", "WNES")
        if order not in ("WNES", "NESW", "wnes", "nesw"):
            raise InvalidProblem(f"{source}: 'order' must be WNES or NESW")
        nesw = tiles if order.upper() == "NESW" else [[n, e, s, w] for w, n, e, s in tiles]
    colors = data.get("colors")
    if colors is not None and (isinstance(colors, bool) or not isinstance(colors, int)):
        raise InvalidProblem(f"{source}: 'colors' must be an integer")
    return compact_tileset(nesw, source, colors)


def read_tileset(path: str | os.PathLike) -> tuple[WangTileSet, list[str]]:
    """Read a tile-set file (see the module docstring): ``(tile set, notes)``."""
    return tileset_from_data(read_json(path), str(path))


def write_tileset(path: str | os.PathLike, tileset: WangTileSet, *, name: str | None = None,
                  about: dict | None = None) -> None:
    """Write a tile set as a version-1 ``tilesolve/wang-tileset`` file, atomically."""
    write_text_atomic(path, dumps(tileset_to_dict(tileset, name=name, about=about)))
