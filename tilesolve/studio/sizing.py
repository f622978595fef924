"""What a studio solve would cost in memory, estimated from the problem before it starts.

A solve whose encoding would need more than :data:`~tilesolve.studio.jobs.SOLVE_MEMORY` bytes
is refused at once with the estimate (HTTP 400), rather than started and stopped by the memory
watch of :mod:`tilesolve.studio.jobs` minutes later. Each entry of :data:`MODELS` counts the
units an encoding grows with (``cells x tiles`` placements of a dappled CNF, ``cells x
colours`` of a board CNF, ...) and multiplies them by the bytes per unit measured as the peak
resident growth of whole studio solves (pose, encode, solve, verify, draw) on this project's
dev machine, rounded up. Routes that encode nothing (the constructive and linear ones) have no
entry: they take memory in proportion to the tiling, which the form's size limits bound.

Measured (``tilesolve.studio.worker.solve_request``, peak RSS growth):

===========================================  ============  ==========
problem                                       route         growth
===========================================  ============  ==========
dappled 128x128, 10 tiles (163,840 units)     sat           171 MiB
dappled 256x256, 10 tiles (655,360 units)     sat           609 MiB
dappled 256x256, 3 tiles (196,608 units)      sat           107 MiB
dappled 128x128, 10 tiles, five conditions    sat           197 MiB
dappled 128x128, 10 tiles                     cpsat         552 MiB
board 128x128, 8 colours (131,072 units)      sat           283 MiB
board 256x256, 3 colours (196,608 units)      sat           364 MiB
board 64x64, 8 colours, 896 tiles             cpsat         1,871 MiB (60 s, unknown)
packing wang C=4 (65,536 units)               sat           168 MiB (60 s, unknown)
packing wang C=5 (390,625 units)              sat           597 MiB (60 s, unknown)
===========================================  ============  ==========

The one reproduced in the issue, dappled 2048x2048 with 10 tiles by ``sat``, is about 41.9
million placements: about 51 GiB by this model (it had passed 7.3 GiB and was growing). A
search's own memory grows with its time (learnt clauses, CP-SAT's workers), so an estimate is a
floor; the memory watch stops what outgrows it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable

from tilesolve.errors import InvalidProblem
from tilesolve.studio.jobs import SOLVE_MEMORY, in_bytes

__all__ = ["Model", "MODELS", "estimate", "refuse_oversized"]


@dataclass(frozen=True)
class Model:
    """The memory model of some routes of one family: ``units(problem) * per_unit`` bytes."""

    units: Callable[[Any], int]
    what: str
    per_unit: int


def _dappled(p) -> int:
    return p.rows * p.cols * p.n_tiles


def _board_colours(p) -> int:
    return p.board.n_cells * p.n_colors


def _board_tiles(p) -> int:
    return p.board.n_cells * len(p.tileset)


def _packing(p) -> int:
    return p.n_tiles * p.n_tiles


_PLACEMENTS = "placements (cell, tile)"

#: ``(family, route) -> Model``; bytes per unit from the measurements above, rounded up.
MODELS: dict[tuple[str, str], Model] = {
    ("dappled", "sat"): Model(_dappled, _PLACEMENTS, 1300),
    ("dappled", "maxsat"): Model(_dappled, _PLACEMENTS, 1300),
    ("dappled", "cpsat"): Model(_dappled, _PLACEMENTS, 3600),
    ("board", "sat"): Model(_board_colours, "cell colours", 2500),
    ("board", "cpsat"): Model(_board_tiles, _PLACEMENTS, 600),
    ("packing", "sat"): Model(_packing, _PLACEMENTS, 2700),
    ("packing", "cpsat"): Model(_packing, _PLACEMENTS, 2700),
    ("packing", "hybrid"): Model(_packing, _PLACEMENTS, 2700),
}


def estimate(family_name: str, route: str, problem: Any) -> tuple[int, int, str] | None:
    """``(bytes, units, what)`` a solve of ``problem`` by ``route`` is estimated to need, or
    None when the route has no model."""
    model = MODELS.get((family_name, route))
    if model is None:
        return None
    units = model.units(problem)
    return units * model.per_unit, units, model.what


def refuse_oversized(fam, problem: Any, method: str) -> None:
    """Raise :class:`InvalidProblem` when the solve would need more than a solve may use."""
    _, route = fam.lookup(method, problem)
    sized = estimate(fam.name, route, problem)
    if sized is not None and sized[0] > SOLVE_MEMORY:
        need, units, what = sized
        raise InvalidProblem(f"too large for the studio: method {route!r} would need about {in_bytes(need)} of memory "
                             f"({units:,} {what}); a solve here may use {in_bytes(SOLVE_MEMORY)}. Try a smaller size, "
                             f"fewer tiles or another method, or the tilesolve command")
