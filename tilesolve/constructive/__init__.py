"""The papers' constructive algorithms (hot loops compiled with numba)."""

from tilesolve.constructive.dappled import (
    ROUTES,
    algorithm1,
    algorithm2,
    dappled_route,
    draughtboard,
    make_dappled,
    remark34,
    trivial,
)

__all__ = [
    "ROUTES",
    "algorithm1",
    "algorithm2",
    "dappled_route",
    "draughtboard",
    "make_dappled",
    "remark34",
    "trivial",
]
