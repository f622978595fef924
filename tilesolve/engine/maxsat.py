"""MaxSAT backend: RC2 (PySAT) with time limits, and an exact lazy decomposition.

Both routes take hard clauses (a :class:`~tilesolve.encodings.ClauseSet`, CNF or list) and
unit soft clauses of weight 1 — the shape of a closest-tiling problem (dappled paper §6
item 3: minimise the Hamming distance to a target) — and return a
:class:`~tilesolve.engine.result.Result` with ``cost`` and ``Status.OPTIMAL``.

Lazy decomposition (:func:`solve_lazy`)
---------------------------------------
For soft units whose "reference" assignment (the target) satisfies every soft clause,
most hard clauses are already satisfied by the reference. :func:`solve_lazy` starts from
the hard clauses the reference falsifies and repeats:

1. split the active hard clauses into connected components (clauses sharing a variable);
2. solve each component exactly with RC2 (only the softs on its variables), keeping the
   reference value everywhere else; the sum of component optima is the optimum of a
   *relaxation* (a subset of the hard clauses), hence a lower bound on the true optimum;
3. if the combined assignment satisfies every hard clause it is feasible and its cost
   equals the lower bound: it is optimal. Otherwise add the falsified clauses and repeat.

Every step is exact (no heuristic reduction); the loop ends because the active set
grows. Components that did not change are not solved again. This pays off on large grids,
where one RC2 run spends most of its time on bookkeeping over all soft clauses per core.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Sequence

import numpy as np

from tilesolve.deadline import NO_LIMIT, Deadline
from tilesolve.engine.result import Result, run_interruptible
from tilesolve.engine.sat import LOAD_CHUNK, _chunks, _millions, _size_of, canonical_solver_name, seeded_phases
from tilesolve.errors import InternalError, MethodNotApplicable
from tilesolve.model.solution import Status

__all__ = ["DEFAULT_MAXSAT_ORACLE", "solve_wcnf", "solve_lazy", "RC2Options"]

#: RC2's oracle: Glucose 3 supports interrupts (time limits) and was the fastest
#: oracle on closest-tiling instances (benchmarks/bench_closest.py).
DEFAULT_MAXSAT_ORACLE = "glucose3"


@dataclass(frozen=True)
class RC2Options:
    """Options of :class:`pysat.examples.rc2.RC2` (see its documentation).

    ``stratified`` selects :class:`~pysat.examples.rc2.RC2Stratified` (useful only with
    distinct weights).
    """

    adapt: bool = False
    exhaust: bool = False
    minz: bool = False
    trim: int = 0
    stratified: bool = False

    def make(self, wcnf, solver: str):
        from pysat.examples.rc2 import RC2, RC2Stratified

        cls = RC2Stratified if self.stratified else RC2
        return cls(wcnf, solver=solver, adapt=self.adapt, exhaust=self.exhaust, minz=self.minz, trim=self.trim)


class _Stopped(Exception):
    """A component solve was stopped by the time limit or Ctrl-C."""

    def __init__(self, why: str) -> None:
        super().__init__(why)
        self.why = why


def _interrupter(rc2):
    def interrupt() -> None:
        try:
            rc2.interrupt()
        except NotImplementedError:  # oracle without interrupt: the call runs to its end
            pass

    return interrupt


def _check_oracle(solver: str, time_limit: float | None) -> str:
    name = canonical_solver_name(solver)
    if time_limit is not None and name.startswith(("cadical", "kissat", "lingeling")):
        raise MethodNotApplicable(
            f"RC2 with oracle {name} cannot honour a time limit (the oracle cannot be interrupted); "
            f"use the default oracle {DEFAULT_MAXSAT_ORACLE}"
        )
    return name


def solve_wcnf(
    hard,
    soft: Sequence[int],
    *,
    weights: Sequence[int] | None = None,
    solver: str = DEFAULT_MAXSAT_ORACLE,
    options: RC2Options = RC2Options(),
    deadline: Deadline = NO_LIMIT,
    seed: int | None = None,
) -> Result:
    """Solve hard clauses plus soft unit clauses with RC2.

    Parameters
    ----------
    hard : ClauseSet, CNF or iterable of clauses
    soft : sequence of int
        One literal per soft unit clause.
    weights : sequence of int, optional
        Default 1 each.
    solver : str
        RC2's SAT oracle (PySAT name).
    deadline : Deadline, optional
        The whole run's deadline; on expiry the result is ``UNKNOWN`` with
        ``stats["lower_bound"]``. Loading the hard clauses into the oracle counts (chunks with
        deadline checks).
    seed : int, optional
        Shuffles the order of the soft clauses (which steers the cores RC2 meets first) and
        draws the oracle's initial phases (:func:`~tilesolve.engine.sat.seeded_phases`):
        where several assignments reach the optimum, different seeds may end in different
        ones; the same seed gives the same one (RC2 and its oracle are deterministic). The
        optimum itself does not depend on the seed.

    Examples
    --------
    >>> r = solve_wcnf([[1, 2]], [-1, -2])
    >>> r.status.value, r.cost
    ('optimal', 1)
    """
    from pysat.formula import WCNF

    t0 = time.perf_counter()
    time_limit = deadline.time_limit
    name = _check_oracle(solver, time_limit)
    solver_name = f"rc2/{name}"
    soft = [int(lit) for lit in soft]
    wts = [1] * len(soft) if weights is None else [int(wt) for wt in weights]
    if seed is not None:  # the order of the soft clauses steers which cores RC2 meets first
        from tilesolve._random import rng_from_seed

        order = rng_from_seed(seed).permutation(len(soft)).tolist()
        soft, wts = [soft[i] for i in order], [wts[i] for i in order]
    n_hard = _size_of(hard)
    top = hard.max_var() if hasattr(hard, "max_var") else 0
    if not hasattr(hard, "max_var"):
        hard = list(_chunks(hard))  # lists: read once for the largest variable
        top = max((abs(v) for ch in hard for c in ch for v in c), default=0)
        n_hard = sum(len(ch) for ch in hard)
    # RC2 gets the soft clauses only; the hard ones go straight into its oracle, in chunks
    # with deadline checks (RC2 would load them in one uninterruptible call).
    w = WCNF()
    for lit, wt in zip(soft, wts):
        w.append([lit], weight=wt)
    w.nv = max(top, max((abs(v) for v in soft), default=0))
    stats: dict = {"hard": 0, "soft": len(w.soft)}

    def unknown(reason: str) -> Result:
        return Result(Status.UNKNOWN, None, time.perf_counter() - t0, None, stats, solver=solver_name, reason=reason)

    with options.make(w, name) as rc2:
        chunks = hard if isinstance(hard, list) else _chunks(hard, LOAD_CHUNK)
        for ch in chunks:
            if deadline.expired():
                of = f" of {_millions(n_hard)}" if n_hard is not None else ""
                return unknown(f"time limit of {time_limit:.3g} s reached while loading the hard clauses into "
                               f"{solver_name} ({_millions(stats['hard'])}{of} loaded)")
            if min(map(len, ch), default=1) == 0:
                return Result(Status.UNSAT, None, time.perf_counter() - t0, None, stats, solver=solver_name,
                              reason="hard clauses contain the empty clause")
            rc2.oracle.append_formula(ch)
            stats["hard"] += len(ch)
        if seed is not None:
            try:
                rc2.oracle.set_phases(seeded_phases(w.nv, seed))
            except NotImplementedError:
                pass
        model, stop = run_interruptible(lambda: rc2.compute(expect_interrupt=True), _interrupter(rc2), deadline)
        stats["lower_bound"] = int(rc2.cost)
        cost = int(rc2.cost)
    rt = time.perf_counter() - t0
    if model is not None:  # RC2 returns None when interrupted, so a model means it finished
        return Result(Status.OPTIMAL, list(model), rt, None, stats, cost=cost, solver=solver_name)
    if stop is not None:
        return Result(Status.UNKNOWN, None, rt, None, stats, solver=solver_name, reason=_stop_reason(stop, time_limit))
    return Result(Status.UNSAT, None, rt, None, stats, solver=solver_name, reason="hard clauses are unsatisfiable")


def _stop_reason(stop: str, time_limit: float | None) -> str:
    if stop == "time limit" and time_limit is not None:
        return f"time limit of {time_limit:.3g} s reached while solving"
    return "interrupted (Ctrl-C)"


class _Component:
    """Clauses of one connected component and (for large ones) a live incremental RC2."""

    __slots__ = ("clauses", "vars", "loc", "pending", "rc2", "values", "cost", "dirty", "softs_given")

    def __init__(self) -> None:
        self.clauses: list[list[int]] = []  # global literals
        self.vars: list[int] = []  # global variable of local id i + 1
        self.loc: dict[int, int] = {}
        self.pending: list[list[int]] = []  # clauses not yet given to self.rc2
        self.rc2 = None
        self.values: np.ndarray | None = None
        self.cost = 0
        self.dirty = True
        self.softs_given = 0  # variables whose soft clause the live RC2 already has

    def add(self, clause: list[int]) -> None:
        for v in clause:
            a = abs(v)
            if a not in self.loc:
                self.vars.append(a)
                self.loc[a] = len(self.vars)
        self.clauses.append(clause)
        self.pending.append(clause)
        self.dirty = True

    def absorb(self, other: "_Component") -> None:
        for c in other.clauses:
            self.add(c)
        other.close()

    def close(self) -> None:
        if self.rc2 is not None:
            self.rc2.delete()
            self.rc2 = None

    def solve(self, soft_of: dict[int, int], name: str, deadline: Deadline, options: RC2Options,
              keep_min: int) -> bool:
        """Re-optimise after new clauses; False when the component is unsatisfiable."""
        from pysat.formula import WCNF

        loc = self.loc
        local = lambda c: [loc[v] if v > 0 else -loc[-v] for v in c]  # noqa: E731
        if self.rc2 is None:
            w = WCNF()
            w.hard = [local(c) for c in self.clauses]
            w.nv = len(self.vars)
            for v in self.vars:
                sl = soft_of.get(v)
                if sl is not None:
                    w.append([loc[v] if sl > 0 else -loc[v]], weight=1)
            rc2 = options.make(w, name)
            self.softs_given = len(self.vars)
        else:
            rc2 = self.rc2
            for c in self.pending:
                rc2.add_clause(local(c))
            for v in self.vars[self.softs_given:]:
                sl = soft_of.get(v)
                if sl is not None:
                    rc2.add_clause([loc[v] if sl > 0 else -loc[v]], weight=1)
            self.softs_given = len(self.vars)
        self.pending = []
        if len(self.clauses) >= keep_min:  # large: run interruptibly (time limit, Ctrl-C)
            model, stop = run_interruptible(lambda: rc2.compute(expect_interrupt=True), _interrupter(rc2), deadline)
            if model is None and stop is not None:
                rc2.delete()
                self.rc2 = None
                raise _Stopped(stop)
        else:
            model = rc2.compute()
        self.cost = int(rc2.cost)
        if len(self.clauses) >= keep_min and model is not None:
            self.rc2 = rc2  # large: keep its cores for the next round
        else:
            rc2.delete()
            self.rc2 = None
        if model is None:
            return False
        val = np.zeros(len(self.vars) + 1, dtype=bool)
        m = np.asarray(model, dtype=np.int64)
        m = m[np.abs(m) <= len(self.vars)]
        val[np.abs(m)] = m > 0
        self.values = val[1:]
        self.dirty = False
        return True


def solve_lazy(
    hard,
    soft: Sequence[int],
    reference: np.ndarray,
    *,
    solver: str = DEFAULT_MAXSAT_ORACLE,
    options: RC2Options = RC2Options(),
    keep_min: int = 64,
    fallback_fraction: float = 0.2,
    deadline: Deadline = NO_LIMIT,
) -> Result:
    """Exact MaxSAT by lazy hard clauses and independent components (see module doc).

    Parameters
    ----------
    hard : ClauseSet
        Hard clauses; every block must be ``grid_only`` (all its variables have a value in
        ``reference``).
    soft : sequence of int
        Soft unit literals (weight 1), each satisfied by ``reference``.
    reference : numpy.ndarray of bool
        ``reference[v]`` for every variable (index 0 unused).
    keep_min : int
        Components with at least this many clauses keep an incremental RC2 between
        rounds (their cores stay valid when hard clauses are added); smaller ones are
        solved from scratch.
    fallback_fraction : float
        When one component holds more than this fraction of all hard clauses the
        decomposition no longer pays: the rest of the time goes to one RC2 run on the
        whole formula (:func:`solve_wcnf`; ``stats["fallback"]`` says so).
    deadline : Deadline, optional
        The whole run's deadline. The decomposition is
        deterministic and takes no seed.

    Returns
    -------
    Result
        ``OPTIMAL`` with a full model over ``reference``'s variables; ``UNSAT`` when a
        relaxation (hence the problem) is infeasible; ``UNKNOWN`` on the time limit, with
        ``stats["lower_bound"]`` from the last complete relaxation.

    Examples
    --------
    >>> from tilesolve.encodings import ClauseSet
    >>> cs = ClauseSet(); cs.add_array(np.array([[1, 2, 3], [2, 3, 4]]), "demo")
    >>> r = solve_lazy(cs, [-1, -2, -3, -4], np.zeros(5, dtype=bool))
    >>> r.status.value, r.cost
    ('optimal', 1)
    """
    t0 = time.perf_counter()
    time_limit = deadline.time_limit
    name = _check_oracle(solver, time_limit)
    if any(not b.grid_only for b in getattr(hard, "blocks", [])):
        raise MethodNotApplicable("lazy decomposition needs clauses over grid variables only (no counts)")
    soft_arr = np.asarray(soft, dtype=np.int64).ravel()
    ref = np.asarray(reference, dtype=bool)
    if (ref[np.abs(soft_arr)] != (soft_arr > 0)).any():
        raise ValueError("the reference assignment must satisfy every soft literal")
    soft_of = dict(zip(np.abs(soft_arr).tolist(), soft_arr.tolist()))
    n_hard = len(hard)
    from networkx.utils import UnionFind

    uf = UnionFind()  # variables joined by a clause share a component
    comps: dict[int, _Component] = {}  # root variable -> component
    cur = ref.copy()
    stats = {"rounds": 0, "component_solves": 0, "lower_bound": 0, "active_clauses": 0}
    solver_name = f"lazy/{name}"

    def stop(status: Status, reason: str) -> Result:
        return Result(status, None, time.perf_counter() - t0, None, stats, solver=solver_name, reason=reason)

    try:
        while True:
            if deadline.expired():
                raise _Stopped("time limit")
            new: list[list[int]] = []
            for block, rows in hard.falsified(cur):
                for lo in range(0, len(rows), 1 << 16):  # list conversion is slow: deadline checks between parts
                    if deadline.expired():
                        raise _Stopped("time limit")
                    part = rows[lo : lo + (1 << 16)]
                    new.extend(block.lits[part].tolist() if block.lits is not None else [block.ragged[i] for i in part])
            if not new:
                break
            if any(len(c) == 0 for c in new):
                return stop(Status.UNSAT, "hard clauses contain the empty clause")
            stats["rounds"] += 1
            stats["active_clauses"] += len(new)
            for i, c in enumerate(new):
                if i % 4096 == 0 and deadline.expired():
                    raise _Stopped("time limit")
                roots = {uf[abs(v)] for v in c}
                parts = [comps.pop(r) for r in roots if r in comps]
                root = abs(c[0])
                for v in c[1:]:
                    uf.union(root, abs(v))
                root = uf[root]
                if parts:
                    parts.sort(key=lambda k: len(k.clauses), reverse=True)
                    base = parts[0]
                    for other in parts[1:]:
                        base.absorb(other)
                else:
                    base = _Component()
                base.add(c)
                comps[root] = base
            largest = max(len(k.clauses) for k in comps.values())
            if largest > fallback_fraction * n_hard:
                for comp in comps.values():
                    comp.close()
                comps = {}
                r = solve_wcnf(hard, soft, solver=name, deadline=deadline, options=options)
                r.stats = {**stats, **r.stats, "fallback": "rc2 on the whole formula"}
                r.runtime = time.perf_counter() - t0
                return r
            cur = ref.copy()
            lb = 0
            for comp in comps.values():
                if comp.dirty:
                    if deadline.expired():
                        raise _Stopped("time limit")
                    ok = comp.solve(soft_of, name, deadline, options, keep_min)
                    stats["component_solves"] += 1
                    if not ok:
                        return stop(Status.UNSAT, "a relaxation of the hard clauses is unsatisfiable")
                cur[np.asarray(comp.vars, dtype=np.int64)] = comp.values
                lb += comp.cost
            stats["lower_bound"] = lb
    except _Stopped as exc:
        return stop(Status.UNKNOWN, _stop_reason(exc.why, time_limit))
    except KeyboardInterrupt:
        return stop(Status.UNKNOWN, "interrupted (Ctrl-C)")
    finally:
        for comp in comps.values():
            comp.close()
    stats["components"] = len(comps)
    stats["largest_component"] = max((len(k.clauses) for k in comps.values()), default=0)
    idx = np.arange(1, cur.size, dtype=np.int64)
    model = np.where(cur[1:], idx, -idx).tolist()
    cost = int((cur[np.abs(soft_arr)] != (soft_arr > 0)).sum())
    if cost != stats["lower_bound"]:  # cannot happen: softs outside every component keep their value
        raise InternalError(f"lazy decomposition: feasible cost {cost} differs from the bound {stats['lower_bound']}")
    return Result(Status.OPTIMAL, model, time.perf_counter() - t0, None, stats, cost=cost, solver=solver_name)
