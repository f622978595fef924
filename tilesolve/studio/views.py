"""The studio's infinite views: one n x n window of a family's procedural plane as PNG
(:attr:`tilesolve.family.Form.window`), for pan and zoom, kept in an LRU cache."""

from __future__ import annotations

import json
import threading
from collections import OrderedDict

from tilesolve import family
from tilesolve.errors import InvalidProblem, TilesolveError
from tilesolve.model.window import Window
from tilesolve.studio import worker

__all__ = ["Views", "VIEW_CACHE"]

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


class Views:
    """The view tiles of one server: rendered on demand, the last :data:`VIEW_CACHE` kept."""

    def __init__(self) -> None:
        self._cache: OrderedDict[tuple, bytes] = OrderedDict()
        self._lock = threading.Lock()

    def png(self, name: str, raw: str, x: int, y: int, n: int) -> bytes:
        """The PNG of the n x n window with bottom-left cell (x, y) of family ``name``'s view for
        the form values ``raw`` (JSON text; every window of one view from one seed)."""
        given = json.loads(raw)
        if isinstance(given, dict):
            given.setdefault("seed", 0)  # every window of one view from one seed
        fam, vals, _, _ = worker.pose(name, given)
        if fam.form.window is None:
            raise InvalidProblem(f"{fam.name} problems have no infinite view")
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
