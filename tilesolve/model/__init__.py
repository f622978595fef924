"""Problems, solutions and their plain data (no solver concepts live here).

Families: dappled tilings (``dappled``), boards and Wang tile sets (``board``), tile sets
with the class notes' indexing (``tiles``) and tile packings (``packing``).
"""

from tilesolve._lazy import lazy_exports

#: Exported names and the module each lives in (imported on first use).
_WHERE = {
    "MAX_CELLS": "tilesolve.model.dappled",
    "Condition": "tilesolve.model.dappled",
    "DappledProblem": "tilesolve.model.dappled",
    "TileCount": "tilesolve.model.dappled",
    "parse_condition": "tilesolve.model.dappled",
    "parse_count": "tilesolve.model.dappled",
    "parse_size": "tilesolve.model.dappled",
    "Board": "tilesolve.model.board",
    "BoardProblem": "tilesolve.model.board",
    "WangTileSet": "tilesolve.model.board",
    "parse_board_spec": "tilesolve.model.board",
    "PackingProblem": "tilesolve.model.packing",
    "Solution": "tilesolve.model.solution",
    "Status": "tilesolve.model.solution",
    "TileSet": "tilesolve.model.tiles",
}

__all__ = list(_WHERE)
__getattr__, __dir__ = lazy_exports(__name__, _WHERE)
