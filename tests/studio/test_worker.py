"""The studio's solve worker (tilesolve.studio.worker): it warms every family through the
family's own hook, and shows a solution in a format its family draws."""

from __future__ import annotations

import ast
import importlib.util
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

from tilesolve import family
from tilesolve.errors import InvalidProblem
from tilesolve.model.solution import Solution, Status
from tilesolve.studio import worker

STUDIO = Path(worker.__file__).resolve().parent


@dataclass(frozen=True)
class Strip:
    """A toy problem: a strip of ``n`` cells, any tiling valid."""

    n: int


def _draw_svg(problem, sol, path, fmt, **options):
    Path(path).write_text(f'<svg xmlns="http://www.w3.org/2000/svg"><title>{problem.n} cells</title></svg>')


@pytest.fixture
def svg_only():
    """A throw-away family whose drawing is SVG only; it records its warm hook's calls."""
    calls = []
    fam = family.register(family.Family(
        name="toy-svg-only", title="a strip", problem_type=Strip,
        routes={"zeros": lambda p, run: Solution(Status.SAT, np.zeros(p.n, np.int8), "zeros", None, run.seed)},
        auto=lambda p: "zeros", verify=lambda p, t: [], draw=_draw_svg, pictures=("svg",),
        warm=lambda: calls.append("warm"),
    ))
    yield fam, calls
    family.unregister(fam.name)


def test_an_svg_only_family_is_shown_as_svg_at_any_size(svg_only):
    big = Strip(worker.SVG_MAX_CELLS * 4)  # past the size the studio draws as PNG
    sol = family.solve(big, seed=1)
    pic = worker.picture(big, sol)
    assert pic == {"format": "svg", "data": f'<svg xmlns="http://www.w3.org/2000/svg"><title>{big.n} cells</title></svg>'}
    with pytest.raises(InvalidProblem, match="toy-svg-only solutions are drawn as svg only, not png"):
        worker.picture(big, sol, "png")


def test_a_family_drawing_both_formats_is_shown_as_png_when_large():
    from tilesolve.model.dappled import DappledProblem

    p = DappledProblem.from_strings("60x50", ["H0=2", "V1=2"])
    assert p.rows * p.cols > worker.SVG_MAX_CELLS
    pic = worker.picture(p, family.solve(p, seed=1))
    assert pic["format"] == "png"


def test_warming_runs_every_family_hook(svg_only):
    _, calls = svg_only
    worker.warm_families()
    assert calls == ["warm"]


def test_the_built_in_hooks_compile_the_kernels():
    code = ("from tilesolve.constructive import _brick_kernels, _dappled_kernels\n"
            "from tilesolve.studio.worker import warm_families\n"
            "assert not _brick_kernels.KERNELS.loaded and not _dappled_kernels.KERNELS.loaded\n"
            "warm_families()\n"
            "print(_brick_kernels.KERNELS.loaded, _dappled_kernels.KERNELS.loaded)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["True", "True"]


def _is_module(name: str) -> bool:
    try:
        return importlib.util.find_spec(name) is not None
    except ModuleNotFoundError:
        return False


def test_the_studio_imports_no_private_module_of_a_lower_layer():
    """Families warm themselves (``Family.warm``): the studio imports no private module (such
    as a family's kernels) from the layers below it."""
    private = []
    for path in sorted(STUDIO.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            names = []
            if isinstance(node, ast.ImportFrom) and node.module:
                names = [node.module] + [f"{node.module}.{a.name}" for a in node.names]
            elif isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            private += [f"{path.name}: {n}" for n in names
                        if n.startswith("tilesolve.") and not n.startswith("tilesolve.studio.")
                        and any(part.startswith("_") for part in n.split(".")) and _is_module(n)]
    assert not private, private


def test_a_solve_whose_process_cannot_start_ends_as_an_error(monkeypatch):
    """When no worker process can be started (fork refused, out of processes), the job does
    not stay 'running' with no process: it ends as an error, and cancel and shutdown pass it by
    (they once failed on the missing process)."""
    from tilesolve.studio import jobs

    pool = jobs.Jobs()

    def refused():
        raise OSError("Resource temporarily unavailable")

    monkeypatch.setattr(pool, "_take", refused)
    with pytest.raises(OSError):
        pool.start("dappled", {}, "auto", None)
    (job,) = pool._jobs.values()
    assert (job.state, job.error) == ("error", "the solver process could not be started") and job.done.is_set()
    assert pool.running() == 0 and pool.cancel(job.id) is job
    pool.close()
