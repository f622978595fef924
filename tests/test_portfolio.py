"""Portfolios of seeded runs: local worker processes, in-process runs, and a Dask cluster.

The tasks are fakes scripted per seed (``scripted``), so every outcome is fixed in advance.
No wall-clock limits: where a test shows that a long run was stopped rather than waited for,
the run sleeps 60 s and the test only checks that the call came back within 30 s (a bound
that a loaded machine still meets, and that waiting for the sleeper never could).
"""

from __future__ import annotations

import functools
import io
import os
import signal
import sys
import time
from concurrent.futures.process import BrokenProcessPool

import numpy as np
import pytest

import tilesolve.engine.portfolio as pf
from tilesolve.engine import progress
from tilesolve.engine.portfolio import run_portfolio
from tilesolve.errors import BackendUnavailable, InvalidProblem
from tilesolve.model.solution import Solution, Status

LONG_S = 60.0  # a run the portfolio must stop, not wait for
BOUND_S = 30.0  # "it did not wait for the 60 s run": not a speed goal


class _OddError(Exception):
    """Pickles, but cannot be rebuilt from its args: the parent gets a RuntimeError instead."""

    def __init__(self, a, b):
        super().__init__(f"odd {a} {b}")


def _tiling(seed: int) -> np.ndarray:
    return np.random.default_rng(seed).integers(0, 4, size=(3, 5))


def scripted(plan: dict, seed: int) -> Solution:
    """A fake randomised run whose outcome for each seed is ``plan[seed]`` (default unknown).

    ``"sat"``, ``"unsat"``, ``"unknown:REASON"``, ``"sleep:S"`` (then unknown), ``"raise"``,
    ``"odd"``, ``"exit"`` (the process dies), ``"sigint:PID:S"`` (Ctrl-C to PID, then sleep S).
    """
    action, _, arg = plan.get(seed, "unknown").partition(":")
    stats = {"pid": os.getpid()}
    time.sleep(0.05)
    if action == "sat":
        return Solution(Status.SAT, _tiling(seed), "fake", "fake-solver", seed, 0.05, stats=stats)
    if action == "unsat":
        return Solution(Status.UNSAT, None, "fake", "fake-solver", seed, 0.05, reason="refuted", stats=stats)
    if action == "sleep":
        time.sleep(float(arg))
    elif action == "raise":
        raise InvalidProblem(f"bad input for seed {seed}")
    elif action == "odd":
        raise _OddError(1, 2)
    elif action == "exit":
        os._exit(7)
    elif action == "sigint":
        pid, _, sleep = arg.partition(":")
        os.kill(int(pid), signal.SIGINT)
        time.sleep(float(sleep))
    reason = (arg or None) if action == "unknown" else "time limit"
    return Solution(Status.UNKNOWN, None, "fake", "fake-solver", seed, 0.05, reason=reason, stats=stats)


def task(**plan) -> functools.partial:
    return functools.partial(scripted, {int(k[1:]): v for k, v in plan.items()})


@pytest.fixture
def ctrl_c():
    """Python's own Ctrl-C handler, whatever this process inherited (a job started in the
    background by a shell without job control ignores SIGINT, and Python then keeps it so)."""
    old = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, old)


def _same(a: Solution, b: Solution) -> None:
    assert (a.status, a.method, a.solver, a.seed, a.reason, a.notes) == (b.status, b.method, b.solver, b.seed,
                                                                         b.reason, b.notes)
    assert np.array_equal(a.tiling, b.tiling)


# ------------------------------------------------------------------------------- in-process


@pytest.mark.parametrize("workers", [1, 2])
def test_one_seed_is_the_plain_call(workers):
    t = task(s5="sat")
    s = run_portfolio(t, [5], workers=workers)
    _same(s, t(5))
    assert s.stats["pid"] == os.getpid() and s.time_s == t(5).time_s


def test_one_worker_runs_the_seeds_in_order_in_this_process():
    t = task(s3="sat", s4="sat")
    s = run_portfolio(t, [0, 1, 2, 3, 4], workers=1)
    assert s.status is Status.SAT and s.seed == 3
    assert np.array_equal(s.tiling, t(3).tiling)  # the same tiling as the plain call
    assert s.stats["pid"] == os.getpid()
    assert s.notes == ("portfolio: seed 3 decided it, after 4 of 5 runs started, in this process (1 worker)",)
    assert s.stats["portfolio_runs"] == 4 and s.stats["run_time_s"] == 0.05


def test_one_worker_all_unknown_is_unknown_with_a_summary():
    s = run_portfolio(task(s0="unknown:time limit", s2="unknown:time limit"), [0, 1, 2], workers=1)
    assert s.status is Status.UNKNOWN and s.tiling is None
    assert s.reason == "no run decided: 3 runs ended unknown (time limit: 2, no reason given: 1)"
    assert (s.method, s.solver, s.seed) == ("fake", "fake-solver", None)


def test_one_worker_ctrl_c_returns_unknown_interrupted(ctrl_c):
    s = run_portfolio(task(s0=f"sigint:{os.getpid()}:{LONG_S}", s1="sat"), [0, 1], workers=1)
    assert s.status is Status.UNKNOWN and s.reason == "interrupted"
    assert s.notes == ("no run decided: 1 run stopped (interrupted); 1 seed not started (interrupted)",)


def test_a_run_that_reports_interrupted_ends_the_portfolio():
    # A solver that catches Ctrl-C itself (engine.result.run_interruptible) returns unknown.
    s = run_portfolio(task(s0="unknown:interrupted", s1="sat"), [0, 1], workers=1)
    assert s.status is Status.UNKNOWN and s.reason == "interrupted"


def test_one_worker_time_limit_starts_no_more_seeds():
    s = run_portfolio(task(s0="sleep:0.3", s1="sat"), [0, 1], workers=1, time_limit=0.1)
    assert s.status is Status.UNKNOWN
    assert s.reason == "no run decided: 1 run ended unknown (time limit: 1); 1 seed not started (time limit)"


@pytest.mark.parametrize("kwargs", [dict(seeds=[]), dict(seeds=[-1]), dict(seeds=[1.5]), dict(workers=0),
                                    dict(workers=True), dict(time_limit=-1.0)])
def test_bad_arguments(kwargs):
    args = dict(seeds=[0, 1], workers=2) | kwargs
    with pytest.raises(InvalidProblem):
        run_portfolio(task(), args.pop("seeds"), **args)


# -------------------------------------------------------------------- local worker processes


def test_first_decisive_run_wins_and_the_others_are_terminated(tmp_path):
    t0 = time.perf_counter()
    s = run_portfolio(task(s0=f"sleep:{LONG_S}", s1="sat", s2=f"sleep:{LONG_S}"), [0, 1, 2], workers=2)
    assert time.perf_counter() - t0 < BOUND_S  # did not wait for the 60 s sleeper
    assert s.status is Status.SAT and s.seed == 1
    assert np.array_equal(s.tiling, _tiling(1))  # a process boundary changes nothing
    assert s.stats["pid"] != os.getpid()
    assert s.notes == ("portfolio: seed 1 decided it, after 2 of 3 runs started, on 2 worker processes",)
    assert s.stats["portfolio_workers"] == 2 and s.time_s >= s.stats["run_time_s"]


def test_more_seeds_than_workers_queue_up():
    s = run_portfolio(task(s5="sat"), range(6), workers=2)
    assert s.status is Status.SAT and s.seed == 5
    assert s.stats["portfolio_runs"] == 6
    assert s.notes[-1].endswith("after 6 of 6 runs started, on 2 worker processes")


def test_unsat_is_decisive():
    s = run_portfolio(task(s2="unsat"), range(4), workers=2)
    assert s.status is Status.UNSAT and s.seed == 2 and s.reason == "refuted"


def test_all_unknown_is_unknown_never_unsat():
    s = run_portfolio(task(s0="unknown:budget", s1="unknown:time limit", s2="unknown:budget"), range(4), workers=2)
    assert s.status is Status.UNKNOWN
    assert s.reason.startswith("no run decided: 4 runs ended unknown (")
    for part in ("budget: 2", "time limit: 1", "no reason given: 1"):
        assert part in s.reason
    assert s.stats == {"portfolio_runs": 4, "portfolio_workers": 2}


def test_time_limit_stops_running_runs():
    t0 = time.perf_counter()
    s = run_portfolio(task(s0=f"sleep:{LONG_S}", s1=f"sleep:{LONG_S}", s2="sat"), range(3), workers=2,
                      time_limit=0.2)
    assert time.perf_counter() - t0 < BOUND_S  # did not wait for the sleepers
    assert s.status is Status.UNKNOWN
    assert s.reason == "no run decided: 2 runs stopped (time limit); 1 seed not started (time limit)"


def test_a_worker_exception_is_reraised_with_its_type_after_stopping_the_others():
    t0 = time.perf_counter()
    with pytest.raises(InvalidProblem, match="bad input for seed 1") as info:
        run_portfolio(task(s0=f"sleep:{LONG_S}", s1="raise"), [0, 1], workers=2)
    assert time.perf_counter() - t0 < BOUND_S
    assert "Traceback" in str(info.value.__cause__) and "scripted" in str(info.value.__cause__)


def test_an_exception_that_cannot_be_rebuilt_arrives_as_runtime_error():
    with pytest.raises(RuntimeError, match=r"test_portfolio\._OddError: odd 1 2"):
        run_portfolio(task(s0="odd"), [0, 1], workers=2)


def test_a_worker_that_dies_breaks_the_pool():
    with pytest.raises(BrokenProcessPool, match="exit code 7.*seed 0"):
        run_portfolio(task(s0="exit", s1=f"sleep:{LONG_S}"), [0, 1], workers=2)


def test_unpicklable_task_is_a_type_error():
    with pytest.raises(TypeError, match="picklable"):
        run_portfolio(lambda seed: Solution(Status.SAT), [0, 1], workers=2)


def test_ctrl_c_in_the_parent_stops_the_workers_and_returns_unknown(ctrl_c):
    t0 = time.perf_counter()
    s = run_portfolio(task(s0=f"sigint:{os.getpid()}:{LONG_S}", s1=f"sleep:{LONG_S}"), [0, 1, 2], workers=2)
    assert time.perf_counter() - t0 < BOUND_S
    assert s.status is Status.UNKNOWN and s.reason == "interrupted"
    assert s.notes == ("no run decided: 2 runs stopped (interrupted); 1 seed not started (interrupted)",)


def test_progress_line_on_a_terminal(monkeypatch):
    class Terminal(io.StringIO):
        def isatty(self):
            return True

    term = Terminal()
    monkeypatch.setattr(sys, "stderr", term)
    monkeypatch.setattr(pf, "status_line", functools.partial(progress.status_line, every=0.01))
    s = run_portfolio(task(s0="unknown:budget", s1="sleep:1", s2="sat"), range(3), workers=2, progress=True,
                      label="packing")
    assert s.status is Status.SAT
    out = term.getvalue()
    assert "packing: " in out and " runs finished, " in out and " running ... " in out
    assert out.endswith("\r\033[K")  # erased when the call returns


def test_no_progress_line_off_a_terminal(monkeypatch):
    term = io.StringIO()
    monkeypatch.setattr(sys, "stderr", term)
    run_portfolio(task(s1="sat"), range(2), workers=2, progress=True)
    assert term.getvalue() == ""


# ------------------------------------------------------------------------------------ Dask


@pytest.fixture(scope="module")
def dask_address():
    import distributed  # a test dependency (the "cluster" extra is part of the "test" extra)

    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=":0") as cluster:  # any free port
        yield cluster.scheduler_address


def test_dask_first_decisive_run_wins(dask_address):
    s = run_portfolio(task(s3="sat"), range(5), cluster=dask_address)
    assert s.status is Status.SAT and s.seed == 3
    assert np.array_equal(s.tiling, _tiling(3))
    assert s.stats["pid"] != os.getpid()
    assert s.notes[-1].startswith("portfolio: seed 3 decided it, after 5 of 5 runs submitted, "
                                  f"on the Dask cluster at {dask_address} (2 workers, 2 threads)")


def test_dask_all_unknown(dask_address):
    s = run_portfolio(task(s0="unknown:budget", s1="unknown:budget"), range(3), cluster=dask_address)
    assert s.status is Status.UNKNOWN
    assert s.reason == "no run decided: 3 runs ended unknown (budget: 2, no reason given: 1)"


def test_dask_exception_keeps_its_type(dask_address):
    with pytest.raises(InvalidProblem, match="bad input for seed 2"):
        run_portfolio(task(s2="raise"), range(3), cluster=dask_address)


def test_dask_open_client_is_used_and_left_open(dask_address):
    from distributed import Client

    with Client(dask_address, set_as_default=False) as client:
        s = run_portfolio(task(s1="sat"), range(2), cluster=client)
        assert s.status is Status.SAT and s.seed == 1
        assert client.status == "running"


def test_dask_time_limit(dask_address):
    t0 = time.perf_counter()
    s = run_portfolio(task(s0="sleep:2", s1="sleep:2"), range(2), cluster=dask_address, time_limit=0.1)
    assert time.perf_counter() - t0 < BOUND_S
    assert s.status is Status.UNKNOWN and s.reason == "no run decided: 2 runs stopped (time limit)"


def test_dask_ctrl_c(dask_address, ctrl_c):
    s = run_portfolio(task(s0=f"sigint:{os.getpid()}:1"), range(2), cluster=dask_address)
    assert s.status is Status.UNKNOWN and s.reason == "interrupted"


def test_unreachable_scheduler_is_a_one_line_error(monkeypatch):
    monkeypatch.setattr(pf, "CONNECT_TIMEOUT_S", 1.0)
    with pytest.raises(BackendUnavailable) as info:
        run_portfolio(task(), [0, 1], cluster="tcp://127.0.0.1:1")
    msg = str(info.value)
    assert msg.startswith("cannot connect to the Dask scheduler at tcp://127.0.0.1:1: ") and "\n" not in msg
    assert info.value.__cause__ is None and info.value.__context__ is None


@pytest.mark.parametrize("address", ["foo://127.0.0.1:1", "ray://127.0.0.1:10001", 8786])
def test_malformed_cluster_address(address):
    with pytest.raises(InvalidProblem):
        run_portfolio(task(), [0, 1], cluster=address)


def test_missing_dask_names_the_extra(monkeypatch):
    monkeypatch.setitem(sys.modules, "distributed", None)  # makes `import distributed` fail
    with pytest.raises(BackendUnavailable, match=r'pip install "tilesolve\[cluster\]"'):
        run_portfolio(task(), [0, 1], cluster="tcp://127.0.0.1:8786")
