"""README promises, run as a user would: every command of the tour through the console script
(in order, in one folder holding a copy of examples/), with the exit code and the printed
number its comment promises, and every Python example as a script of its own."""

from __future__ import annotations

import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text(encoding="utf-8")
BLOCKS = re.findall(r"```(bash|python)\n(.*?)```", README, re.S)
TOUR = [line for kind, body in BLOCKS if kind == "bash" for line in body.splitlines()
        if line.startswith("tilesolve ") and line.split()[1] != "demo"]
PYTHON = [body for kind, body in BLOCKS if kind == "python"]


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    d = tmp_path_factory.mktemp("readme")
    shutil.copytree(ROOT / "examples", d / "examples")
    return d


def test_the_tour_is_long_enough():
    assert len(TOUR) >= 20 and len(PYTHON) >= 3


@pytest.mark.parametrize("line", TOUR)
def test_tour_command(folder, line):
    command, _, comment = line.partition("#")
    proc = subprocess.run([shutil.which("tilesolve"), *shlex.split(command)[1:]], cwd=folder, capture_output=True,
                          text=True, timeout=900)
    expected = 1 if "unsat" in comment else 0
    assert proc.returncode == expected, (line, proc.stdout[-2000:], proc.stderr[-2000:])
    assert "Traceback" not in proc.stderr
    promised = re.match(r"\s*([\d ,]+?)\s*(\(|$)", comment)
    if promised and promised.group(1).strip():
        assert proc.stdout.strip().splitlines()[-1].replace(",", "") == promised.group(1).strip().replace(",", "")


@pytest.mark.parametrize("code", PYTHON)
def test_python_example(folder, code):
    (folder / "example.py").write_text(code)
    proc = subprocess.run([sys.executable, "example.py"], cwd=folder, capture_output=True, text=True, timeout=900)
    assert proc.returncode == 0, (code, proc.stderr[-3000:])
