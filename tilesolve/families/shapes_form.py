"""The studio's form of the shapes family (:mod:`tilesolve.families.shapes`): a polyform typed as
ASCII art or painted on a grid of squares, hexagons or triangles, tiled on a torus or a
rectangle (``tilesolve shapes tile``) or classified with its Heesch number (``tilesolve shapes
heesch``). The command line it copies is the CLI's own: ``--shape 'XX/XX/X.'`` and
``--torus``/``--region WxH``.

Examples
--------
>>> vals = FORM.values({"seed": 1})
>>> problem, _ = FORM.build(vals)
>>> problem.question, problem.lattice, len(problem.shapes[0].cells)
('tile', ((5, 0), (0, 4)), 5)
>>> FORM.command(vals)[0]
['shapes', 'tile', '--grid', 'omino', '--shape', 'XX/XX/X.', '--torus', '5x4']
"""

from __future__ import annotations

from tilesolve.errors import InvalidProblem
from tilesolve.family.forms import Field, Form, form_size
from tilesolve.model.shapes import ShapesProblem, grid, parse_ascii, parse_cells

__all__ = ["FORM", "PAINT_SIDE"]

#: Rows and columns of the painting grid.
PAINT_SIDE = 8


def _paint_extent(values) -> tuple[int, int, int, int]:
    return PAINT_SIDE, PAINT_SIDE, 0, 1


def _shape_text(values) -> str:
    """The shape as the CLI's ``--shape`` text: the painted cells (cropped ASCII art, rows
    joined by ``/``) when any is painted, else the typed shape."""
    painted = values["paint"]
    if painted is None or not any(v == 1 for row in painted for v in row):
        return values["shape"].strip()
    rows = [i for i, row in enumerate(painted) if 1 in row]
    cols = [j for row in painted for j, v in enumerate(row) if v == 1]
    c0 = min(cols)
    if values["grid"] == "iamond" and c0 % 2 != rows[0] % 2:
        c0 -= 1  # keep each triangle's way up: a crop by an odd number of columns flips them
    return "/".join("".join("X" if v == 1 else "." for v in painted[i][c0:max(cols) + 1]) for i in range(rows[0], rows[-1] + 1))


def _shape(values):
    text = _shape_text(values)
    if not text:
        raise InvalidProblem("draw a shape: type it as ASCII art ('XX/X.') or cells ('0,0 1,0'), or paint it")
    if any(ch.isdigit() for ch in text):
        return parse_cells(text, values["grid"])
    return parse_ascii(text.replace("/", "\n"), values["grid"])


def _form_build(values):
    shape = _shape(values)
    reflections = values["reflections"]
    if values["question"] == "heesch":
        return ShapesProblem("classify", (shape,), reflections=reflections, max_level=values["max_level"],
                             max_copies=values["max_copies"], holes=values["holes"]), {}
    rows, cols = form_size(values["size"])
    if values["where"] == "torus":
        return ShapesProblem("tile", (shape,), lattice=((cols, 0), (0, rows)), reflections=reflections), {}
    g = grid(values["grid"])
    types = [(0, 0)] if g.period == 1 else [(1, 1), (2, 2)]  # the translation cell's triangles
    region = tuple((g.period * x + a, g.period * y + b) for x in range(cols) for y in range(rows) for a, b in types)
    return ShapesProblem("tile", (shape,), region=region, reflections=reflections), {}


def _form_command(values) -> tuple[list[str], dict[str, str]]:
    words = ["shapes", values["question"], "--grid", values["grid"], "--shape", _shape_text(values)]
    if values["question"] == "heesch":
        words += ["--max-level", str(values["max_level"]), "--max-copies", str(values["max_copies"])]
        words += ["--holes"] if values["holes"] else []
    else:
        words += [f"--{values['where']}", values["size"]]
    return words + ([] if values["reflections"] else ["--no-reflections"]), {}


#: When a field applies: the tile question's, the heesch question's.
_TILE, _HEESCH = ({"question": ("tile",)},), ({"question": ("heesch",)},)

FORM = Form(
    fields=(
        Field("question", "choice", "question", "tile", "tile: copies cover a torus or a rectangle; heesch: "
              "classify the shape (isohedral or periodic tiler, or its Heesch number)", choices=("tile", "heesch")),
        Field("grid", "choice", "grid", "omino", "squares (polyominoes), hexagons or triangles",
              choices=("omino", "hex", "iamond"), option="--grid"),
        Field("shape", "text", "shape", "XX/XX/X.", "ASCII art, rows top first, '/' between rows, or cells "
              "'x,y x,y'; a painted shape takes its place", option="--shape"),
        Field("where", "choice", "tile on", "torus", "tile: a torus with periods (W, 0), (0, H) or a W x H region",
              choices=("torus", "region"), when=_TILE),
        Field("size", "size", "size (WxH)", "5x4", "tile: W by H translation cells", high=4096, option="--torus",
              when=_TILE),
        Field("reflections", "bool", "mirror images", True, "copies may be reflected (rotations always may)",
              option="--no-reflections"),
        Field("max_level", "int", "most coronas", 3, "heesch: the most coronas tried", low=1, high=6,
              option="--max-level", when=_HEESCH),
        Field("max_copies", "int", "copies per period", 2, "heesch: the most copies per period tried on tori",
              low=1, high=6, option="--max-copies", when=_HEESCH),
        Field("holes", "bool", "holes in the outer corona", False, "heesch: H_h rather than H_c", option="--holes",
              when=_HEESCH),
        Field("paint", "cells", "shape (painted)", None, "paint the shape's cells (1); rows top first as in "
              "ASCII art", option="--shape", extent=_paint_extent),
    ),
    build=_form_build,
    command=_form_command,
)
