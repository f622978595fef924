"""DIMACS CNF / WCNF export of any tilesolve encoding (DESIGN.md, "Encodings", "Files").

The files carry a comment header describing the problem and what each variable means,
so a formula can be handed to any external solver (or proof checker such as drat-trim)
and its model read back. Writes are atomic: a temporary file in the target directory
is filled, flushed, synced and renamed over the target with :func:`os.replace`, so an
interrupted export never leaves a half-written file.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Iterable, Sequence, TextIO

import numpy as np

from tilesolve.io.atomic import atomic_write

__all__ = ["write_dimacs", "dimacs_text"]


def _clause_chunks(clauses) -> Iterable[list[list[int]]]:
    if hasattr(clauses, "chunks"):
        yield from clauses.chunks()
    elif hasattr(clauses, "clauses"):
        yield clauses.clauses
    else:
        yield [list(c) for c in clauses]


def _formula_parts(obj):
    """(hard clauses, soft literals or None, header lines, n_vars) of an encoding or clause list."""
    hard = getattr(obj, "hard", obj)
    soft = getattr(obj, "soft", None)
    header = list(obj.header()) if hasattr(obj, "header") else []
    n_vars = int(getattr(obj, "n_vars", 0) or 0)
    return hard, soft, header, n_vars


def _write(fh: TextIO, obj, comments: Sequence[str], wcnf_format: str) -> None:
    hard, soft, header, n_vars = _formula_parts(obj)
    n_hard = 0
    top = n_vars
    if hasattr(hard, "max_var"):  # a ClauseSet: numpy does the counting
        n_hard, top = len(hard), max(top, hard.max_var())
    else:
        for ch in _clause_chunks(hard):
            n_hard += len(ch)
            for c in ch:
                if c:
                    top = max(top, max(abs(v) for v in c))
    soft_list = [] if soft is None else [int(v) for v in np.asarray(soft).ravel()]
    for v in soft_list:
        top = max(top, abs(v))
    for line in list(header) + list(comments):
        for part in str(line).splitlines() or [""]:
            fh.write("c " + part.encode("ascii", "replace").decode("ascii") + "\n")  # DIMACS is ASCII
    if soft is None:
        fh.write(f"p cnf {top} {n_hard}\n")
        prefix = ""
    elif wcnf_format == "old":
        hard_w = len(soft_list) + 1  # "top": larger than the sum of soft weights
        fh.write(f"p wcnf {top} {n_hard + len(soft_list)} {hard_w}\n")
        prefix = f"{hard_w} "
    elif wcnf_format == "new":
        prefix = "h "
    else:
        raise ValueError(f"wcnf_format must be 'old' or 'new', got {wcnf_format!r}")
    for ch in _clause_chunks(hard):
        fh.write("".join(prefix + " ".join(map(str, c)) + (" 0\n" if c else "0\n") for c in ch))
    fh.write("".join(f"1 {v} 0\n" for v in soft_list))


def dimacs_text(obj, *, comments: Sequence[str] = (), wcnf_format: str = "old") -> str:
    """The DIMACS text of an encoding (or any clause collection), as a string.

    Examples
    --------
    >>> print(dimacs_text([[1, -2], [2]]), end="")
    p cnf 2 2
    1 -2 0
    2 0
    """
    import io

    buf = io.StringIO()
    _write(buf, obj, comments, wcnf_format)
    return buf.getvalue()


def write_dimacs(
    obj,
    path: str | os.PathLike,
    *,
    comments: Sequence[str] = (),
    wcnf_format: str = "old",
) -> Path:
    """Write an encoding as DIMACS CNF, or WCNF when it has soft clauses, atomically.

    Parameters
    ----------
    obj : DappledEncoding, ClauseSet, pysat CNF or list of clauses
        An encoding contributes its :meth:`header` (problem and variable meaning) and,
        if built by ``encode_wcnf``, its soft unit clauses (weight 1 each).
    path : str or path-like
    comments : sequence of str
        Extra comment lines.
    wcnf_format : {"old", "new"}
        ``"old"``: ``p wcnf`` line with a "top" weight for hard clauses; ``"new"``: the
        MaxSAT Evaluation 2022 format (``h`` prefix for hard clauses, no ``p`` line).

    Returns
    -------
    pathlib.Path

    Examples
    --------
    >>> import tempfile, os
    >>> from tilesolve.model import DappledProblem
    >>> from tilesolve.encodings import encode_cnf
    >>> enc = encode_cnf(DappledProblem.from_strings("3x1", ["H0=2"]))
    >>> d = tempfile.mkdtemp(); f = write_dimacs(enc, os.path.join(d, "t.cnf"))
    >>> [l for l in open(f) if not l.startswith("c")]
    ['p cnf 3 1\\n', '1 2 3 0\\n']
    """
    with atomic_write(path, encoding="ascii") as fh:
        _write(fh, obj, comments, wcnf_format)
    return Path(path)
