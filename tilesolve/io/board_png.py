"""PNG pictures of brick walls on boards: bricks and mortar at any size (brick paper, Def. 9).

A brick Wang tile holds one junction of mortar lines: a W_H tile a horizontal line through the
cell at the height of its W (= E) leg and two half vertical lines at its N and S legs, a W_V
tile the converse (the geometry of :mod:`tilesolve.io.svg_board`: colour ``c`` of ``#C`` lies at
``(c + 1) / (#C + 1)`` of the side). The junction is the top-left corner of exactly one brick,
so every brick is the four corner regions that meet around it: the cell's bottom-right region,
its right neighbour's bottom-left, the cell below's top-right and the one below-right's top-left.
A brick is coloured by its id, the lattice point at that junction, with the bricks' one colour hash
(:func:`tilesolve.model.brick_colour.brick_colour_index`, the same as the wall maps' ``id`` map), in
the plane's coordinates when the tiling is a window of the plane, so neighbouring windows of one
wall agree.
No union-find: every pixel finds its brick from its cell and corner region, in numpy.

Examples
--------
>>> from tilesolve.model.board import Board, BoardProblem, WangTileSet
>>> from tilesolve.constructive.brick import solve_linear
>>> p = BoardProblem(Board.rect(6, 4), WangTileSet.brick(3))
>>> img = brick_image(p, solve_linear(p).tiling, scale=8)
>>> img.size, img.mode
((48, 32), 'P')
"""

from __future__ import annotations

import numpy as np

from tilesolve.io.wall_png import MORTAR, N_BRICK_COLOURS, brick_palette
from tilesolve.model.brick_colour import brick_colour_index
from tilesolve.model.window import Window

__all__ = ["brick_image", "brick_scale", "picture_palette", "HOLE"]

#: Palette index of holes (pixels of no cell).
HOLE = N_BRICK_COLOURS
_HOLE_RGB = (244, 244, 244)
_TARGET_PX = 1024  # longest side of the picture


def brick_scale(rows: int, cols: int) -> int:
    """Pixels per cell of a ``rows x cols`` brick picture: the picture about 1,024 px wide,
    each cell at least 4 px (a brick and its mortar stay visible) and at most 24."""
    return int(min(24, max(4, _TARGET_PX // max(rows, cols, 1))))


def picture_palette(colours=None) -> list[tuple[int, int, int]]:
    """The 256 RGB entries of a brick picture's palette: brick colours ``0 .. N_BRICK_COLOURS - 1``,
    :data:`HOLE`, mortar.

    ``colours`` (a list of ``(r, g, b)``, e.g. a palette chosen in the studio) replaces the brick
    colours: brick colour ``i`` becomes ``colours[i % len(colours)]``; without it they are
    :func:`tilesolve.io.wall_png.brick_palette`'s. Holes and mortar keep their colours.

    >>> pal = picture_palette([(1, 2, 3), (4, 5, 6)])
    >>> pal[0], pal[1], pal[2], pal[HOLE], len(pal)
    ((1, 2, 3), (4, 5, 6), (1, 2, 3), (244, 244, 244), 256)
    """
    palette = brick_palette()
    if colours is not None:
        colours = [tuple(int(c) for c in rgb) for rgb in colours]
        if not colours:
            raise ValueError("a brick palette needs at least one colour")
        palette[:N_BRICK_COLOURS] = [colours[i % len(colours)] for i in range(N_BRICK_COLOURS)]
    palette[HOLE] = _HOLE_RGB
    return palette


def _patterns(legs: np.ndarray, k: int, s: int) -> np.ndarray:
    """``(m, s, s)`` uint8 of each brick tile in ``legs`` (``(m, 4)`` colours N, E, S, W of
    ``k``): the corner region of each pixel (TL 0, TR 1, BL 2, BR 3) or 4 on a mortar line."""
    pos = np.clip(np.rint((legs + 1) / (k + 1) * s).astype(np.int64), 1, s - 1)  # N, E, S, W in pixels
    n_, e_, s_, w_ = (pos[:, i, None, None] for i in range(4))
    horizontal = (legs[:, 3] == legs[:, 1])[:, None, None]  # W_H: W = E
    v = np.arange(s)[None, :, None]  # pixel row in the cell
    u = np.arange(s)[None, None, :]  # pixel column
    th = max(1, round(s / 10))
    on = lambda coord, p: (coord >= p - th // 2) & (coord < p - th // 2 + th)  # noqa: E731 - a line's pixels
    top = np.where(horizontal, v < w_, np.where(u < n_, v < w_, v < e_))
    left = np.where(horizontal, np.where(v < w_, u < n_, u < s_), u < n_)
    mortar = np.where(horizontal, on(v, w_) | np.where(v < w_, on(u, n_), on(u, s_)),
                      on(u, n_) | np.where(u < n_, on(v, w_), on(v, e_)))
    return np.where(mortar, 4, 2 * ~top + ~left).astype(np.uint8)  # ~ on bools is not


def brick_image(problem, tiling, *, window: Window | None = None, scale: int | None = None, colours=None):
    """A palette :class:`PIL.Image.Image` of a brick tiling of ``problem.board``.

    Parameters
    ----------
    problem : BoardProblem
        A board with a brick tile set (``problem.tileset.is_brick``).
    tiling : array_like
        ``(n_cells, 4)`` leg colours N, E, S, W.
    window : Window, optional
        Where the tiling lies in the plane: bricks are coloured by their plane position.
    scale : int, optional
        Pixels per cell (:func:`brick_scale` by default).
    colours : list of (int, int, int), optional
        The bricks' colours (:func:`picture_palette`); by default the wall pictures' own.
    """
    from PIL import Image

    b = problem.board
    t = np.asarray(tiling, dtype=np.int64).reshape(-1, 4)
    lab = np.asarray(b.labels, dtype=np.int64)
    rows, cols = int(lab[:, 0].max()) + 1, int(lab[:, 1].max()) + 1
    s = brick_scale(rows, cols) if scale is None else int(scale)
    k = problem.n_colors
    # a cell's pixels depend on its legs only: one pattern per tile (legs as one number in base k)
    _, first, tile_of = np.unique(((t[:, 0] * k + t[:, 1]) * k + t[:, 2]) * k + t[:, 3], return_index=True,
                                  return_inverse=True)
    patterns = _patterns(t[first], k, s)  # (tiles, s, s): region 0..3 or 4 for mortar
    # the brick of a corner region TL, TR, BL, BR has its top-left corner in the cell up (top
    # regions) and left (left regions) of it: one colour per cell and region, then per pixel
    arow = lab[:, 0, None] - np.array([1, 1, 0, 0])
    acol = lab[:, 1, None] - np.array([1, 0, 1, 0])
    if window is not None:
        x, y = window.x0 + acol, (window.y0 + window.height - 1 - arow if window.y_up else window.y0 + arow)
    else:
        x, y = acol, -arow
    # the brick's id: the lattice point at that cell's SE corner (y north, as the wall's), the SW
    # corner of cell (x + 1, y)
    colour = brick_colour_index(x + 1, y, N_BRICK_COLOURS).astype(np.uint8)  # (n, 4)
    colour = np.concatenate([colour, np.full((len(t), 1), MORTAR, np.uint8)], axis=1)
    region = patterns[tile_of.reshape(-1)]
    idx = np.take_along_axis(colour, region.reshape(len(t), -1), axis=1).reshape(region.shape)
    pixels = np.full((rows, s, cols, s), HOLE, dtype=np.uint8)
    pixels[lab[:, 0], :, lab[:, 1], :] = idx
    img = Image.fromarray(pixels.reshape(rows * s, cols * s))
    palette = picture_palette(colours)
    img.putpalette([c for rgb in palette for c in rgb])
    return img
