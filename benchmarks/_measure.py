"""Measuring helpers the benchmark scripts share (imported as ``_measure``: scripts run from
this folder, so it is on ``sys.path``)."""

from __future__ import annotations

import time
import tracemalloc

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
    import os
    import subprocess

    t = time.perf_counter()
    proc = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=env)
    _, status, ru = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - t
    err = proc.stderr.read().decode(errors="replace").strip().splitlines()
    proc.stderr.close()
    return wall, ru.ru_utime + ru.ru_stime, ru.ru_maxrss / 1024, os.waitstatus_to_exitcode(status), (err or [""])[-1]
