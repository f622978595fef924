"""``tilesolve backends``: which solver backends are installed (CPMpy ``SolverLookup`` style)."""

from __future__ import annotations

from dataclasses import dataclass
from importlib import metadata
from typing import Callable

import click

from tilesolve.cli import options as opt

__all__ = ["backends", "BACKENDS", "Backend", "probe"]


def _dist_version(name: str) -> str:
    try:
        return metadata.version(name)
    except metadata.PackageNotFoundError:
        return "?"


def _pysat_solver(name: str) -> Callable[[], str]:
    def check() -> str:
        from pysat.solvers import Solver

        with Solver(name=name, bootstrap_with=[[1, 2]]) as s:
            s.solve()
        return f"python-sat {_dist_version('python-sat')}"

    return check


def _rc2() -> str:
    from pysat.examples.rc2 import RC2  # noqa: F401

    return f"python-sat {_dist_version('python-sat')}"


def _cpsat() -> str:
    from ortools.sat.python import cp_model  # noqa: F401

    return f"ortools {_dist_version('ortools')}"


def _numba() -> str:
    import numba

    return f"numba {numba.__version__}"


def _moderngl() -> str:
    import moderngl  # noqa: F401

    return f"moderngl {_dist_version('moderngl')}"


@dataclass(frozen=True)
class Backend:
    name: str
    kind: str
    used_by: str
    check: Callable[[], str]
    optional: bool = False


#: Backends in order of preference within each kind; the first of a kind is the default.
BACKENDS: tuple[Backend, ...] = (
    Backend("cadical195", "SAT", "--method sat", _pysat_solver("cadical195")),
    Backend("cadical153", "SAT", "--method sat", _pysat_solver("cadical153")),
    Backend("glucose4", "SAT", "--method sat", _pysat_solver("glucose4")),
    Backend("minisat22", "SAT", "--method sat", _pysat_solver("minisat22")),
    Backend("lingeling", "SAT", "--method sat", _pysat_solver("lingeling")),
    Backend("rc2", "MaxSAT", "--method maxsat, --closest-to", _rc2),
    Backend("cp-sat", "CP", "--method cpsat", _cpsat),
    Backend("numba", "JIT", "--method constructive (compiled loops)", _numba),
    Backend("moderngl", "GPU", "tilesolve.gpu (pip install 'tilesolve[gpu]')", _moderngl, optional=True),
)


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
    """List the solver backends and whether each is installed.

    \b
    Example:
      tilesolve backends

    Exit 0 when every required backend works, 1 when one is missing.
    """
    rows = []
    missing_required = False
    for b in BACKENDS:
        ok, info = probe(b)
        missing_required |= not ok and not b.optional
        status = "yes" if ok else ("no (optional)" if b.optional else "NO")
        rows.append((b.name, b.kind, status, info, b.used_by))
    header = ("backend", "kind", "installed", "version / reason", "used by")
    widths = [max(len(r[i]) for r in rows + [header]) for i in range(len(header))]
    for r in [header] + rows:
        click.echo("  ".join(c.ljust(w) for c, w in zip(r, widths)).rstrip())
    ctx.exit(1 if missing_required else 0)
