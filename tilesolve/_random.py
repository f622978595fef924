"""The one helper that turns a ``seed`` argument into a random generator (DESIGN.md, "Randomness")."""

from __future__ import annotations

import numpy as np

__all__ = ["rng_from_seed"]


def rng_from_seed(seed: int | np.random.Generator | None) -> np.random.Generator:
    """Return a :class:`numpy.random.Generator` for ``seed``.

    ``None`` draws fresh entropy; an int gives a reproducible stream; a Generator is
    returned unchanged so callers can thread one through several steps.
    """
    if isinstance(seed, np.random.Generator):
        return seed
    if seed is not None and (not isinstance(seed, (int, np.integer)) or seed < 0):
        from tilesolve.errors import InvalidProblem

        raise InvalidProblem(f"seed must be a non-negative integer, got {seed!r}")
    return np.random.default_rng(seed)
