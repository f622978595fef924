"""The papers' constructive algorithms (hot loops compiled with numba)."""

from tilesolve._lazy import lazy_exports

#: Exported names and the module each lives in (imported on first use).
_WHERE = {
    "ROUTES": "tilesolve.constructive.dappled",
    "algorithm1": "tilesolve.constructive.dappled",
    "algorithm2": "tilesolve.constructive.dappled",
    "dappled_route": "tilesolve.constructive.dappled",
    "draughtboard": "tilesolve.constructive.dappled",
    "make_dappled": "tilesolve.constructive.dappled",
    "remark34": "tilesolve.constructive.dappled",
    "trivial": "tilesolve.constructive.dappled",
}

__all__ = list(_WHERE)
__getattr__, __dir__ = lazy_exports(__name__, _WHERE)
