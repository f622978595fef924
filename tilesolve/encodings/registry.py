"""The named encodings: what a certificate binds a problem to (DESIGN.md, "Trust model").

An ``unsat`` answer (or a refuted board of an aperiodicity report) is a DRAT proof of one exact
CNF. For anyone to check that this CNF *is* the problem the answer talks about, the CNF must
be re-derivable from the problem alone: every CNF encoding that can give an unsat answer is
deterministic and registered here under a name, with a version and its options (JSON
values). A solution records them (``stats["encoding"]``, a report's ``evidence["encoding"]``)::

    {"name": "dappled-cnf", "version": 1, "options": {"card_encoding": "auto"}}

and ``tilesolve verify`` rebuilds the CNF with :func:`encode` from the problem stated in the
file, then checks the proof against that formula. ``export dimacs`` uses the same encoders.

A change to an encoder that changes any CNF it builds must raise its version: a file made with
the old version is then refused with "proof made with encoding X v1; this version encodes v2:
re-solve to re-certify", never accepted against a different formula.

========================  =======  ====================================  ===========================
name                      version  problem                               options
========================  =======  ====================================  ===========================
``dappled-cnf``           1        :class:`~tilesolve.model.dappled.DappledProblem`  ``card_encoding``
``wang-board-cnf``        2        :class:`~tilesolve.model.board.BoardProblem`      none
``packing-cnf``           1        :class:`~tilesolve.model.packing.PackingProblem`  ``anchor_tile``, ``amo_tiles``
``wang-tiles-cnf``        1        :class:`~tilesolve.model.board.BoardProblem`, free boundary,
                                   no line limits (a board of an aperiodicity check)   none
========================  =======  ====================================  ===========================

Examples
--------
>>> from tilesolve.model.dappled import DappledProblem
>>> enc = encode("dappled-cnf", DappledProblem.from_strings("3x1", ["H0=2"]))
>>> enc.named
{'name': 'dappled-cnf', 'version': 1, 'options': {'card_encoding': 'auto'}}
>>> resolve({"name": "dappled-cnf", "version": 0, "options": {}})
Traceback (most recent call last):
...
tilesolve.errors.InvalidProblem: proof made with encoding dappled-cnf v0; this version encodes v1: re-solve to re-certify
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable, Mapping

from tilesolve.deadline import Deadline
from tilesolve.errors import InvalidProblem

__all__ = ["NamedEncoding", "ENCODINGS", "encode", "resolve", "named_of"]


@dataclass(frozen=True)
class NamedEncoding:
    """One registered encoder.

    Attributes
    ----------
    name : str
    version : int
        Raised whenever the CNF the encoder builds for some problem and options changes.
    what : str
        The problems it takes, in words (for messages).
    defaults : Mapping
        Every option and its default value (JSON values).
    build : callable
        ``build(problem, options, deadline) -> encoding`` (the protocol of
        :class:`tilesolve.encodings.Encoding`); raises :class:`InvalidProblem` when the problem
        is not of its kind or an option is out of range.
    """

    name: str
    version: int
    what: str
    defaults: Mapping[str, Any]
    build: Callable[[Any, dict, Deadline | None], Any]


def _need(problem: Any, kind: type, entry: str, what: str) -> None:
    if not isinstance(problem, kind):
        raise InvalidProblem(f"encoding {entry} encodes {what}, not a {type(problem).__name__}")


def _dappled(problem, options, deadline):
    from tilesolve.encodings.dappled import CardEncoding, encode_cnf
    from tilesolve.model.dappled import DappledProblem

    _need(problem, DappledProblem, "dappled-cnf", "dappled problems")
    card = options["card_encoding"]
    if not isinstance(card, str) or card not in {c.value for c in CardEncoding}:
        raise InvalidProblem(f"encoding dappled-cnf: card_encoding must be one of "
                             f"{', '.join(c.value for c in CardEncoding)}, got {card!r}")
    return encode_cnf(problem, card_encoding=card, deadline=deadline)


def _board(problem, options, deadline):
    from tilesolve.encodings.wang import encode_wang
    from tilesolve.model.board import BoardProblem

    _need(problem, BoardProblem, "wang-board-cnf", "board problems")
    return encode_wang(problem, deadline=deadline)


def _packing(problem, options, deadline):
    from tilesolve.encodings.packing import encode_packing
    from tilesolve.model.packing import PackingProblem

    _need(problem, PackingProblem, "packing-cnf", "packing problems")
    anchor, amo = options["anchor_tile"], options["amo_tiles"]
    if anchor is not None and (isinstance(anchor, bool) or not isinstance(anchor, int)
                               or not 0 <= anchor < problem.n_tiles):
        raise InvalidProblem(f"encoding packing-cnf: anchor_tile must be null or a tile 0..{problem.n_tiles - 1}, "
                             f"got {anchor!r}")
    if not isinstance(amo, bool):
        raise InvalidProblem(f"encoding packing-cnf: amo_tiles must be true or false, got {amo!r}")
    return encode_packing(problem, anchor_tile=anchor, amo_tiles=amo, deadline=deadline)


def _tiles(problem, options, deadline):
    from tilesolve.encodings.wang_tiles import encode_tiles
    from tilesolve.model.board import BoardProblem

    _need(problem, BoardProblem, "wang-tiles-cnf", "Wang tile sets on boards")
    if problem.tileset.is_brick or (problem.boundary >= 0).any() or problem.max_h is not None \
            or problem.max_v is not None:
        raise InvalidProblem("encoding wang-tiles-cnf encodes explicit tile sets on boards with a free boundary "
                             "and no line limits")
    try:
        return encode_tiles(problem.board, problem.tileset, deadline=deadline)
    except ValueError as exc:
        raise InvalidProblem(f"encoding wang-tiles-cnf: {exc}") from None


def _shapes_tile(problem, options, deadline):
    from tilesolve.encodings.shapes import encode_tiling
    from tilesolve.model.shapes import ShapesProblem

    _need(problem, ShapesProblem, "shapes-tile-cnf", "polyform tiling problems")
    if problem.question != "tile":
        raise InvalidProblem("encoding shapes-tile-cnf encodes tiling questions, not classifications")
    return encode_tiling(problem)


def _shapes_corona(problem, options, deadline):
    from tilesolve.encodings.shapes import encode_coronas
    from tilesolve.model.shapes import ShapesProblem

    _need(problem, ShapesProblem, "shapes-corona-cnf", "polyform classifications")
    levels, blocked = options["levels"], options["blocked"]
    if isinstance(levels, bool) or not isinstance(levels, int) or not 1 <= levels <= 8:
        raise InvalidProblem(f"encoding shapes-corona-cnf: levels must be an integer in 1..8, got {levels!r}")
    try:
        return encode_coronas(problem, levels, blocked)
    except (KeyError, TypeError, ValueError):
        raise InvalidProblem("encoding shapes-corona-cnf: 'blocked' names a tile that is no placement of its "
                             "level") from None


#: Every named encoding, by name.
ENCODINGS: dict[str, NamedEncoding] = {e.name: e for e in (
    NamedEncoding("dappled-cnf", 1, "dappled problems (tilesolve.encodings.dappled.encode_cnf)",
                  {"card_encoding": "auto"}, _dappled),
    # v2: a line limit longer than a wrapping board's cycle gives a window of the cycle plus one
    # cell (v1 repeated the cycle up to the limit): the same constraint, another CNF text.
    NamedEncoding("wang-board-cnf", 2, "board problems (tilesolve.encodings.wang.encode_wang)", {}, _board),
    NamedEncoding("packing-cnf", 1, "packing problems (tilesolve.encodings.packing.encode_packing)",
                  {"anchor_tile": None, "amo_tiles": True}, _packing),
    NamedEncoding("wang-tiles-cnf", 1, "Wang tile sets on free boards (tilesolve.encodings.wang_tiles.encode_tiles)",
                  {}, _tiles),
    NamedEncoding("shapes-tile-cnf", 1, "polyform tilings of regions and tori (tilesolve.encodings.shapes."
                  "encode_tiling)", {}, _shapes_tile),
    NamedEncoding("shapes-corona-cnf", 1, "coronas around a polyform (tilesolve.encodings.shapes.encode_coronas)",
                  {"levels": 1, "blocked": []}, _shapes_corona),
)}


def encode(name: str, problem: Any, options: Mapping[str, Any] | None = None, *,
           deadline: Deadline | None = None):
    """The encoding ``name`` of ``problem`` with ``options`` (defaults filled in).

    The encoding's ``named`` attribute records ``{"name", "version", "options"}``: what a
    certificate stores so that the CNF can be re-derived.

    Raises
    ------
    InvalidProblem
        Unknown name or option, an option out of range, or a problem of another kind.
    """
    entry = ENCODINGS.get(name)
    if entry is None:
        raise InvalidProblem(f"unknown encoding {name!r}; this tilesolve has {', '.join(ENCODINGS)}")
    opts = dict(entry.defaults)
    extra = sorted(set(options or {}) - set(opts))
    if extra:
        raise InvalidProblem(f"encoding {name} has no option {extra[0]!r}"
                             + (f"; its options are {', '.join(opts)}" if opts else "; it takes none"))
    opts.update(options or {})
    enc = entry.build(problem, opts, deadline)
    enc.named = {"name": name, "version": entry.version, "options": opts}
    return enc


def resolve(spec: Any) -> tuple[NamedEncoding, dict]:
    """The registered encoder and options a recorded ``{"name", "version", "options"}`` stands for.

    Raises
    ------
    InvalidProblem
        With the one line to show: the record is malformed, names an encoding this tilesolve
        does not have, or another version than the one it builds.
    """
    if not isinstance(spec, Mapping) or set(spec) != {"name", "version", "options"} \
            or not isinstance(spec["name"], str) or not isinstance(spec["options"], Mapping) \
            or isinstance(spec["version"], bool) or not isinstance(spec["version"], int):
        raise InvalidProblem("the recorded encoding must be {\"name\": str, \"version\": int, \"options\": {...}}, "
                             f"got {str(spec)[:120]}")
    name, version = spec["name"], spec["version"]
    entry = ENCODINGS.get(name)
    if entry is None:
        raise InvalidProblem(f"proof made with encoding {name[:60]} v{version}; this tilesolve has no encoding "
                             f"of that name ({', '.join(ENCODINGS)}): re-solve to re-certify")
    if version != entry.version:
        raise InvalidProblem(f"proof made with encoding {name} v{version}; this version encodes v{entry.version}: "
                             "re-solve to re-certify")
    return entry, dict(spec["options"])


def named_of(encoding: Any) -> dict | None:
    """The ``{"name", "version", "options"}`` an encoding was built under (``None``: not a named one)."""
    return getattr(encoding, "named", None)
