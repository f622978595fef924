"""The ``tilesolve/substitution-patch`` file (version 1) and its pictures: a Penrose or rep-tile patch.

::

    {
      "format": "tilesolve/substitution-patch", "version": 1,
      "kind": "p3",                      # p3, p2, chair, sphinx, l-tetromino, p-pentomino
      "steps": null,                     # substitution steps, or
      "region": [-20, -10, 40, 20],      # x0, y0, width, height (Penrose windows)
      "grid": "zeta5",                   # coordinates: zeta5, square or triangle (model.substitution.GRIDS)
      "types": [...],                    # one tile type per tile (P3: 0 thin, 1 thick; P2: 0 kite, 1 dart)
      "vertices": [...],                 # (tiles, corners, 4 or 2) integers, counter-clockwise
      "counts": {"thin": 93, "thick": 151},
      "status": "sat", "method": "pentagrid", "seed": 1, "time_s": 0.01, "solver": null,
      "reason": null, "notes": [], "stats": {}
    }

Arrays above :data:`~tilesolve.io.jsonio.COMPACT_MIN_CELLS` values are encoded arrays. Readers
reject unknown fields and malformed values in one line naming the file and field; the tiles
themselves are checked by the family's verifier (``tilesolve verify``), not here.

Pictures: SVG (svgwrite: one polygon per tile, coloured by type) and PNG (Pillow: the same
polygons, filled and outlined).
"""

from __future__ import annotations

import io
import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.io.atomic import atomic_write, write_bytes_atomic
from tilesolve.io.jsonio import (
    COMPACT_MIN_CELLS,
    check_document,
    decode_array,
    encode_array,
    provenance_to_dict,
    solution_from_provenance,
)
from tilesolve.io.svg import PALETTE, titled_canvas
from tilesolve.model.solution import Solution
from tilesolve.model.substitution import GRIDS, Patch, SubstitutionProblem

__all__ = ["PATCH_FORMAT", "VERSIONS", "patch_to_dict", "patch_from_dict", "write_patch_svg", "write_patch_png",
           "MAX_SVG_TILES", "MAX_PNG_PX"]

PATCH_FORMAT = "tilesolve/substitution-patch"
VERSIONS = frozenset({1})
#: Largest patch drawn as SVG (a polygon element per tile); larger ones belong in a PNG.
MAX_SVG_TILES = 200_000
#: Longest side of a PNG picture in pixels.
MAX_PNG_PX = 8192

_KEYS = {"format", "version", "kind", "steps", "region", "grid", "types", "vertices", "counts", "status", "method",
         "solver", "seed", "time_s", "reason", "notes", "stats", "created_by", "comment"}


def _array(a: np.ndarray):
    return encode_array(a) if a.size > COMPACT_MIN_CELLS else np.asarray(a, dtype=np.int64)


def patch_to_dict(problem: SubstitutionProblem, solution: Solution) -> dict:
    """The JSON document of a patch."""
    doc = {"format": PATCH_FORMAT, "version": 1, "kind": problem.kind, "steps": problem.steps,
           "region": list(problem.region) if problem.region is not None else None, "grid": GRIDS[problem.kind]}
    patch = solution.tiling
    if patch is not None:
        doc.update(types=_array(np.asarray(patch.types)), vertices=_array(np.asarray(patch.vertices)),
                   counts=patch.counts())
    doc.update(provenance_to_dict(solution))
    return doc


def patch_from_dict(doc: dict, source: str) -> tuple[SubstitutionProblem, Solution]:
    """Problem and solution of a document; one-line :class:`InvalidProblem` naming ``source`` and the field."""
    check_document(doc, source, {PATCH_FORMAT: VERSIONS})
    extra = set(doc) - _KEYS
    if extra:
        raise InvalidProblem(f"{source}: unknown field {sorted(extra)[0]!r}")
    kind = doc.get("kind")
    if kind not in GRIDS:
        raise InvalidProblem(f"{source}: 'kind' must be one of {', '.join(GRIDS)}, got {kind!r}")
    if doc.get("grid") != GRIDS[kind]:
        raise InvalidProblem(f"{source}: 'grid' must be {GRIDS[kind]!r} for {kind}, got {doc.get('grid')!r}")
    region = doc.get("region")
    if region is not None and (not isinstance(region, list) or len(region) != 4):
        raise InvalidProblem(f"{source}: 'region' must be a list x0, y0, width, height")
    try:
        problem = SubstitutionProblem(kind, doc.get("steps"), tuple(region) if region is not None else None)
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: {exc}") from None
    patch = None
    if "types" in doc or "vertices" in doc:
        types = decode_array(doc.get("types"), "types", source, ndim=1)
        verts = decode_array(doc.get("vertices"), "vertices", source, ndim=3)
        dims = 4 if GRIDS[kind] == "zeta5" else 2
        if verts.ndim != 3 or verts.shape[0] != len(types) or verts.shape[2] != dims:
            raise InvalidProblem(f"{source}: 'vertices' must have shape [tiles, corners, {dims}] with one row per "
                                 f"type, got {list(verts.shape)}")
        patch = Patch(kind, types.astype(np.int8), verts.astype(np.int64))
    return problem, solution_from_provenance(doc, source, patch, what="vertices")


def _colours(patch: Patch) -> list[str]:
    return [PALETTE[1], PALETTE[0]] if patch.kind in ("p3", "p2") else [PALETTE[4]]


def _frame(xy: np.ndarray, px: int) -> tuple[float, np.ndarray, np.ndarray]:
    lo, hi = xy.reshape(-1, 2).min(axis=0), xy.reshape(-1, 2).max(axis=0)
    span = max(float((hi - lo).max()), 1e-9)
    scale = px / span
    return scale, lo, hi


def write_patch_svg(path, patch: Patch, *, title: str | None = None, px: int = 800) -> None:
    """An SVG of the patch, ``px`` on its longer side (svgwrite), y up, under an optional title."""
    if patch.n_tiles > MAX_SVG_TILES:
        raise InvalidProblem(f"a patch of {patch.n_tiles:,} tiles is too large for SVG (at most "
                             f"{MAX_SVG_TILES:,}); draw it as PNG")
    xy = patch.xy()
    scale, lo, hi = _frame(xy, px)
    w, h = (hi - lo) * scale
    dwg, (ox, oy) = titled_canvas(float(w), float(h), title)
    colours = _colours(patch)
    stroke = max(0.3, min(1.0, scale / 20))
    for t, poly in zip(patch.types.tolist(), xy):
        pts = [(float((x - lo[0]) * scale + ox), float((hi[1] - y) * scale + oy)) for x, y in poly]
        dwg.add(dwg.polygon(pts, fill=colours[t % len(colours)], stroke="#333333", stroke_width=stroke))
    with atomic_write(path) as f:
        f.write(dwg.tostring())


def write_patch_png(path, patch: Patch, *, px: int = 1024, title: str | None = None) -> None:
    """A PNG of the patch, ``px`` pixels on its longer side (Pillow), y up, with an optional title under it."""
    from PIL import Image, ImageDraw

    from tilesolve.io.png import captioned

    if not 16 <= px <= MAX_PNG_PX:
        raise InvalidProblem(f"the picture's size must be 16..{MAX_PNG_PX} pixels, got {px}")
    xy = patch.xy()
    scale, lo, hi = _frame(xy, px - 4)
    w, h = ((hi - lo) * scale + 4).astype(int) + 1
    img = Image.new("RGB", (int(w), int(h)), "white")
    draw = ImageDraw.Draw(img)
    colours = _colours(patch)
    outline = "#333333" if scale >= 4 else None
    px_xy = np.stack([(xy[..., 0] - lo[0]) * scale + 2, (hi[1] - xy[..., 1]) * scale + 2], axis=-1)
    for t, poly in zip(patch.types.tolist(), px_xy.tolist()):
        draw.polygon([tuple(p) for p in poly], fill=colours[t % len(colours)], outline=outline)
    buf = io.BytesIO()
    captioned(img, [title] if title else []).save(buf, format="PNG")
    write_bytes_atomic(path, buf.getvalue())
