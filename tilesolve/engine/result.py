"""The record every backend returns (DESIGN.md, "One pipeline"; STYLE.md §3, CPMpy's ExitStatus)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from tilesolve.deadline import Deadline
from tilesolve.model.solution import Status

__all__ = ["Result", "run_interruptible"]


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


def run_interruptible(fn, interrupt, deadline: Deadline, poll: float = 0.05):
    """Run ``fn()`` in a worker thread; call ``interrupt()`` at the deadline or on Ctrl-C.

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
    import threading

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
