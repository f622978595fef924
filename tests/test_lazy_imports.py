"""Start-up stays cheap: `tilesolve --version` imports neither numpy nor numba, and a family
facade loads only what it uses (issue: `import tilesolve.constructive.packing` cost 1 s
because it loaded the dappled numba kernels)."""

import subprocess
import sys

import pytest


def modules_after(code: str) -> set[str]:
    probe = code + "\nimport sys\nprint(' '.join(sorted(sys.modules)))"
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, timeout=300, check=True)
    return set(out.stdout.split())


def test_version_imports_no_numpy():
    """`--version` is answered before click, the registry or any library is loaded."""
    code = ("import contextlib, io\nfrom tilesolve.cli.main import main\n"
            "with contextlib.redirect_stdout(io.StringIO()):\n    assert main(['--version']) == 0")
    loaded = modules_after(code)
    assert "tilesolve.cli.main" in loaded
    assert not {"numpy", "numba", "pysat", "ortools", "click", "importlib.metadata", "tilesolve.family"} & loaded


@pytest.mark.parametrize("module", ["tilesolve.families.packing", "tilesolve.families.board", "tilesolve.families.stochastic", "tilesolve.family", "tilesolve.model",
                                    "tilesolve.verify", "tilesolve.constructive.packing"])
def test_facades_do_not_load_the_dappled_kernels(module):
    loaded = modules_after(f"import {module}")
    assert "tilesolve.constructive._dappled_kernels" not in loaded and "numba" not in loaded
