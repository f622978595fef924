"""The plumbing every family facade shares (STYLE.md §1: a registry, not an if/elif chain).

A facade (``tilesolve.dappled``, ``tilesolve.wang``, ``tilesolve.packing``) keeps a
``SOLVERS`` dict of routes; :func:`lookup` turns the user's ``method`` into a route and
:func:`verified` runs the family's independent checker on whatever a route returns.
"""

from __future__ import annotations

from typing import Callable, Mapping, Sequence

from tilesolve.errors import InvalidProblem
from tilesolve.model.solution import Solution

__all__ = ["lookup", "verified"]


def lookup(
    method: str | Callable[..., Solution],
    solvers: Mapping[str, Callable[..., Solution]],
    auto: Callable[[], str],
) -> tuple[Callable[..., Solution], str]:
    """The route for ``method`` and its name.

    ``method`` is a key of ``solvers``, ``"auto"`` (then ``auto()`` names the key), or a
    callable with the routes' signature.

    >>> lookup("sat", {"sat": len}, lambda: "sat")
    (<built-in function len>, 'sat')
    """
    if callable(method):
        return method, getattr(method, "__name__", "custom")
    name = auto() if method == "auto" else method
    if name not in solvers:
        raise InvalidProblem(f"unknown method {method!r}; choose one of {', '.join(('auto', *solvers))}")
    return solvers[name], name


def verified(sol: Solution, violations: Callable[[object], Sequence], what: str = "tiling") -> Solution:
    """Return ``sol`` once its tiling passes ``violations``; a failure is a bug, never 'sat'."""
    if sol.status.has_tiling:
        bad = violations(sol.tiling)
        if bad:
            raise AssertionError(
                f"internal error: method {sol.method!r} returned a {what} that fails verification "
                f"({len(bad)} violations, first: {bad[0]}); please report this"
            )
    return sol
