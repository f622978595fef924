"""A wall-clock deadline shared by the steps of one run (base layer: every layer may use it).

Routes of every family (constructive, encoding, solver, proof check) count against one
:class:`Deadline`, so a time limit covers the whole run, not only the solver call. It is made
once per run, from the seconds the user gave, at the public entry point
(:func:`tilesolve.family.solve`, :func:`tilesolve.family.count`, a crosscheck), and passed
down; a part of the run with a budget of its own (a portfolio wave, one attempt of a
restarting search) takes :meth:`Deadline.within`, never a new one. A deadline handed to a
worker process (pickled) keeps counting from the run's start there.

A run's clock starts when the run begins, except where the command line asks for the whole
command to count (:func:`first_run_counted_from`): ``tilesolve ... --time-limit 3`` ends within
about 3 s of its process starting, start-up included.
"""

from __future__ import annotations

import contextlib
import contextvars
import os
import time

from tilesolve.errors import InvalidProblem, TilesolveError

__all__ = ["Deadline", "TimeLimitReached", "NO_LIMIT", "process_start", "first_run_counted_from", "run_start"]


class TimeLimitReached(TilesolveError):
    """The deadline passed while a route was still building (encoding, loading a solver).

    Routes turn it into a ``Status.UNKNOWN`` answer whose reason is the message, e.g.
    ``"time limit of 3 s reached while encoding (2.1 M of 8.4 M clauses built)"``; the CLI
    maps an uncaught one to exit code 3 (unknown), never to an error of the user's.
    """

    exit_code = 3


class Deadline:
    """A wall-clock deadline shared by the steps of one solve (``None`` = no limit).

    ``start`` is the :func:`time.perf_counter` reading its clock counts from (default: now).
    """

    def __init__(self, time_limit: float | None, start: float | None = None) -> None:
        if time_limit is not None and time_limit < 0:
            raise InvalidProblem(f"time limit must be >= 0 seconds, got {time_limit}")
        self._clock = time.perf_counter
        self.start = self._clock() if start is None else start
        self.time_limit = time_limit

    def within(self, seconds: float | None) -> "Deadline":
        """A deadline for a part of this run with a budget of its own: it passes ``seconds`` from
        now, or when this one does if that is sooner (``None``: when this one does).

        >>> run = Deadline(10.0)
        >>> run.within(3.0).time_limit, run.within(None).time_limit <= 10.0, Deadline(None).within(None).time_limit
        (3.0, True, None)
        """
        left = self.remaining()
        return Deadline(left if seconds is None else seconds if left is None else min(seconds, left))

    def __reduce__(self):
        """Pickled for a worker process: the time limit and the time spent so far travel (the
        time in transit counted by the wall clock), so the deadline passes there when it does
        here."""
        return _unpickled, (self.time_limit, self.elapsed(), time.time())

    def elapsed(self) -> float:
        return self._clock() - self.start

    def remaining(self) -> float | None:
        if self.time_limit is None:
            return None
        return max(0.0, self.time_limit - self.elapsed())

    def expired(self) -> bool:
        return self.time_limit is not None and self.elapsed() >= self.time_limit

    def check(self, doing: str) -> None:
        """Raise :class:`TimeLimitReached` if the deadline has passed.

        ``doing`` completes the message "time limit of N s reached while ...", e.g.
        ``"encoding (1.2 M clauses built)"``.

        Examples
        --------
        >>> Deadline(None).check("encoding")
        >>> Deadline(0).check("encoding")
        Traceback (most recent call last):
        ...
        tilesolve.deadline.TimeLimitReached: time limit of 0 s reached while encoding
        """
        if self.expired():
            raise TimeLimitReached(f"time limit of {self.time_limit:.3g} s reached while {doing}")


#: The deadline of a call made outside any run (a test, a direct call of an engine function):
#: it never passes. Engine functions take it as their default instead of making a deadline of
#: their own; time is never measured with it (its start is the import).
NO_LIMIT = Deadline(None)


#: Start-up longer than this is taken for a clock that cannot be read (a process start is not
#: counted then): no real start-up of tilesolve is that slow.
_MAX_START_UP_S = 60.0


def process_start() -> float:
    """The :func:`time.perf_counter` reading at which this process started (fork or spawn).

    Read from ``/proc/self/stat`` (its start time, in clock ticks since boot: 10 ms steps on
    Linux); where that cannot be read, or gives no sensible start-up time, it is now.

    >>> process_start() <= time.perf_counter()
    True
    """
    now = time.perf_counter()
    try:
        with open("/proc/self/stat", "rb") as fh:
            stat = fh.read()
        ticks = int(stat.rsplit(b")", 1)[1].split()[19])  # field 22, after "pid (comm)"
        spent = time.clock_gettime(time.CLOCK_BOOTTIME) - ticks / os.sysconf("SC_CLK_TCK")
    except (OSError, ValueError, IndexError, AttributeError):
        return now
    return now - spent if 0 <= spent < _MAX_START_UP_S else now


_FIRST_RUN_START: contextvars.ContextVar[float | None] = contextvars.ContextVar("first_run_start", default=None)


@contextlib.contextmanager
def first_run_counted_from(start: float):
    """Within the block, the first run that begins (:func:`run_start`) counts from ``start``
    (a :func:`time.perf_counter` reading, e.g. :func:`process_start`), the later ones from
    their own beginning; used by the command line so that a time limit covers start-up."""
    token = _FIRST_RUN_START.set(start)
    try:
        yield
    finally:
        _FIRST_RUN_START.reset(token)


def run_start() -> float:
    """Where the clock of a run beginning now starts: the start given by the enclosing
    :func:`first_run_counted_from`, if no run has taken it yet, otherwise now.

    >>> with first_run_counted_from(1.5):
    ...     run_start(), run_start() > 1.5
    (1.5, True)
    """
    start = _FIRST_RUN_START.get()
    if start is None:
        return time.perf_counter()
    _FIRST_RUN_START.set(None)
    return start


def _unpickled(time_limit: float | None, elapsed: float, sent: float) -> Deadline:
    """A pickled :class:`Deadline` in the process that reads it (:meth:`Deadline.__reduce__`)."""
    d = Deadline(time_limit)
    d.start -= elapsed + max(0.0, time.time() - sent)
    return d
