"""Dappled tilings end to end: one facade over the constructive and solver routes.

Every question about dappled tilings (Kaji, Derouet-Jourdan, Ochiai, *Dappled tiling*,
2016) goes through :func:`solve`, :func:`count` or :func:`crosscheck`:

``solve``
    looks the method up in :data:`SOLVERS` (a registry, so the CLI's ``--method``
    choices come from its keys), runs it, and checks every tiling it returns with the
    independent verifier :func:`tilesolve.verify.dappled_violations`. A constructive
    output that fails verification is never returned: the facade falls back to the SAT
    route and says so in ``Solution.notes``.
``count``
    the exact number of tilings by the transfer-matrix programme, or by solver
    enumeration (blocking clauses) where the transfer matrix does not apply.
``crosscheck``
    runs both routes on one problem and confirms that they agree.

Examples
--------
>>> from tilesolve.model import DappledProblem
>>> p = DappledProblem.from_strings("12x8", ["H0=2", "V1=2"])
>>> s = solve(p, seed=1)
>>> s.status.value, s.method
('sat', 'constructive')
>>> count(DappledProblem.from_strings("3x3", ["H0=2", "V1=2"])).value
174
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np

from tilesolve.errors import InvalidProblem, MethodNotApplicable
from tilesolve.family import Codec, Demo, Family, Field, Form, RunOptions, form_size, raise_if_interrupted, register
from tilesolve.family import run_deadline
from tilesolve.family import solve as _solve
from tilesolve.io.dappled_json import DAPPLED_FORMATS, DAPPLED_PROBLEM, DAPPLED_SOLUTION
from tilesolve.model.dappled import DappledProblem
from tilesolve.model.solution import CountResult, CrosscheckReport, Solution, Status
from tilesolve.progress import Progress, as_progress
from tilesolve.verify.dappled import dappled_violations, hamming_distance

__all__ = [
    "FAMILY",
    "SOLVERS",
    "METHODS",
    "COUNT_METHODS",
    "CountResult",
    "CrosscheckReport",
    "constructive",
    "sat",
    "maxsat",
    "cpsat",
    "solve",
    "count",
    "crosscheck",
]


def _solver_notes(run: RunOptions, name: str) -> tuple[str, ...]:
    if run.option("initial") is not None:
        return (f"the initial tiling is only used by the constructive route, not by {name!r}",)
    return ()


def constructive(problem: DappledProblem, run: RunOptions) -> Solution:
    """The papers' algorithms (Algorithm 1, the |T| >= 3 algorithm, Algorithm 2, Remark 3.4).

    Uses ``run.options["initial"]`` as the input tiling when given (dappled §2).
    """
    from tilesolve.constructive.dappled import make_dappled

    if problem.closest_to is not None:
        raise MethodNotApplicable("the constructive route does not minimise distance; use method 'maxsat'")
    t0 = time.perf_counter()
    tiling = make_dappled(problem, run.option("initial"), seed=run.seed)
    return Solution(Status.SAT, tiling, method="constructive", seed=run.seed, time_s=time.perf_counter() - t0)


def sat(problem: DappledProblem, run: RunOptions) -> Solution:
    """SAT on the CNF encoding (§6 item 8); unsat answers carry a checked DRAT proof."""
    from tilesolve.engine.dappled import solve_sat
    from tilesolve.engine.sat import DEFAULT_SAT_SOLVER

    sol = solve_sat(problem, deadline=run.deadline, seed=run.seed, solver=run.solver or DEFAULT_SAT_SOLVER)
    return sol.replace(notes=_solver_notes(run, "sat") + sol.notes)


def maxsat(problem: DappledProblem, run: RunOptions) -> Solution:
    """The closest tiling to ``closest_to``, proved optimal (§6 item 3)."""
    from tilesolve.engine.dappled import solve_maxsat

    sol = solve_maxsat(problem, deadline=run.deadline, seed=run.seed)
    return sol.replace(notes=_solver_notes(run, "maxsat") + sol.notes)


def cpsat(problem: DappledProblem, run: RunOptions) -> Solution:
    """OR-tools CP-SAT on the same clauses (``closest_to`` as the objective)."""
    from tilesolve.engine.cpsat import DEFAULT_CPSAT_WORKERS
    from tilesolve.engine.dappled import solve_cpsat

    sol = solve_cpsat(problem, deadline=run.deadline, seed=run.seed,
                      num_workers=run.workers or DEFAULT_CPSAT_WORKERS)
    return sol.replace(notes=_solver_notes(run, "cpsat") + sol.notes)


#: Solving routes by name. ``"auto"`` is not an entry: it picks one (:func:`auto_method`).
SOLVERS = {"constructive": constructive, "sat": sat, "maxsat": maxsat, "cpsat": cpsat}
METHODS: tuple[str, ...] = ("auto",) + tuple(SOLVERS)
COUNT_METHODS: tuple[str, ...] = ("auto", "transfer", "enumerate")


def auto_method(problem: DappledProblem) -> str:
    """MaxSAT for closest tilings, the constructive algorithms for plain problems, SAT otherwise."""
    if problem.closest_to is not None:
        return "maxsat"
    if problem.is_plain:
        return "constructive"
    return "sat"


def solve(
    problem: DappledProblem,
    *,
    method: str | Any = "auto",
    seed: int | None = None,
    time_limit: float | None = None,
    initial: np.ndarray | None = None,
    progress: bool = False,
) -> Solution:
    """Find an L-dappled tiling (or prove none exists) and verify it independently.

    The generic pipeline :func:`tilesolve.family.solve` with the dappled family's routes.

    Parameters
    ----------
    problem : DappledProblem
    method : {"auto", "constructive", "sat", "maxsat", "cpsat"} or callable
        ``"auto"`` uses the constructive algorithms (Algorithm 1, the trivial |T|>=3
        algorithm, Algorithm 2 / Remark 3.4 for cyclic problems) when they apply, MaxSAT
        for closest tilings, and SAT otherwise (also when a constructive output ever fails
        verification). A callable is a route ``(problem, run) -> Solution``.
    seed : int, optional
        Seeds the random initial tiling of the constructive route and solver randomness;
        drawn and recorded in ``Solution.seed`` when not given.
    time_limit : float, optional
        Seconds for the whole run; a route that runs out returns status ``unknown``.
    initial : numpy.ndarray, optional
        Input tiling for Algorithm 1/2 (§2: "we can start with a random tiling or a user
        specified one").
    progress : bool
        Show the running route and elapsed time on stderr (only when it is a terminal).

    Returns
    -------
    Solution
        ``sat``/``optimal`` with a verified tiling, ``unsat`` with a reason, or ``unknown``.

    Raises
    ------
    MethodNotApplicable
        An explicitly requested method cannot handle the problem; the message names one
        that can.
    """
    if not isinstance(problem, DappledProblem):
        raise InvalidProblem(f"expected a DappledProblem, got {type(problem).__name__}")
    return _solve(problem, method, seed=seed, time_limit=time_limit, progress=progress,
                  options={"initial": initial} if initial is not None else None)


def count(
    problem: DappledProblem,
    *,
    method: str = "auto",
    time_limit: float | None = None,
    progress: Progress | bool = False,
    force: bool = False,
) -> CountResult:
    """Count the tilings that satisfy ``problem`` exactly.

    ``"transfer"`` is the row-by-row transfer-matrix programme (exact big integers; plain
    and cyclic conditions, fixed cells); ``"enumerate"`` enumerates solver models with
    blocking clauses (any problem, small counts); ``"auto"`` prefers the transfer matrix.
    For T = {0,1} and L = {H_0^2, V_1^2} the counts are OEIS A206994 (Remark 1.4).

    ``progress`` (:func:`tilesolve.progress.as_progress`) shows the row sweeps done, with an
    ETA, and announces the planner's estimate before a transfer count expected to take more
    than :data:`ANNOUNCE_S` seconds.
    """
    from tilesolve.constructive.dappled_count import DEFAULT_MAX_OPERATIONS, count_dappled, enumeration_guard
    from tilesolve.deadline import TimeLimitReached

    if method not in COUNT_METHODS:
        raise InvalidProblem(f"unknown count method {method!r}; choose one of {', '.join(COUNT_METHODS)}")
    if problem.closest_to is not None:
        raise InvalidProblem("counting ignores a closest-to target; drop it")
    progress = as_progress(progress)
    t0 = time.perf_counter()
    deadline = run_deadline(time_limit)
    note = None
    if method in ("auto", "transfer"):
        try:
            if progress:
                _announce(problem, progress)
            with progress.task("counting: row sweeps", unit="row") as bar:
                value = count_dappled(problem, progress=bar.set, deadline=deadline,
                                      max_operations=None if (time_limit is not None or force) else
                                      DEFAULT_MAX_OPERATIONS)
            return CountResult(value, Status.SAT, "transfer", time.perf_counter() - t0)
        except TimeLimitReached as exc:
            return CountResult(None, Status.UNKNOWN, "transfer", time.perf_counter() - t0, str(exc))
        except MethodNotApplicable as exc:
            if method == "transfer":
                raise
            if method == "auto":
                enumeration_guard(problem, time_limit=time_limit, force=force,
                                  why=f"the transfer matrix does not apply ({exc})")
            note = f"transfer matrix not applicable ({exc}); counted by solver enumeration"
    from tilesolve.engine.dappled import count_by_enumeration

    res = count_by_enumeration(problem, deadline=deadline, progress=progress)
    notes = [n for n in (res.note, note) if n]
    return res.replace(time_s=time.perf_counter() - t0, note="; ".join(notes) or None)


#: A transfer count planned to take longer than this (seconds) is announced with its estimate.
ANNOUNCE_S = 2.0


def _announce(problem: DappledProblem, progress: Progress) -> None:
    """Print the planner's estimate before a long transfer count (nothing when it is quick or
    when the planner refuses: the count says why)."""
    from tilesolve.constructive.dappled_count import plan_count

    try:
        plan = plan_count(problem)
    except MethodNotApplicable:
        return
    if plan.route in ("transfer", "torus") and plan.seconds > ANNOUNCE_S:
        progress.announce(f"counting: about {plan.seconds:.0f} s by the planner's estimate ({plan.describe()})")


def crosscheck(problem: DappledProblem, *, seed: int | None = None, time_limit: float | None = None) -> CrosscheckReport:
    """Run the constructive and solver routes on ``problem`` and confirm they agree.

    Checks (DESIGN.md, "Cross-checks"): the constructive output passes the verifier and
    satisfies the CNF encoding; SAT and CP-SAT agree on solvability; every tiling they
    return passes the verifier; on small plain grids the transfer-matrix count equals the
    enumeration count. Ctrl-C stops it (``KeyboardInterrupt``), whichever route is running.
    """
    from tilesolve.engine.dappled import tiling_satisfies_encoding
    from tilesolve.family import draw_seed

    seed = draw_seed() if seed is None else seed
    report = CrosscheckReport()
    try:
        cons = constructive(problem, RunOptions(seed))
    except MethodNotApplicable as exc:
        report.lines.append(f"skip constructive route: {exc}")
    else:
        bad = dappled_violations(problem, cons.tiling)
        report.add(not bad, f"constructive tiling verifies ({len(bad)} violations)")
        if not bad:
            report.add(tiling_satisfies_encoding(problem, cons.tiling), "constructive tiling satisfies the CNF encoding")
            report.verdicts["constructive"] = Status.SAT
    for name in ("sat", "cpsat") + (("maxsat",) if problem.closest_to is not None else ()):
        sol = raise_if_interrupted(SOLVERS[name](problem, RunOptions(seed, run_deadline(time_limit))))
        if sol.status.has_tiling:
            bad = dappled_violations(problem, sol.tiling)
            report.add(not bad, f"{name}: {sol.status.value}, tiling verifies ({len(bad)} violations)")
        else:
            report.lines.append(f"     {name}: {sol.status.value}" + (f" ({sol.reason})" if sol.reason else ""))
        if sol.status != Status.UNKNOWN:
            report.verdicts[name] = Status.SAT if sol.status.has_tiling else Status.UNSAT
    report.add_agreement()
    if problem.closest_to is None and problem.size <= 16:
        a, b = count(problem, method="enumerate"), None
        try:
            b = count(problem, method="transfer")
        except MethodNotApplicable:
            pass
        if b is not None:
            report.add(a.value == b.value, f"count: enumeration {a.value} = transfer matrix {b.value}")
    return report


# ----------------------------------------------------------------------------- the family record
def _objective(problem: DappledProblem, tiling) -> int | None:
    return None if problem.closest_to is None else hamming_distance(tiling, problem.closest_to)


def _encode(problem: DappledProblem):
    from tilesolve.encodings.dappled import encode_wcnf
    from tilesolve.encodings.registry import encode

    return encode_wcnf(problem) if problem.closest_to is not None else encode("dappled-cnf", problem)


def _read_problem(doc: dict, source: str):
    from tilesolve.io.dappled_json import problem_from_dict

    return problem_from_dict(doc, source), None


def _read_solution(doc: dict, source: str):
    from tilesolve.io.dappled_json import solution_from_dict

    return solution_from_dict(doc, source)


def _write_solution(problem: DappledProblem, sol: Solution) -> dict:
    from tilesolve.io.dappled_json import solution_to_dict

    return solution_to_dict(problem, sol, arrays=True)


def _draw(problem: DappledProblem, sol: Solution, path, fmt: str, *, repeat: int = 1, grid=None,
          title: str | None = None, notes=()) -> None:
    """SVG (legend, conditions, N x N repeat) or PNG (large grids, the same lines under it) of a
    dappled tiling."""
    legend = [f"{sol.status.value} by {sol.method}" + (f", seed {sol.seed}" if sol.seed is not None else "")]
    if sol.objective is not None:
        legend.append(f"distance to the target: {sol.objective} cells")
    if fmt == "png":
        from tilesolve.io.png import write_png

        caption = [title] if title else []
        caption += [problem.describe(), *legend, *notes] + ([f"shown {repeat}x{repeat}"] if repeat > 1 else [])
        write_png(path, sol.tiling, repeat=repeat, grid=grid, caption=caption, legend=True)
        return
    from tilesolve.io.svg import write_svg

    write_svg(path, sol.tiling, problem=problem, repeat=repeat, grid=grid, title=title, notes=legend + list(notes))


def _example_31() -> DappledProblem:
    """Example 3.1 (dappled §3.1): limits that vary across the grid.

    The paper gives ``p0(i, j) = q1(i, j) = ceil((i+1)/5) + 1`` and ``p1(i, j) = ceil((m-i)/5) + 1``
    with ``i`` the column; the extraction lost ``q0``, which we take equal to ``p1`` so that
    the text's description holds (left: short white rows and orange columns; right: the reverse).
    """
    from tilesolve.model.dappled import Condition

    rows, m = 30, 60
    i = np.arange(m)
    left = np.tile((np.ceil((i + 1) / 5) + 1).astype(np.int32), (rows, 1))
    right = np.tile((np.ceil((m - i) / 5) + 1).astype(np.int32), (rows, 1))
    conds = (Condition("H", (0,), left), Condition("V", (1,), left),
             Condition("H", (1,), right), Condition("V", (0,), right))
    return DappledProblem(rows, m, conditions=conds)


def _disc_target() -> DappledProblem:
    """The closest dappled tiling to a disc (dappled §6 item 3), runs <= 3 both ways."""
    n = 24
    yy, xx = np.mgrid[0:n, 0:n]
    target = (((yy - (n - 1) / 2) ** 2 + (xx - (n - 1) / 2) ** 2) <= (n * 0.36) ** 2).astype(np.int8)
    return DappledProblem.from_strings(f"{n}x{n}", ["H0=3", "V0=3", "H1=3", "V1=3"], closest_to=target)


DEMOS = (
    Demo("plain", "Algorithm 1: tile 0 runs <= 2 across, tile 1 runs <= 3 down",
         lambda: DappledProblem.from_strings("32x20", ["H0=2", "V1=3"])),
    Demo("cyclic", "Algorithm 2: cyclic, runs <= 3 both ways, shown 2x2",
         lambda: DappledProblem.from_strings("16x12", ["H0=3", "V0=3", "H1=3", "V1=3"], cyclic=True),
         draw_options={"repeat": 2}),
    Demo("nonuniform", "Example 3.1: limits vary from left to right", _example_31),
    Demo("closest", "the nearest tiling with runs <= 3 to a disc (MaxSAT)", _disc_target),
    Demo("three-tiles", "|T| = 3, no run longer than 2",
         lambda: DappledProblem.from_strings("30x18", ["H0=2", "V0=2", "H1=2", "V1=2", "H2=2", "V2=2"], n_tiles=3)),
)

def _cells_extent(values) -> tuple[int, int, int, int]:
    rows, cols = form_size(values["size"])
    return rows, cols, 0, values["tiles"] - 1


def _form_grid(values, name: str):
    grid = values.get(name)
    if grid is None or all(v < 0 for row in grid for v in row):
        return None
    return np.array(grid, dtype=np.int64)


def _form_build(values) -> tuple[DappledProblem, dict]:
    """The studio form's problem (the ``dappled solve`` options, painted cells as arrays)."""
    import re

    target = _form_grid(values, "target")
    if target is not None and (target < 0).any():
        raise InvalidProblem("target tiling: paint every cell (or clear it) to ask for the closest tiling")
    conds = [c for c in re.split(r"[,\s]+(?![^{]*\})", values["cond"].strip()) if c]
    counts = values["count"].split() if values["count"] else ()
    return DappledProblem.from_strings(values["size"], conds, n_tiles=values["tiles"], cyclic=values["cyclic"],
                                       counts=counts, fixed=_form_grid(values, "fixed"), closest_to=target), {}


def _grid_text(grid) -> str:
    return "".join("".join("?" if v < 0 else str(v) for v in row) + "\n" for row in grid)


def _form_command(values) -> tuple[list[str], dict[str, str]]:
    words = ["dappled", "solve", "--size", values["size"], "--tiles", str(values["tiles"])]
    if values["cond"].strip():
        words += ["--cond", values["cond"].strip()]
    if values["cyclic"]:
        words.append("--cyclic")
    for k in (values["count"] or "").split():
        words += ["--count", k]
    files = {}
    for name, option in (("fixed", "--fix"), ("target", "--closest-to")):
        if _form_grid(values, name) is not None:
            files[f"{name}.txt"] = _grid_text(values[name])
            words += [option, f"{name}.txt"]
    return words, files


FORM = Form(
    fields=(
        Field("size", "size", "size (WxH)", "16x12", "W columns by H rows", high=1 << 22, option="--size"),
        Field("tiles", "int", "tiles |T|", 2, "tiles 0..K-1", low=2, high=10, option="--tiles"),
        Field("cond", "text", "conditions", "H0=2, V1=2", "e.g. H0=2 (no horizontal run of tile 0 longer "
              "than 2), V{0,1}=3", option="--cond"),
        Field("cyclic", "bool", "cyclic (torus)", False, "runs wrap around both edges (§3.2)", option="--cyclic"),
        Field("count", "text", "tile counts", "", "e.g. 1=30..34 (tile 1 on 30 to 34 cells)", option="--count"),
        Field("fixed", "cells", "fixed cells", None, "click a cell to fix its tile", option="--fix",
              extent=_cells_extent),
        Field("target", "cells", "closest-to target", None, "paint a target: the nearest dappled tiling "
              "(Hamming distance) is found", option="--closest-to", extent=_cells_extent),
    ),
    build=_form_build,
    command=_form_command,
    cells=lambda problem, sol: sol.tiling,
)


def _warm() -> None:
    """Compile the constructive kernels now (the studio's long-lived server)."""
    from tilesolve.constructive.dappled import compile_kernels

    compile_kernels()


FAMILY = register(Family(
    name="dappled",
    title="dappled tilings: no long runs of a tile (Kaji, Derouet-Jourdan, Ochiai 2016)",
    problem_type=DappledProblem,
    routes=SOLVERS,
    auto=auto_method,
    verify=dappled_violations,
    fallback="sat",
    objective=_objective,
    count=count,
    encode=_encode,
    codecs=(
        Codec(DAPPLED_SOLUTION, DAPPLED_FORMATS[DAPPLED_SOLUTION], _read_solution, _write_solution),
        Codec(DAPPLED_PROBLEM, DAPPLED_FORMATS[DAPPLED_PROBLEM], _read_problem),
    ),
    draw=_draw,
    demos=DEMOS,
    commands=("tilesolve.cli.dappled:dappled",),
    form=FORM,
    warm=_warm,
    route_help={
        "constructive": "Algorithm 1, |T| >= 3, Algorithm 2 / Remark 3.4 (numba)",
        "sat": "CNF + PySAT (CaDiCaL), unsat with a checked DRAT proof",
        "maxsat": "closest tiling by RC2 or the lazy decomposition",
        "cpsat": "OR-tools CP-SAT",
    },
))
