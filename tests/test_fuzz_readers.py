"""Property-based fuzzing of every reader through the console script's entry point.

Valid files of every family (dappled, board, packing, stochastic, aperiodic reports, tile sets
in each format, masks, text grids) are mutated (fields deleted, duplicated or retyped, huge
numbers, NaN, deep nesting, truncation, random bytes) and handed to the commands that read
them: ``verify``, ``aperiodic verify``, ``wang count --tiles``, ``aperiodic check``, ``export
dimacs FILE``, ``draw FILE``, ``wang solve --board mask:FILE`` and ``dappled solve --fix FILE``. Whatever the
input, the command ends without a traceback: exit 2 with exactly one ``tilesolve: error:``
line, or, for a document that is still valid, an answer (exit 0, 1 or 3). Never exit 70 (an
internal error) and never "out of memory" (readers validate before they allocate).

The commands run in one long-lived process (tests/fuzz_driver.py), which calls the console
script's entry point once per input as the script would; test_driver_answers_as_the_console_script
checks that it answers exactly as the installed ``tilesolve`` script does. Example counts are
bounded so the module runs in well under a minute.
"""

from __future__ import annotations

import copy
import json
import subprocess
import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from clitools import one_line_error, run

DRIVER = Path(__file__).with_name("fuzz_driver.py")
EXAMPLES = 60

_SETTINGS = settings(max_examples=EXAMPLES, deadline=None, database=None,
                     suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow,
                                            HealthCheck.data_too_large])


class Driver:
    """One ``fuzz_driver.py`` process: :meth:`run` a command line in a folder."""

    def __init__(self) -> None:
        self.proc = subprocess.Popen([sys.executable, str(DRIVER)], stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE, text=True)

    def run(self, argv: list[str], cwd: Path) -> dict:
        self.proc.stdin.write(json.dumps({"argv": argv, "cwd": str(cwd)}) + "\n")
        self.proc.stdin.flush()
        line = self.proc.stdout.readline()
        assert line, f"the driver died on {argv}"
        return json.loads(line)

    def close(self) -> None:
        self.proc.stdin.close()
        self.proc.wait(timeout=60)


@pytest.fixture(scope="module")
def driver():
    d = Driver()
    yield d
    d.close()


#: Valid files made by the commands themselves: name -> command line writing it.
_MAKE = {
    "dappled.json": ["dappled", "solve", "--size", "6x4", "--cond", "H0=2,V1=2", "--seed", "1", "-o", "dappled.json"],
    "dappled3.json": ["dappled", "solve", "--size", "5x4", "--tiles", "3", "--cond", "H0=1", "--count", "2=2..5",
                      "--seed", "1", "-o", "dappled3.json"],
    "unsat.json": ["dappled", "solve", "--size", "3x3", "--cond", "H0=1", "--count", "1=0", "-o", "unsat.json",
                   "--proof-dir", "proofs"],
    "board.json": ["wang", "solve", "--builtin", "jeandel-rao", "--board", "rect:5x4", "--boundary", "free",
                   "--seed", "1", "-o", "board.json"],
    "torus.json": ["brick", "solve", "--board", "torus:4x4", "--colors", "3", "--seed", "1", "-o", "torus.json"],
    "packing.json": ["pack", "--kind", "wang", "--colors", "2", "-o", "packing.json"],
    "corner.json": ["pack", "--kind", "corner", "--colors", "3", "--method", "euler", "-o", "corner.json"],
    "window.json": ["tiling", "--kind", "wang", "--method", "scanline", "--set", "compact", "--colors", "2",
                    "--region", "0,0,8x6", "--seed", "1", "-o", "window.json"],
    "report.json": ["aperiodic", "check", "--builtin", "periodic-7-30", "--max-square", "3", "--max-period", "2",
                    "--seed", "1", "--workers", "1", "-o", "report.json", "--proof-dir", "proofs"],
    "tileset.json": ["tiles", "--builtin", "jeandel-rao", "-o", "tileset.json"],
}
_TEXT = {
    "tiles.tiles": "# n s w e\n0 0 1 0\n1 3 2 0\n2 0 2 1\n",
    "tiles.tilesat": "3 4 2 2\n1 1 2 1\n2 4 3 1\n3 1 3 2\n",
    "tiles.rtlb": "[(0, 0, 1, 0), (1, 3, 2, 0), (2, 0, 2, 1)]\n",
    "mask.txt": "##.\n###\n.##\n",
    "grid.txt": "01?1\n?..0\n1100\n",
    "spaced.txt": "1 0 1 0\n0 1 ? 1\n1, 1, 0, 0\n",
}


@pytest.fixture(scope="module")
def seeds(tmp_path_factory, driver):
    """A folder of valid files of every family, and their bytes."""
    folder = tmp_path_factory.mktemp("seeds")
    for name, argv in _MAKE.items():
        answer = driver.run(["-q", *argv], folder)
        assert answer["rc"] in (0, 1), (argv, answer)
    for name, text in _TEXT.items():
        (folder / name).write_text(text)
    return folder, {p.name: p.read_bytes() for p in folder.iterdir() if p.is_file()}


# ----------------------------------------------------------------------------- mutations
_WEIRD = st.one_of(
    st.none(), st.booleans(), st.integers(), st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([-1, 0, 2**31, 2**63, -(2**63), 10**30, 10**9, 99_999_992, 10**4000]),
    st.text(max_size=6), st.sampled_from(["inf", "-1", "sat", "unsat", "rect:5x5", "1e999"]),
    st.just([]), st.just({}), st.lists(st.integers(-3, 3), max_size=5),
    st.lists(st.lists(st.integers(-2, 12), max_size=5), max_size=4),
    st.fixed_dictionaries({"dtype": st.sampled_from(["bits", "uint8", "int64", "float32"]),
                           "shape": st.lists(st.integers(-1, 10**6), max_size=3),
                           "data": st.sampled_from(["", "AAAA", "8A==", "!!"])}),
)


def _paths(obj, pre=()):
    yield pre
    if len(pre) < 6:
        items = obj.items() if isinstance(obj, dict) else enumerate(obj[:8]) if isinstance(obj, list) else ()
        for k, v in items:
            yield from _paths(v, pre + (k,))


def _at(obj, path):
    for k in path:
        obj = obj[k]
    return obj


def _mutate_doc(data, doc):
    """Apply 1-3 drawn edits to a parsed document; the JSON text (NaN and Infinity allowed)."""
    doc = copy.deepcopy(doc)
    for _ in range(data.draw(st.integers(1, 3))):
        paths = [p for p in _paths(doc) if p]
        if not paths:
            break
        path = data.draw(st.sampled_from(paths))
        parent, key = _at(doc, path[:-1]), path[-1]
        op = data.draw(st.sampled_from(["delete", "retype", "retype", "double", "copy", "add", "nest"]))
        value = parent[key]
        if op == "delete":
            del parent[key]
        elif op == "retype":
            parent[key] = data.draw(_WEIRD)
        elif op == "double":
            if isinstance(value, list):
                parent[key] = value + value
            elif isinstance(value, int) and not isinstance(value, bool):
                parent[key] = value * data.draw(st.sampled_from([-1, 10**6, 2**40])) + data.draw(st.integers(-1, 1))
            elif isinstance(value, str):
                parent[key] = value[:-1] if data.draw(st.booleans()) else value + "0"
        elif op == "copy":
            parent[key] = copy.deepcopy(_at(doc, data.draw(st.sampled_from(paths))))
        elif op == "add":
            if isinstance(parent, dict):
                parent[data.draw(st.sampled_from(["zz", "seed", "time_s", "colors", "grid", "tiling"]))] = \
                    data.draw(_WEIRD)
            else:
                parent.append(data.draw(_WEIRD))
        else:
            depth = data.draw(st.sampled_from([2, 50, 400]))
            for _ in range(depth):
                value = [value]
            parent[key] = value
    try:
        return json.dumps(doc, allow_nan=True).encode()
    except RecursionError:
        return b"[" * 5000 + b"]" * 5000


def _mutate_bytes(data, raw: bytes) -> bytes:
    op = data.draw(st.sampled_from(["truncate", "flip", "insert", "random"]))
    if op == "truncate":
        return raw[:data.draw(st.integers(0, max(0, len(raw) - 1)))]
    if op == "random":
        return data.draw(st.binary(max_size=300))
    i = data.draw(st.integers(0, len(raw)))
    if op == "flip":
        return raw[:i] + data.draw(st.binary(min_size=1, max_size=4)) + raw[i + 4:]
    junk = data.draw(st.sampled_from([b"99999992", b"-1", b"1e999", b"NaN", b"\x00", b"\xff\xfe", b"[" * 3000,
                                      b"(", b"{", b"\n", b"9" * 5000, b"#", b"3 4 2 2\n"]))
    return raw[:i] + junk + raw[i:]


def _mutant(data, raw: bytes) -> bytes:
    try:
        doc = json.loads(raw)
    except ValueError:
        doc = None
    if doc is not None and data.draw(st.booleans()):
        return _mutate_doc(data, doc)
    return _mutate_bytes(data, raw)


def _check(answer: dict, argv: list[str], raw: bytes) -> None:
    what = f"{argv}: input {raw[:300]!r}: {answer}"
    assert "Traceback" not in answer["stderr"], what
    assert answer["rc"] in (0, 1, 2, 3), what
    if answer["rc"] == 2:
        lines = answer["stderr"].strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("tilesolve: error: "), what
        assert "out of memory" not in lines[0] and "internal error" not in lines[0], what


#: reader -> (seed files, command line with FILE for the mutated file)
READERS = {
    "verify": (["dappled.json", "dappled3.json", "unsat.json", "board.json", "torus.json", "packing.json",
                "corner.json", "window.json", "report.json"], ["verify", "FILE"]),
    "verify --proof-dir": (["unsat.json", "report.json"], ["verify", "FILE", "--proof-dir", "proofs"]),
    "aperiodic verify": (["report.json"], ["aperiodic", "verify", "FILE"]),
    "wang count --tiles": (["tileset.json", "tiles.tiles", "tiles.tilesat", "tiles.rtlb"],
                           ["wang", "count", "--tiles", "FILE", "--board", "rect:2x2"]),
    "aperiodic check": (["tileset.json"], ["aperiodic", "check", "FILE", "--max-square", "2", "-o", "out.json"]),
    "export dimacs": (["dappled.json", "dappled3.json", "board.json", "torus.json", "packing.json"],
                      ["export", "dimacs", "FILE", "-o", "out.cnf"]),
    "draw": (["dappled.json", "torus.json", "packing.json", "corner.json", "window.json"],
             ["draw", "FILE", "-o", "out.svg"]),
    "draw png": (["dappled.json", "torus.json", "packing.json", "corner.json", "window.json"],
                 ["draw", "FILE", "-o", "out.png"]),
    "mask": (["mask.txt"], ["wang", "solve", "--builtin", "jeandel-rao", "--board", "mask:FILE", "--boundary", "free",
                            "--time-limit", "10"]),
    "text grid": (["grid.txt", "spaced.txt"], ["dappled", "solve", "--size", "4x3", "--cond", "H0=2", "--fix", "FILE",
                                 "--time-limit", "10"]),
}


@pytest.mark.slow
@pytest.mark.parametrize("reader", list(READERS))
def test_mutated_files_give_one_line_or_an_answer(reader, driver, seeds, tmp_path_factory):
    folder, files = seeds
    names, argv = READERS[reader]

    @_SETTINGS
    @given(data=st.data())
    def check(data):
        name = data.draw(st.sampled_from(names))
        raw = _mutant(data, files[name])
        target = folder / f"fuzz{Path(name).suffix}"
        target.write_bytes(raw)
        line = [a.replace("FILE", target.name) for a in argv]
        _check(driver.run(line, folder), line, raw)

    check()


@pytest.mark.slow
def test_driver_answers_as_the_console_script(driver, seeds):
    """The driver's answers are the installed script's: same exit code, same stderr."""
    folder, _ = seeds
    (folder / "nan.json").write_text((folder / "dappled.json").read_text().replace('"seed": 1', '"seed": NaN'))
    (folder / "short.txt").write_text("3 4 2 2\n1 1 2 1\n2 4 3 1\n")
    for argv in (["verify", "dappled.json"], ["verify", "nan.json"], ["aperiodic", "verify", "report.json"],
                 ["wang", "count", "--tiles", "short.txt", "--board", "rect:2x2"]):
        mine, theirs = driver.run(argv, folder), run(*argv, cwd=folder)
        assert (mine["rc"], mine["stderr"]) == (theirs.returncode, theirs.stderr), argv


@pytest.mark.fast_cases(1)
@pytest.mark.parametrize("field,value", [("seed", "NaN"), ("seed", "-1"), ("time_s", "1e999"), ("time_s", "-0.5"),
                                         ("time_s", "Infinity")])
def test_seed_and_time_must_be_finite_and_non_negative_in_every_family(field, value, seeds):
    """NaN, infinite or negative ``seed``/``time_s`` are refused by every family's reader."""
    folder, files = seeds
    for name in ("dappled.json", "board.json", "packing.json", "window.json", "report.json"):
        doc = json.loads(files[name])
        doc[field] = "VALUE"
        (folder / "bad.json").write_text(json.dumps(doc).replace('"VALUE"', value))
        line = one_line_error(run("verify", "bad.json", cwd=folder))
        assert field in line or "JSON" in line, (name, line)
