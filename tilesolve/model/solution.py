"""Solutions and their status, shared by every problem family (DESIGN.md, "One pipeline")."""

from __future__ import annotations

import enum
from dataclasses import dataclass, field, replace
from typing import Any, Callable

import numpy as np

from tilesolve.model.window import Window

__all__ = ["Status", "Solution", "CountResult", "CrosscheckReport"]


class Status(str, enum.Enum):
    """Outcome of a solve.

    ``UNSAT`` is reported only when impossibility is proved (a solver's refutation,
    ideally with a checked proof); a time limit or an interruption is ``UNKNOWN``.
    """

    SAT = "sat"
    UNSAT = "unsat"
    OPTIMAL = "optimal"
    UNKNOWN = "unknown"

    @property
    def exit_code(self) -> int:
        """CLI exit code: 0 sat/optimal, 1 unsat, 3 unknown."""
        return {"sat": 0, "optimal": 0, "unsat": 1, "unknown": 3}[self.value]

    @property
    def has_tiling(self) -> bool:
        return self in (Status.SAT, Status.OPTIMAL)


@dataclass(frozen=True)
class Solution:
    """A tiling (or the proof that none exists), or a report, plus its provenance.

    Attributes
    ----------
    status : Status
    tiling : numpy.ndarray or None
        The family's tiling, ``None`` unless ``status.has_tiling``: a grid ``tiling[row, col]``
        (row 0 at the top) of tiles (dappled) or tile indices (packings, eq. 2.1 / 2.5), or
        the ``(n_cells, 4)`` leg colours of a board tiling (legs N, E, S, W: each row a tile). The
        family's verifier (``Family.verify``) says what it must satisfy.
    report : object or None
        An answer that is not a tiling, with its own words: a report of certificates (the
        aperiodicity family's :class:`~tilesolve.model.aperiodic.AperiodicReport`). It has a
        ``title`` (what it is: ``"aperiodicity report"``), a ``verdict`` (one word for what its
        certificates establish, e.g. ``"periodic"``, ``"undecided"``) and a ``conclusion`` (the
        same in a sentence). ``tiling`` is ``None`` beside it; ``status`` is ``sat`` when the
        verdict is decided, ``unknown`` when it is ``"undecided"`` (exit codes 0 and 3).
    method : str
        The route that produced it: ``"constructive"``, ``"sat"``, ``"maxsat"``, ``"cpsat"``...
    solver : str or None
        Backend name (e.g. ``"cadical153"``, ``"rc2"``, ``"cp-sat"``).
    seed : int or None
    time_s : float
        Wall-clock seconds spent, encoding included.
    objective : int or None
        Hamming distance for closest-tiling problems.
    reason : str or None
        For ``unsat``: why (e.g. the proof checker's verdict); for ``unknown``: what stopped it.
    notes : tuple of str
        Things the user should know (e.g. "constructive route fell back to sat").
    stats : dict
        Free-form numbers: variables, clauses, proof size, lower bound...
    window : Window or None
        Where the tiling lies in the plane, for a tiling that is a window of an infinite one
        (a procedural or repeatable wall, a stochastic tiling): its grid's row 0 and column 0
        are the cell ``window.cell(0, 0)``. ``None`` for a tiling that is not cut from the plane.
    renderer : callable, optional
        ``renderer(solution, fmt) -> str | bytes``: the picture of this solution as ``"svg"``
        or ``"png"``; set by :func:`tilesolve.family.solve` from the family's drawing, so a
        solution draws itself in a notebook (``_repr_svg_`` / ``_repr_png_``).
    """

    status: Status
    tiling: np.ndarray | None = None
    method: str = ""
    solver: str | None = None
    seed: int | None = None
    time_s: float = 0.0
    objective: int | None = None
    reason: str | None = None
    notes: tuple[str, ...] = ()
    stats: dict[str, Any] = field(default_factory=dict)
    window: Window | None = None
    report: Any = None
    renderer: Callable[["Solution", str], Any] | None = field(default=None, repr=False, compare=False)

    def _repr_svg_(self) -> str | None:
        """SVG for notebooks (``None`` without a tiling, or when the family cannot draw it as SVG)."""
        return self._picture("svg")

    def _repr_png_(self) -> bytes | None:
        """PNG for notebooks (large grids, where SVG is refused)."""
        return self._picture("png")

    @property
    def answer(self) -> Any:
        """What the family's verifier checks: the report, else the tiling when the status has one
        (``None`` when there is neither)."""
        if self.report is not None:
            return self.report
        return self.tiling if self.status.has_tiling else None

    @property
    def verdict(self) -> str:
        """The answer in one word: a report's verdict, else the status (``"sat"``, ``"unsat"``...)."""
        return self.report.verdict if self.report is not None else self.status.value

    def _picture(self, fmt: str):
        if self.renderer is None or self.answer is None:
            return None
        try:
            return self.renderer(self, fmt)
        except Exception:  # noqa: BLE001 - a picture that cannot be drawn is simply not shown
            return None

    def with_note(self, note: str) -> "Solution":
        return replace(self, notes=self.notes + (note,))

    def replace(self, **changes: Any) -> "Solution":
        return replace(self, **changes)


@dataclass(frozen=True)
class CountResult:
    """An exact count of solutions, or ``None`` with status ``unknown`` when time ran out.

    ``method`` names the route (``"transfer"``, ``"enumerate"``, ``"backtrack"``...); ``note``
    says what the user should know (a fallback, where enumeration stopped); ``stats`` holds
    route figures (search nodes, partial counts).
    """

    value: int | None
    status: Status
    method: str
    time_s: float
    note: str | None = None
    stats: dict[str, Any] = field(default_factory=dict)

    @property
    def exact(self) -> bool:
        """True when ``value`` is the exact count."""
        return self.value is not None and self.status is Status.SAT

    def replace(self, **changes: Any) -> "CountResult":
        return replace(self, **changes)


@dataclass
class CrosscheckReport:
    """What a family's ``crosscheck`` ran and found; ``ok`` is False on any disagreement.

    ``verdicts`` maps each route that decided the problem to ``sat`` or ``unsat``.
    """

    ok: bool = True
    lines: list[str] = field(default_factory=list)
    verdicts: dict[str, Status] = field(default_factory=dict)

    def add(self, ok: bool, line: str) -> None:
        self.ok &= ok
        self.lines.append(("ok   " if ok else "FAIL ") + line)

    def add_agreement(self) -> None:
        """Record whether every route that decided the problem agrees on solvability."""
        agree = len(set(self.verdicts.values())) <= 1
        self.add(agree, "routes agree on solvability: " + ", ".join(f"{k}={v.value}" for k, v in self.verdicts.items()))
