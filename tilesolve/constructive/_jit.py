"""Kernels that run as plain Python on small inputs and compiled by numba on large ones.

A kernel module writes its hot loops once, as ordinary functions marked with
:func:`kernel`, and ends with ``KERNELS = Kernels(globals(), threshold)``. Its module
attributes stay the plain functions. ``KERNELS.pick(work)`` returns the namespace to call:

* the module itself (plain Python, no numba import) while the work is small, or
* a namespace of ``numba.njit(cache=True)`` dispatchers, built on first need: importing numba
  and loading its cache costs a few tenths of a second, which pays only above ``threshold``
  cells (measured by ``benchmarks/bench_startup.py``).

Compiled kernels must call compiled helpers, so the compiled namespace is a copy of the
module's globals in which every marked function is rebuilt from the same code object (the
same source, hence the same numba cache files) and replaced by its dispatcher; numba resolves
a kernel's calls in that copy when it compiles. The plain module is untouched.

The choice follows the ski-rental rule: the compiled kernels are used once loaded, for a
single call of at least ``threshold`` cells, or once the plain calls of this process have
together done ``threshold`` cells of work (so a loop of small calls does not stay
interpreted forever). Both paths give the same output bit for bit; the kernels keep to
arithmetic whose result does not depend on the path (tests compare them on random input).
"""

from __future__ import annotations

import os
import sys
import threading
import types
from typing import Callable

import numpy as np

__all__ = ["kernel", "Kernels", "u32", "seed_state", "rand32", "cores"]

_MODES = ("auto", "plain", "compiled")


def kernel(**options) -> Callable:
    """Mark a function as a kernel; ``options`` go to ``numba.njit`` (besides ``cache=True``).

    The function itself is returned unchanged (it is the plain path).
    """

    def mark(func):
        func._njit_options = options
        return func

    return mark


class Kernels:
    """The plain and the compiled namespace of one kernel module.

    Parameters
    ----------
    namespace : dict
        The kernel module's ``globals()``.
    threshold : int
        Cells of work from which compiling pays (see the module docstring).

    Attributes
    ----------
    mode : {"auto", "plain", "compiled"}
        ``"auto"`` chooses as described above; the others force a path (tests, benchmarks).
    """

    def __init__(self, namespace: dict, threshold: int):
        self._namespace = namespace
        self.threshold = int(threshold)
        self.mode = "auto"
        self._plain_work = 0
        self._compiled: types.SimpleNamespace | None = None
        self._lock = threading.Lock()

    def plain(self) -> types.ModuleType:
        """The kernel module itself: its functions run interpreted."""
        return sys.modules[self._namespace["__name__"]]

    def compiled(self) -> types.SimpleNamespace:
        """The numba-compiled namespace (imports numba and compiles or loads the cache on first use)."""
        with self._lock:
            if self._compiled is None:
                self._compiled = self._compile()
            return self._compiled

    @property
    def loaded(self) -> bool:
        """Whether the compiled namespace exists in this process."""
        return self._compiled is not None

    def pick(self, work: int) -> types.ModuleType | types.SimpleNamespace:
        """The namespace to run ``work`` cells with (see the module docstring)."""
        if self.mode not in _MODES:
            raise ValueError(f"Kernels.mode must be one of {_MODES}, got {self.mode!r}")
        if self.mode == "compiled" or (self.mode == "auto" and self._wants_compiled(int(work))):
            return self.compiled()
        return self.plain()

    def _wants_compiled(self, work: int) -> bool:
        if self._compiled is not None:
            return True
        self._plain_work += work
        return work >= self.threshold or self._plain_work >= self.threshold

    def _compile(self) -> types.SimpleNamespace:
        from tilesolve._numba import numba

        ns = dict(self._namespace)
        module = ns["__name__"]
        marked = {k: v for k, v in ns.items() if callable(v) and hasattr(v, "_njit_options")}
        for name, func in marked.items():
            if func.__module__ == module:  # rebuilt so that its globals are the compiled copy
                clone = types.FunctionType(func.__code__, ns, func.__name__, func.__defaults__, func.__closure__)
                clone.__qualname__ = func.__qualname__
                clone.__doc__ = func.__doc__
            else:  # a helper from another module (below); it calls no other kernel
                clone = func
            ns[name] = numba.njit(cache=True, **func._njit_options)(clone)
        return types.SimpleNamespace(**{k: v for k, v in ns.items() if not k.startswith("__")})


# --------------------------------------------------------------------------- shared helpers
@kernel(inline="always")
def u32(x):
    """``x`` as an unsigned 32-bit value (``-1`` is the largest), the same on both paths."""
    return int(x) & 0xFFFFFFFF


@kernel()
def seed_state(seed):
    """A one-word xorshift64 state from a non-negative ``seed < 2**31``."""
    st = np.empty(1, np.uint64)
    st[0] = np.uint64(seed) * np.uint64(2654435761) + np.uint64(88172645463325252)
    if st[0] == 0:
        st[0] = np.uint64(1)
    return st


@kernel()
def rand32(state):
    """xorshift64 step on ``state[0]``; returns 32 random bits (Marsaglia 2003)."""
    x = state[0]
    x ^= (x << np.uint64(13)) & np.uint64(0xFFFFFFFFFFFFFFFF)
    x ^= x >> np.uint64(7)
    x ^= (x << np.uint64(17)) & np.uint64(0xFFFFFFFFFFFFFFFF)
    state[0] = x
    return np.int64(x >> np.uint64(32))


def cores() -> int:
    """The cores this process may run on (its CPU affinity where the system tells it): how many
    threads a kernel that splits its work into bands may use."""
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1
