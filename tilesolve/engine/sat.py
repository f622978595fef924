"""SAT backend over PySAT: time limits, proofs, enumeration and counting.

Generic over problem families: it takes clauses (a
:class:`~tilesolve.encodings.ClauseSet`, a :class:`pysat.formula.CNF` or a list of
lists) and returns :class:`~tilesolve.engine.result.Result` records.

Time limits
-----------
PySAT solvers differ in what they can do (checked against ``pysat.solvers`` 1.9):

* MiniSat-family solvers (Glucose, Maple*, MiniSat, MergeSat, Ergo) support
  ``interrupt()``: a :class:`threading.Timer` interrupts ``solve_limited``.
* CaDiCaL (all versions) and Kissat cannot be interrupted but accept a conflict budget:
  the search runs in conflict-budget slices on a fixed schedule (so that the answer does not
  depend on the machine's speed), the deadline is checked between slices, and a slice that
  would run past it is shortened (CaDiCaL keeps its learnt clauses across calls).
* Lingeling supports neither; a time limit is refused for it.

Loading the clauses into the solver counts against the limit too: they go in chunks of
:data:`LOAD_CHUNK` clauses with a deadline check between chunks, so a formula too large to
load in time ends ``unknown`` ("time limit of 3 s reached while loading the formula into
cadical153 (1.2 M of 8.4 M clauses)") within about one chunk's time of the limit.

A call stopped by the time limit or by Ctrl-C returns ``Status.UNKNOWN``, never ``UNSAT``.

Seeds
-----
A ``seed`` draws the solver's initial phase of every variable (``set_phases``) from
:func:`tilesolve._random.rng_from_seed`, and sets the solver's own random seed where PySAT
exposes one (CaDiCaL, Glucose 4.2). The solvers are deterministic, so the same formula,
solver and seed give the same model; different seeds start the search from different
assignments and, on formulas with many models, end in different ones.

Proofs
------
``with_proof=True`` logs a DRAT proof where the solver can (see :func:`proof_solvers`;
CaDiCaL 1.0.3/1.5.3/1.9.5/3.0.0, Glucose 3/4/4.2, Gluecard 3/4, Lingeling, MapleChrono,
MapleCM, MapleSAT and Ergo do; Kissat, MergeSat, Minicard and the MiniSats do not).
Proofs are only as good as the solver's logging: MapleSAT was seen to emit a unit lemma
that is neither RUP nor RAT (a cyclic 9x9 dappled problem with a count), which
:mod:`tilesolve.verify.drat` rejects, so routes that check proofs report ``unknown``.
Every proof is checked, whatever its size (:mod:`tilesolve.engine.certificates`).
"""

from __future__ import annotations

import contextlib
import gc
import threading
import time
from itertools import repeat
from typing import Callable, Iterable, Iterator, Mapping, Sequence

import numpy as np

from tilesolve.deadline import NO_LIMIT, Deadline
from tilesolve.engine.result import Result, run_interruptible
from tilesolve.errors import BackendUnavailable, InvalidProblem, MethodNotApplicable
from tilesolve.model.solution import CountResult, Status

__all__ = [
    "DEFAULT_SAT_SOLVER",
    "LOAD_CHUNK",
    "SatSession",
    "seeded_phases",
    "solve_cnf",
    "ModelEnumerator",
    "count_models",
    "canonical_solver_name",
    "sat_solvers",
    "proof_solvers",
]

DEFAULT_SAT_SOLVER = "cadical153"

#: Clauses handed to the solver per call while loading (a deadline check between calls;
#: about 0.1 s of loading each on a laptop core).
LOAD_CHUNK = 1 << 14

#: Conflict budget of the first slice and the largest one (solvers without ``interrupt``).
SLICE_CONFLICTS = (100, 32000)

#: Solvers whose random seed PySAT's ``configure`` can set, and the option's name.
_SEED_OPTION = {"cadical153": "seed", "cadical195": "seed", "cadical300": "seed", "glucose42": "rnd-seed"}


def canonical_solver_name(name: str) -> str:
    """Map any PySAT alias (``"cd15"``, ``"g4"``...) to its canonical name.

    Raises
    ------
    BackendUnavailable
        For a name PySAT does not know.
    """
    from pysat.solvers import SolverNames

    key = str(name).lower()
    for canon, aliases in vars(SolverNames).items():
        if canon.startswith("_"):
            continue
        if key == canon or key in aliases:
            return canon
    raise BackendUnavailable(f"unknown SAT solver {name!r}; available: {', '.join(sat_solvers())}")


class _QuietDel:
    """Silence PySAT's ``__del__`` noise from solver objects whose constructor failed.

    On exit the garbage collector runs when ``collect`` is true (a half-built object may sit in
    a reference cycle). It is a full collection, costly in a large process, so a caller that
    knows no constructor failed turns it off.
    """

    def __init__(self, collect: bool = True):
        self.collect = collect

    def __enter__(self):
        import sys

        self._hook = sys.unraisablehook
        sys.unraisablehook = lambda info: None
        return self

    def __exit__(self, *exc):
        import gc
        import sys

        if self.collect:
            gc.collect()
        sys.unraisablehook = self._hook


def sat_solvers() -> list[str]:
    """Canonical names of the PySAT solvers that can be created here."""
    from pysat.solvers import Solver, SolverNames

    out = []
    with _QuietDel():
        for canon, aliases in vars(SolverNames).items():
            if canon.startswith("_"):
                continue
            try:
                with Solver(name=aliases[0]):
                    out.append(canon)
            except Exception:  # noqa: BLE001 - a solver not compiled into this pysat build
                continue
    return out


_PROOF_CACHE: dict[str, bool] = {}


def proof_solvers() -> list[str]:
    """Solvers that log a DRAT proof (probed: refute a tiny formula, read the proof)."""
    from pysat.solvers import Solver

    out = []
    with _QuietDel():
        for name in sat_solvers():
            if name not in _PROOF_CACHE:
                ok = False
                try:
                    with Solver(name=name, bootstrap_with=[[1, 2], [-1, 2], [1, -2], [-1, -2]], with_proof=True) as s:
                        ok = s.solve() is False and s.get_proof() is not None
                except Exception:  # noqa: BLE001 - NotImplementedError or an unsupported option
                    ok = False
                _PROOF_CACHE[name] = ok
            if _PROOF_CACHE[name]:
                out.append(name)
    return out


def _chunks(formula, size: int = 1 << 16) -> Iterator[list[list[int]]]:
    if hasattr(formula, "chunks"):
        yield from formula.chunks(size)
    elif hasattr(formula, "clauses"):
        cl = formula.clauses
        for i in range(0, len(cl), size):
            yield cl[i : i + size]
    else:
        batch: list[list[int]] = []
        for c in formula:
            batch.append(list(c))
            if len(batch) >= size:
                yield batch
                batch = []
        if batch:
            yield batch


@contextlib.contextmanager
def _gc_paused() -> Iterator[None]:
    """No cyclic garbage collection while the block runs: loading makes millions of short-lived
    clause lists, each a tracked container, and the collections they trigger cost more than
    the lists (a third of the load time on a million cells)."""
    was = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if was:
            gc.enable()


#: PySAT backends whose native solver is a handle attribute that ``pysolvers.<name>_add_cl``
#: takes: their clauses are added from C (``map``) rather than by PySAT's Python loop.
_NATIVE_HANDLES = {"cadical103": "cadical", "cadical153": "cadical", "cadical195": "cadical",
                   "glucose3": "glucose", "glucose4": "glucose", "glucose42": "glucose", "minisat22": "minisat"}


def _chunk_loader(solver, name: str) -> Callable[[list[list[int]]], None]:
    """A function adding a chunk of clauses to ``solver`` (a :class:`pysat.solvers.Solver`
    for the backend ``name``).

    For the backends in :data:`_NATIVE_HANDLES` the native ``add_cl`` runs once per clause
    from C (``map``) instead of PySAT's ``append_formula``, which loops in Python; a clause
    it reports as conflicting marks the solver's status, as PySAT's own ``add_clause`` does.
    Any other backend loads through ``append_formula``.
    """
    import pysolvers

    backend = getattr(solver, "solver", None)
    handle = getattr(backend, _NATIVE_HANDLES.get(name, ""), None)
    add = getattr(pysolvers, f"{name}_add_cl", None)
    if handle is None or add is None or not hasattr(backend, "status"):
        return solver.append_formula

    def load(chunk: list[list[int]]) -> None:
        if not all(list(map(add, repeat(handle), chunk))):  # a list: every clause is added
            backend.status = False

    return load


def _size_of(formula) -> int | None:
    """Number of clauses, when it is known without iterating."""
    if hasattr(formula, "clauses"):
        return len(formula.clauses)
    try:
        return len(formula)
    except TypeError:
        return None


def _millions(n: int) -> str:
    return f"{n / 1e6:.1f} M" if n >= 100_000 else f"{n:,}"


def seeded_phases(n_vars: int, seed) -> list[int]:
    """Random preferred literals for variables ``1..n_vars`` drawn from ``seed``.

    Examples
    --------
    >>> seeded_phases(4, 1) == seeded_phases(4, 1), len(seeded_phases(4, 1))
    (True, 4)
    """
    from tilesolve._random import rng_from_seed

    v = np.arange(1, n_vars + 1, dtype=np.int64)
    return np.where(rng_from_seed(seed).random(n_vars) < 0.5, v, -v).tolist()


class SatSession:
    """One PySAT solver with tilesolve's time-limit, interrupt and proof handling.

    Always use it as a context manager (it owns a native solver).

    Parameters
    ----------
    formula : ClauseSet, CNF or iterable of clauses
    solver : str
        PySAT solver name or alias.
    with_proof : bool
        Ask for DRAT proof logging; silently off for solvers that cannot log one
        (``self.proof_logging`` says which happened).
    seed : int, optional
        Draws the initial phases (see "Seeds" above) and sets the solver's random seed
        where it has one.
    deadline : Deadline, optional
        Loading stops when it passes; :meth:`solve` then answers ``unknown`` at once
        (:attr:`stopped` says why).
    options : mapping of str to int, optional
        The solver's own settings, set before the formula is loaded (CaDiCaL's options, e.g.
        ``{"elim": 0}``); a solver without settings refuses them.

    Examples
    --------
    >>> with SatSession([[1, 2], [-1]]) as s:
    ...     r = s.solve()
    >>> r.status.value, r.model
    ('sat', [-1, 2])
    """

    def __init__(self, formula, solver: str = DEFAULT_SAT_SOLVER, with_proof: bool = False, seed: int | None = None,
                 deadline: Deadline | None = None, options: Mapping[str, int] | None = None):
        from pysat.solvers import Solver

        self.name = canonical_solver_name(solver)
        self.seed = seed
        t0 = time.perf_counter()
        self.proof_logging = False
        self._s = None
        try:
            if with_proof:
                with _QuietDel(collect=False) as quiet:  # a refused with_proof leaves a half-built object behind
                    try:
                        self._s = Solver(name=self.name, with_proof=True)
                        self.proof_logging = True
                    except NotImplementedError:
                        quiet.collect = True
            if self._s is None:
                self._s = Solver(name=self.name)
        except Exception as exc:  # noqa: BLE001
            raise BackendUnavailable(f"cannot start SAT solver {self.name}: {exc}") from exc
        self.notes: list[str] = []
        if with_proof and not self.proof_logging:
            self.notes.append(f"{self.name} cannot log proofs")
        if seed is not None:
            option = _SEED_OPTION.get(self.name)
            if option is not None:
                self._s.configure({option: int(seed)})
        if options:
            self._s.configure(dict(options))
        self.n_clauses = 0
        self.empty_clause = False
        #: Why loading stopped early (the deadline passed), else None.
        self.stopped: str | None = None
        total = _size_of(formula)
        load = _chunk_loader(self._s, self.name)
        with _gc_paused():
            for ch in _chunks(formula, LOAD_CHUNK):
                if deadline is not None and deadline.expired():
                    of = f" of {_millions(total)}" if total is not None else ""
                    self.stopped = (f"time limit of {deadline.time_limit:.3g} s reached while loading the formula "
                                    f"into {self.name} ({_millions(self.n_clauses)}{of} clauses loaded)")
                    break
                if min(map(len, ch), default=1) == 0:
                    # Some PySAT backends mishandle an empty clause; it decides the formula anyway.
                    self.empty_clause = True
                    ch = [c for c in ch if len(c)]
                load(ch)
                self.n_clauses += len(ch)
        if seed is not None and self.stopped is None:
            self.set_phases(seeded_phases(self._s.nof_vars(), seed))
        self.load_time = time.perf_counter() - t0
        self._mode = self._probe_limits()
        self._rate: float | None = None  # conflicts per second in the last budget slice

    def _probe_limits(self) -> str:
        try:
            self._s.interrupt()
            self._s.clear_interrupt()
            return "interrupt"
        except NotImplementedError:
            pass
        try:
            self._s.conf_budget(-1)
            return "budget"
        except NotImplementedError:
            return "none"

    def __enter__(self) -> "SatSession":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def close(self) -> None:
        if self._s is not None:
            self._s.delete()
            self._s = None

    # -------------------------------------------------------------------- solving
    def add_clause(self, clause: Sequence[int]) -> None:
        if len(clause) == 0:
            self.empty_clause = True
        else:
            self._s.add_clause(list(map(int, clause)))

    def set_phases(self, literals: Sequence[int]) -> None:
        """Preferred polarities (e.g. a target tiling); ignored by solvers without phases."""
        try:
            self._s.set_phases(list(map(int, literals)))
        except NotImplementedError:
            pass

    def solve(self, assumptions: Sequence[int] = (), deadline: Deadline = NO_LIMIT) -> Result:
        """Decide the formula under ``assumptions``.

        Returns ``SAT`` with the model, ``UNSAT`` (with the DRAT proof when logging and
        no assumptions were used), or ``UNKNOWN`` at the ``deadline`` (the whole run's; the
        reason names its limit) or on Ctrl-C.
        """
        t0 = time.perf_counter()
        time_limit = deadline.time_limit
        assumptions = list(map(int, assumptions))
        stats = {"load_s": self.load_time, "clauses": self.n_clauses}
        if self.stopped is not None:
            return Result(Status.UNKNOWN, None, 0.0, None, stats, solver=self.name, reason=self.stopped)
        if self.empty_clause:
            return Result(Status.UNSAT, None, 0.0, ["0"] if self.proof_logging else None, stats, solver=self.name,
                          reason="the formula contains the empty clause")
        if time_limit is not None and self._mode == "none":
            raise MethodNotApplicable(
                f"SAT solver {self.name} cannot honour a time limit (no interrupt, no budget); "
                "use cadical153 or glucose4"
            )
        stop_flag = threading.Event()
        if self._mode == "interrupt":
            work = lambda: self._s.solve_limited(assumptions=assumptions, expect_interrupt=True)  # noqa: E731
            interrupt = self._s.interrupt
        elif self._mode == "budget":
            work = lambda: self._solve_sliced(assumptions, deadline, stop_flag)  # noqa: E731
            interrupt = stop_flag.set
        else:  # Lingeling: neither; Ctrl-C is noticed only when the call returns
            work = lambda: self._s.solve(assumptions=assumptions)  # noqa: E731
            interrupt = lambda: None  # noqa: E731
        answer, stop = run_interruptible(work, interrupt, deadline)
        if self._mode == "interrupt":
            self._s.clear_interrupt()
        runtime = time.perf_counter() - t0
        try:
            stats.update(self._s.accum_stats() or {})
        except (NotImplementedError, AttributeError):
            pass
        stats["solve_s"] = runtime
        if answer is True:
            return Result(Status.SAT, self._s.get_model(), runtime, None, stats, solver=self.name)
        if answer is False:
            proof = self._s.get_proof() if (self.proof_logging and not assumptions) else None
            return Result(Status.UNSAT, None, runtime, proof, stats, solver=self.name,
                          reason="unsatisfiable under the assumptions" if assumptions else None)
        if stop == "interrupted":
            reason = "interrupted (Ctrl-C)"
        elif time_limit is not None:
            reason = f"time limit of {time_limit:.3g} s reached while solving"
        else:
            reason = "solver gave up"
        return Result(Status.UNKNOWN, None, runtime, None, stats, solver=self.name, reason=reason)

    def _solve_sliced(self, assumptions: list[int], deadline: Deadline, stop: threading.Event):
        """Conflict-budget slices for solvers without ``interrupt`` (CaDiCaL, Kissat).

        Where a slice ends changes the search (the solver backtracks to the top level), so
        the slices follow a fixed schedule (:data:`SLICE_CONFLICTS`: doubling, then constant)
        and the same formula and seed give the same model whatever the machine's speed.
        Only a slice predicted (from the measured conflict rate) to run past the deadline is
        shortened to what is left, so the deadline is honoured within about one short slice;
        a stop request (Ctrl-C) is seen between slices.
        """
        first, cap = SLICE_CONFLICTS
        budget = first
        while True:
            rem = deadline.remaining()
            if stop.is_set() or (rem is not None and rem <= 0):
                return None
            run = budget
            if rem is not None and self._rate is not None:
                run = int(min(budget, max(50.0, self._rate * rem)))
            t = time.perf_counter()
            self._s.conf_budget(run)
            answer = self._s.solve_limited(assumptions=assumptions)
            if answer is not None:
                return answer
            self._rate = run / max(time.perf_counter() - t, 1e-4)
            budget = min(2 * budget, cap)

    def get_model(self) -> list[int] | None:
        return self._s.get_model()


def solve_cnf(
    formula,
    *,
    solver: str = DEFAULT_SAT_SOLVER,
    with_proof: bool = False,
    assumptions: Sequence[int] = (),
    seed: int | None = None,
    phases: Sequence[int] | None = None,
    deadline: Deadline = NO_LIMIT,
    options: Mapping[str, int] | None = None,
) -> Result:
    """Decide a CNF formula once (loading included in ``runtime``) within the run's ``deadline``.

    ``phases`` (e.g. a target tiling) take precedence over the seed's random phases;
    ``options`` are the solver's own settings (CaDiCaL's, e.g. ``{"elim": 0}``).

    Examples
    --------
    >>> solve_cnf([[1], [-1]], with_proof=True).status.value
    'unsat'
    >>> solve_cnf([[1, 2, 3]], seed=4).model == solve_cnf([[1, 2, 3]], seed=4).model
    True
    """
    t0 = time.perf_counter()
    try:
        session = SatSession(formula, solver=solver, with_proof=with_proof, seed=seed, deadline=deadline,
                             options=options)
    except KeyboardInterrupt:
        return Result(Status.UNKNOWN, None, time.perf_counter() - t0, None, {}, solver=canonical_solver_name(solver),
                      reason="interrupted (Ctrl-C) while loading the formula")
    with session as s:
        if phases is not None:
            s.set_phases(phases)
        r = s.solve(assumptions, deadline=deadline)
        r.runtime = time.perf_counter() - t0
        r.stats["notes"] = list(s.notes)
        r.stats["proof_logging"] = s.proof_logging
        return r


class ModelEnumerator:
    """Iterate over the models of a formula, projected on ``projection`` variables.

    Each model found is blocked by a clause over the projection, so two models that
    differ only on auxiliary variables are reported once. After iteration,
    :attr:`complete` tells whether every model was seen (no limit or time limit hit).

    Examples
    --------
    >>> e = ModelEnumerator([[1, 2]], projection=[1, 2])
    >>> sorted(tuple(m) for m in e), e.complete
    ([(-1, 2), (1, -2), (1, 2)], True)
    """

    def __init__(
        self,
        formula,
        projection: Iterable[int],
        *,
        solver: str = DEFAULT_SAT_SOLVER,
        limit: int | None = None,
        deadline: Deadline = NO_LIMIT,
    ) -> None:
        if limit is not None and limit < 0:
            raise InvalidProblem(f"enumeration limit must be >= 0, got {limit}")
        self.formula = formula
        self.projection = np.asarray(list(projection), dtype=np.int64)
        self.solver = solver
        self.limit = limit
        self.deadline = deadline
        self.count = 0
        self.complete = False
        self.reason: str | None = None

    def __iter__(self) -> Iterator[list[int]]:
        deadline = self.deadline
        proj = self.projection
        with SatSession(self.formula, solver=self.solver, deadline=deadline) as s:
            while True:
                if self.limit is not None and self.count >= self.limit:
                    self.reason = f"limit of {self.limit} models reached"
                    return
                r = s.solve(deadline=deadline)
                if r.status is Status.UNSAT:
                    self.complete = True
                    return
                if r.status is Status.UNKNOWN:
                    self.reason = r.reason
                    return
                model = r.model
                val = np.zeros(int(proj.max(initial=0)) + 1, dtype=bool)
                m = np.asarray(model, dtype=np.int64)
                m = m[np.abs(m) < val.size]
                val[np.abs(m)] = m > 0
                block = np.where(val[proj], -proj, proj)
                self.count += 1
                yield model
                if block.size == 0:  # nothing to block on: the projection has one model
                    self.complete = True
                    return
                s.add_clause(block.tolist())


def count_models(
    formula,
    projection: Iterable[int],
    *,
    solver: str = DEFAULT_SAT_SOLVER,
    deadline: Deadline = NO_LIMIT,
    limit: int | None = None,
    on_model: Callable[[int], object] | None = None,
) -> CountResult:
    """Count projected models by enumeration with blocking clauses.

    Returns a :class:`~tilesolve.model.solution.CountResult`: the exact count (status
    ``sat``), or ``None`` with status ``unknown`` when a limit, the time limit or Ctrl-C
    stopped it (the run's ``deadline``; ``note`` says which, starting with "interrupted" for Ctrl-C;
    ``stats["found"]`` is the number of models seen, a lower bound). ``on_model(count)`` is
    called after each model (progress).

    Examples
    --------
    >>> count_models([[1, 2]], [1, 2]).value
    3
    """
    t0 = time.perf_counter()
    e = ModelEnumerator(formula, projection, solver=solver, limit=limit, deadline=deadline)
    try:
        for _ in e:
            if on_model is not None:
                on_model(e.count)
    except KeyboardInterrupt:
        return CountResult(None, Status.UNKNOWN, "enumerate", time.perf_counter() - t0,
                           f"interrupted (Ctrl-C) after {e.count} models", {"found": e.count})
    if not e.complete:
        return CountResult(None, Status.UNKNOWN, "enumerate", time.perf_counter() - t0,
                           f"{e.reason or 'stopped'} after {e.count} models", {"found": e.count})
    return CountResult(e.count, Status.SAT, "enumerate", time.perf_counter() - t0, None, {"found": e.count})
