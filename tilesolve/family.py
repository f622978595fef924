"""The family registry and the one solve pipeline (DESIGN.md, "Families and their contract").

A *family* is one kind of tiling question (dappled tilings, Wang tilings of boards, tile
packings, ...). Each family writes its layer modules (``model/``, ``constructive/``,
``encodings/``, ``verify/``, ``io/``, ``cli/``), declares one :class:`Family` record in its
facade module (``tilesolve/<family>.py``), and registers it once, under the entry-point group
``tilesolve.families`` in ``pyproject.toml``::

    [project.entry-points."tilesolve.families"]
    dappled = "tilesolve.families.dappled:FAMILY"

(or, at run time, with :func:`register`). Everything generic reads the registry: the solve
pipeline below, ``tilesolve verify`` (:func:`verify_file`), ``draw``, ``demo``,
``export dimacs``, ``backends`` and the CLI's command list. Adding a family edits no shared
list. ``docs/ADDING_A_FAMILY.md`` walks through it.

Routes
------
Every route of every family has one signature, ``route(problem, run) -> Solution``, where
``run`` is a :class:`RunOptions`: the resolved seed, the :class:`~tilesolve.deadline.Deadline`
of the whole run, progress, solver, workers, cluster, and the family's own options. A user's
``method=callable`` has the same signature.

The pipeline (:func:`solve`) is written once: look the method up (``"auto"`` asks the
family), draw and record a seed when none is given, show progress, fall back to the
family's fallback route when ``auto``'s choice does not apply or its output fails
verification, verify every tiling with the family's independent checker, and stamp the
provenance (method, seed, time, notes).

Examples
--------
>>> from tilesolve.model.dappled import DappledProblem
>>> s = solve(DappledProblem.from_strings("6x4", ["H0=2", "V1=2"]), seed=3)
>>> s.status.value, s.seed
('sat', 3)
>>> sorted(f.name for f in families())[:4]
['aperiodic', 'board', 'dappled', 'packing']
"""

from __future__ import annotations

import functools
import os
import secrets
from dataclasses import dataclass, field
from typing import Any, Callable, Iterable, Mapping, Sequence

from tilesolve.deadline import Deadline, TimeLimitReached
from tilesolve.errors import InternalError, InvalidProblem, MethodNotApplicable
from tilesolve.model.run import RunOptions
from tilesolve.model.solution import CountResult, Solution, Status

__all__ = [
    "RunOptions",
    "Route",
    "Codec",
    "Demo",
    "Field",
    "Form",
    "form_size",
    "cnf_estimate",
    "cnf_size_refusal",
    "DEFAULT_MAX_CNF",
    "Family",
    "register",
    "unregister",
    "families",
    "get",
    "family_of",
    "codec_of",
    "solve",
    "count",
    "draw_seed",
    "interrupted",
    "raise_if_interrupted",
    "read_document",
    "verify_document",
    "verify_file",
    "write_solution",
    "solution_text",
    "backend_report",
    "render",
    "iter_demos",
    "draw_solution",
    "ENTRY_POINT_GROUP",
]

#: Entry-point group under which packages declare their families.
ENTRY_POINT_GROUP = "tilesolve.families"


#: The one route signature: ``route(problem, run) -> Solution``.
Route = Callable[[Any, RunOptions], Solution]


@dataclass(frozen=True)
class Codec:
    """One versioned JSON file format of a family.

    Attributes
    ----------
    format : str
        The ``"format"`` field, e.g. ``"tilesolve/dappled-solution"``.
    versions : frozenset of int
        Versions this build reads.
    read : callable
        ``read(doc, source) -> (problem, solution or None)``: checks every field's type and
        raises :class:`~tilesolve.errors.InvalidProblem` naming the file and field.
        Problem-only formats return ``None`` as the solution.
    write : callable or None
        ``write(problem, solution) -> dict`` (JSON-ready; numpy arrays allowed).
    """

    format: str
    versions: frozenset[int]
    read: Callable[[dict, str], tuple[Any, Solution | None]]
    write: Callable[[Any, Solution], dict] | None = None


@dataclass(frozen=True)
class Demo:
    """One showcase problem for ``tilesolve demo``.

    ``make()`` builds the problem; the demo runner solves it with ``method``, writes
    ``<name>.json`` and a picture drawn with ``draw_options``.
    """

    name: str
    caption: str
    make: Callable[[], Any]
    method: str = "auto"
    draw_options: Mapping[str, Any] = field(default_factory=dict)


@dataclass(frozen=True)
class Field:
    """One parameter of a family's problem, as the studio's form shows it.

    Attributes
    ----------
    name : str
        Key of the value in the form's values (a JSON object).
    kind : str
        ``"int"``, ``"float"``, ``"text"``, ``"bool"``, ``"choice"`` (one of ``choices``) or
        ``"size"`` (``"WxH"`` text, at most ``high`` cells) or ``"cells"``: a grid the user
        paints, sent as a list of rows of ints (``-1`` = unset).
    label, help : str
        What the form shows.
    default
        The value a new form starts with (``None``: empty).
    low, high : float, optional
        Limits of ``int``/``float`` values (checked again by :meth:`Form.values`).
    choices : tuple of str
        For ``choice``.
    option : str, optional
        The CLI option that takes this value (``"--size"``): the studio's "copy as CLI command".
    extent : callable, optional
        ``cells`` only: ``extent(values) -> (rows, cols, low, high)``, the grid's shape and its
        cell values' range for the other values of the form.
    """

    name: str
    kind: str
    label: str
    default: Any = None
    help: str = ""
    low: float | None = None
    high: float | None = None
    choices: tuple[str, ...] = ()
    option: str | None = None
    extent: Callable[[Mapping[str, Any]], tuple[int, int, int, int]] | None = None

    def public(self) -> dict:
        """The field as JSON for the page (without the callables)."""
        return {k: getattr(self, k) for k in ("name", "kind", "label", "default", "help", "low", "high",
                                               "choices", "option")}


@dataclass(frozen=True)
class Form:
    """How a family's problem is posed from a form (the studio) and as a command line.

    Attributes
    ----------
    fields : tuple of Field
    build : callable
        ``build(values) -> (problem, options)``: the problem (and the ``options`` of
        :func:`solve`) for checked values; raises :class:`InvalidProblem` with the CLI's messages.
        ``values`` holds every field (defaults filled in) and ``"seed"`` (an int, drawn when
        not given: problems with random parts, e.g. a random boundary, use it).
    command : callable
        ``command(values) -> (words, files)``: the words of the ``tilesolve`` command (after
        ``tilesolve``) that poses the same problem, without seed, method and output options,
        and the files it reads (``{name: text}``, e.g. painted cells as a text grid).
    window : callable, optional
        Families with an infinite plane: ``window(values, x0, y0, rows, cols) -> (problem,
        method, options)``, the problem of one window (the studio's pan-and-zoom view).
    cells : callable, optional
        ``cells(problem, solution) -> 2-D int array``: the solution per cell, in the values
        of the form's ``cells`` fields (clicking a cell of the picture fixes it to this value).
    """

    fields: tuple[Field, ...]
    build: Callable[[Mapping[str, Any]], tuple[Any, Mapping[str, Any]]]
    command: Callable[[Mapping[str, Any]], tuple[list[str], dict[str, str]]]
    window: Callable[..., tuple[Any, str, Mapping[str, Any]]] | None = None
    cells: Callable[[Any, Solution], Any] | None = None

    def values(self, given: Mapping[str, Any]) -> dict[str, Any]:
        """``given`` checked against the fields (types, limits, choices), defaults filled in.

        Unknown keys and values of the wrong type raise :class:`InvalidProblem` (one line
        naming the field). ``cells`` grids are checked for shape by :attr:`Field.extent`.
        """
        if not isinstance(given, Mapping):
            raise InvalidProblem("form values must be a JSON object")
        names = {f.name for f in self.fields} | {"seed"}
        extra = sorted(set(given) - names)
        if extra:
            raise InvalidProblem(f"unknown field {extra[0]!r}; fields are {', '.join(sorted(names))}")
        out: dict[str, Any] = {}
        for f in self.fields:
            out[f.name] = _field_value(f, given.get(f.name, f.default))
        seed = given.get("seed")
        out["seed"] = draw_seed() if seed is None else _check_seed(seed)
        for f in self.fields:
            if f.kind == "cells" and out[f.name] is not None:
                rows, cols, lo, hi = f.extent(out)
                grid = out[f.name]
                if len(grid) != rows or any(len(r) != cols for r in grid):
                    raise InvalidProblem(f"{f.label}: the grid must be {cols}x{rows} (WxH) for these values")
                bad = [v for r in grid for v in r if v != -1 and not lo <= v <= hi]
                if bad:
                    raise InvalidProblem(f"{f.label}: cell value {bad[0]} is outside {lo}..{hi} (-1 = unset)")
        return out


def form_size(text: str) -> tuple[int, int]:
    """``(rows, cols)`` of a checked ``size`` field value ``"WxH"``."""
    w, h = (int(v) for v in text.lower().split("x"))
    return h, w


#: Most cells a painted ``cells`` field may hold (checked before the grid is read).
MAX_FORM_CELLS = 1 << 20


def _field_value(f: Field, v: Any) -> Any:
    """One field's value, checked (see :meth:`Form.values`)."""
    if v is None:
        return None
    what = f"{f.label} ({f.name})"
    if f.kind in ("int", "float"):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or (f.kind == "int" and int(v) != v):
            raise InvalidProblem(f"{what} must be {'a whole number' if f.kind == 'int' else 'a number'}, got {v!r}")
        v = int(v) if f.kind == "int" else float(v)
        if (f.low is not None and v < f.low) or (f.high is not None and v > f.high):
            raise InvalidProblem(f"{what} must be in {f.low:g}..{f.high:g}, got {v}")
        return v
    if f.kind == "bool":
        if not isinstance(v, bool):
            raise InvalidProblem(f"{what} must be true or false, got {v!r}")
        return v
    if f.kind == "size":
        import re

        m = re.fullmatch(r"\s*(\d{1,9})\s*[xX×]\s*(\d{1,9})\s*", v) if isinstance(v, str) else None
        if m is None:
            raise InvalidProblem(f"{what} must be WxH (columns x rows), e.g. 16x12, got {v!r}")
        w, h = int(m.group(1)), int(m.group(2))
        if w < 1 or h < 1:
            raise InvalidProblem(f"{what} must be at least 1x1, got {w}x{h}")
        if f.high is not None and w * h > f.high:
            raise InvalidProblem(f"{what} {w}x{h} has {w * h:,} cells; at most {int(f.high):,} here")
        return f"{w}x{h}"
    if f.kind in ("text", "choice"):
        if not isinstance(v, str) or len(v) > 10_000:
            raise InvalidProblem(f"{what} must be a short text")
        if f.kind == "choice" and v not in f.choices:
            raise InvalidProblem(f"{what} must be one of {', '.join(f.choices)}, got {v!r}")
        return v
    if f.kind == "cells":
        if not isinstance(v, list) or not all(isinstance(r, list) for r in v):
            raise InvalidProblem(f"{what} must be a list of rows")
        if sum(len(r) for r in v) > MAX_FORM_CELLS:
            raise InvalidProblem(f"{what} has more than {MAX_FORM_CELLS:,} cells")
        if not all(isinstance(x, int) and not isinstance(x, bool) for r in v for x in r):
            raise InvalidProblem(f"{what} must hold whole numbers")
        return v
    raise InternalError(f"field {f.name!r} has unknown kind {f.kind!r}")


@dataclass(frozen=True)
class Family:
    """Everything generic code needs to know about one family.

    Attributes
    ----------
    name : str
        Registry key (``"dappled"``, ``"board"``, ``"packing"``, ...).
    title : str
        One line for listings.
    problem_type : type
        Problems of this family are instances of it.
    routes : Mapping[str, Route]
        Routes by name (the CLI's ``--method`` choices are ``auto`` plus these keys).
    auto : callable
        ``auto(problem) -> route name``.
    verify : callable
        ``verify(problem, tiling) -> list of violations`` (empty when valid): the family's
        independent checker (``tilesolve.verify``).
    fallback : str or None
        Route used when ``auto``'s choice raises MethodNotApplicable or returns a tiling that
        fails verification (a constructive algorithm without a proof).
    objective : callable or None
        ``objective(problem, tiling) -> int or None``: the value an ``optimal`` answer claims
        (e.g. the Hamming distance of closest tilings); ``None`` when the problem has none.
    count : callable or None
        ``count(problem, *, method, time_limit, progress, force) -> CountResult``.
    encode : callable or None
        ``encode(problem)`` -> an encoding with the protocol of
        :class:`tilesolve.encodings.Encoding` (DIMACS export).
    codecs : tuple of Codec
        File formats; the first solution format is the one solutions are written in.
    draw : callable or None
        ``draw(problem, solution, path, fmt, **options)`` writes an ``"svg"`` or ``"png"``
        picture of a solution.
    demos : tuple of Demo
    commands : tuple of str
        ``"module:attribute"`` of the family's click commands (loaded only when used).
    route_help : Mapping[str, str]
        One line per route, for ``--help`` and ``tilesolve backends``.
    form : Form or None
        The problem's parameters as a form (``tilesolve studio``) and as a command line.
    refutations : callable or None
        ``refutations(problem, solution) -> [(what, problem of the CNF, evidence), ...]``: every
        refutation a solution claims, for ``tilesolve verify`` to re-derive its CNF (the
        evidence's named ``encoding``, :mod:`tilesolve.encodings.registry`) and re-check its
        proof. ``None``: an ``unsat`` solution's own claim (its problem, its ``stats``).
    """

    name: str
    title: str
    problem_type: type
    routes: Mapping[str, Route]
    auto: Callable[[Any], str]
    verify: Callable[[Any, Any], Sequence]
    fallback: str | None = None
    objective: Callable[[Any, Any], int | None] | None = None
    count: Callable[..., CountResult] | None = None
    encode: Callable[[Any], Any] | None = None
    codecs: tuple[Codec, ...] = ()
    draw: Callable[..., None] | None = None
    demos: tuple[Demo, ...] = ()
    commands: tuple[str, ...] = ()
    route_help: Mapping[str, str] = field(default_factory=dict)
    form: Form | None = None
    refutations: Callable[[Any, Solution], Sequence[tuple[str, Any, Mapping[str, Any]]]] | None = None

    @property
    def methods(self) -> tuple[str, ...]:
        """``("auto", *routes)``: the ``method`` values :func:`solve` accepts."""
        return ("auto",) + tuple(self.routes)

    @property
    def solution_codec(self) -> Codec:
        """The codec solutions are written with."""
        for c in self.codecs:
            if c.write is not None:
                return c
        raise InvalidProblem(f"family {self.name!r} has no solution file format")

    def lookup(self, method: str | Route, problem: Any) -> tuple[Route, str]:
        """The route for ``method`` (a name, ``"auto"`` or a callable) and its name."""
        if callable(method):
            return method, getattr(method, "__name__", "custom")
        name = self.auto(problem) if method == "auto" else method
        if name not in self.routes:
            raise InvalidProblem(f"unknown method {method!r} for {self.name} problems; "
                                 f"choose one of {', '.join(self.methods)}")
        return self.routes[name], name


# ----------------------------------------------------------------------------- registry
_REGISTRY: dict[str, Family] = {}
_LOADED = False


def register(family: Family) -> Family:
    """Add ``family`` to the registry (a name registered twice is an error).

    Facade modules call it when imported; the entry points make sure they are imported.
    """
    old = _REGISTRY.get(family.name)
    if old is not None and old is not family:
        raise InvalidProblem(f"a family named {family.name!r} is registered already")
    taken = {c.format for f in _REGISTRY.values() if f is not old for c in f.codecs}
    clash = taken & {c.format for c in family.codecs}
    if clash:
        raise InvalidProblem(f"file format {sorted(clash)[0]!r} belongs to another family")
    _REGISTRY[family.name] = family
    return family


def unregister(name: str) -> None:
    """Remove a family (tests register throw-away families and remove them)."""
    _REGISTRY.pop(name, None)


def _load_builtin() -> None:
    """Load the families declared under :data:`ENTRY_POINT_GROUP` (once)."""
    global _LOADED
    if _LOADED:
        return
    _LOADED = True
    from importlib.metadata import entry_points

    for ep in sorted(entry_points(group=ENTRY_POINT_GROUP), key=lambda e: e.name):
        if ep.name not in _REGISTRY:
            _load_entry(ep)


def _load_entry(ep) -> None:
    """Import one entry point's family (its facade registers it) and record it."""
    fam = ep.load()
    if not isinstance(fam, Family):
        raise InternalError(f"entry point {ep.value} is not a tilesolve Family")
    _REGISTRY.setdefault(fam.name, fam)


def families() -> list[Family]:
    """Every registered family, in registration order."""
    _load_builtin()
    return list(_REGISTRY.values())


def get(name: str) -> Family:
    """The family called ``name`` (only its own entry point is loaded, if it is not registered yet)."""
    if name in _REGISTRY:
        return _REGISTRY[name]
    if not _LOADED:
        from importlib.metadata import entry_points

        for ep in entry_points(group=ENTRY_POINT_GROUP, name=name):
            _load_entry(ep)
        if name in _REGISTRY:
            return _REGISTRY[name]
    _load_builtin()
    try:
        return _REGISTRY[name]
    except KeyError:
        raise InvalidProblem(f"unknown family {name!r}; known: {', '.join(_REGISTRY)}") from None


def family_of(problem: Any) -> Family:
    """The family whose problem type ``problem`` is."""
    for fam in list(_REGISTRY.values()):  # usually registered already, by importing its facade
        if isinstance(problem, fam.problem_type):
            return fam
    for fam in families():
        if isinstance(problem, fam.problem_type):
            return fam
    raise InvalidProblem(f"no tilesolve family solves a {type(problem).__name__}")


def codec_of(fmt: str) -> tuple[Family, Codec]:
    """The family and codec of a file format name."""
    for fam in families():
        for c in fam.codecs:
            if c.format == fmt:
                return fam, c
    known = sorted(c.format for f in families() for c in f.codecs)
    raise InvalidProblem(f"unknown format {fmt!r}; this tilesolve reads {', '.join(known)}")


# ----------------------------------------------------------------------------- pipeline
def draw_seed() -> int:
    """A fresh seed (recorded with the answer, so every run can be repeated)."""
    return secrets.randbelow(2**31)


def solve(
    problem: Any,
    method: str | Route = "auto",
    *,
    seed: int | None = None,
    time_limit: float | None = None,
    progress: bool = False,
    solver: str | None = None,
    workers: int | None = None,
    cluster: Any = None,
    options: Mapping[str, Any] | None = None,
) -> Solution:
    """Solve ``problem`` with its family's routes and verify the answer independently.

    Parameters
    ----------
    problem
        A problem of a registered family.
    method : str or callable
        ``"auto"``, a route name of the family, or a callable ``route(problem, run)``.
    seed : int, optional
        Drawn (and recorded in ``Solution.seed``) when not given.
    time_limit : float, optional
        Seconds for the whole run; expiry gives status ``unknown``, never ``unsat``.
    progress, solver, workers, cluster, options
        See :class:`RunOptions`.

    Returns
    -------
    Solution
        ``sat``/``optimal`` with a verified tiling, ``unsat`` with a reason, or ``unknown``.

    Raises
    ------
    MethodNotApplicable
        An explicitly requested route cannot take the problem (the message names one that can).
    InternalError
        A route returned a tiling that fails verification and no fallback exists (a bug).
    """
    fam = family_of(problem)
    if time_limit is not None and not (time_limit > 0 and time_limit < float("inf")):
        raise InvalidProblem(f"time limit must be a positive number of seconds, got {time_limit}")
    run = RunOptions(
        seed=draw_seed() if seed is None else _check_seed(seed),
        deadline=Deadline(time_limit),
        progress=progress,
        solver=solver,
        workers=workers,
        cluster=cluster,
        options=dict(options or {}),
    )
    return run_route(fam, problem, method, run)


def _check_seed(seed: Any) -> int:
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        import numpy as np

        if isinstance(seed, np.integer) and seed >= 0:
            return int(seed)
        raise InvalidProblem(f"seed must be a non-negative integer, got {seed!r}")
    return seed


def run_route(fam: Family, problem: Any, method: str | Route, run: RunOptions) -> Solution:
    """The pipeline of :func:`solve` once the run is resolved (also used by crosschecks)."""
    from tilesolve.engine.progress import status_line

    route, name = fam.lookup(method, problem)
    notes: list[str] = []
    if method == "auto":
        notes.append(f"auto chose {name!r}")
    with status_line(f"{fam.name}: solving with {name!r}", run.progress):
        try:
            try:
                sol = route(problem, run)
            except MethodNotApplicable as exc:
                if method != "auto" or fam.fallback is None or name == fam.fallback:
                    raise
                notes.append(f"{name!r} not applicable ({exc}); solved with {fam.fallback!r}")
                name = fam.fallback
                sol = fam.routes[name](problem, run)
        except TimeLimitReached as exc:  # a route out of time while encoding or building
            sol = Solution(Status.UNKNOWN, None, name, None, run.seed, run.deadline.elapsed(), reason=str(exc))
    if _uncertified(sol) and name != "sat":
        sol = _certify_infeasible(fam, problem, run, name, sol)
    bad = fam.verify(problem, sol.tiling) if sol.status.has_tiling else ()
    if bad and method == "auto" and fam.fallback is not None and name != fam.fallback:
        notes.append(f"{name!r} output failed verification ({len(bad)} violations, first: {bad[0]}); "
                     f"fell back to {fam.fallback!r}")
        name = fam.fallback
        with status_line(f"{fam.name}: solving with {name!r}", run.progress):
            sol = fam.routes[name](problem, run)
        bad = fam.verify(problem, sol.tiling) if sol.status.has_tiling else ()
    if bad:
        raise InternalError(f"method {sol.method or name!r} returned a tiling that fails verification "
                            f"({len(bad)} violations, first: {bad[0]})")
    if sol.status.has_tiling and fam.objective is not None:
        value = fam.objective(problem, sol.tiling)
        if sol.objective is not None and value != sol.objective:
            raise InternalError(f"method {name!r} reported objective {sol.objective}, the tiling has {value}")
        sol = sol.replace(objective=value)
    return sol.replace(
        method=sol.method or name,
        notes=tuple(notes) + sol.notes,
        time_s=run.deadline.elapsed(),
        seed=run.seed if sol.seed is None else sol.seed,
        renderer=functools.partial(render, problem) if fam.draw is not None else None,
    )


def _certify_infeasible(fam: Family, problem: Any, run: RunOptions, name: str, sol: Solution) -> Solution:
    """An infeasibility claimed without a checked proof (CP-SAT's, or a constructive route's
    clash) re-decided by the family's ``sat`` route, whose unsat carries a checked DRAT proof,
    within what is left of the run's deadline; ``unknown`` ("uncertified: ...") when that
    fails, so that ``unsat`` always comes with a checked proof."""
    from tilesolve.engine.certificates import UNCERTIFIED
    from tilesolve.engine.progress import status_line

    if sol.status is Status.UNSAT:
        claim = f"found it unsatisfiable without a checked proof ({sol.reason})"
    else:
        claim = "(CP-SAT) proved infeasibility without a proof"

    def uncertified(why: str) -> Solution:
        if sol.status is Status.UNKNOWN:
            return sol.replace(reason=f"{sol.reason}; {why}")
        return sol.replace(status=Status.UNKNOWN, reason=f"{UNCERTIFIED} {name!r} {claim}; {why}")

    if "sat" not in fam.routes:
        return uncertified(f"the {fam.name} family has no 'sat' route to certify it")
    if run.deadline.expired():
        return uncertified("no time left to certify it with the 'sat' route")
    with status_line(f"{fam.name}: certifying {name!r}'s infeasibility with 'sat'", run.progress):
        try:
            cert = fam.routes["sat"](problem, run)
        except (TimeLimitReached, MethodNotApplicable) as exc:
            return uncertified(f"the 'sat' route could not certify it: {exc}")
    if cert.status is Status.UNSAT:
        return cert.with_note(f"{name!r} {claim}; certified by the 'sat' route")
    if cert.status.has_tiling:
        raise InternalError(f"{name!r} said infeasible but the 'sat' route found a tiling")
    return uncertified(f"the 'sat' route could not certify it: {cert.reason}")


def _uncertified(sol: Solution) -> bool:
    """An infeasibility claimed without a checked proof: CP-SAT's (reported ``unknown``) or
    any ``unsat`` whose stats do not record a verified proof."""
    from tilesolve.engine.certificates import UNCERTIFIED

    if sol.status is Status.UNSAT:
        return sol.stats.get("proof_status") != "verified"
    return sol.status is Status.UNKNOWN and (bool(sol.stats.get("cpsat_infeasible"))
                                             or (sol.reason or "").startswith(UNCERTIFIED))


def interrupted(result: Solution | CountResult) -> bool:
    """True when Ctrl-C stopped the run: the engine catches it inside a solver and returns
    ``unknown`` with a reason (a note, for counts) starting with "interrupted".

    The CLI exits 130 and writes nothing for such an answer; a time limit is not an interruption.
    """
    why = getattr(result, "reason", None) or getattr(result, "note", None) or ""
    return result.status is Status.UNKNOWN and why.startswith("interrupted")


def raise_if_interrupted(result):
    """Return ``result``, or raise KeyboardInterrupt if Ctrl-C stopped it (so loops over routes,
    trials or demos stop, and the CLI exits 130 without writing)."""
    if interrupted(result):
        raise KeyboardInterrupt
    return result


def count(problem: Any, *, method: str = "auto", time_limit: float | None = None, progress: bool = False,
          force: bool = False) -> CountResult:
    """Count the solutions of ``problem`` exactly with its family's counter."""
    fam = family_of(problem)
    if fam.count is None:
        raise MethodNotApplicable(f"{fam.name} problems have no counter")
    return fam.count(problem, method=method, time_limit=time_limit, progress=progress, force=force)


def cnf_estimate(problem: Any) -> tuple[int, int, int] | None:
    """``(variables, clauses, literals)`` the CNF of ``problem`` is estimated to hold, before
    encoding, or None where no model exists (:func:`tilesolve.encodings.sizing.cnf_estimate`)."""
    from tilesolve.encodings.sizing import cnf_estimate as estimate

    return estimate(problem)


#: Most bytes of DIMACS text a CNF may be estimated at before it is built (``--max-cnf``'s default).
DEFAULT_MAX_CNF = 1 << 30


def cnf_size_refusal(problem: Any, limit: int) -> str | None:
    """Why the CNF of ``problem`` is not built: its :func:`cnf_estimate` as DIMACS text exceeds
    ``limit`` bytes (``export dimacs`` and ``verify``'s ``--max-cnf``); ``None`` when it fits or
    when no estimate exists."""
    from tilesolve.io.units import big, human_bytes

    sized = cnf_estimate(problem)
    if sized is None:
        return None
    n_vars, clauses, lits = sized
    text = lits * (len(str(n_vars)) + 2) + 2 * clauses  # a literal, its sign and a space; "0\n"
    if text <= limit:
        return None
    return (f"the CNF of {problem.describe()} would hold about {big(clauses)} clauses and {big(lits)} literals, "
            f"about {human_bytes(text)} of DIMACS text (and as much memory while encoding), more than --max-cnf "
            f"{human_bytes(limit)}")


# ----------------------------------------------------------------------------- files
def read_document(path: str | os.PathLike) -> tuple[Family, Codec, dict]:
    """Read a tilesolve JSON file and find its family and codec (version checked)."""
    from tilesolve.io.jsonio import read_json

    doc = read_json(path)
    return _identify(doc, str(path)) + (doc,)


def _identify(doc: Any, source: str) -> tuple[Family, Codec]:
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


#: Violation lines printed before "... and N more".
MAX_SHOWN = 50


@dataclass(frozen=True)
class FileReport:
    """What :func:`verify_file` found: the exit code (0 valid, 1 a false claim) and lines."""

    exit_code: int
    lines: tuple[str, ...]

    @property
    def ok(self) -> bool:
        return self.exit_code == 0


def writing_proofs(directory: str | os.PathLike | None):
    """Context manager: write each checked unsat proof (CNF + DRAT) to ``directory``
    (:func:`tilesolve.engine.certificates.writing_proofs`; the CLI's ``--proof-dir``)."""
    from tilesolve.engine.certificates import writing_proofs as writing

    return writing(directory)


def _refutations(fam: Family, problem: Any, sol: Solution) -> Sequence[tuple[str, Any, Mapping[str, Any]]]:
    """Every refutation ``sol`` claims: ``(what, problem of its CNF, evidence)``."""
    if fam.refutations is not None:
        return fam.refutations(problem, sol)
    return [("the unsat claim", problem, sol.stats)] if sol.status is Status.UNSAT else []


#: What re-checking an unsat claim needs, for the lines that say it was not re-checked.
RECHECK_NEEDS = ("re-checking needs the DRAT proof: solve with --proof-dir DIR, then "
                 "tilesolve verify FILE --proof-dir DIR")


#: How a refutation whose CNF is too large to re-derive (:func:`cnf_size_refusal`) is reported.
TOO_LARGE = "cannot be re-derived here"


def _recheck(claims, proof_dir, workers: int, max_cnf: int) -> tuple[list[str], list[str], int]:
    """Re-derive and (with ``proof_dir``) re-check each claimed refutation
    (:func:`tilesolve.engine.certificates.recheck_all`, on ``workers`` processes): ``(refused
    lines, detail lines, refutations re-checked)``. A claim whose CNF is estimated above
    ``max_cnf`` bytes of DIMACS text (:func:`cnf_size_refusal`) is not re-derived, and so not
    confirmed."""
    from tilesolve.engine.certificates import recheck_all

    claims = [(what, problem, evidence if isinstance(evidence, Mapping) else {}) for what, problem, evidence in claims]
    refused, details, checked = [], [], 0
    sized = [(what, cnf_size_refusal(problem, max_cnf)) for what, problem, _ in claims]
    for what, why in sized:
        if why is not None:
            line = f"{what}: the certificate {TOO_LARGE}: {why}; raise --max-cnf to re-derive it"
            refused.append(line)
            details.append(f"  {line}")
    claims = [c for c, (_, why) in zip(claims, sized) if why is None]
    for (what, _, _), rc in zip(claims, recheck_all(claims, proof_dir, workers=workers)):
        if rc.verdict == "refused":
            refused.append(f"{what}: {rc.lines[-1]}")
        checked += rc.ok
        details += [f"  {what}: {ln}" for ln in rc.lines]
    return refused, details, checked


def verify_document(doc: dict, source: str = "<document>", proof_dir: str | os.PathLike | None = None, *,
                    workers: int = 1, max_cnf: int = DEFAULT_MAX_CNF) -> FileReport:
    """Check every claim a solution document makes (``tilesolve verify``).

    The tiling must pass the family's independent verifier; the status must match the
    file's content (``sat``/``optimal`` need a tiling, ``unsat``/``unknown`` must hold none);
    ``optimal`` needs a problem with an objective and the recorded objective must equal the
    tiling's value. Field types are checked by the family's codec.

    Every refutation the file claims (an ``unsat`` answer, a report's refuted boards:
    :attr:`Family.refutations`) is bound to the problem the file states: its CNF is re-derived
    with the named encoding it records and must have the recorded SHA-256 ("the CNF is not the
    encoding of this problem" otherwise). With ``proof_dir`` each DRAT proof, located by the
    recorded digests, is checked against the re-derived formula. Without it an ``unsat`` claim
    is reported as *not* re-checked (exit 1, the status's code). ``workers`` local processes
    share the re-checking of many refutations (a report's). A CNF estimated above ``max_cnf``
    bytes of DIMACS text is not built: its claim is not confirmed (exit 1), and the line says
    so with the estimate.

    The first line is the verdict (``ok: ...`` only when every check passed); detail lines follow,
    indented.
    """
    fam, codec = _identify(doc, source)
    problem, sol = codec.read(doc, source)
    if sol is None:
        raise InvalidProblem(f"{source}: a {codec.format} file holds no solution to verify; solve it first")
    what = problem.describe() if hasattr(problem, "describe") else fam.name
    false: list[str] = []
    if sol.tiling is None:
        if sol.status.has_tiling:
            false.append(f"status {sol.status.value!r} claims a tiling, but the file holds none")
        elif sol.status is Status.UNSAT:
            return _verify_unsat(fam, problem, sol, source, proof_dir, workers, max_cnf)
        else:
            why = f" ({sol.reason})" if sol.reason else ""
            return FileReport(sol.status.exit_code, (f"{source}: status {sol.status.value}{why}; "
                                                     "the file holds no tiling to verify",))
    else:
        if not sol.status.has_tiling:
            false.append(f"status {sol.status.value!r} claims no tiling was found, but the file holds one")
        violations = list(fam.verify(problem, sol.tiling))
        if violations:
            n = len(violations)
            lines = [f"{source}: {n} violation{'s' if n != 1 else ''} of {what}"]
            lines += [f"  {v}" for v in violations[:MAX_SHOWN]]
            if n > MAX_SHOWN:
                lines.append(f"  ... and {n - MAX_SHOWN} more")
            return FileReport(1, tuple(lines + [f"  {f}" for f in false]))
        value = fam.objective(problem, sol.tiling) if fam.objective is not None else None
        if value is None:
            if sol.status is Status.OPTIMAL:
                false.append("status 'optimal' claims an optimum, but the problem has no objective")
            if sol.objective is not None:
                false.append(f"objective {sol.objective} recorded, but the problem has no objective")
        elif sol.objective != value:
            false.append(f"recorded objective {sol.objective}, but the tiling's value is {value}")
    claims = _refutations(fam, problem, sol) if not false else []
    refused, details, checked = _recheck(claims, proof_dir, workers, max_cnf)
    false += refused
    if false:
        verdict = "NOT confirmed" if all(TOO_LARGE in f for f in false) else "false"
        return FileReport(1, (f"{source}: the file's claims are {verdict}",) + tuple(f"  {f}" for f in false))
    head = f"ok: {source} is a valid tiling of {what}"
    if claims and proof_dir is not None:
        head += f"; {checked} refutation(s) re-checked: each DRAT proof refutes the CNF re-derived from the problem"
    elif claims:
        head += (f"; the CNFs of {len(claims)} refutation(s) re-derived from the problem match their digests, "
                 "but their proofs were NOT re-checked (give --proof-dir DIR)")
    return FileReport(0, (head,) + tuple(details))


def _verify_unsat(fam: Family, problem: Any, sol: Solution, source: str, proof_dir, workers: int,
                  max_cnf: int) -> FileReport:
    """:func:`verify_document` of a file whose status is ``unsat``."""
    why = f" ({sol.reason})" if sol.reason else ""
    claims = _refutations(fam, problem, sol)
    if not claims:
        return FileReport(1, (f"{source}: status unsat NOT confirmed: the file names no refutation to re-check",))
    refused, details, _ = _recheck(claims, proof_dir, workers, max_cnf)
    if refused:
        size_only = all(TOO_LARGE in line for line in refused)
        head = f"{source}: status unsat NOT confirmed: its certificate {TOO_LARGE if size_only else 'does not hold'}"
        return FileReport(1, (head,) + tuple(details))
    if proof_dir is None:
        head = (f"{source}: status unsat{why}; the file holds no tiling to verify, and the unsat claim was NOT "
                f"re-checked: {RECHECK_NEEDS}")
        return FileReport(sol.status.exit_code, (head,) + tuple(details))
    head = f"ok: {source}: unsat re-checked: the DRAT proof refutes the CNF re-derived from the file's problem"
    return FileReport(0, (head,) + tuple(details))


def verify_file(path: str | os.PathLike, proof_dir: str | os.PathLike | None = None, *,
                workers: int = 1, max_cnf: int = DEFAULT_MAX_CNF) -> FileReport:
    """:func:`verify_document` on a file (one-line errors for unreadable or malformed files)."""
    from tilesolve.io.jsonio import read_json

    return verify_document(read_json(path), str(path), proof_dir, workers=workers, max_cnf=max_cnf)


def write_solution(path: str | os.PathLike, problem: Any, solution: Solution) -> None:
    """Write ``solution`` in its family's solution format (atomically)."""
    from tilesolve.io.atomic import write_text_atomic

    write_text_atomic(path, solution_text(problem, solution))


def solution_text(problem: Any, solution: Solution) -> str:
    """The JSON text of a solution file."""
    from tilesolve.io.jsonio import dumps

    return dumps(family_of(problem).solution_codec.write(problem, solution))


def draw_solution(path: str | os.PathLike, problem: Any, solution: Solution, *, fmt: str | None = None,
                  **options: Any) -> None:
    """Draw a solution with its family's drawing (``fmt`` from the file suffix by default)."""
    fam = family_of(problem)
    if fam.draw is None:
        raise MethodNotApplicable(f"{fam.name} solutions have no drawing")
    fmt = fmt or os.path.splitext(str(path))[1].lstrip(".").lower()
    if fmt not in ("svg", "png"):
        raise InvalidProblem(f"{path}: pictures are .svg or .png files")
    if not solution.status.has_tiling:
        raise InvalidProblem(f"status {solution.status.value}: no tiling to draw")
    fam.draw(problem, solution, path, fmt, **options)


def backend_report() -> tuple[list[tuple[str, ...]], list[tuple[str, ...]], bool]:
    """What ``tilesolve backends`` prints: ``(backend rows, route rows, a required backend is
    missing)``; backend rows are (name, kind, installed, version or reason, used by), route
    rows (family, route, what it does)."""
    from tilesolve.engine.backends import OTHER_BACKENDS, dist_version, probe, sat_backends

    rows = []
    pysat = f"python-sat {dist_version('python-sat')}"
    sat = sat_backends()
    for name, ok, used_by in sat:
        rows.append((name, "SAT", "yes" if ok else "no", pysat if ok else "not in this python-sat build", used_by))
    missing = not any(ok for _, ok, _ in sat)
    for b in OTHER_BACKENDS:
        ok, info = probe(b)
        missing |= not ok and not b.optional
        rows.append((b.name, b.kind, "yes" if ok else ("no (optional)" if b.optional else "NO"), info, b.used_by))
    routes = [(fam.name, route, fam.route_help.get(route, "")) for fam in families() for route in fam.routes]
    return rows, routes, missing


def render(problem: Any, solution: Solution, fmt: str) -> str | bytes:
    """The picture of ``solution`` as SVG text or PNG bytes (``Solution._repr_svg_`` /
    ``_repr_png_`` call it through ``Solution.renderer``)."""
    import tempfile

    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, f"picture.{fmt}")
        draw_solution(path, problem, solution, fmt=fmt)
        with open(path, "rb") as f:
            data = f.read()
    return data.decode("utf-8") if fmt == "svg" else data


def iter_demos() -> Iterable[tuple[Family, Demo]]:
    """Every family's demos, family by family."""
    for fam in families():
        for d in fam.demos:
            yield fam, d
