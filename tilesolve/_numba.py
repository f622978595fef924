"""numba for the project's compiled kernels, loaded without the ``scipy.linalg`` it probes for.

Every module that compiles kernels imports numba from here (``from tilesolve._numba import
njit``), so that this runs before the first kernel is compiled or loaded from numba's cache.

``numba.np.arraymath`` tries ``import scipy.linalg.cython_blas`` when it loads (at a process's
first kernel), and scipy.linalg's package costs more CPU than loading a command's cached
kernels: every command that runs a kernel paid it at start-up. The kernels use no BLAS. While
that one module loads, the probe fails at once (a ``None`` in :data:`sys.modules` raises
ModuleNotFoundError before any parent package is imported); numba's flag is then set to what
its probe would have found (scipy installed), and a later kernel that uses linear algebra
imports scipy when it compiles (``numba.np.linalg.ensure_blas``), as before. With another
numba's layout this is numba's own import. Python's lock on this module's import keeps two
threads from running it at once.
"""

from __future__ import annotations

import importlib.util
import sys

import numba

__all__ = ["numba", "njit"]

njit = numba.njit


def _numpy_support_without_scipy() -> None:
    key = "scipy.linalg.cython_blas"
    if "numba.np.arraymath" in sys.modules or "scipy.linalg" in sys.modules or key in sys.modules:
        return
    sys.modules[key] = None  # type: ignore[assignment]
    try:
        import numba.np.arraymath as arraymath
    except ImportError:  # pragma: no cover - another numba's layout
        return
    finally:
        if key in sys.modules and sys.modules[key] is None:
            del sys.modules[key]
    if getattr(arraymath, "_HAVE_BLAS", True) is False:
        arraymath._HAVE_BLAS = importlib.util.find_spec("scipy") is not None


_numpy_support_without_scipy()
