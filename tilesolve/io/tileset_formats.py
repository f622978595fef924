"""Wang tile sets in the text formats of other tools, read into :class:`WangTileSet`.

===========  ======================================================================  ============
format       what a file holds                                                       detected by
===========  ======================================================================  ============
``json``     a ``tilesolve/wang-tileset`` document (N, E, S, W) or its legacy forms  ``.json``
             (:mod:`tilesolve.io.tileset_json`)
``nswe``     one tile per line, ``north south west east``; ``#`` starts a comment     ``.tiles``
             line (the meyerphi/tiling collection's ``*.tiles`` files)
``tilesat``  a header ``n_tiles n_colors width height``, then ``n_tiles`` lines      the header
             ``N E S W`` with colours ``1 .. n_colors`` (marccane/TileSAT)
``rtlb``     one tile per line or a Python list of tuples, ``(right, top, left,      a ``(``
             bottom)`` (the order of S. Labbé's Sage package ``slabbe``)
===========  ======================================================================  ============

Colours must be integers; ``nswe`` and ``rtlb`` colours are ``0 ..`` (the set's palette is
``0 .. max``), TileSAT's are shifted down by one. Duplicate tiles are dropped with a note.

Examples
--------
>>> ts, notes = parse_tileset_text("# two tiles\\n0 1 0 1\\n1 0 1 0\\n", "nswe")
>>> ts.nesw().tolist(), notes
([[0, 1, 1, 0], [1, 0, 0, 1]], [])
"""

from __future__ import annotations

import os
import re
from pathlib import Path

from tilesolve.errors import InvalidProblem
from tilesolve.model.board import WangTileSet

__all__ = ["FORMATS", "detect_format", "parse_tileset_text", "read_tileset_file"]

#: Formats by name, with the order of a tile's four colours in each.
FORMATS = {"json": "N E S W", "nswe": "north south west east", "tilesat": "N E S W (colours from 1)",
           "rtlb": "right top left bottom"}
# positions of N, E, S, W in a line of each text format
_TO_NESW = {"nswe": (0, 3, 1, 2), "tilesat": (0, 1, 2, 3), "rtlb": (1, 0, 3, 2)}
_INT = re.compile(r"[+-]?\d+")


def _lines(text: str) -> list[tuple[int, str]]:
    """Numbered lines that carry data (blank lines and ``#`` comments dropped)."""
    out = []
    for i, line in enumerate(text.splitlines(), 1):
        line = line.split("#", 1)[0].strip()
        if line:
            out.append((i, line))
    return out


def detect_format(path: str | os.PathLike, text: str) -> str:
    """The format of a tile-set file: by extension (``.json``, ``.tiles``), else by content
    (a ``(`` means ``rtlb``; a 4-number header followed by that many tile lines means
    ``tilesat``; other lines of four numbers mean ``nswe``)."""
    suffix = Path(path).suffix.lower()
    if suffix == ".json":
        return "json"
    if suffix == ".tiles":
        return "nswe"
    stripped = text.lstrip()
    if stripped.startswith(("{", "[")) and "(" not in stripped:
        return "json"
    if "(" in stripped:
        return "rtlb"
    rows = _lines(text)
    if rows:
        head = rows[0][1].split()
        if len(head) == 4 and all(_INT.fullmatch(x) for x in head) and int(head[0]) == len(rows) - 1:
            return "tilesat"
    return "nswe"


def _colour(token: str, where: str) -> int:
    if not _INT.fullmatch(token):
        raise InvalidProblem(f"{where}: colour {token!r} is not an integer")
    c = int(token)
    if c < 0:
        raise InvalidProblem(f"{where}: colour {c} is negative")
    return c


def parse_tileset_text(text: str, fmt: str, source: str = "<tile set>") -> tuple[WangTileSet, list[str]]:
    """A tile set from the text of a file in format ``fmt`` (see the module docstring).

    Returns
    -------
    (WangTileSet, list of str)
        The set and notes for the user (dropped duplicates).

    Raises
    ------
    InvalidProblem
        One line naming the source and line: wrong number of colours on a line, a colour that
        is not a non-negative integer (or outside ``1 .. n_colors`` for TileSAT), a TileSAT
        header that disagrees with the tiles, or no tiles at all.
    """
    if fmt == "json":
        import json

        from tilesolve.io.tileset_json import tileset_from_data

        try:
            data = json.loads(text)
        except json.JSONDecodeError as exc:
            raise InvalidProblem(f"{source}: not valid JSON (line {exc.lineno}: {exc.msg})") from None
        return tileset_from_data(data, source)
    if fmt not in _TO_NESW:
        raise InvalidProblem(f"unknown tile-set format {fmt!r}; choose one of {', '.join(FORMATS)}")
    order = FORMATS[fmt]
    if fmt == "rtlb":
        # a Python literal [(r, t, l, b), ...] or one tuple per line: one tile per parenthesis
        body = re.sub(r"#[^\n]*", "", text)
        rows = [(body.count("\n", 0, m.start()) + 1, m.group(1).replace(",", " "))
                for m in re.finditer(r"\(([^()]*)\)", body)]
        if not rows:
            rows = _lines(text)
    else:
        rows = _lines(text)
    n_colors = None
    if fmt == "tilesat":
        if not rows:
            raise InvalidProblem(f"{source}: empty file; TileSAT files start with 'n_tiles n_colors width height'")
        line_no, head = rows[0]
        fields = head.split()
        if len(fields) != 4 or not all(_INT.fullmatch(x) for x in fields):
            raise InvalidProblem(f"{source}: line {line_no}: the TileSAT header must be 4 integers "
                                 f"'n_tiles n_colors width height', got {head!r}")
        n_tiles, n_colors = int(fields[0]), int(fields[1])
        rows = rows[1:]
        if n_tiles != len(rows):
            raise InvalidProblem(f"{source}: the TileSAT header announces {n_tiles} tiles, the file has {len(rows)}")
        if n_colors < 1:
            raise InvalidProblem(f"{source}: the TileSAT header gives {n_colors} colours")
    if not rows:
        raise InvalidProblem(f"{source}: the tile set is empty (no tile lines)")
    idx = _TO_NESW[fmt]
    tiles = []
    for line_no, line in rows:
        where = f"{source}: line {line_no}"
        fields = line.split()
        if len(fields) != 4:
            raise InvalidProblem(f"{where}: a tile needs 4 colours ({order}), got {len(fields)}")
        cols = [_colour(x, where) for x in fields]
        if n_colors is not None:
            bad = [c for c in cols if not 1 <= c <= n_colors]
            if bad:
                raise InvalidProblem(f"{where}: colour {bad[0]} is outside 1..{n_colors} (the header's colour count)")
            cols = [c - 1 for c in cols]
        tiles.append([cols[i] for i in idx])
    k = n_colors if n_colors is not None else 1 + max(max(t) for t in tiles)
    ts = WangTileSet.from_nesw(tiles, k)
    notes = []
    if len(ts) < len(tiles):
        notes.append(f"{source}: {len(tiles) - len(ts)} duplicate tile(s) dropped")
    return ts, notes


def read_tileset_file(path: str | os.PathLike, fmt: str | None = None) -> tuple[WangTileSet, list[str]]:
    """Read a tile-set file in any format of :data:`FORMATS` (``fmt=None``: detected)."""
    if fmt == "json" or (fmt is None and Path(path).suffix.lower() == ".json"):
        from tilesolve.io.tileset_json import read_tileset

        return read_tileset(path)
    try:
        text = Path(path).read_text(encoding="utf-8")
    except UnicodeDecodeError:
        raise InvalidProblem(f"cannot read {path}: not a UTF-8 text file") from None
    except OSError as exc:
        raise InvalidProblem(f"cannot read {path}: {exc.strerror or exc}") from None
    return parse_tileset_text(text, fmt or detect_format(path, text), str(path))
