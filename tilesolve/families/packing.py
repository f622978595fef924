"""Tile packings end to end (class notes §5.5): one facade over constructions and solvers.

:func:`solve` looks the method up in :data:`SOLVERS` (so the CLI's ``--method`` choices come
from its keys), runs it, and checks every packing it returns with the independent verifier
:func:`tilesolve.verify.packing.packing_violations`; :func:`count` counts all packings for
``C = 2`` with or without symmetry reduction.

Routes
------
``euler``
    Eulerian constructions over Wei's 1D packing: the Wang outer product (§5.5.2, Fig. 5.10,
    closed-form tile positions) and, for odd ``C``, the corner packing
    ``a[i][j] = s[(j + i(i-1)/2) mod C**2]`` (a 2D de Bruijn torus).
``outer``
    The same constructions over random Eulerian circuits (seeded): varied, but still
    structured (a Wang outer product has equal W/E sequences in every row).
``known``
    The notes' published C = 4 packings (Figs. 5.11, 5.12), under a random symmetry when seeded.
``sat``
    SAT (:data:`~tilesolve.engine.packing.PACKING_SAT_SOLVER`) on
    :func:`tilesolve.encodings.packing.encode_packing`: random-looking packings (the seed
    picks the tile pinned at the origin, the solver seed and preferred colours); honours
    pinned tiles; ``unsat`` comes with a checked DRAT proof. Practical up to C = 3.
``cpsat``
    OR-tools CP-SAT on the same encoding with native exactly-one constraints.
``hybrid``
    Wang only: random Eulerian N/S edge columns, then SAT for the E/W edges and the tiles.
``lift``
    A packing over ``m`` colours repeated over the torus plus a ``k``-ary layer found by SAT
    (``C = m*k``), :mod:`tilesolve.families.packing_search`; measured times in README ("Performance").
``recursive``
    A packing over ``C - 1`` colours pinned in the bottom-left corner, completed by SAT
    (Figs. 5.11-5.12).

Heavy-tailed searches (:data:`PORTFOLIO_ROUTES`) go through
:func:`tilesolve.engine.portfolio.escalate`: the first seed keeps running in this process; if
it has not decided after :data:`~tilesolve.engine.portfolio.QUICK_S` seconds, fresh seeds run
beside it on idle cores (``workers``, always when given explicitly) or on a Dask cluster
(``cluster``), with per-run budgets that double with every wave.

Examples
--------
>>> from tilesolve.model.packing import PackingProblem
>>> s = solve(PackingProblem("corner", 2), method="sat", seed=1)
>>> s.status.value, s.tiling.shape
('sat', (4, 4))
>>> count(PackingProblem("corner", 2)).value, count(PackingProblem("corner", 2), up_to_symmetry=True).value
(32, 1)
"""

from __future__ import annotations

import time
from dataclasses import replace
from typing import Any

import numpy as np

from tilesolve._random import rng_from_seed
from tilesolve.engine.packing import PACKING_SAT_SOLVER
from tilesolve.errors import InvalidProblem, MethodNotApplicable
from tilesolve.family import Codec, Demo, Family, Field, Form, RunOptions, register, run_deadline
from tilesolve.family import solve as _solve
from tilesolve.io.packing_json import PACKING, VERSIONS
from tilesolve.model.packing import PackingProblem
from tilesolve.model.solution import CountResult, Solution, Status
from tilesolve.verify.packing import packing_violations
from tilesolve.progress import Progress

__all__ = ["FAMILY", "SOLVERS", "METHODS", "PACKING_SAT_SOLVER", "PORTFOLIO_ROUTES", "solve", "count",
           "auto_method", "euler", "outer", "known", "sat", "cpsat", "hybrid", "lift", "recursive"]


def _pin_by_translation(problem: PackingProblem, grid: np.ndarray, method: str) -> np.ndarray:
    """Constructions ignore pins; one pin can always be met by translating the torus."""
    if not problem.fixed:
        return grid
    pins = set(problem.fixed)
    if len(pins) > 1:
        raise MethodNotApplicable(f"method {method!r} can honour one pinned tile (by translation), "
                                  f"not {len(pins)}; use method 'sat'")
    (r, c, t), = pins
    r0, c0 = np.argwhere(grid == t)[0]
    return np.roll(grid, (r - int(r0), c - int(c0)), axis=(0, 1))


def euler(problem: PackingProblem, run: RunOptions) -> Solution:
    """Eulerian constructions: Wei's Wang outer product (§5.5.2, Fig. 5.10), the odd-C corner
    de Bruijn torus."""
    from tilesolve.constructive.packing import corner_packing_odd, wang_packing

    t0 = time.perf_counter()
    if problem.kind == "wang":
        g = wang_packing(problem.colors, problem.colors_v)
    else:
        g = corner_packing_odd(problem.colors)
    g = _pin_by_translation(problem, g, "euler")
    return Solution(Status.SAT, g, method="euler", seed=run.seed, time_s=time.perf_counter() - t0)


def outer(problem: PackingProblem, run: RunOptions) -> Solution:
    """The same constructions over random (seeded) Eulerian circuits."""
    from tilesolve.constructive.packing import corner_packing_odd, wang_packing

    t0 = time.perf_counter()
    rng = rng_from_seed(run.seed)
    if problem.kind == "wang":
        g = wang_packing(problem.colors, problem.colors_v, seed=rng)
    else:
        g = corner_packing_odd(problem.colors, seed=rng)
    g = _pin_by_translation(problem, g, "outer")
    return Solution(Status.SAT, g, method="outer", seed=run.seed, time_s=time.perf_counter() - t0)


def known(problem: PackingProblem, run: RunOptions) -> Solution:
    """The notes' published C = 4 packings (Figs. 5.11, 5.12) under a seeded random symmetry."""
    from tilesolve.constructive.packing_known import known_packing

    t0 = time.perf_counter()
    if problem.colors_v is not None and problem.colors_v != problem.colors:
        raise MethodNotApplicable("the notes publish no packing with C_h != C_v; use method 'outer' or 'sat'")
    fig, g = known_packing(problem.kind, problem.colors, seed=run.seed)
    g = _pin_by_translation(problem, g, "known")
    note = f"the packing of the class notes' {fig} under a random symmetry"
    return Solution(Status.SAT, g, method="known", seed=run.seed, time_s=time.perf_counter() - t0, notes=(note,))


def _search(name: str):
    """The facade route of the search ``solve_<name>`` (:mod:`tilesolve.engine.packing` for
    ``sat``/``cpsat``, :mod:`tilesolve.families.packing_search` for the searches over constructions);
    heavy-tailed searches escalate to a seed portfolio (:func:`tilesolve.engine.portfolio.escalate`)."""
    from tilesolve.families import packing_search
    from tilesolve.engine import packing as engine

    raw = getattr(engine if name in ("sat", "cpsat") else packing_search, f"solve_{name}")

    def route(problem: PackingProblem, run: RunOptions) -> Solution:
        clashes = problem.pin_clashes()
        if clashes and name not in ("sat", "cpsat"):
            # A restricted search never proves unsat and would retry forever: pins that clash
            # are refuted on the full formula instead (unsat with a checked proof).
            try:
                sol = sat(problem, run)
            except InvalidProblem:
                raise InvalidProblem(f"the pinned tiles clash: {clashes[0]}") from None
            return sol.replace(notes=(f"the pins clash, so {name!r} was not run: decided on the full formula",)
                               + sol.notes)
        if name not in PORTFOLIO_ROUTES:
            sol = raw(problem, run)
        else:
            from tilesolve.engine.portfolio import escalate

            sol = _proof_written(escalate(raw, problem, run, name=f"{name} packing"), problem, run)
        if sol.status is Status.UNSAT and clashes:
            sol = sol.replace(reason=f"{sol.reason}; in words: " + "; ".join(clashes))
        return sol

    route.__name__ = name
    route.__doc__ = raw.__doc__
    return route


def _proof_written(sol: Solution, problem: PackingProblem, run: RunOptions) -> Solution:
    """An unsat found by a portfolio worker (another process: its proof files were not written)
    decided again here, with the winning seed, when the run asked for proof files, so that every
    unsat it reports has its CNF and proof in the proof directory."""
    from tilesolve.engine.certificates import proofs_wanted
    from tilesolve.engine.packing import solve_sat

    if sol.status is not Status.UNSAT or "proof_name" in sol.stats or not proofs_wanted():
        return sol
    again = solve_sat(problem, replace(run, seed=sol.seed))
    if again.status is Status.UNSAT:
        return again.with_note("decided by a worker process; decided again here to write its proof files")
    return sol.with_note(f"its proof files were not written: deciding it again here ended {again.status.value} "
                         f"({again.reason})")


#: Routes whose run times are heavy-tailed: a run that does not decide quickly is followed
#: by a portfolio of seeds on local processes or a Dask cluster.
PORTFOLIO_ROUTES: tuple[str, ...] = ("sat", "hybrid", "lift", "recursive")

sat = _search("sat")
cpsat = _search("cpsat")
hybrid = _search("hybrid")
lift = _search("lift")
recursive = _search("recursive")

#: Packing routes by name. ``"auto"`` is not an entry: it picks one (see :func:`auto_method`).
SOLVERS = {"euler": euler, "outer": outer, "known": known, "sat": sat, "cpsat": cpsat, "hybrid": hybrid,
           "lift": lift, "recursive": recursive}
METHODS: tuple[str, ...] = ("auto",) + tuple(SOLVERS)


def auto_method(problem: PackingProblem) -> str:
    """The route ``"auto"`` takes.

    More than one pinned tile needs the full search (``sat``). Otherwise ``C = 2`` and Wang
    ``C = 3`` get a random-looking SAT-built packing; Wang ``C = 4, 6`` and even corner sets a
    lifted packing; odd corner sets the de Bruijn construction; other Wang sets (``C = 5`` or
    ``>= 7``, or ``C_h != C_v``) the outer product.
    """
    c = problem.colors
    square = problem.colors_v is None or problem.colors_v == problem.colors
    if len(set(problem.fixed)) > 1 or (square and (c == 2 or (c == 3 and problem.kind == "wang"))):
        return "sat"
    if not square:
        return "outer"
    if problem.kind == "wang":
        return "lift" if c in (4, 6) else "outer"
    if c % 2 == 1:
        return "outer"
    return "lift"


def solve(
    problem: PackingProblem,
    *,
    method: str | Any = "auto",
    seed: int | None = None,
    time_limit: float | None = None,
    workers: int | None = None,
    cluster=None,
    progress: Progress | bool = False,
    solver: str | None = None,
) -> Solution:
    """Find a tile packing (or prove that the pinned tiles allow none) and verify it.

    The generic pipeline :func:`tilesolve.family.solve` with the packing family's routes.

    Parameters
    ----------
    problem : PackingProblem
    method : {"auto", "euler", "outer", "known", "sat", "cpsat", "hybrid", "lift", "recursive"} or callable
    seed : int, optional
        The same seed gives the same packing with ``workers=1``; when a search escalates to a
        portfolio, the note and ``Solution.seed`` name the seed that won (rerun it with
        ``workers=1`` to reproduce it). Drawn and recorded when not given.
    time_limit : float, optional
        Seconds for the whole run; expiry gives status ``unknown``.
    workers : int, optional
        CP-SAT workers for ``cpsat`` (default 2); for the heavy-tailed searches
        (:data:`PORTFOLIO_ROUTES`), the processes of the portfolio, this one included
        (default: up to 2, as idle cores allow; ``1`` runs one seed only).
    cluster : str or distributed.Client, optional
        A Dask scheduler address (``tcp://host:8786``): the portfolio's runs go there instead.
    progress : Progress or bool
        Where the search reports (:func:`tilesolve.progress.as_progress`): a lift's levels and
        attempts, a portfolio's seeds.
    solver : str, optional
        PySAT solver of the ``sat`` route (default :data:`PACKING_SAT_SOLVER`).

    Returns
    -------
    Solution
        ``tiling`` is the packing grid (tile indices per eq. 2.1 / 2.5), verified.

    Raises
    ------
    MethodNotApplicable
        E.g. ``euler`` for an even number of corner colours; the message names a route that works.
    InvalidProblem
        Absurd sizes for a solver route (refused before any clause is built).
    """
    if not isinstance(problem, PackingProblem):
        raise InvalidProblem(f"expected a PackingProblem, got {type(problem).__name__}")
    return _solve(problem, method, seed=seed, time_limit=time_limit, progress=progress, solver=solver,
                  workers=workers, cluster=cluster)


def count(problem: PackingProblem, *, method: str = "auto", time_limit: float | None = None,
          progress: Progress | bool = False, force: bool = False, up_to_symmetry: bool = False) -> CountResult:
    """Count all packings of ``problem``'s tile set (C = 2): the notes publish 32 corner and
    203,520 Wang packings.

    With ``up_to_symmetry`` the packings are counted up to translation, rotation, reflection
    and colour permutation (§5.5.3): 1 for corner tiles (as published), 911 for Wang tiles
    (computed here; the notes give no number).
    """
    from tilesolve.constructive.packing_count import count_packings

    if method not in ("auto", "backtrack"):
        raise InvalidProblem(f"unknown count method {method!r}; choose auto or backtrack")
    if problem.fixed or (problem.colors_v is not None and problem.colors_v != problem.colors):
        raise InvalidProblem("packings are counted for square tile sets without pinned tiles")
    return count_packings(problem.kind, problem.colors, up_to_symmetry=up_to_symmetry,
                          deadline=run_deadline(time_limit))


# ----------------------------------------------------------------------------- the family record
def _encode(problem: PackingProblem):
    from tilesolve.encodings.registry import encode
    from tilesolve.engine.packing import check_search_size

    check_search_size(problem)
    return encode("packing-cnf", problem, {"anchor_tile": None if problem.fixed else 0})


def _read(doc: dict, source: str):
    from tilesolve.io.packing_json import packing_from_dict

    return packing_from_dict(doc, source)


def _write(problem: PackingProblem, sol: Solution) -> dict:
    from tilesolve.io.packing_json import packing_to_dict

    return packing_to_dict(problem, sol)


def _draw(problem: PackingProblem, sol: Solution, path, fmt: str, *, indices: bool = False, title: str | None = None,
          notes=(), **_ignored) -> None:
    """SVG (tiles drawn with their edge or corner colours) or PNG of a packing; a grid that is
    not the problem's torus (a C-colour packing is ``C_h**2 x C_v**2``), or a grid cell that
    holds no tile number, is refused (``tilesolve verify`` reports either as a violation)."""
    shape = np.shape(sol.tiling)
    if shape != problem.shape:
        raise InvalidProblem(f"nothing drawn: the grid is {'x'.join(map(str, shape))}, but the file's problem is the "
                             f"{problem.describe()} (tilesolve verify FILE lists the violations)")
    problem.tiles.check_numbers(sol.tiling)
    if fmt == "png":
        from tilesolve.io.png import write_packing_png

        write_packing_png(path, sol.tiling, problem.kind, problem.colors, colors_v=problem.colors_v,
                          caption=[title or f"{problem.describe()} ({sol.method}, seed {sol.seed})"])
        return
    from tilesolve.io.svg_packing import write_packing_svg

    write_packing_svg(path, sol.tiling, problem.kind, problem.colors, colors_v=problem.colors_v, indices=indices,
                      title=title or f"{problem.describe()} ({sol.method}, seed {sol.seed})")


DEMOS = (
    Demo("packing-wang3", "a random-looking SAT-built Wang packing, C = 3 (81 tiles on a 9x9 torus)",
         lambda: PackingProblem("wang", 3), method="sat", draw_options={"indices": True}),
    Demo("packing-corner4", "a lifted corner packing, C = 4 (the notes' backtracking: 280 CPU-days)",
         lambda: PackingProblem("corner", 4), method="lift", draw_options={"indices": True}),
)

def _pins_extent(values) -> tuple[int, int, int, int]:
    cv = values["colors"] if values["colors_v"] is None or values["kind"] != "wang" else values["colors_v"]
    return values["colors"] ** 2, cv**2, 0, values["colors"] ** 2 * cv**2 - 1


def _form_pins(values) -> tuple[tuple[int, int, int], ...]:
    grid = values.get("pins") or []
    return tuple((r, c, t) for r, row in enumerate(grid) for c, t in enumerate(row) if t >= 0)


def _form_build(values) -> tuple[PackingProblem, dict]:
    """The studio form's packing (the ``pack`` options; painted pins as ``fixed``)."""
    colors_v = values["colors_v"] if values["kind"] == "wang" else None
    return PackingProblem(values["kind"], values["colors"], colors_v, fixed=_form_pins(values)), {}


def _form_command(values) -> tuple[list[str], dict[str, str]]:
    words = ["pack", "--kind", values["kind"], "--colors", str(values["colors"])]
    if values["kind"] == "wang" and values["colors_v"] is not None:
        words += ["--colors-v", str(values["colors_v"])]
    for r, c, t in _form_pins(values):
        words += ["--fix", f"{r},{c},{t}"]
    return words, {}


FORM = Form(
    fields=(
        Field("kind", "choice", "tiles", "wang", "Wang tiles (coloured edges) or corner tiles (coloured corners)",
              choices=("wang", "corner"), option="--kind"),
        Field("colors", "int", "colours C", 3, "C >= 2: the complete set has C^4 tiles", low=2, high=6,
              option="--colors"),
        Field("colors_v", "int", "vertical colours C_v", None, "Wang tiles only: colours of the E/W edges",
              low=2, high=6, option="--colors-v", when=({"kind": ("wang",)},)),
        Field("pins", "cells", "pinned tiles", None, "click a cell to pin its tile (§5.5.4 puzzles)",
              option="--fix", extent=_pins_extent),
    ),
    build=_form_build,
    command=_form_command,
    cells=lambda problem, sol: sol.tiling,
)

FAMILY = register(Family(
    name="packing",
    title="tile packings: every tile of a complete Wang or corner set once on a torus (class notes §5.5)",
    problem_type=PackingProblem,
    routes=SOLVERS,
    auto=auto_method,
    verify=packing_violations,
    count=count,
    encode=_encode,
    codecs=(Codec(PACKING, VERSIONS, _read, _write),),
    draw=_draw,
    demos=DEMOS,
    commands=("tilesolve.cli.pack:pack", "tilesolve.cli.tiles:tiles"),
    form=FORM,
    route_help={
        "euler": "Eulerian constructions (Wang outer product, odd-C corner de Bruijn torus)",
        "outer": "the constructions over random Eulerian circuits",
        "known": "the notes' published C = 4 packings",
        "sat": "full CNF + PySAT (Glucose 4.2), pinned tiles, unsat with a checked DRAT proof",
        "cpsat": "full model in OR-tools CP-SAT",
        "hybrid": "Wang: random Eulerian N/S columns + SAT",
        "lift": "a packing over C/k colours + a k-ary layer by SAT",
        "recursive": "a C-1 packing pinned, completed by SAT (Figs. 5.11-5.12)",
    },
))
