"""Helpers for tests that run the real ``tilesolve`` console script in a subprocess."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest


def _script() -> str:
    here = Path(sys.executable).parent / ("tilesolve.exe" if os.name == "nt" else "tilesolve")
    if here.exists():
        return str(here)
    found = shutil.which("tilesolve")
    if not found:
        pytest.fail("the `tilesolve` console script is not installed (pip install .)")
    return found


SCRIPT = _script()
ENV = dict(os.environ, COLUMNS="100")


def run(*args: str, cwd: Path, timeout: float = 300, stdin=subprocess.DEVNULL) -> subprocess.CompletedProcess:
    """Run ``tilesolve ARGS`` in ``cwd``; text output captured."""
    return subprocess.run([SCRIPT, *args], cwd=cwd, capture_output=True, text=True, timeout=timeout, env=ENV,
                          stdin=stdin)


def one_line_error(proc: subprocess.CompletedProcess, code: int = 2) -> str:
    """Assert the run failed with ``code``, no traceback and exactly one ``tilesolve: error:`` line."""
    assert proc.returncode == code, (proc.returncode, proc.stdout[-2000:], proc.stderr[-2000:])
    assert "Traceback" not in proc.stderr, proc.stderr
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("tilesolve: error: "), proc.stderr
    return lines[0]


def snapshot(folder: Path) -> dict[str, bytes]:
    """Every file under ``folder`` (hidden ones included) with its bytes."""
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}
