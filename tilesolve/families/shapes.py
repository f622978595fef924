"""Polyforms by SAT (class notes Part II §3; Kaplan's heesch-sat): tilings of regions and tori by
polyominoes, polyhexes and polyiamonds, and the classification of a polyform as an isohedral or
periodic tiler or a non-tiler with its Heesch number.

Routes
------
``sat``
    ``tile``: the exact-cover CNF (:func:`tilesolve.encodings.shapes.encode_tiling`) through
    :func:`tilesolve.engine.routes.sat_route` (``unsat`` with a checked DRAT proof);
    ``classify``: :func:`tilesolve.engine.shapes.classify` (torus tilings, then coronas; a
    non-tiler's refuted level with a checked DRAT proof).

:func:`census` classifies every free polyform of a kind and size, on local processes or a Dask
cluster, with the time spent per shape.

Examples
--------
>>> from tilesolve.model.shapes import ShapesProblem, parse_ascii
>>> s = solve(ShapesProblem("classify", (parse_ascii("###", "omino"),)), seed=1)
>>> s.report.verdict, s.report.copies
('isohedral', 1)
"""

from __future__ import annotations

import functools
import time
from dataclasses import dataclass

from tilesolve.errors import InvalidProblem
from tilesolve.families.shapes_form import FORM
from tilesolve.family import Codec, Demo, Family, RunOptions, register, run_deadline
from tilesolve.family import solve as _solve
from tilesolve.io.shapes_json import SHAPES, VERSIONS
from tilesolve.model.shapes import ShapesProblem, ShapesReport, parse_ascii, parse_cells
from tilesolve.model.solution import Solution
from tilesolve.verify.shapes import shapes_violations

__all__ = ["FAMILY", "sat", "solve", "polyforms", "census", "CensusRow", "MAX_LIST_SIZE"]

def sat(problem: ShapesProblem, run: RunOptions) -> Solution:
    """The SAT route: a tiling (exact cover) or a classification (module docstring)."""
    from tilesolve.engine.shapes import SHAPES_SAT_SOLVER, check_size, classify

    t0 = time.perf_counter()
    solver = run.solver or SHAPES_SAT_SOLVER
    if problem.question == "classify":
        return classify(problem, solver=solver, seed=run.seed, deadline=run.deadline, progress=run.progress)
    from tilesolve.encodings.registry import encode
    from tilesolve.engine.routes import sat_route

    check_size(problem)
    return sat_route(encode("shapes-tile-cnf", problem, deadline=run.deadline), run, solver=solver, t0=t0)


def solve(problem: ShapesProblem, *, seed: int | None = None, time_limit: float | None = None,
          progress=False, solver: str | None = None) -> Solution:
    """Answer a polyform question and verify the answer (:func:`tilesolve.family.solve`)."""
    if not isinstance(problem, ShapesProblem):
        raise InvalidProblem(f"expected a ShapesProblem, got {type(problem).__name__}")
    return _solve(problem, "sat", seed=seed, time_limit=time_limit, progress=progress, solver=solver)


#: The largest size listed per grid (about a minute of the generator on one core).
MAX_LIST_SIZE = {"omino": 11, "hex": 9, "iamond": 12}


def polyforms(grid_name: str, size: int, *, holes: bool = True):
    """The free polyforms of ``size`` cells (:func:`tilesolve.constructive.polyforms.free_polyforms`),
    refusing sizes above :data:`MAX_LIST_SIZE`."""
    from tilesolve.constructive.polyforms import free_polyforms
    from tilesolve.model.shapes import grid

    grid(grid_name)
    if not 1 <= size <= MAX_LIST_SIZE[grid_name]:
        raise InvalidProblem(f"{grid_name} polyforms are listed for sizes 1..{MAX_LIST_SIZE[grid_name]} "
                             f"(larger ones take too long here), got {size}")
    return free_polyforms(grid_name, size, holes=holes)


@dataclass(frozen=True)
class CensusRow:
    """One shape of a census: its cells, verdict, Heesch number, copies per period, wall and
    CPU seconds of its classification and verification (the worker's own CPU time: the cost
    of the shape on a loaded machine)."""

    cells: tuple
    verdict: str
    heesch: int | None
    copies: int | None
    time_s: float
    problems: tuple = ()
    cpu_s: float | None = None


def _census_job(grid_name: str, todo: list, options: dict, seed: int) -> CensusRow:
    """Classify job ``seed`` of ``todo`` (``(index in the census, cells)``; a worker's job),
    seeded by the shape's index in the census, and verify its report."""
    from tilesolve.engine.shapes import classify
    from tilesolve.model.shapes import Polyform

    index, cells = todo[seed]
    shape = Polyform(grid_name, cells)
    problem = ShapesProblem("classify", (shape,), **options)
    t0, c0 = time.perf_counter(), time.process_time()
    sol = classify(problem, seed=index)
    bad = tuple(shapes_violations(problem, sol.report))
    r: ShapesReport = sol.report
    return CensusRow(shape.cells, r.verdict, r.heesch, r.copies, time.perf_counter() - t0, bad,
                     time.process_time() - c0)


def census(grid_name: str, size: int, *, holes: bool = False, max_level: int = 3, max_copies: int = 2,
           workers: int | None = 1, cluster=None, time_limit: float | None = None,
           progress=False, done=()) -> tuple[list[CensusRow], int]:
    """Classify every free polyform of ``size`` cells on the grid (without ``holes``: the ones
    without holes), each report verified: ``(rows in the generator's order, shapes)`` (fewer
    rows than shapes when the time limit ran out).

    ``done`` rows (an earlier run of the same census, same options) are kept as they are and
    their shapes not classified again, so a census stopped by its time limit resumes; a row
    whose cells are not a shape of this census is refused.

    Examples
    --------
    >>> rows, n = census("omino", 3)
    >>> [r.verdict for r in rows], n
    (['isohedral', 'isohedral'], 2)
    """
    from tilesolve.progress import as_progress

    shapes = polyforms(grid_name, size, holes=holes)
    index = {s.cells: i for i, s in enumerate(shapes)}
    rows: dict[int, CensusRow] = {}
    for row in done:
        if tuple(map(tuple, row.cells)) not in index:
            raise InvalidProblem(f"a resumed row's cells {list(row.cells)} are not a free {grid_name} polyform of "
                                 f"size {size} of this census")
        rows[index[tuple(map(tuple, row.cells))]] = row
    todo = [(i, list(s.cells)) for i, s in enumerate(shapes) if i not in rows]
    options = {"max_level": max_level, "max_copies": max_copies, "holes": holes}
    run = RunOptions(seed=0, deadline=run_deadline(time_limit), workers=workers, cluster=cluster)
    bar = as_progress(progress)
    with bar.task("shapes", total=len(todo), unit="shape") as task:
        def take(j, row):
            rows[todo[j][0]] = row
            task.advance()
            return False

        job = functools.partial(_census_job, grid_name, todo, options)
        if cluster is None and ((workers or 2) == 1 or len(todo) <= 1):
            # here, as dispatch would run it, without importing the pool and Dask machinery
            for j in range(len(todo)):
                if run.deadline.expired():
                    break
                take(j, job(seed=j))
        else:
            from tilesolve.engine.aperiodic import dispatch

            if dispatch(job, len(todo), run, take, lambda: None):
                raise KeyboardInterrupt  # take never stops the census: dispatch stopped for Ctrl-C
    return [rows[i] for i in sorted(rows)], len(shapes)


# ----------------------------------------------------------------------------- the family record
def _encode(problem: ShapesProblem):
    from tilesolve.encodings.registry import encode
    from tilesolve.engine.shapes import check_size

    if problem.question != "tile":
        raise InvalidProblem("only tiling questions export one CNF (a classification solves many)")
    check_size(problem)
    return encode("shapes-tile-cnf", problem)


def _read(doc: dict, source: str):
    from tilesolve.io.shapes_json import shapes_from_dict

    return shapes_from_dict(doc, source)


def _write(problem: ShapesProblem, sol: Solution) -> dict:
    from tilesolve.io.shapes_json import shapes_to_dict

    return shapes_to_dict(problem, sol)


def refutations(problem: ShapesProblem, sol: Solution):
    """The refuted corona level of a non-tiler's report, or a tiling's own unsat claim."""
    report = sol.report
    if isinstance(report, ShapesReport):
        if report.refutation is None:
            return []
        return [(f"{(report.heesch or 0) + 1} coronas", problem, dict(report.refutation))]
    from tilesolve.model.solution import Status

    return [("the unsat claim", problem, sol.stats)] if sol.status is Status.UNSAT else []


def _draw(problem: ShapesProblem, sol: Solution, path, fmt: str, *, title: str | None = None, repeat: int = 3,
          **_ignored) -> None:
    """The tiling, a torus tiling over ``repeat x repeat`` periods, or the corona patch
    (coloured by corona)."""
    from tilesolve.io.svg_shapes import periodic_rows, write_shapes_picture

    g = problem.geometry
    report = sol.report
    title = title or f"{problem.describe()}: {report.conclusion if report is not None else sol.status.value}"
    if report is None:
        if sol.tiling is None:
            raise InvalidProblem(f"nothing to draw: the answer is {sol.status.value}")
        rows = sol.tiling if problem.lattice is None else periodic_rows(g, sol.tiling, problem.lattice, repeat)
        write_shapes_picture(path, fmt, g, rows, title=title)
    elif report.tiling is not None:
        write_shapes_picture(path, fmt, g, periodic_rows(g, report.tiling, report.lattice, repeat), title=title)
    else:
        write_shapes_picture(path, fmt, g, report.patch, colour_by="label", title=title)


DEMOS = (
    Demo("shapes-pentomino-torus", "the P pentomino tiles a 5-cell torus (a lattice tiling)",
         lambda: ShapesProblem("tile", (parse_ascii("##\n##\n#.", "omino"),), lattice=((5, 0), (2, 1)))),
    Demo("shapes-heesch-hex", "a 6-hex that does not tile, with Heesch number 1: its corona",
         lambda: ShapesProblem("classify", (parse_cells("0,0 0,1 0,2 0,3 1,-1 1,3", "hex"),))),
)

FAMILY = register(Family(
    name="shapes",
    title="polyforms by SAT: tilings of regions and tori, isohedral tilers, Heesch numbers (class notes Part II §3)",
    problem_type=ShapesProblem,
    routes={"sat": sat},
    auto=lambda problem: "sat",
    verify=shapes_violations,
    encode=_encode,
    codecs=(Codec(SHAPES, VERSIONS, _read, _write),),
    draw=_draw,
    demos=DEMOS,
    commands=("tilesolve.cli.shapes:shapes",),
    route_help={"sat": "exact cover / coronas in CNF + PySAT (CaDiCaL 1.5.3), unsat with a checked DRAT proof"},
    refutations=refutations,
    form=FORM,
))
