"""Portfolios of seeded runs: local worker processes, in-process runs, and a Dask cluster;
the escalation of a heavy-tailed route (first run here, workers beside it); scripts without a
``__main__`` guard; workers that die with their parent.

The tasks are fakes scripted per seed (``scripted``, ``planned_route``), so every outcome is
fixed in advance. No wall-clock limits: where a test shows that a long run was stopped rather
than waited for, the run lasts 60 s or more and the test only checks that the call came back
within 30 s (a bound that a loaded machine still meets, and that waiting for the run never
could).
"""

from __future__ import annotations

import functools
import io
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time
from pathlib import Path
from concurrent.futures.process import BrokenProcessPool

import numpy as np
import pytest

import tilesolve.engine.portfolio as pf
from tilesolve.deadline import Deadline
from tilesolve.engine.portfolio import escalate, run_portfolio, seeded_run
from tilesolve.engine.result import run_interruptible
from tilesolve.errors import BackendUnavailable, InvalidProblem
from tilesolve.model.run import RunOptions
from tilesolve.model.solution import Solution, Status
from tilesolve.progress import Stream

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
    s = run_portfolio(task(s0="sleep:0.3", s1="sat"), [0, 1], workers=1, deadline=Deadline(0.1))
    assert s.status is Status.UNKNOWN
    assert s.reason == "no run decided: 1 run ended unknown (time limit: 1); 1 seed not started (time limit)"


@pytest.mark.parametrize("kwargs", [dict(seeds=[]), dict(seeds=[-1]), dict(seeds=[1.5]), dict(workers=0),
                                    dict(workers=True)])
def test_bad_arguments(kwargs):
    args = dict(seeds=[0, 1], workers=2) | kwargs
    with pytest.raises(InvalidProblem):
        run_portfolio(task(), args.pop("seeds"), **args)


# -------------------------------------------------------------------- local worker processes


@pytest.mark.slow
def test_first_decisive_run_wins_and_the_others_are_terminated(tmp_path):
    t0 = time.perf_counter()
    s = run_portfolio(task(s0=f"sleep:{LONG_S}", s1="sat", s2=f"sleep:{LONG_S}"), [0, 1, 2], workers=2)
    assert time.perf_counter() - t0 < BOUND_S  # did not wait for the 60 s sleeper
    assert s.status is Status.SAT and s.seed == 1
    assert np.array_equal(s.tiling, _tiling(1))  # a process boundary changes nothing
    assert s.stats["pid"] != os.getpid()
    assert s.notes == ("portfolio: seed 1 decided it, after 2 of 3 runs started, on 2 worker processes",)
    assert s.stats["portfolio_workers"] == 2 and s.time_s >= s.stats["run_time_s"]


@pytest.mark.slow
def test_more_seeds_than_workers_queue_up():
    s = run_portfolio(task(s5="sat"), range(6), workers=2)
    assert s.status is Status.SAT and s.seed == 5
    assert s.stats["portfolio_runs"] == 6
    assert s.notes[-1].endswith("after 6 of 6 runs started, on 2 worker processes")


@pytest.mark.slow
def test_unsat_is_decisive():
    s = run_portfolio(task(s2="unsat"), range(4), workers=2)
    assert s.status is Status.UNSAT and s.seed == 2 and s.reason == "refuted"


@pytest.mark.slow
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
                      deadline=Deadline(0.2))
    assert time.perf_counter() - t0 < BOUND_S  # did not wait for the sleepers
    assert s.status is Status.UNKNOWN
    assert s.reason == "no run decided: 2 runs stopped (time limit); 1 seed not started (time limit)"


@pytest.mark.slow
def test_a_worker_exception_is_reraised_with_its_type_after_stopping_the_others():
    t0 = time.perf_counter()
    with pytest.raises(InvalidProblem, match="bad input for seed 1") as info:
        run_portfolio(task(s0=f"sleep:{LONG_S}", s1="raise"), [0, 1], workers=2)
    assert time.perf_counter() - t0 < BOUND_S
    assert "Traceback" in str(info.value.__cause__) and "scripted" in str(info.value.__cause__)


@pytest.mark.slow
def test_an_exception_that_cannot_be_rebuilt_arrives_as_runtime_error():
    with pytest.raises(RuntimeError, match=r"test_portfolio\._OddError: odd 1 2"):
        run_portfolio(task(s0="odd"), [0, 1], workers=2)


@pytest.mark.slow
def test_a_worker_that_dies_breaks_the_pool():
    with pytest.raises(BrokenProcessPool, match="exit code 7.*seed 0"):
        run_portfolio(task(s0="exit", s1=f"sleep:{LONG_S}"), [0, 1], workers=2)


def test_unpicklable_task_is_a_type_error():
    with pytest.raises(TypeError, match="picklable"):
        run_portfolio(lambda seed: Solution(Status.SAT), [0, 1], workers=2)


@pytest.mark.slow
def test_ctrl_c_in_the_parent_stops_the_workers_and_returns_unknown(ctrl_c):
    t0 = time.perf_counter()
    s = run_portfolio(task(s0=f"sigint:{os.getpid()}:{LONG_S}", s1=f"sleep:{LONG_S}"), [0, 1, 2], workers=2)
    assert time.perf_counter() - t0 < BOUND_S
    assert s.status is Status.UNKNOWN and s.reason == "interrupted"
    assert s.notes == ("no run decided: 2 runs stopped (interrupted); 1 seed not started (interrupted)",)


@pytest.mark.slow
def test_progress_counts_seeds():
    sent: list[dict] = []
    s = run_portfolio(task(s0="unknown:budget", s1="sleep:1", s2="sat"), range(3), workers=2,
                      progress=Stream(sent.append, every=0), label="packing")
    assert s.status is Status.SAT
    assert {(m["label"], m["unit"], m["total"]) for m in sent} == {("packing", "seed", 3)}
    assert any(m["done"] == 1 and m["note"] == "2 running" for m in sent)  # seed 0 ended unknown, two run
    assert sent[-1].get("closed")


def test_portfolio_progress_nests_in_the_pipelines():
    sent: list[dict] = []
    stream = Stream(sent.append, every=0)
    with stream.task("packing: solving with 'fake'", unit=None):
        s = run_portfolio(task(s0="sleep:0.3", s1="sleep:0.3", s2="sat"), range(3), workers=1, progress=stream,
                          label="fake search")
    assert s.status is Status.SAT
    inner = [m for m in sent if m["label"] == "fake search"]
    assert inner and all(m["depth"] == 1 for m in inner)
    assert {m["done"] for m in inner} == {0, 1, 2}  # seeds finished, counted as each next one starts
    assert inner[-2]["note"] == "1 running (seed 2)"


@pytest.mark.slow
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


@pytest.mark.slow
def test_dask_first_decisive_run_wins(dask_address):
    s = run_portfolio(task(s3="sat"), range(5), cluster=dask_address)
    assert s.status is Status.SAT and s.seed == 3
    assert np.array_equal(s.tiling, _tiling(3))
    assert s.stats["pid"] != os.getpid()
    assert s.notes[-1].startswith("portfolio: seed 3 decided it, after 5 of 5 runs submitted, "
                                  f"on the Dask cluster at {dask_address} (2 workers, 2 threads)")


@pytest.mark.slow
def test_dask_all_unknown(dask_address):
    s = run_portfolio(task(s0="unknown:budget", s1="unknown:budget"), range(3), cluster=dask_address)
    assert s.status is Status.UNKNOWN
    assert s.reason == "no run decided: 3 runs ended unknown (budget: 2, no reason given: 1)"


@pytest.mark.slow
def test_dask_exception_keeps_its_type(dask_address):
    with pytest.raises(InvalidProblem, match="bad input for seed 2"):
        run_portfolio(task(s2="raise"), range(3), cluster=dask_address)


@pytest.mark.slow
def test_dask_open_client_is_used_and_left_open(dask_address):
    from distributed import Client

    with Client(dask_address, set_as_default=False) as client:
        s = run_portfolio(task(s1="sat"), range(2), cluster=client)
        assert s.status is Status.SAT and s.seed == 1
        assert client.status == "running"


@pytest.mark.slow
def test_dask_time_limit(dask_address):
    t0 = time.perf_counter()
    s = run_portfolio(task(s0="sleep:2", s1="sleep:2"), range(2), cluster=dask_address, deadline=Deadline(0.1))
    assert time.perf_counter() - t0 < BOUND_S
    assert s.status is Status.UNKNOWN and s.reason == "no run decided: 2 runs stopped (time limit)"


@pytest.mark.slow
def test_dask_ctrl_c(dask_address, ctrl_c):
    s = run_portfolio(task(s0=f"sigint:{os.getpid()}:1"), range(2), cluster=dask_address)
    assert s.status is Status.UNKNOWN and s.reason == "interrupted"


@pytest.mark.slow
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


# --------------------------------------------------------------------- escalate (a route)


def planned_route(plan: dict, run: RunOptions):
    """A fake route over the "problem" ``plan`` (the run's seed -> action, default ``"wait"``).

    ``"sat"``; ``"sleep:S"`` (then ``sat``: decides late and cannot be stopped early);
    ``"raise"``; ``"wait"``: a "solver" that runs until it is interrupted (the time limit, or
    the escalation's stop request) and then answers ``unknown``.
    """
    seed, solver = run.seed, run.solver
    action, _, arg = plan.get(seed, "wait").partition(":")
    stats = {"pid": os.getpid(), "time_limit": run.deadline.time_limit, "nice": os.nice(0)}
    if action == "raise":
        raise InvalidProblem(f"bad input for seed {seed}")
    if action == "wait":
        solving = threading.Event()
        _, stop = run_interruptible(solving.wait, solving.set, run.deadline)
        return Solution(Status.UNKNOWN, None, "fake", solver, seed, 0.0, reason=stop, stats=stats)
    if action == "sleep":
        time.sleep(float(arg))
    return Solution(Status.SAT, _tiling(seed), "fake", solver, seed, 0.0, stats=stats)


def _escalate(plan: dict, *, time_limit: float | None = None, **kwargs) -> Solution:
    run = RunOptions(**({"seed": 1, "solver": "s", "deadline": Deadline(time_limit)} | kwargs))
    return escalate(planned_route, plan, run, name="fake search")


@pytest.fixture
def at_once(monkeypatch):
    """Workers join the first run at once, and their runs last past the 30 s bound; they keep
    this process's priority (niced, a loaded machine could stretch their start past the bound)."""
    monkeypatch.setattr(pf, "QUICK_S", 0.0)
    monkeypatch.setattr(pf, "FIRST_BUDGET_S", LONG_S)
    monkeypatch.setattr(pf, "WORKER_NICE", 0)


def test_escalate_first_run_that_decides_quickly_is_the_plain_call():
    s = _escalate({1: "sat"})
    plain = planned_route({1: "sat"}, RunOptions(seed=1, solver="s"))
    _same(s, plain)
    assert s.stats == plain.stats and s.stats["pid"] == os.getpid()


@pytest.mark.parametrize("workers", [1, 2])
def test_escalate_keeps_the_first_run_with_the_whole_time_limit(workers, monkeypatch):
    monkeypatch.setattr(pf, "QUICK_S", 0.1)
    s = _escalate({1: "sleep:0.5"}, workers=workers, time_limit=50.0)
    assert s.status is Status.SAT and s.seed == 1 and s.stats["pid"] == os.getpid()
    assert s.stats["time_limit"] == 50.0  # not cut to QUICK_S: the first run is never thrown away
    if workers == 2:
        assert s.notes == ("portfolio: seed 1 decided it in this process; 1 run started beside it on "
                           "1 worker process",)
        assert s.stats["portfolio_runs"] == 1 and s.stats["portfolio_workers"] == 1
    else:
        assert s.notes == () and "portfolio_runs" not in s.stats


@pytest.mark.fast_cases(1)
@pytest.mark.parametrize("idle, started", [(0.0, False), (0.2, False), (0.5, True), (1.0, True)])
def test_escalate_by_default_starts_workers_only_on_idle_cores(idle, started, monkeypatch):
    clock = iter(range(1, 10**6))

    def cpu_times():  # the machine's (idle, total) ticks: a fixed fraction of 2 cores idle
        total = 100.0 * next(clock)
        return idle * total, total

    monkeypatch.setattr(pf, "_cpu_times", cpu_times)
    monkeypatch.setattr(pf.os, "cpu_count", lambda: 2)
    monkeypatch.setattr(pf, "QUICK_S", 0.1)
    s = _escalate({1: "sleep:1"})  # workers=None: the default
    assert s.status is Status.SAT and s.seed == 1 and s.stats["pid"] == os.getpid()
    assert ("portfolio_workers" in s.stats) is started
    if started:
        assert s.stats["portfolio_workers"] == 1  # DEFAULT_WORKERS = 2: this process and one worker


def test_idle_cores_from_cpu_time_samples(monkeypatch):
    monkeypatch.setattr(pf.os, "cpu_count", lambda: 4)
    assert pf._idle_cores((100.0, 1000.0), (175.0, 1100.0), 9) == 3  # 75 % of 4 cores
    assert pf._idle_cores((100.0, 1000.0), (110.0, 1100.0), 9) == 0
    assert pf._idle_cores(None, (110.0, 1100.0), 9) == 9  # the machine does not tell
    if sys.platform.startswith("linux"):
        idle, total = pf._cpu_times()
        assert 0 <= idle <= total


@pytest.mark.slow
def test_escalate_worker_that_decides_stops_the_first_run(at_once):
    t0 = time.perf_counter()
    s = _escalate({1: "wait", 3: "sat"}, workers=3)  # the first run alone would wait forever
    assert time.perf_counter() - t0 < BOUND_S
    assert s.status is Status.SAT and s.seed == 3 and np.array_equal(s.tiling, _tiling(3))
    assert s.stats["pid"] != os.getpid() and s.stats["time_limit"] == LONG_S  # the first wave's budget
    assert s.notes == ("portfolio: seed 3 decided it, after 2 of 64 runs started, on 2 worker processes "
                       "beside seed 1 in this process",)


def test_escalate_first_run_that_decides_terminates_the_workers(at_once):
    t0 = time.perf_counter()
    s = _escalate({1: "sleep:1"}, workers=3)  # seeds 2, 3 (and on) wait for 60 s
    assert time.perf_counter() - t0 < BOUND_S
    assert s.status is Status.SAT and s.seed == 1 and s.stats["pid"] == os.getpid()
    assert s.notes[-1] == "portfolio: seed 1 decided it in this process; 2 runs started beside it on 2 worker processes"


@pytest.mark.slow
def test_escalate_workers_run_at_the_lowest_priority(monkeypatch):
    """The first run keeps this process's priority; its workers take WORKER_NICE more."""
    monkeypatch.setattr(pf, "QUICK_S", 0.0)
    s = _escalate({1: "wait", 2: "sat"}, workers=2)
    assert s.status is Status.SAT and s.seed == 2 and s.stats["pid"] != os.getpid()
    assert s.stats["nice"] == min(19, os.nice(0) + pf.WORKER_NICE)
    first = planned_route({1: "sat"}, RunOptions(seed=1))
    assert first.stats["nice"] == os.nice(0)


@pytest.mark.slow
def test_portfolio_workers_keep_the_callers_priority():
    s = run_portfolio(functools.partial(seeded_run, planned_route, {1: "sat"}, RunOptions(seed=0)), [0, 1],
                      workers=2)
    assert s.status is Status.SAT and s.stats["pid"] != os.getpid() and s.stats["nice"] == os.nice(0)


@pytest.mark.slow
def test_escalate_undecided_keeps_the_first_runs_reason_and_summarises_the_workers(monkeypatch):
    monkeypatch.setattr(pf, "QUICK_S", 0.0)
    s = _escalate({}, workers=2, time_limit=3.0)
    assert s.status is Status.UNKNOWN and s.tiling is None and s.seed == 1
    assert s.reason == "time limit" and s.stats["pid"] == os.getpid()
    assert s.notes[-1].startswith("portfolio beside seed 1: no run decided: ")


def test_escalate_ctrl_c_stops_the_first_run_and_the_workers(at_once, ctrl_c):
    t0 = time.perf_counter()
    threading.Timer(1.0, os.kill, (os.getpid(), signal.SIGINT)).start()
    s = _escalate({}, workers=3)
    assert time.perf_counter() - t0 < BOUND_S
    assert s.status is Status.UNKNOWN and s.reason == "interrupted" and s.seed == 1
    assert s.notes == ("portfolio beside seed 1: no run decided: 2 runs stopped (the first run ended); "
                       "62 seeds not started (the first run ended)",)


def test_escalate_reraises_a_worker_error_and_stops_the_first_run(at_once):
    t0 = time.perf_counter()
    with pytest.raises(InvalidProblem, match="bad input for seed 2"):
        _escalate({1: "wait", 2: "raise"}, workers=2)
    assert time.perf_counter() - t0 < BOUND_S


def test_escalate_checks_workers():
    s = _escalate({}, time_limit=0.0)  # the first run undecided at once
    assert s.status is Status.UNKNOWN and s.seed == 1
    with pytest.raises(InvalidProblem, match="workers"):
        _escalate({1: "sat"}, workers=0)


# ------------------------------------------------- scripts without a __main__ guard (issue 9)


def _run_script(tmp_path: Path, code: str) -> subprocess.CompletedProcess:
    """Run ``code`` as a script file with this interpreter, from a directory of its own."""
    script = tmp_path / "script.py"
    script.write_text(textwrap.dedent(code))
    return subprocess.run([sys.executable, str(script)], cwd=tmp_path, capture_output=True, text=True,
                          timeout=600)


@pytest.mark.slow
def test_readme_packing_example_runs_as_a_script_without_main_guard(tmp_path):
    # The README's second Python example, verbatim: corner C = 8 takes longer than QUICK_S,
    # so a worker starts beside the first run if a core is idle (the worker used to re-run
    # the script and die). The next test starts workers whatever the load.
    r = _run_script(tmp_path, """\
        from tilesolve.families import packing
        from tilesolve.model.packing import PackingProblem

        s = packing.solve(PackingProblem("corner", 8), method="lift", seed=1)   # 64x64 de Bruijn torus
        print(s.status.value, s.tiling.shape, s.notes)
        """)
    assert r.returncode == 0, r.stderr
    assert r.stdout.startswith("sat (64, 64) (")


@pytest.mark.slow
def test_forced_portfolio_runs_as_a_script_without_main_guard(tmp_path):
    r = _run_script(tmp_path, """\
        import functools
        from tilesolve.families import packing
        from tilesolve.engine import portfolio
        from tilesolve.families.packing_search import solve_lift
        from tilesolve.model.packing import PackingProblem
        from tilesolve.model.run import RunOptions

        portfolio.QUICK_S = 0.0  # workers start beside the first run at once
        s = packing.solve(PackingProblem("corner", 6), method="lift", seed=1, workers=2)
        print(s.status.value, s.stats["portfolio_workers"])
        task = functools.partial(portfolio.seeded_run, solve_lift, PackingProblem("corner", 4), RunOptions(seed=0))
        s = portfolio.run_portfolio(task, [1, 2], workers=2)
        print(s.status.value, s.stats["portfolio_workers"], s.notes[-1])
        """)
    assert r.returncode == 0, r.stderr
    lines = r.stdout.splitlines()
    assert lines[0] == "sat 1"
    assert lines[1].startswith("sat 2 portfolio: seed ") and lines[1].endswith("on 2 worker processes")


_MAIN_TASK = """\
    from tilesolve.engine.portfolio import run_portfolio
    from tilesolve.model.solution import Solution, Status

    def task(seed):  # defined in __main__: the workers must import this script to find it
        return Solution(Status.SAT if seed == 1 else Status.UNKNOWN, seed=seed)

    {call}
    """


@pytest.mark.slow
def test_task_defined_in_a_guarded_script_runs_in_the_workers(tmp_path):
    call = 'if __name__ == "__main__":\n        print(run_portfolio(task, [0, 1], workers=2).notes[-1])'
    r = _run_script(tmp_path, _MAIN_TASK.format(call=call))
    assert r.returncode == 0, r.stderr
    assert r.stdout == "portfolio: seed 1 decided it, after 2 of 2 runs started, on 2 worker processes\n"


@pytest.mark.slow
def test_task_defined_in_an_unguarded_script_is_a_clear_error(tmp_path):
    r = _run_script(tmp_path, _MAIN_TASK.format(call="print(run_portfolio(task, [0, 1], workers=2))"))
    assert r.returncode == 1 and r.stdout == ""
    last = r.stderr.strip().splitlines()[-1]
    assert last.startswith("tilesolve.errors.InvalidProblem: ") and "script.py starts a tilesolve portfolio" in last
    assert last.endswith("put its top-level code under 'if __name__ == \"__main__\":'")


# ---------------------------------------------------------- workers die with their parent


def _children(pid: int) -> list[int]:
    """Live (non-zombie) child processes of ``pid``, from /proc."""
    out = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit() and _state(int(entry.name)) not in (None, "Z"):
            try:
                fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
            except OSError:
                continue
            if int(fields[1]) == pid:
                out.append(int(entry.name))
    return out


def _state(pid: int) -> str | None:
    """``R``, ``S``, ``Z``... from /proc/PID/stat; None when the process is gone."""
    try:
        return (Path("/proc") / str(pid) / "stat").read_text().rsplit(")", 1)[1].split()[0]
    except OSError:
        return None


def _solving(pid: int) -> bool:
    """Whether process ``pid`` has loaded PySAT's solvers (read from /proc/PID/maps)."""
    try:
        return "pysolvers" in (Path("/proc") / str(pid) / "maps").read_text()
    except OSError:
        return False


def _until(predicate) -> bool:
    t0 = time.perf_counter()
    while time.perf_counter() - t0 < BOUND_S:
        if predicate():
            return True
        time.sleep(0.1)
    return False


@pytest.mark.slow
@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGKILL])
def test_workers_die_with_the_cli_process(sig):
    # A CLI run escalates at once to 2 worker processes whose runs would last 600 s (corner
    # C = 4 by full SAT: minutes per seed); the parent is then terminated or killed.
    boot = ("import sys; import tilesolve.engine.portfolio as p; p.QUICK_S = 0.0; p.FIRST_BUDGET_S = 600.0; "
            "p.WORKER_NICE = 0; "  # niced, a loaded machine could stretch their start past the bound
            "from tilesolve.cli.main import main; sys.exit(main(sys.argv[1:]))")
    cli = subprocess.Popen([sys.executable, "-c", boot, "pack", "--kind", "corner", "--colors", "4", "--method", "sat",
                            "--seed", "1", "--workers", "3"], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    workers = []
    try:
        assert _until(lambda: len(_children(cli.pid)) == 2), "the portfolio did not start"
        workers = _children(cli.pid)
        # In their runs (the SAT solver loaded), not still starting (then they would see the
        # pipe close and leave anyway).
        assert _until(lambda: all(_solving(w) for w in workers)), "the workers did not start solving"
        cli.send_signal(sig)
        cli.wait(timeout=BOUND_S)
        assert _until(lambda: all(_state(w) in (None, "Z") for w in workers)), "workers outlived their parent"
    finally:
        for pid in [cli.pid] + workers:  # nothing of this test outlives it, even when it fails
            if _state(pid) not in (None, "Z"):
                os.kill(pid, signal.SIGKILL)
        cli.wait()
        cli.stderr.close()


@pytest.mark.parametrize("sent", [0, 1, 2])
def test_a_worker_whose_parent_vanishes_ends_without_a_word(sent):
    """Ctrl-C can end the parent while its workers start or wait: a worker then finds its pipe
    closed (before the path, before the task, or while waiting for a seed) and ends without a
    traceback on the stderr it shares with the user's terminal (once seen as an EOFError
    traceback under a census's "interrupted" line)."""
    import multiprocessing
    import pickle

    from tilesolve.engine.portfolio import _BOOT

    parent_end, child_end = multiprocessing.Pipe()
    fd = child_end.fileno()
    boot = _BOOT.format(fd=fd, ppid=os.getpid(), nice=0)
    proc = subprocess.Popen([sys.executable, "-c", boot], pass_fds=(fd,), stdin=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True)
    child_end.close()
    if sent >= 1:
        parent_end.send(sys.path)
    if sent >= 2:
        parent_end.send((None, pickle.dumps(abs)))
    parent_end.close()
    _, err = proc.communicate(timeout=120)
    assert err == "" and proc.returncode in (0, 1)
