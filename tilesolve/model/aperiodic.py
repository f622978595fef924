"""Aperiodicity checks of Wang tile sets: the problem, its lattices and its certificates.

Class notes Part II §8.2 (seed 002): a set of Wang tiles either tiles no plane, tiles the
plane periodically, or is *aperiodic* (tiles the plane, never periodically). Wang's procedure
separates the first two cases: an ``n x n`` square that cannot be tiled proves, by the
Extension Theorem (Grünbaum and Shephard §3.8, quoted in §8.2), that the set tiles no plane;
a tiled torus is a translational unit of a periodic tiling. An aperiodic set is one that tiles
every square and no torus, which no finite search can prove: an :class:`AperiodicReport` says
exactly which squares and periods were checked, each with its certificate (a witness tiling, a
checked refutation, or "undecided" with why).

Lattices
--------
Every lattice of periods of a periodic tiling of ``Z^2`` has a basis in Hermite normal form
``(q, s), (0, p)`` (column shift, row shift): a tiling with these periods is a tiling of the
*sheared torus* :class:`Lattice` ``(p, q, s)``: ``p`` rows, ``q`` columns, the S legs of the
last row meet the N legs of the first row in the same column, and the E leg of cell
``(r, q - 1)`` meets the W leg of cell ``((r + s) mod p, 0)``. ``s = 0`` is the plain torus.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, ClassVar, Mapping, NamedTuple

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.model.board import E, N, S, W, Board, WangTileSet
from tilesolve.model.solution import Status

__all__ = ["Lattice", "AperiodicProblem", "Certificate", "AperiodicReport", "square_board", "rectangle_name",
           "leg_colours", "MAX_CLAUSES", "MAX_LATTICES", "STATUSES", "VERDICTS", "estimate_refusal"]

#: Largest CNF (clauses, estimated before building) a board may need: about 5 GB of clauses.
MAX_CLAUSES = 50_000_000
#: Most lattices one check may sweep.
MAX_LATTICES = 200_000


#: What a certificate can say about its board.
STATUSES = ("tiles", "refuted", "undecided")

#: A report's verdict (:attr:`AperiodicReport.verdict`): what its certificates establish, in one
#: word. The literature's words where a finite check can reach them (``periodic``, ``finite``);
#: a check never says ``aperiodic``.
VERDICTS = {
    "periodic": "a torus is tiled: the set tiles the plane periodically, so it is not aperiodic",
    "finite": "a square cannot be tiled: the set tiles no plane (Extension Theorem)",
    "open": "every board asked was decided, and none is a tiled torus or an untileable square: "
            "the check neither shows nor excludes aperiodicity",
    "undecided": "a board asked was left undecided (a time limit), and no decided one settles the question",
}


class Lattice(NamedTuple):
    """The sheared torus of ``rows`` x ``cols`` cells whose horizontal wrap shifts by ``shear``
    rows (module docstring). A tiling of it is periodic with periods ``(cols, shear)`` and
    ``(0, rows)`` (column offset, row offset)."""

    rows: int
    cols: int
    shear: int = 0

    def name(self) -> str:
        s = f"torus {self.rows}x{self.cols}"
        return s + (f" shear {self.shear}" if self.shear else "")

    def board(self) -> Board:
        """The board (every leg joined: no boundary). Cell ``r * cols + c`` is ``(r, c)``."""
        p, q, s = int(self.rows), int(self.cols), int(self.shear)
        if s == 0:
            return Board.torus(q, p)
        r, c = np.divmod(np.arange(p * q, dtype=np.int64), q)
        east = np.where(c < q - 1, r * q + c + 1, ((r + s) % p) * q)
        south = ((r + 1) % p) * q + c
        a = np.arange(p * q, dtype=np.int64)
        edges = np.concatenate([np.stack([a, np.full_like(a, E), east, np.full_like(a, W)], axis=1),
                                np.stack([a, np.full_like(a, S), south, np.full_like(a, N)], axis=1)])
        return Board.from_edges(np.stack([r, c], axis=1), edges, kind="sheared torus")


def square_board(rows: int, cols: int | None = None) -> Board:
    """The free rectangle of ``rows`` x ``cols`` cells (cell ``r * cols + c`` is ``(r, c)``)."""
    return Board.rect(int(rows if cols is None else cols), int(rows))


def leg_colours(tileset: WangTileSet, tiling) -> np.ndarray:
    """``(rows * cols, 4)`` leg colours (N, E, S, W) of a grid of tile indices, row-major:
    the form :func:`tilesolve.verify.board.board_violations` checks."""
    t = np.asarray(tiling, dtype=np.int64)
    return tileset.tiles[t.ravel()]


@dataclass(frozen=True, eq=False)
class AperiodicProblem:
    """Which squares and periods of a Wang tile set to check (class notes Part II §8.2).

    Parameters
    ----------
    tileset : WangTileSet
        The tiles (in the order the user gave them; tile indices in certificates refer to
        ``tileset.tiles``).
    max_square : int
        Find the largest ``n <= max_square`` with a tiled ``n x n`` square (0: no squares).
    max_period : int
        Check every torus ``p x q`` with ``1 <= p, q <= max_period`` (0: no periods).
    shears : bool
        Also every sheared torus ``(p, q, s)``, ``0 < s < p`` (every lattice of periods with
        both sides at most ``max_period``).
    name : str, optional
        The set's name (a built-in set's).
    info : Mapping, optional
        What the literature says about a built-in set (``"literature"``: a sentence); copied to
        the report, never used as a result.

    Examples
    --------
    >>> ws = WangTileSet([[0, 0, 0, 0]], 1)
    >>> p = AperiodicProblem(ws, 3, 2, shears=True)
    >>> [l.name() for l in p.lattices()]
    ['torus 1x1', 'torus 1x2', 'torus 2x1', 'torus 2x1 shear 1', 'torus 2x2', 'torus 2x2 shear 1']
    """

    tileset: WangTileSet
    max_square: int
    max_period: int
    shears: bool = False
    name: str | None = None
    info: Mapping[str, Any] | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.tileset, WangTileSet):
            raise InvalidProblem("tileset must be a WangTileSet")
        if self.tileset.is_brick:
            raise InvalidProblem("aperiodicity checks take an explicit Wang tile set, not the brick tiles")
        for what in ("max_square", "max_period"):
            v = getattr(self, what)
            if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < 0:
                raise InvalidProblem(f"{what.replace('_', ' ')} must be a non-negative integer, got {v!r}")
            object.__setattr__(self, what, int(v))
        refusal = estimate_refusal(self.max_square, self.max_period, len(self.tileset), bool(self.shears))
        if refusal:
            raise InvalidProblem(refusal)
        if self.max_square == 0 and self.max_period == 0:
            raise InvalidProblem("nothing to check: give max square or max period (or both) above 0")
        object.__setattr__(self, "shears", bool(self.shears))
        object.__setattr__(self, "info", dict(self.info or {}))

    def lattices(self) -> list[Lattice]:
        """Every lattice to check, by rows, then columns, then shear."""
        n = self.max_period
        return [Lattice(p, q, s) for p in range(1, n + 1) for q in range(1, n + 1)
                for s in (range(p) if self.shears else (0,))]

    def describe(self) -> str:
        what = f"{self.name} ({len(self.tileset)} Wang tiles)" if self.name else f"{len(self.tileset)} Wang tiles"
        parts = []
        if self.max_square:
            parts.append(f"squares up to {self.max_square}x{self.max_square}")
        if self.max_period:
            parts.append(f"{'lattice' if self.shears else 'torus'} periods up to {self.max_period}")
        return f"aperiodicity check of {what}, {self.tileset.n_colors} colours: {', '.join(parts)}"


def clauses_per_cell(m: int) -> int:
    """Clauses a cell costs in the tile-selection CNF of ``m`` tiles (at least one, at most one,
    and a support clause per tile and leg)."""
    return 1 + m * (m - 1) // 2 + 4 * m


def estimate_refusal(max_square: int, max_period: int, m: int, shears: bool) -> str | None:
    """The one-line refusal of bounds too large to check, with what they would cost (else None)."""
    per = clauses_per_cell(m)
    if max_square * max_square * per > MAX_CLAUSES:
        return (f"max square {max_square} is too large: the {max_square}x{max_square} square needs about "
                f"{max_square * max_square * per:,} clauses ({m} tiles); at most {MAX_CLAUSES:,} are built")
    boards = max_period * max_period * ((max_period + 1) // 2 if shears else 1)
    if boards > MAX_LATTICES or max_period * max_period * per > MAX_CLAUSES:
        return (f"max period {max_period} is too large: {boards:,} {'lattices' if shears else 'tori'} of up to "
                f"{max_period * max_period:,} cells (about {max_period * max_period * per:,} clauses each); at most "
                f"{MAX_LATTICES:,} lattices of {MAX_CLAUSES:,} clauses")
    return None


@dataclass(frozen=True)
class Certificate:
    """What was established about one board (a square or a :class:`Lattice`).

    Attributes
    ----------
    board : str
        ``"square 12x12"``, ``"rectangle 8x26"``, ``"torus 3x4"``, ``"torus 3x4 shear 1"``.
    status : str
        ``"tiles"`` (``tiling`` is a witness, verified independently), ``"refuted"`` (no tiling:
        ``evidence`` holds the checked proof's digests) or ``"undecided"`` (``evidence["why"]``).
    tiling : numpy.ndarray or None
        ``(rows, cols)`` tile indices into the problem's ``tileset.tiles`` (witnesses only).
    method : str
        The route that decided it (``"sat"``, ``"transducer"``, ``"cache"``...).
    evidence : dict
        Refutations by SAT: ``cnf_sha256``, ``drat_sha256``, ``proof_lemmas``,
        ``proof_checked_lemmas``, ``checker``, ``reason`` (and ``proof_name`` with a proof
        directory). Other routes put their own keys (e.g. a transducer's power).
    time_s : float
    """

    board: str
    status: str
    tiling: np.ndarray | None = None
    method: str = "sat"
    evidence: Mapping[str, Any] = field(default_factory=dict)
    time_s: float = 0.0

    def __post_init__(self) -> None:
        if self.status not in STATUSES:
            raise InvalidProblem(f"certificate status must be one of {STATUSES}, got {self.status!r}")
        if (self.tiling is not None) != (self.status == "tiles"):
            raise InvalidProblem(f"{self.board}: a '{self.status}' certificate "
                                 f"{'needs' if self.status == 'tiles' else 'holds no'} tiling")

    @property
    def shape(self) -> tuple[int, int, int]:
        """``(rows, cols, shear)`` parsed from :attr:`board`."""
        return parse_board_name(self.board)


def rectangle_name(rows: int, cols: int) -> str:
    """The board name of the free ``rows`` x ``cols`` rectangle: ``"square NxN"`` when its sides
    are equal, else ``"rectangle RxC"``.

    >>> rectangle_name(5, 5), rectangle_name(8, 26)
    ('square 5x5', 'rectangle 8x26')
    """
    return f"{'square' if int(rows) == int(cols) else 'rectangle'} {int(rows)}x{int(cols)}"


def parse_board_name(name: str) -> tuple[int, int, int]:
    """``(rows, cols, shear)`` of ``"square RxC"`` / ``"rectangle RxC"`` / ``"torus RxC [shear S]"``
    (shear -1: a free rectangle; reports written before :func:`rectangle_name` called every
    rectangle a square, so ``"square RxC"`` is read with any sides)."""
    parts = str(name).split()
    try:
        rows, cols = (int(v) for v in parts[1].split("x"))
        if parts[0] in ("square", "rectangle") and len(parts) == 2:
            return rows, cols, -1
        if parts[0] == "torus" and len(parts) == 2:
            return rows, cols, 0
        if parts[0] == "torus" and len(parts) == 4 and parts[2] == "shear":
            return rows, cols, int(parts[3])
    except (IndexError, ValueError):
        pass
    raise InvalidProblem(f"not a board name: {name!r} (expected 'square RxC', 'rectangle RxC' or 'torus RxC "
                         "[shear S]')")


def board_of(name: str) -> Board:
    """The board a certificate's name stands for."""
    rows, cols, shear = parse_board_name(name)
    return square_board(rows, cols) if shear < 0 else Lattice(rows, cols, shear).board()


@dataclass(frozen=True)
class AperiodicReport:
    """Every certificate of one check and what they prove, in words.

    Attributes
    ----------
    squares : tuple of Certificate
        Squares decided (the largest tiled one and the refuted one above it, when any).
    periods : tuple of Certificate
        One per lattice checked.
    largest_square : int or None
        The largest ``n`` with a witness (``None`` when squares were not asked).
    conclusion : str
        What the certificates prove, and only that.
    literature : str or None
        What the literature says about a built-in set (quoted, not checked here).
    stated : str or None
        The verdict a report file states (``None``: not stated): a claim, which the family's
        verifier holds to :attr:`verdict`.
    """

    #: What the answer is, in the words :func:`tilesolve.family.verify_document` and the studio use.
    title: ClassVar[str] = "aperiodicity report"

    squares: tuple[Certificate, ...] = ()
    periods: tuple[Certificate, ...] = ()
    largest_square: int | None = None
    conclusion: str = ""
    literature: str | None = None
    stated: str | None = None

    @property
    def undecided(self) -> list[Certificate]:
        return [c for c in self.squares + self.periods if c.status == "undecided"]

    @property
    def complete(self) -> bool:
        """True when every requested check was decided."""
        return not self.undecided

    @property
    def verdict(self) -> str:
        """What the certificates establish, one of :data:`VERDICTS`: ``periodic`` (a tiled torus),
        ``finite`` (a refuted square), else ``undecided`` when a board is undecided or none was
        decided, else ``open``.

        >>> AperiodicReport().verdict, AperiodicReport(periods=(Certificate("torus 1x1", "refuted"),)).verdict
        ('undecided', 'open')
        """
        if any(c.status == "tiles" for c in self.periods):
            return "periodic"
        if any(c.status == "refuted" for c in self.squares):
            return "finite"
        return "undecided" if self.undecided or not (self.squares or self.periods) else "open"

    @property
    def status(self) -> Status:
        """The status of the Solution that carries this report: ``sat`` when the verdict is
        decided, ``unknown`` when it is ``undecided`` (the CLI's exit codes 0 and 3)."""
        return Status.UNKNOWN if self.verdict == "undecided" else Status.SAT
