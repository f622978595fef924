"""Problems, solutions and their plain data (no solver concepts live here)."""

from tilesolve.model.dappled import (
    MAX_CELLS,
    Condition,
    DappledProblem,
    TileCount,
    parse_condition,
    parse_count,
    parse_size,
)
from tilesolve.model.solution import Solution, Status

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
]
