"""Bad-input sweep: every command and option of the real console script, fed malformed,
absurd and hostile values.

Each run must end with exit 2 (DESIGN.md, "Errors"), exactly one ``tilesolve: error: ...``
line on stderr and no traceback, and leave the folder exactly as it was: no new file, no
temporary, and the pre-existing ``keep.json`` (named as an output in many cases) byte-identical.
The commands come from ``tilesolve --help``; a test checks that none is missing here. Every
command of a registered family is also swept from its own options (found through the registry),
so a new family's commands are covered without an edit here.

Every case fails on input checks, before any search, so the sweep stays cheap.
"""

from __future__ import annotations

import importlib
import os
import re
import shlex
import stat

import click
import numpy as np
import pytest
from clitools import one_line_error, run, snapshot

from tilesolve import family
from tilesolve.io.dappled_json import write_solution
from tilesolve.model.dappled import DappledProblem
from tilesolve.model.solution import Solution, Status

BIG = "1" + "0" * 30  # 10^30

#: command -> the cases: (name, arguments). Files named here are made by the ``folder`` fixture.
CASES: dict[str, list[tuple[str, str]]] = {
    "dappled solve": [
        ("size not a number", "--size abcxdef -o keep.json"),
        ("size zero", "--size 0x0"),
        ("size 10^30", f"--size {BIG}x{BIG} -o keep.json"),
        ("tiles not a number", "--size 4x4 --tiles abc"),
        ("tiles 10^30", f"--size 4x4 --tiles {BIG}"),
        ("condition garbage", "--size 4x4 --cond H0=abc"),
        ("condition limit 10^30", f"--size 4x4 --cond H0={BIG} -o keep.json"),
        ("condition tile 10^30", f"--size 4x4 --cond H{BIG}=2"),
        ("count 10^30", f"--size 4x4 --count 1={BIG}"),
        ("method unknown", "--size 4x4 --method magic -o keep.json"),
        ("seed 10^30", f"--size 4x4 --seed {BIG}"),
        ("time limit zero", "--size 4x4 --time-limit 0"),
        ("time limit negative", "--size 4x4 --time-limit -1"),
        ("time limit nan", "--size 4x4 --time-limit nan -o keep.json"),
        ("time limit inf", "--size 4x4 --time-limit inf"),
        ("time limit 1e400", "--size 4x4 --time-limit 1e400"),
        ("problem missing", "--problem missing.json -o keep.json"),
        ("problem binary", "--problem garbage.bin"),
        ("problem wrong JSON", "--problem wrong.json"),
        ("problem is a directory", "--problem adir"),
        ("problem unreadable", "--problem locked.json"),
        ("fix binary", "--size 4x4 --fix garbage.bin"),
        ("initial is a directory", "--size 2x2 --initial adir"),
        ("output is a directory", "--size 4x4 -o adir"),
        ("output in a missing directory", "--size 4x4 -o nodir/x.json"),
        ("output where a file is the directory", "--size 4x4 -o garbage.bin/x.json"),
        ("output twice", "--size 4x4 -o keep.json --svg ./keep.json"),
        ("output name too long", f"--size 4x4 -o {'x' * 300}.json"),
        ("stdout twice", "--size 4x4 -o - --svg -"),
        ("output under /proc", "--size 4x4 -o keep.json --png /proc/x.png"),
        ("repeat zero", "--size 4x4 --svg a.svg --repeat 0"),
        ("repeat without a picture", "--size 4x4 --repeat 2 -o keep.json"),
    ],
    "dappled count": [
        ("size zero", "--size 0x0"),
        ("method unknown", "--size 3x3 --method magic"),
        ("time limit nan", "--size 3x3 --time-limit nan"),
    ],
    "dappled crosscheck": [
        ("trials zero", "--size 3x3 --trials 0"),
        ("trials text", "--size 3x3 --trials many"),
    ],
    "pack": [
        ("colors 1000", "--kind corner --colors 1000 -o keep.json"),
        ("colors 10^30", f"--kind wang --colors {BIG}"),
        ("colors text", "--kind corner --colors abc"),
        ("kind unknown", "--kind hex --colors 3"),
        ("no kind", "--colors 3"),
        ("workers zero", "--kind corner --colors 3 --workers 0"),
        ("workers 10^30", f"--kind corner --colors 3 --workers {BIG}"),
        ("fix garbage", "--kind corner --colors 3 --fix a,b,c"),
        ("fix 10^30", f"--kind corner --colors 3 --fix {BIG},0,0"),
        ("dimacs with -o", "--kind corner --colors 3 --dimacs x.cnf -o keep.json"),
        ("dimacs with --svg --indices", "--kind corner --colors 3 --dimacs x.cnf --svg x.svg --indices"),
        ("indices without svg", "--kind corner --colors 3 --indices"),
        ("method unknown", "--kind corner --colors 3 --method magic"),
        ("svg under /proc", "--kind corner --colors 4 -o keep.json --svg /proc/x.svg"),
        ("svg of 83,521 tiles", "--kind corner --colors 17 --method euler -o keep.json --svg x.svg"),
        ("output is a directory", "--kind corner --colors 3 -o adir"),
        ("time limit negative", "--kind corner --colors 3 --time-limit -1"),
    ],
    "pack count": [
        ("kind unknown", "--kind hex --colors 2"),
        ("colors text", "--kind wang --colors two"),
        ("time limit inf", "--kind wang --colors 2 --time-limit inf"),
    ],
    "brick solve": [
        ("board zero", "--board rect:0x0"),
        ("board 10^30", f"--board rect:{BIG}x{BIG} -o keep.json"),
        ("board kind unknown", "--board hex:3x3"),
        ("mask binary", "--board mask:garbage.bin"),
        ("mask missing", "--board mask:missing.txt"),
        ("colors 1000", "--board rect:4x4 --colors 1000 -o keep.json"),
        ("colors 10^30", f"--board rect:4x4 --colors {BIG}"),
        ("colors two", "--board rect:4x4 --colors 2"),
        ("boundary binary", "--board rect:2x2 --boundary garbage.bin"),
        ("boundary wrong JSON", "--board rect:2x2 --boundary wrong.json"),
        ("max-h 10^30", f"--board rect:4x4 --max-h {BIG}"),
        ("method unknown", "--board rect:4x4 --method magic"),
        ("output is a directory", "--board rect:4x4 -o adir"),
        ("svg and output the same", "--board rect:4x4 -o keep.json --svg keep.json"),
    ],
    "brick wall": [
        ("size garbage", "--size abc --max-line 2"),
        ("size 10^30", f"--size {BIG}x2 --max-line 2 -o keep.json"),
        ("max-line zero", "--size 4x4 --max-line 0"),
        ("max-line 10^30", f"--size 4x4 --max-line {BIG}"),
        ("colors 10^30", f"--size 4x4 --max-line 2 --colors {BIG}"),
    ],
    "wall": [
        ("region garbage", "--region abc --max-line 2"),
        ("region 10^30 wide", f"--region 0,0,{BIG}x2 --max-line 2 -o keep.json"),
        ("region off the plane", f"--region {BIG},0,4x4 --max-line 2 -o keep.json"),
        ("max-line zero", "--region 0,0,4x4 --max-line 0"),
        ("colors two", "--region 0,0,4x4 --max-line 2 --colors 2"),
        ("method unknown", "--region 0,0,4x4 --max-line 2 --method magic"),
        ("held region too large", "--region 0,0,20000x20000 --max-line 2 -o keep.json"),
        ("map without png", "--region 0,0,4x4 --max-line 2 --map uv -o keep.json"),
        ("npd period too small", "--region 0,0,8x8 --max-line 2 --method npd --period 2x8 --png keep.png"),
    ],
    "crosscheck wall": [
        ("trials zero", "--trials 0"),
        ("colors two", "--colors 2"),
        ("max-line zero", "--max-line 0"),
    ],
    "crosscheck tiling": [
        ("kind unknown", "--kind hex"),
        ("max-size zero", "--max-size 0"),
    ],
    "wall-lines": [
        ("max-line zero", "--max-line 0 -o keep.json"),
        ("max-line 10^30", f"--max-line {BIG} -o keep.json"),
        ("size garbage", "--size abc"),
        ("size 10^30", f"--size {BIG}x2 -o keep.json"),
        ("npd period too small", "--method npd --size 2x8 --max-line 2 -o keep.json"),
        ("colors two", "--colors 2 -o keep.json"),
        ("samples zero", "--samples 0 --max-line 2"),
        ("method unknown", "--method magic"),
    ],
    "aperiodic check": [
        ("no tile set", "--max-square 3"),
        ("tiles and builtin", "tiles.json --builtin jeandel-rao --max-square 3"),
        ("builtin unknown", "--builtin nope --max-square 3 -o keep.json"),
        ("nothing to check", "--builtin jeandel-rao -o keep.json"),
        ("max square 10^30", f"--builtin jeandel-rao --max-square {BIG} -o keep.json"),
        ("max period absurd", "--builtin jeandel-rao --max-period 5000 --shears -o keep.json"),
        ("tiles wrong JSON", "wrong.json --max-square 3 -o keep.json"),
        ("tiles binary", "garbage.bin --max-square 3"),
        ("workers and cluster", "--builtin jeandel-rao --max-square 3 --workers 2 --cluster tcp://127.0.0.1:1"),
        ("output is a directory", "--builtin jeandel-rao --max-square 3 -o adir"),
    ],
    "aperiodic verify": [
        ("report missing", "missing.json"),
        ("report binary", "garbage.bin"),
        ("not a report", "solution.json"),
        ("proof dir missing", "solution.json --proof-dir nodir"),
    ],
    "tiling": [
        ("region garbage", "--kind wang --method direct --colors 2 --region abc"),
        ("region 10^30 wide", f"--kind wang --method direct --colors 2 --region 0,0,{BIG}x2 -o keep.json"),
        ("region off the plane", f"--kind corner --method direct --colors 2 --region {BIG},0,4x4 -o keep.json"),
        ("colors zero", "--kind wang --method direct --colors 0 --region 0,0,4x4"),
        ("kind unknown", "--kind hex --method direct --colors 2 --region 0,0,4x4"),
        ("method not applicable", "--kind corner --method direct --set compact --colors 2 --region 0,0,4x4 -o keep.json"),
    ],
    "brick count": [
        ("colors 1000", "--board rect:2x2 --colors 1000"),
        ("board garbage", "--board rect:axb"),
    ],
    "brick crosscheck": [
        ("trials zero", "--board rect:2x2 --trials 0"),
    ],
    "wang solve": [
        ("tiles binary", "--tiles garbage.bin --board rect:2x2"),
        ("tiles wrong JSON", "--tiles wrong.json --board rect:2x2 -o keep.json"),
        ("tiles missing", "--tiles missing.json --board rect:2x2"),
        ("tiles is a directory", "--tiles adir --board rect:2x2"),
        ("board zero", "--tiles tiles.json --board rect:0x3"),
        ("builtin unknown", "--builtin nope --board rect:2x2"),
        ("tiles and builtin", "--tiles tiles.json --builtin jeandel-rao --board rect:2x2"),
    ],
    "wang count": [
        ("no tile set", "--board rect:2x2"),
        ("builtin unknown", "--builtin nope --board rect:2x2"),
        ("format unknown", "--tiles tiles.json --format svg --board rect:2x2"),
        ("tiles wrong arity", "--tiles tiles.json --format nswe --board rect:2x2"),
        ("board zero", "--builtin jeandel-rao --board rect:0x3"),
        ("transfer on a mobius strip", "--builtin jeandel-rao --board mobius:3x3 --method transfer"),
        ("rows too long", "--builtin labbe-u19 --board rect:100x100"),
    ],
    "tiles": [
        ("builtin unknown", "--builtin nope"),
        ("builtin with kind", "--builtin jeandel-rao --kind wang"),
        ("kind unknown", "--kind hex --colors 2"),
        ("colors 1000", "--kind wang --colors 1000"),
        ("colors 10^30", f"--kind corner --colors {BIG}"),
        ("colors one", "--kind wang --colors 1"),
        ("set unknown", "--kind wang --colors 2 --set weird"),
        ("svg is a directory", "--kind wang --colors 2 --svg adir"),
        ("proof dir is a file", "--kind wang --colors 2 --proof-dir garbage.bin"),
    ],
    "verify": [
        ("missing", "missing.json"),
        ("binary", "garbage.bin"),
        ("wrong JSON", "wrong.json"),
        ("wrong format name", "teapot.json"),
        ("directory", "adir"),
        ("no file", ""),
        ("proof dir missing", "solution.json --proof-dir nodir"),
    ],
    "draw": [
        ("missing", "missing.json -o x.svg"),
        ("binary", "garbage.bin -o x.svg"),
        ("unknown picture format", "solution.json -o x.bmp"),
        ("output in a missing directory", "solution.json -o nodir/x.svg"),
        ("output over the input", "solution.json -o solution.json"),
        ("repeat 10^30", f"solution.json -o x.svg --repeat {BIG}"),
    ],
    "export dimacs": [
        ("size zero", "--size 0x0 -o x.cnf"),
        ("output is a directory", "--size 3x3 -o adir"),
        ("output in a missing directory", "--size 3x3 -o nodir/x.cnf"),
        ("file binary", "garbage.bin -o x.cnf"),
    ],
    "demo": [
        ("out is a file", "--out garbage.bin"),
        ("time limit zero", "--time-limit 0"),
        ("family unknown", "--family nope"),
    ],
    "backends": [
        ("extra argument", "everything"),
    ],
    "studio": [
        ("port not a number", "--port abc"),
        ("port too large", "--port 70000"),
        ("exit-after not positive", "--exit-after 0"),
        ("extra argument", "everything"),
    ],
    "render texture": [
        ("example missing", "--example missing.png --size 64x64 -o out.png"),
        ("example not an image", "--example garbage.bin --size 64x64 -o out.png"),
        ("example is a directory", "--example adir --size 64x64 -o out.png"),
        ("example unreadable", "--example locked.json --size 64x64 -o out.png"),
        ("size garbage", "--example garbage.bin --size axb -o out.png"),
        ("size 10^30", f"--example garbage.bin --size {BIG}x{BIG} -o out.png"),
        ("colors 9", "--example garbage.bin --colors 9 --size 8x8 -o out.png"),
        ("tile odd", "--example garbage.bin --tile 9 --size 8x8 -o out.png"),
        ("atlas too large", "--example garbage.bin --colors 8 --tile 512 --size 8x8 -o out.png"),
        ("origin garbage", "--example garbage.bin --size 8x8 --origin a,b -o out.png"),
        ("origin 10^30", f"--example garbage.bin --size 8x8 --origin {BIG},0 -o out.png"),
        ("nothing to do", "--example garbage.bin --size 8x8"),
        ("output is a directory", "--example garbage.bin --size 8x8 -o adir"),
    ],
    "render wall": [
        ("size zero", "--size 0x0 -o out.png"),
        ("size 10^30", f"--size {BIG}x{BIG} -o out.png"),
        ("max line zero", "--size 8x8 --max-line 0 -o out.png"),
        ("samples 3", "--size 8x8 --samples 3 -o out.png"),
        ("samples 64", "--size 8x8 --samples 64 -o out.png"),
        ("colors 2", "--size 8x8 --colors 2 -o out.png"),
        ("origin 10^30", f"--size 8x8 --origin 0,-{BIG} -o out.png"),
        ("nothing to do", "--size 8x8"),
        ("output in a missing directory", "--size 8x8 -o nodir/w.png"),
    ],
    "gpu info": [
        ("extra argument", "everything"),
    ],
    "": [
        ("unknown command", "frobnicate"),
        ("unknown option", "--frobnicate"),
        ("unknown subcommand", "dappled frobnicate"),
    ],
}


@pytest.fixture
def folder(tmp_path):
    """A folder of hostile inputs, and ``keep.json``, an earlier result that must survive."""
    (tmp_path / "garbage.bin").write_bytes(bytes(range(256)) * 4)
    (tmp_path / "wrong.json").write_text('{"tiles": [1, 2,')
    (tmp_path / "teapot.json").write_text('{"format": "tilesolve/teapot", "version": 1}')
    (tmp_path / "tiles.json").write_text('{"colors": 2, "tiles": [[0, 0, 0, 0]]}')
    problem = DappledProblem.from_strings("2x2", ["H0=1"])
    write_solution(tmp_path / "solution.json", problem, Solution(Status.SAT, np.array([[0, 1], [1, 0]]), method="sat"))
    (tmp_path / "locked.json").write_bytes((tmp_path / "solution.json").read_bytes())
    (tmp_path / "locked.json").chmod(0)
    (tmp_path / "adir").mkdir()
    (tmp_path / "keep.json").write_text('{"an": "earlier result"}\n')
    yield tmp_path
    (tmp_path / "locked.json").chmod(stat.S_IRUSR | stat.S_IWUSR)


@pytest.mark.fast_cases(1)
@pytest.mark.parametrize("command,args", [pytest.param(c, a, id=f"{c or 'tilesolve'}: {n}")
                                          for c, cases in CASES.items() for n, a in cases])
def test_refused_in_one_line_leaving_everything_as_it_was(folder, command, args):
    if "locked.json" in args and os.geteuid() == 0:
        pytest.skip("root reads files whatever their mode")
    before = snapshot(folder)
    proc = run(*shlex.split(command), *shlex.split(args), cwd=folder)
    one_line_error(proc)
    assert snapshot(folder) == before


def _leaves(name: str, command: click.Command) -> list[tuple[str, click.Command]]:
    if isinstance(command, click.Group):
        return [leaf for sub, c in command.commands.items() for leaf in _leaves(f"{name} {sub}", c)]
    return [(name, command)]


def _family_commands() -> dict[str, click.Command]:
    """Every command of every registered family (``Family.commands``), groups opened:
    ``{"brick solve": <command>, ...}``."""
    out = {}
    for fam in family.families():
        for target in fam.commands:
            module, attr = target.split(":")
            out.update(_leaves(attr, getattr(importlib.import_module(module), attr)))
    return out


def _malformed_options(command: click.Command) -> list[tuple[str, str]]:
    """The cases every family command gets from its own options, with no edit here: an unknown
    option, and a malformed value for its first number option and its first choice option."""
    options = [p for p in command.params if isinstance(p, click.Option) and not p.is_flag]
    number = next((p for p in options if isinstance(p.type, (click.types.IntParamType, click.types.FloatParamType))),
                  None)
    choice = next((p for p in options if isinstance(p.type, click.Choice)), None)
    cases = [("unknown option", "--frobnicate 1")]
    if number is not None:
        cases.append((f"{number.opts[-1]} not a number", f"{number.opts[-1]} abc"))
    if choice is not None:
        cases.append((f"{choice.opts[-1]} not a choice", f"{choice.opts[-1]} not-a-choice"))
    return cases


FAMILY_COMMANDS = _family_commands()


@pytest.mark.fast_cases(4)
@pytest.mark.parametrize("command,args", [pytest.param(c, a, id=f"{c}: {n}") for c, cmd in FAMILY_COMMANDS.items()
                                          for n, a in _malformed_options(cmd)])
def test_every_family_command_refuses_malformed_options(folder, command, args):
    before = snapshot(folder)
    one_line_error(run(*command.split(), *shlex.split(args), cwd=folder))
    assert snapshot(folder) == before


def _commands(args: tuple[str, ...], folder) -> list[str]:
    """The command names ``tilesolve ARGS --help`` lists (its sections of commands)."""
    out = run(*args, "--help", cwd=folder).stdout
    blocks = re.findall(r"^(?:Commands|Family commands|Tools):\n(.*?)(?:\n\n|\Z)", out, flags=re.M | re.S)
    return [name for block in blocks for name in re.findall(r"^  (\S+)", block, flags=re.M)]


@pytest.mark.slow
def test_every_command_is_swept(tmp_path):
    """The tools have their cases above; a family's commands are swept from their own options
    (a new family edits nothing here), and any cases above come on top."""
    swept = {c for c in CASES if c} | set(FAMILY_COMMANDS)
    names = _commands((), tmp_path)
    assert {"dappled", "verify"} <= set(names)
    for name in names:
        assert any(c.split()[0] == name for c in swept), f"add bad-input cases for `tilesolve {name}`"
        for sub in _commands((name,), tmp_path):
            path = f"{name} {sub}"  # a command, or a group whose commands are swept
            assert any(c == path or c.startswith(path + " ") for c in swept), f"add bad-input cases for `tilesolve {path}`"


@pytest.mark.parametrize("name, what", [("pts.npy", "NumPy point file"), ("pts.csv", "CSV point file"),
                                        ("t.png", "PNG picture"), ("t.svg", "SVG picture")])
def test_verify_names_a_point_file_or_a_picture_and_the_file_it_reads(tmp_path, name, what):
    """`verify pts.npy` said 'not a UTF-8 text file'; it now says what the file is and what
    verify reads instead."""
    (tmp_path / name).write_bytes(b"\x93NUMPY\x01\x00" if name.endswith(".npy") else b"x,y\n0.5,0.5\n")
    line = one_line_error(run("verify", name, cwd=tmp_path))
    assert line == (f"tilesolve: error: {name}: a {what} holds no problem to check it against; "
                    f"tilesolve verify reads the JSON files tilesolve writes (-o NAME.json)")
