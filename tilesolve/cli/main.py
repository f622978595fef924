"""The console script's entry point (pyproject's ``[project.scripts]``): :func:`main`.

``tilesolve --version`` is answered here, before click or anything else is loaded, so it costs
little more than starting Python; every other command line goes to the click group,
:mod:`tilesolve.cli.group` (:data:`main_group` and :data:`GENERIC` are read from there on first
use, under these names too).
"""

from __future__ import annotations

import sys
import time

from tilesolve import __version__

__all__ = ["main", "main_group", "GENERIC"]


def main(argv: list[str] | None = None) -> int:
    """Console-script entry point; returns the exit code (see :func:`tilesolve.cli.group.run`).

    As the console script (``argv`` ``None``: the command line is ``sys.argv``) a
    ``--time-limit`` counts from the start of the process, start-up included; called with
    ``argv``, from this call.
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

    return run(argv, started)


def __getattr__(name: str):
    """:data:`main_group` and :data:`GENERIC` of :mod:`tilesolve.cli.group`, loaded on first use."""
    if name in ("main_group", "GENERIC"):
        from tilesolve.cli import group

        return getattr(group, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
