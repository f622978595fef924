"""Measuring helpers the benchmark scripts share (imported as ``_measure``: scripts run from
this folder, so it is on ``sys.path``)."""

from __future__ import annotations

import os
import subprocess
import tempfile
import time
import tracemalloc
from typing import NamedTuple

import numpy as np


def best(fn, repeat: int):
    """Best wall-clock and best CPU time (this process) of ``repeat`` runs, and the last output.

    On a shared machine the CPU time is the better measure of one core's work."""
    out, t_best, cpu_best = None, np.inf, np.inf
    for _ in range(repeat):
        out = None  # free the previous result first: the peak is one call's
        t, c = time.perf_counter(), time.process_time()
        out = fn()
        t_best = min(t_best, time.perf_counter() - t)
        cpu_best = min(cpu_best, time.process_time() - c)
    return t_best, cpu_best, out


def peak_mib(fn) -> float:
    """Peak Python-traced memory (MiB) of one call of ``fn`` (numpy buffers included)."""
    tracemalloc.start()
    try:
        fn()
        return tracemalloc.get_traced_memory()[1] / 2**20
    finally:
        tracemalloc.stop()


def command(argv: list[str], env: dict | None = None) -> tuple[float, float, float, int, str]:
    """Run ``argv`` as a fresh process: wall s, CPU s (user + sys of the process, from
    ``os.wait4``), peak RSS (MiB), exit code, and the last line of its stderr."""
    r = child(argv, env=env)
    return r.wall, r.cpu, r.rss_mib, r.returncode, (r.stderr.strip().splitlines() or [""])[-1]


class ChildRun(NamedTuple):
    """What one child process cost: wall seconds, CPU seconds (user, sys), peak RSS (MiB), and
    what it said."""

    wall: float
    user: float
    sys: float
    rss_mib: float
    returncode: int
    stdout: str
    stderr: str

    @property
    def cpu(self) -> float:
        return self.user + self.sys


def child(argv: list[str], *, cwd=None, env: dict | None = None) -> ChildRun:
    """Run ``argv`` as a child process and measure that process alone (``os.wait4``: its own
    CPU time and peak resident size, not the sum over children as ``RUSAGE_CHILDREN`` gives).

    Linux starts a child's peak RSS from its parent's at the fork: measure from a small parent
    (heavy imports after the children, or in a child of their own)."""
    t = time.perf_counter()
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        proc = subprocess.Popen(argv, cwd=cwd, env=env, stdout=out, stderr=err)
        _, status, ru = os.wait4(proc.pid, 0)
        wall = time.perf_counter() - t
        proc.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0)
        err.seek(0)
        return ChildRun(wall, ru.ru_utime, ru.ru_stime, ru.ru_maxrss / 1024, proc.returncode,
                        out.read().decode(errors="replace"), err.read().decode(errors="replace"))


def best_child(argv: list[str], repeat: int, *, cwd=None) -> ChildRun:
    """The run of least CPU time among ``repeat`` runs of :func:`child` (after none: warm up
    first); a run that fails stops the benchmark with its stderr."""
    runs = [child(argv, cwd=cwd) for _ in range(repeat)]
    for r in runs:
        if r.returncode != 0:
            raise SystemExit(f"{' '.join(argv)} exited {r.returncode}: {r.stderr}")
    return min(runs, key=lambda r: r.cpu)
