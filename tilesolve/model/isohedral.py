"""Isohedral tilings for design (class notes Part II §7): the 93 types IH1..IH93, their templates,
edge shapes, the problem and its answer.

The types' templates come from Kaplan's tables (tactile-js ``src/tiling_data.inc``, as shipped by
the PyPI package ``tactile`` 0.1.0, BSD-3-Clause; §7.4.1 of the notes): for each type, the tiling
vertices, the translation vectors and the aspects' rigid motions as *linear* functions of the
type's parameters (§7.4.1: "the coordinates of the tiling vertices are all linear functions of the
parameters, as are the entries in the hop transformation matrices"), the edge classes with their
constraint J, U, S or I (§7.3.1), and a colouring (§7.2, §7.4.1). :func:`isohedral_type` reads them
here; nothing else in tilesolve touches the package (its fill and colour code are not used). The
package's 81 records were compared field by field with tactile-js's ``src/tiling_data.inc`` at
commit fd58ec372a4398e3dfc22663d120da186790834e when the dependency was chosen: identical.

Twelve types (IH19, 35, 48, 60, 63, 65, 70, 75, 80, 87, 89, 92) have no table: they "can only be
represented with marked tiles" (Grünbaum and Shephard, Fig. 6.2.5; class notes Part II §7.1), their
edges are all straight, and their tiles' outlines form the tiling of an unmarked all-I type of the
same topological type, its *outline twin* (:data:`MARKED`), whose tables give the outlines. A marked
type's tiles carry a *marking* (:class:`MarkedType`), and its symmetry group is smaller than the
twin's. The derivation is the project's own, from the definitions (Grünbaum and Shephard §6.2, the
notes §7.1): the outline twin is the all-I type of the topological type (an I edge stays I in a
larger group; each topological type has one all-I type but 4^4, with the rectangle IH72 and the
square IH76); every edge of the twin lies on a mirror of its tiling, so the reflections in the
tiles' edge lines generate a group R that maps the tiling to itself and acts on its tiles simply
transitively up to the stabilizer R_P of the prototile P. A group G with R <= G <= Sym(twin) is
tile-transitive and its edges stay on mirrors (straight, so no edge can be deformed): G = R.H with
H = G_P, a subgroup of the prototile's symmetries that contains R_P. The types other than the
twin's own are the marked ones: for 3^6 (hexagon, R_P = D3 through vertices) one, p3m1; for
3.6.3.6 (rhombus, R_P = the mirror in the short diagonal) one, p3m1; for 4.8^2 (IH82's triangle,
R_P trivial) one, p4m; for 6^3 (the equilateral triangle, R_P trivial) H = 1, C3, D1; for 4^4
(R_P trivial) the subgroups of D4 but D2 through edge midpoints (IH72) and D4 (IH76): 1, C2, D1
through edge midpoints, D1 along a diagonal, C4, D2 along the diagonals; 12 in all, G&S's count.
Which IH number is which H (:data:`MARKINGS`) is confirmed by Grünbaum and Shephard's Table 5.2.3
(the 51 pattern types: for each, the tiling's symmetry group S(P), the group S(P|M) the tiling
induces on a tile, and its IH types), as transcribed in github.com/usnistgov/escherized-colloids,
``design/table.py`` at commit 68befdc17581f65a112da28f01fbc2c5a93d6c72 (:data:`GS_TABLE_5_2_3`,
its rows for the twelve): each marked type's (group, H) is the row that lists its number, and
within a topological type no two marked types share a row, so the table settles every number. In
4^4 the two d1 rows differ by group: pmm (IH65, the mirror through edge midpoints) and p4m (IH70,
the mirror along a diagonal, which forces the square and quarter-turns at its vertices). The class
notes give no such table (their Figures 16-17 are missing from the text) and tactile-js has no
record for the twelve; the transcription is a third party's, not G&S's page. Three 4^4 types (C4
and the diagonal mirrors: IH63, 70, 75) force the square: they take no parameter; the other three
keep IH72's rectangle.

A marked tile carries the motif of :func:`tilesolve.constructive.isohedral.motif`: H's images of an asymmetric flag, so the marked
prototile's symmetry group is exactly H; tile X = g(P) for g in G carries g(motif), and a tile's
neighbour across an edge is its mirror image in that edge, motif included.

Coordinates: the tables' own (y up; a tiling edge is about one unit long). An edge shape lives in
its edge's unit frame: a path from (0, 0) to (1, 0) (§7.4.2), a polyline or a chain of cubic Bézier
curves, drawn as :data:`BEZIER_CHORDS` chords per cubic.

>>> t = isohedral_type(41)
>>> t.name, t.n_params, t.edge_kinds, t.n_aspects
('IH41', 2, ('J', 'J'), 1)
>>> isohedral_type(19).outline_of, isohedral_type(19).marking.group
(20, 'p3m1')
>>> EdgeShape.parse("bezier:0.3,0.2/0.7,-0.2").text()
'bezier:0.3,0.2/0.7,-0.2'
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np

from tilesolve.errors import InvalidProblem

__all__ = [
    "KINDS", "GS_TABLE_5_2_3", "MARKED", "MARKINGS", "MarkedType", "FLAG", "TYPES", "BEZIER_CHORDS", "MAX_EDGE_POINTS", "MAX_TILES", "MAX_OUTLINE", "IsohedralType", "isohedral_type",
    "parse_type", "EdgeShape", "STRAIGHT", "IsohedralProblem", "IsohedralTiling",
]

#: The four edge constraints (§7.3.1): J free, U mirror-symmetric, S symmetric by a half-turn, I straight.
KINDS = ("J", "U", "S", "I")


@dataclass(frozen=True)
class MarkedType:
    """A marked type's marking (see the module docstring).

    Attributes
    ----------
    twin : int
        The outline twin, whose tables give the tiles' outlines.
    group : str
        The tiling's symmetry group (a wallpaper group).
    stabilizer : tuple of (int, bool)
        H, the symmetries of the prototile kept by the marking, each as a map of its tiling
        vertices: ``(k, False)`` takes vertex ``i`` to ``k + i``, ``(k, True)`` to ``k - i`` (mod n).
    aspects : int
        Tiles per translational unit of the marked tiling: the point group's order over ``|H|``.
    square : bool
        The marking forces IH72's rectangle to be the square (no parameter).
    """

    twin: int
    group: str
    stabilizer: tuple[tuple[int, bool], ...]
    aspects: int
    square: bool = False


#: Grünbaum and Shephard's Table 5.2.3, the rows of the twelve marked types: IH number -> (symmetry
#: group S(P), induced group S(P|M) of the tile). Transcribed from github.com/usnistgov/escherized-colloids
#: ``design/table.py`` at commit 68befdc17581f65a112da28f01fbc2c5a93d6c72 (its rows PP14, 15, 18,
#: 24, 27, 28, 29, 34, 37, 39, 40, 47). :data:`MARKINGS` agrees with it (a test checks).
GS_TABLE_5_2_3 = {
    19: ("p3m1", "d3"), 35: ("p3m1", "d1"), 48: ("pmm", "c1"), 60: ("cmm", "c2"),
    63: ("p4g", "c4"), 65: ("pmm", "d1"), 70: ("p4m", "d1"), 75: ("p4m", "d2"),
    80: ("p4m", "c1"), 87: ("p3m1", "c1"), 89: ("p31m", "c3"), 92: ("p6m", "d1"),
}

_ID = ((0, False),)
#: The twelve marked types: H derived from the definitions, the numbers checked against
#: :data:`GS_TABLE_5_2_3` (see the module docstring).
MARKINGS = {
    19: MarkedType(20, "p3m1", ((0, False), (2, False), (4, False), (0, True), (2, True), (4, True)), 1),
    35: MarkedType(37, "p3m1", ((0, False), (0, True)), 3),
    48: MarkedType(72, "pmm", _ID, 4),
    60: MarkedType(72, "cmm", ((0, False), (2, False)), 2),
    63: MarkedType(72, "p4g", ((0, False), (1, False), (2, False), (3, False)), 2, square=True),
    65: MarkedType(72, "pmm", ((0, False), (1, True)), 2),
    70: MarkedType(72, "p4m", ((0, False), (0, True)), 4, square=True),
    75: MarkedType(72, "p4m", ((0, False), (2, False), (0, True), (2, True)), 2, square=True),
    80: MarkedType(82, "p4m", _ID, 8),
    87: MarkedType(93, "p3m1", _ID, 6),
    89: MarkedType(93, "p31m", ((0, False), (1, False), (2, False)), 2),
    92: MarkedType(93, "p6m", ((0, False), (0, True)), 6),
}
#: Marked types -> their outline twin (see the module docstring).
MARKED = {n: m.twin for n, m in MARKINGS.items()}
#: IH72's parameter that makes its rectangle the square.
_SQUARE = (0.9 / 3.9,)
#: The marking's asymmetric flag, a polyline in units of the prototile's inradius about its centroid
#: (a pole and a pennant, off every axis of the tile): :func:`motif` places H's images of it.
FLAG = ((-0.08, 0.4), (-0.1, 0.82), (-0.36, 0.72), (-0.09, 0.62))
#: Every type number.
TYPES = tuple(range(1, 94))
#: Chords per cubic Bézier piece when an edge is drawn (part of the file format: the verifier samples alike).
BEZIER_CHORDS = 16
#: Most points an edge shape may have (control points, or polyline points).
MAX_EDGE_POINTS = 256
#: Most tiles a drawing may hold.
MAX_TILES = 200_000
#: Most points on a prototile's outline.
MAX_OUTLINE = 4096
#: Edge shapes' coordinates stay within this box of the unit frame.
MAX_COORD = 4.0
#: Tolerance of the symmetry checks on edge shapes (the frame's unit).
SYMMETRY_TOL = 1e-9


@dataclass(frozen=True)
class IsohedralType:
    """One isohedral type's template.

    Attributes
    ----------
    number : int
        1..93 (Grünbaum and Shephard's IH number).
    n_params, n_aspects, n_vertices : int
        Tiling-vertex parameters, aspects in a translational unit, tiling vertices (= tiling edges).
    edge_kinds : tuple of str
        One of :data:`KINDS` per edge class (the user's edge shapes, in this order).
    edge_classes : tuple of int
        The class of each tiling edge, edge ``k`` running from vertex ``k`` to ``k + 1``.
    orientations : tuple of (bool, bool)
        Per tiling edge, (flip, rotate): the class's shape is mirrored in x = 1/2 (flip), turned a
        half-turn about (1/2, 0) (rotate), or reflected in the x axis (both) before it is mapped
        onto the edge (tactile's ``M_orients``); with exactly one of them the path runs backwards.
    default_params : tuple of float
    vertex_coeffs : numpy.ndarray
        ``(n_vertices, 2, n_params + 1)``: x and y of each tiling vertex as ``coeffs @ (*params, 1)``.
    translation_coeffs : numpy.ndarray
        ``(2, 2, n_params + 1)``: T1 and T2 likewise.
    aspect_coeffs : numpy.ndarray
        ``(n_aspects, 2, 3, n_params + 1)``: each aspect's affine map ``[[a, b, c], [d, e, f]]``.
    colouring : tuple of int
        tactile's 19 numbers: colours of up to 12 aspects, the permutations of T1 and T2, the number
        of colours (§7.4.1, Fig. 20).
    outline_of : int or None
        For a marked type, its outline twin (whose tables these are).
    marking : MarkedType or None
        For a marked type, its marking.
    """

    number: int
    n_params: int
    n_aspects: int
    n_vertices: int
    edge_kinds: tuple[str, ...]
    edge_classes: tuple[int, ...]
    orientations: tuple[tuple[bool, bool], ...]
    default_params: tuple[float, ...]
    vertex_coeffs: np.ndarray = field(repr=False, compare=False)
    translation_coeffs: np.ndarray = field(repr=False, compare=False)
    aspect_coeffs: np.ndarray = field(repr=False, compare=False)
    colouring: tuple[int, ...] = field(repr=False)
    outline_of: int | None = None
    marking: MarkedType | None = field(default=None, repr=False)

    @property
    def name(self) -> str:
        """``IH01`` .. ``IH93``."""
        return f"IH{self.number:02d}"

    @property
    def n_colours(self) -> int:
        """Colours of the type's colouring."""
        return self.colouring[18]


def parse_type(text) -> int:
    """A type number from ``IH41``, ``ih7``, ``41`` or an int; one-line error otherwise.

    >>> parse_type("IH07"), parse_type(93)
    (7, 93)
    """
    if isinstance(text, (int, np.integer)) and not isinstance(text, bool):
        n = int(text)
    else:
        m = re.fullmatch(r"\s*(?:IH)?0*(\d{1,3})\s*", str(text), re.IGNORECASE)
        n = int(m.group(1)) if m else -1
    if n not in TYPES:
        raise InvalidProblem(f"unknown isohedral type {text!r}: expected IH1..IH93 (e.g. IH41)")
    return n


@lru_cache(maxsize=None)
def isohedral_type(number: int) -> IsohedralType:
    """The template of type ``number`` (a marked type gets its outline twin's tables).

    >>> isohedral_type(16).edge_classes
    (0, 1, 1, 1, 1, 0)
    """
    number = parse_type(number)
    from tactile.tiling_data import TilingTypeData  # the one reader of the package's tables

    marking = MARKINGS.get(number)
    twin = marking.twin if marking else None
    d = TilingTypeData.get_data(twin or number)
    p1 = d.num_params + 1
    eo = list(d.edge_orientations)
    vertex = np.asarray(d.vertex_coeffs, float).reshape(d.num_vertices, 2, p1)
    translation = np.asarray(d.translation_coeffs, float).reshape(2, 2, p1)
    aspect = np.asarray(d.aspect_coeffs, float).reshape(d.num_aspects, 2, 3, p1)
    n_params, defaults = d.num_params, tuple(float(p) for p in d.default_params)
    if marking and marking.square:  # the parameter folded into the constant terms
        vertex, translation, aspect = (c[..., -1:] + c[..., :-1] @ np.array(_SQUARE)[:, None]
                                       for c in (vertex, translation, aspect))
        n_params, defaults = 0, ()
    return IsohedralType(
        number=number,
        n_params=n_params,
        n_aspects=d.num_aspects,
        n_vertices=d.num_vertices,
        edge_kinds=tuple(e.name for e in d.edge_shapes),
        edge_classes=tuple(int(i) for i in d.edge_shape_ids),
        orientations=tuple((bool(eo[2 * k]), bool(eo[2 * k + 1])) for k in range(d.num_vertices)),
        default_params=defaults,
        vertex_coeffs=vertex,
        translation_coeffs=translation,
        aspect_coeffs=aspect,
        colouring=tuple(int(c) for c in d.coloring),
        outline_of=twin,
        marking=marking,
    )


_POINT = r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?"


@dataclass(frozen=True)
class EdgeShape:
    """An edge shape in its unit frame: a path from (0, 0) to (1, 0).

    Attributes
    ----------
    kind : str
        ``"line"``: a polyline through ``points``; ``"bezier"``: a chain of cubic Bézier curves,
        ``points`` being ``c1, c2, p1, c1, c2, p2, ..., c1, c2`` (3k - 1 points for k cubics; the
        chain ends at (1, 0)).
    points : tuple of (float, float)
        The points between the ends (none: a straight edge).
    """

    kind: str
    points: tuple[tuple[float, float], ...] = ()

    def __post_init__(self) -> None:
        if self.kind not in ("line", "bezier"):
            raise InvalidProblem(f"edge shape kind must be line or bezier, got {self.kind!r}")
        if len(self.points) > MAX_EDGE_POINTS:
            raise InvalidProblem(f"an edge shape has at most {MAX_EDGE_POINTS} points, got {len(self.points)}")
        for p in self.points:
            if len(p) != 2 or not all(isinstance(c, (int, float)) and not isinstance(c, bool)
                                      and math.isfinite(c) and abs(c) <= MAX_COORD for c in p):
                raise InvalidProblem(f"edge shape point {p!r} must be two finite numbers within "
                                     f"+-{MAX_COORD:g} (the edge runs from 0,0 to 1,0)")
        if self.kind == "bezier" and len(self.points) % 3 != 2:
            raise InvalidProblem(f"a Bézier edge has 3k-1 points (two control points per cubic, a joint between "
                                 f"cubics), got {len(self.points)}")

    @classmethod
    def parse(cls, text: str) -> "EdgeShape":
        """``line`` (straight), ``line:X,Y/X,Y/...`` or ``bezier:X,Y/X,Y[/...]``.

        >>> EdgeShape.parse("line:0.5,0.2").points
        ((0.5, 0.2),)
        """
        m = re.fullmatch(r"\s*(line|bezier)\s*(?::(.*))?", str(text))
        if m is None:
            raise InvalidProblem(f"cannot read edge shape {text!r}: expected line, line:X,Y/X,Y/... or "
                                 "bezier:X,Y/X,Y (points in the edge's frame, from 0,0 to 1,0)")
        points = []
        for part in (m.group(2) or "").split("/") if m.group(2) else []:
            pm = re.fullmatch(rf"\s*({_POINT})\s*,\s*({_POINT})\s*", part)
            if pm is None:
                raise InvalidProblem(f"cannot read point {part!r} of edge shape {text!r}: expected X,Y")
            points.append((float(pm.group(1)), float(pm.group(2))))
        return cls(m.group(1), tuple(points))

    def text(self) -> str:
        """The spelling :meth:`parse` reads (``repr`` of each number: exact round trip)."""
        if not self.points:
            return self.kind
        return f"{self.kind}:" + "/".join(f"{_num(x)},{_num(y)}" for x, y in self.points)

    def is_straight(self) -> bool:
        """Whether the path is the segment itself (no point off the x axis between 0 and 1)."""
        return all(abs(y) <= SYMMETRY_TOL for _, y in self.points) and \
            all(-SYMMETRY_TOL <= x <= 1 + SYMMETRY_TOL for x, _ in self.points) and \
            all(a[0] <= b[0] + SYMMETRY_TOL for a, b in zip(((0.0, 0.0),) + self.points, self.points + ((1.0, 0.0),)))

    def mirrored(self) -> tuple[tuple[float, float], ...]:
        """The points after the reflection in x = 1/2, in path order (a U edge's are its own)."""
        return tuple((1.0 - x, y) for x, y in reversed(self.points))

    def turned(self) -> tuple[tuple[float, float], ...]:
        """The points after the half-turn about (1/2, 0), in path order (an S edge's are its own)."""
        return tuple((1.0 - x, -y) for x, y in reversed(self.points))

    def check(self, kind: str, what: str) -> None:
        """Refuse a shape that breaks its class's constraint ``kind`` (§7.3.1); ``what`` names the class."""
        def same(a, b):
            return all(abs(p - q) <= SYMMETRY_TOL for u, v in zip(a, b) for p, q in zip(u, v))

        if kind == "I" and not self.is_straight():
            raise InvalidProblem(f"{what} is an I edge: it must be straight (give 'line')")
        if kind == "U" and not same(self.points, self.mirrored()):
            raise InvalidProblem(f"{what} is a U edge: its points must be symmetric in x = 0.5 "
                                 f"(X,Y and 1-X,Y in reverse order)")
        if kind == "S" and not same(self.points, self.turned()):
            raise InvalidProblem(f"{what} is an S edge: its points must be symmetric by a half-turn about 0.5,0 "
                                 f"(X,Y and 1-X,-Y in reverse order)")


def _num(v: float) -> str:
    return repr(float(v)).removesuffix(".0") if float(v) != int(v) or abs(v) >= 1e16 else str(int(v))


#: The straight edge.
STRAIGHT = EdgeShape("line")


@dataclass(frozen=True)
class IsohedralProblem:
    """Draw a region of an isohedral tiling of one type with given parameters and edge shapes.

    Parameters
    ----------
    type : int
        1..93.
    params : tuple of float, optional
        The tiling-vertex parameters (default: the type's defaults).
    edges : tuple of EdgeShape, optional
        One per edge class (default: straight); each must keep its class's constraint.
    region : (x0, y0, width, height)
        The rectangle drawn, in the tables' units (y up); the tiles that meet it are kept.
    scale : float
        Pixels per unit in pictures.
    """

    type: int
    params: tuple[float, ...] | None = None
    edges: tuple[EdgeShape, ...] | None = None
    region: tuple[float, float, float, float] = (0.0, 0.0, 8.0, 6.0)
    scale: float = 40.0

    def __post_init__(self) -> None:
        t = isohedral_type(self.type)
        object.__setattr__(self, "type", t.number)
        params = t.default_params if self.params is None else tuple(self.params)
        if len(params) != t.n_params:
            raise InvalidProblem(f"{t.name} takes {t.n_params} parameter{'s' if t.n_params != 1 else ''}, "
                                 f"got {len(params)}")
        if not all(isinstance(p, (int, float)) and not isinstance(p, bool) and math.isfinite(p) and abs(p) <= 100
                   for p in params):
            raise InvalidProblem(f"{t.name}'s parameters must be finite numbers within +-100, got {list(params)}")
        object.__setattr__(self, "params", tuple(float(p) for p in params))
        n = len(t.edge_kinds)
        edges = tuple(self.edges) if self.edges is not None else (STRAIGHT,) * n
        if len(edges) != n:
            raise InvalidProblem(f"{t.name} has {n} edge class{'es' if n != 1 else ''}, got {len(edges)} edge shapes")
        for i, (shape, kind) in enumerate(zip(edges, t.edge_kinds)):
            if not isinstance(shape, EdgeShape):
                raise InvalidProblem(f"edge {i} must be an EdgeShape, got {type(shape).__name__}")
            shape.check(kind, f"{t.name}'s edge {i}")
        object.__setattr__(self, "edges", edges)
        region = tuple(self.region)
        if len(region) != 4 or not all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
                                       and abs(v) <= 1e6 for v in region) or region[2] <= 0 or region[3] <= 0:
            raise InvalidProblem(f"the region must be x0, y0, width, height with positive sizes within 1e6, "
                                 f"got {list(region)}")
        object.__setattr__(self, "region", tuple(float(v) for v in region))
        if not (isinstance(self.scale, (int, float)) and not isinstance(self.scale, bool)
                and math.isfinite(self.scale) and 1 <= self.scale <= 1000):
            raise InvalidProblem(f"the scale must be 1..1000 pixels per unit, got {self.scale!r}")
        object.__setattr__(self, "scale", float(self.scale))

    @property
    def template(self) -> IsohedralType:
        """The type's template."""
        return isohedral_type(self.type)

    def describe(self) -> str:
        """One line: type and region."""
        x0, y0, w, h = self.region
        return f"{self.template.name} in the region {_num(x0)},{_num(y0)},{_num(w)}x{_num(h)}"


@dataclass(frozen=True)
class IsohedralTiling:
    """The answer: the prototile, the translational unit, and the tiles that meet the region.

    Attributes
    ----------
    type : int
    outline : numpy.ndarray
        ``(n, 2)`` the prototile's boundary, in tiling-vertex order (the tables' order), not closed.
    corners : tuple of int
        Index in ``outline`` of each tiling vertex (``corners[0] == 0``, increasing).
    aspects : numpy.ndarray
        ``(n_aspects, 2, 3)`` each aspect's rigid motion of the prototile.
    translations : numpy.ndarray
        ``(2, 2)`` rows T1 and T2.
    placements : numpy.ndarray
        ``(k, 3)`` int: tile ``(i, j, a)`` is aspect ``a`` moved by ``i T1 + j T2``.
    colours : numpy.ndarray
        ``(k,)`` the colour of each placed tile (0 .. colours - 1).
    motif : tuple of numpy.ndarray
        A marked type's marking: polylines ``(m, 2)`` in the prototile's frame (empty: unmarked).
    symmetries : numpy.ndarray or None
        A marked type's ``(s, 2, 3)`` symmetries of the prototile's outline (the first the identity).
    marks : numpy.ndarray or None
        A marked type's ``(k,)`` index into ``symmetries`` per placed tile: tile ``k`` carries
        the motif moved by :meth:`mark_motion`.
    """

    type: int
    outline: np.ndarray
    corners: tuple[int, ...]
    aspects: np.ndarray
    translations: np.ndarray
    placements: np.ndarray
    colours: np.ndarray
    motif: tuple[np.ndarray, ...] = ()
    symmetries: np.ndarray | None = None
    marks: np.ndarray | None = None

    @property
    def n_tiles(self) -> int:
        """Tiles placed."""
        return int(len(self.placements))

    def tile(self, k: int) -> np.ndarray:
        """The polygon of placed tile ``k`` (``(n, 2)``)."""
        i, j, a = (int(v) for v in self.placements[k])
        m = self.aspects[a]
        return self.outline @ m[:, :2].T + m[:, 2] + i * self.translations[0] + j * self.translations[1]

    def mark_motion(self, k: int) -> np.ndarray:
        """The motion ``(2, 3)`` that carries the prototile and its motif onto placed tile ``k``
        (its aspect's motion after the prototile symmetry ``marks[k]``)."""
        i, j, a = (int(v) for v in self.placements[k])
        m, s = self.aspects[a], self.symmetries[int(self.marks[k])]
        return np.hstack([m[:, :2] @ s[:, :2], m[:, :2] @ s[:, 2:] + m[:, 2:]
                          + (i * self.translations[0] + j * self.translations[1])[:, None]])

    def counts(self) -> dict[str, int]:
        """Tiles per colour."""
        return {f"colour {c}": int(n) for c, n in enumerate(np.bincount(self.colours.astype(np.int64)))}
