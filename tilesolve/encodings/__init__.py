"""Solver-free encodings of tiling problems (DESIGN.md, "Encodings").

Each family has its own module (``tilesolve.encodings.dappled``, ...) that turns a
Problem into clauses and a model back into a tiling. Encodings may use PySAT's pure
``formula``/``card`` modules and build OR-tools CP-SAT *models*, but never call a solver.

This module holds the one piece every family shares: :class:`ClauseSet`, a list of
clauses stored as numpy blocks of equal width (so that millions of window clauses can be
generated, counted, evaluated and handed to a solver without a Python loop per clause)
plus ragged clauses from cardinality encodings.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Iterable, Iterator, Protocol

import numpy as np

__all__ = [
    "ClauseBlock",
    "ClauseSet",
    "Encoding",
    "cardinality",
    "DappledEncoding",
    "encode_cnf",
    "encode_wcnf",
    "build_cpsat",
    "CpSatDappled",
]


@dataclass(frozen=True)
class ClauseBlock:
    """Clauses of one kind and one width, one clause per row of ``lits``.

    Attributes
    ----------
    label : str
        What the clauses say (``"H0=2 windows"``, ``"fixed cells"``, ...); used in DIMACS
        comments and by algorithms that must tell grid clauses from auxiliary ones.
    lits : numpy.ndarray
        ``int64`` array of shape ``(n_clauses, width)`` (DIMACS literals, no zeros) for a
        rectangular block, or ``None`` for a ragged block.
    ragged : list of list of int
        The clauses of a ragged block (e.g. from :mod:`pysat.card`), else empty.
    grid_only : bool
        True when the clauses mention only grid variables (no auxiliary variables).
    """

    label: str
    lits: np.ndarray | None = None
    ragged: list = field(default_factory=list)
    grid_only: bool = True

    def __len__(self) -> int:
        return len(self.ragged) if self.lits is None else int(self.lits.shape[0])

    def lists(self, chunk: int = 1 << 16) -> Iterator[list[list[int]]]:
        """Yield the clauses as Python lists, ``chunk`` clauses at a time."""
        if self.lits is None:
            for i in range(0, len(self.ragged), chunk):
                yield self.ragged[i : i + chunk]
        else:
            for i in range(0, self.lits.shape[0], chunk):
                yield self.lits[i : i + chunk].tolist()


class ClauseSet:
    """An ordered collection of :class:`ClauseBlock` objects.

    Iterating gives each clause as a list of ints, as :class:`pysat.formula.CNF` does;
    :meth:`chunks` is the fast path for handing millions of clauses to a solver.

    Examples
    --------
    >>> cs = ClauseSet()
    >>> cs.add_array(np.array([[1, 2], [-1, 2]]), "demo")
    >>> cs.add_lists([[-2]], "unit")
    >>> len(cs), list(cs)
    (3, [[1, 2], [-1, 2], [-2]])
    """

    def __init__(self) -> None:
        self.blocks: list[ClauseBlock] = []

    def add_array(self, lits: np.ndarray, label: str, grid_only: bool = True) -> None:
        """Append the rows of a 2-D literal array as clauses (an empty array is ignored)."""
        lits = np.asarray(lits, dtype=np.int64)
        if lits.ndim != 2:
            raise ValueError("clause arrays must be 2-D (one clause per row)")
        if lits.shape[0] == 0:
            return
        if lits.shape[1] == 0:
            # Empty clauses: one is enough to make the formula unsatisfiable.
            self.blocks.append(ClauseBlock(label, None, [[]], grid_only))
            return
        self.blocks.append(ClauseBlock(label, lits, [], grid_only))

    def add_lists(self, clauses: Iterable[Iterable[int]], label: str, grid_only: bool = True) -> None:
        """Append ragged clauses (lists of DIMACS literals)."""
        cl = [list(map(int, c)) for c in clauses]
        if cl:
            self.blocks.append(ClauseBlock(label, None, cl, grid_only))

    def __len__(self) -> int:
        return sum(len(b) for b in self.blocks)

    def __iter__(self) -> Iterator[list[int]]:
        for chunk in self.chunks():
            yield from chunk

    def chunks(self, chunk: int = 1 << 16) -> Iterator[list[list[int]]]:
        """Yield lists of clauses (each a list of ints), block by block."""
        for b in self.blocks:
            yield from b.lists(chunk)

    def to_lists(self) -> list[list[int]]:
        """All clauses as one list of lists."""
        out: list[list[int]] = []
        for ch in self.chunks():
            out.extend(ch)
        return out

    @property
    def n_literals(self) -> int:
        return sum(
            (sum(len(c) for c in b.ragged) if b.lits is None else int(b.lits.size)) for b in self.blocks
        )

    def max_var(self) -> int:
        """Largest variable mentioned (0 for an empty set)."""
        top = 0
        for b in self.blocks:
            if b.lits is not None:
                top = max(top, int(np.abs(b.lits).max()))
            else:
                for c in b.ragged:
                    if c:
                        top = max(top, max(abs(v) for v in c))
        return top

    def falsified(self, values: np.ndarray) -> list[tuple[ClauseBlock, np.ndarray]]:
        """Clauses falsified by a total assignment.

        Parameters
        ----------
        values : numpy.ndarray of bool
            ``values[v]`` is the truth value of variable ``v`` (index 0 unused); must
            cover every variable of the blocks inspected.

        Returns
        -------
        list of (ClauseBlock, numpy.ndarray)
            For each block with falsified clauses, the block and the row indices
            (ragged blocks: indices into ``block.ragged``).
        """
        out = []
        for b in self.blocks:
            if b.lits is not None:
                lit_true = values[np.abs(b.lits)] ^ (b.lits < 0)
                bad = np.flatnonzero(~lit_true.any(axis=1))
            else:
                bad = np.array(
                    [i for i, c in enumerate(b.ragged) if not any(values[abs(v)] ^ (v < 0) for v in c)],
                    dtype=np.int64,
                )
            if bad.size:
                out.append((b, bad))
        return out


def cardinality(kind: str, lits, bound: int, **kwargs) -> list[list[int]]:
    """The clauses of ``pysat.card.CardEnc.<kind>(lits, bound, **kwargs)`` (``"atmost"`` or
    ``"atleast"``).

    PySAT's C extension reports Ctrl-C during an encoding as its own error ("Caught keyboard
    interrupt"); it becomes ``KeyboardInterrupt`` here, so a user's Ctrl-C reads the same
    wherever it lands.
    """
    from pysat.card import CardEnc

    try:
        return getattr(CardEnc, kind)(lits, bound=bound, **kwargs).clauses
    except Exception as exc:
        if "keyboard interrupt" in str(exc).lower():
            raise KeyboardInterrupt from None
        raise


class Encoding(Protocol):
    """What every family's CNF encoding offers (one protocol, so one SAT driver,
    :func:`tilesolve.engine.routes.sat_route`, and one DIMACS writer serve every family).

    Attributes
    ----------
    hard : ClauseSet
        The clauses.
    n_vars : int
        Largest variable in use.
    restricted : bool
        True when the formula searches only part of the problem's space (e.g. lifted
        packings): then unsat proves nothing.
    soft : numpy.ndarray or None
        Weighted encodings only: one literal per unit soft clause of weight 1.
    named : dict
        Set by :func:`tilesolve.encodings.registry.encode` only: ``{"name", "version",
        "options"}`` of the registered encoder that built it, which re-derives the same CNF
        from the problem (what an unsat certificate records).
    """

    hard: ClauseSet
    n_vars: int
    restricted: bool

    def projection(self) -> np.ndarray:
        """Variables that determine the tiling (enumeration blocks on them)."""

    def decode(self, model) -> np.ndarray:
        """The tiling of a model (signed DIMACS literals)."""

    def literals(self, tiling) -> list[int]:
        """Unit literals that pin ``tiling`` (check that a tiling satisfies the formula)."""

    def header(self) -> list[str]:
        """DIMACS comment lines that explain the variables."""


_DAPPLED = ("DappledEncoding", "encode_cnf", "encode_wcnf", "build_cpsat", "CpSatDappled")


def __getattr__(name: str):
    # The dappled encoders import pysat; load them on first use (PEP 562).
    if name in _DAPPLED:
        from tilesolve.encodings import dappled

        return getattr(dappled, name)
    raise AttributeError(f"module 'tilesolve.encodings' has no attribute {name!r}")
