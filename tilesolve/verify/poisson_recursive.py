"""Independent checks of recursive Wang tiles and their windows (Kopf et al. 2006; class notes
Part V; definitions in :mod:`tilesolve.model.poisson_recursive`).

Written from the definitions, sharing no code with the builder
(:mod:`tilesolve.constructive.poisson_recursive`):

* :func:`tileset_violations`: the corner-based tiles every level places are a valid set
  (:func:`tilesolve.verify.poisson.tileset_violations`: every tiling of them is a Poisson disk
  distribution), and the subdivision rules make the sub-tiles of *any* tiling a tiling: each
  rule keeps its tile's corner colours (eq. 2.5), and all edges with the same end colours
  carry the same sub-colours (horizontal and vertical apart), so that two neighbouring tiles
  agree on the sub-lattice of their common edge. Then the depth-``k`` lattice of every level
  is a lattice colouring, and the candidates of every level a Poisson disk distribution at
  ``d_k`` (§4.3).
* :func:`window_violations`: every level ``l`` of a window, the points of level ``<= l``, is a
  Poisson disk distribution at ``d_l = d n^-l`` (a grid search,
  :func:`tilesolve.verify.poisson.point_violations`; a message's point numbers count the
  points of that level in file order), levels and ranks are in range, and the points lie in
  the window.

>>> import math

import numpy as np
>>> from tilesolve.model.poisson_recursive import RecursiveWindow
>>> from tilesolve.model.window import Window
>>> w = RecursiveWindow(Window(0, 0, 1, 1), np.array([[0.1, 0.1], [0.3, 0.1], [0.32, 0.1]]),
...                     np.array([0, 0, 1], np.int8), np.array([0.1, 0.2, 0.3]), 0.1, 4)
>>> [v.message for v in window_violations(w)]
['level 1: points 1 and 2 are 0.02 apart, closer than 0.025']
"""

from __future__ import annotations

import math

import numpy as np

from tilesolve.model.poisson_recursive import MAX_LEVEL, RecursiveTileSet, RecursiveWindow
from tilesolve.verify.dappled import Violation
from tilesolve.verify.poisson import MAX_LISTED, point_violations
from tilesolve.verify.poisson import tileset_violations as base_violations

__all__ = ["tileset_violations", "rule_violations", "window_violations", "label_violations"]


def rule_violations(rules: np.ndarray, colors: int) -> list[Violation]:
    """Every way ``rules[t, b, a]`` (colour of sub-lattice point ``(a, b)`` of tile ``t``, y
    north) fails to subdivide every tiling of the complete corner set into a tiling."""
    rules = np.asarray(rules)
    c = colors
    if rules.ndim != 3 or rules.shape[0] != c**4 or rules.shape[1] != rules.shape[2] or rules.shape[1] < 3:
        return [Violation("shape", f"subdivision rules must be a ({c**4}, n + 1, n + 1) array, n >= 2")]
    if ((rules < 0) | (rules >= c)).any():
        return [Violation("shape", f"subdivision rules hold colours outside 0..{c - 1}")]
    n = rules.shape[1] - 1
    out = []
    edges: dict = {}
    for t in range(c**4):
        ne, se, sw, nw = (t // c**3) % c, (t // c**2) % c, (t // c) % c, t % c
        r = rules[t]
        if (int(r[0, 0]), int(r[0, n]), int(r[n, n]), int(r[n, 0])) != (sw, se, ne, nw):
            out.append(Violation("rule", f"tile {t}: the rule's corners are not the tile's corner colours"))
        for key, seq in ((("h", sw, se), r[0, 1:n]), (("h", nw, ne), r[n, 1:n]),
                         (("v", sw, nw), r[1:n, 0]), (("v", se, ne), r[1:n, n])):
            first = edges.setdefault(key, (t, tuple(seq.tolist())))
            if first[1] != tuple(seq.tolist()):
                way = "horizontal" if key[0] == "h" else "vertical"
                out.append(Violation("rule", f"tiles {first[0]} and {t}: a {way} edge of end colours "
                                             f"{key[1]}, {key[2]} subdivides two ways"))
        if len(out) >= MAX_LISTED:
            break
    return out


def tileset_violations(ts: RecursiveTileSet) -> list[Violation]:
    """The corner tiles' violations, then the rules' (see the module docstring)."""
    if not isinstance(ts, RecursiveTileSet):
        return [Violation("shape", "the answer is no recursive Wang tile set")]
    return base_violations(ts.base) or rule_violations(ts.rules, ts.problem.colors)


def window_violations(w: RecursiveWindow) -> list[Violation]:
    """Every way a window fails: a level out of range, a rank out of ``[0, 1)``, or a level
    whose points (those of level ``<=`` it) are not a Poisson disk distribution at its distance."""
    if not isinstance(w, RecursiveWindow):
        return [Violation("shape", "the answer is no window of recursive Wang points")]
    level, rank = np.asarray(w.level), np.asarray(w.rank, dtype=np.float64)
    n = len(w.local)
    if level.shape != (n,) or rank.shape != (n,):
        return [Violation("shape", "every point needs one level and one rank")]
    if n and (level.min() < 0 or level.max() > MAX_LEVEL):
        return [Violation("level", f"levels must lie within 0..{MAX_LEVEL}")]
    if not np.isfinite(rank).all() or (rank < 0).any() or (rank >= 1).any():
        return [Violation("rank", "ranks must lie in [0, 1)")]
    out = []
    for lv in range(int(level.max()) + 1 if n else 0):
        pts = w.local[level <= lv]
        d = w.distance / w.subdivision**lv
        out += [Violation(v.kind, f"level {lv}: {v.message}")
                for v in point_violations(pts, d, w.window.width, w.window.height)]
        if len(out) >= MAX_LISTED:
            break
    return out


def label_violations(label: str, grid, level: int) -> list[Violation]:
    """Whether a window's density label (shown in ``verify``'s verdict) says what its density
    grid holds (``None``: a window at one level), when it is one of the labels tilesolve writes:
    ``level L`` (no grid, that level), ``density D`` (D everywhere), ``ramp D0,D1`` (one row
    rising linearly from D0 to D1), ``image ..., up to D`` (nothing above D) or ``density up to D
    a unit area`` (its largest value); any other label is the user's own words."""
    grid = None if grid is None else np.atleast_2d(np.asarray(grid, dtype=np.float64))
    def number(text: str) -> float | None:
        try:
            v = float(text)
        except ValueError:
            return None
        return v if math.isfinite(v) else None

    def fail(what: str) -> list[Violation]:
        return [Violation("label", f"the density's label {label[:80]!r} says {what}, but the window's density "
                                   f"{'is none (one level)' if grid is None else 'is another'}")]

    words = label.split(" ")
    if len(words) == 2 and words[0] == "level" and words[1].isdigit():
        if grid is not None:
            return fail(f"level {words[1]} and no density")
        if int(words[1]) != level:
            return [Violation("label", f"the density's label {label!r} says level {words[1]}, but the window's "
                                       f"level is {level}")]
        return []
    if len(words) == 2 and words[0] == "density" and number(words[1]) is not None:
        if grid is None or not np.allclose(grid, number(words[1]), rtol=1e-5, atol=0):
            return fail(f"a density of {words[1]} everywhere")
        return []
    ends = words[1].split(",") if len(words) == 2 and words[0] == "ramp" else []
    if len(ends) == 2 and None not in map(number, ends):
        lo, hi = map(number, ends)
        if grid is None or grid.shape[0] != 1 or not np.allclose(grid[0], np.linspace(lo, hi, grid.shape[1]),
                                                                  rtol=1e-9, atol=1e-9 * max(abs(lo), abs(hi))):
            return fail(f"a ramp from {lo:g} to {hi:g} west to east")
        return []
    if label.startswith("image ") and ", up to " in label:
        top = number(label.rsplit(", up to ", 1)[1])
        if top is not None and (grid is None or grid.max() > top * (1 + 1e-9)):
            return fail(f"no density above {top:g}")
    if label.startswith("density up to ") and label.endswith(" a unit area"):
        top = number(label[len("density up to "):-len(" a unit area")])
        if top is not None and (grid is None or not math.isclose(float(grid.max()), top, rel_tol=1e-5)):
            return fail(f"a largest density of {top:g}")
    return []
