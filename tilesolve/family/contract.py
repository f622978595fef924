"""The family contract: the :class:`Family` record a facade declares, its routes, file
formats (:class:`Codec`) and demos."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable, Mapping, Sequence

from tilesolve.errors import InvalidProblem
from tilesolve.family.forms import Form
from tilesolve.model.run import RunOptions
from tilesolve.model.solution import CountResult, Solution

__all__ = ["Route", "Codec", "Demo", "Family"]


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
        ``verify(problem, answer) -> list of violations`` (empty when valid): the family's
        independent checker (``tilesolve.verify``), given ``Solution.answer``: the tiling, or
        the report of a family whose answers are reports (``Solution.report``).
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
        ``draw(problem, solution, path, fmt, **options)`` writes a picture of a solution in
        ``fmt``, one of :attr:`pictures`.
    pictures : tuple of str
        The formats ``draw`` writes: ``("svg", "png")``, or one of them. Other formats are
        refused (``tilesolve draw``, :func:`~tilesolve.family.draw_solution`), and the studio
        shows and exports a solution in a format its family draws (an SVG-only family's
        large tilings as SVG too).
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
    warm : callable or None
        ``warm()`` makes the family's later solves fast in a long-lived process (the studio's
        server and its forkserver call it once at start): e.g. loads compiled kernels.
    answer : str
        What one answer of the family is called in reports (``ok: FILE is a valid ANSWER of
        ...``): ``"tiling"``, or ``"point set"`` for the sampling families.
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
    pictures: tuple[str, ...] = ("svg", "png")
    warm: Callable[[], None] | None = None
    answer: str = "tiling"

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
