"""The window that steers the square search ``"markov"`` of the aperiodic facade's SAT route.

The SAT engine (:mod:`tilesolve.engine.aperiodic_square`) takes the window as a callable, since
the constructive route lies above it; this module makes that callable for the built-in sets
with a Markov partition (:mod:`tilesolve.constructive.markov`).
"""

from __future__ import annotations

import functools
from typing import Callable

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.model.board import WangTileSet

__all__ = ["markov_set", "square_window", "steering"]


def markov_set(tileset: WangTileSet) -> str | None:
    """The name of the built-in tile set with a Markov partition whose tiles are ``tileset``'s
    (the same tiles in the same order, the order a window's indices follow), else ``None``.

    >>> from tilesolve.io.builtin_tilesets import load
    >>> markov_set(load("jeandel-rao")[0]), markov_set(load("kari-14")[0])
    ('jeandel-rao', None)
    """
    from tilesolve.constructive.markov import NAMES
    from tilesolve.io.builtin_tilesets import load

    tiles = np.asarray(tileset.tiles)
    for name in NAMES:
        ref = load(name)[0]
        if ref.n_colors == tileset.n_colors and np.array_equal(np.asarray(ref.tiles), tiles):
            return name
    return None


def square_window(name: str, seed: int, n: int) -> np.ndarray:
    """The ``n x n`` window ``Window(0, 0, n, n)`` of the Markov tiling ``name`` for ``seed``:
    tile indices of the built-in set, row 0 the top row (a square board's order)."""
    from tilesolve.constructive.markov import markov_window
    from tilesolve.model.window import Window

    return markov_window(name, Window(0, 0, n, n), seed).astype(np.int64)


def steering(tileset: WangTileSet, seed: int | None) -> Callable[[int], np.ndarray]:
    """The window callable for ``tileset`` (``n -> n x n`` grid; it pickles, for worker
    processes); raises :class:`InvalidProblem` for a set without a Markov partition."""
    name = markov_set(tileset)
    if name is None:
        raise InvalidProblem("the square search 'markov' takes a tile set with a Markov partition: the "
                             "built-in jeandel-rao or labbe-u19, its tiles in their order")
    return functools.partial(square_window, name, 0 if seed is None else seed)
