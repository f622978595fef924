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


def cut(doc: dict) -> str:
    """A forgery for :func:`verify_forgery`: the first half of the document's JSON text."""
    import json

    text = json.dumps(doc)
    return text[:len(text) // 2]


def verify_forgery(folder: Path, doc: dict, forge, code: int, words: str) -> None:
    """Write a copy of ``doc`` (a parsed file) changed by ``forge`` (which edits it, or returns the
    text to write instead) to ``folder/forged.json``, run ``tilesolve verify`` on it and assert the
    verdict: ``code`` 1 with ``words`` in its report, or 2 with ``words`` in its one-line error."""
    import json

    copy = json.loads(json.dumps(doc))
    text = forge(copy)
    (folder / "forged.json").write_text(text if isinstance(text, str) else json.dumps(copy))
    r = run("verify", "forged.json", cwd=folder)
    if code == 2:
        assert words in one_line_error(r)
    else:
        assert r.returncode == code and words in r.stdout, r.stdout + r.stderr
