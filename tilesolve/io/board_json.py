"""JSON files of Wang tilings of boards: ``"format": "tilesolve/board-solution"``, versions 1 and 2.

The board travels as plain data so any tool can re-check a tiling without tilesolve.
Fields of both versions:

``board_kind``
    how the board was built (``"rect"``, ``"mobius"``, ``"mask"``, ``"mobius|U"``, ...).
``leg_order``
    ``["W", "N", "E", "S"]``: legs l1..l4 go round the cell, so l1/l3 and l2/l4 are
    opposite (Def. 9 of the brick paper assumes this).
``colors``
    ``#C``; colours are ``0 .. colors-1``.
``tileset``
    ``"brick"`` for W_B (Def. 9) or a list of tiles, each the colours of its legs l1..l4.
``max_h``, ``max_v``
    brick walls: longest horizontal run of W_H tiles / vertical run of W_V tiles (or null).

plus the solution's ``status``, ``method``, ``solver``, ``seed``, ``time_s``, ``reason``,
``notes`` and ``stats``.

Version 1 (plain lists; written for boards of at most :data:`COMPACT_MIN_CELLS` cells)
--------------------------------------------------------------------------------------
``cells``
    ``[row, col]`` label of each cell (cell ``i`` is the ``i``-th entry).
``edges``
    ``[a, ka, b, kb]``: leg ``ka`` of cell ``a`` is joined to leg ``kb`` of cell ``b``;
    ``b = -1`` means the wall, and then ``kb`` numbers that boundary leg (0, 1, ...).
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
    for a board cut from a grid (rectangle, torus, cylinder, Möbius strip, Klein bottle,
    ring, mask, or a restriction of one): ``{"rows": R, "cols": C, "wrap_rows": w,
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
    ``[n, 2]`` and ``[m, 4]``, read as in version 1.
``boundary``
    encoded array of shape ``[n_boundary]``: the colour required on each boundary leg, -1 = free.
``tiles``
    encoded array of shape ``[n, 4]`` (the colours of each cell's legs W, N, E, S), or null.
"""

from __future__ import annotations

import os
from typing import Any

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.io.atomic import write_text_atomic
from tilesolve.io.jsonio import (
    check_document, decode_array, dumps, encode_array, provenance_to_dict, read_json, solution_from_provenance,
)
from tilesolve.model.board import LEG_NAMES, Board, BoardProblem, GridSpec, WangTileSet
from tilesolve.model.solution import Solution

__all__ = ["BOARD_SOLUTION", "VERSIONS", "COMPACT_MIN_CELLS", "board_solution_to_dict", "board_solution_from_dict",
           "write_board_solution", "read_board_solution", "read_boundary"]

BOARD_SOLUTION = "tilesolve/board-solution"
#: Versions of ``tilesolve/board-solution`` this module reads.
VERSIONS = frozenset({1, 2})
#: Boards with more cells than this are written as version 2.
COMPACT_MIN_CELLS = 4096
_WRAP_NAMES = (None, "plain", "twist")


def board_solution_to_dict(problem: BoardProblem, solution: Solution, *, compact: bool | None = None) -> dict:
    """The JSON document of a board solution.

    Parameters
    ----------
    problem, solution
    compact : bool, optional
        Write version 2 (encoded arrays, grid boards as their grid and mask) rather than
        version 1 (plain lists). Default: version 2 for boards of more than
        :data:`COMPACT_MIN_CELLS` cells.
    """
    b = problem.board
    if compact is None:
        compact = b.n_cells > COMPACT_MIN_CELLS
    stats = {k: v for k, v in solution.stats.items() if not isinstance(v, np.ndarray)}
    doc = {
        "format": BOARD_SOLUTION,
        "version": 2 if compact else 1,
        "board_kind": b.kind,
        "leg_order": list(LEG_NAMES),
        "colors": problem.n_colors,
        "tileset": "brick" if problem.tileset.is_brick else np.asarray(problem.tileset.tiles),
        "max_h": problem.max_h,
        "max_v": problem.max_v,
        **provenance_to_dict(solution),
        "stats": stats,
    }
    tiles = None if solution.tiling is None else np.asarray(solution.tiling)
    if not compact:
        doc["cells"] = np.asarray(b.labels)
        doc["edges"] = b.edge_array()
        doc["boundary"] = [None if c < 0 else c for c in problem.boundary.tolist()]
        doc["tiles"] = None if tiles is None else tiles.astype(np.int64, copy=False)
        return doc
    if b.grid_spec is not None:
        spec = b.grid_spec
        doc["grid"] = {"rows": spec.rows, "cols": spec.cols, "wrap_rows": spec.wrap_rows, "wrap_cols": spec.wrap_cols}
        doc["mask"] = None if b.n_cells == spec.rows * spec.cols else encode_array(b.mask_of())
    else:
        doc["cells"] = encode_array(b.labels)
        doc["edges"] = encode_array(b.edge_array())
    doc["boundary"] = encode_array(problem.boundary)
    doc["tiles"] = None if tiles is None else encode_array(tiles)
    return doc


def _int(doc: dict, name: str, source: Any, *, optional: bool = False) -> int | None:
    v = doc.get(name)
    if v is None and optional:
        return None
    if isinstance(v, bool) or not isinstance(v, int):
        raise InvalidProblem(f"{source}: {name!r} must be an integer, got {v!r}")
    return v


def _check_header(doc: Any, source: Any) -> int:
    """The file's version, once its format and version are checked."""
    return check_document(doc, source, {BOARD_SOLUTION: VERSIONS})["version"]


def _grid_board(doc: dict, source: Any, kind: str) -> Board:
    g = doc["grid"]
    if not isinstance(g, dict) or set(g) != {"rows", "cols", "wrap_rows", "wrap_cols"}:
        raise InvalidProblem(f"{source}: 'grid' must be {{\"rows\", \"cols\", \"wrap_rows\", \"wrap_cols\"}}")
    rows, cols = _int(g, "rows", f"{source}: 'grid'"), _int(g, "cols", f"{source}: 'grid'")
    for name in ("wrap_rows", "wrap_cols"):
        if g[name] not in _WRAP_NAMES:
            raise InvalidProblem(f"{source}: 'grid'.{name} must be null, \"plain\" or \"twist\", got {g[name]!r}")
    if rows < 1 or cols < 1:
        raise InvalidProblem(f"{source}: 'grid' must have positive rows and cols, got {cols}x{rows}")
    if doc.get("mask") is None:
        mask = np.ones((rows, cols), bool)
    else:
        m = decode_array(doc["mask"], "mask", source)
        if m.shape != (rows, cols) or ((m != 0) & (m != 1)).any():
            raise InvalidProblem(f"{source}: 'mask' must hold 0/1 values of shape [{rows}, {cols}], "
                                 f"got shape {list(m.shape)}")
        mask = m.astype(bool)
    try:
        return Board.from_grid_spec(GridSpec(rows, cols, g["wrap_rows"], g["wrap_cols"]), mask, kind=kind)
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: 'grid': {exc}") from None


def board_solution_from_dict(doc: dict, source: Any = "<document>") -> tuple[BoardProblem, Solution]:
    """Rebuild ``(problem, solution)`` from a version 1 or 2 document; the tiles are read as
    written (the verifier judges them).

    Raises
    ------
    InvalidProblem
        One line naming ``source`` and the field, for anything malformed.
    """
    version = _check_header(doc, source)
    order = doc.get("leg_order", list(LEG_NAMES))
    if list(order) != list(LEG_NAMES):
        raise InvalidProblem(f"{source}: leg_order {order!r} is not supported; tilesolve writes {list(LEG_NAMES)}")
    colors = _int(doc, "colors", source)
    ts = doc.get("tileset")
    try:
        tileset = WangTileSet.brick(colors) if ts == "brick" else WangTileSet(ts if ts is not None else [], colors)
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: {exc}") from None
    kind = doc.get("board_kind") or "board"
    if not isinstance(kind, str):
        raise InvalidProblem(f"{source}: 'board_kind' must be a string, got {kind!r}")
    if version >= 2 and "grid" in doc:
        board = _grid_board(doc, source, kind)
    elif "cells" in doc and "edges" in doc:
        cells, edges = doc["cells"], doc["edges"]
        if version >= 2:
            cells, edges = decode_array(cells, "cells", source), decode_array(edges, "edges", source)
        try:
            board = Board.from_edges(cells, edges, kind=kind)
        except InvalidProblem as exc:
            raise InvalidProblem(f"{source}: {exc}") from None
    else:
        need = "'grid' or 'cells' and 'edges'" if version >= 2 else "'cells' and 'edges'"
        raise InvalidProblem(f"{source}: a board solution needs {need}")
    bnd = doc.get("boundary")
    if bnd is None:
        beta = np.full(board.n_boundary, -1, np.int64)
    elif version >= 2:
        beta = decode_array(bnd, "boundary", source, ndim=1)
    else:
        if not isinstance(bnd, list) or not all(v is None or (isinstance(v, int) and not isinstance(v, bool))
                                                for v in bnd):
            raise InvalidProblem(f"{source}: 'boundary' must be a list of colours or null")
        beta = [-1 if v is None else v for v in bnd]
    try:
        problem = BoardProblem(board, tileset, beta,
                               max_h=_int(doc, "max_h", source, optional=True),
                               max_v=_int(doc, "max_v", source, optional=True))
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: {exc}") from None
    tiles = doc.get("tiles")
    tiling = None
    if tiles is not None:
        if version >= 2:
            tiling = decode_array(tiles, "tiles", source)
        else:
            try:
                tiling = np.asarray(tiles, dtype=np.int64)
            except (TypeError, ValueError):
                raise InvalidProblem(f"{source}: 'tiles' must be a list of 4 integer colours per cell") from None
    return problem, solution_from_provenance(doc, source, tiling, what="tiles")


def write_board_solution(path: str | os.PathLike, problem: BoardProblem, solution: Solution, *,
                         compact: bool | None = None) -> None:
    """Write a ``tilesolve/board-solution`` file atomically (``compact`` as in
    :func:`board_solution_to_dict`)."""
    write_text_atomic(path, dumps(board_solution_to_dict(problem, solution, compact=compact)))


def read_board_solution(path: str | os.PathLike) -> tuple[BoardProblem, Solution]:
    """Read a ``tilesolve/board-solution`` file (version 1 or 2) as ``(problem, solution)``."""
    return board_solution_from_dict(read_json(path), path)


def read_boundary(path: str | os.PathLike) -> np.ndarray:
    """A boundary file: a JSON list of colours by boundary-leg number (``null`` = free), or an
    object whose ``"boundary"`` field is that list. Returns colours with ``-1`` for free legs."""
    data = read_json(path)
    if isinstance(data, dict):
        data = data.get("boundary")
    if not isinstance(data, list) or not all(v is None or (isinstance(v, int) and not isinstance(v, bool))
                                             for v in data):
        raise InvalidProblem(f"{path}: a boundary file holds a list of colours (null = free), "
                             "or an object with 'boundary'")
    return np.array([-1 if v is None else v for v in data], dtype=np.int64)
