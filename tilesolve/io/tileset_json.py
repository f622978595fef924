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
brick paper's legs l1..l4). Duplicate tiles are dropped (a set), with a note returned.
"""

from __future__ import annotations

import os
from typing import Any

from tilesolve.errors import InvalidProblem
from tilesolve.io.atomic import write_text_atomic
from tilesolve.io.jsonio import check_document, dumps, read_json
from tilesolve.model.board import WangTileSet, wang_from_nesw

__all__ = ["WANG_TILESET", "VERSIONS", "tileset_to_dict", "tileset_from_data", "read_tileset", "write_tileset"]

WANG_TILESET = "tilesolve/wang-tileset"
#: Versions of the tile-set format this module reads and writes.
VERSIONS = frozenset({1})
_KEYS = {"format", "version", "order", "colors", "tiles", "name", "comment", "created_by", "about"}


def tileset_to_dict(tileset: WangTileSet, *, name: str | None = None, about: dict | None = None) -> dict:
    """The JSON document of a tile set (tiles in N, E, S, W order)."""
    doc: dict[str, Any] = {"format": WANG_TILESET, "version": 1, "order": ["N", "E", "S", "W"],
                           "colors": tileset.n_colors, "tiles": tileset.nesw().tolist()}
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
                and all(isinstance(c, int) and not isinstance(c, bool) for c in t)):
            raise InvalidProblem(f"{source}: tile {i} must be a list of 4 integer colours, got {t!r}")
    return value


def tileset_from_data(data: Any, source: str = "<tile set>") -> tuple[WangTileSet, list[str]]:
    """A tile set from a parsed document (versioned or legacy) and notes for the user."""
    notes: list[str] = []
    if isinstance(data, dict) and "format" in data:
        check_document(data, source, {WANG_TILESET: VERSIONS})
        extra = set(data) - _KEYS
        if extra:
            raise InvalidProblem(f"{source}: unknown field {sorted(extra)[0]!r}")
        if "about" in data and not isinstance(data["about"], dict):
            raise InvalidProblem(f"{source}: 'about' must be an object")
        if data.get("order", ["N", "E", "S", "W"]) != ["N", "E", "S", "W"]:
            raise InvalidProblem(f"{source}: 'order' must be [\"N\", \"E\", \"S\", \"W\"]")
        tiles = wang_from_nesw(_tiles(data.get("tiles"), source)).tolist()
    else:
        if isinstance(data, list):
            data = {"tiles": data}
        if not isinstance(data, dict):
            raise InvalidProblem(f"{source}: expected a tilesolve/wang-tileset document or a list of tiles")
        tiles = _tiles(data.get("tiles"), source)
        order = str(data.get("order", "WNES")).upper()
        if order not in ("WNES", "NESW"):
            raise InvalidProblem(f"{source}: 'order' must be WNES or NESW")
        if order == "NESW":
            tiles = wang_from_nesw(tiles).tolist()
    colors = data.get("colors", 1 + max(max(t) for t in tiles))
    if isinstance(colors, bool) or not isinstance(colors, int):
        raise InvalidProblem(f"{source}: 'colors' must be an integer")
    try:
        ts = WangTileSet(tiles, colors)
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: {exc}") from None
    if len(ts) < len(tiles):
        notes.append(f"{source}: {len(tiles) - len(ts)} duplicate tile(s) dropped")
    return ts, notes


def read_tileset(path: str | os.PathLike) -> tuple[WangTileSet, list[str]]:
    """Read a tile-set file (see the module docstring): ``(tile set, notes)``."""
    return tileset_from_data(read_json(path), str(path))


def write_tileset(path: str | os.PathLike, tileset: WangTileSet, *, name: str | None = None,
                  about: dict | None = None) -> None:
    """Write a tile set as a version-1 ``tilesolve/wang-tileset`` file, atomically."""
    write_text_atomic(path, dumps(tileset_to_dict(tileset, name=name, about=about)))
