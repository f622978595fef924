"""Every example that a ``--help`` prints runs as written, through the console script, in an
empty folder, with the exit code and the number its comment promises.

The rules (what a reader of the help may rely on):

* An example is a line of a help text that starts with ``tilesolve ``. Its command ends where
  its comment starts: at `` #`` (a space, then ``#``), or at a run of two or more spaces (the
  top-level help's "Start with:" lines); a ``#`` inside a word (``mask:##/#.``) is no comment.
* The examples of one help run in order in one empty folder: an earlier example may write a
  file that a later one reads (``-o t.json``, then ``tilesolve verify t.json``); nothing else is
  put there first.
* Exit 1 is expected when the comment says ``unsat``, else 0; a comment that starts with a
  number (``# prints 432``) promises the last line of stdout.

:data:`COMMANDS` lists every command whose help shows examples; a slow test walks the help tree
(``tilesolve --help`` and the command lists of every group) and checks the list is complete.
"""

from __future__ import annotations

import re
import shlex
import subprocess

import pytest
from clitools import ENV, SCRIPT

COMMANDS = [(), ("aperiodic", "census"), ("aperiodic", "check"), ("aperiodic", "tiling"), ("aperiodic", "verify"),
            ("brick", "count"), ("brick", "crosscheck"), ("brick", "solve"), ("brick", "wall"),
            ("wang", "count"), ("wang", "solve"), ("wall",), ("dappled", "count"), ("dappled", "crosscheck"),
            ("dappled", "solve"), ("pack",), ("pack", "count"), ("tiles",), ("shapes",), ("shapes", "census"),
            ("shapes", "heesch"), ("shapes", "list"), ("shapes", "tile"), ("tiling",), ("penrose",), ("reptile",),
            ("verify",), ("draw",), ("export", "dimacs"), ("demo",), ("backends",), ("crosscheck", "tiling"),
            ("crosscheck", "wall"), ("render",), ("render", "texture"), ("render", "wall"), ("gpu",), ("gpu", "info"),
            ("wall-lines",), ("studio",), ("isohedral", "draw"), ("isohedral", "list"),
            ("sample", "poisson-tiles"), ("sample", "poisson-tiles", "build"), ("sample", "poisson-tiles", "spectrum"),
            ("sample", "poisson-tiles", "window"), ("sample", "poisson-tiles", "texture"),
            ("sample", "poisson-spheres"), ("sample", "poisson-spheres", "build"), ("sample", "poisson-spheres", "window"), ("sample", "stipple"),
            ("sample", "importance-spectrum"), ("sample", "recursive-wang"), ("sample", "recursive-wang", "build"),
            ("sample", "recursive-wang", "window")]


def run(args: list[str], cwd) -> subprocess.CompletedProcess:
    return subprocess.run([SCRIPT, *args], cwd=cwd, capture_output=True, text=True, timeout=1200, env=ENV,
                          stdin=subprocess.DEVNULL)


def help_text(command: tuple[str, ...], cwd) -> str:
    proc = run([*command, "--help"], cwd)
    assert proc.returncode == 0, proc.stderr
    return proc.stdout


def examples(text: str) -> list[tuple[str, str]]:
    """``(command, comment)`` of every example in a help text (the module docstring's rules)."""
    out = []
    for line in text.splitlines():
        line = line.strip()
        if line.startswith("tilesolve "):
            command, comment = re.split(r" #|  +", line + "  ", maxsplit=1)
            out.append((command, comment.strip()))
    return out


def subcommands(text: str) -> list[str]:
    """The commands a group's help lists (its sections "... commands:" and "Tools:")."""
    found, listing = [], False
    for line in text.splitlines():
        if re.match(r"^\S.*:$", line):
            listing = line.lower().endswith("commands:") or line == "Tools:"
        elif listing and (m := re.match(r"^  (\S+)(\s{2,}|$)", line)):
            found.append(m.group(1))
    return found


def test_examples_are_split_from_their_comments():
    text = "  tilesolve demo     pictures of a few problems\n  tilesolve brick count --board 'mask:##/#.' # prints 7\n"
    assert examples(text) == [("tilesolve demo", "pictures of a few problems"),
                              ("tilesolve brick count --board 'mask:##/#.'", "prints 7")]
    assert subcommands("Usage: x\n\nCommands:\n  a  one\n  b\n\nOptions:\n  -h  help\n") == ["a", "b"]


@pytest.mark.slow
def test_every_command_with_examples_is_listed(tmp_path):
    shown, todo = set(), [()]
    while todo:
        command = todo.pop()
        text = help_text(command, tmp_path)
        if examples(text):
            shown.add(command)
        todo += [(*command, name) for name in subcommands(text)]
    assert shown == set(COMMANDS)


@pytest.mark.slow
@pytest.mark.parametrize("command", COMMANDS, ids=lambda c: " ".join(c) or "tilesolve")
def test_help_examples_run_in_an_empty_folder(tmp_path, command):
    shown = examples(help_text(command, tmp_path))
    assert shown, f"tilesolve {' '.join(command)} --help shows no example"
    assert not list(tmp_path.iterdir())
    for line, comment in shown:
        proc = run(shlex.split(line)[1:], tmp_path)
        assert proc.returncode == (1 if "unsat" in comment else 0), (line, proc.stdout[-1500:], proc.stderr[-1500:])
        assert "Traceback" not in proc.stderr, line
        promised = re.match(r"(?:prints\s+)?([\d ]+?)\s*(\(|$)", comment)
        if promised and promised.group(1).strip():
            assert proc.stdout.strip().splitlines()[-1] == promised.group(1).strip(), line
