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
from clitools import SCRIPT

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


@pytest.mark.slow
@pytest.mark.parametrize("line", TOUR)
def test_tour_command(folder, line):
    command, _, comment = line.partition("#")
    proc = subprocess.run([SCRIPT, *shlex.split(command)[1:]], cwd=folder, capture_output=True,
                          text=True, timeout=900)
    expected = 1 if "unsat" in comment else 0
    assert proc.returncode == expected, (line, proc.stdout[-2000:], proc.stderr[-2000:])
    assert "Traceback" not in proc.stderr
    promised = re.match(r"\s*([\d ,]+?)\s*(\(|$)", comment)
    if promised and promised.group(1).strip():
        assert proc.stdout.strip().splitlines()[-1].replace(",", "") == promised.group(1).strip().replace(",", "")


@pytest.mark.slow
@pytest.mark.parametrize("code", PYTHON)
def test_python_example(folder, code):
    (folder / "example.py").write_text(code)
    proc = subprocess.run([sys.executable, "example.py"], cwd=folder, capture_output=True, text=True, timeout=900)
    assert proc.returncode == 0, (code, proc.stderr[-3000:])


def test_the_test_command_is_what_ci_runs():
    """The README's test command is scripts/test.sh (installing, then pytest on every core), and
    .ci/run runs it."""
    commands = [line.split("#")[0].strip() for kind, body in BLOCKS if kind == "bash" for line in body.splitlines()
                if line.startswith("scripts/test.sh")]
    assert commands[0] == "scripts/test.sh"
    script = (ROOT / "scripts" / "test.sh").read_text(encoding="utf-8")
    assert 'pip install -q ".[test]"' in script and "python -m pytest -q -n auto" in script
    assert (ROOT / "scripts" / "test.sh").stat().st_mode & 0o111
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    assert any(line.split()[-1:] == ["scripts/test.sh"] for line in ci.splitlines() if not line.startswith("#"))


def test_the_test_command_names_missing_packages_without_root(tmp_path):
    """Without root, sudo or apt-get, scripts/test.sh stops in one line naming what is missing
    (here chromium), before it makes a virtual environment."""
    bin_ = tmp_path / "bin"
    bin_.mkdir()
    for tool in ("dirname", "grep", "ls", "sort", "tr"):
        (bin_ / tool).symlink_to(shutil.which(tool))
    (bin_ / "python3.11").symlink_to(sys.executable)
    (bin_ / "ldconfig").symlink_to(shutil.which("ldconfig") or "/sbin/ldconfig")
    (bin_ / "id").write_text("#!/bin/sh\necho 1000\n")
    (bin_ / "id").chmod(0o755)
    proc = subprocess.run(["/bin/bash", str(ROOT / "scripts" / "test.sh")], capture_output=True, text=True,
                          env={"PATH": str(bin_), "VENV": str(tmp_path / "venv")}, timeout=60)
    assert proc.returncode == 1 and proc.stdout == "", proc
    [line] = proc.stderr.splitlines()
    assert line.startswith("scripts/test.sh: missing system packages: ") and "chromium" in line
    assert not (tmp_path / "venv").exists()
