"""The layer rules of DESIGN.md as a tested contract.

Every ``import`` in the package (module level or inside a function: a lazy import is still an
edge) is read with :mod:`ast`, and each edge between tilesolve's layers must point downwards:

=============  =====================================================================
layer          may import (besides itself and third-party packages)
=============  =====================================================================
base           ``tilesolve``, ``errors``, ``deadline``, ``_random``, ``_lazy``, ``_numba``, ``inputs``,
               ``progress``: nothing
model          base
verify         base, model, and numpy only among third-party packages
encodings      base, model
constructive   base, model
io             base, model
engine         base, model, encodings, ``verify.drat`` (the proof checker)
facades        ``family`` and the family facades: everything below
cli            base, model, io, facades
=============  =====================================================================
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "tilesolve"

BASE = {"tilesolve", "tilesolve.errors", "tilesolve.deadline", "tilesolve._random", "tilesolve._lazy", "tilesolve.progress",
        "tilesolve.inputs", "tilesolve._numba"}
#: The facades: the family contract (the package ``tilesolve.family``), every module of ``tilesolve.families``
#: (found from the package, so a new family needs no edit here) and the GPU path.
FACADES = {"tilesolve.family", "tilesolve.families", "tilesolve.gpu"}
FACADE_PACKAGES = ("tilesolve.family.", "tilesolve.families.", "tilesolve.gpu.")

#: layer -> the layers it may import
ALLOWED = {
    "base": set(),
    "model": {"base"},
    "verify": {"base", "model"},
    "encodings": {"base", "model"},
    "constructive": {"base", "model"},
    "io": {"base", "model"},
    "engine": {"base", "model", "encodings", "verify.drat"},
    "facades": {"base", "model", "verify", "verify.drat", "encodings", "constructive", "io", "engine"},
    "cli": {"base", "model", "io", "facades", "studio"},
    "studio": {"base", "model", "verify", "verify.drat", "encodings", "constructive", "io", "engine", "facades"},
}
#: Third-party packages a verifier may use (DESIGN.md: "dependency-light (numpy only)"; numba
#: compiles the board verifier's one-pass loop, written in the verifier from the definitions).
VERIFY_THIRD_PARTY = {"numpy", "numba", "__future__", "dataclasses", "typing", "time", "math", "itertools",
                      "collections", "hashlib", "os", "sys", "functools", "enum"}


def layer_of(module: str) -> str | None:
    """The layer of a tilesolve module name (``None`` outside the package)."""
    if module in BASE:
        return "base"
    if module in FACADES or module.startswith(FACADE_PACKAGES):
        return "facades"
    if module == "tilesolve.verify.drat":
        return "verify.drat"
    parts = module.split(".")
    if parts[0] != "tilesolve" or len(parts) < 2:
        return None
    if parts[1] in ("model", "verify", "encodings", "constructive", "io", "engine", "cli", "studio"):
        return parts[1]
    raise AssertionError(f"{module}: not placed in a layer; add it to the table in tests/test_layers.py")


def module_name(path: Path) -> str:
    rel = path.relative_to(PACKAGE.parent).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def imports_of(source: str, module: str) -> list[tuple[int, str]]:
    """``(line, imported module)`` for every import statement in ``source``."""
    package = module if module.count(".") == 0 else module.rsplit(".", 1)[0]
    out = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            out += [(node.lineno, a.name) for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = package.split(".")[: len(package.split(".")) - node.level + 1]
                base = ".".join(anchor + ([base] if base else []))
            if base == "tilesolve" or (node.level and not node.module):
                # "from tilesolve import dappled": each name may be a submodule
                out += [(node.lineno, f"{base}.{a.name}") if f"{base}.{a.name}" in _ALL_MODULES else (node.lineno, base)
                        for a in node.names]
            else:
                out.append((node.lineno, base))
    return out


def violations(source: str, module: str) -> list[str]:
    """Forbidden import edges of one module, as readable lines."""
    here = layer_of(module)
    bad = []
    for line, target in imports_of(source, module):
        if target.split(".")[0] != "tilesolve":
            if here == "verify" and target.split(".")[0] not in VERIFY_THIRD_PARTY:
                bad.append(f"{module}:{line} imports {target} (verifiers use numpy only)")
            continue
        there = layer_of(target)
        if there is None or there == here or (here == "verify.drat" and there == "verify"):
            continue
        if here == "verify.drat":
            here_rules = ALLOWED["verify"]
        else:
            here_rules = ALLOWED[here]
        if there not in here_rules and not (there == "verify.drat" and "verify" in here_rules):
            bad.append(f"{module}:{line} ({here}) imports {target} ({there})")
    return bad


_ALL_MODULES = {module_name(p) for p in PACKAGE.rglob("*.py")}


def test_every_import_points_downwards():
    bad = []
    for path in sorted(PACKAGE.rglob("*.py")):
        bad += violations(path.read_text(encoding="utf-8"), module_name(path))
    assert not bad, "forbidden imports:\n" + "\n".join(bad)


@pytest.mark.parametrize("module, source", [
    ("tilesolve.constructive.brick", "from tilesolve import family\n"),
    ("tilesolve.constructive.brick", "def f():\n    from tilesolve.engine.sat import solve_cnf\n"),
    ("tilesolve.model.board", "from tilesolve.io.mask import read_mask\n"),
    ("tilesolve.verify.board", "import pysat\n"),
    ("tilesolve.verify.board", "from tilesolve.constructive.brick import solve_linear\n"),
    ("tilesolve.engine.sat", "from tilesolve.family import solve\n"),
    ("tilesolve.engine.sat", "from tilesolve.verify.board import board_violations\n"),
    ("tilesolve.cli.pack", "from tilesolve.engine.packing import solve_lift\n"),
    ("tilesolve.encodings.wang", "from . import dappled\nfrom ..constructive import brick\n"),
    ("tilesolve.constructive.brick", "from tilesolve.families import dappled\n"),
])
def test_a_forbidden_import_is_caught(module, source):
    assert violations(source, module), f"{source!r} in {module} should break the layer rules"


@pytest.mark.parametrize("module, source", [
    ("tilesolve.engine.sat", "from tilesolve.verify.drat import check_drat\n"),
    ("tilesolve.cli.pack", "from tilesolve.families import packing\nfrom tilesolve.io.svg import write_svg\n"),
    ("tilesolve.families.dappled", "from tilesolve.engine.dappled import solve_sat\n"),
    ("tilesolve.verify.grid", "import numpy as np\nfrom tilesolve.errors import InvalidProblem\n"),
])
def test_an_allowed_import_passes(module, source):
    assert violations(source, module) == []


def test_every_registered_family_is_a_facade():
    """The registry is the list of families: each entry point's module sits in the facade layer
    (``tilesolve/families/``), so the layer table needs no edit for a new family."""
    from importlib.metadata import entry_points

    from tilesolve.family import ENTRY_POINT_GROUP, families

    modules = {ep.module for ep in entry_points(group=ENTRY_POINT_GROUP)}
    assert {fam.name for fam in families()} >= {ep.name for ep in entry_points(group=ENTRY_POINT_GROUP)}
    assert modules and all(m.startswith("tilesolve.families.") and layer_of(m) == "facades" for m in modules), modules


def test_the_readme_picture_names_every_package():
    """The README's picture of the layers shows every package of tilesolve."""
    readme = (PACKAGE.parent / "README.md").read_text(encoding="utf-8")
    picture = readme.split("## Package layout", 1)[1].split("Around them", 1)[0]
    packages = {p.name for p in PACKAGE.iterdir() if (p / "__init__.py").is_file()} - {"data"}
    assert packages and not [p for p in sorted(packages) if f"{p}/" not in picture]


def test_the_facades_import_no_circle():
    """No facade imports itself back through another (DESIGN.md: "layers import only downwards";
    inside the facade layer the imports form a tree, so ``board`` and ``walls`` do not import
    each other)."""
    import networkx as nx

    graph = nx.DiGraph()
    for path in sorted(PACKAGE.rglob("*.py")):
        module = module_name(path)
        if layer_of(module) != "facades":
            continue
        for _, target in imports_of(path.read_text(), module):
            if target != module and target.startswith("tilesolve.") and layer_of(target) == "facades":
                graph.add_edge(module, target)
    cycles = list(nx.simple_cycles(graph))
    assert not cycles, "import circles among the facades: " + "; ".join(" -> ".join(c) for c in cycles)


def test_the_tests_mirror_the_package():
    """A module's tests are found from its path: ``tests/io/test_board_json.py`` tests
    ``tilesolve/io/board_json.py``; every test folder is named after a package of tilesolve, and
    the tests at the top of ``tests/`` are those that cross every layer (README, examples, layers)."""
    tests = PACKAGE.parent / "tests"
    folders = {p.name for p in tests.iterdir() if p.is_dir() and any(p.glob("test_*.py"))}
    packages = {p.name for p in PACKAGE.iterdir() if (p / "__init__.py").is_file()}
    assert folders and folders <= packages, f"test folders with no package of that name: {sorted(folders - packages)}"
