"""Solution files: a document's family and codec found from its ``format``, and the one writer."""

from __future__ import annotations

import os
from typing import Any

from tilesolve.errors import InvalidProblem
from tilesolve.family.contract import Codec, Family
from tilesolve.family.registry import codec_of, family_of
from tilesolve.model.solution import Solution

__all__ = ["read_document", "identify", "write_solution", "solution_text"]


def read_document(path: str | os.PathLike) -> tuple[Family, Codec, dict]:
    """Read a tilesolve JSON file and find its family and codec (version checked)."""
    from tilesolve.io.jsonio import read_json

    doc = read_json(path)
    return identify(doc, str(path)) + (doc,)


def identify(doc: Any, source: str) -> tuple[Family, Codec]:
    """The family and codec of a parsed document, its ``format`` and ``version`` checked."""
    from tilesolve.io.jsonio import check_document

    fmt = doc.get("format") if isinstance(doc, dict) else None
    if not isinstance(fmt, str):
        check_document(doc, source, {})  # raises: not a tilesolve file
    try:
        fam, codec = codec_of(fmt)
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: {exc}") from None
    check_document(doc, source, {fmt: codec.versions})
    return fam, codec


def write_solution(path: str | os.PathLike, problem: Any, solution: Solution) -> None:
    """Write ``solution`` in its family's solution format (atomically)."""
    from tilesolve.io.atomic import write_text_atomic

    write_text_atomic(path, solution_text(problem, solution))


def solution_text(problem: Any, solution: Solution) -> str:
    """The JSON text of a solution file."""
    from tilesolve.io.jsonio import dumps

    return dumps(family_of(problem).solution_codec.write(problem, solution))
