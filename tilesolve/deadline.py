"""A wall-clock deadline shared by the steps of one run (base layer: every layer may use it).

Routes of every family (constructive, encoding, solver, proof check) count against one
:class:`Deadline`, so a time limit covers the whole run, not only the solver call.
"""

from __future__ import annotations

import time

from tilesolve.errors import InvalidProblem

__all__ = ["Deadline"]


class Deadline:
    """A wall-clock deadline shared by the steps of one solve (``None`` = no limit)."""

    def __init__(self, time_limit: float | None) -> None:
        if time_limit is not None and time_limit < 0:
            raise InvalidProblem(f"time limit must be >= 0 seconds, got {time_limit}")
        self._clock = time.perf_counter
        self.start = self._clock()
        self.time_limit = time_limit

    def elapsed(self) -> float:
        return self._clock() - self.start

    def remaining(self) -> float | None:
        if self.time_limit is None:
            return None
        return max(0.0, self.time_limit - self.elapsed())

    def expired(self) -> bool:
        return self.time_limit is not None and self.elapsed() >= self.time_limit
