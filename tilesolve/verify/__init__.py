"""Independent checkers (numpy only; never import encodings or constructive code)."""

from tilesolve.verify.board import board_violations, is_valid_board_tiling
from tilesolve.verify.dappled import Violation, dappled_violations, hamming_distance, is_dappled

__all__ = ["Violation", "dappled_violations", "hamming_distance", "is_dappled", "board_violations",
           "is_valid_board_tiling"]
