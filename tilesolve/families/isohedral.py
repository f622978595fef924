"""Isohedral tilings for design (class notes Part II §7): the ``isohedral`` family.

A problem (:class:`~tilesolve.model.isohedral.IsohedralProblem`) names one of the 93 isohedral
types, its tiling-vertex parameters, one edge shape per edge class (J free, U mirror-symmetric,
S symmetric by a half-turn, I straight) and a region; the answer is an
:class:`~tilesolve.model.isohedral.IsohedralTiling` (the prototile, the translational unit, the
coloured tiles that meet the region, and a marked type's markings), checked by the independent
verifier :mod:`tilesolve.verify.isohedral` (the type's template, congruence, a tiling of the torus
by area and edge matching, the drawing's cover and colours, and the markings' symmetry).

Route
-----
``template``
    The type's template at the parameters, the prototile from its edges, the region filled
    lattice cell by lattice cell (:mod:`tilesolve.constructive.isohedral`).

For a studio: :func:`draw` gives the SVG text of a drawing in one call.

Examples
--------
>>> from tilesolve.model.isohedral import EdgeShape, IsohedralProblem
>>> s = solve(IsohedralProblem(41, edges=(EdgeShape.parse("bezier:0.3,0.2/0.7,-0.2"),) * 2, region=(0, 0, 6, 4)))
>>> s.status.value, s.method, s.tiling.n_tiles
('sat', 'template', 48)
>>> draw("IH16", region=(0, 0, 3, 2)).startswith("<svg")
True
"""

from __future__ import annotations

import time
from typing import Any, Sequence

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.family import Codec, Demo, Family, Field, Form, RunOptions, register
from tilesolve.family import solve as _solve
from tilesolve.io.isohedral_json import TILING_FORMAT, VERSIONS
from tilesolve.model.isohedral import (
    BEZIER_CHORDS,
    TYPES,
    EdgeShape,
    IsohedralProblem,
    IsohedralTiling,
    isohedral_type,
    parse_type,
)
from tilesolve.model.solution import Solution, Status
from tilesolve.progress import Progress

__all__ = ["FAMILY", "SOLVERS", "solve", "template", "draw", "problem"]


def template(problem: IsohedralProblem, run: RunOptions) -> Solution:
    """The tiling from the type's template (:func:`tilesolve.constructive.isohedral.layout`)."""
    from tilesolve.constructive.isohedral import layout

    t0 = time.perf_counter()
    tiling = layout(problem)
    marking = problem.template.marking
    return Solution(Status.SAT, tiling, method="template", time_s=time.perf_counter() - t0,
                    stats={"tiles": tiling.n_tiles, "aspects": marking.aspects if marking else int(len(tiling.aspects)),
                           "outline_points": int(len(tiling.outline))})


#: Routes by name.
SOLVERS = {"template": template}


def _verify(problem: IsohedralProblem, tiling) -> list:
    from tilesolve.verify.dappled import Violation
    from tilesolve.verify.isohedral import tiling_violations

    if not isinstance(tiling, IsohedralTiling):
        return [Violation("shape", "the answer is no isohedral tiling")]
    return tiling_violations(problem, tiling)


def solve(problem: IsohedralProblem, *, method: str | Any = "auto", seed: int | None = None,
          time_limit: float | None = None, progress: Progress | bool = False) -> Solution:
    """Draw the tiling and verify it (:func:`tilesolve.family.solve` with this family's route).

    The tiling does not depend on the seed; none is recorded (``seed=0`` is passed down).
    """
    if not isinstance(problem, IsohedralProblem):
        raise InvalidProblem(f"expected an IsohedralProblem, got {type(problem).__name__}")
    return _solve(problem, method, seed=0 if seed is None else seed, time_limit=time_limit, progress=progress)


def problem(type: int | str, params: Sequence[float] | None = None,
            edges: Sequence[str | EdgeShape] | dict | None = None,
            region: Sequence[float] = (0.0, 0.0, 8.0, 6.0), scale: float = 40.0) -> IsohedralProblem:
    """An :class:`IsohedralProblem` from plain values: ``edges`` as shapes or their text
    (``"bezier:0.3,0.2/0.7,-0.2"``), a list (one per edge class) or a dict class -> shape
    (the others straight)."""
    number = parse_type(type)
    from tilesolve.model.isohedral import STRAIGHT

    n = len(isohedral_type(number).edge_kinds)
    if isinstance(edges, dict):
        bad = [k for k in edges if not isinstance(k, int) or not 0 <= k < n]
        if bad:
            raise InvalidProblem(f"edge class {bad[0]!r} does not exist: IH{number:02d} has classes 0..{n - 1}")
        edges = [edges.get(k, STRAIGHT) for k in range(n)]
    shapes = None if edges is None else tuple(e if isinstance(e, EdgeShape) else EdgeShape.parse(e) for e in edges)
    return IsohedralProblem(number, None if params is None else tuple(params), shapes, tuple(region), scale)


def draw(type: int | str, params: Sequence[float] | None = None, edges: Sequence[str | EdgeShape] | dict | None = None,
         region: Sequence[float] = (0.0, 0.0, 8.0, 6.0), scale: float = 40.0) -> str:
    """The SVG text of a verified drawing (the studio's call): see :func:`problem` for the arguments.

    Raises
    ------
    InvalidProblem
        An unknown type, wrong parameters, an edge shape that breaks its constraint, or a tile
        that crosses itself (one line each).
    """
    from tilesolve.io.isohedral_json import svg_text

    p = problem(type, params, edges, region, scale)
    return svg_text(p, solve(p).tiling)


def _read(doc: dict, source: str):
    from tilesolve.io.isohedral_json import tiling_from_dict

    return tiling_from_dict(doc, source)


def _write(problem: IsohedralProblem, sol: Solution) -> dict:
    from tilesolve.io.isohedral_json import tiling_to_dict

    return tiling_to_dict(problem, sol)


def _draw(problem: IsohedralProblem, sol: Solution, path, fmt: str, **_ignored) -> None:
    """SVG (the prototile in ``<defs>``, a ``<use>`` per tile) or PNG (Pillow)."""
    from tilesolve.io.isohedral_json import write_png, write_svg

    if not isinstance(sol.tiling, IsohedralTiling):
        raise InvalidProblem("nothing drawn: the solution holds no isohedral tiling")
    (write_png if fmt == "png" else write_svg)(path, problem, sol.tiling)


DEMOS = (
    Demo("isohedral-ih41", "an IH41 tiling (translations only) with Bézier edges",
         lambda: problem(41, edges=["bezier:0.3,0.25/0.6,-0.2", "bezier:0.35,-0.2/0.7,0.2"], region=(0, 0, 8, 6))),
)

#: Most edge classes of a type (IH04 has five).
_FORM_EDGES = 5


def _form_values(values) -> tuple[str, tuple[float, ...] | None, dict[int, str], tuple[float, float, float, float], float]:
    """Type, parameters, edges by class, region and scale from the form's values."""
    text = values["params"].strip()
    try:
        params = tuple(float(p) for p in text.split(",")) if text else None
    except ValueError:
        raise InvalidProblem(f"cannot read parameters {text!r}: expected numbers separated by commas") from None
    n = len(isohedral_type(parse_type(values["type"])).edge_kinds)  # the others do not apply (hidden)
    edges = {k: values[f"edge{k}"].strip() for k in range(n) if values[f"edge{k}"].strip()}
    w, h = (int(v) for v in values["region"].lower().split("x"))
    return values["type"], params, edges, (0.0, 0.0, float(w), float(h)), values["scale"]


def _form_build(values) -> tuple[IsohedralProblem, dict]:
    """The drawing the form describes (edge classes left empty are straight)."""
    return problem(*_form_values(values)), {}


def _form_sketch(values) -> dict:
    """The prototile's sides for the studio's live edge editor (:attr:`tilesolve.family.Form.sketch`)."""
    from tilesolve.constructive.isohedral import side_maps

    p = _form_build(values)[0]
    t = p.template
    return {"edges": [{"field": f"edge{k}", "kind": kind} for k, kind in enumerate(t.edge_kinds)],
            "sides": [{"edge": c, "map": np.round(m, 12).tolist(), "reverse": reverse}
                      for c, (m, reverse) in zip(t.edge_classes, side_maps(t, p.params))],
            "chords": BEZIER_CHORDS}


def _form_command(values) -> tuple[list[str], dict[str, str]]:
    typ, params, edges, (_, _, w, h), scale = _form_values(values)
    words = ["isohedral", "draw", "--type", typ]
    if params is not None:
        words += ["--params", ",".join(f"{p:.12g}" for p in params)]
    for k, shape in sorted(edges.items()):
        words += ["--edge", f"{k}={shape}"]
    return words + ["--region", f"{w:g}x{h:g}", "--scale", f"{scale:g}"], {}


FORM = Form(
    fields=(
        Field("type", "choice", "type", "IH41", "the isohedral type (tilesolve isohedral list)",
              choices=tuple(f"IH{n:02d}" for n in TYPES), option="--type"),
        Field("params", "text", "parameters", "", "tiling-vertex parameters, comma-separated (empty: the type's own)",
              option="--params"),
        *(Field(f"edge{k}", "text", f"edge class {k}", "bezier:0.3,0.2/0.7,-0.2" if k < 2 else "",
                "line, line:X,Y/... or bezier:X,Y/X,Y (empty: straight); J free, U mirror-symmetric, "
                "S half-turn-symmetric, I straight", option="--edge",
                when=({"type": tuple(f"IH{n:02d}" for n in TYPES if len(isohedral_type(n).edge_kinds) > k)},))
          for k in range(_FORM_EDGES)),
        Field("region", "size", "region (WxH)", "10x8", "width by height in tile units", high=100_000,
              option="--region"),
        Field("scale", "float", "pixels per unit", 40.0, "the picture is W and H times this", low=1, high=1000,
              option="--scale"),
    ),
    build=_form_build,
    command=_form_command,
    time_limit=False,
    sketch=_form_sketch,
)

FAMILY = register(Family(
    name="isohedral",
    title="isohedral tilings for design: the 93 types IH1..IH93 with edge shapes J, U, S, I "
          "(class notes Part II §7)",
    problem_type=IsohedralProblem,
    routes=SOLVERS,
    auto=lambda problem: "template",
    verify=_verify,
    codecs=(Codec(TILING_FORMAT, VERSIONS, _read, _write),),
    draw=_draw,
    demos=DEMOS,
    commands=("tilesolve.cli.isohedral:isohedral",),
    form=FORM,
    route_help={"template": "the type's template (tiling vertices, aspects, translations) and the edge shapes (§7.3-7.4)"},
))
