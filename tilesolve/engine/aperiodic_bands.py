"""Bands shared by tori: one band refuted and checked once certifies every torus that holds it.

The first ``h`` columns of a ``p x q`` torus (any shear, ``h < q``) are a cylinder of ``p`` rows
that wrap top to bottom and two open sides: the clauses of the named encoding
``wang-tiles-cnf`` on those cells (:meth:`~tilesolve.encodings.wang_tiles.TileEncoding.part`)
are the same for every ``q > h`` and every shear, up to renaming the cells' variables (a
shear moves only the horizontal wrap). Likewise the first ``h`` rows of an unsheared torus
(``h < p``) for every ``p``, with the same variables (cells are numbered row-major).

So a band is solved once (:func:`refute_band`, smallest width first), on its *canonical*
formula: the band of the ``p x (h + 1)`` (or ``(h + 1) x q``) torus. Its DRAT proof is checked
once by :mod:`tilesolve.verify.drat` against that formula, trimmed to the lemmas the check used
(and the deletions of the clauses kept, :func:`trim`), and the trimmed proof is checked again.
Each torus then gets the trimmed proof renamed into its own variables (:func:`band_refutation`)
once the renamed band formula is found to be exactly the torus's own clauses on the band's
cells. A proof whose lemmas are all RUP (none accepted by RAT; required here) stays valid when
clauses are added to its formula, so it refutes the torus's whole formula, which ``verify``
re-derives from the torus's name and checks the renamed proof against, as any refutation.

Jeandel-Rao's tori with ``p, q <= 24``: the narrowest refuted band of first columns is 3 to 15
wide for every height but 14 and 23 (none up to 23 columns), and of first rows 4 to 20 tall for
every width but 8, 13, 16, 21 and 24; bands up to 16 leave 78 of the 576 tori to be solved whole,
most of them small (benchmarks/bench_aperiodic_sat.py).
"""

from __future__ import annotations

import hashlib
import os
import time
from dataclasses import dataclass

import numpy as np

from tilesolve.deadline import Deadline
from tilesolve.model.aperiodic import Certificate, parse_board_name
from tilesolve.model.board import WangTileSet
from tilesolve.model.solution import Status

__all__ = ["BandProof", "refute_band", "band_refutation", "renamed_text", "trim", "covers"]


@dataclass(frozen=True)
class BandProof:
    """A band refuted with a checked, trimmed DRAT proof in its canonical formula's variables.

    Attributes
    ----------
    axis : {"cols", "rows"}
        The first ``width`` columns of tori with ``length`` rows, or the first ``width`` rows
        of unsheared tori with ``length`` columns.
    length, width : int
    lits, sizes, dels : numpy.ndarray
        The trimmed proof's steps (literals, sizes, deletion flags; the empty clause last).
    stats : dict
        The solver and the checks' figures (recorded in each torus's evidence).
    """

    axis: str
    length: int
    width: int
    lits: np.ndarray
    sizes: np.ndarray
    dels: np.ndarray
    stats: dict

    def what(self) -> str:
        return f"its first {self.width} {'column' if self.axis == 'cols' else 'row'}(s)"


def covers(band: BandProof, name: str) -> bool:
    """True when ``band`` holds in the torus ``name`` (its band is the canonical one renamed)."""
    rows, cols, shear = parse_board_name(name)
    if shear < 0:
        return False
    if band.axis == "cols":
        return rows == band.length and cols > band.width
    return shear == 0 and cols == band.length and rows > band.width


def _canonical(tileset: WangTileSet, axis: str, length: int, width: int, deadline: Deadline | None = None):
    """The canonical band's torus encoding and cell mask."""
    from tilesolve.engine.aperiodic import board_encoding

    name = f"torus {length}x{width + 1}" if axis == "cols" else f"torus {width + 1}x{length}"
    enc = board_encoding(tileset, name, deadline=deadline)
    return enc, enc.labels[:, 1 if axis == "cols" else 0] < width


def trim(formula, proof, used: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The steps of ``proof`` that a backward check of it against ``formula`` used (``used``,
    :attr:`~tilesolve.verify.drat.DratResult.used`), in order, with the deletions of the
    clauses kept (each deletion matched, as the checker does, to the last live copy of its
    clause), and the empty clause: ``(literals, sizes, deletion flags)``. The result must be
    checked again (a deletion the checker ignored in ``proof`` may count in the trimmed one).

    Examples
    --------
    >>> f = [[1, 2], [1, -2], [-1, 2], [-1, -2]]
    >>> lits, sizes, dels = trim(f, ["3 0", "1 0", "d 3 0", "0"], np.array([1]))
    >>> lits.tolist(), sizes.tolist(), dels.tolist()
    ([1], [1, 0], [0, 0])
    """
    from tilesolve.verify.drat import formula_arrays, proof_arrays

    f_lits, f_sizes, _ = formula_arrays(formula)
    p_lits, p_sizes, p_del = proof_arrays(proof)
    fkeys, pkeys = _keys(f_lits, f_sizes), _keys(p_lits, p_sizes)
    live: dict[int, list[int]] = {}
    for key in fkeys:
        live.setdefault(key, []).append(-1)  # a formula clause: kept
    is_used = np.zeros(p_sizes.size, bool)
    is_used[used] = True
    keep = np.zeros(p_sizes.size, bool)
    for i in range(int(used.max()) + 1 if used.size else 0):
        if p_del[i]:
            ids = live.get(pkeys[i])
            if ids:
                j = ids.pop()
                keep[i] = j < 0 or is_used[j]
        else:
            live.setdefault(pkeys[i], []).append(i)
            keep[i] = is_used[i]
    starts = np.concatenate(([0], np.cumsum(p_sizes)[:-1]))
    steps = np.flatnonzero(keep)
    lits = np.concatenate([p_lits[starts[i]:starts[i] + p_sizes[i]] for i in steps] or [np.zeros(0, np.int64)])
    return lits, np.append(p_sizes[steps], 0), np.append(p_del[steps], 0).astype(np.int8)


def _keys(lits: np.ndarray, sizes: np.ndarray) -> list[int]:
    """Each clause's identity as a deletion names it (its literals in any order): a 64-bit hash
    of its literals. Two clauses that collide can only mismatch a deletion, which the check of
    the trimmed proof then catches.

    >>> k = _keys(np.array([1, -2, -2, 1, 3, 1, 4, 2, 3]), np.array([2, 2, 1, 2, 2]))
    >>> k[0] == k[1], k[0] == k[2], k[3] == k[4]  # the last two: the same sum of literal codes
    (True, False, False)
    """
    if lits.size == 0:
        return [0] * sizes.size
    x = (np.abs(lits) * 2 + (lits < 0)).astype(np.uint64)
    x = x * np.uint64(0x9E3779B97F4A7C15) + np.uint64(0x632BE59BD9B4E019)  # splitmix64's finaliser
    x = (x ^ (x >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
    x = (x ^ (x >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    x ^= x >> np.uint64(31)
    starts = np.concatenate(([0], np.cumsum(sizes)[:-1]))
    h = np.add.reduceat(x, np.minimum(starts, x.size - 1))
    return np.where(sizes > 0, h + sizes.astype(np.uint64), 0).tolist()


def refute_band(tileset: WangTileSet, axis: str, length: int, max_width: int, *, solver: str, seed: int | None,
                deadline: Deadline, budget: tuple[int, float] | None = None) -> BandProof | None:
    """The narrowest band (width ``1 .. max_width``) that cannot be tiled, with its checked and
    trimmed proof; ``None`` when every band up to ``max_width`` is tiled, or when the deadline,
    a proof that does not check, or a lemma accepted only by RAT stops it. With ``budget``
    ``(width, seconds)``, a band wider than ``width`` that is not solved within ``seconds``
    stops it too (no wider band is tried)."""
    from tilesolve.engine.sat import solve_cnf
    from tilesolve.verify.drat import check_drat, drat_bytes

    for width in range(1, max_width + 1):
        if deadline.expired():
            return None
        enc, mask = _canonical(tileset, axis, length, width, deadline)
        part = enc.part(mask)
        t0 = time.perf_counter()
        within = deadline.within(budget[1]) if budget is not None and width > budget[0] else deadline
        r = solve_cnf(part, solver=solver, with_proof=True, seed=seed, deadline=within)
        if r.status is Status.SAT:
            continue
        if r.status is not Status.UNSAT or r.proof is None:
            return None
        solve_s = time.perf_counter() - t0
        proof = list(r.proof)
        if not proof or proof[-1].strip() != "0":
            proof.append("0")
        first = check_drat(part, proof, time_limit=deadline.remaining())
        if not first.verified or first.rat_lemmas:
            return None
        lits, sizes, dels = trim(part, proof, first.used)
        chk = check_drat(part, drat_bytes(lits, sizes, dels), time_limit=deadline.remaining())
        if not chk.verified or chk.rat_lemmas:
            return None
        stats = {"solver": r.solver, "band_solve_s": round(solve_s, 6), "proof_lines": len(proof),
                 "proof_lemmas": chk.lemmas, "proof_checked_lemmas": chk.checked,
                 "proof_check_s": round(first.time_s + chk.time_s, 6), "proof_trimmed_from": first.lemmas}
        return BandProof(axis, length, width, lits, sizes, dels.astype(np.int8), stats)
    return None


def _rows_of(blocks) -> dict[str, np.ndarray]:
    """Every block's clauses by label, each clause's literals sorted and the clauses sorted."""
    out: dict[str, list[np.ndarray]] = {}
    for b in blocks:
        out.setdefault((str(b.label), b.lits.shape[1]), []).append(b.lits)
    rows = {}
    for key, parts in out.items():
        a = np.sort(np.concatenate(parts), axis=1)
        rows[key] = a[np.lexsort(a.T[::-1])]
    return rows


def renamed_text(band: BandProof, ren: np.ndarray) -> bytes:
    """The DRAT text of ``band``'s proof with variable ``v`` renamed ``ren[v]``: the text
    :func:`~tilesolve.verify.drat.drat_bytes` writes of the renamed steps, put together from one
    word per literal of the band (a torus's proof is written in a few milliseconds, where
    writing every number costs a tenth of a second).

    >>> band = BandProof("cols", 1, 1, np.array([1, -2, 2]), np.array([2, 1, 0]), np.array([0, 1, 0]), {})
    >>> renamed_text(band, np.array([0, 7, 30]))
    b'7 -30 0\\nd 30 0\\n0\\n'
    """
    n = ren.size - 1
    words = np.array([f"{-x} " for x in ren[:0:-1].tolist()] + ["0\n"] + [f"{x} " for x in ren[1:].tolist()] + ["d "],
                     dtype=object)
    ends = np.cumsum(band.sizes)
    tok = np.insert(band.lits + n, ends, n)  # a literal's word, or "0\n" ending its step
    firsts = (ends - band.sizes + np.arange(band.sizes.size))[band.dels != 0]
    tok = np.insert(tok, firsts, 2 * n + 1)  # "d " before a deletion's first literal
    return "".join(words[tok].tolist()).encode("ascii")


def band_refutation(tileset: WangTileSet, name: str, band: BandProof, *, deadline: Deadline,
                    proof_dirs: tuple[tuple[str, bool], ...] = ()) -> Certificate | None:
    """The torus ``name`` refuted by ``band`` (:func:`covers` it): the band's proof renamed into the
    torus's variables, once the renamed canonical band formula is exactly the torus's own
    clauses on the band's cells; ``None`` when it is not. The CNF (unless ``False``) and the
    proof are written to each ``(directory, with CNF)`` of ``proof_dirs``."""
    from tilesolve.engine.aperiodic import board_encoding
    from tilesolve.engine.certificates import proof_name, write_proof_files
    from tilesolve.verify.drat import dimacs_bytes

    t0 = time.perf_counter()
    rows, cols, _ = parse_board_name(name)
    canon, cmask = _canonical(tileset, band.axis, band.length, band.width, deadline)
    enc = board_encoding(tileset, name, deadline=deadline)
    m = enc.n_tiles
    mask = enc.labels[:, 1 if band.axis == "cols" else 0] < band.width
    # canonical variable -> the torus's: cell (r, c) keeps its row and column
    a = np.arange(canon.n_cells)
    r, c = canon.labels[a, 0], canon.labels[a, 1]
    cell = r * cols + c
    ren = np.zeros(canon.n_vars + 1, np.int64)
    ren[1:] = (1 + cell[:, None] * m + np.arange(m)[None, :]).ravel()
    renamed = canon.part(cmask)
    for b in renamed.blocks:
        b.lits[...] = np.sign(b.lits) * ren[np.abs(b.lits)]
    want, got = _rows_of(renamed.blocks), _rows_of(enc.part(mask).blocks)
    if want.keys() != got.keys() or any(not np.array_equal(want[k], got[k]) for k in want):
        return None
    drat = renamed_text(band, ren)
    cnf = dimacs_bytes(enc.hard)
    ev = {"encoding": dict(enc.named), "cnf_sha256": hashlib.sha256(cnf).hexdigest(),
          "drat_sha256": hashlib.sha256(drat).hexdigest(), "clauses": len(enc.hard), "variables": enc.n_vars,
          **{k: v for k, v in band.stats.items() if k != "solver"}}
    name_ = proof_name(ev["cnf_sha256"], ev["drat_sha256"])
    for directory, with_cnf in proof_dirs:
        write_proof_files(directory, name_, cnf if with_cnf else None, drat)
        ev["proof_name"] = name_
    what, st = band.what(), band.stats
    ev.update(solver=st["solver"], checker="tilesolve.verify.drat",
              reason=(f"proved unsatisfiable by {st['solver']}; DRAT proof of {st['proof_lemmas']} lemma(s) (trimmed "
                      f"from {st['proof_trimmed_from']}; {st['proof_checked_lemmas']} used, none by RAT) checked by "
                      f"tilesolve.verify.drat against the formula of {what}, solved "
                      "once for every torus that holds them; that formula, renamed, is this torus's own clauses on "
                      f"those cells, so the proof refutes {what}"),
              band=what)
    return Certificate(name, "refuted", None, "sat", ev, round(time.perf_counter() - t0, 6))


def proof_dirs(proof_dir: str | None, store: str | None) -> tuple[tuple[str, bool], ...]:
    """Where a sweep's job writes proofs: the report's proof directory (CNF and proof) and the
    cache's store (the proof only)."""
    return tuple((os.fspath(d), cnf) for d, cnf in ((proof_dir, True), (store, False)) if d is not None)
