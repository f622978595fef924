"""Every example printed by a command's --help runs as shown (through the console script),
with the exit code and the number its comment promises. Input files the examples name are
made first (partial.txt, target.txt, shape.png, shape.txt, tiles.json, c4.json)."""

from __future__ import annotations

import re
import shlex
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
from clitools import SCRIPT

ROOT = Path(__file__).resolve().parents[2]
COMMANDS = [("dappled", "solve"), ("dappled", "count"), ("dappled", "crosscheck"), ("brick", "solve"),
            ("brick", "wall"), ("brick", "count"), ("brick", "crosscheck"), ("wang", "solve"), ("wall",), ("pack",),
            ("pack", "count"), ("tiles",), ("verify",), ("draw",), ("export", "dimacs"), ("demo",), ("backends",),
            ("render",), ("render", "texture"), ("render", "wall"), ("gpu",), ("gpu", "info"),
            ("tiling",), ("aperiodic", "check"), ("aperiodic", "verify"), ("aperiodic", "tiling"),
            ("wall-lines",), ("studio",),
            ("wang", "count"), ("crosscheck", "wall"), ("crosscheck", "tiling")]


def run(args, cwd):
    return subprocess.run([SCRIPT, *args], cwd=cwd, capture_output=True, text=True, timeout=1200)


def examples(command) -> list[str]:
    text = run([*command, "--help"], cwd=ROOT).stdout
    return [line.strip() for line in text.splitlines() if line.strip().startswith("tilesolve ")]


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    d = tmp_path_factory.mktemp("help")
    (d / "partial.txt").write_text("\n".join(["0???????", "????????", "??1?????"] + ["????????"] * 5) + "\n")
    (d / "target.txt").write_text("\n".join("".join(str((r + c) % 2) for c in range(12)) for r in range(8)) + "\n")
    shutil.copy(ROOT / "examples" / "shape.txt", d / "shape.txt")
    shutil.copy(ROOT / "examples" / "tiles.json", d / "tiles.json")
    from PIL import Image

    alpha = np.zeros((10, 16), dtype=np.uint8)
    alpha[1:9, 1:15] = 255
    alpha[4:6, 5:9] = 0  # a hole
    rgba = np.dstack([np.zeros((10, 16, 3), dtype=np.uint8), alpha])
    Image.fromarray(rgba, "RGBA").save(d / "shape.png")
    assert run(["pack", "--kind", "corner", "--colors", "4", "-o", "c4.json"], cwd=d).returncode == 0
    return d


@pytest.mark.slow
@pytest.mark.parametrize("command", COMMANDS, ids=" ".join)
def test_help_examples_run(folder, command):
    shown = examples(command)
    assert shown, f"tilesolve {' '.join(command)} --help shows no example"
    for line in shown:
        cmd, _, comment = line.partition("#")
        proc = run(shlex.split(cmd)[1:], cwd=folder)
        assert proc.returncode == (1 if "unsat" in comment else 0), (line, proc.stdout[-1500:], proc.stderr[-1500:])
        assert "Traceback" not in proc.stderr
        promised = re.match(r"\s*(?:prints\s+)?([\d ]+?)\s*(\(|$)", comment)
        if promised and promised.group(1).strip():
            assert proc.stdout.strip().splitlines()[-1] == promised.group(1).strip(), line
