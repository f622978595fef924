"""Solver backends: time limits, enumeration, counting, proofs (DESIGN.md, "engine").

Backends are generic (clauses in, :class:`Result` out) so every problem family reuses
them; family modules such as :mod:`tilesolve.engine.dappled` turn Results into
:class:`~tilesolve.model.solution.Solution` objects.

:data:`BACKENDS` is the registry of installed backends (STYLE.md §3, CPMpy's
``SolverLookup``): :func:`backend_status` lists them for a ``tilesolve backends`` command.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

from tilesolve.deadline import Deadline
from tilesolve.engine.result import Result

__all__ = [
    "Result",
    "Deadline",
    "Backend",
    "BACKENDS",
    "backend_status",
    "solve_sat",
    "solve_maxsat",
    "solve_cpsat",
    "enumerate_tilings",
    "count_by_enumeration",
]


@dataclass(frozen=True)
class Backend:
    """One installed solver backend.

    Attributes
    ----------
    name : str
        Registry key (``"sat"``, ``"maxsat"``, ``"cpsat"``).
    description : str
    version : callable
        Returns the backend's version string; raises ``BackendUnavailable`` if missing.
    """

    name: str
    description: str
    version: Callable[[], str]

    def supported(self) -> bool:
        try:
            self.version()
            return True
        except Exception:  # noqa: BLE001 - any import failure means "not installed"
            return False


def _pysat_version() -> str:
    import pysat

    return f"python-sat {pysat.__version__}"


def _cpsat_version() -> str:
    from tilesolve.engine.cpsat import cpsat_version

    return f"ortools {cpsat_version()}"


#: Ordered registry: the first entry is the default route.
BACKENDS: dict[str, Backend] = {
    "sat": Backend("sat", "PySAT SAT solvers (default CaDiCaL 1.5.3) with DRAT proofs", _pysat_version),
    "maxsat": Backend("maxsat", "RC2 core-guided MaxSAT (PySAT) and an exact lazy decomposition", _pysat_version),
    "cpsat": Backend("cpsat", "OR-tools CP-SAT", _cpsat_version),
}


def backend_status() -> list[dict]:
    """``[{"name", "description", "supported", "version"}, ...]`` for every backend."""
    out = []
    for b in BACKENDS.values():
        ok = b.supported()
        out.append({"name": b.name, "description": b.description, "supported": ok,
                    "version": b.version() if ok else None})
    return out


def __getattr__(name: str):
    # The dappled routes import encodings and verifiers; load them on first use.
    if name in ("solve_sat", "solve_maxsat", "solve_cpsat", "enumerate_tilings", "count_by_enumeration"):
        from tilesolve.engine import dappled

        return getattr(dappled, name)
    raise AttributeError(f"module 'tilesolve.engine' has no attribute {name!r}")
