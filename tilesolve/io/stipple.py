"""Importance sampling's files: the density image read, the stippled picture and the
periodogram pictures written (class notes Part V, stippling; Part IV, spectra).

* :func:`read_density`: a picture file (any format Pillow reads) as a density, its darkness
  ``1 - grey / 255``: black draws the most samples, white none.
* :func:`stipple_svg` / :func:`write_stipple`: the samples as black dots on white, sized by the
  density where they sit (SVG with svgwrite, PNG with Pillow).
* :func:`write_periodograms_png`: 2-D periodograms side by side, log scale, the spectra in
  which a tiling's structure shows as peaks.
* :func:`stipple_to_dict` / :func:`stipple_from_dict` / :func:`dump`: the samples as a file,
  ``tilesolve/stipple`` (version 2), with everything they are made from::

      {
        "format": "tilesolve/stipple", "version": 2,
        "method": "penrose", "points": 20000,       # the sampler, about how many samples
        "tile": "x-pentomino", "lloyd": 4, "jitter": true, "seed": 1,
        "correct": true,                            # the polyomino correction table asked for
        "image": "radial",                          # the density's name, for people
        "density": [[v, ...], ...],                 # the density sampled: a value a pixel,
                                                    # rows from the top (darkness, 0 white)
        "samples": [[x, y], ...]                    # y up, the image's longer side 1
      }

  ``tilesolve verify`` checks the samples against the embedded density (counts of blocks,
  :func:`tilesolve.verify.importance.importance_violations`) and samples it again with the
  seed: the file's samples must be those, exactly (:class:`Samples`). Version 1 (before the
  polyomino sampler's correction table, Ostromoukhov 2007) has no ``correct`` and is read as
  ``correct: false``, the sampler it was written by.

>>> import numpy as np
>>> from tilesolve.model.importance import builtin_density
>>> text = stipple_svg(np.array([[0.5, 0.5]]), builtin_density("flat", 4), "one dot")
>>> text.startswith("<svg") and text.count("<path") == 1 and text.count("M") == 1
True
"""

from __future__ import annotations

import json
import math
import os
from dataclasses import dataclass

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.io.atomic import atomic_write
from tilesolve.io.images import read_rgba
from tilesolve.io.jsonio import check_document
from tilesolve.io.poisson_json import read_points, read_seed
from tilesolve.model.importance import MAX_PIXELS, MAX_POINTS, TEST_IMAGES, DensityMap, ImportanceProblem
from tilesolve.model.solution import Solution, Status

__all__ = ["MAX_STIPPLE_POINTS", "FORMAT", "VERSIONS", "Samples", "read_density", "dot_radii", "stipple_svg",
           "write_stipple", "write_periodograms_png", "stipple_to_dict", "stipple_from_dict", "dump"]

FORMAT = "tilesolve/stipple"
VERSIONS = frozenset({1, 2})
_KEYS_V1 = {"format", "version", "method", "points", "tile", "lloyd", "jitter", "seed", "image", "density", "samples"}
_KEYS = _KEYS_V1 | {"correct"}


@dataclass(frozen=True, eq=False)
class Samples:
    """The samples of an importance problem: ``points``, ``(n, 2)`` (y up, the image's longer
    side 1), and the ``seed`` they claim to be sampled with (``None``: no claim; a file states
    one, and ``tilesolve verify`` samples again with it)."""

    points: np.ndarray
    seed: int | None = None

#: Most dots a stippled picture draws (an SVG of more is too slow to open).
MAX_STIPPLE_POINTS = 200_000
_SIDE = 800  # pixels of the picture's longer side


def read_density(path: str | os.PathLike) -> DensityMap:
    """The darkness of a picture file as a density, transparent pixels white paper (one line of
    error for a file that is not a readable picture, or one of more than
    :data:`~tilesolve.model.importance.MAX_PIXELS` pixels: :func:`tilesolve.io.images.read_rgba`)."""
    from PIL import Image

    rgba = read_rgba(path, MAX_PIXELS)
    img = Image.fromarray(rgba, "RGBA")
    if (rgba[..., 3] < 255).any():
        img = Image.alpha_composite(Image.new("RGBA", img.size, (255, 255, 255, 255)), img)
    grey = np.asarray(img.convert("L"), dtype=np.float64)
    name = os.path.basename(os.fspath(path))
    if name in TEST_IMAGES:  # a file named like a built-in image is not that image (verify checks those)
        name = os.path.join(".", name)
    return DensityMap(1.0 - grey / 255.0, name)


def dot_radii(points: np.ndarray, density: DensityMap) -> np.ndarray:
    """Each dot's radius in domain units: ``r0 (0.45 + 0.5 d / d_max)``, ``d`` the density under
    the dot, ``r0 = sqrt(mean(d) W H / (pi n))`` the radius whose ``n`` disjoint dots would cover
    the mean darkness (so the dots' ink roughly follows the image's tone, larger where it is dark,
    covering about 90% of the darkest parts)."""
    v = density.values
    n = max(len(points), 1)
    r0 = np.sqrt(v.mean() * density.width * density.height / (np.pi * n))
    col = np.clip((points[:, 0] / density.pixel).astype(np.int64), 0, density.cols - 1)
    row = np.clip(((density.height - points[:, 1]) / density.pixel).astype(np.int64), 0, density.rows - 1)
    return r0 * (0.45 + 0.5 * v[row, col] / v.max())


def _check(n: int) -> None:
    # The samplers give *about* the points asked for (a few more or fewer), and an ask of at most
    # MAX_STIPPLE_POINTS is allowed: the picture takes their overshoot too.
    if n > MAX_STIPPLE_POINTS + MAX_STIPPLE_POINTS // 20:
        raise InvalidProblem(f"a stippled picture draws at most {MAX_STIPPLE_POINTS:,} points, not {n:,}")


def stipple_svg(points: np.ndarray, density: DensityMap, caption: str) -> str:
    """SVG text: black dots on white, the longer side 800 pixels, a caption below."""
    import svgwrite

    _check(len(points))
    px = _SIDE / max(density.width, density.height)
    w, h = density.width * px, density.height * px
    dwg = svgwrite.Drawing(size=(f"{w:.0f}", f"{h + 24:.0f}"), profile="full", debug=False)
    dwg.add(dwg.rect((0, 0), (w, h + 24), fill="white"))
    if len(points):
        # the dots as one path of circles (two arcs each): svgwrite builds one element instead of
        # one per dot, 20 times faster for the 200,000 dots a picture may hold
        r = np.round(dot_radii(points, density) * px, 2)
        x, y = np.round(points[:, 0] * px - r, 2), np.round(h - points[:, 1] * px, 2)
        d = "".join(f"M{a:g},{b:g}a{c:g},{c:g} 0 1,0 {2 * c:g},0a{c:g},{c:g} 0 1,0 {-2 * c:g},0"
                    for a, b, c in zip(x.tolist(), y.tolist(), r.tolist()))
        dwg.add(dwg.path(d=d, fill="black"))
    dwg.add(dwg.text(caption, insert=(4, h + 17), font_size="12px", font_family="sans-serif", fill="#333333"))
    return dwg.tostring()


def write_stipple(path: str | os.PathLike, points: np.ndarray, density: DensityMap, caption: str, fmt: str) -> None:
    """The stippled picture as ``fmt`` (``"svg"`` or ``"png"``, the PNG drawn at 2x and
    averaged down for smooth dots); y grows upwards in the picture."""
    if fmt == "svg":
        text = stipple_svg(points, density, caption)
        with atomic_write(path) as f:
            f.write(text)
        return
    from PIL import Image, ImageDraw

    _check(len(points))
    px = 2 * _SIDE / max(density.width, density.height)
    w, h = int(round(density.width * px)), int(round(density.height * px))
    img = Image.new("L", (w, h), 255)
    draw = ImageDraw.Draw(img)
    for (x, y), r in zip(points.tolist(), (dot_radii(points, density) * px).tolist()):
        cx, cy = x * px, h - y * px
        draw.ellipse([cx - r, cy - r, cx + r, cy + r], fill=0)
    small = img.resize((w // 2, h // 2), Image.LANCZOS)
    out = Image.new("L", (w // 2, h // 2 + 20), 255)
    out.paste(small, (0, 0))
    ImageDraw.Draw(out).text((4, h // 2 + 4), caption, fill=51)
    with atomic_write(path, "wb", encoding=None) as f:
        out.save(f, format="PNG")


def write_periodograms_png(path: str | os.PathLike, panels: list[tuple[str, np.ndarray]], title: str) -> None:
    """2-D periodograms (each ``(2k + 1, 2k + 1)``, zero frequency at the centre) side by side,
    ``log10`` of the power mapped to grey (white 0.01, black 100), each with its label."""
    from PIL import Image, ImageDraw

    if not panels:
        raise InvalidProblem("no periodogram to draw")
    size = 320
    img = Image.new("L", (len(panels) * (size + 10) + 10, size + 50), 255)
    draw = ImageDraw.Draw(img)
    draw.text((10, 6), title, fill=0)
    for i, (label, power) in enumerate(panels):
        grey = 255 - np.clip((np.log10(np.maximum(power, 1e-12)) + 2) / 4, 0, 1) * 255
        tile = Image.fromarray(grey.T[::-1].astype(np.uint8), "L").resize((size, size), Image.NEAREST)
        img.paste(tile, (10 + i * (size + 10), 22))
        draw.text((10 + i * (size + 10), size + 28), label, fill=0)
    with atomic_write(path, "wb", encoding=None) as f:
        img.save(f, format="PNG")


def stipple_to_dict(problem: ImportanceProblem, solution: Solution) -> dict:
    """The document of a stipple (``solution.tiling`` is the :class:`Samples`; the seed is the
    solution's)."""
    return {"format": FORMAT, "version": 2, "method": problem.method, "points": problem.points, "tile": problem.tile,
            "lloyd": problem.lloyd, "jitter": bool(problem.jitter), "correct": bool(problem.correct),
            "seed": solution.seed,
            "image": problem.density.name, "density": problem.density.values,
            "samples": np.asarray(solution.tiling.points, dtype=np.float64).reshape(-1, 2)}


def _density(value, name, source: str) -> DensityMap:
    if not (isinstance(value, list) and value and isinstance(value[0], list) and value[0]
            and len(value) * len(value[0]) <= MAX_PIXELS and all(
                isinstance(r, list) and len(r) == len(value[0]) and all(
                    isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) and v >= 0
                    for v in r) for r in value)):
        raise InvalidProblem(f"{source}: 'density' must be equal rows of non-negative numbers, {MAX_PIXELS:,} at most")
    try:
        return DensityMap(np.array(value, dtype=np.float64), name if isinstance(name, str) else "image")
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: {exc}") from None


def stipple_from_dict(doc: dict, source: str = "<document>") -> tuple[ImportanceProblem, Solution]:
    """Read :func:`stipple_to_dict`'s document: the problem (its density embedded) and the
    :class:`Samples` with their seed; one-line errors naming ``source`` and the field. Version 1
    has no ``correct`` field and is read as ``correct=False`` (it was sampled without the table);
    version 2 states it."""
    check_document(doc, source, {FORMAT: VERSIONS})
    v1 = doc["version"] == 1
    check_document(doc, source, {FORMAT: VERSIONS}, fields=_KEYS_V1 if v1 else _KEYS,
                   required=("method", "points", "density", "samples", "seed") + (() if v1 else ("correct",)))
    for key in ("jitter", "correct"):
        if not isinstance(doc.get(key, False), bool):
            raise InvalidProblem(f"{source}: '{key}' must be true or false, got {doc[key]!r}")
    name = doc.get("image", "image")
    if not isinstance(name, str):
        raise InvalidProblem(f"{source}: 'image' must be the density's name, a string, got {name!r}")
    density = _density(doc["density"], name, source)
    try:
        problem = ImportanceProblem(density, doc["points"], doc["method"], doc.get("tile", "chair"),
                                    doc.get("lloyd", 0), doc.get("jitter", False), doc.get("correct", False))
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: {exc}") from None
    seed = read_seed(doc, source)
    if seed is None:
        raise InvalidProblem(f"{source}: a stipple file states the seed it was sampled with, not null")
    points = read_points(doc["samples"], "samples", source, 2 * MAX_POINTS)
    return problem, Solution(Status.SAT, Samples(points, seed), method=problem.method, seed=seed)


def dump(doc: dict) -> str:
    """JSON text: a row of the density a line, a sample a line (floats written to round-trip exactly)."""
    head = {k: v for k, v in doc.items() if k not in ("density", "samples")}
    text = json.dumps(head, indent=2)[:-2]
    rows = np.asarray(doc["density"], dtype=np.float64).tolist()
    text += ',\n  "density": [' + ",".join("\n    [" + ", ".join(map(repr, r)) + "]" for r in rows) + "\n  ]"
    pts = np.asarray(doc["samples"], dtype=np.float64).reshape(-1, 2).tolist()
    text += ',\n  "samples": [' + ",".join(f"\n    [{x!r}, {y!r}]" for x, y in pts) + ("\n  ]" if pts else "]")
    return text + "\n}\n"
