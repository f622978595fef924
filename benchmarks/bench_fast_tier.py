"""The fast tier, ``python -m pytest -m "not slow"``: its wall time, and that it covers every module.

Two runs of the fast tier from the repository root (issue 18, "Tests a developer runs on every
change"):

1. timed: ``python -m pytest -q -m "not slow"`` in one process (no pytest-xdist workers); its wall
   time and test count are printed. Goal: under 3 minutes on a 2-core machine.
2. under coverage.py, with ``[run] patch = subprocess`` so that the console-script runs of the CLI
   tests, and pytest-xdist's workers (this run uses every core when pytest-xdist is installed),
   are measured too. A module of ``tilesolve`` is covered when a line inside one of its
   functions ran (importing it, as the doctest collection does for every module, is not enough).
   A module without functions of its own is covered when any line ran; numba kernels
   (``@njit``) are left out of the count, as coverage cannot see inside compiled code, and so is
   the one module that runs only in the studio's forkserver (``FORKSERVER_ONLY``). The script
   lists every module that is not covered and exits 1.

Both runs take a few minutes each; the coverage run is the slower one.

Usage::

    python benchmarks/bench_fast_tier.py                 # both runs
    python benchmarks/bench_fast_tier.py --no-coverage   # the timed run only
    python benchmarks/bench_fast_tier.py --no-timing     # the coverage run only
    python benchmarks/bench_fast_tier.py tests/io        # the fast tier of some tests only
"""

from __future__ import annotations

import argparse
import ast
import importlib.util
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "tilesolve"
FAST = ["-m", "pytest", "-q", "-p", "no:cacheprovider", "-m", "not slow"]
#: Modules whose functions run only in a process that coverage.py does not follow (the studio's
#: multiprocessing forkserver imports tilesolve.studio.warm): covered once imported.
FORKSERVER_ONLY = {"tilesolve/studio/warm.py"}


def _pytest(prefix: list[str], paths: list[str], options: list[str] = ()) -> tuple[int, float, str]:
    """Run the fast tier of ``paths`` (all when empty) under ``python *prefix``, with pytest's
    ``options``: exit code, wall seconds, pytest's closing line."""
    start = time.perf_counter()
    proc = subprocess.run([sys.executable, *prefix, *FAST, *options, *paths], cwd=ROOT, capture_output=True, text=True)
    seconds = time.perf_counter() - start
    lines = [line for line in proc.stdout.splitlines() if line.strip()]
    closing = lines[-1].strip("= ") if lines else "(no output)"
    if proc.returncode != 0:
        sys.stdout.write(proc.stdout[-6000:] + proc.stderr[-3000:])
    return proc.returncode, seconds, closing


def _function_lines(tree: ast.Module) -> set[int]:
    """Lines inside the bodies of the module's functions and methods, numba kernels left out."""
    lines: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            if any("jit" in ast.unparse(d) for d in node.decorator_list):
                continue
            lines.update(range(node.body[0].lineno, node.end_lineno + 1))
    return lines


def uncovered(executed: dict[Path, set[int]], statements) -> tuple[int, list[str]]:
    """How many modules of the package have statements, and those ``executed`` does not cover.

    ``executed`` maps a file to the lines that ran; ``statements(path)`` gives a file's statements."""
    modules, out = 0, []
    for path in sorted(PACKAGE.rglob("*.py")):
        if not statements(path):
            continue  # nothing to run (an empty package marker, a docstring alone)
        modules += 1
        ran = executed.get(path, set())
        inside = set() if str(path.relative_to(ROOT)) in FORKSERVER_ONLY else _function_lines(
            ast.parse(path.read_text(encoding="utf-8")))
        if not (ran & inside if inside else ran):
            out.append(str(path.relative_to(ROOT)))
    return modules, out


def coverage_run(paths: list[str]) -> tuple[int, float, str, int, list[str]]:
    """The fast tier under coverage.py: exit code, wall seconds, closing line, module count and
    the modules it does not cover."""
    from coverage import Coverage

    with tempfile.TemporaryDirectory() as tmp:
        rc = Path(tmp) / "coveragerc"
        # The CLI tests run the installed console script: map an installed copy onto the tree.
        rc.write_text(f"[run]\nsource_pkgs = tilesolve\npatch = subprocess\nparallel = true\n"
                      f"data_file = {tmp}/.coverage\n\n[paths]\nsource =\n    {PACKAGE}\n"
                      f"    */site-packages/tilesolve\n")
        # On every core when pytest-xdist is there: its workers are subprocesses, measured too.
        workers = ["-n", "auto", "--dist", "loadscope"] if importlib.util.find_spec("xdist") else []
        code, seconds, closing = _pytest(["-m", "coverage", "run", f"--rcfile={rc}"], paths, workers)
        cov = Coverage(data_file=f"{tmp}/.coverage", config_file=str(rc))
        cov.combine()
        data = cov.get_data()
        executed = {Path(f): set(data.lines(f) or ()) for f in data.measured_files()}
        modules, missing = uncovered(executed, lambda path: cov.analysis2(str(path))[1])
    return code, seconds, closing, modules, missing


def _count(closing: str) -> str:
    """'1234 passed, 5 skipped' out of pytest's closing line."""
    return re.sub(r"\s+in\s+[\d.]+s.*$", "", closing)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--no-timing", action="store_true", help="skip the timed run")
    ap.add_argument("--no-coverage", action="store_true", help="skip the coverage run")
    ap.add_argument("paths", nargs="*", help="test files or folders (default: the configured testpaths)")
    args = ap.parse_args()
    status = 0
    if not args.no_timing:
        code, seconds, closing = _pytest([], args.paths)
        print(f"fast tier: {seconds:.0f} s wall ({seconds / 60:.1f} min), one process: {_count(closing)}")
        status = status or code
    if not args.no_coverage:
        code, seconds, closing, modules, missing = coverage_run(args.paths)
        print(f"fast tier under coverage: {seconds:.0f} s wall: {_count(closing)}")
        status = status or code
        if missing:
            print(f"{len(missing)} of {modules} modules not covered by the fast tier:")
            print("\n".join(f"  {m}" for m in missing))
            status = status or 1
        else:
            print(f"every one of the {modules} modules of tilesolve is covered by the fast tier")
    return status


if __name__ == "__main__":
    sys.exit(main())
