"""Studio solves in worker processes: progress, cancel, and a server that never breaks.

Each solve runs :func:`tilesolve.studio.worker.solve_request` in its own process, forked
from a *forkserver* that has imported (and compiled) the families once; a few processes are
started ahead and wait for a request, so a solve starts at once. Cancelling a solve ends its
process: whatever the solver was doing, nothing of it is left in the server, and other solves
go on. A thread per job waits for the answer, so no request handler ever blocks the event loop.

Progress: the solve reports on a :class:`tilesolve.progress.Stream` whose snapshots the worker
sends up its pipe (``("progress", snapshot)``) as they come; the waiting thread keeps the open
tasks in :attr:`Job.tasks` and wakes whoever waits for a change (:meth:`Job.wait_change`, the
server's event stream).

Memory: a solve may grow by :data:`SOLVE_MEMORY` bytes of resident memory above what its
process held when it started; the thread that waits for it reads the process's resident size
(``/proc/PID/statm``) every :data:`WATCH_S` seconds and ends a process past the cap, and the job
then says so. (A resident-size watch, not ``RLIMIT_AS``: the solvers reserve address space
they never touch, e.g. a malloc arena and a stack per CP-SAT thread, so a cap on address space
would refuse solves that fit.)

Lifetime: the processes die with the server, even when it is killed by SIGKILL and runs no
cleanup. The forkserver is started by one thread that lives as long as the server process
(:data:`_KEEPER`) and asks the kernel for a parent-death signal when it imports
:mod:`tilesolve.studio.warm`; every worker asks for one too, bound to the forkserver. This is
the parent-death arrangement of the CLI's portfolio workers
(:func:`tilesolve.engine.portfolio._die_with_parent`). The kernel's signal follows the
*thread* that started a process, hence the one long-lived starting thread.
"""

from __future__ import annotations

import contextlib
import itertools
import multiprocessing
import os
import sys
import threading
import time
import traceback
from collections import OrderedDict
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from typing import Any

from tilesolve.errors import InvalidProblem

#: The process id a studio process dies with: set by the server while it starts the forkserver
#: (:mod:`tilesolve.studio.warm` then arms the forkserver's parent-death signal and warms it),
#: and by the forkserver, to its own id, for the workers it forks. Unset anywhere else.
PARENT_ENV = "TILESOLVE_STUDIO_PARENT"

__all__ = ["Job", "Jobs", "TooBusy", "MAX_RUNNING", "KEEP", "SPARES", "SOLVE_MEMORY", "PARENT_ENV", "in_bytes"]

#: Solves that may run at once (more are refused with a message, not queued).
MAX_RUNNING = 4
#: Finished jobs kept for their exports.
KEEP = 32
#: Worker processes started ahead of need.
SPARES = 2
#: Resident memory a solve may add to its process (bytes); a solve past it is ended.
SOLVE_MEMORY = 2 << 30
#: How often a running solve's memory is read (seconds).
WATCH_S = 0.1

#: The one thread that starts studio processes (module docstring, "Lifetime"): it lives as long
#: as the server process, so the forkserver's parent-death signal fires only when that dies.
_KEEPER = ThreadPoolExecutor(max_workers=1, thread_name_prefix="tilesolve-studio-processes")


def in_bytes(n: int) -> str:
    """``n`` bytes for messages: ``"2.0 GiB"``, ``"16 MiB"``."""
    return f"{n / (1 << 30):,.1f} GiB" if n >= 1 << 30 else f"{n / (1 << 20):,.0f} MiB"


def _resident(pid: int) -> int:
    """Resident memory of process ``pid`` in bytes (0 where /proc cannot tell)."""
    try:
        with open(f"/proc/{pid}/statm", "rb") as f:
            return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, IndexError):
        return 0


class TooBusy(InvalidProblem):
    """Too many solves are running."""


def _child(conn) -> None:
    """The worker process: die with the forkserver, wait for one request, solve it, sending
    ``("progress", snapshot)`` as it goes, and send ``("ok", answer)``, ``("error", message)``
    or ``("internal", message)``, then end (an internal error's traceback goes to the server's
    standard error)."""
    from tilesolve.engine.portfolio import _die_with_parent
    from tilesolve.errors import InvalidProblem as Bad
    from tilesolve.progress import Stream
    from tilesolve.studio.worker import solve_request

    sending = threading.Lock()  # a portfolio reports from a helper thread too

    def send(message) -> None:
        with sending:
            conn.send(message)

    _die_with_parent(int(os.environ.get(PARENT_ENV, os.getppid())))  # the forkserver's id, set by warm
    try:
        request = conn.recv()
    except (EOFError, OSError):  # the server went away before giving this process a job
        return
    try:
        send(("ok", solve_request(*request, progress=Stream(lambda snapshot: send(("progress", snapshot))))))
    except Bad as exc:
        send(("error", " ".join(str(exc).split())))
    except MemoryError:
        send(("error", "out of memory in the solver process; try a smaller problem"))
    except Exception as exc:  # noqa: BLE001 - reported to the page as an internal error, the server goes on
        traceback.print_exc(limit=8, file=sys.stderr)
        send(("internal", " ".join(str(exc).split()) or "no message"))
    finally:
        conn.close()


@contextlib.contextmanager
def _parent_env():
    """:data:`PARENT_ENV` set to this process while a studio process starts (the forkserver, if
    it is not running, inherits it), and unset again."""
    os.environ[PARENT_ENV] = str(os.getpid())
    try:
        yield
    finally:
        del os.environ[PARENT_ENV]


@dataclass
class Job:
    """One solve: ``state`` is ``running``, ``done``, ``error`` or ``cancelled``."""

    id: str
    family: str
    time_limit: float | None
    started: float = field(default_factory=time.perf_counter)
    state: str = "running"
    result: dict | None = None
    error: str | None = None
    finished: float | None = None
    done: threading.Event = field(default_factory=threading.Event)
    process: Any = None
    resident: int = 0  # the process's resident memory when it took the job (bytes)
    tasks: list = field(default_factory=list)  # the solve's open progress tasks, outermost first
    announced: str | None = None  # the solve's last announcement (an estimate)
    version: int = 0  # counts the changes of progress and state
    changed: threading.Condition = field(default_factory=threading.Condition)

    def take_progress(self, snapshot: dict) -> None:
        """Keep a :class:`tilesolve.progress.Stream` snapshot: a task at depth ``d`` replaces
        the tasks from ``d`` on; a closed one removes them."""
        with self.changed:
            if "announce" in snapshot:
                self.announced = str(snapshot["announce"])
            else:
                depth = int(snapshot.get("depth", 0))
                self.tasks = self.tasks[:depth] + ([] if snapshot.get("closed") else [snapshot])
            self.bump()

    def bump(self) -> None:
        """Count a change and wake who waits for one (call with :attr:`changed` held)."""
        self.version += 1
        self.changed.notify_all()

    def wait_change(self, version: int, timeout: float) -> int:
        """Wait until the job changed since ``version`` (or ``timeout`` seconds); the version now."""
        with self.changed:
            self.changed.wait_for(lambda: self.version != version, timeout)
            return self.version

    def public(self) -> dict:
        """What ``GET /api/jobs/ID`` answers: the state, the time, the open progress tasks
        (:mod:`tilesolve.progress` snapshots), and when done the result or the error."""
        end = self.finished if self.finished is not None else time.perf_counter()
        out = {"id": self.id, "family": self.family, "state": self.state, "elapsed_s": round(end - self.started, 3),
               "time_limit": self.time_limit, "progress": list(self.tasks), "announce": self.announced}
        if self.result is not None:
            out["result"] = self.result
        if self.error is not None:
            out["error"] = self.error
        return out


class Jobs:
    """The running and recent solves of one server."""

    def __init__(self, preload: tuple[str, ...] = ("tilesolve.studio.warm",)) -> None:
        self._ctx = multiprocessing.get_context("forkserver")
        self._ctx.set_forkserver_preload(list(preload))
        self._spares: list[tuple[Any, Any]] = []  # started processes waiting for their request
        self._jobs: OrderedDict[str, Job] = OrderedDict()
        self._lock = threading.Lock()
        self._ids = itertools.count(1)
        self._closed = False

    def warm(self) -> None:
        """Start the forkserver (it imports and compiles the families once) and the spare
        processes now, so the first solve does not wait for them."""
        self._refill()

    def _spawn(self) -> tuple[Any, Any]:
        """A started worker process and the server's end of its pipe (started by :data:`_KEEPER`)."""
        return _KEEPER.submit(self._spawn_here).result()

    def _spawn_here(self) -> tuple[Any, Any]:
        mine, theirs = self._ctx.Pipe()
        process = self._ctx.Process(target=_child, args=(theirs,), daemon=True)
        with _parent_env():  # the forkserver, started by the first spawn, warms itself
            process.start()
        theirs.close()
        return process, mine

    def _refill(self) -> None:
        """Keep :data:`SPARES` processes started and waiting (a solve then starts at once:
        the process start, and its share of the main module's imports, is paid in advance)."""
        while True:
            with self._lock:
                if self._closed or len(self._spares) >= SPARES:
                    return
            spare = self._spawn()
            with self._lock:
                self._spares.append(spare)

    def _take(self) -> tuple[Any, Any]:
        with self._lock:
            while self._spares:
                process, conn = self._spares.pop()
                if process.is_alive():
                    break
                conn.close()
            else:
                process = None
        if process is None:
            process, conn = self._spawn()
        threading.Thread(target=self._refill, daemon=True).start()
        return process, conn

    def running(self) -> int:
        with self._lock:
            return sum(j.state == "running" for j in self._jobs.values())

    def start(self, family: str, values: Any, method: str, time_limit: float | None) -> Job:
        """Start a solve (the request was checked by the caller)."""
        with self._lock:
            if sum(j.state == "running" for j in self._jobs.values()) >= MAX_RUNNING:
                raise TooBusy(f"at most {MAX_RUNNING} solves run at once; wait for one or cancel it")
            job = Job(f"j{next(self._ids)}", family, time_limit)
            self._jobs[job.id] = job
            while len(self._jobs) > KEEP + MAX_RUNNING:
                old = next((k for k, j in self._jobs.items() if j.state != "running"), None)
                if old is None:
                    break
                del self._jobs[old]
        try:
            job.process, conn = self._take()
        except BaseException:  # no process to solve it: the job ends here, as an error
            with self._lock:
                job.finished = time.perf_counter()
                job.state, job.error = "error", "the solver process could not be started"
            job.done.set()
            raise
        job.resident = _resident(job.process.pid)
        conn.send((family, values, method, time_limit))
        threading.Thread(target=self._wait, args=(job, conn), daemon=True).start()
        return job

    def _wait(self, job: Job, conn) -> None:
        """Wait for the job's answer, reading its memory meanwhile (ended past the cap)."""
        kind, payload = "gone", None
        try:
            while True:
                if _resident(job.process.pid) - job.resident > SOLVE_MEMORY:
                    job.process.kill()
                    kind = "memory"
                    break
                if not conn.poll(WATCH_S):
                    continue
                kind, payload = conn.recv()
                if kind != "progress":
                    break
                job.take_progress(payload)
                kind, payload = "gone", None
        except (EOFError, OSError):
            pass
        finally:
            conn.close()
        if kind == "gone":
            job.process.join(5)  # for its exit code
        with self._lock:
            job.finished = time.perf_counter()
            if job.state == "running":
                if kind == "ok":
                    job.state, job.result = "done", payload
                elif kind == "error":
                    job.state, job.error = "error", payload
                elif kind == "internal":
                    job.state, job.error = "error", "internal error in the solver process: " + payload
                elif kind == "memory":
                    job.state, job.error = "error", (f"stopped: the solve needed more than {in_bytes(SOLVE_MEMORY)} of "
                                                     f"memory, the studio's limit per solve; try a smaller problem "
                                                     f"(the tilesolve command has no such limit)")
                else:
                    job.state, job.error = "error", f"the solver process ended (exit code {job.process.exitcode})"
        with job.changed:
            job.tasks = []
            job.bump()
        job.done.set()
        job.process.join()

    def get(self, job_id: str) -> Job:
        with self._lock:
            job = self._jobs.get(job_id)
        if job is None:
            raise KeyError(job_id)
        return job

    def cancel(self, job_id: str) -> Job:
        """End a running solve's process (a finished job is left as it is)."""
        job = self.get(job_id)
        with self._lock:
            if job.state != "running":
                return job
            job.state, job.error = "cancelled", "cancelled"
        job.process.kill()
        job.done.wait(10)
        return job

    def close(self) -> None:
        """End every running solve and the spare processes (server shutdown)."""
        with self._lock:
            self._closed = True
            spares, self._spares = self._spares, []
        for process, conn in spares:
            conn.close()
            process.join(5)
        for job in list(self._jobs.values()):
            if job.state == "running":
                self.cancel(job.id)
