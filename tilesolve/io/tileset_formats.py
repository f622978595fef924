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

Colours must be integers; ``nswe`` and ``rtlb`` colours are ``0 ..``, TileSAT's are shifted
down by one. A set's palette is the colours its tiles use, relabelled ``0 .. k-1`` in order
when they are not already (with a note); duplicate tiles are dropped with a note. A file is
read through the input limit (:func:`tilesolve.inputs.read_input`), and a file that
contradicts its format (a TileSAT header announcing more tiles than follow, an ``rtlb`` list
cut short) is refused, never re-read as another format.

Examples
--------
>>> ts, notes = parse_tileset_text("# two tiles\\n0 1 0 1\\n1 0 1 0\\n", "nswe")
>>> ts.tiles.tolist(), notes
([[0, 1, 1, 0], [1, 0, 0, 1]], [])
"""

from __future__ import annotations

import os
import re
from pathlib import Path

from tilesolve.errors import InvalidProblem
from tilesolve.inputs import read_input_text
from tilesolve.io.jsonio import parse_json
from tilesolve.io.tileset_json import compact_tileset, tileset_from_data
from tilesolve.model.board import WangTileSet

__all__ = ["FORMATS", "detect_format", "parse_tileset_text", "read_tileset_file"]

#: Formats by name, with the order of a tile's four colours in each.
FORMATS = {"json": "N E S W", "nswe": "north south west east", "tilesat": "N E S W (colours from 1)",
           "rtlb": "right top left bottom"}
# positions of N, E, S, W in a line of each text format
_TO_NESW = {"nswe": (0, 3, 1, 2), "tilesat": (0, 1, 2, 3), "rtlb": (1, 0, 3, 2)}
_INT = re.compile(r"[+-]?\d+")
_TUPLE = re.compile(r"\(([^()]*)\)")


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
    ``tilesat``; other lines of four numbers mean ``nswe``).

    Detection never switches silently: a first line that reads as a TileSAT header announcing
    more tiles than the file holds (every colour after it within the header's ``1 ..
    n_colors``) is a truncated TileSAT file or an ``nswe`` file, and is refused until
    ``--format`` says which.

    >>> detect_format("t.txt", "3 4 2 2\\n1 1 2 1\\n2 4 3 1\\n3 1 3 2\\n")
    'tilesat'
    >>> detect_format("t.txt", "3 4 2 2\\n1 1 2 1\\n2 4 3 1\\n")
    Traceback (most recent call last):
    ...
    tilesolve.errors.InvalidProblem: t.txt: the first line reads as a TileSAT header announcing 3 tiles, but 2 tile lines follow; give --format tilesat (and complete the file) or --format nswe
    """
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
    head = rows[0][1].split() if rows else []
    if len(head) != 4 or not all(_INT.fullmatch(x) and len(x) < 20 for x in head):
        return "nswe"
    n_tiles, n_colors = int(head[0]), int(head[1])
    if n_tiles == len(rows) - 1:
        return "tilesat"
    rest = [x for _, line in rows[1:] for x in line.split()]
    if n_tiles > len(rows) - 1 and all(_INT.fullmatch(x) and len(x) < 20 and 1 <= int(x) <= n_colors for x in rest):
        raise InvalidProblem(f"{path}: the first line reads as a TileSAT header announcing {n_tiles} tiles, but "
                             f"{len(rows) - 1} tile lines follow; give --format tilesat (and complete the file) "
                             "or --format nswe")
    return "nswe"


def _colour(token: str, where: str) -> int:
    if not _INT.fullmatch(token):
        raise InvalidProblem(f"{where}: colour {token[:20]!r} is not an integer")
    if len(token.lstrip("+-0")) > 18:
        raise InvalidProblem(f"{where}: colour {token[:20]}... is too large (colours are below 10**18)")
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
        return tileset_from_data(parse_json(text, source), source)
    if fmt not in _TO_NESW:
        raise InvalidProblem(f"unknown tile-set format {fmt!r}; choose one of {', '.join(FORMATS)}")
    order = FORMATS[fmt]
    if fmt == "rtlb":
        # a Python literal [(r, t, l, b), ...] or one tuple per line: one tile per parenthesis
        body = re.sub(r"#[^\n]*", "", text)
        rows = [(body.count("\n", 0, m.start()) + 1, m.group(1).replace(",", " "))
                for m in _TUPLE.finditer(body)]
        if rows:
            _check_tuple_list(body, source)
        else:
            rows = _lines(text)
    else:
        rows = _lines(text)
    n_colors = None
    if fmt == "tilesat":
        if not rows:
            raise InvalidProblem(f"{source}: empty file; TileSAT files start with 'n_tiles n_colors width height'")
        line_no, head = rows[0]
        fields = head.split()
        if len(fields) != 4 or not all(_INT.fullmatch(x) and len(x) < 20 for x in fields):
            raise InvalidProblem(f"{source}: line {line_no}: the TileSAT header must be 4 integers "
                                 f"'n_tiles n_colors width height', got {head[:60]!r}")
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
    return compact_tileset(tiles, source, n_colors)


def _check_tuple_list(body: str, source: str) -> None:
    """Between the tuples of an ``rtlb`` file only commas, brackets, blanks and an assignment
    (``tiles = [...]``) may stand, and brackets and parentheses must close: a truncated or
    garbled file is refused, not read as the tuples that survived."""
    rest = re.sub(r"(?m)^\s*[A-Za-z_][\w.]*\s*=", " ", _TUPLE.sub(" ", body))
    stray = re.search(r"[^\s,\[\]]", rest)
    if stray:
        line = rest.count("\n", 0, stray.start()) + 1
        what = "an unclosed '(' (is the file truncated?)" if stray.group() == "(" else repr(rest[stray.start():][:20])
        raise InvalidProblem(f"{source}: line {line}: {what} outside the (right, top, left, bottom) tuples")
    if rest.count("[") != rest.count("]"):
        raise InvalidProblem(f"{source}: the brackets of the list of tuples do not close (is the file truncated?)")


def read_tileset_file(path: str | os.PathLike, fmt: str | None = None) -> tuple[WangTileSet, list[str]]:
    """Read a tile-set file in any format of :data:`FORMATS` (``fmt=None``: detected)."""
    if fmt == "json" or (fmt is None and Path(path).suffix.lower() == ".json"):
        from tilesolve.io.tileset_json import read_tileset

        return read_tileset(path)
    text = read_input_text(path)
    return parse_tileset_text(text, fmt or detect_format(path, text), str(path))
