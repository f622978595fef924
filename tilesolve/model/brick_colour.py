"""The one colour hash of bricks: a brick id (the lattice point of its vertex) to a palette index.

Every brick picture colours a brick by the same function of the brick's place in the plane, so
the same brick has the same colour in every window and every picture of one wall (004 Fig. 9 b:
"a color based on the brick id"): the board pictures (:func:`tilesolve.io.board_png.brick_image`,
the studio's view tiles), the ``id`` map (:func:`tilesolve.constructive.wall_maps.wall_maps` via
``tilesolve render wall-map``), its compiled loop (``_wall_map_kernels.colour_of_vertex``) and
the GPU wall shader's board look (:mod:`tilesolve.gpu.wall`, ``brick_index``). It lives in
``model`` because ``io`` and ``constructive`` both use it and neither may import the other.

A brick's id is the lattice point ``(X, Y)`` it holds (004 §3.1: each tile holds the corner
junction of four bricks; ``Y`` grows north): lattice point ``(X, Y)`` is the south-west corner of
cell ``(X, Y)``, so the brick whose top-left corner lies in cell ``(i, j)`` has id ``(i + 1, j)``.

Examples
--------
>>> import numpy as np
>>> brick_colour_index(np.array([0, 1, -1]), np.array([0, 0, 5]), 254).tolist()
[0, 224, 196]
"""

from __future__ import annotations

import numpy as np

__all__ = ["brick_colour_index", "SPLITMIX_X", "SPLITMIX_Y"]

#: Multipliers of the two coordinates before they are mixed (the golden-ratio increment of
#: splitmix64 and a constant of xxHash64; odd, so each is a bijection of 64-bit words).
SPLITMIX_X = 0x9E3779B97F4A7C15
SPLITMIX_Y = 0xC2B2AE3D27D4EB4F


def brick_colour_index(vx, vy, n: int) -> np.ndarray:
    """A colour index ``0 .. n-1`` per brick id ``(vx, vy)`` (int64 arrays or scalars, broadcast).

    ``z = vx * SPLITMIX_X ^ vy * SPLITMIX_Y`` on 64-bit words (two's complement), then the
    splitmix64 finaliser (Steele, Lea and Flood 2014, "Fast splittable pseudorandom number
    generators"; shifts 30, 27, 31), reduced to ``n`` by a multiply-shift of its high 32 bits
    (``(z >> 32) * n >> 32``): neighbouring bricks get unrelated colours, and a GPU computes the
    same with 32-bit words (:mod:`tilesolve.gpu.wall`).

    Parameters
    ----------
    vx, vy : array_like of int
        Brick ids: lattice points, ``vy`` growing north (module docstring).
    n : int
        Number of colours, ``1 <= n < 2**32``.

    Returns
    -------
    numpy.ndarray of int64
    """
    with np.errstate(over="ignore"):
        z = (np.asarray(vx, dtype=np.int64).astype(np.uint64) * np.uint64(SPLITMIX_X)
             ^ np.asarray(vy, dtype=np.int64).astype(np.uint64) * np.uint64(SPLITMIX_Y))
        z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
        z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
        z ^= z >> np.uint64(31)
    return ((z >> np.uint64(32)) * np.uint64(n) >> np.uint64(32)).astype(np.int64)
