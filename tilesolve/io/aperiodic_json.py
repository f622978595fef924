"""The ``tilesolve/aperiodic-report`` file (version 2): an aperiodicity check and its certificates.

::

    {
      "format": "tilesolve/aperiodic-report", "version": 2,
      "name": "jeandel-rao",               # or null
      "tileset": {"colours": 5, "sides": ["N", "E", "S", "W"], "tiles": [[4, 2, 1, 2], ...]},
      "max_square": 40, "max_period": 6, "shears": false,
      "largest_square": 40,                # null when squares were not asked or not decided
      "conclusion": "...",                 # what the certificates prove, in words
      "verdict": "periodic",               # the same in one word (model.aperiodic.VERDICTS)
      "literature": "...",                 # a built-in set's literature note, or null
      "squares": [CERT, ...], "periods": [CERT, ...],
      "status": "sat",                     # "sat", or "unknown" when the verdict is "undecided"
      "method": "sat", "solver": null, "seed": 1, "time_s": 3.2,
      "reason": null, "notes": [], "stats": {}
    }

    CERT = {"board": "torus 3x4 shear 1", "status": "tiles" | "refuted" | "undecided",
            "method": "sat", "tiling": [[tile index, ...], ...] or null,
            "evidence": {"encoding": {"name": "wang-tiles-cnf", "version": 1, "options": {}},
                         "cnf_sha256": ..., "drat_sha256": ..., ...}, "time_s": 0.1}

Tile indices refer to ``tileset.tiles`` in the order written, which is the order of the tile
set the check was given (reports written before tilesolve kept that order list the tiles sorted
by their colours W, N, E, S, and their indices refer to that list). A refutation's
``evidence`` names the encoding that re-derives its CNF from the tile set
and the board's name; a verdict taken from a sweep's cache says so (``"cached": true``,
``"cache_check"``), one decided again because its cache line did not hold says why
(``"cache_rejected"``). The verdict and the status are what the certificates give
(:attr:`~tilesolve.model.aperiodic.AperiodicReport.verdict`, ``.status``); in a file they
are claims, which ``tilesolve verify`` holds to the certificates (a file that says otherwise is
false, exit 1). Version 1 (no ``verdict``; ``status`` ``"sat"`` whatever the verdict, or
``"unknown"`` for a run stopped before its report) is read with both taken from its
certificates; a ``verdict`` in a version 1 file is refused (exit 2): v1 has none, so a version 2
body relabelled version 1 would carry a verdict word nothing checks. A version 1 ``status``
other than those two is a claim v1 never made and is held to the certificates like version 2's.
Readers reject
unknown fields and malformed values (a tile that is not four colours of the set, a ``colours``
count other than the number of colours the tiles use, a tile written twice, a ``time_s`` that
is not a duration, ...) with one line naming the file and field; the certificates' claims are
checked by the family's verifier and re-derived by ``tilesolve verify``.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.io.jsonio import check_document, check_time_s, provenance_to_dict, solution_from_provenance
from tilesolve.io.tileset_json import compact_tileset
from tilesolve.model.aperiodic import STATUSES, VERDICTS, AperiodicProblem, AperiodicReport, Certificate
from tilesolve.model.solution import Solution, Status

__all__ = ["APERIODIC_REPORT", "VERSIONS", "report_to_dict", "report_from_dict", "certificate_to_dict"]

APERIODIC_REPORT = "tilesolve/aperiodic-report"
VERSIONS = frozenset({1, 2})

_KEYS = {"format", "version", "name", "tileset", "max_square", "max_period", "shears", "largest_square",
         "conclusion", "verdict", "literature", "squares", "periods", "status", "method", "solver", "seed", "time_s",
         "reason", "notes", "stats", "created_by", "comment"}
_CERT_KEYS = {"board", "status", "method", "tiling", "evidence", "time_s"}


def certificate_to_dict(c: Certificate) -> dict:
    return {"board": c.board, "status": c.status, "method": c.method,
            "tiling": None if c.tiling is None else np.asarray(c.tiling, dtype=np.int64).tolist(),
            "evidence": dict(c.evidence), "time_s": c.time_s}


def report_to_dict(problem: AperiodicProblem, solution: Solution) -> dict:
    rep = solution.report if isinstance(solution.report, AperiodicReport) else AperiodicReport()
    doc = {"format": APERIODIC_REPORT, "version": 2, "name": problem.name,
           "tileset": {"colours": int(problem.tileset.n_colors), "sides": ["N", "E", "S", "W"],
                       "tiles": problem.tileset.tiles.tolist()},
           "max_square": problem.max_square, "max_period": problem.max_period, "shears": problem.shears,
           "largest_square": rep.largest_square, "conclusion": rep.conclusion, "verdict": rep.verdict,
           "literature": rep.literature,
           "squares": [certificate_to_dict(c) for c in rep.squares],
           "periods": [certificate_to_dict(c) for c in rep.periods]}
    doc.update(provenance_to_dict(solution))
    return doc


def _fail(source: Any, field: str, why: str) -> InvalidProblem:
    return InvalidProblem(f"{source}: {field!r} {why}")


def _int(doc: dict, key: str, source: Any, *, optional: bool = False) -> int | None:
    v = doc.get(key)
    if v is None and optional:
        return None
    if isinstance(v, bool) or not isinstance(v, int) or v < 0:
        raise _fail(source, key, f"must be a non-negative integer, got {v!r}")
    return v


def _certificate(d: Any, where: str, source: Any) -> Certificate:
    if not isinstance(d, dict) or not set(d) <= _CERT_KEYS or "board" not in d or "status" not in d:
        raise _fail(source, where, f"must be an object with fields {sorted(_CERT_KEYS)}")
    if d["status"] not in STATUSES or not isinstance(d["board"], str):
        raise _fail(source, where, f"has a bad board or status (status one of {STATUSES})")
    tiling = d.get("tiling")
    if tiling is not None:
        try:
            tiling = np.asarray(tiling, dtype=np.int64)
        except (TypeError, ValueError):
            raise _fail(source, where + ".tiling", "must be rows of tile indices") from None
        if tiling.ndim != 2:
            raise _fail(source, where + ".tiling", "must be rows of tile indices")
    ev = d.get("evidence", {})
    if not isinstance(ev, dict):
        raise _fail(source, where + ".evidence", "must be an object")
    t = check_time_s(d.get("time_s", 0.0), source, where + ".time_s")
    try:
        return Certificate(d["board"], d["status"], tiling, str(d.get("method", "sat")), ev, t)
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: {where}: {exc}") from None


def _check_builtin_name(name, tileset, source: Any) -> None:
    """A report named after a built-in tile set (the name ``verify``'s verdict shows) must hold that
    set, tile for tile; other names (a file's) are the user's."""
    from tilesolve.io.builtin_tilesets import load, names

    if name is None or name not in names():
        return
    builtin, _ = load(name)
    if not np.array_equal(np.asarray(builtin.tiles), np.asarray(tileset.tiles)):
        raise InvalidProblem(f"{source}: 'name' is the built-in tile set {name!r}, but 'tileset' is not that set")


def report_from_dict(doc: dict, source: Any = "<document>") -> tuple[AperiodicProblem, Solution]:
    check_document(doc, source, {APERIODIC_REPORT: VERSIONS})
    extra = set(doc) - _KEYS
    if extra:
        raise _fail(source, sorted(extra)[0], "is not a field of a tilesolve/aperiodic-report file")
    ts = doc.get("tileset")
    if not isinstance(ts, dict) or not isinstance(ts.get("tiles"), list) or ts.get("sides") != ["N", "E", "S", "W"]:
        raise _fail(source, "tileset", "must be {'colours': K, 'sides': ['N', 'E', 'S', 'W'], 'tiles': [...]}")
    colours = _int(ts, "colours", source)
    for i, t in enumerate(ts["tiles"]):
        if not isinstance(t, list) or len(t) != 4 or not all(
                isinstance(v, int) and not isinstance(v, bool) and 0 <= v < colours for v in t):
            raise _fail(source, f"tileset.tiles[{i}]", f"must be [N, E, S, W]: 4 integer colours in 0..{colours - 1}, "
                                                       f"got {str(t)[:60]}")
    tileset, notes = compact_tileset(ts["tiles"], f"{source}: 'tileset'", colours)
    if tileset.n_colors != colours or notes:  # the set as written must be the set its indices refer to
        why = notes[0] if notes else f"{source}: 'tileset': 'colours' is {colours}, but its tiles use {tileset.n_colors}"
        raise InvalidProblem(f"{why} (a report writes its tile set with colours 0..K-1 all used, each tile once)")
    if not isinstance(doc.get("shears"), bool):
        raise _fail(source, "shears", "must be true or false")
    name = doc.get("name")
    if name is not None and not isinstance(name, str):
        raise _fail(source, "name", "must be a string or null")
    _check_builtin_name(name, tileset, source)
    try:
        problem = AperiodicProblem(tileset, _int(doc, "max_square", source), _int(doc, "max_period", source),
                                   doc["shears"], name)
    except InvalidProblem as exc:
        raise InvalidProblem(f"{source}: {exc}") from None
    certs = {}
    for key in ("squares", "periods"):
        if not isinstance(doc.get(key), list):
            raise _fail(source, key, "must be a list of certificates")
        certs[key] = tuple(_certificate(d, f"{key}[{i}]", source) for i, d in enumerate(doc[key]))
    for key in ("conclusion", "literature"):
        if doc.get(key) is not None and not isinstance(doc[key], str):
            raise _fail(source, key, "must be a string")
    stated = None
    if doc["version"] == 1 and "verdict" in doc:  # v1 states none: a v2 body relabelled v1 would go unchecked
        raise _fail(source, "verdict", "is not a field of a version 1 report (version 2 states its verdict, and "
                                       "verify holds it to the certificates)")
    if doc["version"] >= 2:
        stated = doc.get("verdict")
        if not isinstance(stated, str) or stated not in VERDICTS:
            raise _fail(source, "verdict", f"must be one of {', '.join(VERDICTS)}, got {str(stated)[:60]!r}")
    report = AperiodicReport(certs["squares"], certs["periods"], _int(doc, "largest_square", source, optional=True),
                             doc.get("conclusion") or "", doc.get("literature"), stated)
    sol = solution_from_provenance(doc, source, report, what="report").replace(tiling=None, report=report)
    if doc["version"] >= 2 or sol.status not in (Status.SAT, Status.UNKNOWN):  # claims v1 never made: checked
        return problem, sol
    return problem, sol.replace(status=report.status)
