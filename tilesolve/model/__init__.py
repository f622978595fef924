"""Problems, solutions and their plain data (no solver concepts live here).

Families: dappled tilings (``dappled``), boards and Wang tile sets (``board``), tile sets
with the class notes' indexing (``tiles``) and tile packings (``packing``).
"""

from tilesolve.model.dappled import (
    MAX_CELLS,
    Condition,
    DappledProblem,
    TileCount,
    parse_condition,
    parse_count,
    parse_size,
)
from tilesolve.model.board import Board, BoardProblem, WangTileSet, parse_board_spec
from tilesolve.model.packing import PackingProblem
from tilesolve.model.solution import Solution, Status
from tilesolve.model.tiles import TileSet

__all__ = [
    "MAX_CELLS",
    "Condition",
    "DappledProblem",
    "TileCount",
    "parse_condition",
    "parse_count",
    "parse_size",
    "Solution",
    "Status",
    "Board",
    "BoardProblem",
    "WangTileSet",
    "parse_board_spec",
    "PackingProblem",
    "TileSet",
]
