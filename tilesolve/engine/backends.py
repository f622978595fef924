"""Which solver backends are installed (CPMpy ``SolverLookup`` style): the SAT solvers PySAT
knows, and the other backends tilesolve's routes use. ``tilesolve backends`` prints them with
every family's routes (:func:`tilesolve.family.backend_report`).
"""

from __future__ import annotations

import gc
import sys
from dataclasses import dataclass
from importlib import metadata
from typing import Callable

__all__ = ["Backend", "OTHER_BACKENDS", "probe", "sat_backends", "dist_version"]


def dist_version(name: str) -> str:
    try:
        return metadata.version(name)
    except metadata.PackageNotFoundError:
        return "?"


def _rc2() -> str:
    from pysat.examples.rc2 import RC2  # noqa: F401

    return f"python-sat {dist_version('python-sat')}"


def _cpsat() -> str:
    from ortools.sat.python import cp_model  # noqa: F401

    return f"ortools {dist_version('ortools')}"


def _numba() -> str:
    import numba

    return f"numba {numba.__version__}"


def _distributed() -> str:
    import distributed  # noqa: F401

    return f"distributed {dist_version('distributed')}"


@dataclass(frozen=True)
class Backend:
    name: str
    kind: str
    used_by: str
    check: Callable[[], str]
    optional: bool = False


#: Backends besides the PySAT SAT solvers (which are listed from :mod:`tilesolve.engine.sat`).
OTHER_BACKENDS: tuple[Backend, ...] = (
    Backend("rc2", "MaxSAT", "--method maxsat, --closest-to", _rc2),
    Backend("cp-sat", "CP", "--method cpsat", _cpsat),
    Backend("numba", "JIT", "--method constructive (compiled loops)", _numba),
    Backend("dask", "cluster", "--cluster ADDRESS (pip install 'tilesolve[cluster]')", _distributed, optional=True),
)


def sat_backends() -> list[tuple[str, bool, str]]:
    """``(name, installed, notes)`` for every SAT solver PySAT knows."""
    from pysat.solvers import SolverNames

    from tilesolve.engine.sat import DEFAULT_SAT_SOLVER, proof_solvers, sat_solvers

    # Probing a solver that lacks an option makes PySAT's half-built object complain from
    # __del__ ("Exception ignored in ..."); that noise says nothing about the backend.
    hook, sys.unraisablehook = sys.unraisablehook, lambda unraisable: None
    try:
        usable, proofs = set(sat_solvers()), set(proof_solvers())
        gc.collect()
    finally:
        sys.unraisablehook = hook
    out = []
    for name in (n for n in vars(SolverNames) if not n.startswith("_")):
        notes = [w for w, ok in (("default", name == DEFAULT_SAT_SOLVER), ("DRAT proofs", name in proofs)) if ok]
        out.append((name, name in usable, ", ".join(["--method sat"] + notes)))
    return out


def probe(backend: Backend) -> tuple[bool, str]:
    """``(installed, version or reason)`` for one backend."""
    try:
        return True, backend.check()
    except Exception as exc:  # any import or start-up failure means "not usable"
        reason = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        return False, reason[:70]
