"""The one exception hierarchy of tilesolve.

The CLI maps each class to an exit code (DESIGN.md, "Errors"):

======================  =========  ==============================================
exception               exit code  meaning
======================  =========  ==============================================
``InvalidProblem``      2          the input is malformed or out of range
``MethodNotApplicable`` 2          a method's preconditions fail (names another)
``BackendUnavailable``  2          a solver backend or optional package is missing
``Unsatisfiable``       1          raised only by APIs that must return a tiling
``InternalError``       70         a bug: an answer failed its own verification
======================  =========  ==============================================

A solver run that ends on a time limit is *not* an error: it returns a
:class:`~tilesolve.model.solution.Solution` with status ``unknown`` (exit 3).
"""

__all__ = [
    "TilesolveError",
    "InvalidProblem",
    "MethodNotApplicable",
    "BackendUnavailable",
    "Unsatisfiable",
    "InternalError",
]


class TilesolveError(Exception):
    """Base class of every error tilesolve raises on purpose."""

    exit_code = 2


class InvalidProblem(TilesolveError, ValueError):
    """The problem or input file is malformed, contradictory in form, or too large."""

    exit_code = 2


class MethodNotApplicable(InvalidProblem):
    """A method's preconditions fail for this problem; the message names a route that works."""

    exit_code = 2


class BackendUnavailable(TilesolveError, RuntimeError):
    """A solver backend or optional dependency is not installed or cannot start."""

    exit_code = 2


class Unsatisfiable(TilesolveError):
    """No tiling exists (proved). Raised only by APIs that must return a tiling."""

    exit_code = 1


class InternalError(TilesolveError, AssertionError):
    """A bug, never the user's fault: e.g. a route returned a tiling its verifier rejects.

    Exit code 70 (``EX_SOFTWARE``); the message asks for a report.
    """

    exit_code = 70

    def __init__(self, message: str) -> None:
        super().__init__(f"internal error: {message}; please report this")
