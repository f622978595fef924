"""What one run of a route may use (DESIGN.md, "Families and their contract").

Every route of every family has the signature ``route(problem, run) -> Solution``;
``run`` is a :class:`RunOptions`, resolved once by :func:`tilesolve.family.solve`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Mapping

from tilesolve.deadline import Deadline
from tilesolve.progress import SILENT, Progress, as_progress

__all__ = ["RunOptions"]


@dataclass(frozen=True)
class RunOptions:
    """What one run of a route may use, resolved once by :func:`solve`.

    Attributes
    ----------
    seed : int
        Always set: the pipeline draws one when the caller gives none, and records it.
    deadline : Deadline
        The whole run's wall-clock budget (encoding, solving and proof checking count), made
        once where the run begins (:func:`tilesolve.family.run_deadline`) and passed down as it
        is; a part of the run with a budget of its own takes ``deadline.within(seconds)``.
        Without one, a RunOptions is a run of its own, without a limit.
    progress : Progress
        Where the run reports progress (:mod:`tilesolve.progress`; default silent). A bool is
        taken as :func:`tilesolve.progress.as_progress` takes it: ``True``, bars on stderr when
        it is a terminal. Pickled (to a worker process), it is silent.
    solver : str or None
        Backend choice (e.g. a PySAT solver name) for routes that take one.
    workers : int or None
        Parallel workers (CP-SAT threads, portfolio processes); ``None`` = the route's default.
    cluster : str or object or None
        A Dask scheduler address (or client) for routes that can run on a cluster.
    options : Mapping
        The family's own options (e.g. ``initial`` for the dappled constructive route).
    """

    seed: int
    deadline: Deadline = field(default_factory=lambda: Deadline(None))
    progress: Progress = SILENT
    solver: str | None = None
    workers: int | None = None
    cluster: Any = None
    options: Mapping[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        object.__setattr__(self, "progress", as_progress(self.progress))

    def option(self, name: str, default: Any = None) -> Any:
        """A family option, or ``default``."""
        return self.options.get(name, default)
