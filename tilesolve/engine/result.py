"""The record every backend returns (DESIGN.md, "One pipeline"; STYLE.md §3, CPMpy's ExitStatus)."""

from __future__ import annotations

import contextlib
import contextvars
import threading
from dataclasses import dataclass, field
from typing import Any, Iterator

from tilesolve.deadline import Deadline
from tilesolve.model.solution import Status

__all__ = ["Result", "run_interruptible", "stop_on"]

#: The event set by :func:`stop_on` in this context, if any.
_STOP_REQUEST: contextvars.ContextVar[threading.Event | None] = contextvars.ContextVar("tilesolve_stop", default=None)


@dataclass
class Result:
    """Outcome of one backend call, before it is turned into a family's Solution.

    Attributes
    ----------
    status : Status
        ``SAT``/``OPTIMAL`` with a model, ``UNSAT`` only when proved, ``UNKNOWN`` on a
        time limit or an interruption (never ``UNSAT``).
    model : list of int or None
        Signed DIMACS literals (SAT and MaxSAT backends) or ``[bool, ...]`` variable values
        (CP-SAT), ``None`` without a solution.
    runtime : float
        Seconds spent in the backend (loading the formula included).
    proof : list of str or None
        DRAT proof lines when the solver logged one and the answer is ``UNSAT``.
    stats : dict
        Backend numbers (variables, clauses, conflicts, cores, bounds...).
    cost : int or None
        Objective value for optimisation backends.
    solver : str
        Backend name as the user gave it (e.g. ``"cadical153"``).
    reason : str or None
        Why the status is what it is (``"time limit"``, ``"interrupted"``...).
    """

    status: Status
    model: list | None = None
    runtime: float = 0.0
    proof: list[str] | None = None
    stats: dict[str, Any] = field(default_factory=dict)
    cost: int | None = None
    solver: str = ""
    reason: str | None = None


@contextlib.contextmanager
def stop_on(event: threading.Event) -> Iterator[None]:
    """Inside the block, ``event`` being set interrupts :func:`run_interruptible` as Ctrl-C does.

    A seed portfolio runs its first seed in the calling thread and stops it this way when a
    worker process decides first (:func:`tilesolve.engine.portfolio.escalate`); the run then
    returns ``unknown`` ("interrupted") at its next solver call, within one poll.

    >>> stop, solving = threading.Event(), threading.Event()
    >>> stop.set()
    >>> with stop_on(stop):  # a "solver" that runs until interrupted
    ...     run_interruptible(solving.wait, solving.set, Deadline(None))
    (True, 'interrupted')
    """
    token = _STOP_REQUEST.set(event)
    try:
        yield
    finally:
        _STOP_REQUEST.reset(token)


def run_interruptible(fn, interrupt, deadline: Deadline, poll: float = 0.05):
    """Run ``fn()`` in a worker thread; call ``interrupt()`` at the deadline, on Ctrl-C, or
    when the :func:`stop_on` event of this context is set.

    Native solvers block the main thread inside C, where Python cannot deliver
    ``KeyboardInterrupt``; waiting on an event keeps the main thread responsive, so a
    time limit and Ctrl-C both end in a clean ``interrupt()`` of the solver.

    Returns
    -------
    (value, stop) : tuple
        ``fn``'s return value and ``None``, ``"time limit"`` or ``"interrupted"``.

    Examples
    --------
    >>> run_interruptible(lambda: 42, lambda: None, Deadline(None))
    (42, None)
    """
    requested = _STOP_REQUEST.get()
    done = threading.Event()
    box: dict = {}

    def work() -> None:
        try:
            box["value"] = fn()
        except BaseException as exc:  # noqa: BLE001 - re-raised in the caller's thread
            box["error"] = exc
        finally:
            done.set()

    worker = threading.Thread(target=work, name="tilesolve-solver", daemon=True)
    worker.start()
    stop = None
    while True:
        try:
            rem = deadline.remaining()
            wait = poll if rem is None else min(poll, rem + 1e-3)
            if done.wait(wait):
                break
            if stop is None and deadline.expired():
                stop = "time limit"
            if requested is not None and requested.is_set():
                stop = "interrupted"
            if stop is not None:
                # Repeated on every poll: an interrupt that lands before the solver has
                # entered its search can be cleared when the search starts (seen with
                # Glucose under very short budgets), and the run would never end.
                interrupt()
        except KeyboardInterrupt:
            if stop != "interrupted":
                stop = "interrupted"
                interrupt()
    worker.join()
    if "error" in box:
        raise box["error"]
    return box.get("value"), stop
