"""Seeds: every run records the seed it used, so that it can be repeated."""

from __future__ import annotations

import secrets
from typing import Any

from tilesolve.errors import InvalidProblem

__all__ = ["draw_seed", "check_seed"]


def draw_seed() -> int:
    """A fresh seed (recorded with the answer, so every run can be repeated)."""
    return secrets.randbelow(2**31)


def check_seed(seed: Any) -> int:
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        import numpy as np

        if isinstance(seed, np.integer) and seed >= 0:
            return int(seed)
        raise InvalidProblem(f"seed must be a non-negative integer, got {seed!r}")
    return seed
