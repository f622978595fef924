"""Polyforms on the three regular grids and the questions asked of them (class notes Part II §3).

A *polyform* is a finite edge-connected set of cells of the square grid (polyominoes), the
hexagonal grid (polyhexes) or the triangular grid (polyiamonds). Every cell is an integer point:

- ``omino``: the cell ``(x, y)`` is the unit square with lower-left corner ``(x, y)``;
- ``hex``: axial coordinates ``(q, r)`` of the hexagon's centre (``x = q + r/2``,
  ``y = r*sqrt(3)/2``);
- ``iamond``: three times the centroid of the triangle in the axial coordinates of the
  triangular lattice: the up triangle with corners ``(a, b), (a+1, b), (a, b+1)`` is
  ``(3a+1, 3b+1)``, the down triangle with corners ``(a+1, b), (a, b+1), (a+1, b+1)`` is
  ``(3a+2, 3b+2)``.

In these coordinates every symmetry of the grid that fixes the origin is an integer 2x2 matrix
(:attr:`Grid.matrices`: 8 for squares, 12 for hexagons and triangles) and the grid's translations
are the vectors ``period * Z^2`` (``period`` 1, or 3 for triangles).

Questions (:class:`ShapesProblem`):

``tile``
    Do copies of the shapes (rotated and reflected, unless ``fixed``) tile a finite region (a
    set of cells) exactly, or a torus ``Z^2 / L`` (``lattice``: two period vectors in
    translation units)?
``classify``
    Is the shape a tiler (a periodic tiling found on a torus, isohedral when the torus tiling's
    symmetries move any tile onto any other) or a non-tiler with Heesch number ``H`` (§3: the
    most coronas that can surround it)?
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from tilesolve.errors import InvalidProblem

__all__ = ["Grid", "GRIDS", "grid", "Polyform", "parse_cells", "parse_ascii", "ShapesProblem",
           "QUESTIONS", "MAX_CELLS", "VERDICTS", "ShapesReport", "enclosed"]

#: The most cells a region, torus or shape may have (checked before anything is built).
MAX_CELLS = 20_000


def _rot(k: int, r: np.ndarray) -> list[np.ndarray]:
    mats = [np.eye(2, dtype=np.int64)]
    for _ in range(k - 1):
        mats.append(r @ mats[-1])
    return mats


@dataclass(frozen=True)
class Grid:
    """One of the three regular grids.

    Attributes
    ----------
    name : {"omino", "hex", "iamond"}
    period : int
        Translations are ``period * Z^2``.
    rotation, reflection : tuple
        Generators of the point group, as integer matrices (rows).
    order : int
        Rotations in the point group (4 or 6).
    """

    name: str
    period: int
    rotation: tuple
    reflection: tuple
    order: int

    @functools.cached_property
    def matrices(self) -> tuple[np.ndarray, ...]:
        """The point group: rotations first, then the reflected rotations."""
        rots = _rot(self.order, np.array(self.rotation, dtype=np.int64))
        f = np.array(self.reflection, dtype=np.int64)
        return tuple(rots + [m @ f for m in rots])

    def is_cell(self, c) -> bool:
        """Whether the integer point ``c`` names a cell."""
        if self.name != "iamond":
            return True
        return c[0] % 3 == c[1] % 3 and c[0] % 3 != 0

    def vertices(self, c) -> list[tuple[int, int]]:
        """The cell's corners, in order around it, as integer points (scaled: x2 for squares'
        centre frame, x3 in the axial frame for hexagons and triangles)."""
        x, y = int(c[0]), int(c[1])
        if self.name == "omino":
            return [(x, y), (x + 1, y), (x + 1, y + 1), (x, y + 1)]
        if self.name == "hex":
            return [(3 * x + dx, 3 * y + dy) for dx, dy in ((2, -1), (1, 1), (-1, 2), (-2, 1), (-1, -1), (1, -2))]
        a, b = x // 3, y // 3
        if x % 3 == 1:
            return [(3 * a, 3 * b), (3 * a + 3, 3 * b), (3 * a, 3 * b + 3)]
        return [(3 * a + 3, 3 * b), (3 * a + 3, 3 * b + 3), (3 * a, 3 * b + 3)]

    def to_xy(self, points) -> np.ndarray:
        """Cartesian coordinates of vertex points (:meth:`vertices`) in units of the cell edge."""
        p = np.asarray(points, dtype=float).reshape(-1, 2)
        if self.name == "omino":
            return p
        s = 3.0 if self.name == "iamond" else np.sqrt(3.0)  # hexagon centres are sqrt(3) edges apart
        return np.stack([(p[:, 0] + p[:, 1] / 2) / s, p[:, 1] * np.sqrt(3) / 2 / s], axis=1)

    def centre(self, c) -> np.ndarray:
        """The cell's centroid in Cartesian coordinates."""
        return self.to_xy(self.vertices(c)).mean(axis=0)

    @functools.cached_property
    def _offsets(self) -> dict:
        """Edge- and vertex-neighbour offsets per cell type (computed from :meth:`vertices`)."""
        out = {}
        reach = 3 * self.period + 3
        types = [(0, 0)] if self.name != "iamond" else [(1, 1), (2, 2)]
        for t in types:
            vs = set(self.vertices(t))
            edge, vertex = [], []
            for dx in range(-reach, reach + 1):
                for dy in range(-reach, reach + 1):
                    c = (t[0] + dx, t[1] + dy)
                    if (dx, dy) == (0, 0) or not self.is_cell(c):
                        continue
                    shared = len(vs & set(self.vertices(c)))
                    if shared >= 2:
                        edge.append((dx, dy))
                    if shared >= 1:
                        vertex.append((dx, dy))
            out[t] = (tuple(edge), tuple(vertex))
        return out

    def cell_type(self, c) -> tuple[int, int]:
        """The cell's type: ``(0, 0)``, or for triangles ``(1, 1)`` up and ``(2, 2)`` down."""
        return (0, 0) if self.name != "iamond" else (c[0] % 3, c[1] % 3)

    def neighbours(self, c) -> list[tuple[int, int]]:
        """Cells sharing an edge with ``c``."""
        return [(c[0] + dx, c[1] + dy) for dx, dy in self._offsets[self.cell_type(c)][0]]

    def touching(self, c) -> list[tuple[int, int]]:
        """Cells sharing at least a corner with ``c``."""
        return [(c[0] + dx, c[1] + dy) for dx, dy in self._offsets[self.cell_type(c)][1]]

    def normalise(self, cells) -> tuple[tuple[int, int], ...]:
        """The cells translated by a grid translation so that the least cell lies in the
        period cell at the origin; sorted."""
        cs = sorted((int(x), int(y)) for x, y in cells)
        p = self.period
        x0, y0 = cs[0][0] // p * p, cs[0][1] // p * p
        return tuple((x - x0, y - y0) for x, y in cs)

    def images(self, cells, reflections: bool = True) -> list[tuple[tuple[int, int], ...]]:
        """The distinct normalised images of a cell set under the point group (rotations only
        without ``reflections``)."""
        pts = np.asarray(cells, dtype=np.int64)
        mats = self.matrices if reflections else self.matrices[: self.order]
        seen = {}
        for m in mats:
            img = self.normalise((pts @ m.T).tolist())
            seen.setdefault(img, None)
        return list(seen)

    def canonical(self, cells) -> tuple[tuple[int, int], ...]:
        """The least image under the point group: equal for congruent polyforms (free form)."""
        return min(self.images(cells))


GRIDS = {
    "omino": Grid("omino", 1, ((0, -1), (1, 0)), ((0, 1), (1, 0)), 4),
    "hex": Grid("hex", 1, ((0, -1), (1, 1)), ((0, 1), (1, 0)), 6),
    "iamond": Grid("iamond", 3, ((0, -1), (1, 1)), ((0, 1), (1, 0)), 6),
}


def grid(name: str) -> Grid:
    """The grid named ``name`` (``omino``, ``hex``, ``iamond``)."""
    try:
        return GRIDS[name]
    except KeyError:
        raise InvalidProblem(f"unknown grid {name!r}; choose one of {', '.join(GRIDS)}") from None


@dataclass(frozen=True)
class Polyform:
    """A polyform: its grid and its cells (normalised, sorted).

    Examples
    --------
    >>> Polyform("omino", ((0, 0), (1, 0), (0, 1))).size
    3
    """

    grid: str
    cells: tuple[tuple[int, int], ...]

    def __post_init__(self) -> None:
        g = grid(self.grid)
        try:
            cells = [(int(x), int(y)) for x, y in self.cells]
        except (TypeError, ValueError):
            raise InvalidProblem(f"a polyform's cells are pairs of integers, got {self.cells!r}") from None
        if not cells:
            raise InvalidProblem("a polyform needs at least one cell")
        if len(cells) > MAX_CELLS:
            raise InvalidProblem(f"a polyform of {len(cells)} cells is too large (at most {MAX_CELLS})")
        if len(set(cells)) != len(cells):
            raise InvalidProblem("a polyform's cells must be distinct")
        bad = [c for c in cells if not g.is_cell(c)]
        if bad:
            raise InvalidProblem(f"{bad[0]} is not a cell of the triangle grid (x = y = 1 or 2 mod 3)")
        cs = set(cells)
        seen, todo = {cells[0]}, [cells[0]]
        while todo:
            c = todo.pop()
            for n in g.neighbours(c):
                if n in cs and n not in seen:
                    seen.add(n)
                    todo.append(n)
        if len(seen) != len(cs):
            raise InvalidProblem("a polyform's cells must be edge-connected")
        object.__setattr__(self, "cells", g.normalise(cells))

    @property
    def size(self) -> int:
        return len(self.cells)

    @property
    def geometry(self) -> Grid:
        return GRIDS[self.grid]

    def holes(self) -> list[tuple[tuple[int, int], ...]]:
        """The holes: edge-connected sets of cells outside the polyform that do not reach the
        outside of its bounding box."""
        return enclosed(self.geometry, set(self.cells))

    def describe(self) -> str:
        word = {"omino": "polyomino", "hex": "polyhex", "iamond": "polyiamond"}[self.grid]
        return f"{word} of {self.size} cells"

    def ascii(self) -> str:
        """The polyform as ASCII art (``#`` cells, ``.`` others), top row first; squares and
        hexagons only (rows of a hex grid are shifted half a cell per row)."""
        xs = [c[0] for c in self.cells]
        ys = [c[1] for c in self.cells]
        cs = set(self.cells)
        rows = []
        for y in range(max(ys), min(ys) - 1, -1):
            rows.append("".join("#" if (x, y) in cs else "." for x in range(min(xs), max(xs) + 1)))
        return "\n".join(rows)


def enclosed(g: Grid, cells: set) -> list[tuple[tuple[int, int], ...]]:
    """Edge-connected components of the cells outside ``cells`` that cannot reach the border of
    a box around them (the holes of a patch)."""
    xs = [c[0] for c in cells]
    ys = [c[1] for c in cells]
    m = 2 * g.period + 2
    p = g.period
    # whole translation cells, so that the cells of the box around the patch are edge-connected
    lo_x, hi_x = (min(xs) - m) // p * p, (max(xs) + m) // p * p + p - 1
    lo_y, hi_y = (min(ys) - m) // p * p, (max(ys) + m) // p * p + p - 1

    def inside(c):
        return lo_x <= c[0] <= hi_x and lo_y <= c[1] <= hi_y

    def flood(c) -> set:
        """The cells outside ``cells`` and inside the box edge-connected to ``c``."""
        comp, todo = {c}, [c]
        while todo:
            d = todo.pop()
            for n in g.neighbours(d):
                if inside(n) and n not in cells and n not in comp:
                    comp.add(n)
                    todo.append(n)
        return comp

    outside = flood((lo_x + p // 2, lo_y + p // 2))
    holes, done = [], set()
    for x in range(lo_x, hi_x + 1):
        for y in range(lo_y, hi_y + 1):
            c = (x, y)
            if not g.is_cell(c) or c in cells or c in outside or c in done:
                continue
            comp = flood(c)
            done |= comp
            holes.append(tuple(sorted(comp)))
    return holes


def parse_cells(text: str, grid_name: str) -> Polyform:
    """A polyform from ``"x,y x,y ..."`` (or ``;``-separated) cell coordinates.

    Examples
    --------
    >>> parse_cells("0,0 1,0 2,0", "omino").cells
    ((0, 0), (1, 0), (2, 0))
    """
    cells = []
    for item in text.replace(";", " ").split():
        parts = item.split(",")
        try:
            x, y = (int(v) for v in parts)
        except ValueError:
            raise InvalidProblem(f"a cell is 'x,y' with integers, got {item!r}") from None
        cells.append((x, y))
    return Polyform(grid_name, tuple(cells))


def parse_ascii(text: str, grid_name: str) -> Polyform:
    """A polyform from ASCII art: any of ``#``, ``X``, ``x``, ``*``, ``o`` is a cell, ``.`` or a
    space is not; the first line is the top row. Squares: cell ``(col, -row)``. Hexagons: rows
    of the axial grid (cell ``(col, -row)``, each row drawn half a cell right of the one
    below). Triangles: column ``col`` of row ``row`` is an up triangle when ``col + row`` is
    even (the top-left triangle points up).

    Examples
    --------
    >>> parse_ascii("##\\n#.", "omino").cells
    ((0, 0), (0, 1), (1, 1))
    """
    cells = []
    for row, line in enumerate(text.splitlines()):
        for col, ch in enumerate(line.rstrip()):
            if ch in "#Xx*o":
                if grid_name == "iamond":
                    a, b = (col + row) // 2, -row
                    up = (col + row) % 2 == 0
                    cells.append((3 * a + 1, 3 * b + 1) if up else (3 * a + 2, 3 * b + 2))
                else:
                    cells.append((col, -row))
            elif ch not in ". ":
                raise InvalidProblem(f"ASCII art marks a cell with one of '#', 'X', 'x', '*', 'o' and no cell with "
                                     f"'.' or a space, got {ch!r} in row {row + 1}")
    return Polyform(grid_name, tuple(cells))


#: The questions a ShapesProblem asks.
QUESTIONS = ("tile", "classify")


@dataclass(frozen=True)
class ShapesProblem:
    """A question about polyforms.

    Parameters
    ----------
    question : {"tile", "classify"}
    shapes : tuple of Polyform
        One grid for all; ``classify`` takes one shape.
    region : tuple of (x, y), optional
        ``tile`` on a finite region: the cells to cover exactly.
    lattice : ((a, b), (c, d)), optional
        ``tile`` on the torus ``Z^2 / L``: the two period vectors, in translation units
        (multiplied by the grid's ``period``).
    reflections : bool
        Whether reflected copies are allowed (rotations always are).
    max_level : int
        ``classify``: the most coronas tried (a shape still surrounded at this level is
        ``inconclusive``), and ``max_copies`` the most copies per period tried on tori.
    holes : bool
        ``classify``: Heesch number with holes allowed in the outer corona (``H_h``), else ``H_c``.
    """

    question: str
    shapes: tuple[Polyform, ...]
    region: tuple[tuple[int, int], ...] | None = None
    lattice: tuple[tuple[int, int], tuple[int, int]] | None = None
    reflections: bool = True
    max_level: int = 3
    max_copies: int = 2
    holes: bool = False

    def __post_init__(self) -> None:
        if self.question not in QUESTIONS:
            raise InvalidProblem(f"unknown question {self.question!r}; choose one of {', '.join(QUESTIONS)}")
        if not self.shapes or not all(isinstance(s, Polyform) for s in self.shapes):
            raise InvalidProblem("a shapes problem needs at least one Polyform")
        if len({s.grid for s in self.shapes}) > 1:
            raise InvalidProblem("all shapes must lie on one grid")
        if self.question == "classify":
            if len(self.shapes) != 1:
                raise InvalidProblem("classify takes exactly one shape")
            if not 1 <= self.max_level <= 8:
                raise InvalidProblem(f"max level must be in 1..8, got {self.max_level}")
            if not 1 <= self.max_copies <= 12:
                raise InvalidProblem(f"max copies must be in 1..12, got {self.max_copies}")
            return
        if (self.region is None) == (self.lattice is None):
            raise InvalidProblem("a tiling question needs a region or a torus lattice, not both")
        g = self.geometry
        if self.region is not None:
            cells = tuple(sorted({(int(x), int(y)) for x, y in self.region}))
            if not cells:
                raise InvalidProblem("the region is empty")
            if len(cells) > MAX_CELLS:
                raise InvalidProblem(f"a region of {len(cells)} cells is too large (at most {MAX_CELLS})")
            bad = [c for c in cells if not g.is_cell(c)]
            if bad:
                raise InvalidProblem(f"region cell {bad[0]} is not a cell of the triangle grid")
            object.__setattr__(self, "region", cells)
        else:
            (a, b), (c, d) = ((int(v) for v in row) for row in self.lattice)
            det = abs(a * d - b * c)
            if det == 0:
                raise InvalidProblem("the torus's period vectors are parallel")
            n = det * (2 if g.name == "iamond" else 1)
            if n > MAX_CELLS:
                raise InvalidProblem(f"a torus of {n} cells is too large (at most {MAX_CELLS})")
            object.__setattr__(self, "lattice", ((a, b), (c, d)))

    @property
    def geometry(self) -> Grid:
        return self.shapes[0].geometry

    def n_cells(self) -> int:
        """Cells of the region or torus (``tile``)."""
        if self.region is not None:
            return len(self.region)
        (a, b), (c, d) = self.lattice
        return abs(a * d - b * c) * (2 if self.geometry.name == "iamond" else 1)

    def describe(self) -> str:
        shapes = ", ".join(s.describe() for s in self.shapes[:3]) + (" ..." if len(self.shapes) > 3 else "")
        if self.question == "classify":
            return f"classify the {shapes} (Heesch number up to {self.max_level} coronas, " \
                   f"tori with up to {self.max_copies} copies)"
        where = f"region of {len(self.region)} cells" if self.region is not None else \
            f"torus with periods {list(self.lattice[0])}, {list(self.lattice[1])} ({self.n_cells()} cells)"
        return f"tile a {where} with {shapes}"


#: Verdicts of a classification.
VERDICTS = ("isohedral", "periodic", "non-tiler", "inconclusive")


@dataclass(frozen=True)
class ShapesReport:
    """A polyform's classification with its certificates.

    Attributes
    ----------
    verdict : {"isohedral", "periodic", "non-tiler", "inconclusive"}
        ``isohedral``: a torus tiling whose symmetries move any tile onto any other;
        ``periodic``: a torus tiling with ``copies`` tiles per period (``copies``-isohedral at
        most), none isohedral found; ``non-tiler``: ``heesch`` coronas are possible (``patch``)
        and ``heesch + 1`` are refuted (``refutation``, a checked DRAT proof); ``inconclusive``:
        no torus tiling with up to ``max_copies`` copies and ``heesch`` coronas possible.
    heesch : int or None
        Coronas shown possible (``H_c`` without holes, ``H_h`` with ``holes``).
    copies : int or None
        Tiles per period of the torus tiling.
    lattice : ((a, b), (c, d)) or None
        The torus's periods (translation units).
    tiling : numpy.ndarray or None
        The torus tiling: rows ``(piece, 0, x, y)`` per cell, pieces as placed in the plane.
    patch : numpy.ndarray or None
        The corona patch: rows ``(piece, level, x, y)``; piece 0 is the shape.
    refutation : dict
        Stats of the refuted level (``cnf_sha256``, ``encoding``, proof figures).
    holes : bool
        Whether the outer corona may have holes.
    """

    verdict: str
    heesch: int | None = None
    copies: int | None = None
    lattice: tuple | None = None
    tiling: np.ndarray | None = None
    patch: np.ndarray | None = None
    refutation: dict | None = None
    holes: bool = False
    title = "polyform classification"

    @property
    def status(self):
        from tilesolve.model.solution import Status

        return Status.UNKNOWN if self.verdict == "inconclusive" else Status.SAT

    @property
    def conclusion(self) -> str:
        h = "H_h" if self.holes else "H_c"
        if self.verdict == "isohedral":
            return f"tiles the plane isohedrally ({self.copies} cop{'y' if self.copies == 1 else 'ies'} per period)"
        if self.verdict == "periodic":
            return (f"tiles the plane periodically with {self.copies} copies per period (at most "
                    f"{self.copies}-isohedral; no isohedral tiling found)")
        if self.verdict == "non-tiler":
            return f"does not tile the plane: Heesch number {h} = {self.heesch}"
        return f"inconclusive: {self.heesch} corona(s) possible, no periodic tiling found"
