"""Progress on long work: the one home of progress reporting (DESIGN.md, "Long work ... shows
progress on a TTY").

Kernels, engines and facades never draw anything themselves and never import the CLI: they take
a :class:`Progress` (default :data:`SILENT`, which does nothing) and open *tasks* on it. Whoever
starts the run decides where progress goes:

- the CLI passes :func:`terminal` (``terminal(quiet=verbosity() < 0)``): `tqdm
  <https://tqdm.github.io>`_ bars on stderr, or :data:`SILENT` when stderr is not a terminal or
  under ``-q``;
- the studio passes a :class:`Stream`, which hands snapshots (plain dicts) to a callback that
  forwards them to the browser;
- a library caller passes nothing and gets silence.

The API
-------
``with progress.task(label, total=None, unit="it") as t:`` opens a task (a bar on a terminal);
inside, ``t.advance(n=1)`` counts work done, ``t.set(done, total=None)`` sets it outright (a
kernel that reports ``callback(done, total)`` can be handed ``t.set``), ``t.note(text)`` shows a
detail (``"decided 3, refuted 1, undecided 0"``, ``"seed 7"``). With a ``total`` the bar shows
the fraction done and an ETA; without one it shows the count and rate, or, with ``unit=None``
(work that cannot be counted, e.g. one solver call), the label, the note and the elapsed time,
refreshed twice a second. On a terminal a task shows once it has run :data:`DELAY_S` seconds,
so quick work draws nothing. Tasks nest (``levels`` outside, ``seeds`` inside): each is a line of its
own, erased when its ``with`` block ends. ``progress.announce(text)`` prints one line that stays
(the estimate before a run that will be long: ``"about 40 s: 2,100,000 states x 16 rows"``).

Keep kernels fast: advance per row, level, band or seed, never per cell. Updates from several
threads are safe. A :class:`Progress` is false when it shows nothing (``if progress:`` before
preparing a costly estimate), and pickles as :data:`SILENT`: a worker process reports nothing;
its parent reports for it.

>>> with SILENT.task("rows", total=3, unit="row") as t:
...     for _ in range(3):
...         t.advance()
>>> p = Stream(print, every=0)
>>> with p.task("rows", total=2, unit="row") as t:
...     t.advance()  # doctest: +ELLIPSIS
{'label': 'rows', 'done': 0, 'total': 2, 'unit': 'row', 'note': '', 'elapsed_s': ..., 'eta_s': None, 'depth': 0}
{'label': 'rows', 'done': 1, 'total': 2, 'unit': 'row', 'note': '', 'elapsed_s': ..., 'eta_s': ..., 'depth': 0}
{'label': 'rows', 'done': 1, ..., 'closed': True}
>>> as_progress(False) is SILENT, as_progress(None) is SILENT, bool(SILENT)
(True, True, False)
>>> import pickle
>>> pickle.loads(pickle.dumps(p)) is SILENT
True
"""

from __future__ import annotations

import contextlib
import os
import sys
import threading
import time
from typing import Any, Callable, Iterator

__all__ = ["Progress", "Task", "SILENT", "Terminal", "Stream", "terminal", "as_progress", "DELAY_S", "DELAY_ENV"]

#: Seconds a task runs before its bar shows on a terminal (quick work draws nothing).
DELAY_S = 0.5
#: Environment variable overriding :data:`DELAY_S` (``0``: every bar at once).
DELAY_ENV = "TILESOLVE_PROGRESS_DELAY"


class Task:
    """One piece of work being reported; this base class reports nothing (:data:`SILENT`'s).

    Methods are cheap no-ops here; subclasses draw or stream.
    """

    def advance(self, n: int = 1) -> None:
        """Count ``n`` more units done."""

    def set(self, done: int, total: int | None = None) -> None:
        """Set the units done (and the total, when it becomes known)."""

    def note(self, text: str) -> None:
        """Show ``text`` beside the count (e.g. ``"decided 3, refuted 1, undecided 0"``)."""


class Progress:
    """Where a run reports progress. This base class is silent (:data:`SILENT`); subclasses
    (:class:`Terminal`, :class:`Stream`) override :meth:`_open` and :meth:`announce`."""

    #: Whether anything is shown (also the truth value): skip a costly estimate when False.
    enabled = False

    @contextlib.contextmanager
    def task(self, label: str, total: int | None = None, *, unit: str | None = "it") -> Iterator[Task]:
        """A task reported while the ``with`` block runs, closed (erased) when it ends.

        Parameters
        ----------
        label : str
            What is being done, e.g. ``"counting: rows"``, ``"lift levels"``.
        total : int, optional
            Units of work in all, when known: the bar then shows a fraction and an ETA.
        unit : str or None
            What is counted (``"row"``, ``"board"``, ``"band"``); ``None`` for work that is not
            counted (a solver call): the label, the note and the elapsed time are shown.
        """
        task = self._open(label, total, unit)
        try:
            yield task
        finally:
            self._close(task)

    def announce(self, text: str) -> None:
        """Print ``text`` as a line that stays (e.g. the estimate before a long run)."""

    def _open(self, label: str, total: int | None, unit: str | None) -> Task:
        return _NULL_TASK

    def _close(self, task: Task) -> None:
        pass

    def __bool__(self) -> bool:
        return self.enabled

    def __reduce__(self):
        # A worker process cannot draw on its parent's terminal or stream: it gets SILENT.
        return _silent, ()


def _silent() -> "Progress":
    return SILENT


_NULL_TASK = Task()
#: Reports nothing: the default of every ``progress`` parameter.
SILENT = Progress()


def as_progress(value: "Progress | bool | None") -> Progress:
    """A :class:`Progress` for a ``progress`` argument: itself, or for a bool, :func:`terminal`
    (``True``: bars on stderr when it is a terminal) or :data:`SILENT` (``False``, ``None``)."""
    if isinstance(value, Progress):
        return value
    return terminal() if value else SILENT


def terminal(quiet: bool = False) -> Progress:
    """Bars on stderr (:class:`Terminal`) when stderr is a terminal and not ``quiet``, else
    :data:`SILENT`: piped output and ``-q`` stay clean."""
    try:
        tty = sys.stderr.isatty()
    except (AttributeError, ValueError):  # stderr replaced or closed
        tty = False
    return Terminal() if tty and not quiet else SILENT


# ------------------------------------------------------------------------------ terminal


class _Bar(Task):
    """A task drawn as a tqdm bar (once it has run ``bar.delay`` seconds)."""

    def __init__(self, bar, label: str, ticker: bool) -> None:
        self.bar, self.label, self.ticker = bar, label, ticker

    def draw(self) -> None:
        """Redraw the bar, unless it is younger than its delay (tqdm's own updates wait too)."""
        now = time.time()
        if now >= self.bar.start_t + self.bar.delay:
            self.bar.refresh()
            self.bar.last_print_t = now  # tqdm erases a bar when it closes only if it printed it

    def advance(self, n: int = 1) -> None:
        self.bar.update(n)

    def set(self, done: int, total: int | None = None) -> None:
        new_total = total is not None and total != self.bar.total
        if new_total:
            self.bar.total = total
        self.bar.update(done - self.bar.n)
        if new_total:  # the bar's shape changes (a fraction, an ETA): show it now, not at tqdm's next interval
            self.draw()

    def note(self, text: str) -> None:
        if self.ticker:  # no count to put it beside: the note follows the label
            self.bar.set_description_str(f"{self.label}: {text}" if text else self.label, refresh=False)
        else:
            self.bar.set_postfix_str(text, refresh=False)
        self.draw()


class Terminal(Progress):
    """tqdm bars on stderr, one line per open task, refreshed twice a second by a helper thread
    (so an ETA and the elapsed time move even between updates) and erased when done.

    A task shows up once it has run ``delay`` seconds (default :data:`DELAY_S`, or the
    environment's :data:`DELAY_ENV`): quick work leaves the terminal alone.
    """

    enabled = True

    def __init__(self, every: float = 0.5, delay: float | None = None) -> None:
        self.every = every
        self.delay = _delay() if delay is None else delay
        self._open_bars: list[_Bar] = []
        self._lock = threading.Lock()
        self._stop: threading.Event | None = None

    def _open(self, label: str, total: int | None, unit: str | None) -> Task:
        from tqdm import tqdm

        ticker = unit is None
        with self._lock:
            size = _unsized()
            bar = tqdm(total=total, desc=label, unit=unit or "it", file=sys.stderr, leave=False,
                       dynamic_ncols=size is None, ncols=size and size[0], nrows=size and size[1],
                       position=len(self._open_bars), mininterval=0.1, smoothing=0.1, delay=self.delay,
                       bar_format="{desc} [{elapsed}]" if ticker else None)
            task = _Bar(bar, label, ticker)
            self._open_bars.append(task)
            if self._stop is None:
                self._stop = threading.Event()
                threading.Thread(target=self._refresh, args=(self._stop,), name="tilesolve-progress",
                                 daemon=True).start()
        return task

    def _close(self, task: Task) -> None:
        with self._lock:
            self._open_bars.remove(task)
            task.bar.close()
            if not self._open_bars and self._stop is not None:
                self._stop.set()
                self._stop = None

    def _refresh(self, stop: threading.Event) -> None:
        while not stop.wait(self.every):
            with self._lock:
                for task in self._open_bars:
                    task.draw()

    def announce(self, text: str) -> None:
        from tqdm import tqdm

        tqdm.write(text, file=sys.stderr)


def _delay() -> float:
    """Seconds before a bar shows: :data:`DELAY_ENV` when it holds a number >= 0, else :data:`DELAY_S`."""
    try:
        value = float(os.environ.get(DELAY_ENV, DELAY_S))
    except ValueError:
        return DELAY_S
    return value if value >= 0 else DELAY_S


def _unsized() -> tuple[int, int] | None:
    """``None`` (follow the terminal's size) where stderr's terminal tells its size; 80 x 24
    where it says 0 x 0 (a pseudo-terminal nobody sized), on which tqdm would draw nothing."""
    try:
        size = os.get_terminal_size(sys.stderr.fileno())
    except (AttributeError, ValueError, OSError):
        return 80, 24
    return None if size.columns and size.lines else (80, 24)


# -------------------------------------------------------------------------------- stream


class _Reported(Task):
    """A task of a :class:`Stream`: its numbers, sent as a snapshot when they change."""

    def __init__(self, stream: "Stream", label: str, total: int | None, unit: str | None, depth: int) -> None:
        self.stream, self.label, self.total, self.unit, self.depth = stream, label, total, unit, depth
        self.done, self.text, self.t0 = 0, "", time.perf_counter()

    def advance(self, n: int = 1) -> None:
        self.done += n
        self.stream._changed(self)

    def set(self, done: int, total: int | None = None) -> None:
        self.done = done
        if total is not None:
            self.total = total
        self.stream._changed(self)

    def note(self, text: str) -> None:
        self.text = text
        self.stream._changed(self)

    def snapshot(self) -> dict[str, Any]:
        """The task as a JSON-ready dict (``eta_s`` only where a total is known and work is done)."""
        elapsed = time.perf_counter() - self.t0
        eta = None
        if self.total and 0 < self.done <= self.total:
            eta = round(elapsed * (self.total - self.done) / self.done, 1)
        return {"label": self.label, "done": self.done, "total": self.total, "unit": self.unit, "note": self.text,
                "elapsed_s": round(elapsed, 1), "eta_s": eta, "depth": self.depth}


class Stream(Progress):
    """Progress as snapshots handed to ``send`` (the studio forwards them to the browser).

    ``send(snapshot)`` gets a task's :meth:`_Reported.snapshot` dict when the task opens, at
    most once every ``every`` seconds while it changes, and, with ``"closed": True`` added,
    when it ends; :meth:`announce` sends ``{"announce": text}``. ``send`` runs in the thread
    that reported, so it should be quick (put the dict on a queue or a pipe).
    """

    enabled = True

    def __init__(self, send: Callable[[dict[str, Any]], object], every: float = 0.25) -> None:
        self.send, self.every = send, every
        self._depth = 0
        self._last = 0.0
        self._lock = threading.Lock()

    def _open(self, label: str, total: int | None, unit: str | None) -> Task:
        with self._lock:
            task = _Reported(self, label, total, unit, self._depth)
            self._depth += 1
        self.send(task.snapshot())
        return task

    def _close(self, task: Task) -> None:
        with self._lock:
            self._depth -= 1
        self.send({**task.snapshot(), "closed": True})

    def _changed(self, task: _Reported) -> None:
        now = time.perf_counter()
        with self._lock:
            if now - self._last < self.every:
                return
            self._last = now
        self.send(task.snapshot())

    def announce(self, text: str) -> None:
        self.send({"announce": text})
