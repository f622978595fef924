"""The studio's forms of the sampling families: corner-based Poisson disk tiles
(:mod:`tilesolve.families.poisson`), Poisson sphere tiles (:mod:`tilesolve.families.poisson_sphere`),
recursive Wang tiles (:mod:`tilesolve.families.poisson_recursive`) and stippling
(:mod:`tilesolve.families.importance`: :data:`STIPPLE_FORM`, a built-in test image stippled by
``tilesolve sample stipple``).

Each form builds a tile set and either shows a window of the plane (a box of space) tiled with
it, or the set itself (``show``). A window's set is built first, verified, from its own seed
(``set seed``; the run's seed is the window's tiling), and kept (:func:`built_set`), so that a
form's check builds it once. The command line a form copies is the CLI's own two steps: the
set's ``build`` (the file the window command reads, :attr:`tilesolve.family.Form.command`),
then its ``window``.

A window's set is built while the form is checked, so its size is bounded here
(:data:`SET_BUDGETS`); the ``set`` question builds larger sets as a solve, which can be
cancelled. Windows are bounded in points (:data:`WINDOW_BUDGET`), so that their pictures stay
light.

Examples
--------
>>> vals = POISSON_FORM.values({"seed": 5})
>>> problem, _ = POISSON_FORM.build(vals)
>>> problem.window.width, problem.tileset.problem.points
(8, 32)
>>> words, files = POISSON_FORM.command(vals)
>>> words
['sample', 'poisson-tiles', 'window', 'set.json', '--region=0,0,8x8', '--tiling', 'direct']
>>> files["set.json"]
['sample', 'poisson-tiles', 'build', '-C', '2', '-N', '32', '--rho', '0.75', '--lloyd', '0', '--seed', '1', '-o', 'set.json']
"""

from __future__ import annotations

import functools
from typing import Any, Callable

from tilesolve.errors import InvalidProblem
from tilesolve.family.forms import Field, Form, form_size
from tilesolve.model.importance import ImportanceProblem, builtin_density
from tilesolve.model.poisson import PoissonTilesProblem, PoissonWindowProblem
from tilesolve.model.poisson_recursive import RecursiveTilesProblem, RecursiveWindowProblem
from tilesolve.model.poisson_sphere import Box, PoissonSphereTilesProblem, PoissonSphereWindowProblem
from tilesolve.model.window import Window

__all__ = ["POISSON_FORM", "SPHERE_FORM", "RECURSIVE_FORM", "STIPPLE_FORM", "built_set", "SET_BUDGETS", "WINDOW_BUDGET", "SET_FILE"]

#: Most points over all the tiles of a set a window's form builds (tiles x points a tile), by
#: family; each builds and verifies in a few seconds: a 2-D set of C = 2 at N = 64 (26 tiles), a
#: sphere set of C = 2 at N = 64 (318 tiles), a recursive set of C = 2 at N = 32 (16 tiles). The
#: ``set`` question builds larger sets.
SET_BUDGETS = {"poisson": 26 * 64, "poisson-sphere": 318 * 64, "recursive-wang": 16 * 32}
#: Most points a window shows.
WINDOW_BUDGET = 20_000
#: The file the copied command writes the set to, and its window command reads.
SET_FILE = "set.json"

_WINDOW = {"show": ("window",)}
_SHOW = ("window", "set")
_SHOW_HELP = ("window: build the set, then sample a window of the plane tiled with it (its points are "
              "verified); set: the tile set itself (every tiling of it verified), drawn as a window at the origin")


@functools.lru_cache(maxsize=8)
def built_set(problem, seed: int):
    """The tile set of ``problem`` (a set question) built with ``seed`` and verified by the
    family's pipeline; kept for the next check of the same form."""
    from tilesolve.family import solve

    sol = solve(problem, "auto", seed=seed)
    if not sol.status.has_tiling:
        raise InvalidProblem(f"the tile set was not built: {sol.status.value}: {sol.reason or 'no set'}")
    return sol.tiling


def _show_field() -> Field:
    return Field("show", "choice", "show", "window", _SHOW_HELP, choices=_SHOW)


def _set_seed_field() -> Field:
    return Field("set_seed", "int", "set seed", 1, "window: the seed the set is built with (the run's seed "
                 "tiles the plane)", low=0, high=2**31 - 1, option="--seed", when=(_WINDOW,))


def _region_fields(size: str, high: int, what: str) -> tuple[Field, ...]:
    return (
        Field("x0", "int", "window x0", 0, f"window: the west column of {what} (y grows upwards)", low=-10**12,
              high=10**12, option="--region", when=(_WINDOW,)),
        Field("y0", "int", "window y0", 0, f"window: the south row of {what}", low=-10**12, high=10**12,
              option="--region", when=(_WINDOW,)),
        Field("size", "size", "window (WxH)", size, f"window: W x H {what}", high=high, option="--region",
              when=(_WINDOW,)),
    )


def _set_for_window(problem, values, budget: int) -> Any:
    """The built set a window's problem samples, within ``budget`` (:data:`SET_BUDGETS`)."""
    work = problem.n_tiles * problem.points
    if work > budget:
        raise InvalidProblem(f"a window's set is built while the form is checked: at most {budget:,} points "
                             f"over its tiles here, this one has {work:,} ({problem.n_tiles} tiles x "
                             f"{problem.points}); build it with show = set, or with the command line")
    return built_set(problem, values["set_seed"])


def _check_points(n: float) -> None:
    if n > WINDOW_BUDGET:
        raise InvalidProblem(f"this window holds about {n:,.0f} points; the studio shows at most "
                             f"{WINDOW_BUDGET:,}: ask for a smaller window")


def _form(name: str, fields: tuple[Field, ...], set_problem: Callable, set_words: Callable, window_points: Callable,
          window_problem: Callable, window_words: Callable) -> Form:
    """Family ``name``'s form: the set question ``set_problem(values)`` and its build command
    ``set_words(values)``; the window question, about ``window_points(values)`` points (checked
    before the set is built), ``window_problem(values, tileset)`` and its window command
    ``window_words(values)`` (it reads :data:`SET_FILE`)."""

    def build(values):
        problem = set_problem(values)
        if values["show"] == "set":
            return problem, {}
        _check_points(window_points(values))
        return window_problem(values, _set_for_window(problem, values, SET_BUDGETS[name])), {}

    def command(values) -> tuple[list[str], dict[str, Any]]:
        if values["show"] == "set":
            return set_words(values), {}
        prelude = [*set_words(values), "--seed", str(values["set_seed"]), "-o", SET_FILE]
        return window_words(values), {SET_FILE: prelude}

    return Form(fields=fields, build=build, command=command, time_limit=False)


def _window(values) -> Window:
    rows, cols = form_size(values["size"])
    return Window(values["x0"], values["y0"], cols, rows)


def _region(values) -> str:
    return f"--region={values['x0']},{values['y0']},{values['size']}"


# ----------------------------------------------------------------------------- Poisson disk tiles
def _poisson_set(values) -> PoissonTilesProblem:
    return PoissonTilesProblem(values["colors"], values["points"], values["rho"], values["lloyd"])


def _cells(values) -> int:
    """Tiles (cells) of the window's ``size``."""
    rows, cols = form_size(values["size"])
    return rows * cols


POISSON_FORM = _form(
    "poisson",
    (
        _show_field(),
        Field("colors", "int", "colours C", 2, "corner colours: C + 2C^2 + C^4 tiles", low=1, high=8, option="-C"),
        Field("points", "int", "points a tile N", 32, "points a tile", low=1, high=4096, option="-N"),
        Field("rho", "float", "relative radius rho", 0.75, "no two points closer than 2 rho r_max(N) (eq. 4.3)",
              low=0.05, high=0.85, option="--rho"),
        Field("lloyd", "int", "Lloyd steps", 0, "Lloyd relaxation steps after dart throwing (§4.2.4.3)", low=0,
              high=20, option="--lloyd"),
        _set_seed_field(),
        *_region_fields("8x8", 1024, "tiles"),
        Field("tiling", "choice", "corner tiling", "direct", "window: the stochastic corner tiling that colours "
              "the lattice (§3.3.1 direct, §3.2.2 scanline)", choices=("direct", "scanline"), option="--tiling",
              when=(_WINDOW,)),
    ),
    _poisson_set,
    lambda v: ["sample", "poisson-tiles", "build", "-C", str(v["colors"]), "-N", str(v["points"]), "--rho",
               str(v["rho"]), "--lloyd", str(v["lloyd"])],
    lambda v: _cells(v) * v["points"],
    lambda v, tileset: PoissonWindowProblem(tileset, _window(v), tiling=v["tiling"]),
    lambda v: ["sample", "poisson-tiles", "window", SET_FILE, _region(v), "--tiling", v["tiling"]],
)


# ----------------------------------------------------------------------------- Poisson sphere tiles
def _sphere_set(values) -> PoissonSphereTilesProblem:
    return PoissonSphereTilesProblem(values["colors"], values["points"], values["rho"])


def _sphere_window(values, tileset) -> PoissonSphereWindowProblem:
    w = _window(values)
    return PoissonSphereWindowProblem(tileset, Box(w.x0, w.y0, values["z0"], w.width, w.height, values["depth"]))


SPHERE_FORM = _form(
    "poisson-sphere",
    (
        _show_field(),
        Field("colors", "int", "colours C", 2, "corner colours: C + 3C^2 + 3C^4 + C^8 tiles", low=1, high=4,
              option="-C"),
        Field("points", "int", "points a cell N", 64, "points a unit cell", low=1, high=4096, option="-N"),
        Field("rho", "float", "relative radius rho", 0.6, "no two points closer than 2 rho r_max(N) (eq. 4.6)",
              low=0.05, high=0.85, option="--rho"),
        _set_seed_field(),
        *_region_fields("6x6", 256, "cells"),
        Field("z0", "int", "box z0", 0, "window: the lowest layer of the box (the picture shows its floor, one "
              "distance thick, seen along z)", low=-10**12, high=10**12, option="--region", when=(_WINDOW,)),
        Field("depth", "int", "box depth", 1, "window: layers of cells", low=1, high=16, option="--region",
              when=(_WINDOW,)),
    ),
    _sphere_set,
    lambda v: ["sample", "poisson-spheres", "build", "-C", str(v["colors"]), "-N", str(v["points"]), "--rho",
               str(v["rho"])],
    lambda v: _cells(v) * v["depth"] * v["points"],
    _sphere_window,
    lambda v: ["sample", "poisson-spheres", "window", SET_FILE,
               f"--region={v['x0']},{v['y0']},{v['z0']},{v['size']}x{v['depth']}"],
)


# ----------------------------------------------------------------------------- recursive Wang tiles
def _recursive_set(values) -> RecursiveTilesProblem:
    return RecursiveTilesProblem(values["colors"], values["points"], values["rho"], values["subdivision"],
                                 values["lloyd"])


def _recursive_points(values) -> float:
    if values["by"] == "level":
        return _cells(values) * values["points"] * values["subdivision"] ** (2 * values["level"])
    return _cells(values) * values["density"]


def _recursive_window(values, tileset) -> RecursiveWindowProblem:
    w = _window(values)
    if values["by"] == "level":
        return RecursiveWindowProblem(tileset, w, level=values["level"])
    return RecursiveWindowProblem(tileset, w, density=values["density"], label=f"density {values['density']:g}")


_BY_LEVEL, _BY_DENSITY = ({"show": ("window",), "by": ("level",)},), ({"show": ("window",), "by": ("density",)},)

RECURSIVE_FORM = _form(
    "recursive-wang",
    (
        _show_field(),
        Field("colors", "int", "colours C", 2, "corner colours: C^4 Wang tiles", low=1, high=8, option="-C"),
        Field("points", "int", "points a tile N", 16, "points a tile at level 0", low=1, high=4096, option="-N"),
        Field("rho", "float", "relative radius rho", 0.7, "every level l keeps 2 rho r_max(N) / n^l", low=0.05,
              high=0.85, option="--rho"),
        Field("subdivision", "int", "subdivision n", 4, "each tile splits into n x n sub-tiles: n^2 times the "
              "density a level", low=2, high=8, option="-n"),
        Field("lloyd", "int", "Lloyd steps", 0, "Lloyd relaxation steps of the corner tiles (§4.2.4.3)", low=0,
              high=20, option="--lloyd"),
        _set_seed_field(),
        *_region_fields("4x4", 256, "level-0 tiles"),
        Field("by", "choice", "points by", "level", "window: every point of a level, or a uniform density (points "
              "a tile, any number: the level it needs and the first points of it by rank)",
              choices=("level", "density"), when=(_WINDOW,)),
        Field("level", "int", "level", 1, "window: every point of this level (N n^(2l) points a tile)", low=0,
              high=12, option="--level", when=_BY_LEVEL),
        Field("density", "float", "density", 600.0, "window: points a unit area (a level-0 tile)", low=0.001,
              high=1e9, option="--density", when=_BY_DENSITY),
    ),
    _recursive_set,
    lambda v: ["sample", "recursive-wang", "build", "-C", str(v["colors"]), "-N", str(v["points"]), "--rho",
               str(v["rho"]), "-n", str(v["subdivision"]), "--lloyd", str(v["lloyd"])],
    _recursive_points,
    _recursive_window,
    lambda v: ["sample", "recursive-wang", "window", SET_FILE, _region(v),
               *(["--level", str(v["level"])] if v["by"] == "level" else ["--density", str(v["density"])])],
)



# ----------------------------------------------------------------------------- stippling
_TILES = ("x-pentomino", "chair", "l-tetromino", "p-pentomino")


def _stipple_problem(values) -> ImportanceProblem:
    """The CLI's ``--test-image`` (its default side) stippled with the form's settings."""
    return ImportanceProblem(builtin_density(values["image"]), values["points"], values["method"], values["tile"],
                             values["lloyd"], values["jitter"])


def _stipple_words(values) -> tuple[list[str], dict[str, Any]]:
    return ["sample", "stipple", "--test-image", values["image"], "--points", str(values["points"]), "--method",
            values["method"], "--tile", values["tile"], "--lloyd", str(values["lloyd"]),
            "--jitter" if values["jitter"] else "--no-jitter"], {}


STIPPLE_FORM = Form(
    fields=(
        Field("image", "choice", "test image", "radial", "a built-in 256 x 256 picture: dark is dense",
              choices=("radial", "gradient", "flat"), option="--test-image"),
        Field("points", "int", "points", 3000, "about how many samples", low=1, high=50_000, option="--points"),
        Field("method", "choice", "sampler", "penrose", "Penrose tilings' Robinson triangles (Ostromoukhov, Donohue, "
              "Jodoin 2004), a self-similar polyomino (Ostromoukhov 2007) or plain rejection sampling",
              choices=("penrose", "polyomino", "rejection"), option="--method"),
        Field("tile", "choice", "polyomino", "x-pentomino", "polyomino: the self-similar tile", choices=_TILES,
              option="--tile", when=({"method": ("polyomino",)},)),
        Field("lloyd", "int", "Lloyd steps", 4, "density-weighted Lloyd steps after sampling", low=0, high=50,
              option="--lloyd"),
        Field("jitter", "bool", "jitter", True, "each sample at a random point of its tile, not its centroid "
              "(penrose, polyomino)", option="--jitter"),
    ),
    build=lambda v: (_stipple_problem(v), {}),
    command=_stipple_words,
    time_limit=False,
)
