"""The studio's infinite views: one n x n window of a family's procedural plane as PNG
(:attr:`tilesolve.family.Form.window`), for pan and zoom, kept in an LRU cache; and for the
procedural wall, the GPU path's shaders that let the page draw the view itself (WebGL2).

A palette chosen on the page (``colours``: a list of RGB) recolours both: a brick picture's
bricks take the colours in turn (:func:`tilesolve.io.board_png.picture_palette`, the palette
texture of the wall's shaders too), another picture's tile ``k`` takes ``colours[k]`` (as the
page recolours its solved pictures)."""

from __future__ import annotations

import json
import threading
from collections import OrderedDict

from tilesolve import family
from tilesolve.errors import InvalidProblem, TilesolveError
from tilesolve.model.window import Window
from tilesolve.studio import worker

__all__ = ["Views", "VIEW_CACHE", "recolour"]

#: Most view tiles kept (an LRU of PNG bytes).
VIEW_CACHE = 512


def _square(data: bytes) -> bytes:
    """A view tile's PNG without the caption a picture carries under its (square) window: the
    page draws tiles edge to edge at one scale, so a tile is its window's pixels only."""
    import io

    from PIL import Image

    with Image.open(io.BytesIO(data)) as img:
        if img.height <= img.width:
            return data
        buf = io.BytesIO()
        img.crop((0, 0, img.width, img.width)).save(buf, format="PNG")
        return buf.getvalue()


def recolour(data: bytes, colours) -> bytes:
    """A view tile's PNG (a palette image, as every view's pictures are) in the chosen ``colours``
    (RGB triples): a brick picture's brick colours, entries ``0 .. N_BRICK_COLOURS - 1`` of its
    palette, become :func:`~tilesolve.io.board_png.picture_palette`'s; in another picture, a
    palette entry of tile ``k``'s colour (:func:`tilesolve.io.svg.tile_colour`) becomes
    ``colours[k]``. Only the palette changes: every pixel keeps its index."""
    import io

    from PIL import Image

    from tilesolve.io.board_png import picture_palette
    from tilesolve.io.svg import tile_colour
    from tilesolve.io.wall_png import N_BRICK_COLOURS, brick_palette

    colours = [tuple(c) for c in colours]
    with Image.open(io.BytesIO(data)) as img:
        if img.mode != "P":
            return data
        entries = [tuple(img.getpalette()[3 * k:3 * k + 3]) for k in range(len(img.getpalette()) // 3)]
        if entries[:N_BRICK_COLOURS] == brick_palette()[:N_BRICK_COLOURS]:
            new = picture_palette(colours)[:N_BRICK_COLOURS] + entries[N_BRICK_COLOURS:]
        else:
            tiles = {tuple(int(tile_colour(k)[i:i + 2], 16) for i in (1, 3, 5)): colours[k] for k in range(len(colours))}
            new = [tiles.get(rgb, rgb) for rgb in entries]
        if new == entries:
            return data
        img.putpalette([c for rgb in new for c in rgb])
        buf = io.BytesIO()
        img.save(buf, format="PNG")
        return buf.getvalue()


def _posed(name: str, raw: str):
    """``(family, checked form values)`` of a view request (``raw``: JSON text); one seed, 0
    unless given, for every window of one view."""
    given = json.loads(raw)
    if isinstance(given, dict):
        given.setdefault("seed", 0)
    fam, vals, _, _ = worker.pose(name, given)
    if fam.form.window is None:
        raise InvalidProblem(f"{fam.name} problems have no infinite view")
    return fam, vals


class Views:
    """The view tiles of one server: rendered on demand, the last :data:`VIEW_CACHE` kept."""

    def __init__(self) -> None:
        self._cache: OrderedDict[tuple, bytes] = OrderedDict()
        self._lock = threading.Lock()

    def png(self, name: str, raw: str, x: int, y: int, n: int, colours=None) -> bytes:
        """The PNG of the n x n window with bottom-left cell (x, y) of family ``name``'s view for
        the form values ``raw`` (JSON text; every window of one view from one seed), in the
        chosen ``colours`` (:func:`recolour`) when given."""
        if colours:
            return recolour(self.png(name, raw, x, y, n), colours)
        fam, vals = _posed(name, raw)
        key = (fam.name, json.dumps(vals, sort_keys=True), x, y, n)
        with self._lock:
            if key in self._cache:
                self._cache.move_to_end(key)
                return self._cache[key]
        problem, method, options = fam.form.window(vals, Window(x, y, n, n))
        sol = family.solve(problem, method, seed=vals["seed"], options=options)
        if not sol.status.has_tiling:
            raise InvalidProblem(f"window ({x}, {y}): {sol.status.value}: {sol.reason or 'no tiling'}")
        data = _square(family.render(problem, sol, "png"))
        with self._lock:
            self._cache[key] = data
            while len(self._cache) > VIEW_CACHE:
                self._cache.popitem(last=False)
        return data

    def webgl(self, name: str, raw: str, colours=None) -> dict:
        """How the page draws family ``name``'s view itself for the form values ``raw``: the
        wall's GLSL ES shaders, uniforms and palette (:func:`tilesolve.gpu.wall.webgl_wall`, in
        the look of :meth:`png`'s tiles, its bricks in the chosen ``colours`` when given; ``kind``
        ``"wall"``) when the view is the procedural wall, else ``{"kind": None}`` (server tiles)."""
        from tilesolve.gpu.wall import webgl_wall

        fam, vals = _posed(name, raw)
        problem, method, _ = fam.form.window(vals, Window(0, 0, 1, 1))
        if method != "procedural":
            return {"kind": None}
        return {"kind": "wall", **webgl_wall(colors=problem.n_colors, max_line=problem.max_h, seed=vals["seed"],
                                             colours=colours or None)}

    def warm(self) -> None:
        """Run the families' warm hooks and render one small window of every view, so that the
        first pan of a page is fast (the server starts it in the background)."""
        worker.warm_families()
        for fam in family.families():
            if fam.form is not None and fam.form.window is not None:
                try:
                    self.png(fam.name, json.dumps({"seed": 0}), 0, 0, 8)
                except TilesolveError:
                    continue
