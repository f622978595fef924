"""Independent checkers (numpy only; never import encodings or constructive code)."""

from tilesolve.verify.board import board_violations, is_valid_board_tiling
from tilesolve.verify.dappled import Violation, dappled_violations, hamming_distance, is_dappled
from tilesolve.verify.packing import is_packing, packing_violations

__all__ = [
    "Violation",
    "dappled_violations",
    "hamming_distance",
    "is_dappled",
    "board_violations",
    "is_valid_board_tiling",
    "packing_violations",
    "is_packing",
]
