"""PNG files of brick-wall maps, streamed band by band (004 §3.2, Fig. 9, 10, 19).

The pixels come from :mod:`tilesolve.constructive.wall_maps` (via
:func:`tilesolve.families.wall_render.write_wall_png`, which computes one band of cell rows at a time);
this module only knows how a map becomes PNG bytes:

``id``
    8-bit palette: one of :data:`N_BRICK_COLOURS` colours per brick id, dark mortar lines
    (palette index :data:`MORTAR`) where a pixel lies within a line's half width of a brick edge;
``distance``
    the distance to the brick's nearest edge, 0 on the edge, 255 from :data:`DISTANCE_FULL`
    cells inwards (the band's values), written in colour: a perceptual colour map over the
    whole range (:data:`DISTANCE_COLOURS`, dark violet on the edges to yellow inside), with a
    colour bar under the picture that reads the scale;
``uv``
    8-bit RGB: red = ``u``, green = ``v`` (the brick's Cartesian parameterization, Fig. 10
    left), blue 0.

Lines of ``caption`` are written under the picture (:func:`tilesolve.io.png.caption_mask`). The file is written row by row from an iterator of bands (:func:`tilesolve.io.png.write_packed_rows`),
atomically (a temporary file renamed at the end): memory is one band, whatever the picture's size.

Examples
--------
>>> import numpy as np, os, tempfile
>>> path = os.path.join(tempfile.mkdtemp(), "g.png")
>>> write_bands_png(path, 3, 2, iter([np.zeros((1, 3), np.uint8), np.full((1, 3), 255, np.uint8)]), "distance")
>>> from PIL import Image
>>> with Image.open(path) as img:
...     img.size, img.mode
((3, 2), 'RGB')
"""

from __future__ import annotations

import colorsys
import os
from typing import Iterable

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.io.atomic import atomic_write
from tilesolve.io.png import caption_mask, caption_rows, write_packed_rows

__all__ = ["N_BRICK_COLOURS", "MORTAR", "DISTANCE_FULL", "DISTANCE_COLOURS", "MAP_KINDS", "brick_palette",
           "map_pixels", "distance_legend", "write_bands_png"]

#: Brick colours of the ``id`` map (palette indices ``0 .. N_BRICK_COLOURS - 1``).
N_BRICK_COLOURS = 254
#: Palette index of mortar pixels in the ``id`` map.
MORTAR = 255
#: Distance (cells) drawn as full white in the ``distance`` map.
DISTANCE_FULL = 0.5
#: Map kind -> PNG colour planes (1: palette or grey, 3: RGB).
MAP_KINDS = {"id": 1, "distance": 1, "uv": 3}
_MORTAR_RGB = (58, 52, 48)
_WHITE, _INK = (255, 255, 255), (51, 51, 51)
#: viridis (van der Walt & Smith), sampled at nine points: dark to light, readable in grey
#: and by colour-blind viewers.
_VIRIDIS = ((68, 1, 84), (71, 44, 122), (59, 81, 139), (44, 113, 142), (33, 144, 141), (39, 173, 129),
            (92, 200, 99), (170, 220, 50), (253, 231, 37))


def _distance_colours() -> np.ndarray:
    """``(256, 3)`` RGB of each distance value ``0..255`` (:data:`DISTANCE_COLOURS`)."""
    t = np.arange(256) / 255.0 * (len(_VIRIDIS) - 1)
    anchors = np.asarray(_VIRIDIS, dtype=np.float64)
    return np.stack([np.interp(t, np.arange(len(_VIRIDIS)), anchors[:, k]) for k in range(3)],
                    axis=1).round().astype(np.uint8)


#: RGB of each ``distance`` map value (viridis, from the edge to :data:`DISTANCE_FULL`).
DISTANCE_COLOURS = _distance_colours()


def brick_palette() -> list[tuple[int, int, int]]:
    """The 256-entry palette of the ``id`` map: brick colours spread by the golden ratio over
    hue (as the SVG's bricks, :mod:`tilesolve.io.svg_board`), then white (the background of a
    caption) and the mortar colour."""
    pal = []
    for i in range(N_BRICK_COLOURS):
        hue = (0.07 + 0.618034 * i) % 1.0
        r, g, b = colorsys.hls_to_rgb(hue, 0.5 + 0.1 * ((i * 7) % 3 - 1), 0.45)
        pal.append((round(r * 255), round(g * 255), round(b * 255)))
    return pal + [_WHITE, _MORTAR_RGB]  # white (under a caption), then the mortar


def map_pixels(kind: str, *, colour_index=None, distance=None, u=None, v=None, mortar_px: float = 0.0,
               ppc: int = 1) -> np.ndarray:
    """PNG pixel values of one band of a map (``uint8``, ``(H, W)`` or ``(H, W, 3)``).

    Parameters
    ----------
    kind : {"id", "distance", "uv"}
    colour_index : numpy.ndarray of int, optional
        Brick colour index ``0 .. N_BRICK_COLOURS - 1`` per pixel (``id``).
    distance : numpy.ndarray of float, optional
        Distance to the brick's edges in cells (``id`` mortar, ``distance``).
    u, v : numpy.ndarray of float, optional
        Cartesian UV in ``[0, 1]`` (``uv``).
    mortar_px : float
        Half width of the mortar lines in pixels (``id``; 0: none).
    ppc : int
        Pixels per cell (converts ``distance`` to pixels for the mortar).
    """
    if kind == "id":
        px = np.asarray(colour_index).astype(np.uint8)
        if mortar_px > 0:
            px[np.asarray(distance) * ppc < mortar_px] = MORTAR
        return px
    if kind == "distance":
        return np.minimum(np.asarray(distance, dtype=np.float64) * (255.0 / DISTANCE_FULL) + 0.5, 255).astype(np.uint8)
    if kind == "uv":
        out = np.zeros(np.shape(u) + (3,), dtype=np.uint8)
        out[..., 0] = np.clip(np.asarray(u) * 255 + 0.5, 0, 255)
        out[..., 1] = np.clip(np.asarray(v) * 255 + 0.5, 0, 255)
        return out
    raise InvalidProblem(f"unknown wall map {kind!r}; choose one of {', '.join(MAP_KINDS)}")


def distance_legend(width: int) -> np.ndarray:
    """``(h, width, 3)`` RGB rows under a ``distance`` map: its colour bar (edge on the left,
    :data:`DISTANCE_FULL` cells and more on the right) and the line that reads it; none for a
    picture under 64 px wide."""
    if width < 64:
        return np.zeros((0, width, 3), dtype=np.uint8)
    bar = np.full((14, width, 3), 255, dtype=np.uint8)
    values = np.linspace(0, 255, width - 8).round().astype(np.uint8)
    bar[4:14, 4:-4] = DISTANCE_COLOURS[values][None]
    text = caption_rows(caption_mask([f"colour: distance to the brick's edge, 0 (left) to {DISTANCE_FULL:g} cell "
                                      "or more (right)"], width), _WHITE, _INK)
    return np.concatenate([bar, text])


def write_bands_png(path: str | os.PathLike, width: int, height: int, bands: Iterable[np.ndarray], kind: str, *,
                    compression: int = 6, caption=()) -> None:
    """Write ``height`` pixel rows, given as consecutive bands (arrays of :func:`map_pixels`), as a PNG,
    with the lines ``caption`` under them (and a ``distance`` map's colour bar,
    :func:`distance_legend`).

    Only one band is in memory at a time; the file appears (atomically) once every row is
    written, and a failure or Ctrl-C leaves no file.
    """
    import png

    if kind not in MAP_KINDS:
        raise InvalidProblem(f"unknown wall map {kind!r}; choose one of {', '.join(MAP_KINDS)}")
    mask = caption_mask(caption, width)
    if kind == "id":
        below = caption_rows(mask, N_BRICK_COLOURS, MORTAR)  # white, and the mortar's dark brown
        writer = png.Writer(width, height + len(below), palette=brick_palette(), bitdepth=8, compression=compression)
    else:
        below = caption_rows(mask, _WHITE, _INK)
        if kind == "distance":
            below = np.concatenate([distance_legend(width), below])
        writer = png.Writer(width, height + len(below), greyscale=False, bitdepth=8, compression=compression)

    def rows():
        n = 0
        for band in bands:
            flat = np.ascontiguousarray(band).reshape(band.shape[0], -1)
            if flat.shape[1] != width * MAP_KINDS[kind]:
                raise InvalidProblem(f"a band of {flat.shape[1]} values per row does not fit a {width} px wide "
                                     f"{kind} map")
            n += flat.shape[0]
            yield from (DISTANCE_COLOURS[flat].reshape(flat.shape[0], -1) if kind == "distance" else flat)
        if n != height:
            raise InvalidProblem(f"the bands gave {n} pixel rows for a {height} px high picture")
        yield from below.reshape(len(below), -1) if len(below) else ()

    with atomic_write(path, "wb") as f:
        write_packed_rows(writer, f, rows())
