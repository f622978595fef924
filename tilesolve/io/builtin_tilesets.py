"""Built-in Wang tile sets: aperiodic sets from the literature and test sets with known answers.

Each set is a ``tilesolve/wang-tileset`` file shipped in ``tilesolve/data/tilesets/`` whose
``about`` object records where the tiles were transcribed from (repository, path, commit and
that source's edge order) and what the literature says about the set:

``verdict``
    ``"aperiodic"`` (tiles the plane, never periodically; a published proof), ``"periodic"``
    (tiles the plane periodically; ``period`` as the source collection names it) or
    ``"finite"`` (tiles some squares but not the plane; ``max_square`` where the source states
    it). These are the sources' statements, not results computed by tilesolve.

Where a second public source lists the same set, its tiles are kept too (``sources[i].tiles``,
in that source's own order and labels, with ``turned`` degrees where that source draws the set
rotated clockwise, and the ``lines`` of the file that hold them where it holds more); the tests check that both transcriptions are the same tile set up to a
relabelling of the colours on each axis (an isomorphism of tile sets).

Examples
--------
>>> ts, info = load("jeandel-rao")
>>> len(ts), info["verdict"]
(11, 'aperiodic')
"""

from __future__ import annotations

import functools
import json
from importlib import resources
from typing import Any

from tilesolve.errors import InvalidProblem
from tilesolve.model.board import WangTileSet

__all__ = ["names", "load", "VERDICTS"]

#: The literature verdicts a built-in set may carry.
VERDICTS = ("aperiodic", "periodic", "finite")


def _dir():
    return resources.files("tilesolve") / "data" / "tilesets"


@functools.lru_cache(maxsize=1)
def names() -> list[str]:
    """The names of the built-in tile sets, sorted."""
    return sorted(p.name[:-5] for p in _dir().iterdir() if p.name.endswith(".json"))


@functools.lru_cache(maxsize=None)
def _document(name: str) -> dict[str, Any]:
    if name not in names():
        raise InvalidProblem(f"no built-in tile set {name!r}; `tilesolve tiles --builtin` lists them")
    return json.loads((_dir() / f"{name}.json").read_text(encoding="utf-8"))


def load(name: str) -> tuple[WangTileSet, dict[str, Any]]:
    """The built-in tile set ``name`` and what is known about it.

    Returns
    -------
    (WangTileSet, dict)
        The info dict has ``name``, ``title``, ``verdict`` (one of :data:`VERDICTS`),
        ``reference``, ``sources`` (a list of ``{"repo", "path", "commit", "order"[, "tiles", "lines"]}``),
        ``n_tiles``, ``n_colors``, and where known ``period``, ``max_square`` and ``note``.
    """
    from tilesolve.io.tileset_json import tileset_from_data

    doc = _document(name)
    ts, _ = tileset_from_data(doc, f"built-in tile set {name}")
    info = json.loads(json.dumps(doc["about"]))
    info.update(name=name, n_tiles=len(ts), n_colors=ts.n_colors)
    return ts, info
