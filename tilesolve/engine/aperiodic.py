"""The SAT route of aperiodicity checks: squares by bisection, periods by parallel sweeps.

Class notes Part II §8.2 (Wang's procedure). Every board is decided by
:func:`tilesolve.engine.routes.sat_route` on the tile-selection CNF of
:mod:`tilesolve.encodings.wang_tiles`: a model is a witness tiling (verified independently
by the family's verifier), ``unsat`` comes only with a DRAT proof checked by
:mod:`tilesolve.verify.drat`, and a time limit or Ctrl-C leaves the board *undecided*.

Squares (:func:`square_scan`)
    Tiling an ``n x n`` square implies tiling every smaller one, so the largest tiled
    ``n <= N`` is found by bisection: ``N`` first (a witness ends the scan), then halving
    between a tiled and a refuted size; the scan ends with a witness at ``n`` and a checked
    refutation at ``n + 1``, which proves that the set tiles no plane (Extension Theorem).
    Each square is the full formula, solved (search ``"phase"``) in one process
    with CaDiCaL's initial phase "no tile here" and the phases it saves
    (:data:`WITNESS_OPTIONS`), not with random phases drawn from the seed: CaDiCaL holds such
    phases above the ones it saves, which made Jeandel-Rao's squares heavy-tailed over seeds
    (benchmarks/bench_aperiodic_sat.py measures both). The search before it, ``"portfolio"``:
    squares above :data:`DIRECT_SIDE` as a portfolio of two processes (both cores), the full
    formula and a *guided* restricted formula in which only the pairs of neighbouring tiles
    that occur in the interior of a smaller tiling (:data:`GUIDE_SIDE`) are allowed, both with
    the seed's random phases; the first witness wins, and a restricted "unsat" proves nothing,
    so only the full formula refutes. The default, ``"race"``, is that portfolio with its full
    formula searched as ``"phase"`` does: the phase search's time jumps with the size, and the
    guided run often beats it where it is slow. ``"markov"`` is the race with the guided run
    replaced by the full formula phased by a window of a known tiling (the constructive
    route's, for Jeandel-Rao and U19: :mod:`tilesolve.engine.aperiodic_square`), steered and
    labelled so (its witnesses' method). Every way a witness is verified and a
    refutation's proof checked.

Periods (:func:`sweep`)
    One SAT run per :class:`~tilesolve.model.aperiodic.Lattice`, on local worker processes
    (``workers``, default both cores, through :mod:`tilesolve.engine.portfolio`'s workers) or
    on a Dask cluster (``cluster``). Decided lattices are appended to a cache file as they
    come in (JSON lines keyed by the tile set's digest; the proofs of refutations beside it, in
    :func:`cache_proof_dir`), so a rerun re-checks them instead of solving them: a cache is not
    evidence, and a line whose witness or proof does not hold is decided again. A time limit or
    Ctrl-C leaves the rest undecided (never refuted).

    The sweep first refutes tori through *shared bands* (:mod:`tilesolve.engine.aperiodic_bands`):
    per torus height, the narrowest band of first columns that cannot be tiled is solved and its
    proof checked once, and every torus of that height wider than the band gets the trimmed
    proof renamed into its own variables (Jeandel-Rao's 576 tori up to 24 x 24 rest on a few
    dozen bands); then bands of first rows for the unsheared tori left; the rest one by one,
    largest first, and the sweep stops at its first witness.

    A torus decided on its own (:func:`decide`) of at least :data:`BAND_MIN_CELLS` cells is first
    tried through its *bands*, its first ``h`` columns or rows (:func:`_by_bands`): a band's
    clauses are a subset of the torus's formula, so a band's DRAT proof, checked against the whole torus's CNF, refutes the
    torus (Jeandel-Rao 24x24 falls to its first 10 columns: 19 s CPU, where the whole formula
    was not refuted in 300 s). Then a witness is sought on a tall cylinder
    (:func:`_cylinder_witness`; periodic-10-30's 30x30 torus in 22 s CPU, where the torus
    itself was not tiled in 200 s); else the whole torus decides.

Every refutation's CNF is the named encoding ``wang-tiles-cnf`` of the tile set on the board
its name stands for (:func:`board_problem`), recorded in the certificate, so that anyone can
re-derive it.
"""

from __future__ import annotations

import functools
import hashlib
import json
import os
import time
from dataclasses import replace
from typing import Callable, Sequence

import numpy as np

from tilesolve.deadline import Deadline
from tilesolve.errors import InvalidProblem
from tilesolve.model.aperiodic import Certificate, board_of, parse_board_name
from tilesolve.model.board import BoardProblem, WangTileSet
from tilesolve.model.run import RunOptions
from tilesolve.model.solution import Solution, Status

__all__ = ["decide", "square_scan", "sweep", "tileset_digest", "read_cache", "cache_proof_dir", "board_problem",
           "board_encoding", "GUIDE_SIDE", "DEFAULT_SOLVER", "SQUARE_SEARCHES", "WITNESS_OPTIONS"]

#: Side of the square whose interior guides large witnesses (its border rows are dropped).
GUIDE_SIDE = 30
#: Squares at most this large are solved with the full formula directly.
DIRECT_SIDE = 40
#: Tori of at least this many cells are tried through bands and a cylinder before they are
#: solved whole (smaller ones are solved whole faster: JR 16x16 2.9 s by bands, 2.2 s whole;
#: 20x20 7.5 s and 16 s CPU).
BAND_MIN_CELLS = 300
#: The widest band a torus decided on its own tries (:data:`SHARED_BAND_MAX` in a sweep); a
#: wide band of a periodic set can be slow to tile (periodic-10-30: 30 rows by 13 columns,
#: 50 s CPU, where bands up to 12 take 2.3 s together).
BAND_MAX = 12
#: The widest band a sweep shares between tori; each band wider than :data:`BAND_MAX` is
#: solved within :data:`WIDE_BAND_S` seconds or not used (a wide band of a periodic set can be
#: slow to tile). Jeandel-Rao's tori with p, q <= 24 need bands up to 16 wide (18 rows need 15
#: columns; 20 and 23 columns need 16 rows) to leave only small tori and a few that no band of
#: either axis refutes (23 rows by 13, 16, 21 or 24 columns; 14 rows by 16 to 24 columns).
SHARED_BAND_MAX = 16
#: Seconds a band wider than :data:`BAND_MAX` may take to solve in a sweep.
WIDE_BAND_S = 30.0
#: A cylinder searched for a torus witness is this many times the torus's height (plus 2 rows).
CYLINDER_LAPS = 6
#: CaDiCaL's settings for a search whose answer is a witness: no inprocessing (variable
#: elimination, subsumption, probing, vivification), which a satisfiable tiling formula pays
#: for and seldom uses (JR 100x100: 6.4 s instead of 18 s wall, the same conflicts).
SEARCH_OPTIONS = {"elim": 0, "subsume": 0, "probe": 0, "vivify": 0}
#: CaDiCaL's settings for a square's search ``"phase"``: every variable's first value is false
#: ("not this tile here"), and the solver's saved phases steer it from then on (no random phases
#: are drawn from the seed, which CaDiCaL would hold above them). Inprocessing stays on: on
#: Jeandel-Rao squares it changes the conflicts little.
WITNESS_OPTIONS = {"phase": 0}
#: How :func:`square_scan` searches: ``"phase"`` (the full formula with
#: :data:`WITNESS_OPTIONS`, one process), ``"portfolio"`` (the route before it: squares above
#: :data:`DIRECT_SIDE` as the full formula and a guided one on two processes, seeded random phases)
#: or ``"race"`` (the default: that portfolio with the full formula searched as ``"phase"`` does,
#: which covers the sizes where ``"phase"`` alone is slow), or ``"markov"`` (the race with the
#: guided run replaced by the full formula phased by a window of a known tiling, the constructive
#: route's for the sets with a Markov partition: :mod:`tilesolve.engine.aperiodic_square`), or
#: ``"grams"`` (the race with the guided run restricted to the short runs along rows and columns
#: of a :data:`~tilesolve.engine.aperiodic_square.GRAM_SIDE` witness found by ``"phase"``).
SQUARE_SEARCHES = ("phase", "portfolio", "race", "markov", "grams")
#: The SAT solver (CaDiCaL logs DRAT proofs).
DEFAULT_SOLVER = "cadical153"


def tileset_digest(tileset: WangTileSet) -> str:
    """SHA-256 of the tiles (in the set's order, which the CNF follows) and colour count: the
    cache key of a tile set. The tiles' colours are hashed in the order W, N, E, S, the key's
    order since caches were first written, so that those caches stay valid."""
    wnes = tileset.tiles[:, [3, 0, 1, 2]]
    data = json.dumps({"colours": int(tileset.n_colors), "tiles": wnes.tolist()}, separators=(",", ":"))
    return hashlib.sha256(data.encode()).hexdigest()


def _certificate(name: str, sol, method: str = "sat") -> Certificate:
    st = dict(sol.stats)
    if sol.status is Status.SAT:
        return Certificate(name, "tiles", np.asarray(sol.tiling, dtype=np.int64), method,
                           {"solver": sol.solver, "variables": st.get("variables"), "clauses": st.get("clauses")},
                           round(sol.time_s, 6))
    if sol.status is Status.UNSAT:
        keep = ("encoding", "cnf_sha256", "drat_sha256", "proof_lines", "proof_lemmas", "proof_checked_lemmas",
                "proof_check_s", "proof_name", "clauses", "variables")
        ev = {k: st[k] for k in keep if k in st}
        ev.update(solver=sol.solver, checker="tilesolve.verify.drat", reason=sol.reason)
        return Certificate(name, "refuted", None, method, ev, round(sol.time_s, 6))
    return Certificate(name, "undecided", None, method, {"why": sol.reason or "undecided"}, round(sol.time_s, 6))


def board_problem(tileset: WangTileSet, name: str) -> BoardProblem:
    """The board problem a certificate's board name stands for: ``tileset`` on that square or
    (sheared) torus, boundary free (what the named encoding ``wang-tiles-cnf`` encodes)."""
    return BoardProblem(board_of(name), tileset)


def board_encoding(tileset: WangTileSet, name: str, *, allowed=None, deadline: Deadline | None = None):
    """The tile-selection CNF of ``tileset`` on the board ``name``: the named encoding
    ``wang-tiles-cnf`` (its refutations are re-derivable certificates), or with ``allowed``
    pairs the restricted formula of a guided search (whose unsat proves nothing)."""
    if allowed is None:
        from tilesolve.encodings.registry import encode

        return encode("wang-tiles-cnf", board_problem(tileset, name), deadline=deadline)
    from tilesolve.encodings.wang_tiles import encode_tiles

    return encode_tiles(board_of(name), tileset, allowed=allowed, deadline=deadline)


def decide(tileset: WangTileSet, name: str, run: RunOptions, *, allowed=None, bands: bool = True,
           phase_search: bool = False, cylinder: bool = True) -> Certificate:
    """Decide whether ``tileset`` tiles the board called ``name`` (``"square 5x5"``,
    ``"torus 3x4 shear 1"``) with the SAT route; ``allowed`` pairs make a guided
    (restricted) search whose unsat is reported undecided. ``bands=False`` skips a torus's
    bands (a sweep has tried them already) but still looks for its witness on a cylinder, unless
    ``cylinder`` is False (a sweep refuted a band of the cylinder's rows).
    ``phase_search`` solves with CaDiCaL's :data:`WITNESS_OPTIONS` instead of the seed's random
    phases (a refutation still carries its checked proof)."""
    from tilesolve.deadline import TimeLimitReached
    from tilesolve.engine.routes import sat_route

    t0 = time.perf_counter()
    try:
        enc = board_encoding(tileset, name, allowed=allowed, deadline=run.deadline)
    except TimeLimitReached as exc:
        return Certificate(name, "undecided", None, "sat", {"why": str(exc)}, round(time.perf_counter() - t0, 6))
    rows, cols, shear = parse_board_name(name)
    if allowed is None and shear >= 0 and rows * cols >= BAND_MIN_CELLS:
        cert = _by_bands(tileset, name, enc, run, t0, bands, cylinder)
        if cert is not None:
            return cert
    solver = run.solver or DEFAULT_SOLVER
    options = _cadical_options(WITNESS_OPTIONS, solver) if phase_search else None
    sol = sat_route(enc, run, solver=solver, t0=t0, options=options, seeded_phases=not phase_search)
    return _certificate(name, sol, "sat guided" if allowed is not None else "sat")


def _bands(labels: np.ndarray, rows: int, cols: int) -> list[tuple[int, np.ndarray, str]]:
    """The bands of a ``rows x cols`` torus, smallest first: ``(cells, mask, what)`` for the
    first ``h`` columns (``h <= cols / 2``, :data:`BAND_MAX`; they wrap top to bottom) and the
    first ``h`` rows (``h <= rows / 2``, :data:`BAND_MAX`; they wrap side to side, with the shear)."""
    out = [(h * rows, labels[:, 1] < h, f"its first {h} column(s)") for h in range(1, min(cols // 2, BAND_MAX) + 1)]
    out += [(h * cols, labels[:, 0] < h, f"its first {h} row(s)") for h in range(1, min(rows // 2, BAND_MAX) + 1)]
    return sorted(out, key=lambda b: b[0])


def _by_bands(tileset: WangTileSet, name: str, enc, run: RunOptions, t0: float, bands: bool,
              cylinder: bool = True) -> Certificate | None:
    """A torus refuted through one of its bands (:func:`_bands`), smallest first, or a witness
    read off a cylinder (:func:`_cylinder_witness`); ``None`` when neither settles it.

    A band's clauses are a subset of the torus's formula (:meth:`TileEncoding.part`), so the
    band's DRAT proof is checked against the torus's whole formula and, once it passes, is the
    torus's certificate like any other (the named encoding's CNF, re-derivable). Most of
    Jeandel-Rao's tori fall to bands a few cells wide, not all: a vertically periodic strip of
    period 23 tiles at every width up to 23 (:data:`SHARED_BAND_MAX`).
    """
    from tilesolve.engine.certificates import unsat_solution
    from tilesolve.engine.sat import solve_cnf

    rows, cols, shear = parse_board_name(name)
    solver = run.solver or DEFAULT_SOLVER
    for _, mask, what in _bands(enc.labels, rows, cols) if bands else ():
        if run.deadline.expired():
            return None
        r = solve_cnf(enc.part(mask), solver=solver, with_proof=True, seed=run.seed, deadline=run.deadline)
        if r.status is Status.UNSAT:
            stats = {"clauses": len(enc.hard), "variables": enc.n_vars, "band": what}
            sol = unsat_solution(enc.hard, r, method="sat", seed=run.seed, t0=t0, stats=stats,
                                 deadline=run.deadline, encoding=getattr(enc, "named", None))
            if sol.status is Status.UNSAT:
                return _certificate(name, sol.replace(reason=f"{sol.reason}; the proof refutes {what}"), "sat")
            return None  # a proof that does not carry over: the whole torus decides
        if r.status is not Status.SAT:
            return None
    if shear == 0 and cylinder:
        return _cylinder_witness(tileset, name, run, t0)
    return None


def _cadical_options(options: dict, solver: str) -> dict | None:
    """``options`` (CaDiCaL's settings) for CaDiCaL, none for other solvers."""
    from tilesolve.engine.sat import canonical_solver_name

    return options if canonical_solver_name(solver).startswith("cadical") else None


def _stacked(grid: np.ndarray, tiles: np.ndarray, rows: int) -> np.ndarray | None:
    """A ``rows x cols`` torus tiling cut from ``grid``, a tiling of a cylinder whose columns
    wrap: rows ``r1 + 1 .. r2`` whose top colours are the bottom colours of row ``r2``
    (``r2 - r1`` dividing ``rows``) make a torus, stacked ``rows / (r2 - r1)`` times; else ``None``.
    ``tiles`` are the set's tiles (N, E, S, W) that ``grid`` indexes."""
    seen: dict[bytes, list[int]] = {}
    for r in range(grid.shape[0]):
        key = tiles[grid[r], 2].tobytes()  # the row's bottom (S) colours
        for r1 in seen.get(key, []):
            if rows % (r - r1) == 0:
                return np.tile(grid[r1 + 1:r + 1], (rows // (r - r1), 1))
        seen.setdefault(key, []).append(r)
    return None


def _cylinder_witness(tileset: WangTileSet, name: str, run: RunOptions, t0: float) -> Certificate | None:
    """A witness for the torus ``name`` (``p x q``, no shear) read off a tiled cylinder of ``q``
    columns (they wrap) and :data:`CYLINDER_LAPS` ``p + 2`` rows: a tall cylinder is easier to
    tile than the torus, and two of its rows with the same bottom colours, a divisor of ``p``
    apart, bound a block that tiles the torus (:func:`_stacked`; the family's verifier checks
    it like any witness). ``None`` when the cylinder gives none."""
    from tilesolve.encodings.wang_tiles import encode_tiles
    from tilesolve.engine.sat import solve_cnf
    from tilesolve.model.board import Board

    p, q, _ = parse_board_name(name)
    height = CYLINDER_LAPS * p + 2
    enc = encode_tiles(Board.grid(np.ones((height, q), bool), wrap_cols="plain"), tileset, deadline=run.deadline)
    solver = run.solver or DEFAULT_SOLVER
    r = solve_cnf(enc.hard, solver=solver, deadline=run.deadline, options=_cadical_options(SEARCH_OPTIONS, solver))
    grid = _stacked(enc.decode(r.model), np.asarray(tileset.tiles), p) if r.status is Status.SAT else None
    if grid is None:
        return None
    return Certificate(name, "tiles", grid, "sat cylinder", {"solver": r.solver, "cylinder": f"{height} x {q}"},
                       round(time.perf_counter() - t0, 6))


def _guide(grid: np.ndarray, m: int) -> tuple[np.ndarray, np.ndarray]:
    """The E-W and N-S neighbour pairs in the interior of a tiling (its outer quarter dropped)."""
    b = max(1, grid.shape[0] // 5)
    inner = grid[b:-b, b:-b] if grid.shape[0] > 2 * b + 1 else grid
    east = np.zeros((m, m), dtype=bool)
    south = np.zeros((m, m), dtype=bool)
    east[inner[:, :-1].ravel(), inner[:, 1:].ravel()] = True
    south[inner[:-1, :].ravel(), inner[1:, :].ravel()] = True
    return east, south


def _square_task(tiles: list, n_colors: int, n: int, deadline: Deadline, solver: str | None,
                 proof_dir: str | None, seed0: int, search: str, window=None, *, seed: int):
    """One run of the square portfolio: ``seed`` 0 decides the full formula (with
    :data:`WITNESS_OPTIONS` unless ``search`` is ``"portfolio"``, else the seed's random phases),
    1 searches the guided one (its guide from a :data:`GUIDE_SIDE` square), or with ``search``
    ``"markov"`` the full formula phased by ``window(n)``
    (:func:`tilesolve.engine.aperiodic_square.window_phases`), or with ``"grams"`` (squares above
    :data:`~tilesolve.engine.aperiodic_square.GRAM_SIDE`) the formula restricted to the short runs
    of a smaller witness's interior (:func:`tilesolve.engine.aperiodic_square.gram_encoding`);
    returns a Solution."""
    from tilesolve.engine import aperiodic_square as steer
    from tilesolve.engine.certificates import writing_proofs
    from tilesolve.engine.routes import sat_route

    tileset = WangTileSet(np.asarray(tiles, dtype=np.int64), n_colors)
    run = RunOptions(seed=seed0, deadline=deadline, solver=solver)  # the run's deadline, in this worker
    allowed, method, phases, gram_guide = None, "sat", None, None
    if seed == 1 and search == "markov":
        method = steer.METHOD
    elif seed == 1 and search == "grams" and n > steer.GRAM_SIDE:
        g = decide(tileset, f"square {steer.GRAM_SIDE}x{steer.GRAM_SIDE}", run, phase_search=True)
        if g.status != "tiles":
            return Solution(Status.UNKNOWN, None, steer.GRAMS_METHOD, solver, seed0, 0.0, reason="no guide")
        b = steer.GRAM_SIDE // 10
        method, gram_guide = steer.GRAMS_METHOD, g.tiling[b:-b, b:-b]
    elif seed == 1:
        g = decide(tileset, f"square {GUIDE_SIDE}x{GUIDE_SIDE}", run)
        if g.status != "tiles":
            return Solution(Status.UNKNOWN, None, "sat guided", solver, seed0, 0.0, reason="no guide")
        allowed, method = _guide(g.tiling, len(tileset)), "sat guided"
    t0 = time.perf_counter()
    enc = board_encoding(tileset, f"square {n}x{n}", allowed=allowed, deadline=run.deadline)
    if seed == 1 and search == "markov":
        phases = steer.window_phases(enc, window(n))
    elif gram_guide is not None:
        enc = steer.gram_encoding(enc, steer.grams(gram_guide))
    solver = solver or DEFAULT_SOLVER
    phase = search != "portfolio" and allowed is None
    with writing_proofs(proof_dir):
        return sat_route(enc, run, method=method, solver=solver, t0=t0, seeded_phases=not phase, phases=phases,
                         options=_cadical_options(WITNESS_OPTIONS, solver) if phase else None)


def square_scan(tileset: WangTileSet, max_n: int, run: RunOptions, *, proof_dir: str | os.PathLike | None = None,
                search: str = "race", window: Callable[[int], np.ndarray] | None = None
                ) -> tuple[list[Certificate], int | None]:
    """The largest ``n <= max_n`` for which ``tileset`` tiles an ``n x n`` square.

    ``search`` (:data:`SQUARE_SEARCHES`): ``"phase"`` decides every square in this process with
    :data:`WITNESS_OPTIONS` (the seed changes nothing); ``"portfolio"`` sends squares above
    :data:`DIRECT_SIDE` to a portfolio of two runs on ``run.workers`` local processes (default
    2), the full formula and the guided one, where the first decisive answer wins (a witness
    from either; a refutation only from the full formula, with its checked proof); ``"race"``
    is that portfolio with its full formula searched as ``"phase"`` does (and ``"phase"`` where
    the portfolio does not run); ``"markov"`` is the race with the full formula phased by
    ``window(n)`` (an ``n x n`` tiling known otherwise, e.g. the constructive route's: it
    pickles, for the worker) in place of the guided run
    (:mod:`tilesolve.engine.aperiodic_square`; its witnesses' method says which run found them);
    ``"grams"`` is the race whose guided run is restricted to the runs of at most
    :data:`~tilesolve.engine.aperiodic_square.GRAM_LENGTH` cells along the rows and columns of a
    :data:`~tilesolve.engine.aperiodic_square.GRAM_SIDE` witness of the phase search (no outside
    tiling: unguided by anything but SAT; a restricted "unsat" proves nothing). Returns the certificates decided (in the order decided) and that ``n`` (``None`` when undecided).
    ``run.progress`` shows the squares decided and the bounds known.
    """
    from tilesolve.engine.portfolio import run_portfolio

    if search not in SQUARE_SEARCHES:
        raise InvalidProblem(f"unknown square search {search!r}: one of {', '.join(SQUARE_SEARCHES)}")
    if search == "markov" and window is None:
        raise InvalidProblem("the square search 'markov' needs a window of a known tiling to steer it")
    certs: list[Certificate] = []
    known_sat, known_unsat = 0, max_n + 1
    proof_dir = None if proof_dir is None else os.fspath(proof_dir)

    def at(n: int, bar) -> Certificate:
        name = f"square {n}x{n}"
        bar.note(f"deciding {name}; " + (f"tiles {known_sat}x{known_sat}, " if known_sat else "")
                 + (f"not {known_unsat}x{known_unsat}" if known_unsat <= max_n else "no bound above"))
        if search == "phase" or n <= DIRECT_SIDE or (run.workers or 2) < 2:
            from tilesolve.engine.certificates import writing_proofs

            with writing_proofs(proof_dir):
                return decide(tileset, name, run, phase_search=search != "portfolio")
        task = functools.partial(_square_task, tileset.tiles.tolist(), int(tileset.n_colors), n, run.deadline,
                                 run.solver, proof_dir, run.seed, search, window)
        sol = run_portfolio(task, [0, 1], workers=2, deadline=run.deadline, progress=run.progress, label=name)
        return _certificate(name, sol, sol.method or "sat")

    n = max_n
    with run.progress.task("squares", unit="square") as bar:
        while known_unsat - known_sat > 1:
            c = at(n, bar)
            certs.append(c)
            bar.advance()
            if c.status == "tiles":
                known_sat = n
            elif c.status == "refuted":
                known_unsat = n
            else:
                return certs, None
            n = (known_sat + known_unsat) // 2
    return certs, known_sat


# ------------------------------------------------------------------------------- sweeps
def read_cache(path: str | os.PathLike | None, digest: str) -> dict[str, dict]:
    """Decided records (as dicts) of the tile set with ``digest`` in a cache file: claims to be
    checked (:func:`sweep` re-verifies each before it uses it), never evidence."""
    out: dict[str, dict] = {}
    if path is None or not os.path.exists(path):
        return out
    from tilesolve.inputs import read_input

    # Through the input limit; a line that is not JSON (cut by a kill, or forged) is ignored and
    # its board decided again.
    for line in read_input(path, "cache ").decode("utf-8", errors="replace").splitlines():
        try:
            rec = json.loads(line)
        except (ValueError, RecursionError):
            continue
        if isinstance(rec, dict) and rec.get("tileset") == digest and rec.get("status") in ("tiles", "refuted"):
            out[str(rec.get("board"))] = rec
    return out


def cache_proof_dir(cache: str | os.PathLike) -> str:
    """Where a sweep keeps the DRAT proofs of the refutations in ``cache``: ``CACHE.proofs/``."""
    return os.fspath(cache) + ".proofs"


def _append_cache(path, digest: str, cert: Certificate) -> None:
    rec = {"tileset": digest, "board": cert.board, "status": cert.status, "method": cert.method,
           "tiling": None if cert.tiling is None else cert.tiling.tolist(), "evidence": dict(cert.evidence),
           "time_s": cert.time_s}
    with open(path, "a", encoding="utf-8") as f:
        f.write(json.dumps(rec, separators=(",", ":"), default=str) + "\n")


def _from_cache(rec: dict, how: str) -> Certificate | None:
    """The certificate a cache record claims (``None`` when malformed), marked as cached."""
    ev = rec.get("evidence")
    try:
        tiling = None if rec.get("tiling") is None else np.asarray(rec["tiling"], dtype=np.int64)
        return Certificate(str(rec["board"]), rec["status"], tiling, str(rec.get("method", "sat")),
                           {**ev, "cached": True, "cache_check": how}, float(rec.get("time_s", 0.0)))
    except (InvalidProblem, TypeError, ValueError, KeyError, OverflowError):
        return None


def _cached_refutation(tileset: WangTileSet, rec: dict, store: str | None, proof_dir: str | None,
                       deadline: Deadline) -> tuple[Certificate | None, str]:
    """A cached refutation, used only when its proof (kept in ``store``) refutes the CNF
    re-derived from the tile set and the board's name; its CNF and proof then go to
    ``proof_dir`` like any other refutation's. Returns ``(certificate or None, why not)``."""
    from tilesolve.engine.certificates import proof_name, recheck_unsat, write_proof_files

    ev = rec.get("evidence")
    if not isinstance(ev, dict) or rec.get("method") not in ("sat", "sat+transducer"):
        return None, "a refutation without a SAT proof's evidence"
    if store is None:
        return None, "no proof kept with the cache"
    try:
        problem = board_problem(tileset, str(rec.get("board")))
    except InvalidProblem as exc:
        return None, str(exc)
    check = recheck_unsat(problem, ev, store, deadline=deadline)
    if not check.ok:
        return None, check.lines[-1]
    name = proof_name(ev["cnf_sha256"], ev["drat_sha256"])
    if proof_dir is not None:
        write_proof_files(proof_dir, name, check.cnf, check.drat)
    cert = _from_cache({**rec, "evidence": {**ev, "proof_name": name}},
                       "proof re-checked against the re-derived CNF")
    return cert, "" if cert is not None else "a malformed cache line"


def _cells(name: str) -> int:
    rows, cols, _ = parse_board_name(name)
    return rows * cols


def _job(tiles: list, n_colors: int, names: Sequence[str], cached: dict, tried: dict, deadline: Deadline,
         solver: str | None, proof_dir: str | None, store: str | None, seed0: int, *, seed: int) -> Certificate:
    """One lattice of a sweep (``seed`` is its index in ``names``), in a worker process: its
    cached refutation re-checked (``cached``), else decided by SAT (its bands skipped when it is
    in ``tried``: the sweep's band stage tried them; its cylinder too where ``tried`` says True:
    the band stage refuted a band of the cylinder's rows)."""
    from tilesolve.engine.certificates import writing_proofs

    tileset = WangTileSet(np.asarray(tiles, dtype=np.int64), n_colors)
    name = names[seed]
    rejected = None
    if name in cached:
        cert, rejected = _cached_refutation(tileset, cached[name], store, proof_dir, deadline)
        if cert is not None:
            return cert
    run = RunOptions(seed=seed0, deadline=deadline, solver=solver)  # the run's deadline, in this worker
    with writing_proofs(proof_dir), writing_proofs(store, cnf=False):
        cert = decide(tileset, name, run, bands=name not in tried, cylinder=not tried.get(name, False))
    if rejected is None:
        return cert
    why = f"its cached refutation was not used: {rejected}"
    return replace(cert, evidence={**cert.evidence, "cache_rejected": why})


def _band_job(tiles: list, n_colors: int, specs: Sequence[tuple[str, int, int]], names: Sequence[str],
              deadline: Deadline, solver: str | None, proof_dir: str | None, store: str | None, seed0: int, *,
              seed: int) -> tuple[int | None, list[Certificate]]:
    """Band ``specs[seed]`` (``(axis, length, widest)``) of a sweep, in a worker process: the
    width of the narrowest refuted band (:func:`~tilesolve.engine.aperiodic_bands.refute_band`;
    ``None`` when every band is tiled) and the refutations of every torus of ``names`` it holds
    in. The time limit ends it with the refutations made so far: the other tori stay for the
    sweep."""
    from tilesolve.deadline import TimeLimitReached
    from tilesolve.engine.aperiodic_bands import band_refutation, covers, proof_dirs, refute_band

    tileset = WangTileSet(np.asarray(tiles, dtype=np.int64), n_colors)
    axis, length, widest = specs[seed]
    out = []
    band = None
    try:
        band = refute_band(tileset, axis, length, widest, solver=solver or DEFAULT_SOLVER, seed=seed0,
                           deadline=deadline, budget=(BAND_MAX, WIDE_BAND_S))
        for name in names if band is not None else ():
            if covers(band, name) and not deadline.expired():
                cert = band_refutation(tileset, name, band, deadline=deadline, proof_dirs=proof_dirs(proof_dir, store))
                if cert is not None:
                    out.append(cert)
    except TimeLimitReached:
        pass
    return (None if band is None else band.width), out


def _band_specs(names: Sequence[str], axis: str) -> list[tuple[str, int, int]]:
    """The bands a sweep tries for ``names``: for every torus height (``axis`` "cols") or
    unsheared torus width ("rows"), bands up to :data:`SHARED_BAND_MAX` and narrower than the
    largest torus that could hold them; the tallest first."""
    widest: dict[int, int] = {}
    for name in names:
        rows, cols, shear = parse_board_name(name)
        if axis == "cols":
            widest[rows] = max(widest.get(rows, 0), cols - 1)
        elif shear == 0:
            widest[cols] = max(widest.get(cols, 0), rows - 1)
    return [(axis, n, min(w, SHARED_BAND_MAX)) for n, w in sorted(widest.items(), reverse=True) if w >= 1]


def sweep(tileset: WangTileSet, names: Sequence[str], run: RunOptions, *, cache: str | os.PathLike | None = None,
          proof_dir: str | os.PathLike | None = None, label: str = "periods",
          check_witness: Callable[[Certificate], bool] | None = None,
          stop_at_witness: bool = True) -> tuple[list[Certificate], bool]:
    """Decide the boards in ``names``; returns ``(certificates in order, interrupted)``.

    Bands first (:mod:`tilesolve.engine.aperiodic_bands`): for every torus height, the
    narrowest refuted band of its first columns, solved and checked once, refutes every torus
    of that height that holds it; then, for the unsheared tori left, every width's band of
    first rows; the tori left are decided one by one (:func:`decide`). With ``stop_at_witness``
    the sweep stops at the first tiled board (a periodic tiling decides the question); the
    boards left are undecided and say so.

    ``run.workers`` local processes (default 2; 1 runs here), or ``run.cluster`` (a Dask
    scheduler address or client). Decided boards are appended to ``cache``, the proofs of its
    refutations kept in :func:`cache_proof_dir`. A cache is never evidence: a cached witness is
    used when ``check_witness`` (the family's verifier) accepts it, a cached refutation when its
    kept proof refutes the CNF re-derived from the tile set and the board's name; any other line
    is decided again (its certificate says so in ``evidence["cache_rejected"]``). Certificates
    taken from the cache say so (``evidence["cached"]``, ``evidence["cache_check"]``). With
    ``proof_dir``, every refutation reported has its CNF and proof there, cached or not.
    """
    digest = tileset_digest(tileset)
    cached = {n: rec for n, rec in read_cache(cache, digest).items() if n in set(names)}
    result: dict[str, Certificate] = {}
    rejected: dict[str, str] = {}
    for n, rec in cached.items():
        if rec["status"] != "tiles":
            continue
        cert = _from_cache(rec, "witness re-verified")
        if cert is not None and cert.board == n and check_witness is not None and check_witness(cert):
            result[n] = cert
        else:
            rejected[n] = "its cached witness was not used: it " + (
                "is malformed" if cert is None else "was not re-verified" if check_witness is None
                else "fails the verifier")
    refutations = {n: rec for n, rec in cached.items() if rec["status"] == "refuted"}
    # largest boards first: the long runs start early and the short ones fill the gaps at the end
    todo = sorted((n for n in names if n not in result), key=lambda n: -_cells(n))
    store = None if cache is None else cache_proof_dir(cache)
    common = (run.deadline, run.solver, None if proof_dir is None else os.fspath(proof_dir), store, run.seed)
    tiles, n_colors = tileset.tiles.tolist(), int(tileset.n_colors)
    interrupted = False
    stopped: list[str] = []  # the board whose witness stopped the sweep
    counts = {"tiles": 0, "refuted": 0, "undecided": 0}
    for c in result.values():
        counts[c.status] += 1

    def take(name: str, cert: Certificate) -> bool:
        if name in rejected:
            cert = replace(cert, evidence={**cert.evidence, "cache_rejected": rejected[name]})
        result[name] = cert
        counts[cert.status] += 1
        if cert.status != "undecided" and cache is not None and not cert.evidence.get("cached"):
            _append_cache(cache, digest, cert)
        if cert.status == "tiles" and stop_at_witness:
            stopped.append(name)
            return True
        return cert.status == "undecided" and str(cert.evidence.get("why", "")).startswith("interrupted")

    refuted_bands: dict[tuple[str, int], int] = {}  # (axis, length) -> the narrowest refuted band's width

    def take_band(i: int, payload: tuple[int | None, list[Certificate]]) -> bool:
        width, certs = payload
        if width is not None:
            refuted_bands[specs[i][:2]] = width
        for cert in certs:
            take(cert.board, cert)
        return False

    def cylinder_refuted(name: str) -> bool:
        """True when a refuted band of rows shows that the cylinder of :func:`_cylinder_witness`
        cannot be tiled (its first rows hold the band)."""
        rows, cols, shear = parse_board_name(name)
        return shear == 0 and refuted_bands.get(("rows", cols), CYLINDER_LAPS * rows + 3) <= CYLINDER_LAPS * rows + 2

    with run.progress.task(label, total=len(names), unit="board") as bar:
        def show() -> None:  # boards decided or cached, of all
            bar.note(f"{counts['tiles']} tiled, {counts['refuted']} refuted, {counts['undecided']} undecided")
            bar.set(len(result))

        try:
            tried: set[str] = set()
            fresh = [n for n in todo if n not in refutations]
            for axis in ("cols", "rows") if not (stop_at_witness and counts["tiles"]) else ():
                left = [n for n in fresh if n not in result]
                specs = _band_specs(left, axis)
                task = functools.partial(_band_job, tiles, n_colors, tuple(specs), tuple(left), *common)
                if dispatch(task, len(specs), run, take_band, show):
                    interrupted = True
                    break
                tried.update(n for n in left if parse_board_name(n)[2] == 0)
            # the largest first (todo's order): a torus whose bands all tile is likely tiled, and the
            # largest such is the likeliest (periodic-10-30: its 30x30 torus, through a cylinder)
            left = [n for n in todo if n not in result]
            if not interrupted and not (stop_at_witness and counts["tiles"]):
                skip = {n: cylinder_refuted(n) for n in tried}
                task = functools.partial(_job, tiles, n_colors, tuple(left), refutations, skip, *common)
                interrupted = dispatch(task, len(left), run, lambda i, cert: take(left[i], cert), show)
        except KeyboardInterrupt:
            interrupted = True
    if stopped or (stop_at_witness and counts["tiles"]):
        interrupted = False
        first = stopped[0] if stopped else next(n for n, c in result.items() if c.status == "tiles")
        why = f"not decided: the sweep stopped at the first tiled board, the {first}, which shows the set periodic"
    else:
        why = "interrupted (Ctrl-C) before it was decided" if interrupted else \
            f"time limit of {run.deadline.time_limit:.3g} s reached before it was decided" \
            if run.deadline.time_limit is not None else "not decided"
    return [result.get(n) or Certificate(n, "undecided", None, "sat", {"why": why}) for n in names], interrupted


def dispatch(task, n_jobs: int, run: RunOptions, take, show) -> bool:
    """Run jobs ``task(seed=i)``, ``0 <= i < n_jobs``: as Dask futures on ``run.cluster``, on
    ``run.workers`` local processes (default 2), or here (one worker, or one job), until
    ``run.deadline`` passes. ``take(i, result)`` receives each result in this process as its job
    ends (True: stop), ``show()`` is called as they come. Returns True when stopped by ``take``
    or Ctrl-C (the period sweep; the census of :mod:`tilesolve.engine.census`)."""
    if n_jobs == 0:
        return False
    if run.cluster is not None:
        return _on_dask(task, n_jobs, run, take, show)
    if (run.workers or 2) > 1 and n_jobs > 1:
        return _on_pool(task, n_jobs, min(run.workers or 2, n_jobs), run, take, show)
    for i in range(n_jobs):
        if run.deadline.expired():
            break
        show()
        if take(i, task(seed=i)):
            return True
    return False


def _on_pool(task, n_jobs: int, n_workers: int, run: RunOptions, take, show) -> bool:
    """Every job on local worker processes, ``show()`` as they end; True when Ctrl-C stopped it."""
    from multiprocessing.connection import wait as wait_for_any

    from tilesolve.engine.portfolio import GRACE_S, _Pool, _unpack_exception

    pool = _Pool(task, list(range(n_jobs)), n_workers, run.deadline, "aperiodic sweep")
    try:
        pool.start()
        while True:
            busy = pool.busy()
            if not busy:
                return False
            show()
            timeout = None
            if run.deadline.time_limit is not None:
                timeout = run.deadline.time_limit + GRACE_S - run.deadline.elapsed()
                if timeout <= 0:
                    return False
            ready = set(wait_for_any([w.conn for w in busy], min(timeout, 0.5) if timeout else 0.5))
            for w in busy:
                if w.conn not in ready:
                    continue
                kind, i, payload = pool._receive(w)
                if kind == "error":
                    raise _unpack_exception(payload)
                if take(i, payload):
                    return True
                pool.assign(w)
    except KeyboardInterrupt:
        return True
    finally:
        pool.close()


def _on_dask(task, n_jobs: int, run: RunOptions, take, show) -> bool:
    """Every job as a Dask future, ``show()`` as they end; True when Ctrl-C stopped it."""
    from tilesolve.engine.portfolio import GRACE_S, _connect

    client, owned = _connect(run.cluster)
    from distributed import as_completed

    futures: list = []
    try:
        futures = [client.submit(task, seed=i, pure=False) for i in range(n_jobs)]
        index = {f.key: i for i, f in enumerate(futures)}
        timeout = None
        if run.deadline.time_limit is not None:
            timeout = max(0.0, run.deadline.time_limit + GRACE_S - run.deadline.elapsed())
        pending = as_completed(futures, loop=client.loop, timeout=timeout)
        while True:
            show()
            try:
                fut = next(pending)
            except StopIteration:
                return False
            except TimeoutError:
                return False
            if take(index[fut.key], fut.result()):
                return True
    except KeyboardInterrupt:
        return True
    finally:
        if futures:
            client.cancel(futures)
        if owned:
            client.close()

