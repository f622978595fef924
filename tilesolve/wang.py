"""Wang tilings of boards end to end: one facade over the linear algorithm and the solvers.

Every question about Wang tilings of boards (Derouet-Jourdan, Kaji, Mizoguchi, *A linear
algorithm for brick Wang tiling*, 2016) goes through :func:`solve`, :func:`count` or
:func:`crosscheck`, as for dappled tilings (:mod:`tilesolve.dappled`):

``solve``
    looks the method up in :data:`SOLVERS`, runs it, and checks every tiling it returns
    with the independent verifier :func:`tilesolve.verify.board.board_violations`.
``count`` / ``enumerate_tilings``
    all valid tilings of small boards by solver enumeration with blocking clauses (the
    paper's future work, §5).
``crosscheck``
    runs the linear algorithm, SAT and CP-SAT on one problem and confirms they agree.

Examples
--------
>>> from tilesolve.model.board import Board, BoardProblem, WangTileSet
>>> p = BoardProblem(Board.rect(4, 4), WangTileSet.brick(3), [1] * 16)
>>> s = solve(p, seed=1)
>>> s.status.value, s.method
('sat', 'linear')
>>> count(BoardProblem(Board.rect(1, 1), WangTileSet.brick(3))).value
36
"""

from __future__ import annotations

import time
from typing import Callable, Iterator

import numpy as np

from tilesolve.engine.routes import lookup, verified
from tilesolve.errors import InvalidProblem, MethodNotApplicable
from tilesolve.model.board import BoardProblem
from tilesolve.model.solution import CountResult, CrosscheckReport, Solution, Status
from tilesolve.verify.board import board_violations

__all__ = [
    "SOLVERS", "METHODS", "solve", "solve_sat", "solve_cpsat", "enumerate_tilings", "count",
    "CountResult", "crosscheck", "CrosscheckReport",
]


def solve_sat(problem: BoardProblem, *, seed=None, time_limit=None, proof: bool = True,
              solver: str | None = None) -> Solution:
    """Decide ``problem`` with a SAT solver (:mod:`tilesolve.encodings.wang`).

    UNSAT answers carry a DRAT proof checked by :mod:`tilesolve.verify.drat` (when the
    formula is small enough to check); a time limit gives ``unknown``.
    """
    from tilesolve.encodings.wang import encode_wang
    from tilesolve.engine.certificates import unsat_solution
    from tilesolve.deadline import Deadline
    from tilesolve.engine.sat import DEFAULT_SAT_SOLVER, solve_cnf

    t0 = time.perf_counter()
    deadline = Deadline(time_limit)
    enc = encode_wang(problem)
    stats = {"variables": enc.n_vars, "clauses": len(enc.clauses), "encode_s": round(time.perf_counter() - t0, 6)}
    r = solve_cnf(enc.clauses, solver=solver or DEFAULT_SAT_SOLVER, time_limit=deadline.remaining(),
                  with_proof=proof, seed=seed)
    stats["solve_s"] = round(r.runtime, 6)
    notes = tuple(r.stats.get("notes", ()))
    if r.status is Status.SAT:
        return Solution(Status.SAT, enc.decode(r.model), "sat", r.solver, seed, time.perf_counter() - t0,
                        notes=notes, stats=stats)
    if r.status is Status.UNSAT:
        rem = deadline.remaining()
        sol = unsat_solution(enc.clauses, r, method="sat", seed=seed, t0=t0, stats=stats, check_proof=True,
                              proof_time_limit=None if rem is None else max(rem, 1.0))
        return sol.replace(notes=sol.notes + notes)
    return Solution(Status.UNKNOWN, None, "sat", r.solver, seed, time.perf_counter() - t0, reason=r.reason,
                    notes=notes, stats=stats)


def solve_cpsat(problem: BoardProblem, *, seed=None, time_limit=None) -> Solution:
    """Decide ``problem`` with OR-tools CP-SAT (table constraints, one per cell)."""
    from tilesolve.encodings.wang import build_cpsat_wang
    from tilesolve.engine.cpsat import solve_cp_model

    t0 = time.perf_counter()
    cp = build_cpsat_wang(problem)
    r = solve_cp_model(cp.model, cp.bools, time_limit=time_limit, seed=seed)
    stats = dict(r.stats)
    if r.status.has_tiling:
        return Solution(Status.SAT, cp.decode(r.model), "cpsat", "cp-sat", seed, time.perf_counter() - t0, stats=stats)
    return Solution(r.status, None, "cpsat", "cp-sat", seed, time.perf_counter() - t0, reason=r.reason, stats=stats)


def _linear(problem: BoardProblem, *, seed=None, time_limit=None) -> Solution:
    from tilesolve.constructive.brick import solve_linear

    return solve_linear(problem, seed=seed)


def _theorem7(problem: BoardProblem, *, seed=None, time_limit=None) -> Solution:
    from tilesolve.constructive.wang import theorem7_solve

    return theorem7_solve(problem, seed=seed, time_limit=time_limit)


def _sat(problem: BoardProblem, *, seed=None, time_limit=None) -> Solution:
    return solve_sat(problem, seed=seed, time_limit=time_limit)


def _cpsat(problem: BoardProblem, *, seed=None, time_limit=None) -> Solution:
    return solve_cpsat(problem, seed=seed, time_limit=time_limit)


#: Solving routes by name. ``"auto"`` is not an entry: it picks one (see :func:`solve`).
SOLVERS: dict[str, Callable[..., Solution]] = {
    "linear": _linear,
    "sat": _sat,
    "cpsat": _cpsat,
    "theorem7": _theorem7,
}
METHODS: tuple[str, ...] = ("auto",) + tuple(SOLVERS)


def solve(problem: BoardProblem, *, method: str | Callable[..., Solution] = "auto", seed: int | None = None,
          time_limit: float | None = None) -> Solution:
    """Find a valid tiling of a board problem (or prove none exists), verified independently.

    Parameters
    ----------
    problem : BoardProblem
    method : {"auto", "linear", "sat", "cpsat", "theorem7"} or callable
        ``"linear"`` is the linear algorithm of §4 (brick Wang tiles, no line limits);
        ``"theorem7"`` tiles outside a small core leaves first and solves the core by SAT
        (any three-boundary tile set; ``unknown`` when the core fails);
        ``"auto"`` uses it where it applies and falls back to SAT, saying why in
        ``Solution.notes``.
    seed : int, optional
    time_limit : float, optional
        Seconds for the solver routes; expiry gives ``unknown``.

    Returns
    -------
    Solution
        ``tiling`` is an ``(n_cells, 4)`` array of leg colours (W, N, E, S).
    """
    if not isinstance(problem, BoardProblem):
        raise InvalidProblem(f"expected a BoardProblem, got {type(problem).__name__}")
    t0 = time.perf_counter()
    notes: list[str] = []
    runner, name = lookup(method, SOLVERS, lambda: "linear")
    try:
        sol = runner(problem, seed=seed, time_limit=time_limit)
    except MethodNotApplicable as exc:
        if method != "auto":
            raise
        notes.append(f"linear algorithm not applicable ({exc}); solved with 'sat'")
        sol = SOLVERS["sat"](problem, seed=seed, time_limit=time_limit)
    sol = verified(sol, lambda tiling: board_violations(tiling, problem))
    return sol.replace(notes=tuple(notes) + sol.notes, time_s=time.perf_counter() - t0, seed=seed)


def enumerate_tilings(problem: BoardProblem, *, limit: int | None = None,
                      time_limit: float | None = None) -> Iterator[np.ndarray]:
    """Yield every valid tiling (``(n_cells, 4)`` arrays), each once, by SAT enumeration."""
    from tilesolve.encodings.wang import encode_wang
    from tilesolve.engine.sat import ModelEnumerator

    enc = encode_wang(problem)
    for model in ModelEnumerator(enc.clauses, enc.projection, limit=limit, time_limit=time_limit):
        yield enc.decode(model)


def count(problem: BoardProblem, *, time_limit: float | None = None) -> CountResult:
    """Count the valid tilings of a (small) board problem exactly, by enumeration."""
    from tilesolve.encodings.wang import encode_wang
    from tilesolve.engine.sat import count_models

    t0 = time.perf_counter()
    enc = encode_wang(problem)
    mc = count_models(enc.clauses, enc.projection, time_limit=time_limit)
    if not mc.complete:
        return CountResult(None, Status.UNKNOWN, "enumerate", time.perf_counter() - t0,
                           f"stopped after {mc.count} tilings: {mc.reason}")
    return CountResult(mc.count, Status.SAT, "enumerate", time.perf_counter() - t0)


def crosscheck(problem: BoardProblem, *, seed: int | None = None, time_limit: float | None = None,
               methods=("linear", "sat", "cpsat")) -> CrosscheckReport:
    """Run several routes on ``problem``: verdicts must agree and every tiling must verify.

    The linear algorithm's tiling must also satisfy the CNF encoding.
    """
    from tilesolve.encodings.wang import encode_wang
    from tilesolve.engine.sat import solve_cnf

    rep = CrosscheckReport()
    for name in methods:
        try:
            sol = SOLVERS[name](problem, seed=seed, time_limit=time_limit)
        except MethodNotApplicable as exc:
            rep.lines.append(f"skip {name}: {exc}")
            continue
        if sol.status.has_tiling:
            bad = board_violations(sol.tiling, problem)
            rep.add(not bad, f"{name}: sat, tiling verifies ({len(bad)} violations)")
            if name == "linear" and not bad:
                enc = encode_wang(problem)
                r = solve_cnf(enc.clauses, assumptions=enc.assumptions_for(sol.tiling))
                rep.add(r.status is Status.SAT, "linear tiling satisfies the CNF encoding")
        else:
            rep.lines.append(f"     {name}: {sol.status.value}" + (f" ({sol.reason})" if sol.reason else ""))
        if sol.status is not Status.UNKNOWN:
            rep.verdicts[name] = Status.SAT if sol.status.has_tiling else Status.UNSAT
    rep.add_agreement()
    return rep
