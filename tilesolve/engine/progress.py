"""Progress on long work (DESIGN.md, "Long work ... shows progress on a TTY").

Solver calls give no intermediate numbers we can trust to mean "x % done", so a solve shows
what is true: which route is running and for how long, refreshed twice a second on stderr,
and erased when the call returns.
"""

from __future__ import annotations

import contextlib
import sys
import threading
import time
from typing import Callable, Iterator

__all__ = ["ticker", "status_line"]

#: The detail cells of the lines being drawn (outermost first): a nested line writes there.
_drawn: list[list[str]] = []


@contextlib.contextmanager
def ticker(label: str, enabled: bool, *, every: float = 0.5) -> Iterator[None]:
    """Show ``label`` and the elapsed seconds on stderr while the ``with`` block runs.

    Does nothing unless ``enabled`` and stderr is a terminal, so piped output stays clean.

    >>> with ticker("solving", enabled=False):
    ...     pass
    """
    with status_line(label, enabled, every=every):
        yield


@contextlib.contextmanager
def status_line(label: str, enabled: bool, *, every: float = 0.5) -> Iterator[Callable[[str], None]]:
    """Show ``label``, a detail the caller keeps up to date (e.g. runs started/finished) and
    the elapsed seconds on stderr while the ``with`` block runs.

    Yields ``set_detail(text)``; the line reads ``label: text ... N s`` and is erased when the
    ``with`` block ends. Does nothing unless ``enabled`` and stderr is a terminal. Nested in
    another line (the solve pipeline's, around a seed portfolio's), it draws no line of its
    own: the outer line's detail shows ``label: text`` until the block ends.

    >>> with status_line("search", enabled=False) as set_detail:
    ...     set_detail("1 of 4 runs finished")
    """
    if not (enabled and sys.stderr.isatty()):
        yield lambda text: None
        return
    if _drawn:
        outer = _drawn[-1]
        before = outer[0]

        def set_inner(text: str) -> None:
            outer[0] = f"{label}: {text}" if text else label

        set_inner("")
        try:
            yield set_inner
        finally:
            outer[0] = before
        return
    stop = threading.Event()
    t0 = time.perf_counter()
    detail = [""]

    def set_detail(text: str) -> None:
        detail[0] = text  # one reference swap: safe to read from the drawing thread

    def run() -> None:
        while not stop.wait(every):
            text = f": {detail[0]}" if detail[0] else ""
            sys.stderr.write(f"\r\033[K  {label}{text} ... {time.perf_counter() - t0:.0f} s")
            sys.stderr.flush()

    thread = threading.Thread(target=run, daemon=True)
    thread.start()
    _drawn.append(detail)
    try:
        yield set_detail
    finally:
        _drawn.remove(detail)
        stop.set()
        thread.join()
        sys.stderr.write("\r\033[K")
        sys.stderr.flush()
