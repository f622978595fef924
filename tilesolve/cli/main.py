"""The console script's entry point (pyproject's ``[project.scripts]``): :func:`main`.

``tilesolve --version`` is answered here, before click or anything else is loaded, so it costs
little more than starting Python; every other command line goes to the click group,
:mod:`tilesolve.cli.group` (:data:`main_group` and :data:`GENERIC` are read from there on first
use, under these names too).

The console script ends its process as soon as the command is done (:func:`_exit`): the
interpreter's own teardown, freeing every object one by one, took 0.2-0.4 s after a large
encoding or CP-SAT model, after the time limit.
"""

from __future__ import annotations

import os
import sys
import time
from typing import NoReturn

from tilesolve import __version__

__all__ = ["main", "main_group", "GENERIC"]


def main(argv: list[str] | None = None) -> int:
    """Console-script entry point; returns the exit code (see :func:`tilesolve.cli.group.run`).

    As the console script (``argv`` ``None``: the command line is ``sys.argv``) a
    ``--time-limit`` counts from the start of the process, start-up included, and the process
    ends here (:func:`_exit`); called with ``argv``, the limit counts from this call and the
    exit code is returned.
    """
    if list(sys.argv[1:] if argv is None else argv) == ["--version"]:
        sys.stdout.write(f"tilesolve {__version__}\n")
        return 0
    if argv is None:
        from tilesolve.deadline import process_start

        started = process_start()
    else:
        started = time.perf_counter()
    from tilesolve.cli.group import run

    code = run(argv, started)
    if argv is None and sys.getprofile() is None and sys.gettrace() is None:  # not under a profiler
        _exit(code)
    return code


def _exit(code: int) -> NoReturn:
    """End the process as the interpreter does at exit, less the freeing of its objects: wait for
    the threads that are not daemons (and shut executors down), run the ``atexit`` handlers
    (logging, temporary folders, multiprocessing's children, coverage), flush stdout and stderr,
    and exit with ``code``."""
    import atexit
    import threading

    threading._shutdown()  # what the interpreter calls first at exit
    atexit._run_exitfuncs()
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):  # a closed pipe or stream: nothing more can reach it
            pass
    os._exit(code)


def __getattr__(name: str):
    """:data:`main_group` and :data:`GENERIC` of :mod:`tilesolve.cli.group`, loaded on first use."""
    if name in ("main_group", "GENERIC"):
        from tilesolve.cli import group

        return getattr(group, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
