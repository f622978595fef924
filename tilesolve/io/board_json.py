"""JSON files of Wang tilings of boards: ``"format": "tilesolve/board-solution"``, versions 1, 2 and 3.

The board travels as plain data so any tool can re-check a tiling without tilesolve.
tilesolve writes version 3; it reads all three (:func:`read_board_solution`), and ``tilesolve
verify`` checks files of every version.

Fields of every version:

``board_kind``
    how the board was built (``"rect"``, ``"mobius"``, ``"mask"``, ``"mobius|U"``, ...).
``leg_order``
    the order of each tile's four colours and the numbers of a cell's legs in ``edges``:
    ``["N", "E", "S", "W"]`` in version 3 (tilesolve's public edge order, as in tile-set files
    and reports); ``["W", "N", "E", "S"]`` in versions 1 and 2 (the brick paper's legs
    l1..l4). Either way the legs go round the cell, so legs 0/2 and 1/3 are opposite.
``colors``
    ``#C``; colours are ``0 .. colors-1``.
``tileset``
    ``"brick"`` for W_B (Def. 9) or a list of tiles, each its colours in ``leg_order``. Tile
    ``i`` is the ``i``-th of the list.
``max_h``, ``max_v``
    brick walls: longest horizontal run of W_H tiles / vertical run of W_V tiles (or null).
``grid``, ``mask``
    for a board cut from a grid (rectangle, torus, cylinder, Möbius strip, Klein bottle,
    ring, mask, or a restriction of one): the grid and the cells present, as in version 2
    below (in version 1, ``mask`` is a list of rows of 0/1).
``window`` (version 3, optional)
    where the tiling lies in the plane, for a tiling cut from an infinite one (a procedural
    or repeatable wall): ``{"x0", "y0", "width", "height", "y_up"}``
    (:class:`~tilesolve.model.window.Window`); grid row 0, column 0 is its cell
    ``(x0, y0 + height - 1)`` when ``y_up``. The window is the board's grid: a file whose window
    is not ``cols x rows`` of its ``grid`` is refused. Files of versions 1 and 2 record no
    window (a wall's window was only named in a note, which is not read): theirs is unknown.

plus the solution's ``status``, ``method``, ``solver``, ``seed``, ``time_s``, ``reason``,
``notes`` and ``stats``, and the free texts ``created_by`` and ``comment``. A reader refuses
any other field.

Boundary legs are numbered ``0, 1, ...`` in order of cell, then of the cell's legs: N, E, S, W
in version 3 (the board model's numbering, which ``--boundary`` files use too), W, N, E, S in
versions 1 and 2 (converted when read, :func:`_boundary_seam`).

The board is *described* by ``board_kind`` with ``grid`` and ``mask``; a file without
``grid`` (written before version 1 had it) describes a board of a kind in
:data:`~tilesolve.model.board.GRID_KINDS` by the grid its cells' labels span. A board of any
other kind (a sheared torus, a board given by its joins) is described by ``cells`` and
``edges`` alone. Where a file both describes its board and lists ``cells`` and ``edges``, the
list must be exactly the board described: ``tilesolve verify`` reports every difference as a
violation (exit 1), and ``tilesolve draw`` refuses the file (exit 2). A file that holds no
tiling (an ``unsat`` or ``unknown`` answer, which is about the board described) is refused
when the board family reads it (exit 2). The kind binds the grid: a ``rect``, ``torus``,
``cylinder``, ``mobius`` or ``klein`` board is every cell of its grid, with the sides
identified as that kind's are; a ``ring`` board the border of its grid; a ``mask`` or
``tree`` board any cells of a grid whose sides meet the wall; a restriction such as
``mobius|U`` any cells of the Möbius strip of its grid.

Sizes and colour counts are checked before anything is built: a grid of at most
:data:`~tilesolve.model.board.MAX_BOARD_CELLS` cells; ``colors`` from 3 to
:data:`~tilesolve.model.board.MAX_BRICK_COLORS` for ``"brick"`` (the limit of
``tilesolve brick``), at most :data:`MAX_LIST_COLORS` for a list of tiles; line limits
up to :data:`MAX_LINE`.

Version 1 (plain lists; written for boards of at most :data:`COMPACT_MIN_CELLS` cells)
--------------------------------------------------------------------------------------
``cells``
    ``[row, col]`` label of each cell (cell ``i`` is the ``i``-th entry).
``edges``
    ``[a, ka, b, kb]``: leg ``ka`` of cell ``a`` is joined to leg ``kb`` of cell ``b``;
    ``b = -1`` means the wall, and then ``kb`` numbers that boundary leg (0, 1, ...).
    tilesolve lists a join once, from its smaller ``(cell, leg)``, in order of ``(a, ka)``;
    a reader takes the joins in any order and either way round.
``boundary``
    the colour required on each boundary leg, by boundary-leg number (``null`` = free).
``tiles``
    for each cell, the colours of its legs l1..l4 (absent or null when there is no tiling).

Version 2 (compact; written for larger boards)
----------------------------------------------
Every array is an *encoded array* ``{"dtype", "shape", "data"}``: base64 of the values in
row-major order, little-endian integers or bit-packed 0/1 values (``bits``); the exact
rules and a five-line Python reader are in :mod:`tilesolve.io.jsonio`.

``grid``
    for a board cut from a grid: ``{"rows": R, "cols": C, "wrap_rows": w,
    "wrap_cols": w}`` with ``w`` one of ``null`` (the sides meet the wall), ``"plain"``
    (column ``C-1`` meets column 0 in the same row; for ``wrap_rows``, row ``R-1`` meets
    row 0 in the same column) or ``"twist"`` (row ``r`` meets row ``R-1-r``, the Möbius
    identification of Example 5; for ``wrap_rows``, column ``c`` meets ``C-1-c``).
``mask``
    with ``grid``: ``bits`` array of shape ``[R, C]``, 1 where a cell is present, or null
    when every grid cell is. Cells are numbered in row-major order of the mask. Each
    cell's legs W, N, E, S meet the E, S, W, N legs of its neighbours at ``(r, c-1)``,
    ``(r-1, c)``, ``(r, c+1)``, ``(r+1, c)`` (across the identified sides as above); a leg
    with no cell there meets the wall, and the wall legs are numbered 0, 1, ... in order of
    cell then leg (W, N, E, S).
``cells``, ``edges``
    instead of ``grid``/``mask``, for any other board: encoded arrays of shapes
    ``[n, 2]`` and ``[m, 4]``, read as in version 1. (A file may carry them besides
    ``grid``; they must then be that board.)
``boundary``
    encoded array of shape ``[n_boundary]``: the colour required on each boundary leg, -1 = free.
``tiles``
    encoded array of shape ``[n, 4]`` (the colours of each cell's legs W, N, E, S), or null.

Version 3 (written by tilesolve now)
------------------------------------
Version 2's fields, with every tile in the order N, E, S, W: ``tileset``, each cell's
``tiles`` and the leg numbers of ``edges`` (0 = N, 1 = E, 2 = S, 3 = W); the wall legs of a
grid board numbered in order of cell, then of leg N, E, S, W; and an optional ``window``.
An array may be a plain list (as in version 1; ``boundary`` then holds ``null`` for a free
leg) or an encoded array; tilesolve writes plain lists, with ``cells`` and
``edges`` listed, for boards of at most :data:`COMPACT_MIN_CELLS` cells, and encoded arrays
(grid boards as their grid and mask alone) for larger ones.

The board model numbers its legs as version 3 does, N, E, S, W (:mod:`tilesolve.model.board`),
so version 3 is written and read as it stands; an older file's leg order is converted when read
at one place, :func:`_leg_seam` (and its boundary-leg numbers at :func:`_boundary_seam`).
"""

from __future__ import annotations

import dataclasses
import json
import os
from dataclasses import dataclass
from typing import Any

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.io.atomic import atomic_write, write_text_atomic
from tilesolve.io.jsonio import (
    check_document, decode_array, dumps, encode_array, encoded_dtype, encoded_text, provenance_to_dict, read_json,
    solution_from_provenance,
)
from tilesolve.model.board import (
    GRID_KINDS, LEG_NAMES, MAX_BOARD_CELLS, MAX_BRICK_COLORS, E, N, S, W, Board, BoardProblem, GridSpec,
    WangTileSet, described_board, grid_kind,
)
from tilesolve.model.solution import Solution
from tilesolve.model.window import Window

__all__ = ["BOARD_SOLUTION", "VERSIONS", "VERSION", "LEG_ORDERS", "COMPACT_MIN_CELLS", "MAX_LIST_COLORS", "MAX_LINE", "ListedBoardProblem",
           "board_solution_to_dict", "board_solution_from_dict", "write_board_solution", "write_rect_solution",
           "read_board_solution", "read_boundary"]

BOARD_SOLUTION = "tilesolve/board-solution"
#: Versions of ``tilesolve/board-solution`` this module reads.
VERSIONS = frozenset({1, 2, 3})
#: The version this module writes.
VERSION = 3
#: The leg order of each version's tiles and edges.
LEG_ORDERS = {1: ("W", "N", "E", "S"), 2: ("W", "N", "E", "S"), 3: LEG_NAMES}
#: Boards with more cells than this are written with encoded arrays.
COMPACT_MIN_CELLS = 4096
#: Cells of tiles :func:`write_rect_solution` encodes at a time (a multiple of 6: whole base64 pieces).
STREAM_CELLS = 6 << 14
#: Stands for the tiles' base64 text in the document :func:`write_rect_solution` splits around it.
_PIECES = "\x00tiles"
#: Most colours a tile set given as a list of tiles may declare: more than 16,384 tiles can
#: use with four new colours each.
MAX_LIST_COLORS = 1 << 16
#: Longest line limit (``max_h``, ``max_v``): the bound of the CLI's ``--max-h`` and ``--max-v``.
MAX_LINE = 2**31 - 1
_WRAP_NAMES = (None, "plain", "twist")
_KEYS = frozenset({
    "format", "version", "board_kind", "leg_order", "colors", "tileset", "max_h", "max_v", "grid", "mask", "cells",
    "edges", "boundary", "tiles", "window", "status", "method", "solver", "seed", "time_s", "reason", "notes",
    "stats", "created_by", "comment",
})
#: The board model's leg of each leg 0..3 of a version 1 or 2 file (W, N, E, S), and the file's
#: column of each of the model's legs (N, E, S, W).
_LEG_OF_OLD = np.array([W, N, E, S])
_OLD_COLUMN = np.argsort(_LEG_OF_OLD)


@dataclass(frozen=True, eq=False)
class ListedBoardProblem(BoardProblem):
    """A board problem read from a file that both describes its board and lists it.

    ``board`` is rebuilt from the description (kind, grid, mask); ``listed_cells`` and
    ``listed_edges`` are the ``cells`` and ``edges`` the file lists, as read, for the verifier
    to hold against it (:func:`tilesolve.verify.board.listing_violations`).
    """

    listed_cells: np.ndarray | None = None
    listed_edges: np.ndarray | None = None


def _leg_seam(version: int, *, tiles=None, edges=None) -> tuple:
    """The one seam between a file's leg order (:data:`LEG_ORDERS`) and the board model's legs
    N, E, S, W: each cell's ``tiles`` (colours per leg) and the leg numbers of ``edges``
    (``[a, ka, b, kb]``; ``kb`` numbers a boundary leg where ``b = -1`` and is left alone), out
    of a file of ``version``. Version 3 is in the model's order; versions 1 and 2 list the legs
    W, N, E, S. Leg numbers outside 0..3 are left as read, for the board's checks to name.
    Returns ``(tiles, edges)`` as ``(n, 4)`` integer arrays (or ``None`` where not given).

    >>> tiles, edges = _leg_seam(2, tiles=[[3, 0, 1, 2]], edges=[[0, 2, 1, 0], [0, 0, -1, 0]])
    >>> tiles.tolist(), edges.tolist()
    ([[0, 1, 2, 3]], [[0, 1, 1, 3], [0, 3, -1, 0]])
    """
    old = version < 3
    if tiles is not None:  # a file's integer array: its columns reordered while narrow, then widened once
        tiles = np.asarray(tiles).reshape(-1, 4)
        tiles = (tiles[:, _OLD_COLUMN] if old else tiles).astype(np.int64)
    if edges is not None:
        edges = np.array(edges, dtype=np.int64).reshape(-1, 4)
        for legs, on in ((edges[:, 1], True), (edges[:, 3], edges[:, 2] >= 0)) if old else ():
            move = on & (legs >= 0) & (legs < 4)
            legs[move] = _LEG_OF_OLD[legs[move]]
    return tiles, edges


def _boundary_seam(version: int, board: Board, boundary: np.ndarray, listed):
    """A version 1 or 2 file's boundary-leg numbers as the board model gives them, for a board
    rebuilt from the file's description: the colours of ``boundary`` and the wall legs of the
    ``listed`` ``(cells, edges)``. Those versions numbered boundary legs in order of cell, then
    of leg W, N, E, S; the model numbers them by cell, then N, E, S, W, as version 3 does. A
    board given by its joins alone keeps the file's own numbers.
    """
    if version >= 3 or board.grid_spec is None:
        return boundary, listed
    a, k = np.nonzero(board.nbr_cell < 0)
    old = np.argsort(a * 4 + _OLD_COLUMN[k], kind="stable")  # in order of cell, then of leg W, N, E, S
    new = board.nbr_leg[a[old], k[old]]  # the model's number of the file's boundary leg 0, 1, ...
    if boundary.shape == new.shape:  # another length is BoardProblem's to name
        moved = np.empty_like(boundary)
        moved[new] = boundary
        boundary = moved
    if listed is not None:
        e = listed[1].copy()
        wall = (e[:, 2] == -1) & (e[:, 3] >= 0) & (e[:, 3] < new.size)
        e[wall, 3] = new[e[wall, 3]]
        listed = (listed[0], e)
    return boundary, listed


def _head(kind: str, tileset: WangTileSet, max_h: int | None, max_v: int | None, solution: Solution) -> dict:
    """The fields of a version 3 document before the board's grid and arrays."""
    doc = {
        "format": BOARD_SOLUTION,
        "version": VERSION,
        "board_kind": kind,
        "leg_order": list(LEG_ORDERS[VERSION]),
        "colors": tileset.n_colors,
        "tileset": "brick" if tileset.is_brick else np.asarray(tileset.tiles),
        "max_h": max_h,
        "max_v": max_v,
        **provenance_to_dict(solution),
        "stats": {k: v for k, v in solution.stats.items() if not isinstance(v, np.ndarray)},
    }
    if solution.window is not None:
        doc["window"] = solution.window.to_dict()
    return doc


def _grid_fields(spec: GridSpec) -> dict:
    return {"rows": spec.rows, "cols": spec.cols, "wrap_rows": spec.wrap_rows, "wrap_cols": spec.wrap_cols}


def board_solution_to_dict(problem: BoardProblem, solution: Solution, *, compact: bool | None = None) -> dict:
    """The JSON document (version 3) of a board solution.

    Parameters
    ----------
    problem, solution
    compact : bool, optional
        Write encoded arrays (grid boards as their grid and mask alone) rather than plain
        lists (grid boards also listed cell by cell). Default: encoded arrays for boards of
        more than :data:`COMPACT_MIN_CELLS` cells.
    """
    b = problem.board
    if compact is None:
        compact = b.n_cells > COMPACT_MIN_CELLS
    doc = _head(b.kind, problem.tileset, problem.max_h, problem.max_v, solution)
    array = encode_array if compact else np.asarray
    if b.grid_spec is not None:
        spec = b.grid_spec
        doc["grid"] = _grid_fields(spec)
        doc["mask"] = None if b.n_cells == spec.rows * spec.cols else array(b.mask_of().astype(np.uint8))
    tiles = None if solution.tiling is None else np.asarray(solution.tiling, dtype=np.int64).reshape(-1, 4)
    if not compact or b.grid_spec is None:
        doc["cells"] = array(b.labels)
        doc["edges"] = array(b.edge_array())
    if compact:
        doc["boundary"] = encode_array(problem.boundary)
        doc["tiles"] = None if tiles is None else encode_array(tiles)
    else:
        doc["boundary"] = [None if c < 0 else c for c in problem.boundary.tolist()]
        doc["tiles"] = tiles
    return doc


def _int(doc: dict, name: str, source: Any, *, optional: bool = False) -> int | None:
    v = doc.get(name)
    if v is None and optional:
        return None
    if isinstance(v, bool) or not isinstance(v, int):
        raise InvalidProblem(f"{source}: {name!r} must be an integer, got {v!r}")
    return v


def _check_header(doc: Any, source: Any) -> int:
    """The file's version, once its format, version and fields are checked."""
    version = check_document(doc, source, {BOARD_SOLUTION: VERSIONS})["version"]
    unknown = sorted(set(doc) - _KEYS)
    if unknown:
        raise InvalidProblem(f"{source}: unknown field {unknown[0]!r} in a {BOARD_SOLUTION} file")
    return version


def _array(doc: dict, name: str, source: Any, version: int, ndim: int, width: int | None = None) -> np.ndarray:
    """Field ``name`` as an integer array (a list in version 1, a list or encoded array in 2)."""
    value = doc[name]
    if version < 2 and not isinstance(value, list):
        raise InvalidProblem(f"{source}: {name!r} must be a list (encoded arrays need version 2)")
    arr = decode_array(value, name, source, ndim=ndim)
    if arr.size == 0 and width is not None:
        arr = arr.reshape(0, width)
    if width is not None and arr.shape[1:] != (width,):
        raise InvalidProblem(f"{source}: {name!r} must hold {width} integers per entry, got shape {list(arr.shape)}")
    return arr


def _tileset(doc: dict, source: Any, version: int) -> WangTileSet:
    """The tile set (in the file's order), its colour count checked before anything is built."""
    colors = _int(doc, "colors", source)
    ts = doc.get("tileset")
    if ts == "brick":
        if not 3 <= colors <= MAX_BRICK_COLORS:
            raise InvalidProblem(f"{source}: 'colors' is {colors}; brick Wang tiles have 3 to {MAX_BRICK_COLORS} "
                                 "colours here (Def. 9)")
        return WangTileSet.brick(colors)
    if not isinstance(ts, list):
        raise InvalidProblem(f"{source}: 'tileset' must be \"brick\" or a list of tiles, got {type(ts).__name__}")
    if not 1 <= colors <= MAX_LIST_COLORS:
        raise InvalidProblem(f"{source}: 'colors' is {colors}; a list of tiles has 1 to {MAX_LIST_COLORS} colours here")
    tiles = decode_array(ts, "tileset", source)
    if version < 3 and tiles.ndim == 2 and tiles.shape[1] == 4:
        tiles = tiles[:, _OLD_COLUMN]  # versions 1 and 2 list the legs W, N, E, S
    try:
        return WangTileSet(tiles, colors)
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: 'tileset': {exc}") from None


def _grid_spec(g: Any, source: Any) -> GridSpec:
    if not isinstance(g, dict) or set(g) != {"rows", "cols", "wrap_rows", "wrap_cols"}:
        raise InvalidProblem(f"{source}: 'grid' must be {{\"rows\", \"cols\", \"wrap_rows\", \"wrap_cols\"}}")
    rows, cols = _int(g, "rows", f"{source}: 'grid'"), _int(g, "cols", f"{source}: 'grid'")
    for name in ("wrap_rows", "wrap_cols"):
        if g[name] not in _WRAP_NAMES:
            raise InvalidProblem(f"{source}: 'grid'.{name} must be null, \"plain\" or \"twist\", got {g[name]!r}")
    if rows < 1 or cols < 1:
        raise InvalidProblem(f"{source}: 'grid' must have positive rows and cols, got {cols}x{rows}")
    if rows * cols > MAX_BOARD_CELLS:
        raise InvalidProblem(f"{source}: 'grid' is {cols}x{rows}; tilesolve's boards have at most "
                             f"{MAX_BOARD_CELLS:,} cells")
    return GridSpec(rows, cols, g["wrap_rows"], g["wrap_cols"])


def _mask(doc: dict, spec: GridSpec, source: Any, version: int) -> np.ndarray | None:
    if doc.get("mask") is None:
        return None
    m = _array(doc, "mask", source, version, ndim=2)
    if m.shape != (spec.rows, spec.cols) or ((m != 0) & (m != 1)).any():
        raise InvalidProblem(f"{source}: 'mask' must hold 0/1 values of shape [{spec.rows}, {spec.cols}], "
                             f"got shape {list(m.shape)}")
    return m.astype(bool)


def _spanned_grid(kind: str, cells: np.ndarray, source: Any) -> tuple[GridSpec, np.ndarray]:
    """The grid and mask of a grid kind's board in a file without ``grid``: the grid its cells'
    labels span, the cells where they are."""
    if cells.size == 0:
        raise InvalidProblem(f"{source}: a {kind} board needs cells")
    if cells.min() < 0:
        i = int(np.flatnonzero((cells < 0).any(axis=1))[0])
        raise InvalidProblem(f"{source}: cell {i} has the label {cells[i].tolist()}; without 'grid', a {kind} "
                             "board's grid is the one its cells' labels span")
    rows, cols = (int(v) + 1 for v in cells.max(axis=0))
    if rows * cols > MAX_BOARD_CELLS:
        raise InvalidProblem(f"{source}: the cells' labels span {cols}x{rows}; tilesolve's boards have at most "
                             f"{MAX_BOARD_CELLS:,} cells")
    mask = np.zeros((rows, cols), bool)
    mask[cells[:, 0], cells[:, 1]] = True
    return GridSpec(rows, cols, *GRID_KINDS[grid_kind(kind)]), mask


def _board(doc: dict, source: Any, version: int, kind: str, listed) -> Board:
    """The board the file describes (see the module docstring)."""
    if doc.get("grid") is not None:
        spec = _grid_spec(doc["grid"], source)
        grid = spec, _mask(doc, spec, source, version)
    elif listed is None:
        raise InvalidProblem(f"{source}: a board solution needs 'grid' or 'cells' and 'edges'")
    elif grid_kind(kind) is not None:
        grid = _spanned_grid(kind, listed[0], source)
    else:
        grid = None
    try:
        return Board.from_edges(*listed, kind=kind) if grid is None else described_board(kind, *grid)
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: {exc}") from None


def _colour_list(value: Any, what: str, source: Any, message: str) -> np.ndarray:
    """A JSON list of colours (``null`` = free) as an array with ``-1`` for free legs."""
    if not isinstance(value, list) or not all(v is None or (isinstance(v, int) and not isinstance(v, bool))
                                              for v in value):
        raise InvalidProblem(f"{source}: {message}")
    return decode_array([-1 if v is None else v for v in value], what, source, ndim=1)


def _boundary(doc: dict, source: Any, version: int, board: Board) -> np.ndarray:
    bnd = doc.get("boundary")
    if bnd is None:
        return np.full(board.n_boundary, -1, np.int64)
    if version >= 2 and not (version >= 3 and isinstance(bnd, list)):
        return decode_array(bnd, "boundary", source, ndim=1)
    return _colour_list(bnd, "boundary", source, "'boundary' must be a list of colours or null")


def board_solution_from_dict(doc: dict, source: Any = "<document>") -> tuple[BoardProblem, Solution]:
    """Rebuild ``(problem, solution)`` from a version 1, 2 or 3 document, in the board model's
    legs N, E, S, W (:func:`_leg_seam`); the tiles are read as written (the verifier judges
    them).

    The board is rebuilt from the file's description. Where the file also lists its cells
    and edges, the problem is a :class:`ListedBoardProblem` that keeps them for the verifier.

    Raises
    ------
    InvalidProblem
        One line naming ``source`` and the field, for anything malformed, out of range or
        contradictory (a board description that contradicts itself, an unknown field).
    """
    version = _check_header(doc, source)
    order = list(LEG_ORDERS[version])
    if doc.get("leg_order", order) != order:
        raise InvalidProblem(f"{source}: leg_order {doc['leg_order']!r} is not that of version {version}, {order}")
    tileset = _tileset(doc, source, version)
    kind = doc.get("board_kind") or "board"
    if not isinstance(kind, str):
        raise InvalidProblem(f"{source}: 'board_kind' must be a string, got {kind!r}")
    listed = None
    if "cells" in doc or "edges" in doc:
        if not ("cells" in doc and "edges" in doc):
            raise InvalidProblem(f"{source}: a board solution lists 'cells' and 'edges' together")
        edges = _array(doc, "edges", source, version, 2, 4)
        listed = (_array(doc, "cells", source, version, 2, 2),
                  _leg_seam(version, edges=edges)[1])
        if listed[0].shape[0] > MAX_BOARD_CELLS:
            raise InvalidProblem(f"{source}: 'cells' lists {listed[0].shape[0]:,} cells; tilesolve's boards have at "
                                 f"most {MAX_BOARD_CELLS:,}")
    elif version < 2:
        raise InvalidProblem(f"{source}: a version 1 board solution lists 'cells' and 'edges'")
    board = _board(doc, source, version, kind, listed)
    beta = _boundary(doc, source, version, board)
    beta, listed = _boundary_seam(version, board, beta, listed)
    lines = {name: _int(doc, name, source, optional=True) for name in ("max_h", "max_v")}
    for name, v in lines.items():
        if v is not None and not 1 <= v <= MAX_LINE:
            raise InvalidProblem(f"{source}: {name!r} is {v}; a line limit is 1 to {MAX_LINE}")
    try:
        if listed is not None and board.grid_spec is not None:  # described and listed: keep the list
            problem = ListedBoardProblem(board, tileset, beta, **lines, listed_cells=listed[0], listed_edges=listed[1])
        else:
            problem = BoardProblem(board, tileset, beta, **lines)
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: {exc}") from None
    tiling = None
    if doc.get("tiles") is not None:
        tiling = _array(doc, "tiles", source, version, 2)
        if tiling.ndim == 2 and tiling.shape[1] == 4:  # another shape is left for the verifier to name
            tiling = _leg_seam(version, tiles=tiling)[0]
    solution = solution_from_provenance(doc, source, tiling, what="tiles")
    if doc.get("window") is not None:
        if version < 3:
            raise InvalidProblem(f"{source}: 'window' needs version 3")
        try:
            window = Window.from_dict(doc["window"])
        except InvalidProblem as exc:
            raise InvalidProblem(f"{source}: 'window': {exc}") from None
        spec = board.grid_spec
        if spec is None or (spec.rows, spec.cols) != window.shape:
            grid = "no grid" if spec is None else f"the grid {spec.cols}x{spec.rows}"
            raise InvalidProblem(f"{source}: 'window' is {window.width}x{window.height} cells (WxH), but the board "
                                 f"has {grid}: a window of the plane is the board's grid")
        solution = dataclasses.replace(solution, window=window)
    return problem, solution


def write_board_solution(path: str | os.PathLike, problem: BoardProblem, solution: Solution, *,
                         compact: bool | None = None) -> None:
    """Write a ``tilesolve/board-solution`` file atomically (``compact`` as in
    :func:`board_solution_to_dict`)."""
    write_text_atomic(path, dumps(board_solution_to_dict(problem, solution, compact=compact)))


def write_rect_solution(path: str | os.PathLike, legs, tileset: WangTileSet, solution: Solution, *,
                        max_h: int | None = None, max_v: int | None = None) -> None:
    """Write the ``tilesolve/board-solution`` file of a tiling of the free rectangle, streamed.

    The file is byte for byte :func:`write_board_solution` of
    ``BoardProblem(Board.rect(cols, rows), tileset, None, max_h=max_h, max_v=max_v)`` and
    ``solution`` with the tiling ``legs``, but neither the board nor the document's text is
    built whole: the tiles' base64 is written a piece at a time, so a large wall costs its
    ``legs`` and one piece (:data:`STREAM_CELLS` cells).

    Parameters
    ----------
    path : str or os.PathLike
        Written atomically (``"-"``: standard output).
    legs : numpy.ndarray
        ``(rows, cols, 4)`` leg colours (N, E, S, W) of each cell, row 0 at the top.
    tileset, solution, max_h, max_v
        As :class:`~tilesolve.model.board.BoardProblem` and
        :func:`board_solution_to_dict` take them (``solution.tiling`` is not read).

    Examples
    --------
    >>> import io, json
    >>> from tilesolve.model.solution import Status
    >>> legs = np.array([[[1, 0, 2, 0], [1, 2, 1, 0]]])
    >>> out = io.StringIO()
    >>> from contextlib import redirect_stdout
    >>> with redirect_stdout(out):
    ...     write_rect_solution("-", legs, WangTileSet.brick(3), Solution(Status.SAT))
    >>> json.loads(out.getvalue())["tiles"]
    [[1, 0, 2, 0], [1, 2, 1, 0]]
    """
    legs = np.asarray(legs)
    rows, cols = legs.shape[:2]
    n = rows * cols
    flat = legs.reshape(n, 4)
    if n <= COMPACT_MIN_CELLS:  # plain lists, cells and edges listed: small enough to build whole
        problem = BoardProblem(Board.rect(cols, rows), tileset, None, max_h=max_h, max_v=max_v)
        write_board_solution(path, problem, dataclasses.replace(solution, tiling=flat))
        return
    doc = _head("rect", tileset, max_h, max_v, solution)
    doc["grid"] = _grid_fields(GridSpec(rows, cols, None, None))
    doc["mask"] = None
    doc["boundary"] = encode_array(np.full(2 * (rows + cols), -1, np.int8))
    name = encoded_dtype(int(flat.min()), int(flat.max()))
    doc["tiles"] = {"dtype": name, "shape": [n, 4], "data": _PIECES}
    head, tail = dumps(doc).split(json.dumps(_PIECES))
    with atomic_write(path, "w") as f:
        f.write(head + '"')
        for i in range(0, n, STREAM_CELLS):
            f.write(encoded_text(flat[i:i + STREAM_CELLS], name))
        f.write('"' + tail)


def read_board_solution(path: str | os.PathLike) -> tuple[BoardProblem, Solution]:
    """Read a ``tilesolve/board-solution`` file (version 1, 2 or 3) as ``(problem, solution)``."""
    return board_solution_from_dict(read_json(path), path)


def read_boundary(path: str | os.PathLike) -> np.ndarray:
    """A boundary file: a JSON list of colours by boundary-leg number (``null`` = free; legs
    numbered by cell, then N, E, S, W), or an object whose ``"boundary"`` field is that list.
    A board solution's boundary is read as the solution is (any version, its numbers as the
    board model's). Returns colours with ``-1`` for free legs."""
    data = read_json(path)
    if isinstance(data, dict) and data.get("format") == BOARD_SOLUTION:
        return board_solution_from_dict(data, path)[0].boundary
    if isinstance(data, dict):
        data = data.get("boundary")
    return _colour_list(data, "boundary", path, "a boundary file holds a list of colours (null = free), "
                                                "or an object with 'boundary'")
