"""The ``tilesolve/isohedral-tiling`` file (version 2; version 1 is read) and its pictures: a region
of an isohedral tiling.

::

    {
      "format": "tilesolve/isohedral-tiling", "version": 2,
      "type": "IH41",                       # IH01..IH93
      "outline_of": null,                   # a marked type's outline twin ("IH20"), else null
      "params": [0.23, 0.5],                # the tiling-vertex parameters
      "edge_kinds": ["J", "J"],             # the type's edge classes (checked against the type)
      "edges": ["bezier:0.3,0.2/0.7,-0.2", "line"],   # one shape per edge class, in its unit frame
      "region": [0, 0, 12, 8], "scale": 40, # x0, y0, width, height in units (y up); pixels per unit
      "outline": [[x, y], ...],             # the prototile, tiling-vertex order
      "corners": [0, 17, ...],              # index of each tiling vertex in the outline
      "aspects": [[[a, b, c], [d, e, f]], ...],   # each aspect's rigid motion
      "translations": [[x, y], [x, y]],     # T1, T2
      "placements": [[i, j, aspect], ...],  # the tiles whose bounding boxes meet the region, all of them
      "colours": [...], "counts": {...},    # a colour per placement; tiles per colour ("colour 0": n, ...)
      "marking": null,                      # a marked type's: {"motif": [[[x, y], ...], ...],
                                            #   "symmetries": [[[a, b, c], [d, e, f]], ...], "marks": [...]}
      "status": "sat", "method": "template", "seed": null, "solver": null,
      "reason": null, "notes": [], "stats": {}
    }

Version 2 adds ``marking``: a marked type's motif (polylines in the prototile's frame), the
prototile's symmetries, and per placed tile the symmetry after which its aspect's motion carries
the motif onto it (:meth:`~tilesolve.model.isohedral.IsohedralTiling.mark_motion`). A version 1
file has none; a marked type read from one fails verification (its tiles carry no marking).

No time is recorded: the same command writes the same bytes. Readers refuse unknown fields and
malformed values in one line naming the file and field, a ``type`` that is not a name, ``counts``
that are not the colours' own, a version 1 file with a ``marking``, and a drawing's fields
without its ``outline``; whether the geometry is a tiling of the stated type, and the drawing the
whole region, is the verifier's question (``tilesolve verify``).

Pictures: SVG (the prototile once, as a path in ``<defs>``, and one ``<use>`` per tile with its
motion, clipped to the region: small files) and PNG (Pillow polygons), the region ``width x scale`` by
``height x scale`` pixels, tiles filled by colour and outlined; a marked type's motif drawn in
every tile, moved by that tile's marking motion (SVG: the motif once in ``<defs>``, one ``<use>``
per tile).
"""

from __future__ import annotations

import io

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.io.atomic import write_bytes_atomic, write_text_atomic
from tilesolve.io.jsonio import (
    COMPACT_MIN_CELLS,
    check_document,
    decode_array,
    encode_array,
    provenance_to_dict,
    solution_from_provenance,
)
from tilesolve.model.isohedral import (
    MAX_OUTLINE,
    MAX_TILES,
    EdgeShape,
    IsohedralProblem,
    IsohedralTiling,
    isohedral_type,
    parse_type,
)
from tilesolve.model.solution import Solution

__all__ = ["TILING_FORMAT", "VERSIONS", "COLOURS", "MAX_PX", "tiling_to_dict", "tiling_from_dict", "svg_text",
           "png_bytes", "write_svg", "write_png"]

TILING_FORMAT = "tilesolve/isohedral-tiling"
VERSIONS = frozenset({1, 2})
#: Stroke colour of the markings.
MARK_COLOUR = "#111111"
#: Most polylines and points per polyline in a motif, and most prototile symmetries.
MAX_MOTIF = 64
MAX_SYMMETRIES = 12
#: Fill colours of the colouring's classes (at most 4 are used by any type).
COLOURS = ("#E8B04B", "#3E7CB1", "#D1495B", "#66A182")
#: Stroke colour of the tiles' outlines.
STROKE = "#1F1F1F"
#: Longest side of a picture in pixels.
MAX_PX = 8192

_FIELDS = {"format", "version", "type", "outline_of", "params", "edge_kinds", "edges", "region", "scale", "outline",
           "corners", "aspects", "translations", "placements", "colours", "counts", "marking", "status", "method", "solver",
           "seed", "time_s", "reason", "notes", "stats", "created_by", "comment"}


def _floats(a) -> list:
    return np.round(np.asarray(a, float), 12).tolist()


def tiling_to_dict(problem: IsohedralProblem, solution: Solution) -> dict:
    """The JSON document of a drawing (no time: the same problem gives the same bytes)."""
    t = problem.template
    doc = {"format": TILING_FORMAT, "version": 2, "type": t.name,
           "outline_of": f"IH{t.outline_of:02d}" if t.outline_of else None, "params": list(problem.params),
           "edge_kinds": list(t.edge_kinds), "edges": [e.text() for e in problem.edges],
           "region": list(problem.region), "scale": problem.scale}
    tiling = solution.tiling
    if tiling is not None:
        placed = np.asarray(tiling.placements, np.int64)
        colours = np.asarray(tiling.colours, np.int64)
        doc.update(outline=_floats(tiling.outline), corners=list(tiling.corners), aspects=_floats(tiling.aspects),
                   translations=_floats(tiling.translations),
                   placements=encode_array(placed) if placed.size > COMPACT_MIN_CELLS else placed,
                   colours=encode_array(colours) if colours.size > COMPACT_MIN_CELLS else colours,
                   counts=tiling.counts(), marking=None)
        if tiling.marks is not None:
            marks = np.asarray(tiling.marks, np.int64)
            doc["marking"] = {"motif": [_floats(p) for p in tiling.motif], "symmetries": _floats(tiling.symmetries),
                              "marks": encode_array(marks) if marks.size > COMPACT_MIN_CELLS else marks}
    prov = provenance_to_dict(solution)
    del prov["time_s"]
    doc.update(prov)
    return doc


def _number_array(value, name: str, source: str, shape: tuple, limit: int | None = None) -> np.ndarray:
    """A nested list of finite numbers of the given shape (``-1``: any length up to ``limit``)."""
    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InvalidProblem(f"{source}: {name!r} must be a nested list of numbers") from None
    if a.dtype == object or isinstance(value, (str, bytes)) or a.ndim != len(shape) or \
            any(want not in (-1, got) for want, got in zip(shape, a.shape)):
        raise InvalidProblem(f"{source}: {name!r} must have shape {list(shape)} (-1: any), got "
                             f"{list(a.shape) if a.dtype != object else 'a ragged list'}")
    if limit is not None and a.shape[0] > limit:
        raise InvalidProblem(f"{source}: {name!r} has {a.shape[0]:,} rows, at most {limit:,}")
    if not np.isfinite(a).all() or np.abs(a).max(initial=0) > 1e9:
        raise InvalidProblem(f"{source}: {name!r} must hold finite numbers within 1e9")
    if any(isinstance(v, bool) for v in np.asarray(value, dtype=object).ravel()):
        raise InvalidProblem(f"{source}: {name!r} must hold numbers, not booleans")
    return a


def tiling_from_dict(doc: dict, source: str) -> tuple[IsohedralProblem, Solution]:
    """Problem and solution of a document; one-line :class:`InvalidProblem` naming ``source`` and the field."""
    check_document(doc, source, {TILING_FORMAT: VERSIONS}, fields=_FIELDS,
                   required=("type", "params", "edges", "region", "scale"))
    if not isinstance(doc["type"], str):
        raise InvalidProblem(f"{source}: 'type' must be a type name such as 'IH41', got {doc['type']!r}")
    try:
        number = parse_type(doc["type"])
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: 'type': {exc}") from None
    if doc["version"] < 2 and "marking" in doc:
        raise InvalidProblem(f"{source}: 'marking' is a field of version 2 files; this file says version 1")
    t = isohedral_type(number)
    twin = f"IH{t.outline_of:02d}" if t.outline_of else None
    if doc.get("outline_of", twin) != twin:
        raise InvalidProblem(f"{source}: 'outline_of' must be {twin!r} for {t.name}, got {doc.get('outline_of')!r}")
    if doc.get("edge_kinds", list(t.edge_kinds)) != list(t.edge_kinds):
        raise InvalidProblem(f"{source}: 'edge_kinds' must be {list(t.edge_kinds)} for {t.name}")
    for name, kind in (("params", list), ("edges", list), ("region", list)):
        if not isinstance(doc[name], kind):
            raise InvalidProblem(f"{source}: {name!r} must be a list")
    if not all(isinstance(e, str) and len(e) <= 20_000 for e in doc["edges"]) or len(doc["edges"]) > 16:
        raise InvalidProblem(f"{source}: 'edges' must be a list of edge shapes such as 'line' or 'bezier:X,Y/X,Y'")
    try:
        problem = IsohedralProblem(number, tuple(doc["params"]), tuple(EdgeShape.parse(e) for e in doc["edges"]),
                                   tuple(doc["region"]), doc["scale"])
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: {exc}") from None
    tiling = None
    if "outline" in doc:
        outline = _number_array(doc["outline"], "outline", source, (-1, 2), MAX_OUTLINE)
        corners = doc.get("corners")
        if not isinstance(corners, list) or not all(isinstance(c, int) and not isinstance(c, bool) for c in corners):
            raise InvalidProblem(f"{source}: 'corners' must be a list of integers")
        aspects = _number_array(doc.get("aspects"), "aspects", source, (t.n_aspects, 2, 3))
        trans = _number_array(doc.get("translations"), "translations", source, (2, 2))
        placed = decode_array(doc.get("placements"), "placements", source, ndim=2)
        colours = decode_array(doc.get("colours"), "colours", source, ndim=1)
        if placed.shape[1:] != (3,) or len(placed) > MAX_TILES or colours.shape != (len(placed),):
            raise InvalidProblem(f"{source}: 'placements' must be at most {MAX_TILES:,} rows i, j, aspect and "
                                 "'colours' one per row")
        tiling = IsohedralTiling(number, outline, tuple(corners), aspects, trans, placed.astype(np.int64),
                                 colours.astype(np.int64), *_marking(doc.get("marking"), len(placed), source))
        _check_counts(doc.get("counts"), colours, t.n_colours, source)
    else:
        drawn = sorted(set(doc) & {"corners", "aspects", "translations", "placements", "colours", "counts", "marking"})
        if drawn:
            raise InvalidProblem(f"{source}: {', '.join(map(repr, drawn))} without an 'outline': a drawing is "
                                 "all of its fields or none")
    return problem, solution_from_provenance(doc, source, tiling, what="outline")


def _check_counts(counts, colours: np.ndarray, n_colours: int, source: str) -> None:
    """``counts`` (tiles per colour, a summary the writer adds) must be the colours' own; colours
    outside the type's range are left to the verifier."""
    if counts is None or not len(colours) or colours.min() < 0 or colours.max() >= n_colours:
        return
    have = {f"colour {c}": int(n) for c, n in enumerate(np.bincount(colours.astype(np.int64)))}
    if counts != have:
        raise InvalidProblem(f"{source}: 'counts' does not match 'colours': the tiles per colour are {have}")


def _marking(value, n_tiles: int, source: str) -> tuple:
    """Motif, symmetries and marks of a ``marking`` field (``()``: none)."""
    if value is None:
        return ()
    if not isinstance(value, dict) or set(value) != {"motif", "symmetries", "marks"}:
        raise InvalidProblem(f"{source}: 'marking' must be null or an object with motif, symmetries and marks")
    if not isinstance(value["motif"], list) or not 1 <= len(value["motif"]) <= MAX_MOTIF:
        raise InvalidProblem(f"{source}: 'marking.motif' must be a list of 1..{MAX_MOTIF} polylines")
    motif = tuple(_number_array(p, "marking.motif", source, (-1, 2), MAX_MOTIF) for p in value["motif"])
    if any(len(p) < 2 for p in motif):
        raise InvalidProblem(f"{source}: 'marking.motif' polylines have at least 2 points")
    syms = _number_array(value["symmetries"], "marking.symmetries", source, (-1, 2, 3), MAX_SYMMETRIES)
    marks = decode_array(value["marks"], "marking.marks", source, ndim=1)
    if marks.shape != (n_tiles,) or (n_tiles and (marks.min() < 0 or marks.max() >= len(syms))):
        raise InvalidProblem(f"{source}: 'marking.marks' must be one index into 'marking.symmetries' per placement")
    return motif, syms, marks.astype(np.int64)


def _size(problem: IsohedralProblem) -> tuple[int, int]:
    _, _, w, h = problem.region
    wp, hp = max(1, round(w * problem.scale)), max(1, round(h * problem.scale))
    if max(wp, hp) > MAX_PX:
        raise InvalidProblem(f"the picture would be {wp}x{hp} pixels, at most {MAX_PX} a side: "
                             "lower --scale or the region")
    return wp, hp


def _f(v: float) -> str:
    return f"{v:.6f}".rstrip("0").rstrip(".") if v != 0 else "0"


def _motif_def(tiling: IsohedralTiling, scale: float) -> str:
    """The motif as ``<path id="mark">`` (nothing for an unmarked type)."""
    if tiling.marks is None:
        return ""
    d = " ".join("M" + " L".join(f"{_f(x)} {_f(y)}" for x, y in p) for p in tiling.motif)
    return (f'<path id="mark" d="{d}" fill="none" stroke="{MARK_COLOUR}" stroke-width="{_f(2.0 / scale)}" '
            'stroke-linecap="round" stroke-linejoin="round"/>')


def svg_text(problem: IsohedralProblem, tiling: IsohedralTiling) -> str:
    """The SVG of the drawing: the prototile once in ``<defs>``, one ``<use>`` per tile.

    SVG's ``matrix(a b c d e f)`` maps (x, y) to (a x + c y + e, b x + d y + f): a motion
    ``[[m00, m01, m02], [m10, m11, m12]]`` is ``matrix(m00 m10 m01 m11 m02 m12)``.
    """
    from xml.sax.saxutils import escape

    from tilesolve.io.svg import BACKGROUND, CAPTION_COLOUR, caption_box

    wp, hp = _size(problem)
    x0, y0, w, h = problem.region
    s = problem.scale
    caption = problem.describe()
    cw, ch = caption_box([caption])
    W, H = max(wp, round(cw) + 8), hp + round(ch) + 4  # the caption under the picture, never clipped
    path = "M" + " L".join(f"{_f(x)} {_f(y)}" for x, y in tiling.outline) + " Z"
    lines = [f'<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" '
             f'width="{W}" height="{H}" viewBox="0 0 {W} {H}">',
             f'<title>{escape(caption)}</title>',
             f'<rect x="0" y="0" width="{W}" height="{H}" fill="{BACKGROUND}"/>',
             f'<text x="4" y="{hp + 14}" font-family="sans-serif" font-size="12" fill="{CAPTION_COLOUR}">'
             f'{escape(caption)}</text>',
             f'<defs><path id="tile" d="{path}"/>{_motif_def(tiling, s)}'
             f'<clipPath id="region-clip"><rect x="0" y="0" width="{wp}" height="{hp}"/></clipPath></defs>',
             '<g clip-path="url(#region-clip)">',  # tiles that cross the region's edge stop there, off the caption
             f'<g transform="matrix({_f(s)} 0 0 {_f(-s)} {_f(-x0 * s)} {_f((y0 + h) * s)})" '
             f'stroke="{STROKE}" stroke-width="{_f(1.0 / s)}" stroke-linejoin="round">']
    T = tiling.translations
    for (i, j, a), c in zip(tiling.placements.tolist(), tiling.colours.tolist()):
        m = tiling.aspects[a]
        e, f = m[:, 2] + i * T[0] + j * T[1]
        lines.append(f'<use xlink:href="#tile" fill="{COLOURS[c % len(COLOURS)]}" '
                     f'transform="matrix({_f(m[0, 0])} {_f(m[1, 0])} {_f(m[0, 1])} {_f(m[1, 1])} {_f(e)} {_f(f)})"/>')
    if tiling.marks is not None:
        for k in range(tiling.n_tiles):
            m = tiling.mark_motion(k)
            lines.append(f'<use xlink:href="#mark" transform="matrix({_f(m[0, 0])} {_f(m[1, 0])} {_f(m[0, 1])} '
                         f'{_f(m[1, 1])} {_f(m[0, 2])} {_f(m[1, 2])})"/>')
    lines += ["</g>", "</g>", "</svg>"]
    return "\n".join(lines) + "\n"


def png_bytes(problem: IsohedralProblem, tiling: IsohedralTiling) -> bytes:
    """The PNG of the drawing (Pillow): each tile a filled, outlined polygon."""
    from PIL import Image, ImageDraw

    wp, hp = _size(problem)
    x0, y0, w, h = problem.region
    s = problem.scale
    img = Image.new("RGB", (wp, hp), "white")
    draw = ImageDraw.Draw(img)
    placed = np.asarray(tiling.placements)
    aspect_tiles = np.einsum("aij,nj->ani", tiling.aspects[:, :, :2], tiling.outline) + tiling.aspects[:, None, :, 2]
    xy = aspect_tiles[placed[:, 2]] + (placed[:, :2] @ tiling.translations)[:, None, :]
    px = np.stack([(xy[..., 0] - x0) * s, (y0 + h - xy[..., 1]) * s], axis=-1).reshape(len(placed), -1)
    for flat, c in zip(px.tolist(), tiling.colours.tolist()):
        draw.polygon(flat, fill=COLOURS[c % len(COLOURS)], outline=STROKE)
    if tiling.marks is not None:
        for k in range(tiling.n_tiles):
            m = tiling.mark_motion(k)
            for p in tiling.motif:
                q = p @ m[:, :2].T + m[:, 2]
                draw.line([((x - x0) * s, (y0 + h - y) * s) for x, y in q.tolist()], fill=MARK_COLOUR,
                          width=max(1, round(s / 20)))
    from tilesolve.io.png import captioned

    buf = io.BytesIO()
    captioned(img, [problem.describe()]).save(buf, format="PNG")
    return buf.getvalue()


def write_svg(path, problem: IsohedralProblem, tiling: IsohedralTiling) -> None:
    """Write :func:`svg_text` atomically."""
    write_text_atomic(path, svg_text(problem, tiling))


def write_png(path, problem: IsohedralProblem, tiling: IsohedralTiling) -> None:
    """Write :func:`png_bytes` atomically."""
    write_bytes_atomic(path, png_bytes(problem, tiling))
