"""Pictures of procedural brick walls of any size: brick ids, distance to the edges, UV (004 §3.2).

A window of the infinite procedural wall (:func:`tilesolve.constructive.walls.wall_window`)
is drawn as bricks (004 §3.2, Fig. 9-10, 19): the bricks are merged from the edge structure
(:mod:`tilesolve.constructive.wall_maps`: every brick is the brick around one lattice vertex)
and written as one of three maps (:mod:`tilesolve.io.wall_png`):

``id``
    a colour per brick id (the vertex's absolute coordinates), mortar lines when cells are at
    least 4 px wide;
``distance``
    distance from each pixel to its brick's nearest edge;
``uv``
    the brick's Cartesian UV parameterization (Fig. 10, left).

:func:`write_wall_png` never holds the region: it computes a band of cell rows at a time
(the band and a one-cell halo from ``wall_window``, random access making the bands agree),
converts it to pixels and streams them to the file. Each band is also checked with the
board verifier (:func:`tilesolve.verify.board.board_violations`, line limits included) on
the band grown by ``max_line`` rows upwards, so that every vertical line crossing a band
border is seen whole once.

Examples
--------
>>> import os, tempfile
>>> path = os.path.join(tempfile.mkdtemp(), "w.png")
>>> rep = write_wall_png(path, (-5, 3, 12, 8), colors=3, max_line=2, seed=1, kind="uv", ppc=4)
>>> rep.size_px, rep.verified_cells
((48, 32), 96)
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Callable

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.families.walls import BandChecker, npd_problem
from tilesolve.progress import Progress, as_progress

__all__ = ["RenderReport", "write_wall_png", "wall_source", "wall_map_pixels", "default_ppc", "MAP_MIN_PPC", "BAND_PIXELS", "BAND_CELLS", "MAX_RENDER_PIXELS"]

#: Pixels computed per band (1 to 3 bytes each, written as they are made).
BAND_PIXELS = 1 << 22
#: Cells per band: the board verifier takes about 1 KiB a cell (its board and arrays).
BAND_CELLS = 1 << 18
#: Largest picture (pixels): streaming bounds memory, this bounds the time a render may take.
MAX_RENDER_PIXELS = 1 << 32
_TARGET_PX = 1024


@dataclass(frozen=True)
class RenderReport:
    """What :func:`write_wall_png` drew: picture size, cells, bands, verified cells, time."""

    size_px: tuple[int, int]
    cells: int
    bands: int
    verified_cells: int
    time_s: float


#: Fewest pixels per cell of a ``distance`` or ``uv`` map by default: at 1 or 2 pixels a cell,
#: the values inside a brick read as noise.
MAP_MIN_PPC = 8


def default_ppc(w: int, h: int) -> int:
    """Pixels per cell when none is given: about 1024 px on the longer side, 1 to 32."""
    return max(1, min(32, _TARGET_PX // max(int(w), int(h))))


def wall_map_pixels(legs_halo, kind: str, *, colors: int, ppc: int, origin: tuple[int, int],
                    compiled: bool = True) -> np.ndarray:
    """PNG pixel values (:func:`tilesolve.io.wall_png.map_pixels`) of the inner cells of a legs
    array with a one-cell halo.

    ``compiled`` runs the numba loop of :mod:`tilesolve.constructive._wall_map_kernels`;
    otherwise the numpy arrays of :func:`tilesolve.constructive.wall_maps.wall_maps` are built
    (the reference form; the same pixels).
    """
    from tilesolve.io.wall_png import DISTANCE_FULL, MAP_KINDS, MORTAR, N_BRICK_COLOURS, map_pixels

    if kind not in MAP_KINDS:
        raise InvalidProblem(f"unknown wall map {kind!r}; choose one of {', '.join(MAP_KINDS)}")
    mortar_px = max(0.5, ppc / 24) if ppc >= 4 else 0.0
    legs = np.ascontiguousarray(legs_halo, dtype=np.int8)
    if compiled:
        from tilesolve.constructive._wall_map_kernels import map_band

        rows, cols = legs.shape[0] - 2, legs.shape[1] - 2
        out = np.empty((rows * ppc, cols * ppc, MAP_KINDS[kind]), dtype=np.uint8)
        map_band(legs, int(colors), int(ppc), int(origin[0]), int(origin[1]), ("id", "distance", "uv").index(kind),
                 N_BRICK_COLOURS, MORTAR, float(mortar_px), float(DISTANCE_FULL), out)
        return out if kind == "uv" else out[..., 0]
    from tilesolve.constructive.wall_maps import wall_maps
    from tilesolve.model.brick_colour import brick_colour_index

    m = wall_maps(legs, colors, ppc, origin=origin)
    if kind == "id":
        return map_pixels("id", colour_index=brick_colour_index(m.vx, m.vy, N_BRICK_COLOURS), distance=m.distance,
                          mortar_px=mortar_px, ppc=ppc)
    return map_pixels(kind, distance=m.distance, u=m.u, v=m.v)


def wall_source(method: str, *, colors: int, max_line: int | None, seed: int,
                period: tuple[int, int] | None = None) -> Callable[[int, int, int, int], np.ndarray]:
    """``window(x0, y0, w, h) -> (h, w, 4)`` legs of an infinite wall, any window at any time.

    ``procedural``: :func:`tilesolve.constructive.walls.wall_window`. ``npd``: the repeatable
    wall of 004 App. A, one ``period = (width, height)`` solved once by the board family's
    ``npd`` route on a torus, then indexed (:func:`tilesolve.constructive.npd.periodic_window`),
    so that a window of any size costs the period's memory.
    """
    from tilesolve.constructive.walls import wall_window

    if method == "procedural":
        wall_window(0, 0, 1, 1, colors=colors, max_line=max_line, seed=seed)  # checks colours, n and seed first
        return lambda x0, y0, w, h: wall_window(x0, y0, w, h, colors=colors, max_line=max_line, seed=seed)
    if method != "npd":
        raise InvalidProblem(f"unknown wall method {method!r}; choose procedural or npd")
    from tilesolve.constructive.npd import periodic_window
    from tilesolve.errors import MethodNotApplicable
    from tilesolve.family import raise_if_interrupted, solve
    from tilesolve.model.board import MAX_BOARD_CELLS

    if max_line is None or period is None:
        raise InvalidProblem("the npd wall needs a line limit and a period")
    pw, ph = (int(v) for v in period)
    if pw * ph > MAX_BOARD_CELLS:
        raise InvalidProblem(f"the npd period {pw}x{ph} has {pw * ph:,} cells, more than the {MAX_BOARD_CELLS:,} "
                             "a board may have; choose a smaller period (the wall repeats it)")
    problem = npd_problem(pw, ph, max_line, n_colors=colors)
    sol = raise_if_interrupted(solve(problem, "npd", seed=seed))
    if not sol.status.has_tiling:
        raise MethodNotApplicable(f"no wall with lines <= {max_line} repeats with period {pw}x{ph} "
                                  f"({sol.status.value}{': ' + sol.reason if sol.reason else ''}); "
                                  "choose another period or method 'procedural'")
    legs = np.zeros((ph, pw, 4), dtype=np.int8)
    lab = problem.board.labels
    legs[lab[:, 0], lab[:, 1]] = sol.tiling
    return lambda x0, y0, w, h: periodic_window(legs, x0, y0, w, h)


def write_wall_png(path, region: tuple[int, int, int, int], *, colors: int = 3, max_line: int | None = None,
                   seed: int = 0, method: str = "procedural", period: tuple[int, int] | None = None,
                   kind: str = "id", ppc: int | None = None, verify: bool = True,
                   compression: int = 6, progress: Progress | bool = False, caption=()) -> RenderReport:
    """Draw the window ``region = (x0, y0, w, h)`` of an infinite wall as a PNG map, streamed.

    Parameters
    ----------
    path : str or os.PathLike
        The PNG file (written atomically).
    region : (int, int, int, int)
        Bottom-left cell ``(x0, y0)`` (``y`` north) and size ``w x h`` in cells; any size up
        to :data:`MAX_RENDER_PIXELS` pixels.
    colors, max_line, seed
        The wall (:func:`tilesolve.constructive.walls.wall_window`).
    method, period
        ``procedural`` (004 §4) or ``npd`` (App. A, repeating ``period = (width, height)``;
        default the region's size), see :func:`wall_source`.
    kind : {"id", "distance", "uv"}
        The map (module docstring).
    ppc : int, optional
        Pixels per cell side (default :func:`default_ppc`; for the ``distance`` and ``uv`` maps,
        whose values vary inside a cell, at least :data:`MAP_MIN_PPC` where the picture stays
        within :data:`MAX_RENDER_PIXELS`).
    verify : bool
        Check every band with the board verifier (module docstring); a violation is an
        :class:`~tilesolve.errors.InternalError` and no file is written.
    compression : int
        zlib level of the PNG (0-9).
    progress : Progress or bool
        Where the bands drawn are counted (:func:`tilesolve.progress.as_progress`).
    caption : sequence of str
        Lines written under the picture.

    Returns
    -------
    RenderReport
    """
    from tilesolve.constructive.hashes import LATTICE_BOUND, check_int
    from tilesolve.io.wall_png import MAP_KINDS, write_bands_png

    x0, y0 = check_int(region[0], "x0"), check_int(region[1], "y0")
    w, h = check_int(region[2], "width", 1), check_int(region[3], "height", 1)
    b = LATTICE_BOUND - 2
    if not (-b <= x0 and x0 + w <= b and -b <= y0 and y0 + h <= b):
        raise InvalidProblem(f"wall region [{x0}, {x0 + w}) x [{y0}, {y0 + h}) leaves the lattice the hashes "
                             "address (|coordinates| < 2**62, one cell of margin for the bricks around it)")
    if kind not in MAP_KINDS:
        raise InvalidProblem(f"unknown wall map {kind!r}; choose one of {', '.join(MAP_KINDS)}")
    if ppc is None:
        ppc = default_ppc(w, h)
        if kind != "id":  # as many as MAP_MIN_PPC where the pixel limit allows
            ppc = max(ppc, min(MAP_MIN_PPC, math.isqrt(MAX_RENDER_PIXELS // (w * h))))
    ppc = check_int(ppc, "pixels per cell", 1)
    width, height = w * ppc, h * ppc
    if width * height > MAX_RENDER_PIXELS:
        raise InvalidProblem(f"a {width:,} x {height:,} px picture is larger than the {MAX_RENDER_PIXELS:,} px limit; "
                             "lower the pixels per cell or the region")
    window = wall_source(method, colors=colors, max_line=max_line, seed=seed,
                         period=(w, h) if period is None else period)
    band = max(1, min(h, BAND_PIXELS // (w * ppc * ppc), BAND_CELLS // w))
    n_bands = -(-h // band)
    checker = BandChecker(colors, max_line) if verify else None
    t0 = time.perf_counter()
    state = {"verified": 0}

    def bands():
        for top in range(0, h, band):
            hh = min(band, h - top)
            yb = y0 + h - top - hh  # the band's bottom row (y north)
            legs = window(x0 - 1, yb - 1, w + 2, hh + 2)
            if checker is not None:
                state["verified"] += checker.check(legs[1:-1, 1:-1], f"the {method} wall of seed {seed}",
                                                   (x0, yb + hh - 1), last=top + hh >= h)
            yield wall_map_pixels(legs, kind, colors=colors, ppc=ppc, origin=(x0, yb))
            bar.advance()

    with as_progress(progress).task(f"PNG {width:,} x {height:,} px", total=n_bands, unit="band") as bar:
        write_bands_png(path, width, height, bands(), kind, compression=compression, caption=caption)
    return RenderReport((width, height), w * h, n_bands, state["verified"], time.perf_counter() - t0)
