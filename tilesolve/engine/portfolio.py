"""Portfolios of randomised runs: local worker processes by default, or a Dask cluster.

A long search (a seeded SAT run on a tile packing, say) has heavy-tailed run times: one seed
finishes in a second where another needs minutes. :func:`run_portfolio` runs several seeds
at once and keeps the first *decisive* answer (``sat``, ``optimal``, or a proved ``unsat``);
the other runs are stopped. A portfolio in which every run ends ``unknown`` is ``unknown``,
never ``unsat`` (DESIGN.md, "Status").

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

Limits
------
- ``task`` must be picklable: a module-level function, or a :func:`functools.partial` of
  one (the Dask path also takes closures, through cloudpickle). Functions defined in
  ``__main__`` work from a script that guards its entry point with
  ``if __name__ == "__main__":`` (the usual rule of process pools that do not fork).
- Each run honours the time limit baked into ``task``; ``time_limit`` here is the wall-clock
  budget of the whole portfolio: no seed starts once it is spent, and runs still going
  :data:`GRACE_S` seconds later are stopped (status ``unknown``).
- A Dask task that is already running cannot be stopped: cancelling releases its result,
  and the run ends at its own time limit on the cluster.
- Tasks should not draw progress on the terminal (every worker shares it); the portfolio
  draws one status line (``progress=True``).

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
import pickle
import signal
import time
import traceback
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass, field
from multiprocessing.connection import wait as wait_for_any
from typing import Any, Callable, Iterable

from tilesolve.engine.progress import status_line
from tilesolve.deadline import Deadline
from tilesolve.errors import BackendUnavailable, InvalidProblem
from tilesolve.model.solution import Solution, Status

__all__ = ["run_portfolio", "escalate", "DEFAULT_WORKERS", "START_METHOD", "GRACE_S", "CONNECT_TIMEOUT_S",
           "QUICK_S", "FIRST_BUDGET_S", "PORTFOLIO_SEEDS"]

#: Local worker processes when the caller names none: the machines tilesolve targets have two
#: cores (as :data:`tilesolve.engine.cpsat.DEFAULT_CPSAT_WORKERS`).
DEFAULT_WORKERS = 2

#: How worker processes start. Never ``fork``: the parent may already run threads (OR-tools,
#: numba's pool, the progress line, a Dask client), and a forked child inherits their locks
#: in whatever state they were. ``forkserver`` forks each worker from a small single-threaded
#: server process started once per session; ``spawn`` starts a fresh interpreter per worker.
#: Measured on the dev machine (2 cores, Python 3.11), whole call for 2 seeds on 2 workers
#: with a task that answers at once: spawn 0.38-0.52 s; forkserver 0.27-0.33 s (0.33-0.46 s
#: on the first call, which starts the server). A task that imports the solver stack (pysat,
#: OR-tools, numba) costs 1.1-1.6 s either way: the imports dominate. Forkserver is the
#: cheaper of the two, is Python 3.14's default on Linux, and keeps the fork away from the
#: parent's threads; where it does not exist (Windows) spawn is used. Both are small next to
#: the searches a portfolio is for. (Preloading the solver stack into the server would save
#: the imports, but the server is shared process-wide state; not worth it.)
START_METHOD = "forkserver" if "forkserver" in multiprocessing.get_all_start_methods() else "spawn"

#: Seconds the runs get, past ``time_limit``, to report before they are stopped: each run
#: honours its own limit, which starts a little later than the portfolio's (process start).
GRACE_S = 1.0

#: Seconds to wait for a Dask scheduler to answer before giving up with a one-line error.
CONNECT_TIMEOUT_S = 5.0

#: Seconds the first, in-process run of an escalated search gets before the portfolio starts
#: (most packings up to C = 6 take well under a second, and then no process is started).
QUICK_S = 5.0
#: Per-run budget of the first wave of portfolio runs; it doubles with every wave, so a seed
#: stuck in a heavy tail is abandoned for a fresh one (a restart strategy).
FIRST_BUDGET_S = 20.0
#: Seeds a portfolio may draw (seed + 1, seed + 2, ...).
PORTFOLIO_SEEDS = 64

_DECISIVE = (Status.SAT, Status.OPTIMAL, Status.UNSAT)


def run_portfolio(
    task: Callable[[int], Solution],
    seeds: Iterable[int],
    *,
    workers: int = DEFAULT_WORKERS,
    cluster: Any = None,
    time_limit: float | None = None,
    progress: bool = False,
    label: str = "search",
) -> Solution:
    """Run ``task(seed=seed)`` for each seed concurrently; return the first decisive Solution.

    Parameters
    ----------
    task : callable
        ``task(seed=seed) -> Solution``: one independent randomised search that honours its
        own time limit. The seed is passed by keyword, so a :func:`functools.partial` of any
        tilesolve ``solve`` function works as it is, e.g. ``partial(tilesolve.packing.solve,
        problem, method="sat", time_limit=60)``. Must pickle (module docstring).
    seeds : iterable of int
        One run per seed, started in this order (a seed starts when a worker is free).
    workers : int
        Local worker processes (default 2). With one worker, or one seed, the runs happen in
        this process one after the other, exactly as plain calls. Ignored with ``cluster``.
    cluster : str or distributed.Client, optional
        A Dask scheduler address (``"tcp://host:8786"``) or an open ``distributed.Client``:
        run the seeds there instead of in local processes.
    time_limit : float, optional
        Wall-clock budget of the whole portfolio in seconds: no seed starts after it, and
        runs still going :data:`GRACE_S` later are stopped (in this process a run cannot be
        stopped from outside: it ends at the limit baked into ``task``).
    progress : bool
        Show a one-line live status (label, runs started and finished, elapsed seconds) on
        stderr when it is a terminal.
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
        No seeds, a seed that is not a non-negative int, ``workers < 1``, a negative time
        limit, or a malformed cluster address.
    BackendUnavailable
        ``cluster`` given but Dask distributed is not installed, or the scheduler cannot be
        reached within :data:`CONNECT_TIMEOUT_S` seconds.
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
    seeds = _check_seeds(seeds)
    deadline = Deadline(time_limit)  # validates time_limit
    if cluster is not None:
        return _run_dask(task, seeds, cluster, deadline, progress, label)
    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
        raise InvalidProblem(f"workers must be an integer >= 1, got {workers!r}")
    if len(seeds) == 1:
        return _run_single(task, seeds[0], progress, label)
    if workers == 1:
        return _run_inline(task, seeds, deadline, progress, label)
    return _run_pool(task, seeds, min(workers, len(seeds)), deadline, progress, label)


def _wave_run(route, problem, seed0, workers, time_limit, solver, *, seed):
    """One portfolio run: ``route`` with seed ``seed`` and the budget of its wave."""
    budget = FIRST_BUDGET_S * 2 ** ((seed - seed0 - 1) // workers)
    if time_limit is not None:
        budget = min(budget, time_limit)
    return route(problem, seed=seed, time_limit=budget, solver=solver)


def escalate(route, problem, *, name, seed=None, time_limit=None, workers=None, cluster=None, progress=False,
             solver=None) -> Solution:
    """Run a heavy-tailed search; if it does not decide quickly, escalate to a seed portfolio.

    Parameters
    ----------
    route : callable
        The raw route ``route(problem, *, seed, time_limit, solver) -> Solution`` (an
        ``engine`` search such as :func:`tilesolve.engine.packing.solve_lift`, never a facade):
        it is what the worker processes run, so it must pickle (a module-level function).
    problem
        The problem handed to ``route`` (pickled to the workers).
    name : str
        What the progress line and the notes call the search (e.g. ``"lift packing"``).
    seed : int, optional
        Seed of the first run; portfolio runs take ``seed + 1, seed + 2, ...``.
    time_limit : float, optional
        Wall-clock budget of the whole search in seconds.
    workers : int, optional
        Local processes (default :data:`DEFAULT_WORKERS`); ``1`` runs the one seed, plainly.
    cluster : str or distributed.Client, optional
        A Dask scheduler: the portfolio's runs go there.
    progress : bool
        Show a live status line on a terminal.
    solver : str, optional
        Passed to ``route``.

    Returns
    -------
    Solution
        The first decisive run's Solution (see :func:`run_portfolio`).
    """
    from tilesolve._random import rng_from_seed
    from tilesolve.engine.progress import ticker

    n = DEFAULT_WORKERS if workers is None else workers
    if n <= 1 and cluster is None:
        with ticker(name, progress):
            return route(problem, seed=seed, time_limit=time_limit, solver=solver)
    t0 = time.perf_counter()
    seed0 = int(rng_from_seed(None).integers(2**31)) if seed is None else seed
    rem = time_limit
    if cluster is None:
        quick = QUICK_S if time_limit is None else min(QUICK_S, time_limit)
        with ticker(f"{name} (first run)", progress):
            first = route(problem, seed=seed0, time_limit=quick, solver=solver)
        if first.status is not Status.UNKNOWN or (first.reason or "").startswith("interrupted"):
            return first
        rem = None if time_limit is None else max(0.0, time_limit - (time.perf_counter() - t0))
        if rem is not None and rem < 1.0:
            return first
    task = functools.partial(_wave_run, route, problem, seed0, n, rem, solver)
    seeds = [seed0 + i for i in range(1, PORTFOLIO_SEEDS + 1)]
    return run_portfolio(task, seeds, workers=n, cluster=cluster, time_limit=rem, progress=progress, label=name)


# ----------------------------------------------------------------------------- bookkeeping


def _check_seeds(seeds: Iterable[int]) -> list[int]:
    out = list(seeds)
    if not out:
        raise InvalidProblem("a portfolio needs at least one seed")
    for s in out:
        if isinstance(s, bool) or not isinstance(s, int) or s < 0:
            raise InvalidProblem(f"seeds must be non-negative integers, got {s!r}")
    return out


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
        summary = "no run decided: " + "; ".join(parts)
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


def _runs(n: int) -> str:
    return f"{n} run{'s' * (n != 1)}"


# ------------------------------------------------------------------------ in this process


def _run_single(task, seed: int, progress: bool, label: str) -> Solution:
    """One seed: the plain call (its own Solution, unchanged), Ctrl-C giving ``unknown``."""
    t0 = time.perf_counter()
    with status_line(label, progress) as show:
        show("1 run")
        try:
            return task(seed=seed)
        except KeyboardInterrupt:
            pass
    return Solution(Status.UNKNOWN, seed=seed, time_s=time.perf_counter() - t0, reason="interrupted")


def _run_inline(task, seeds: list[int], deadline: Deadline, progress: bool, label: str) -> Solution:
    runs = _Runs(seeds, "in this process (1 worker)", 1, deadline)
    stop, stopped = None, 0
    with status_line(label, progress) as show:
        try:
            for seed in seeds:
                if deadline.expired():
                    stop = "time limit"
                    break
                runs.started += 1
                show(runs.detail(1))
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


def _worker_main(conn, task_blob: bytes) -> None:
    """A worker process: answer ``("done" | "error", seed, payload)`` for each seed received."""
    # Ctrl-C on a terminal reaches the whole process group; the parent alone handles it (by
    # terminating the workers), so a worker never prints a KeyboardInterrupt traceback.
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        task, load_error = pickle.loads(task_blob), None
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
        conn.send_bytes(data)


@dataclass
class _Worker:
    process: Any
    conn: Any
    seed: int | None = None  # the seed it is running, None when idle


def _pickled_task(task) -> bytes:
    try:
        return pickle.dumps(task)
    except Exception as exc:
        raise TypeError(f"run_portfolio needs a picklable task (a module-level function or a "
                        f"functools.partial of one), got {task!r}: {exc}") from None


def _run_pool(task, seeds: list[int], n: int, deadline: Deadline, progress: bool, label: str) -> Solution:
    blob = _pickled_task(task)
    ctx = multiprocessing.get_context(START_METHOD)
    runs = _Runs(seeds, f"on {n} worker processes", n, deadline)
    queue = collections.deque(seeds)
    pool: list[_Worker] = []
    winner = error = stop = None
    stopped = 0

    def assign(w: _Worker) -> None:
        w.seed = None
        if queue and not deadline.expired():
            w.seed = queue.popleft()
            runs.started += 1
            try:
                w.conn.send(w.seed)
            except OSError:  # the worker is gone (killed from outside)
                raise BrokenProcessPool(f"a {label} worker process is gone (exit code {w.process.exitcode})") from None

    with status_line(label, progress) as show:
        try:
            for i in range(n):
                parent_end, child_end = ctx.Pipe()
                p = ctx.Process(target=_worker_main, args=(child_end, blob), name=f"tilesolve-{label}-{i}")
                p.start()
                child_end.close()
                pool.append(_Worker(p, parent_end))
                assign(pool[-1])
            while winner is None and error is None:
                busy = [w for w in pool if w.seed is not None]
                if not busy:
                    if queue:  # seeds left, but the budget is spent
                        stop = "time limit"
                    break
                show(runs.detail(len(busy)))
                timeout = None
                if deadline.time_limit is not None:
                    timeout = deadline.time_limit + GRACE_S - deadline.elapsed()
                    if timeout <= 0:
                        stop, stopped = "time limit", len(busy)
                        break
                ready = set(wait_for_any([w.conn for w in busy] + [w.process.sentinel for w in busy], timeout))
                for w in busy:
                    if w.conn not in ready and w.process.sentinel not in ready:
                        continue
                    kind, seed, payload = _receive(w, label)
                    if kind == "error":
                        error = _unpack_exception(payload)
                        break
                    if payload.status in _DECISIVE:
                        winner = (seed, payload)
                        break
                    if runs.record(seed, payload):
                        stop, stopped = "interrupted", len(busy) - 1
                        break
                    assign(w)
                if stop is not None:
                    break
        except KeyboardInterrupt:
            stop, stopped = "interrupted", sum(w.seed is not None for w in pool)
        except BaseException as exc:  # e.g. BrokenProcessPool, or a worker that cannot start
            error = exc
        finally:
            _stop_all(pool)
    if error is not None:
        raise error
    if winner is not None:
        return runs.won(*winner)
    return runs.undecided(stop, stopped)


def _receive(w: _Worker, label: str) -> tuple:
    """The worker's answer; a worker that died without one is a broken pool."""
    try:
        if w.conn.poll():
            return pickle.loads(w.conn.recv_bytes())
    except (EOFError, OSError):
        pass
    w.process.join(timeout=1.0)
    raise BrokenProcessPool(f"a {label} worker process died (exit code {w.process.exitcode}) "
                            f"while running seed {w.seed}")


def _stop_all(pool: list[_Worker]) -> None:
    """Terminate every worker now (a run inside native code cannot be asked to stop)."""
    for w in pool:
        if w.process.is_alive():
            w.process.terminate()
    for w in pool:
        w.process.join(timeout=2.0)
        if w.process.is_alive():  # SIGTERM blocked or ignored by native code
            w.process.kill()
            w.process.join()
        w.conn.close()
        w.process.close()


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


def _run_dask(task, seeds: list[int], cluster, deadline: Deadline, progress: bool, label: str) -> Solution:
    client, owned = _connect(cluster)  # checks first that Dask distributed is installed
    from distributed import as_completed

    futures: list = []
    try:
        nthreads = client.nthreads()  # {worker address: threads}: how many runs go at once
        n, threads = len(nthreads), sum(nthreads.values())
        where = f"on the Dask cluster at {client.scheduler.address} ({n} workers, {threads} threads)"
        runs = _Runs(seeds, where, n, deadline, started_word="submitted")
        stop = None
        with status_line(label, progress) as show:
            try:
                futures = [client.submit(task, seed=s, pure=False) for s in seeds]
                seed_of = {f.key: s for f, s in zip(futures, seeds)}
                runs.started = len(seeds)  # submitted: the scheduler decides when each one starts
                timeout = None
                if deadline.time_limit is not None:
                    timeout = max(0.0, deadline.time_limit + GRACE_S - deadline.elapsed())
                pending = as_completed(futures, loop=client.loop, timeout=timeout)
                while True:
                    show(runs.detail(len(seeds) - runs.finished, "queued or running"))
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

