"""``tilesolve backends``: which solver backends are installed (CPMpy ``SolverLookup`` style),
and every family's routes (read from the registry, :mod:`tilesolve.family`)."""

from __future__ import annotations

import gc
import sys
from dataclasses import dataclass
from importlib import metadata
from typing import Callable

import click

from tilesolve.cli import options as opt

__all__ = ["backends", "OTHER_BACKENDS", "Backend", "probe", "sat_backends"]


def _dist_version(name: str) -> str:
    try:
        return metadata.version(name)
    except metadata.PackageNotFoundError:
        return "?"


def _rc2() -> str:
    from pysat.examples.rc2 import RC2  # noqa: F401

    return f"python-sat {_dist_version('python-sat')}"


def _cpsat() -> str:
    from ortools.sat.python import cp_model  # noqa: F401

    return f"ortools {_dist_version('ortools')}"


def _numba() -> str:
    import numba

    return f"numba {numba.__version__}"


def _distributed() -> str:
    import distributed  # noqa: F401

    return f"distributed {_dist_version('distributed')}"


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


@click.command(context_settings=opt.CONTEXT_SETTINGS)
@click.pass_context
def backends(ctx) -> None:
    """List the solver backends (and whether each is installed) and every family's routes.

    \b
    Example:
      tilesolve backends

    Exit 0 when every required backend works (at least one SAT solver), 1 otherwise.
    """
    rows = []
    pysat = f"python-sat {_dist_version('python-sat')}"
    sat = sat_backends()
    for name, ok, used_by in sat:
        rows.append((name, "SAT", "yes" if ok else "no", pysat if ok else "not in this python-sat build", used_by))
    missing_required = not any(ok for _, ok, _ in sat)
    for b in OTHER_BACKENDS:
        ok, info = probe(b)
        missing_required |= not ok and not b.optional
        status = "yes" if ok else ("no (optional)" if b.optional else "NO")
        rows.append((b.name, b.kind, status, info, b.used_by))
    _table(("backend", "kind", "installed", "version / reason", "used by"), rows)
    from tilesolve.family import families

    click.echo("")
    _table(("family", "route", "what it does"),
           [(fam.name, route, fam.route_help.get(route, "")) for fam in families() for route in fam.routes])
    ctx.exit(1 if missing_required else 0)


def _table(header: tuple[str, ...], rows: list[tuple[str, ...]]) -> None:
    widths = [max(len(r[i]) for r in rows + [header]) for i in range(len(header))]
    for r in [header] + rows:
        click.echo("  ".join(c.ljust(w) for c, w in zip(r, widths)).rstrip())
