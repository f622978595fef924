"""Studio solves in worker processes: progress, cancel, and a server that never breaks.

Each solve runs :func:`tilesolve.studio.worker.solve_request` in its own process, forked
from a *forkserver* that has imported (and compiled) the families once, so a process starts
in milliseconds. Cancelling a solve ends its process: whatever the solver was doing, nothing
of it is left in the server, and other solves go on. A thread per job waits for the answer,
so no request handler ever blocks the event loop.
"""

from __future__ import annotations

import itertools
import multiprocessing
import threading
import time
import traceback
from collections import OrderedDict
from dataclasses import dataclass, field
from typing import Any

from tilesolve.errors import InvalidProblem

__all__ = ["Job", "Jobs", "TooBusy", "MAX_RUNNING", "KEEP"]

#: Solves that may run at once (more are refused with a message, not queued).
MAX_RUNNING = 4
#: Finished jobs kept for their exports.
KEEP = 32


class TooBusy(InvalidProblem):
    """Too many solves are running."""


def _child(conn, request: tuple) -> None:
    """The worker process: solve and send ``("ok", answer)``, ``("error", message)`` or
    ``("internal", traceback)``."""
    from tilesolve.errors import InvalidProblem as Bad
    from tilesolve.studio.worker import solve_request

    try:
        conn.send(("ok", solve_request(*request)))
    except Bad as exc:
        conn.send(("error", " ".join(str(exc).split())))
    except Exception:  # noqa: BLE001 - reported to the page as an internal error, the server goes on
        conn.send(("internal", traceback.format_exc(limit=8)))
    finally:
        conn.close()


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

    def public(self) -> dict:
        """What ``GET /api/jobs/ID`` answers."""
        end = self.finished if self.finished is not None else time.perf_counter()
        out = {"id": self.id, "family": self.family, "state": self.state, "elapsed_s": round(end - self.started, 3),
               "time_limit": self.time_limit}
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
        self._jobs: OrderedDict[str, Job] = OrderedDict()
        self._lock = threading.Lock()
        self._ids = itertools.count(1)

    def warm(self) -> None:
        """Start the forkserver now (it imports and compiles the families once)."""
        p = self._ctx.Process(target=time.sleep, args=(0,))
        p.start()
        p.join()

    def running(self) -> int:
        with self._lock:
            return sum(j.state == "running" for j in self._jobs.values())

    def start(self, family: str, values: Any, method: str, time_limit: float | None) -> Job:
        """Start a solve (the request was checked by the caller)."""
        with self._lock:
            if sum(j.state == "running" for j in self._jobs.values()) >= MAX_RUNNING:
                raise TooBusy(f"{MAX_RUNNING} solves are running; wait for one or cancel it")
            job = Job(f"j{next(self._ids)}", family, time_limit)
            self._jobs[job.id] = job
            while len(self._jobs) > KEEP + MAX_RUNNING:
                old = next((k for k, j in self._jobs.items() if j.state != "running"), None)
                if old is None:
                    break
                del self._jobs[old]
        recv, send = self._ctx.Pipe(duplex=False)
        job.process = self._ctx.Process(target=_child, args=(send, (family, values, method, time_limit)),
                                        daemon=True)
        job.process.start()
        send.close()
        threading.Thread(target=self._wait, args=(job, recv), daemon=True).start()
        return job

    def _wait(self, job: Job, conn) -> None:
        try:
            kind, payload = conn.recv()
        except (EOFError, OSError):
            kind, payload = "gone", None
        finally:
            conn.close()
        job.process.join(5)
        with self._lock:
            job.finished = time.perf_counter()
            if job.state == "running":
                if kind == "ok":
                    job.state, job.result = "done", payload
                elif kind == "error":
                    job.state, job.error = "error", payload
                elif kind == "internal":
                    job.state, job.error = "error", "internal error: " + payload.strip().splitlines()[-1]
                else:
                    job.state, job.error = "error", f"the solver process ended (exit code {job.process.exitcode})"
        job.done.set()

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
        """End every running solve (server shutdown)."""
        for job in list(self._jobs.values()):
            if job.state == "running":
                self.cancel(job.id)
