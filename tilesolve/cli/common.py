"""Pieces the commands share: error display, problem building, output checks, summaries."""

from __future__ import annotations

import os
import re
import sys
from pathlib import Path
from typing import Iterable

import click

from tilesolve.errors import InvalidProblem

__all__ = ["CliError", "build_problem", "check_writable", "say", "verbosity", "progress_wanted", "split_conditions"]


class CliError(click.ClickException):
    """A user-facing error: one line ``tilesolve: error: ...`` on stderr and an exit code."""

    def __init__(self, message: str, exit_code: int = 2) -> None:
        super().__init__(message)
        self.exit_code = exit_code

    def show(self, file=None) -> None:  # noqa: D102 - click API
        message = " ".join(self.format_message().split("\n"))
        click.echo(f"tilesolve: error: {message}", err=True)


def verbosity() -> int:
    """``-v`` count minus ``-q`` count of the current invocation (0 without a context)."""
    ctx = click.get_current_context(silent=True)
    obj = ctx.find_root().obj if ctx else None
    return obj.get("verbosity", 0) if isinstance(obj, dict) else 0


def say(message: str, *, level: int = 0) -> None:
    """Print a human summary line on stderr when verbosity >= ``level`` (``-q`` hides level 0)."""
    if verbosity() >= level:
        click.echo(message, err=True)


def progress_wanted() -> bool:
    """Show progress only on an interactive terminal, and not under ``-q``."""
    try:
        return sys.stderr.isatty() and verbosity() >= 0
    except (AttributeError, ValueError):
        return False


_SPLIT = re.compile(r"[,\s]+(?![^{]*\})")


def split_conditions(items: Iterable[str]) -> list[str]:
    """Split ``--cond`` values on commas/spaces outside braces: ``"H0=2,V{0,1}=3"`` -> two."""
    return [part for item in items for part in _SPLIT.split(item.strip()) if part]


def build_problem(
    *,
    size: str | None,
    conditions: Iterable[str],
    n_tiles: int | None,
    cyclic: bool,
    fix: str | None,
    problem_file: str | None,
    counts: Iterable[str] = (),
    closest_to: str | None = None,
):
    """The :class:`~tilesolve.model.DappledProblem` described by the problem options.

    The size is checked first (absurd sizes are refused before anything is allocated),
    then the conditions and counts, then the files.
    """
    from tilesolve.io.jsonio import read_problem, read_tiling
    from tilesolve.model.dappled import DappledProblem, parse_condition, parse_count, parse_size

    conditions, counts = list(conditions), list(counts)
    if problem_file:
        given = [name for name, v in (("--size", size), ("--cond", conditions), ("--tiles", n_tiles),
                                      ("--cyclic", cyclic), ("--fix", fix), ("--count", counts),
                                      ("--closest-to", closest_to)) if v]
        if given:
            raise InvalidProblem(f"--problem gives the whole problem; drop {', '.join(given)}")
        return read_problem(problem_file)
    if not size:
        raise InvalidProblem("--size is required, e.g. --size 12x8 (12 columns, 8 rows), or give --problem FILE")
    rows, cols = parse_size(size)
    conds = tuple(parse_condition(c) for c in split_conditions(conditions))
    tile_counts = tuple(parse_count(k) for k in counts)
    fixed = read_tiling(fix, allow_free=True, what="partial tiling") if fix else None
    target = read_tiling(closest_to, what="target tiling") if closest_to else None
    try:
        return DappledProblem(
            rows,
            cols,
            n_tiles=2 if n_tiles is None else n_tiles,
            conditions=conds,
            cyclic=cyclic,
            fixed=fixed,
            counts=tile_counts,
            closest_to=target,
        )
    except InvalidProblem as exc:
        src = [f for f, a in ((fix, "partial tiling"), (closest_to, "target tiling")) if f and a in str(exc)]
        raise InvalidProblem(f"{src[0]}: {exc}" if src else str(exc)) from None


def check_writable(path: str | None) -> None:
    """Refuse an output path whose directory is missing, before any work is done."""
    if not path or path == "-":
        return
    p = Path(path)
    if p.is_dir():
        raise InvalidProblem(f"cannot write {path}: it is a directory")
    parent = p.parent if str(p.parent) else Path(".")
    if not parent.is_dir():
        raise InvalidProblem(f"cannot write {path}: directory {parent} does not exist")
    if not os.access(parent, os.W_OK):
        raise InvalidProblem(f"cannot write {path}: directory {parent} is not writable")


def check_distinct(*paths: str | None) -> None:
    """Refuse two outputs (or an output and an input) that name the same file."""
    seen: dict[str, str] = {}
    for p in paths:
        if p and p != "-":
            key = os.path.realpath(p)
            if key in seen:
                raise InvalidProblem(f"{p} is named twice (as input and output, or as two outputs)")
            seen[key] = p
