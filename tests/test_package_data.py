"""Every file the package reads at run time is in the wheel: ``pip install .`` (what a user and
CI run) copies only the non-Python files that ``[tool.setuptools.package-data]`` names, so a
data file the globs miss works in an editable checkout and is missing from an install."""

from __future__ import annotations

import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "tilesolve"


def test_every_data_file_is_named_by_package_data():
    globs = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["package-data"]["tilesolve"]
    named = {p for g in globs for p in PACKAGE.glob(g)}
    data = [p for p in PACKAGE.rglob("*") if p.is_file() and p.suffix not in (".py", ".pyc")
            and "__pycache__" not in p.parts and not p.name.endswith((".nbi", ".nbc"))]
    assert data, "no data files found: the test looks in the wrong place"
    assert sorted(str(p.relative_to(PACKAGE)) for p in data if p not in named) == []
