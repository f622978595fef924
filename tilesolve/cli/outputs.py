"""What a command run leaves behind: its output files, all or none, and nothing on Ctrl-C.

Every command that writes files builds one :class:`Outputs` from all the outputs it was
given (``-o``, ``--svg``, ``--png``, ``--dimacs``...) before any work. The constructor
checks them all: each can be written (directory exists and accepts a new file, the name is
not a directory, an existing device or FIFO is writable), and no two name the same file
(``-`` is standard output, and only one output may use it). The command then writes through
the library's writers inside :meth:`Outputs.commit`, which stages every file and commits
them together when the block ends cleanly: a failure of any write leaves no file of this run
(:func:`tilesolve.io.atomic.commit_together`).

Every output option names its format by its suffix (``--svg t.svg``, ``--png t.png``,
``-o t.json``): its click type :class:`OutputFile` refuses a name whose suffix is another
format's, while the options are read (:func:`check_suffix`, the one check every command uses).

Interruptions (README, "Exit codes"): Ctrl-C exits 130 and SIGTERM exits 143, writing
nothing and leaving existing files as they were. The engine turns Ctrl-C inside a solver
into an ``unknown`` result whose reason starts with ``"interrupted"``;
:func:`tilesolve.family.raise_if_interrupted` is the one place that recognises such a result, and turns it
back into the interruption it was, before any file is written. A *time limit* is not an
interruption: its ``unknown`` record is written as documented (exit 3).
"""

from __future__ import annotations

import contextlib
import os
import signal
from pathlib import Path
from typing import Iterator, Sequence

import click

from tilesolve.errors import InvalidProblem
from tilesolve.io.atomic import commit_together, probe_writable

__all__ = ["Outputs", "OutputFile", "check_suffix", "check_target", "sigterm_as_interrupt", "interruption",
           "stop_if_interrupted", "interrupt_received"]

_state = {"terminated": False, "interrupted": False, "pid": 0, "active": False}


def check_target(path: str) -> None:
    """Refuse an output that cannot be written, before any work is done."""
    if path == "-":
        return
    p = Path(path)
    if p.is_dir() or path.endswith(("/", os.sep)):
        raise InvalidProblem(f"cannot write {path}: it is a directory")
    parent = p.parent if str(p.parent) else Path(".")
    if not parent.exists():
        raise InvalidProblem(f"cannot write {path}: directory {parent} does not exist")
    if not parent.is_dir():
        raise InvalidProblem(f"cannot write {path}: {parent} is not a directory")
    try:
        probe_writable(p)
    except OSError as exc:
        why = (exc.strerror or str(exc)).lower()
        if p.exists():
            raise InvalidProblem(f"cannot write {path}: {why}") from None
        raise InvalidProblem(f"cannot write {path}: cannot create a file in {parent} ({why})") from None


def check_suffix(path: str, formats: Sequence[str], option: str = "the output") -> str:
    """The format of the output ``path`` among ``formats`` (``"svg"``, ``"png"``, ``"json"``...),
    read from its suffix; ``-`` (standard output) is the first format.

    Raises
    ------
    InvalidProblem
        The suffix names none of ``formats``.

    Examples
    --------
    >>> check_suffix("T.PNG", ("svg", "png"))
    'png'
    >>> check_suffix("c3.png", ("svg",), "--svg")
    Traceback (most recent call last):
    tilesolve.errors.InvalidProblem: cannot write c3.png: --svg writes .svg files (the name's suffix is the format)
    """
    if path == "-":
        return formats[0]
    fmt = os.path.splitext(path)[1].lower().lstrip(".")
    if fmt in formats:
        return fmt
    names = " or ".join(f".{f}" for f in formats)
    raise InvalidProblem(f"cannot write {path}: {option} writes {names} files (the name's suffix is the format)")


class OutputFile(click.Path):
    """The click type of an output option: a file (not a directory) whose suffix is one of
    ``formats`` (:func:`check_suffix`); ``-`` (standard output) where ``allow_dash``, and any
    existing device or FIFO (``/dev/stdout``, a named pipe: a stream, whose name says no format)."""

    def __init__(self, *formats: str, allow_dash: bool = True) -> None:
        super().__init__(dir_okay=False, allow_dash=allow_dash)
        self.formats = formats

    def convert(self, value, param, ctx):  # noqa: D102 - click API
        value = super().convert(value, param, ctx)
        if os.path.exists(value) and not os.path.isfile(value):
            return value  # a device or a FIFO (a directory is refused above)
        check_suffix(os.fsdecode(value), self.formats, "/".join(param.opts) if param is not None else "the output")
        return value


def _same(a: str, b: str) -> bool:
    if a == "-" or b == "-":
        return a == b
    try:
        return os.path.samefile(a, b)
    except OSError:
        return os.path.realpath(a) == os.path.realpath(b)


class Outputs:
    """All the outputs of one command run (``None`` entries are options not given).

    Examples
    --------
    >>> import os, tempfile
    >>> from tilesolve.io.atomic import write_text_atomic
    >>> d = tempfile.mkdtemp()
    >>> a, b = os.path.join(d, "a.txt"), os.path.join(d, "b.txt")
    >>> outs = Outputs(a, None, b)
    >>> with outs.commit():
    ...     write_text_atomic(a, "one")
    ...     os.path.exists(a)                  # staged: not there yet
    ...     write_text_atomic(b, "two")
    False
    >>> sorted(os.listdir(d))
    ['a.txt', 'b.txt']
    >>> Outputs(a, "-", a)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    tilesolve.errors.InvalidProblem: ... is named twice (two outputs cannot share a file)
    """

    def __init__(self, *paths: str | None) -> None:
        self.paths = [str(p) for p in paths if p]
        for i, p in enumerate(self.paths):
            for q in self.paths[:i]:
                if _same(p, q):
                    if p == "-":
                        raise InvalidProblem("only one output can go to standard output ('-')")
                    raise InvalidProblem(f"{p} is named twice (two outputs cannot share a file)")
        for p in self.paths:
            check_target(p)

    def __bool__(self) -> bool:
        return bool(self.paths)

    @property
    def files(self) -> list[str]:
        """The outputs that are files (not standard output), for the summary line."""
        return [p for p in self.paths if p != "-"]

    @contextlib.contextmanager
    def commit(self, result=None) -> Iterator[None]:
        """Stage the writes of the block and commit them together at its end.

        ``result`` (a solution or a count) is checked first: an interrupted one ends the run
        here, before anything is written (:func:`tilesolve.family.raise_if_interrupted`).
        """
        if result is not None:
            from tilesolve.family import raise_if_interrupted

            raise_if_interrupted(result)
        with commit_together():
            yield


def _on_sigterm(signum, frame) -> None:
    if os.getpid() != _state["pid"]:  # a child that inherited the handler: die as by default
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        os.kill(os.getpid(), signal.SIGTERM)
        return
    _state["terminated"] = True
    # Unwinds like Ctrl-C: solvers stop through the engine's interrupt path, and every
    # temporary is removed by the writer that opened it.
    raise KeyboardInterrupt


def _on_sigint(signum, frame) -> None:
    _state["interrupted"] = True
    raise KeyboardInterrupt


@contextlib.contextmanager
def sigterm_as_interrupt() -> Iterator[None]:
    """Inside the block, SIGTERM in this process behaves as Ctrl-C, remembered for the exit
    code (143); after it, SIGTERM ends the process at once again, as by default. Ctrl-C is
    remembered too (:func:`interrupt_received`), for this run only."""
    _state.update(pid=os.getpid(), terminated=False, interrupted=False)
    try:
        previous = signal.signal(signal.SIGTERM, _on_sigterm)
    except (ValueError, OSError, AttributeError):  # not the main thread, or no SIGTERM here
        yield
        return
    _state["active"] = True
    previous_int = signal.getsignal(signal.SIGINT)
    if previous_int is signal.default_int_handler:  # an ignored Ctrl-C stays ignored
        signal.signal(signal.SIGINT, _on_sigint)
    try:
        yield
    finally:
        _state["active"] = False  # a later run in this process starts with no signal received
        signal.signal(signal.SIGTERM, previous)
        if previous_int is signal.default_int_handler:
            signal.signal(signal.SIGINT, previous_int)


def interrupt_received() -> bool:
    """Whether Ctrl-C or SIGTERM reached this run. An exception that follows one is its
    consequence, not a bug: numpy, for one, turns a ``KeyboardInterrupt`` raised inside a
    structured-array comparison into a ``TypeError``."""
    return _state["active"] and (_state["interrupted"] or _state["terminated"])


def stop_if_interrupted() -> None:
    """Raise KeyboardInterrupt when Ctrl-C or SIGTERM reached this run: a loop of trials calls
    it after each one, so a signal that a solver caught and turned into an answer (``unknown``,
    or a failed check) ends the loop with exit 130 instead of being reported as a result."""
    if interrupt_received():
        raise KeyboardInterrupt


def interruption() -> tuple[int, str]:
    """Exit code and word for the interruption being handled: (143, "terminated") after
    SIGTERM, else (130, "interrupted")."""
    return (143, "terminated") if _state["terminated"] else (130, "interrupted")
