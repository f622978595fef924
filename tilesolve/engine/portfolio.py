"""Portfolios of randomised runs: local worker processes by default, or a Dask cluster.

A long search (a seeded SAT run on a tile packing, say) has heavy-tailed run times: one seed
finishes in a second where another needs minutes. :func:`run_portfolio` runs several seeds
at once and keeps the first *decisive* answer (``sat``, ``optimal``, or a proved ``unsat``);
the other runs are stopped. A portfolio in which every run ends ``unknown`` is ``unknown``,
never ``unsat`` (DESIGN.md, "Status"). :func:`escalate` is how a facade runs a heavy-tailed
route: one seed in this process, joined by worker processes on the other (idle) cores when
it has not decided within :data:`QUICK_S` seconds.

Where the runs go (DESIGN.md, "Parallel and distributed work")
--------------------------------------------------------------
``workers=N`` (default :data:`DEFAULT_WORKERS` = 2, "both cores")
    ``N`` local worker processes fed from a queue: a seed starts as soon as a worker is
    free. When a run decides, the other workers are terminated (SIGTERM, then SIGKILL):
    a native solver inside a worker cannot be stopped any other way, and nobody waits for
    it. One worker (or one seed) runs in this process, one seed after the other, with no
    pool at all: exactly the plain calls, so results are reproducible.
``cluster="tcp://host:8786"``
    An existing Dask distributed scheduler, at any address ``distributed.Client`` accepts
    (``tcp://``, ``tls://``, ``ws://``...; a bare ``host:port`` means ``tcp://``), or an
    open ``distributed.Client`` (left open). One future per seed; the first decisive one
    wins and the rest are cancelled. Needs ``pip install "tilesolve[cluster]"``.

Dask, not Ray: Dask distributed is a pure-Python wheel with a light scheduler that one
command starts (``dask scheduler`` / ``dask worker ADDRESS``), a ``LocalCluster`` for tests,
and futures with ``as_completed``: all this module needs. Ray brings a large native runtime
for the same one-function-per-seed pattern; one engine is supported, and DESIGN.md forbids
a home-made cluster protocol. Ray is not implemented.

Worker processes
----------------
A worker is a fresh interpreter (:mod:`subprocess`, ``python -c``) that imports this module
and answers over a :func:`multiprocessing.Pipe`. Not a :mod:`multiprocessing` start method:
``spawn`` and ``forkserver`` re-import the caller's ``__main__`` in every worker, which
re-runs a script that lacks an ``if __name__ == "__main__":`` guard (the worker then tries
to start its own pool and dies: a library call must not depend on the caller's script
layout), and ``fork`` copies the parent's threads' locks (OR-tools, numba, the progress
line, a Dask client) in whatever state they were. A worker imports the caller's
``__main__`` only when the task was defined there (see Limits). On Linux a worker dies with
the thread that started it (``prctl(PR_SET_PDEATHSIG)``): a parent killed by SIGTERM or
SIGKILL, which runs no cleanup, leaves no worker running its search to the end; elsewhere a
watchdog thread in the worker checks the parent twice a second. :func:`escalate`'s workers
lower their priority first (:data:`WORKER_NICE`); :func:`run_portfolio`'s keep the
caller's. Start-up cost is the imports: about 0.5 s of CPU per worker for the interpreter
and this module (numpy is most of it; measured with ``python -X importtime``), then the
task's own (the solver stack, pysat, OR-tools, numba: about 1 s more), as with ``spawn``.
On the shared dev machine (2 cores, load 7) a whole :func:`run_portfolio` call of 2 seeds
on 2 workers took 2.0-2.2 s with a task that answers at once and 3.7-4.1 s with the corner
C = 4 lift.

Limits
------
- POSIX only for local workers (the pipe is handed over with ``pass_fds``); on Windows use
  ``workers=1`` or a Dask cluster.
- ``task`` must be picklable: a module-level function, or a :func:`functools.partial` of
  one (the Dask path also takes closures, through cloudpickle). A task defined in
  ``__main__`` makes the workers import that script (as ``__mp_main__``), so the script must
  guard its entry point with ``if __name__ == "__main__":``; one that does not gets an
  :class:`~tilesolve.errors.InvalidProblem` saying so. Tasks from importable modules (all of
  tilesolve's routes) need no guard.
- Each run honours the deadline baked into ``task``; ``deadline`` here is the wall-clock
  budget of the whole portfolio: no seed starts once it is spent, and runs still going
  :data:`GRACE_S` seconds later are stopped (status ``unknown``).
- A Dask task that is already running cannot be stopped: cancelling releases its result,
  and the run ends at its own time limit on the cluster.
- Tasks should not report progress (a worker's ``RunOptions.progress`` pickles as silent);
  the portfolio reports the runs started and finished (``progress``, :mod:`tilesolve.progress`).

Examples
--------
>>> from tilesolve.model.solution import Solution, Status
>>> def task(seed):  # module-level in real code, so that it pickles
...     return Solution(Status.SAT if seed == 2 else Status.UNKNOWN, seed=seed)
>>> s = run_portfolio(task, [0, 1, 2, 3], workers=1)
>>> s.status.value, s.seed, s.notes
('sat', 2, ('portfolio: seed 2 decided it, after 3 of 4 runs started, in this process (1 worker)',))
"""

from __future__ import annotations

import collections
import functools
import gc
import multiprocessing
import os
import pickle
import signal
import subprocess
import sys
import threading
import time
import traceback
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass, field, replace
from multiprocessing.connection import wait as wait_for_any
from typing import Any, Callable, Iterable

from tilesolve.deadline import Deadline
from tilesolve.progress import Progress, Task, as_progress
from tilesolve.engine.result import stop_on
from tilesolve.errors import BackendUnavailable, InvalidProblem
from tilesolve.model.run import RunOptions
from tilesolve.model.solution import Solution, Status

__all__ = ["run_portfolio", "escalate", "seeded_run", "DEFAULT_WORKERS", "GRACE_S", "CONNECT_TIMEOUT_S", "QUICK_S",
           "FIRST_BUDGET_S", "PORTFOLIO_SEEDS", "WORKER_NICE"]

#: Processes when the caller names none: the machines tilesolve targets have two cores (as
#: :data:`tilesolve.engine.cpsat.DEFAULT_CPSAT_WORKERS`). For :func:`escalate` this process
#: counts as one of them, and the others start only on idle cores.
DEFAULT_WORKERS = 2

#: Seconds the runs get, past the deadline, to report before they are stopped: each run
#: honours its own limit, which starts a little later than the portfolio's (process start).
GRACE_S = 1.0

#: Seconds to wait for a Dask scheduler to answer before giving up with a one-line error.
CONNECT_TIMEOUT_S = 5.0

#: Seconds :func:`escalate`'s first run goes alone before worker processes join it (most
#: packings up to C = 6 take well under a second, and then no process is started); by
#: default they join only on idle cores, looked for every QUICK_S seconds.
QUICK_S = 5.0
#: Per-run budget of the first wave of worker runs in :func:`escalate`; it doubles with every
#: wave, so a seed stuck in a heavy tail is abandoned for a fresh one (a restart strategy).
FIRST_BUDGET_S = 20.0
#: Seeds :func:`escalate`'s workers may draw (seed + 1, seed + 2, ...).
PORTFOLIO_SEEDS = 64
#: Niceness of :func:`escalate`'s worker processes (``os.nice``; 19, the lowest priority): a
#: worker runs on a core nothing else wants, and on a busy one it yields to the first run. The
#: first run and its workers share one scheduling group (Linux autogroups: one session), so a
#: worker at the first run's priority halves the first run's share of a loaded machine. With
#: one CPU hog in another session, ``pack --kind corner --colors 8 --method lift --workers 2``
#: took 2.7x and 1.5x the single seed's time (seeds 1, 2) with workers at nice 0, 1.25x and
#: 0.91x niced.
WORKER_NICE = 19

_DECISIVE = (Status.SAT, Status.OPTIMAL, Status.UNSAT)


def run_portfolio(
    task: Callable[[int], Solution],
    seeds: Iterable[int],
    *,
    workers: int = DEFAULT_WORKERS,
    cluster: Any = None,
    deadline: Deadline | None = None,
    progress: Progress | bool = False,
    label: str = "search",
) -> Solution:
    """Run ``task(seed=seed)`` for each seed concurrently; return the first decisive Solution.

    Parameters
    ----------
    task : callable
        ``task(seed=seed) -> Solution``: one independent randomised search that honours its
        own deadline. The seed is passed by keyword: a route becomes a task through
        :func:`seeded_run`, e.g. ``partial(seeded_run, tilesolve.families.packing_search.solve_lift,
        problem, run)``. Must pickle (module docstring).
    seeds : iterable of int
        One run per seed, started in this order (a seed starts when a worker is free).
    workers : int
        Local worker processes (default 2). With one worker, or one seed, the runs happen in
        this process one after the other, exactly as plain calls. Ignored with ``cluster``.
    cluster : str or distributed.Client, optional
        A Dask scheduler address (``"tcp://host:8786"``) or an open ``distributed.Client``:
        run the seeds there instead of in local processes.
    deadline : Deadline, optional
        The run's deadline, the wall-clock budget of the whole portfolio: no seed starts after
        it, and runs still going :data:`GRACE_S` later are stopped (in this process a run cannot
        be stopped from outside: it ends at the deadline baked into ``task``). ``None``: a
        portfolio run on its own, without a limit.
    progress : Progress or bool
        Where to report the runs finished and running (:func:`tilesolve.progress.as_progress`;
        ``True``: a bar on stderr when it is a terminal).
    label : str
        What the status line and messages call the search.

    Returns
    -------
    Solution
        The winning run's Solution, with its own ``seed`` (the winning seed when the run left
        it unset), a note naming the winning seed and the workers, ``time_s`` the portfolio's
        wall-clock time, and ``stats`` extended with ``run_time_s`` (the run's own time),
        ``portfolio_runs`` (runs started) and ``portfolio_workers``. With a single seed the
        run's Solution is returned unchanged. If no run decides, an ``unknown`` Solution
        whose ``reason`` summarises the runs (``"interrupted"`` after Ctrl-C, the summary
        then going to ``notes``).

    Raises
    ------
    InvalidProblem
        No seeds, a seed that is not a non-negative int, ``workers < 1``, a malformed cluster
        address, or a call made while a worker imports an
        unguarded script (module docstring, Limits).
    BackendUnavailable
        ``cluster`` given but Dask distributed is not installed, or the scheduler cannot be
        reached within :data:`CONNECT_TIMEOUT_S` seconds; local workers on Windows.
    TypeError
        ``task`` does not pickle (local workers only).
    BrokenProcessPool
        A worker process died without answering (killed, or a crash in native code).
    Exception
        Whatever a run raised, re-raised here with the same type (its remote traceback as
        ``__cause__``) once the other runs are stopped.

    Ctrl-C stops every run and returns ``unknown`` with reason ``"interrupted"``.

    Examples
    --------
    >>> from tilesolve.model.solution import Solution, Status
    >>> s = run_portfolio(lambda seed: Solution(Status.UNKNOWN, reason="time limit"), [0, 1], workers=1)
    >>> s.status.value, s.reason
    ('unknown', 'no run decided: 2 runs ended unknown (time limit: 2)')
    """
    _refuse_while_importing_main()
    seeds = _check_seeds(seeds)
    progress = as_progress(progress)
    if deadline is None:  # a portfolio that is a run of its own, without a limit
        deadline = Deadline(None)
    if cluster is not None:
        return _run_dask(task, seeds, cluster, deadline, progress, label)
    _check_workers(workers)
    if len(seeds) == 1:
        return _run_single(task, seeds[0], progress, label)
    if workers == 1:
        return _run_inline(task, seeds, deadline, progress, label)
    return _run_pool(task, seeds, min(workers, len(seeds)), deadline, progress, label)


def escalate(route: Callable[[Any, RunOptions], Solution], problem: Any, run: RunOptions, *, name: str) -> Solution:
    """Run a heavy-tailed route: one seed here, joined by worker processes if it is slow.

    The first run, ``route(problem, run)`` with the run's seed, runs in this process with the
    run's whole deadline, exactly the plain call (Ctrl-C reaches it as usual). If it has not
    decided within
    :data:`QUICK_S` seconds, ``workers - 1`` worker processes start beside it and run fresh
    seeds ``seed + 1, seed + 2, ...`` with per-run budgets of :data:`FIRST_BUDGET_S` seconds
    that double with every wave (a restart strategy against heavy tails). The first decisive
    run wins: a worker that wins stops the first run (:func:`tilesolve.engine.result.stop_on`:
    at its next solver call, within 50 ms), the first run that wins terminates the workers.

    The first run is never thrown away, and by default (``workers=None``) a worker starts
    only on a core that sat idle over the last :data:`QUICK_S` seconds (Linux: /proc/stat;
    checked again every :data:`QUICK_S` seconds until one is): a worker on a busy machine
    takes its CPU from the first run (Linux shares the CPU between sessions, and the first
    run and its workers are one session), which made a loaded 2-core machine twice as slow
    (``benchmarks/bench_portfolio.py``). And the workers run at the lowest priority
    (:data:`WORKER_NICE`): a machine that becomes busy after they started takes their CPU, not
    the first run's, and their start-up (imports, the task's set-up) does not slow it either.
    So the default is never slower than the single seed, up to what a worker costs on the
    memory bus. A ``workers`` the caller names is obeyed (the count; they are niced all the same).

    With ``cluster``, every run goes to the Dask cluster (seeds ``seed + 1, ...``); with
    ``workers=1`` and no cluster, this is the plain call.

    Parameters
    ----------
    route : callable
        The raw route, ``route(problem, run) -> Solution`` (the one route signature): a search
        such as :func:`tilesolve.families.packing_search.solve_lift` or
        :func:`tilesolve.engine.packing.solve_sat`, never a facade's ``solve``. Workers run
        it, so it must pickle (a module-level function).
    problem : object
        The problem handed to ``route`` (pickled to the workers).
    run : RunOptions
        The run: ``seed`` (of the first run; the workers take ``seed + 1, ...``), ``deadline``
        (the whole search's; each worker run gets its wave's budget within it,
        :meth:`~tilesolve.deadline.Deadline.within`), ``workers`` (processes, this one included;
        default ``None``: up to :data:`DEFAULT_WORKERS`, as idle cores allow, above; 1 on
        Windows, which has no local workers), ``cluster`` (a Dask scheduler address or client,
        :func:`run_portfolio`), ``progress`` (where the seeds' runs are reported,
        :mod:`tilesolve.progress`) and ``solver`` (for ``route``).
    name : str
        What the progress line and the notes call the search, e.g. ``"lift packing"``.

    Returns
    -------
    Solution
        The winning run's Solution. Once workers have started, its notes say which seed
        decided it and where, and its stats hold ``portfolio_runs`` (worker runs started) and
        ``portfolio_workers``; ``seed`` is the winning seed, so ``workers=1`` with that seed
        reproduces it. ``unknown`` when no run decided: the first run's reason, the workers'
        summary in a note.

    Raises
    ------
    InvalidProblem
        ``workers < 1``, or what ``run_portfolio`` refuses.
    Exception
        Whatever the first run raises, or a worker's exception when the first run did not
        decide (re-raised with its type, as in :func:`run_portfolio`).

    Examples
    --------
    >>> from tilesolve.families.packing_search import solve_lift
    >>> from tilesolve.model.packing import PackingProblem
    >>> s = escalate(solve_lift, PackingProblem("corner", 4), RunOptions(seed=1), name="lift packing")
    >>> s.status.value, s.seed, s.tiling.shape  # decided alone in well under QUICK_S
    ('sat', 1, (16, 16))
    """
    _refuse_while_importing_main()
    workers, cluster = run.workers, run.cluster
    workers_given = workers is not None
    if workers is None:  # no local workers on Windows (module docstring, Limits): one seed
        workers = DEFAULT_WORKERS if os.name == "posix" or cluster is not None else 1
    n = workers
    _check_workers(n)
    if n == 1 and cluster is None:
        with run.progress.task(name, unit=None):
            return route(problem, run)
    worker_run = replace(run, workers=1, cluster=None, progress=False)  # what a worker's run may use
    if cluster is not None:
        task = functools.partial(_wave_run, route, problem, run.seed, n, FIRST_BUDGET_S, worker_run)
        seeds = [run.seed + i for i in range(1, PORTFOLIO_SEEDS + 1)]
        return run_portfolio(task, seeds, cluster=cluster, deadline=run.deadline, progress=run.progress, label=name)
    return _Escalation(route, problem, name, run, worker_run, n - 1, workers_given).run(run.progress)


def seeded_run(route: Callable[[Any, RunOptions], Solution], problem: Any, run: RunOptions, *, seed: int) -> Solution:
    """``route(problem, run)`` with ``seed`` for the run's seed: a route as a portfolio task,
    ``functools.partial(seeded_run, route, problem, run)`` (:func:`run_portfolio`)."""
    return route(problem, replace(run, seed=seed))


def _wave_run(route, problem, seed0, per_wave, first_budget, run: RunOptions, *, seed):
    """One worker run of :func:`escalate`: ``route`` with ``seed`` and the budget of its wave
    (``per_wave`` runs per wave, the first wave ``first_budget`` seconds) within the run's deadline."""
    budget = first_budget * 2 ** ((seed - seed0 - 1) // per_wave)
    return seeded_run(route, problem, replace(run, deadline=run.deadline.within(budget)), seed=seed)


class _Escalation:
    """:func:`escalate` on local processes: the first run in the calling thread, the worker
    pool (runs of ``worker_run`` with their own seeds) driven by a helper thread (which also
    started the workers, so that they die with it)."""

    def __init__(self, route, problem, name, run: RunOptions, worker_run: RunOptions, helpers, obey) -> None:
        self.route, self.problem, self.name, self.seed0 = route, problem, name, run.seed
        self.run_options, self.worker_run = run, worker_run
        self.helpers = helpers  # at most this many workers; all of them when the caller named them (obey)
        self.obey = obey
        self.clock = run.deadline
        self.first_done = threading.Event()  # the first run has returned
        self.stop_first = threading.Event()  # a worker decided (or failed): stop the first run
        self.wake_r, self.wake_w = multiprocessing.Pipe(duplex=False)  # wakes the helper
        self.pool: _Pool | None = None
        self.winner: tuple[int, Solution] | None = None
        self.stop: str | None = None  # why the pool's runs were cut, and how many (_Pool.drive)
        self.stopped = 0
        self.error: BaseException | None = None
        self.bar: Task = Task()

    def run(self, progress: Progress) -> Solution:
        helper = threading.Thread(target=self._helper, name=f"tilesolve-{self.name}-portfolio", daemon=True)
        with progress.task(self.name, unit=None) as bar:
            self.bar = bar
            bar.note(f"seed {self.seed0}")
            helper.start()
            try:
                with stop_on(self.stop_first):
                    first = self.route(self.problem, self.run_options)
            except KeyboardInterrupt:
                first = Solution(Status.UNKNOWN, seed=self.seed0, time_s=self.clock.elapsed(), reason="interrupted")
            finally:
                self.first_done.set()
                self.wake_w.send_bytes(b"")
                helper.join()
                self.wake_r.close()
                self.wake_w.close()
        return self._outcome(first)

    def _helper(self) -> None:
        before = _cpu_times()
        while not self.first_done.wait(QUICK_S):
            rem = self.clock.remaining()
            if rem is not None and rem < 1.0:  # workers could not start in time
                return
            after = _cpu_times()
            n = self.helpers if self.obey else min(self.helpers, _idle_cores(before, after, self.helpers))
            before = after
            if n >= 1:
                self._drive_pool(n)
                return

    def _drive_pool(self, n: int) -> None:
        task = functools.partial(_wave_run, self.route, self.problem, self.seed0, n, FIRST_BUDGET_S, self.worker_run)
        seeds = [self.seed0 + i for i in range(1, PORTFOLIO_SEEDS + 1)]
        where = f"on {_processes(n)} beside seed {self.seed0} in this process"
        pool = None
        try:
            self.pool = pool = _Pool(task, seeds, n, self.clock, self.name, where, nice=WORKER_NICE)
            pool.start()
            self.winner, self.stop, self.stopped = pool.drive(
                lambda running: self.bar.note(f"seed {self.seed0} here; {pool.runs.detail(running)} in {_processes(n)}"),
                wake=self.wake_r)
        except BaseException as exc:  # noqa: BLE001 - re-raised by the caller's thread
            self.error = exc
        finally:
            if self.winner is not None or self.error is not None:
                self.stop_first.set()
            if pool is not None:
                pool.close()

    def _outcome(self, first: Solution) -> Solution:
        pool, elapsed = self.pool, self.clock.elapsed()
        if first.status not in _DECISIVE and self.error is not None:
            raise self.error
        if pool is None:  # decided (or ended) before any worker started: the plain call
            return first
        if first.status not in _DECISIVE and self.winner is not None:
            return pool.runs.won(*self.winner).replace(time_s=elapsed)
        if first.status in _DECISIVE:
            note = (f"portfolio: seed {self.seed0} decided it in this process; {_runs(pool.runs.started)} "
                    f"started beside it on {_processes(pool.n)}")
        else:
            stop = "the first run ended" if self.stop == "stopped" else self.stop
            note = f"portfolio beside seed {self.seed0}: {pool.runs.summary(stop, self.stopped)}"
        stats = dict(first.stats, run_time_s=first.time_s, portfolio_runs=pool.runs.started,
                     portfolio_workers=pool.n)
        return first.replace(time_s=elapsed, stats=stats, notes=first.notes + (note,))


def _cpu_times() -> tuple[float, float] | None:
    """(idle, total) CPU time of the machine so far, in clock ticks (Linux: /proc/stat)."""
    try:
        with open("/proc/stat") as f:
            ticks = [float(x) for x in f.readline().split()[1:]]
    except (OSError, ValueError):
        return None
    return ticks[3] + ticks[4], sum(ticks[:8])  # idle + iowait; user .. steal (guests are in user)


def _idle_cores(before, after, otherwise: int) -> int:
    """Cores that sat idle between two :func:`_cpu_times` samples, rounded; ``otherwise``
    where the machine does not tell."""
    if before is None or after is None or after[1] <= before[1]:
        return otherwise
    return int((after[0] - before[0]) / (after[1] - before[1]) * (os.cpu_count() or 1) + 0.5)


def _processes(n: int) -> str:
    return f"{n} worker process{'es' * (n != 1)}"


# ----------------------------------------------------------------------------- bookkeeping


def _check_seeds(seeds: Iterable[int]) -> list[int]:
    out = list(seeds)
    if not out:
        raise InvalidProblem("a portfolio needs at least one seed")
    for s in out:
        if isinstance(s, bool) or not isinstance(s, int) or s < 0:
            raise InvalidProblem(f"seeds must be non-negative integers, got {s!r}")
    return out


def _check_workers(workers: int) -> None:
    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
        raise InvalidProblem(f"workers must be an integer >= 1, got {workers!r}")


@dataclass
class _Runs:
    """What a portfolio has started and seen, and the Solutions it reports from that."""

    seeds: list[int]
    where: str  # "on 2 worker processes", "on the Dask cluster at tcp://..."
    n_workers: int
    deadline: Deadline
    started_word: str = "started"  # a Dask run is "submitted": the scheduler starts it
    started: int = 0
    unknown: list[tuple[int, Solution]] = field(default_factory=list)

    @property
    def finished(self) -> int:
        return len(self.unknown)

    def detail(self, running: int, state: str = "running") -> str:
        return f"{self.finished}/{len(self.seeds)} runs finished, {running} {state}"

    def report(self, bar: Task, running: int, state: str = "running") -> None:
        """Show the runs finished as ``bar``'s count (one unit a seed), the runs ``running`` beside it."""
        bar.set(self.finished)
        bar.note(f"{running} {state}")

    def record(self, seed: int, sol: Solution) -> bool:
        """Count an undecided run; True when it ends the whole portfolio (a run that returns
        ``unknown`` because of Ctrl-C)."""
        self.unknown.append((seed, sol))
        return sol.status is Status.UNKNOWN and (sol.reason or "").startswith("interrupted")

    def won(self, seed: int, sol: Solution) -> Solution:
        stats = dict(sol.stats, run_time_s=sol.time_s, portfolio_runs=self.started,
                     portfolio_workers=self.n_workers)
        note = (f"portfolio: seed {seed} decided it, after {self.started} of {len(self.seeds)} "
                f"runs {self.started_word}, {self.where}")
        return sol.replace(seed=seed if sol.seed is None else sol.seed, time_s=self.deadline.elapsed(),
                           stats=stats, notes=sol.notes + (note,))

    def undecided(self, stop: str | None = None, stopped: int = 0) -> Solution:
        """``unknown``: every run ended so, or ``stop`` ("time limit", "interrupted") cut them."""
        summary = self.summary(stop, stopped)
        sols = [sol for _, sol in self.unknown]
        methods = {s.method for s in sols}
        solvers = {s.solver for s in sols}
        stats = {"portfolio_runs": self.started, "portfolio_workers": self.n_workers}
        if stop == "interrupted":
            reason, notes = "interrupted", (summary,)
        else:
            reason, notes = summary, ()
        return Solution(Status.UNKNOWN, None, methods.pop() if len(methods) == 1 else "portfolio",
                        solvers.pop() if len(solvers) == 1 else None, None, self.deadline.elapsed(),
                        reason=reason, notes=notes, stats=stats)

    def summary(self, stop: str | None = None, stopped: int = 0) -> str:
        """``"no run decided: ..."``: how the runs ended, how many ``stop`` cut, how many never began."""
        parts = []
        if self.unknown:
            counts = collections.Counter(sol.reason or "no reason given" for _, sol in self.unknown)
            why = ", ".join(f"{r}: {n}" for r, n in counts.most_common())
            parts.append(f"{_runs(len(self.unknown))} ended unknown ({why})")
        if stopped:
            parts.append(f"{_runs(stopped)} stopped ({stop})")
        if self.started < len(self.seeds):
            n = len(self.seeds) - self.started
            parts.append(f"{n} seed{'s' * (n != 1)} not {self.started_word} ({stop or 'time limit'})")
        return "no run decided: " + "; ".join(parts)


def _runs(n: int) -> str:
    return f"{n} run{'s' * (n != 1)}"


# ------------------------------------------------------------------------ in this process


def _run_single(task, seed: int, progress: Progress, label: str) -> Solution:
    """One seed: the plain call (its own Solution, unchanged), Ctrl-C giving ``unknown``."""
    t0 = time.perf_counter()
    with progress.task(label, unit=None) as bar:
        bar.note(f"seed {seed}")
        try:
            return task(seed=seed)
        except KeyboardInterrupt:
            pass
    return Solution(Status.UNKNOWN, seed=seed, time_s=time.perf_counter() - t0, reason="interrupted")


def _run_inline(task, seeds: list[int], deadline: Deadline, progress: Progress, label: str) -> Solution:
    runs = _Runs(seeds, "in this process (1 worker)", 1, deadline)
    stop, stopped = None, 0
    with progress.task(label, total=len(seeds), unit="seed") as bar:
        try:
            for seed in seeds:
                if deadline.expired():
                    stop = "time limit"
                    break
                runs.started += 1
                runs.report(bar, 1, f"running (seed {seed})")
                sol = task(seed=seed)
                if sol.status in _DECISIVE:
                    return runs.won(seed, sol)
                if runs.record(seed, sol):
                    stop = "interrupted"
                    break
        except KeyboardInterrupt:
            stop, stopped = "interrupted", 1
    return runs.undecided(stop, stopped)


# ------------------------------------------------------------------- local worker processes


class _RemoteTraceback(Exception):
    """The ``__cause__`` of an exception re-raised from a worker: the worker's traceback."""

    def __init__(self, tb: str) -> None:
        super().__init__(tb)
        self.tb = tb

    def __str__(self) -> str:
        return self.tb


def _pack_exception(exc: BaseException) -> tuple:
    """(pickled exception or None, type name, message, formatted traceback)."""
    tb = "".join(traceback.format_exception(exc))
    try:
        blob = pickle.dumps(exc)
        pickle.loads(blob)  # some exceptions pickle but cannot be rebuilt (extra __init__ args)
    except Exception:  # noqa: BLE001 - then the parent rebuilds it from its name and message
        blob = None
    return blob, f"{type(exc).__module__}.{type(exc).__qualname__}", str(exc), tb


def _unpack_exception(packed: tuple) -> BaseException:
    blob, name, message, tb = packed
    exc = None
    if blob is not None:
        try:
            exc = pickle.loads(blob)
        except Exception:  # noqa: BLE001 - the type is not importable here
            exc = None
    if exc is None:
        exc = RuntimeError(f"{name}: {message}")
    exc.__cause__ = _RemoteTraceback(f'\n"""\n{tb}"""')
    return exc


#: What a worker interpreter runs (``python -c``): lower its priority by ``nice`` (before its
#: imports, which are part of its start-up cost), ignore Ctrl-C (the parent alone handles it,
#: by terminating the workers, so no worker prints a KeyboardInterrupt traceback), take the
#: parent's ``sys.path`` from the pipe (so the task's modules import as they do there), then
#: hand over to :func:`_worker_main`. A parent gone before it sent the path (Ctrl-C while its
#: workers start) ends the worker quietly: its stderr is the user's terminal.
_BOOT = ("import os, signal, sys; os.nice({nice}); signal.signal(signal.SIGINT, signal.SIG_IGN)\n"
         "from multiprocessing.connection import Connection; conn = Connection({fd})\n"
         "try:\n    sys.path[:] = conn.recv()\nexcept (EOFError, OSError):\n    os._exit(1)\n"
         "from tilesolve.engine.portfolio import _worker_main; _worker_main(conn, {ppid})")

#: ``PR_SET_PDEATHSIG`` of ``<linux/prctl.h>``: the signal a process gets when its parent dies.
_PR_SET_PDEATHSIG = 1

#: Where ``__main__`` is being imported in this worker (module docstring, Limits), else None.
_importing_main: str | None = None


def _refuse_while_importing_main() -> None:
    """A script without a ``__main__`` guard, imported by a worker for its task, would start
    portfolios of its own in every worker: refuse with what to change."""
    if _importing_main is not None:
        raise InvalidProblem(f"{_importing_main} starts a tilesolve portfolio when it is imported, and the worker "
                             f"processes import it to find the task defined there: put its top-level code "
                             f"under 'if __name__ == \"__main__\":'")


def _die_with_parent(ppid: int) -> None:
    """End this worker when its parent dies, even by SIGKILL: the kernel's parent-death signal
    on Linux, a watchdog thread elsewhere."""
    if sys.platform.startswith("linux"):
        import ctypes

        ctypes.CDLL(None, use_errno=True).prctl(_PR_SET_PDEATHSIG, signal.SIGKILL)
    else:
        def watch() -> None:
            while os.getppid() == ppid:
                time.sleep(0.5)
            os._exit(1)

        threading.Thread(target=watch, daemon=True).start()
    if os.getppid() != ppid:  # the parent died before the signal was armed
        os._exit(1)


def _main_of_parent() -> tuple[str, str] | None:
    """How a worker imports the parent's ``__main__``: ``("module", name)`` for ``python -m``,
    ``("path", file)`` for a script, None for an interactive session."""
    main = sys.modules["__main__"]
    name = getattr(getattr(main, "__spec__", None), "name", None)
    if name is not None:
        return "module", name
    path = getattr(main, "__file__", None)
    return None if path is None else ("path", os.path.abspath(path))


def _load_task(blob: bytes, main: tuple[str, str] | None):
    """Unpickle the task; one defined in the parent's ``__main__`` first needs that module,
    imported as ``__mp_main__`` (as :mod:`multiprocessing` does) so its guarded code stays off."""
    global _importing_main
    try:
        return pickle.loads(blob)
    except (AttributeError, ImportError):
        if main is None or b"__main__" not in blob:
            raise
    import runpy
    import types

    kind, where = main
    _importing_main = where
    try:
        if kind == "module":
            namespace = runpy.run_module(where, run_name="__mp_main__", alter_sys=False)
        else:
            namespace = runpy.run_path(where, run_name="__mp_main__")
    finally:
        _importing_main = None
    module = types.ModuleType("__mp_main__")
    module.__dict__.update(namespace)
    sys.modules["__main__"] = sys.modules["__mp_main__"] = module
    return pickle.loads(blob)


def _worker_main(conn, ppid: int) -> None:
    """A worker process: answer ``("done" | "error", seed, payload)`` for each seed received;
    return when the parent is gone (a closed pipe), without a word on the shared stderr."""
    _die_with_parent(ppid)
    try:
        main, blob = conn.recv()
    except (EOFError, OSError):  # the parent is gone
        return
    try:
        task, load_error = _load_task(blob, main), None
    except BaseException as exc:  # noqa: BLE001 - e.g. the task's module is not importable here
        task, load_error = None, _pack_exception(exc)
    while True:
        try:
            seed = conn.recv()
        except (EOFError, OSError):  # the parent is gone
            return
        if seed is None:
            return
        if task is None:
            reply = ("error", seed, load_error)
        else:
            try:
                reply = ("done", seed, task(seed=seed))
            except BaseException as exc:  # noqa: BLE001 - re-raised in the parent
                reply = ("error", seed, _pack_exception(exc))
        try:
            data = pickle.dumps(reply)
        except BaseException as exc:  # noqa: BLE001 - an unpicklable Solution is the task's bug
            data = pickle.dumps(("error", seed, _pack_exception(exc)))
        try:
            conn.send_bytes(data)
        except OSError:  # the parent is gone
            return


@dataclass
class _Worker:
    process: subprocess.Popen
    conn: Any
    seed: int | None = None  # the seed it is running, None when idle


def _pickled_task(task) -> bytes:
    try:
        return pickle.dumps(task)
    except Exception as exc:
        raise TypeError(f"run_portfolio needs a picklable task (a module-level function or a "
                        f"functools.partial of one), got {task!r}: {exc}") from None


class _Pool:
    """Worker processes running ``task`` on a queue of seeds until one decides."""

    def __init__(self, task, seeds: list[int], n: int, deadline: Deadline, label: str, where: str = "",
                 nice: int = 0) -> None:
        if os.name != "posix":
            raise BackendUnavailable("local worker processes need a POSIX system; use workers=1 or a Dask cluster")
        self.blob = _pickled_task(task)
        self.n, self.label, self.deadline, self.nice = n, label, deadline, nice
        self.where = where or f"on {_processes(n)}"
        self.runs = _Runs(seeds, self.where, n, deadline)
        self.queue = collections.deque(seeds)
        self.workers: list[_Worker] = []

    def start(self) -> None:
        for _ in range(self.n):  # all interpreters start at once; each then reads its pipe
            parent_end, child_end = multiprocessing.Pipe()
            fd = child_end.fileno()
            try:
                boot = _BOOT.format(fd=fd, ppid=os.getpid(), nice=self.nice)
                process = subprocess.Popen([sys.executable, "-c", boot], pass_fds=(fd,), stdin=subprocess.DEVNULL)
            finally:
                child_end.close()
            self.workers.append(_Worker(process, parent_end))
        main = _main_of_parent()
        for w in self.workers:
            try:
                w.conn.send(sys.path)
                w.conn.send((main, self.blob))
            except OSError:  # the interpreter could not start, or was killed from outside
                raise BrokenProcessPool(f"a {self.label} worker process is gone "
                                        f"(exit code {w.process.poll()})") from None
            self.assign(w)

    def busy(self) -> list[_Worker]:
        return [w for w in self.workers if w.seed is not None]

    def assign(self, w: _Worker) -> None:
        w.seed = None
        if self.queue and not self.deadline.expired():
            w.seed = self.queue.popleft()
            self.runs.started += 1
            try:
                w.conn.send(w.seed)
            except OSError:  # the worker is gone (killed from outside)
                raise BrokenProcessPool(f"a {self.label} worker process is gone "
                                        f"(exit code {w.process.poll()})") from None

    def drive(self, show: Callable[[int], None], wake=None) -> tuple[tuple[int, Solution] | None, str | None, int]:
        """Run seeds until one decides: ``(winner, None, 0)``; else ``(None, stop, stopped)``
        with ``stop`` the reason runs were cut (``"time limit"``, ``"interrupted"``, or
        ``"stopped"`` when ``wake`` became readable) and ``stopped`` how many. ``show(running)``
        is called whenever the runs change. Re-raises a run's exception, or BrokenProcessPool."""
        while True:
            busy = self.busy()
            if not busy:
                return None, "time limit" if self.queue else None, 0  # seeds left: the budget is spent
            show(len(busy))
            timeout = None
            if self.deadline.time_limit is not None:
                timeout = self.deadline.time_limit + GRACE_S - self.deadline.elapsed()
                if timeout <= 0:
                    return None, "time limit", len(busy)
            ready = set(wait_for_any([w.conn for w in busy] + ([wake] if wake is not None else []), timeout))
            if wake is not None and wake in ready:
                return None, "stopped", len(busy)
            for w in busy:
                if w.conn not in ready:
                    continue
                kind, seed, payload = self._receive(w)
                if kind == "error":
                    raise _unpack_exception(payload)
                if payload.status in _DECISIVE:
                    return (seed, payload), None, 0
                if self.runs.record(seed, payload):
                    return None, "interrupted", len(busy) - 1
                self.assign(w)

    def _receive(self, w: _Worker) -> tuple:
        """The worker's answer; a worker that died without one is a broken pool."""
        try:
            return pickle.loads(w.conn.recv_bytes())
        except (EOFError, OSError):
            pass
        try:
            code = w.process.wait(timeout=1.0)
        except subprocess.TimeoutExpired:
            code = None
        raise BrokenProcessPool(f"a {self.label} worker process died (exit code {code}) while running seed {w.seed}")

    def close(self) -> None:
        """Terminate every worker now (a run inside native code cannot be asked to stop)."""
        for w in self.workers:
            if w.process.poll() is None:
                w.process.terminate()
        for w in self.workers:
            try:
                w.process.wait(timeout=2.0)
            except subprocess.TimeoutExpired:  # SIGTERM blocked or ignored by native code
                w.process.kill()
                w.process.wait()
            w.conn.close()


def _run_pool(task, seeds: list[int], n: int, deadline: Deadline, progress: Progress, label: str) -> Solution:
    pool = _Pool(task, seeds, n, deadline, label)
    with progress.task(label, total=len(seeds), unit="seed") as bar:
        try:
            pool.start()
            winner, stop, stopped = pool.drive(functools.partial(pool.runs.report, bar))
        except KeyboardInterrupt:
            winner, stop, stopped = None, "interrupted", len(pool.busy())
        finally:
            pool.close()
    if winner is not None:
        return pool.runs.won(*winner)
    return pool.runs.undecided(stop, stopped)


# ---------------------------------------------------------------------------------- Dask


def _connect(cluster) -> tuple[Any, bool]:
    """(client, whether we opened it) for an address or an open ``distributed.Client``."""
    try:
        from distributed import Client
    except ImportError:
        raise BackendUnavailable('running on a cluster needs Dask distributed: pip install "tilesolve[cluster]"') from None
    if isinstance(cluster, Client):
        return cluster, False
    if not isinstance(cluster, str):
        raise InvalidProblem(f"cluster must be a Dask scheduler address such as 'tcp://host:8786', got {cluster!r}")
    if cluster.startswith("ray://"):
        raise InvalidProblem("Ray clusters are not supported; give the address of a Dask scheduler (tcp://host:8786)")
    failure = None
    try:
        return Client(cluster, timeout=CONNECT_TIMEOUT_S, set_as_default=False), True
    except ValueError as exc:  # unknown scheme, malformed address
        failure = InvalidProblem(f"not a Dask scheduler address: {cluster!r} ({_first_line(exc)})")
    except Exception as exc:  # noqa: BLE001 - OSError on timeout; anything else is as fatal
        failure = BackendUnavailable(f"cannot connect to the Dask scheduler at {cluster}: {_first_line(exc)}")
    # The half-built Client sits in the traceback just dropped; collect it now, while its
    # event loop still runs: left to interpreter exit its __del__ waits 2x the timeout and
    # prints a traceback.
    gc.collect()
    raise failure


def _first_line(exc: BaseException) -> str:
    text = str(exc).strip()
    return text.splitlines()[0] if text else type(exc).__name__


def _run_dask(task, seeds: list[int], cluster, deadline: Deadline, progress: Progress, label: str) -> Solution:
    client, owned = _connect(cluster)  # checks first that Dask distributed is installed
    from distributed import as_completed

    futures: list = []
    try:
        nthreads = client.nthreads()  # {worker address: threads}: how many runs go at once
        n, threads = len(nthreads), sum(nthreads.values())
        where = f"on the Dask cluster at {client.scheduler.address} ({n} workers, {threads} threads)"
        runs = _Runs(seeds, where, n, deadline, started_word="submitted")
        stop = None
        with progress.task(label, total=len(seeds), unit="seed") as bar:
            try:
                futures = [client.submit(task, seed=s, pure=False) for s in seeds]
                seed_of = {f.key: s for f, s in zip(futures, seeds)}
                runs.started = len(seeds)  # submitted: the scheduler decides when each one starts
                timeout = None
                if deadline.time_limit is not None:
                    timeout = max(0.0, deadline.time_limit + GRACE_S - deadline.elapsed())
                pending = as_completed(futures, loop=client.loop, timeout=timeout)
                while True:
                    runs.report(bar, len(seeds) - runs.finished, "queued or running")
                    try:
                        fut = next(pending)
                    except StopIteration:
                        break
                    except TimeoutError:  # distributed.TimeoutError is the builtin one
                        stop = "time limit"
                        break
                    seed = seed_of[fut.key]
                    sol = fut.result()  # re-raises the run's exception, same type
                    if sol.status in _DECISIVE:
                        return runs.won(seed, sol)
                    if runs.record(seed, sol):
                        stop = "interrupted"
                        break
            except KeyboardInterrupt:
                stop = "interrupted"
        return runs.undecided(stop, len(seeds) - runs.finished if stop else 0)
    finally:
        if futures:
            client.cancel(futures)
        if owned:
            client.close()

