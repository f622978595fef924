"""A small constructive solve loads no compiler, solver or drawing library (issue 9,
"Start-up": numba, pillow and svgwrite cost more than the whole 100x100 solve)."""

import json
import subprocess
import sys

import pytest

HEAVY = {"numba", "PIL", "svgwrite", "pysat", "ortools"}


def _modules_after_cli(args: list[str]) -> set[str]:
    code = (
        "import contextlib, io, sys\nfrom tilesolve.cli.main import main\n"
        f"with contextlib.redirect_stdout(io.StringIO()):\n    rc = main({args!r})\n"
        "print(rc, ' '.join(sorted(m.split('.')[0] for m in sys.modules)))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300, check=True)
    rc, mods = out.stdout.strip().split(" ", 1)
    assert rc == "0", out.stderr
    return set(mods.split())


@pytest.mark.fast_cases(1)
@pytest.mark.parametrize("args", [
    ["dappled", "solve", "--size", "100x100", "--cond", "H0=2,V1=2"],
    ["dappled", "solve", "--size", "60x40", "--cond", "H0=3,V1=3", "--cyclic"],
    ["brick", "solve", "--board", "rect:50x50"],
])
def test_small_constructive_solve_loads_nothing_heavy(tmp_path, args):
    out = tmp_path / "out.json"
    assert not HEAVY & _modules_after_cli(args + ["-o", str(out)])
    assert json.loads(out.read_text())["status"] == "sat"


@pytest.mark.slow
def test_picture_still_loads_its_library(tmp_path):
    loaded = _modules_after_cli(["dappled", "solve", "--size", "8x8", "--cond", "H0=2,V1=2",
                                 "-o", str(tmp_path / "t.json"), "--svg", str(tmp_path / "t.svg")])
    assert "svgwrite" in loaded and not {"numba", "PIL"} & loaded
    assert (tmp_path / "t.svg").read_text().startswith("<?xml")
