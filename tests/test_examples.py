"""Every script in examples/ runs from a clean folder and writes only where it is told."""

import subprocess
import sys
from pathlib import Path

import pytest

EXAMPLES = sorted((Path(__file__).resolve().parents[1] / "examples").glob("*.py"))
#: Examples that take more than a few seconds (the 8-colour corner packing by lifting): slow.
SLOW = {"corner_packings.py"}


@pytest.mark.parametrize("script", [pytest.param(p, marks=pytest.mark.slow) if p.name in SLOW else p for p in EXAMPLES],
                         ids=lambda p: p.name)
def test_example_runs_and_writes_into_the_given_folder(tmp_path, script):
    out = tmp_path / "out"
    before = sorted(p.name for p in script.parent.iterdir())
    proc = subprocess.run([sys.executable, str(script), str(out)], cwd=tmp_path, capture_output=True, text=True,
                          timeout=900)
    assert proc.returncode == 0, proc.stderr[-3000:]
    assert any(out.iterdir())
    assert sorted(p.name for p in script.parent.iterdir()) == before  # nothing written into the source tree
