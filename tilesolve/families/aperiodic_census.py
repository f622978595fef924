"""A census of small Wang tile sets: every set of ``N`` tiles over at most ``K`` colours per
axis, up to symmetry, classified as finite, periodic or undecided at given bounds, each with
its certificate (issue 20 §4; class notes Part II §8.2 for Wang's procedure).

The sets, one per class of colour relabellings, turns and mirrors, and the runs on local cores
or a Dask cluster are the engine's (:mod:`tilesolve.engine.census`); this facade classifies a
set and keeps the census file.

Classes (:func:`classify`), every one with a certificate checked here
    * ``periodic``: a torus tiled by the set (the transducer route's cycle, Jeandel-Rao §3),
      checked by the family's verifier (:func:`tilesolve.verify.aperiodic.witness_violations`);
    * ``finite``: the largest tiled square ``n x n`` (a witness, verified likewise) and the
      ``(n + 1) x (n + 1)`` square refuted by SAT with a checked DRAT proof
      (:func:`tilesolve.engine.aperiodic.square_scan`), so the set tiles no plane (Extension
      Theorem); searched when the transducer finds ``T_k`` empty, up to the larger side of the
      ``k x w`` rectangle it rules out (:func:`~tilesolve.constructive.transducer.strip_width`);
    * ``undecided``: neither within the bounds (or a time limit).

    Jeandel and Rao proved that no set of at most 10 tiles is aperiodic, so with bounds large
    enough every set ends finite or periodic.

The census file
    A header line (:data:`CENSUS_FORMAT`, the sets and bounds), then one JSON record a set,
    appended as jobs end: a census stopped by Ctrl-C, a time limit or a lost worker resumes from
    it (:func:`census` with ``resume``). The DRAT proof of every refutation is kept beside it
    (``CENSUS.proofs/``, :func:`tilesolve.engine.aperiodic.cache_proof_dir`). A record is a
    claim, not evidence: a resumed record is kept only when its witnesses pass the verifier
    again and its refutation's kept proof refutes the CNF re-derived from the set and the board
    (:func:`tilesolve.engine.certificates.recheck_unsat`); the others, and undecided ones, are
    classified again.

Examples
--------
>>> rec = classify([0], 2, 4, 4, Deadline(None))  # the tile with colour 0 on every side
>>> rec["class"], rec["torus"]
('periodic', 'torus 1x1')
"""

from __future__ import annotations

import functools
import json
import os
import time
from dataclasses import dataclass, field

import numpy as np

from tilesolve.deadline import Deadline
from tilesolve.engine.census import canonical_sets, run_jobs, tiles_of
from tilesolve.errors import InvalidProblem
from tilesolve.model.run import RunOptions

__all__ = ["classify", "census", "CensusResult", "CENSUS_FORMAT", "CLASSES"]

#: The first line of a census file (then one JSON record a set).
CENSUS_FORMAT = "tilesolve/wang-census"
#: What a census says of a set.
CLASSES = ("finite", "periodic", "undecided")


def classify(numbers, k: int, max_square: int, max_period: int, deadline: Deadline, solver: str | None = None,
             proof_dir: str | None = None, store: str | None = None) -> dict:
    """The census record of one set (tile numbers over ``k`` colours per axis).

    The transducer (:func:`tilesolve.constructive.transducer.decide`, up to
    ``max(max_square, max_period)`` rows) points the way: a periodic cycle is a torus witness; an
    empty ``T_k`` sends the squares to SAT (:func:`tilesolve.engine.aperiodic.square_scan` up to
    ``max_square``), whose refutation comes with a checked proof (written to ``proof_dir`` with
    its CNF, and to ``store`` alone, where a resumed census re-checks it). Every witness is
    checked by the family's verifier before it is recorded (a failure is an
    :class:`~tilesolve.errors.InternalError`).

    Returns
    -------
    dict
        ``set`` (tile numbers), ``tiles`` (N, E, S, W), ``class`` (one of ``finite``,
        ``periodic``, ``undecided``), ``why`` (in words), ``time_s``, and for ``periodic``
        ``torus`` (board name) and ``tiling``; for ``finite`` ``largest_square``, ``tiling``
        (its witness) and ``refutation`` (board, proof evidence).
    """
    from tilesolve.constructive.transducer import decide, strip_width
    from tilesolve.deadline import TimeLimitReached
    from tilesolve.engine.aperiodic import square_scan
    from tilesolve.engine.certificates import writing_proofs
    from tilesolve.errors import InternalError
    from tilesolve.model.aperiodic import AperiodicProblem, Certificate
    from tilesolve.model.board import WangTileSet
    from tilesolve.verify.aperiodic import witness_violations

    t0 = time.perf_counter()
    numbers = [int(x) for x in numbers]
    tiles = tiles_of(numbers, k)
    ts = WangTileSet(tiles, int(k))
    problem = AperiodicProblem(ts, int(max_square), int(max_period))
    rec: dict = {"set": numbers, "tiles": tiles.tolist()}

    def checked(cert) -> None:
        bad = witness_violations(problem, cert)
        if bad:
            raise InternalError(f"census set {numbers}: the witness of the {cert.board} fails the verifier: "
                                f"{bad[0].message}")

    def done(cls: str, why: str, **more) -> dict:
        return {**rec, "class": cls, "why": why, **more, "time_s": round(time.perf_counter() - t0, 6)}

    v = decide(ts, max_k=max(int(max_square), int(max_period)), deadline=deadline)
    if v.verdict == "periodic":
        rows, cols = v.torus.shape
        cert = Certificate(f"torus {rows}x{cols}", "tiles", v.torus, "transducer")
        checked(cert)
        return done("periodic", f"tiles the {rows}x{cols} torus (a cycle of T_{v.k}; witness verified)",
                    torus=cert.board, tiling=v.torus.tolist())
    if v.verdict != "empty":
        return done("undecided", f"transducer: {v.reason}; no torus of height at most {v.k}")
    run = RunOptions(seed=0, deadline=deadline, solver=solver)
    try:
        # no k x w rectangle is tiled: the square scan need not look past the larger side
        w = strip_width(ts, v.k, deadline=deadline)
        side = int(max_square) if w is None else min(int(max_square), max(v.k, w))
        with writing_proofs(proof_dir), writing_proofs(store, cnf=False):
            certs, largest = square_scan(ts, side, run)
    except (TimeLimitReached, InvalidProblem) as exc:
        return done("undecided", f"T_{v.k} is empty, the squares undecided ({exc})")
    if largest is None:
        return done("undecided", f"T_{v.k} is empty, the squares undecided ({certs[-1].evidence.get('why')})")
    if largest >= side:
        if side < int(max_square):
            raise InternalError(f"census set {numbers}: the transducer rules out a {side}x{side} square "
                                f"(T_{v.k} is empty), SAT tiled one")
        return done("undecided", f"T_{v.k} is empty but every square up to {largest}x{largest} is tiled")
    by_side = {c.board: c for c in certs}
    witness = by_side.get(f"square {largest}x{largest}")
    refuted = by_side[f"square {largest + 1}x{largest + 1}"]
    checked(witness)
    ev = refuted.evidence
    return done("finite", f"tiles the {largest}x{largest} square, not the {largest + 1}x{largest + 1} one "
                          "(checked proof): no plane", largest_square=largest, tiling=witness.tiling.tolist(),
                refutation={"board": refuted.board, **{key: ev.get(key) for key in (
                    "encoding", "cnf_sha256", "drat_sha256", "proof_lemmas", "proof_checked_lemmas", "checker")}})



def _classify_all(k: int, max_square: int, max_period: int, deadline: Deadline, solver: str | None,
                  proof_dir: str | None, store: str, sets: list) -> list[dict]:
    """One job of a census (in a worker process): the records of its sets."""
    return [classify(s, k, max_square, max_period, deadline, solver, proof_dir, store) for s in sets]


@dataclass
class CensusResult:
    """What a census established.

    Attributes
    ----------
    n_tiles, colours, max_square, max_period : int
    records : list of dict
        One per canonical set decided or left undecided, in enumeration order (see
        :func:`classify`); sets not reached (a stop) have none.
    n_sets : int
        Canonical sets (classes of sets up to symmetry).
    resumed : int
        Records taken from the output file (their witnesses re-verified).
    interrupted : bool
    seconds : float
    """

    n_tiles: int
    colours: int
    max_square: int
    max_period: int
    n_sets: int
    records: list = field(default_factory=list)
    resumed: int = 0
    interrupted: bool = False
    seconds: float = 0.0

    def counts(self) -> dict[str, int]:
        """Sets of each class, and ``"not reached"``."""
        out = {c: sum(r["class"] == c for r in self.records) for c in CLASSES}
        out["not reached"] = self.n_sets - len(self.records)
        return out

    @property
    def undecided(self) -> list[dict]:
        return [r for r in self.records if r["class"] == "undecided"]

    @property
    def complete(self) -> bool:
        return len(self.records) == self.n_sets and not self.undecided


def _header(n_tiles: int, k: int, max_square: int, max_period: int, n_sets: int) -> dict:
    return {"format": CENSUS_FORMAT, "version": 1, "tiles": n_tiles, "colours": k, "max_square": max_square,
            "max_period": max_period, "sets": n_sets}


def _resumed(path: str, header: dict, k: int, max_square: int, max_period: int, deadline: Deadline
             ) -> dict[tuple, dict]:
    """The records of an earlier run of the same census in ``path`` that still hold: a witness
    re-verified, a refutation's kept proof re-checked against the re-derived CNF. A file of
    another census is refused; a line cut short or not confirmed is dropped (its set is
    classified again)."""
    from tilesolve.engine.aperiodic import board_problem, cache_proof_dir
    from tilesolve.engine.certificates import recheck_unsat
    from tilesolve.inputs import read_input
    from tilesolve.model.aperiodic import AperiodicProblem, Certificate
    from tilesolve.model.board import WangTileSet
    from tilesolve.verify.aperiodic import witness_violations

    lines = read_input(path, "census ").decode("utf-8", errors="replace").splitlines()
    try:
        first = json.loads(lines[0]) if lines else None
    except ValueError:
        first = None
    if first != header:
        raise InvalidProblem(f"{path} is not a census of these sets and bounds ({json.dumps(header)}); "
                             "give another output file or the same options")
    out: dict[tuple, dict] = {}
    for line in lines[1:]:
        try:
            rec = json.loads(line)
            key = tuple(int(x) for x in rec["set"])
            cls = rec["class"]
            ts = WangTileSet(tiles_of(key, k), k)
            problem = AperiodicProblem(ts, max_square, max_period)
            if cls == "periodic":
                ok = not witness_violations(problem, Certificate(rec["torus"], "tiles", np.asarray(rec["tiling"]),
                                                                 "transducer"))
            elif cls == "finite":
                n = int(rec["largest_square"])
                ref = rec["refutation"]
                ok = (not witness_violations(problem, Certificate(f"square {n}x{n}", "tiles",
                                                                  np.asarray(rec["tiling"])))
                      and ref["board"] == f"square {n + 1}x{n + 1}"
                      and recheck_unsat(board_problem(ts, ref["board"]), ref, cache_proof_dir(path),
                                        deadline=deadline).ok)
            else:
                ok = cls == "undecided"
        except (ValueError, KeyError, TypeError, IndexError, InvalidProblem):
            continue
        if ok:
            out[key] = rec
    return out


def census(n_tiles: int, k: int, run: RunOptions, out: str | os.PathLike, *, max_square: int = 12,
           max_period: int = 12, resume: bool = False, proof_dir: str | os.PathLike | None = None) -> CensusResult:
    """Classify every canonical set of ``n_tiles`` tiles over at most ``k`` colours per axis.

    Parameters
    ----------
    n_tiles, k : int
    run : RunOptions
        ``workers`` local processes (default 2; 1 runs here) or ``cluster`` (a Dask scheduler
        address or client); ``deadline`` stops the census (the sets not reached have no record);
        ``progress`` counts the sets.
    out : path
        The census file: a header line, then one JSON record a set (:func:`classify`), appended
        as jobs end. Written anew unless ``resume``.
    max_square, max_period : int
        The bounds: squares up to ``max_square``, transducers up to ``max(max_square,
        max_period)`` rows (so tori of that height at most).
    resume : bool
        Continue the census in ``out``: its records whose certificates still hold are kept
        (undecided ones are classified again), the other sets classified.
    proof_dir : path, optional
        Where the CNF and DRAT proof of every refutation are written.

    Returns
    -------
    CensusResult
    """
    from tilesolve.engine.aperiodic import cache_proof_dir
    from tilesolve.io.atomic import write_text_atomic

    t0 = time.perf_counter()
    for what, v in (("max square", max_square), ("max period", max_period)):
        if int(v) < 1:
            raise InvalidProblem(f"{what} must be at least 1, got {v}")
    n_tiles, k, max_square, max_period = int(n_tiles), int(k), int(max_square), int(max_period)
    sets = canonical_sets(n_tiles, k)
    header = _header(n_tiles, k, max_square, max_period, len(sets))
    out = os.fspath(out)
    done: dict[tuple, dict] = {}
    if resume and os.path.exists(out):
        done = {key: rec for key, rec in _resumed(out, header, k, max_square, max_period, run.deadline).items()
                if rec["class"] != "undecided"}
    write_text_atomic(out, "".join(json.dumps(x, separators=(",", ":")) + "\n"
                                   for x in [header, *done.values()]))
    todo = [s.tolist() for s in sets if tuple(s.tolist()) not in done]
    job = functools.partial(_classify_all, k, max_square, max_period, run.deadline, run.solver,
                            None if proof_dir is None else os.fspath(proof_dir), cache_proof_dir(out))
    records = dict(done)
    with run.progress.task("census", total=len(sets), unit="set") as bar, open(out, "a", encoding="utf-8") as fh:
        def show() -> None:
            counts = {c: sum(r["class"] == c for r in records.values()) for c in CLASSES}
            bar.note(", ".join(f"{v} {c}" for c, v in counts.items()))
            bar.set(len(records))

        def take(recs: list[dict]) -> None:
            for rec in recs:
                records[tuple(rec["set"])] = rec
                fh.write(json.dumps(rec, separators=(",", ":")) + "\n")
            fh.flush()

        interrupted = run_jobs(todo, job, run, take, show)
        show()
    ordered = [records[tuple(s.tolist())] for s in sets if tuple(s.tolist()) in records]
    return CensusResult(n_tiles, k, max_square, max_period, len(sets), ordered, len(done), interrupted,
                        time.perf_counter() - t0)
