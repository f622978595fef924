"""Aperiodicity checks of Wang tile sets, every answer a certificate (class notes Part II §8.2).

Wang's procedure separates the tile sets that are not aperiodic: an ``n x n`` square that
cannot be tiled proves the set tiles no plane (Extension Theorem, Grünbaum and Shephard
§3.8), a tiled torus is a periodic tiling. :class:`~tilesolve.model.aperiodic.AperiodicProblem`
asks for the largest tiled square up to a bound and for every (sheared) torus up to a bound;
the answer is an :class:`~tilesolve.model.aperiodic.AperiodicReport` of certificates (in
``Solution.report``, with its verdict: ``Solution.verdict``; there is no tiling): witness
tilings (verified by :func:`tilesolve.verify.aperiodic.aperiodic_violations`, which re-checks
each one as a board tiling), refutations with checked DRAT proofs, and undecided boards with
why. A report never calls a set aperiodic from search alone; for a built-in set it quotes the
literature.

Routes
------
``sat``
    :mod:`tilesolve.engine.aperiodic`: squares by bisection (the full formula with CaDiCaL's
    initial phase false, raced against a guided search for large witnesses), periods as a parallel sweep (local processes or a Dask cluster), resumable
    through a cache file (``options={"cache": PATH, "proof_dir": DIR}``) whose lines are used
    only once re-checked: a witness by the verifier, a refutation by its kept proof against
    the CNF re-derived from the tile set and board.

Every refutation records the named encoding of its CNF (``evidence["encoding"]``,
``wang-tiles-cnf``), so that ``tilesolve verify`` re-derives each board's CNF from the report's
tile set and board name (:func:`refutations`) and checks the proof against it.
``transducer``
    :mod:`tilesolve.constructive.transducer` (Jeandel and Rao §2-3), its emptiness verdicts
    certified by the SAT route.
``lattice``
    :mod:`tilesolve.constructive.periods`: every lattice of periods of index (cells of one
    period) at most ``max_period``, smallest first, by a bounded backtracking search that stops
    at the first one tiled. It finds witnesses only (``periodic-10-35``'s one-row period of 35
    tiles, which the other routes reach in minutes); it refutes nothing.

Examples
--------
>>> from tilesolve.model.board import WangTileSet
>>> ws = WangTileSet([[0, 1, 1, 1], [1, 1, 0, 1]], 2)   # N, E, S, W: a 2-row period
>>> s = solve(AperiodicProblem(ws, 3, 2), seed=1, workers=1)
>>> s.report.largest_square, [c.status for c in s.report.periods]  # the sweep stops at a witness
(3, ['undecided', 'refuted', 'undecided', 'tiles'])
>>> s.verdict, s.status.value, s.tiling is None
('periodic', 'sat', True)
"""

from __future__ import annotations

import functools

from tilesolve.errors import InvalidProblem
from tilesolve.family import Codec, Demo, Family, Field, Form, RunOptions, register
from tilesolve.family import solve as _solve
from tilesolve.families.aperiodic_window import tiling
from tilesolve.io.aperiodic_json import APERIODIC_REPORT, VERSIONS, report_from_dict, report_to_dict
from tilesolve.model.aperiodic import AperiodicProblem, AperiodicReport, Certificate
from tilesolve.model.solution import Solution, Status
from tilesolve.verify.aperiodic import aperiodic_violations, witness_violations

__all__ = ["AperiodicProblem", "AperiodicReport", "Certificate", "solve", "sat", "transducer", "lattice",
           "build_report", "refutations", "witness", "tiling", "FAMILY"]


def build_report(problem: AperiodicProblem, squares, largest: int | None, periods) -> AperiodicReport:
    """The report of decided certificates, with a conclusion that says exactly what they prove."""
    squares, periods = tuple(squares), tuple(periods)
    said = []
    tiled = [c for c in periods if c.status == "tiles"]
    if tiled:
        said.append(f"The set tiles the plane periodically: the {tiled[0].board} is tiled (verified witness), so "
                    "the set is not aperiodic.")
    if problem.max_square:
        if largest is None:
            said.append("The square scan was not decided.")
        elif largest < problem.max_square:
            said.append(f"The set tiles no plane: the {largest + 1}x{largest + 1} square cannot be tiled (checked "
                        f"proof), so by the Extension Theorem no tiling of the plane exists; the largest tiled "
                        f"square is {largest}x{largest} (verified witness).")
        else:
            from tilesolve.engine.aperiodic_square import METHOD

            top = next((c for c in squares if c.board == f"square {largest}x{largest}"), None)
            steered = ", found by the run phased by the constructive route's window" \
                if top is not None and top.method == METHOD else ""
            said.append(f"The set tiles every square up to {largest}x{largest} (verified witness at "
                        f"{largest}x{largest}{steered}).")
    if problem.max_period and not tiled:
        refuted = sum(c.status == "refuted" for c in periods)
        undecided = len(periods) - refuted
        what = (f"every lattice of periods with sides at most {problem.max_period} (tori p x q, 1 <= p, q <= "
                f"{problem.max_period}, every shear)" if problem.shears else
                f"every torus p x q with 1 <= p, q <= {problem.max_period}")
        if undecided == 0:
            said.append(f"No periodic tiling with these periods: {what} is refuted, each with its checked proof "
                        f"({refuted} refutations).")
        else:
            said.append(f"Of {what}, {refuted} are refuted (checked proofs) and {undecided} are undecided; "
                        "no periodic tiling was found.")
    if not tiled and not (largest is not None and largest < problem.max_square):
        said.append("A finite search does not prove a set aperiodic; this report states only what was checked.")
    lit = None
    if problem.info:
        lit = (f"{problem.info.get('reference', '')} (literature verdict: {problem.info.get('verdict', '?')}; "
               "quoted, not checked here)").strip()
    return AperiodicReport(squares, periods, largest, " ".join(said), lit)


def sat(problem: AperiodicProblem, run: RunOptions) -> Solution:
    """The SAT route (:mod:`tilesolve.engine.aperiodic`): squares by bisection, periods swept in
    parallel; ``run.options``: ``proof_dir`` (CNF + DRAT of every refutation), ``cache`` (a
    results file: decided lattices are read from it and added to it), ``every_board`` (decide
    every lattice, not only up to the first tiled torus), ``square_search`` (how squares are
    searched: :data:`tilesolve.engine.aperiodic.SQUARE_SEARCHES`, default ``"race"``)."""
    from tilesolve.engine.aperiodic import square_scan, sweep

    proof_dir = run.option("proof_dir")
    squares, largest = [], None
    if problem.max_square:
        search = run.option("square_search", "race")
        window = None
        if search == "markov":
            from tilesolve.families.aperiodic_square import steering

            window = steering(problem.tileset, run.seed)
        try:
            squares, largest = square_scan(problem.tileset, problem.max_square, run, proof_dir=proof_dir,
                                           search=search, window=window)
        except KeyboardInterrupt:
            return Solution(Status.UNKNOWN, None, "sat", None, run.seed, run.deadline.elapsed(),
                            reason="interrupted (Ctrl-C) while scanning squares")
        if squares and squares[-1].status == "undecided" and str(squares[-1].evidence.get("why")).startswith(
                "interrupted"):
            return Solution(Status.UNKNOWN, None, "sat", None, run.seed, run.deadline.elapsed(),
                            reason="interrupted (Ctrl-C) while scanning squares")
    periods = []
    if problem.max_period:
        names = [lat.name() for lat in problem.lattices()]
        periods, interrupted = sweep(problem.tileset, names, run, cache=run.option("cache"), proof_dir=proof_dir,
                                     check_witness=functools.partial(_witness_holds, problem),
                                     stop_at_witness=not run.option("every_board", False))
        if interrupted:
            done = sum(c.status != "undecided" for c in periods)
            return Solution(Status.UNKNOWN, None, "sat", None, run.seed, run.deadline.elapsed(),
                            reason=f"interrupted (Ctrl-C) after {done} of {len(periods)} lattices were decided")
    report = build_report(problem, squares, largest, periods)
    n_und = len(report.undecided)
    reason = None if report.complete else f"{n_und} board(s) undecided ({report.undecided[0].evidence.get('why')})"
    cached = sum(bool(c.evidence.get("cached")) for c in periods)
    rejected = sum("cache_rejected" in c.evidence for c in periods)
    stats = {"squares_decided": sum(c.status != "undecided" for c in squares),
             "periods_tiled": sum(c.status == "tiles" for c in periods),
             "periods_refuted": sum(c.status == "refuted" for c in periods), "undecided": n_und,
             "periods_from_cache": cached, "cache_lines_rejected": rejected}
    notes = ()
    if cached or rejected:
        notes = (f"{cached} lattice verdict(s) taken from the cache after re-checking (witness verified, or proof "
                 f"re-checked against the re-derived CNF); {rejected} cache line(s) not confirmed and decided "
                 "again",)
    return Solution(report.status, None, "sat", "cadical153", run.seed, run.deadline.elapsed(), reason=reason,
                    notes=notes, stats=stats, report=report)


def transducer(problem: AperiodicProblem, run: RunOptions) -> Solution:
    """The transducer route (Jeandel and Rao §2-3, :mod:`tilesolve.constructive.transducer`):
    ``T^k`` for ``k = 1 .. max_k`` (run option ``max_k``); a cycle that writes what it reads is a
    torus witness, an empty ``T_k`` is certified by the SAT route's checked refutation of a
    ``k x w`` rectangle. ``run.options["proof_dir"]`` as for :func:`sat`."""
    from tilesolve.constructive.transducer import transducer_report
    from tilesolve.engine.aperiodic import decide
    from tilesolve.engine.certificates import writing_proofs

    with writing_proofs(run.option("proof_dir")):
        verdict, report = transducer_report(problem, run, refute=lambda name, r: decide(problem.tileset, name, r))
    reason = report.conclusion if report.verdict == "undecided" else None
    return Solution(report.status, None, "transducer", None, run.seed, run.deadline.elapsed(), reason=reason,
                    stats={"transducer_verdict": verdict}, report=report)


def lattice(problem: AperiodicProblem, run: RunOptions) -> Solution:
    """The lattice route (:mod:`tilesolve.constructive.periods`): the lattices of periods of index
    at most ``max_period``, smallest first, until one is tiled. Its witness is the plain torus the
    lattice repeats to (both sides at most its index, so a torus of the check); the family's
    verifier checks it on its board. The search refutes nothing: without a witness every lattice
    of the check is undecided. Periods only (no squares)."""
    from tilesolve.constructive.periods import NODE_BUDGET, rectangle, search

    if problem.max_square:
        raise InvalidProblem("the lattice route looks for periods only: check squares with --method sat")
    try:
        found = search(problem.tileset, problem.max_period, deadline=run.deadline)
    except KeyboardInterrupt:
        return Solution(Status.UNKNOWN, None, "lattice", None, run.seed, run.deadline.elapsed(),
                        reason="interrupted (Ctrl-C) while searching the lattices")
    stats = {"lattices_searched": found.tried, "over_budget": found.over_budget, "node_budget": NODE_BUDGET}
    if found.lattice is not None:  # its plain torus: rows p <= index, columns q p / gcd(p, s) <= index
        grid = rectangle(found.lattice, found.tiling)
        board = f"torus {grid.shape[0]}x{grid.shape[1]}"
        periods = [Certificate(board, "tiles", grid, "lattice", {**stats, "lattice": found.lattice.name(),
                                                                 "index": found.index}, round(found.seconds, 6))]
        note = (f"the lattice search tried {found.tried:,} lattices ({found.over_budget:,} left at the node budget): "
                f"{found.reason}" + ("" if board == found.lattice.name() else f", which repeats to the {board}"))
    else:
        why = f"the lattice search finds witnesses only: {found.reason}"
        periods = [Certificate(lat.name(), "undecided", None, "lattice", {"why": why}) for lat in problem.lattices()]
        note = why
    report = build_report(problem, (), None, periods)
    return Solution(report.status, None, "lattice", None, run.seed, run.deadline.elapsed(),
                    reason=None if found.lattice is not None else found.reason, notes=(note,), stats=stats,
                    report=report)


def refutations(problem: AperiodicProblem, sol: Solution) -> list[tuple[str, object, dict]]:
    """Every refuted board of a report: ``(board name, the board problem its CNF encodes,
    evidence)`` (the family's :attr:`~tilesolve.family.Family.refutations`: ``tilesolve verify``
    re-derives each CNF from the report's tile set and the board's name)."""
    from tilesolve.engine.aperiodic import board_problem

    report = sol.report
    if not isinstance(report, AperiodicReport):
        return []
    return [(c.board, board_problem(problem.tileset, c.board), dict(c.evidence))
            for c in report.squares + report.periods if c.status == "refuted"]


def _violations(problem: AperiodicProblem, report) -> list:
    """The family's verifier (:func:`aperiodic_violations`), and a report's words claim no more
    than its certificates: the verdict a file states must be theirs, a sweep's conclusion the one
    they give (:func:`build_report`)."""
    from tilesolve.constructive.transducer import UNDECIDED_OPENINGS
    from tilesolve.verify.dappled import Violation

    out = aperiodic_violations(problem, report)
    if isinstance(report, AperiodicReport) and report.stated not in (None, report.verdict):
        out.append(Violation("verdict", f"the verdict {report.stated!r} is not what the certificates give: "
                                        f"{report.verdict!r}"))
    certs = report.squares + report.periods if isinstance(report, AperiodicReport) else ()
    if out or any("transducer" in str(c.method) for c in certs):
        return out
    if not certs and report.conclusion.startswith(UNDECIDED_OPENINGS):
        return out  # the transducer's undecided report: no certificate, nothing claimed
    said = build_report(problem, report.squares, report.largest_square, report.periods).conclusion
    if report.conclusion != said:
        out.append(Violation("conclusion", f"the conclusion is not what the certificates prove: {said!r}"))
    return out


def _witness_holds(problem: AperiodicProblem, cert: Certificate) -> bool:
    """True when a (cached) witness tiles its board (the family's verifier)."""
    return not witness_violations(problem, cert)


def solve(problem: AperiodicProblem, method: str = "auto", **kwargs) -> Solution:
    """:func:`tilesolve.family.solve` for aperiodicity checks (keyword arguments as there)."""
    return _solve(problem, method, **kwargs)


def witness(report: AperiodicReport) -> Certificate | None:
    """The report's most telling witness: the first tiled (sheared) torus, a periodic tiling's
    unit, else the largest tiled square (class notes Part II §8.2); ``None`` without one."""
    tori = [c for c in report.periods if c.status == "tiles"]
    if tori:
        return tori[0]
    squares = [c for c in report.squares if c.status == "tiles"]
    return max(squares, key=lambda c: c.tiling.size) if squares else None


def _draw(problem: AperiodicProblem, sol: Solution, path, fmt: str, *, title: str | None = None, notes=(),
          **_ignored) -> None:
    """The witness of :func:`witness` drawn as a board tiling of its Wang tiles (SVG with a
    title and legend, PNG for large witnesses); a torus's seams are marked as on any board."""
    from tilesolve.model.aperiodic import board_of, leg_colours
    from tilesolve.model.board import BoardProblem

    cert = witness(sol.report)
    if cert is None:
        raise InvalidProblem("this report has no witness tiling to draw")
    board_problem = BoardProblem(board_of(cert.board), problem.tileset)
    legs = leg_colours(problem.tileset, cert.tiling)
    what = problem.name or f"{len(problem.tileset)} Wang tiles"
    legend = [f"witness: the {cert.board} tiled ({cert.method}" +
              (f", seed {sol.seed})" if sol.seed is not None else ")")]
    title = title or f"{what}: {cert.board}"
    if fmt == "png":
        from tilesolve.io.png import write_board_png

        write_board_png(path, board_problem, legs, caption=[title, *legend, *notes])
        return
    from tilesolve.io.svg_board import write_board_svg

    write_board_svg(path, board_problem, legs, title=title, notes=legend + list(notes))


def _jeandel_rao_demo() -> AperiodicProblem:
    from tilesolve.io.builtin_tilesets import load

    tileset, info = load("jeandel-rao")
    return AperiodicProblem(tileset, 12, 2, name="jeandel-rao", info=info)


DEMOS = (
    Demo("jeandel-rao",
         "the Jeandel-Rao set (11 tiles): a tiled 12x12 square, no torus up to 2x2 (class notes Part II §8.2)",
         _jeandel_rao_demo, method="sat"),
)


def _form_build(values) -> tuple[AperiodicProblem, dict]:
    """The studio form's check (the ``aperiodic check --builtin`` options)."""
    from tilesolve.io.builtin_tilesets import load

    tileset, info = load(values["tileset"])
    return AperiodicProblem(tileset, values["max_square"], values["max_period"], values["shears"],
                            values["tileset"], info), {}


def _form_command(values) -> tuple[list[str], dict[str, str]]:
    words = ["aperiodic", "check", "--builtin", values["tileset"], "--max-square", str(values["max_square"]),
             "--max-period", str(values["max_period"])]
    return words + (["--shears"] if values["shears"] else []), {}


def _form() -> Form:
    from tilesolve.io.builtin_tilesets import names

    most_period = 8
    return Form(
        fields=(
            Field("tileset", "choice", "tile set", "jeandel-rao", "a built-in Wang tile set",
                  choices=tuple(names()), option="--builtin"),
            Field("max_square", "int", "max square", 12, "find the largest tiled n x n square, n <= this (0: none)",
                  low=0, high=40, option="--max-square"),
            Field("max_period", "int", "max period", 2, "check every torus p x q, p, q <= this (0: none)",
                  low=0, high=most_period, option="--max-period"),
            Field("shears", "bool", "sheared tori", False, "also every sheared torus (every lattice of periods)",
                  option="--shears", when=({"max_period": tuple(range(1, most_period + 1))},)),
        ),
        build=_form_build,
        command=_form_command,
    )


FAMILY = register(Family(
    name="aperiodic",
    title="aperiodicity checks of Wang tile sets: squares, tori and lattice periods, with certificates",
    problem_type=AperiodicProblem,
    routes={"sat": sat, "transducer": transducer, "lattice": lattice},
    auto=lambda problem: "sat",
    verify=_violations,
    codecs=(Codec(APERIODIC_REPORT, VERSIONS, report_from_dict, report_to_dict),),
    draw=_draw,
    demos=DEMOS,
    commands=("tilesolve.cli.aperiodic:aperiodic",),
    form=_form(),
    refutations=refutations,
    route_help={"sat": "squares by bisection and (sheared) tori swept in parallel; witnesses verified, "
                       "refutations with checked DRAT proofs (class notes Part II §8.2)",
                "transducer": "Jeandel-Rao transducers T^k: a periodic cycle gives a torus witness, an empty T_k a "
                              "rectangle refuted by SAT with a checked proof",
                "lattice": "every lattice of periods of index (cells of one period) up to the max period, smallest "
                           "first, by bounded backtracking: a verified torus witness or nothing (refutes nothing)"},
))
