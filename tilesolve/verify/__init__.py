"""Independent checkers (numpy, and numba for loops of their own; never import encodings or
constructive code)."""

from tilesolve._lazy import lazy_exports

#: Exported names and the module each lives in (imported on first use).
_WHERE = {
    "board_violations": "tilesolve.verify.board",
    "is_valid_board_tiling": "tilesolve.verify.board",
    "Violation": "tilesolve.verify.dappled",
    "dappled_violations": "tilesolve.verify.dappled",
    "hamming_distance": "tilesolve.verify.dappled",
    "is_dappled": "tilesolve.verify.dappled",
    "is_packing": "tilesolve.verify.packing",
    "packing_violations": "tilesolve.verify.packing",
}

__all__ = list(_WHERE)
__getattr__, __dir__ = lazy_exports(__name__, _WHERE)
