"""JSON files of Wang tilings of boards: ``"format": "tilesolve/board-solution"``, version 1.

The board travels as plain data so any tool can re-check a tiling without tilesolve:

``cells``
    ``[row, col]`` label of each cell (cell ``i`` is the ``i``-th entry).
``edges``
    ``[a, ka, b, kb]``: leg ``ka`` of cell ``a`` is joined to leg ``kb`` of cell ``b``;
    ``b = -1`` means the wall, and then ``kb`` numbers that boundary leg (0, 1, ...).
``leg_order``
    ``["W", "N", "E", "S"]``: legs l1..l4 go round the cell, so l1/l3 and l2/l4 are
    opposite (Def. 9 of the brick paper assumes this).
``colors``
    ``#C``; colours are ``0 .. colors-1``.
``tileset``
    ``"brick"`` for W_B (Def. 9) or a list of tiles, each the colours of its legs l1..l4.
``boundary``
    the colour required on each boundary leg, by boundary-leg number (``null`` = free).
``tiles``
    for each cell, the colours of its legs l1..l4 (absent when there is no tiling).
``max_h``, ``max_v``
    brick walls: longest horizontal run of W_H tiles / vertical run of W_V tiles (or null).

plus the solution's ``status``, ``method``, ``solver``, ``seed``, ``time_s``, ``reason``,
``notes`` and ``stats``.
"""

from __future__ import annotations

import os
from typing import Any

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.io.atomic import write_text_atomic
from tilesolve.io.jsonio import check_document, dumps, load_document, provenance_to_dict, solution_from_provenance
from tilesolve.model.board import LEG_NAMES, Board, BoardProblem, WangTileSet
from tilesolve.model.solution import Solution

__all__ = ["BOARD_SOLUTION", "board_solution_to_dict", "board_solution_from_dict", "write_board_solution",
           "read_board_solution"]

BOARD_SOLUTION = "tilesolve/board-solution"


def board_solution_to_dict(problem: BoardProblem, solution: Solution) -> dict:
    """The JSON document of a board solution (numpy grids kept for :func:`dumps`)."""
    b = problem.board
    boundary = [None if int(c) < 0 else int(c) for c in problem.boundary]
    stats = {k: v for k, v in solution.stats.items() if not isinstance(v, np.ndarray)}
    return {
        "format": BOARD_SOLUTION,
        "version": 1,
        "board_kind": b.kind,
        "leg_order": list(LEG_NAMES),
        "colors": problem.n_colors,
        "tileset": "brick" if problem.tileset.is_brick else np.asarray(problem.tileset.tiles),
        "max_h": problem.max_h,
        "max_v": problem.max_v,
        **provenance_to_dict(solution),
        "stats": stats,
        "cells": np.asarray(b.labels),
        "edges": np.asarray(b.edge_list(), dtype=np.int64).reshape(-1, 4),
        "boundary": boundary,
        "tiles": None if solution.tiling is None else np.asarray(solution.tiling, dtype=np.int64),
    }


def _int(doc: dict, name: str, source: Any, *, optional: bool = False) -> int | None:
    v = doc.get(name)
    if v is None and optional:
        return None
    if isinstance(v, bool) or not isinstance(v, int):
        raise InvalidProblem(f"{source}: {name!r} must be an integer, got {v!r}")
    return v


def board_solution_from_dict(doc: dict, source: Any = "<document>") -> tuple[BoardProblem, Solution]:
    """Rebuild ``(problem, solution)``; the tiles are read as written (the verifier judges them)."""
    check_document(doc, source, formats=(BOARD_SOLUTION,))
    order = doc.get("leg_order", list(LEG_NAMES))
    if list(order) != list(LEG_NAMES):
        raise InvalidProblem(f"{source}: leg_order {order!r} is not supported; tilesolve writes {list(LEG_NAMES)}")
    colors = _int(doc, "colors", source)
    ts = doc.get("tileset")
    try:
        tileset = WangTileSet.brick(colors) if ts == "brick" else WangTileSet(ts if ts is not None else [], colors)
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: {exc}") from None
    if "cells" not in doc or "edges" not in doc:
        raise InvalidProblem(f"{source}: a board solution needs 'cells' and 'edges'")
    try:
        board = Board.from_edges(doc["cells"], doc["edges"], kind=str(doc.get("board_kind") or "board"))
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: {exc}") from None
    bnd = doc.get("boundary")
    if bnd is None:
        bnd = [None] * board.n_boundary
    if not isinstance(bnd, list) or not all(v is None or (isinstance(v, int) and not isinstance(v, bool)) for v in bnd):
        raise InvalidProblem(f"{source}: 'boundary' must be a list of colours or null")
    try:
        problem = BoardProblem(board, tileset, [-1 if v is None else v for v in bnd],
                               max_h=_int(doc, "max_h", source, optional=True),
                               max_v=_int(doc, "max_v", source, optional=True))
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: {exc}") from None
    tiles = doc.get("tiles")
    tiling = None
    if tiles is not None:
        try:
            tiling = np.asarray(tiles, dtype=np.int64)
        except (TypeError, ValueError):
            raise InvalidProblem(f"{source}: 'tiles' must be a list of 4 integer colours per cell") from None
    return problem, solution_from_provenance(doc, source, tiling, what="tiles")


def write_board_solution(path: str | os.PathLike, problem: BoardProblem, solution: Solution) -> None:
    """Write a ``tilesolve/board-solution`` file atomically."""
    write_text_atomic(path, dumps(board_solution_to_dict(problem, solution)))


def read_board_solution(path: str | os.PathLike) -> tuple[BoardProblem, Solution]:
    return board_solution_from_dict(load_document(path, formats=(BOARD_SOLUTION,)), path)
