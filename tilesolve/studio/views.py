"""The studio's infinite views: one n x n window of a family's procedural plane as PNG
(:attr:`tilesolve.family.Form.window`), for pan and zoom, kept in an LRU cache; and for the
procedural wall, the GPU path's shaders that let the page draw the view itself (WebGL2).

A view of corner tiles of the complete set (the stochastic family's) has a second look, the
``texture``: the corner-tile texture of the GPU path (:mod:`tilesolve.gpu.texture`, ``tilesolve
render texture``) synthesised from :func:`texture_example`, the studio's built-in wall, with the
view's colours and seed, its atlas tiles :data:`TEXTURE_TILE` texels a side. The page draws it
with the texture shader as GLSL ES (:func:`tilesolve.gpu.texture.webgl_texture`), or from the
server's tiles (:func:`tilesolve.gpu.texture.texture_window`, the CPU's), the same pixels at one
texel a pixel.

A palette chosen on the page (``colours``: a list of RGB) recolours both: a brick picture's
bricks take the colours in turn (:func:`tilesolve.io.board_png.picture_palette`, the palette
texture of the wall's shaders too), another picture's tile ``k`` takes ``colours[k]`` (as the
page recolours its solved pictures)."""

from __future__ import annotations

import json
import threading
from collections import OrderedDict

import numpy as np

from tilesolve import family
from tilesolve.errors import InvalidProblem, TilesolveError
from tilesolve.model.window import Window
from tilesolve.studio import worker

__all__ = ["Views", "VIEW_CACHE", "LOOKS", "TEXTURE_TILE", "TEXTURE_MAX_COLORS", "recolour", "texture_example"]

#: Most view tiles kept (an LRU of PNG bytes).
VIEW_CACHE = 512
#: How a view is drawn: its family's pictures, or the corner-tile texture.
LOOKS = ("picture", "texture")
#: Texels a tile side of a texture view's atlas (the server's tiles at 24, 16 and 8 px a tile).
TEXTURE_TILE = 24
#: Most colours of a texture view: its atlas holds C**4 synthesised tiles (C = 4: 256).
TEXTURE_MAX_COLORS = 4
#: Texture atlases kept (one per colours and seed).
ATLAS_CACHE = 8


#: The texture example's brick colours: four terracotta shades (with the board pictures' dark
#: mortar the example reads as a wall, and so does its texture).
TEXTURE_BRICKS = ((178, 74, 52), (150, 60, 44), (196, 98, 66), (128, 52, 40))


def texture_example() -> np.ndarray:
    """The example of the texture views: a 192 x 192 px board picture (:func:`tilesolve.io.board_png.brick_image`,
    8 px a cell, its bricks in :data:`TEXTURE_BRICKS`) of the procedural wall's 24 x 24 cells at the
    origin (004; 3 colours, lines of at most 3, seed 1), ``(192, 192, 3)`` uint8 RGB. Its bricks are
    small enough for a 24-texel tile to hold a few of them (:func:`tilesolve.gpu.texture.synthesis_scale`
    is 1: the texture shows the example at its own size)."""
    from tilesolve.constructive.walls import wall_window
    from tilesolve.io.board_png import brick_image
    from tilesolve.model.board import Board, BoardProblem, WangTileSet

    legs = wall_window(0, 0, 24, 24, colors=3, max_line=3, seed=1)
    img = brick_image(BoardProblem(Board.rect(24, 24), WangTileSet.brick(3)), legs.reshape(-1, 4),
                      window=Window(0, 0, 24, 24), scale=8, colours=TEXTURE_BRICKS)
    return np.asarray(img.convert("RGB"))


def _texture_source(fam, vals) -> tuple[int, str]:
    """``(colours, hash)`` of a view's texture look; a one-line error for a view without one."""
    from tilesolve.model.stochastic import StochasticProblem

    problem, _, _ = fam.form.window(vals, Window(0, 0, 1, 1))
    if not (isinstance(problem, StochasticProblem) and problem.kind == "corner" and problem.variant == "complete"):
        raise InvalidProblem(f"the texture look draws corner tiles of the complete set (the stochastic family, "
                             f"kind corner, set complete); {fam.name} with these values has none")
    if problem.colors > TEXTURE_MAX_COLORS:
        raise InvalidProblem(f"the texture look synthesises C**4 tiles: at most {TEXTURE_MAX_COLORS} colours, "
                             f"got {problem.colors}")
    return problem.colors, problem.hash


def _png(pixels: np.ndarray) -> bytes:
    import io

    from PIL import Image

    buf = io.BytesIO()
    Image.fromarray(np.ascontiguousarray(pixels[..., :3]), "RGB").save(buf, format="PNG")
    return buf.getvalue()


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
            tiles = {tuple(int(tile_colour(k)[i:i + 2], 16) for i in (1, 3, 5)): colours[k]
                     for k in range(len(colours))}
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
        self._atlases: OrderedDict[tuple, object] = OrderedDict()
        self._atlas_lock = threading.Lock()  # one synthesis at a time: the others wait for its atlas

    def _atlas(self, colors: int, seed: int):
        """The texture views' atlas of ``colors`` colours and ``seed`` (synthesised once, kept)."""
        from tilesolve.gpu.texture import Atlas

        key = (colors, seed)
        with self._atlas_lock:
            if key not in self._atlases:
                self._atlases[key] = Atlas.from_example(texture_example(), colors, tile=TEXTURE_TILE, seed=seed)
                while len(self._atlases) > ATLAS_CACHE:
                    self._atlases.popitem(last=False)
            self._atlases.move_to_end(key)
            return self._atlases[key]

    def has_texture(self, name: str) -> bool:
        """Whether family ``name``'s view, with its form's default values, has the texture look."""
        try:
            fam, vals = _posed(name, "{}")
            _texture_source(fam, vals)
        except TilesolveError:
            return False
        return True

    def texture_png(self, name: str, raw: str, x: int, y: int, n: int) -> bytes:
        """The texture look's PNG of the n x n window with bottom-left tile (x, y): the CPU's
        (:func:`tilesolve.gpu.texture.texture_window`), ``brick_scale(n, n)`` px a tile (24 for
        the page's finest tiles: one texel a pixel)."""
        from tilesolve.gpu.texture import texture_window
        from tilesolve.io.board_png import brick_scale

        fam, vals = _posed(name, raw)
        colors, hash_ = _texture_source(fam, vals)
        key = ("texture", fam.name, json.dumps(vals, sort_keys=True), x, y, n)
        with self._lock:
            if key in self._cache:
                self._cache.move_to_end(key)
                return self._cache[key]
        atlas = self._atlas(colors, vals["seed"])
        data = _png(texture_window(atlas, x, y, n, n, seed=vals["seed"], hash=hash_,
                                   tile_px=min(TEXTURE_TILE, brick_scale(n, n))))
        with self._lock:
            self._cache[key] = data
            while len(self._cache) > VIEW_CACHE:
                self._cache.popitem(last=False)
        return data

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

    def webgl(self, name: str, raw: str, colours=None, look: str = "picture") -> dict:
        """How the page draws family ``name``'s view itself for the form values ``raw``: the
        wall's GLSL ES shaders, uniforms and palette (:func:`tilesolve.gpu.wall.webgl_wall`, in
        the look of :meth:`png`'s tiles, its bricks in the chosen ``colours`` when given; ``kind``
        ``"wall"``) when the view is the procedural wall; in the ``texture`` look, the texture
        shader, its tables and atlas (:func:`tilesolve.gpu.texture.webgl_texture`, ``kind``
        ``"texture"``); else ``{"kind": None}`` (server tiles)."""
        from tilesolve.gpu.wall import webgl_wall

        fam, vals = _posed(name, raw)
        if look == "texture":
            from tilesolve.gpu.texture import webgl_texture

            colors, hash_ = _texture_source(fam, vals)
            atlas = self._atlas(colors, vals["seed"])
            return {"kind": "texture", **webgl_texture(atlas, seed=vals["seed"], hash=hash_)}
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
