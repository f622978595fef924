"""A small independent forward DRAT proof checker (pure Python, no solver imports).

When a SAT solver says "unsatisfiable", tilesolve keeps the solver's DRAT proof and checks
it here, so that an ``unsat`` answer (e.g. the dappled paper's Example 6.2, §6 item 7) is a
certificate rather than a claim. The checker is written from the definition of DRAT
(Wetzler, Heule, Hunt, *DRAT-trim: Efficient checking and trimming using expressive
clausal proofs*, SAT 2014):

* a lemma ``C`` is accepted if it is **RUP** — unit propagation on ``F and not C``
  reaches a conflict — or, failing that, **RAT** on its first literal ``l``: for every
  clause ``D`` of ``F`` containing ``-l`` the resolvent ``C | (D - {-l})`` is RUP;
* accepted lemmas are added to ``F``; ``d`` lines delete clauses from ``F``;
* the proof is valid when ``F`` becomes inconsistent under unit propagation (the empty
  clause is RUP).

Like drat-trim, deletions of clauses that are currently the reason of a top-level unit
are ignored (keeping a clause can only make RUP easier and RAT harder, so ignoring a
deletion never accepts an invalid proof). The checker works forwards with two watched
literals per clause. It imports nothing from the solvers or encodings it checks.

Examples
--------
>>> f = [[1, 2], [1, -2], [-1, 2], [-1, -2]]
>>> check_drat(f, ["1 0", "0"]).verified
True
>>> r = check_drat([[-2, 3]], ["2 0"])
>>> r.status, r.reason
('failed', 'lemma 1 (proof line 1: 2 0) is neither RUP nor RAT')
"""

from __future__ import annotations

import os
import time
from dataclasses import dataclass
from typing import Iterable, Sequence

__all__ = ["DratResult", "check_drat", "parse_drat"]


@dataclass(frozen=True)
class DratResult:
    """Verdict of :func:`check_drat`.

    Attributes
    ----------
    status : {"verified", "failed", "skipped", "unknown"}
        ``verified``: the proof refutes the formula; ``failed``: a lemma is neither RUP
        nor RAT, or the proof never derives the empty clause; ``skipped``: over the size
        guard, not checked; ``unknown``: the time guard stopped the check.
    reason : str
        One line for humans.
    lemmas, deletions, rat_lemmas, ignored_deletions : int
        Counts of proof steps seen.
    time_s : float
    """

    status: str
    reason: str
    lemmas: int = 0
    deletions: int = 0
    rat_lemmas: int = 0
    ignored_deletions: int = 0
    time_s: float = 0.0

    @property
    def verified(self) -> bool:
        return self.status == "verified"


def _read_varint(data: bytes, i: int) -> tuple[int, int]:
    shift = 0
    x = 0
    while True:
        b = data[i]
        i += 1
        x |= (b & 0x7F) << shift
        if b < 0x80:
            return x, i
        shift += 7


def parse_drat(proof) -> list[tuple[bool, list[int]]]:
    """Parse a DRAT proof into ``[(is_deletion, literals), ...]``.

    Accepts a list of text lines (as :meth:`pysat.solvers.Solver.get_proof` returns), a
    string, a path to a file, or bytes in text or binary DRAT format.
    """
    is_path = isinstance(proof, os.PathLike) or (
        isinstance(proof, str) and "\n" not in proof and not proof.strip().endswith(" 0") and os.path.isfile(proof)
    )
    if is_path:
        with open(proof, "rb") as fh:
            proof = fh.read()
    if isinstance(proof, (bytes, bytearray)):
        data = bytes(proof)
        if data[:1] in (b"a", b"d") and any(b > 127 or b == 0 for b in data[:64]):
            return _parse_binary(data)
        proof = data.decode("ascii")
    if isinstance(proof, str):
        proof = proof.splitlines()
    out: list[tuple[bool, list[int]]] = []
    for line in proof:
        s = line.strip() if isinstance(line, str) else line.decode("ascii").strip()
        if not s or s[0] == "c":
            continue
        delete = s[0] == "d"
        toks = s[1:].split() if delete else s.split()
        nums = [int(t) for t in toks]
        if not nums or nums[-1] != 0:
            raise ValueError(f"DRAT line does not end with 0: {s!r}")
        out.append((delete, nums[:-1]))
    return out


def _parse_binary(data: bytes) -> list[tuple[bool, list[int]]]:
    out = []
    i, n = 0, len(data)
    while i < n:
        tag = data[i]
        i += 1
        if tag not in (0x61, 0x64):
            raise ValueError(f"bad binary DRAT tag {tag:#x} at byte {i - 1}")
        lits = []
        while True:
            x, i = _read_varint(data, i)
            if x == 0:
                break
            lits.append(-(x >> 1) if x & 1 else x >> 1)
        out.append((tag == 0x64, lits))
    return out


class _Checker:
    """Clause database with two watched literals and a top-level trail."""

    def __init__(self, n_vars: int) -> None:
        self.off = n_vars
        self.lv = [0] * (2 * n_vars + 1)  # literal value: 1 true, -1 false, 0 unassigned
        self.watches: list[list[int]] = [[] for _ in range(2 * n_vars + 1)]
        self.clauses: list[list[int] | None] = []
        self.index: dict[tuple[int, ...], list[int]] = {}
        self.trail: list[int] = []
        self.qhead = 0
        self.inconsistent = False

    # -- assignment --------------------------------------------------------------
    def _assign(self, lit: int) -> None:
        self.lv[lit + self.off] = 1
        self.lv[-lit + self.off] = -1
        self.trail.append(lit)

    def _backtrack(self, size: int) -> None:
        lv, off, trail = self.lv, self.off, self.trail
        for lit in trail[size:]:
            lv[lit + off] = 0
            lv[-lit + off] = 0
        del trail[size:]
        self.qhead = size

    def _propagate(self) -> bool:
        """Unit propagation; True on conflict."""
        lv, off, trail, watches, clauses = self.lv, self.off, self.trail, self.watches, self.clauses
        while self.qhead < len(trail):
            false_lit = -trail[self.qhead]
            self.qhead += 1
            ws = watches[false_lit + off]
            i = j = 0
            n = len(ws)
            while i < n:
                ci = ws[i]
                i += 1
                c = clauses[ci]
                if c is None:  # deleted: drop the watch lazily
                    continue
                if c[0] == false_lit:
                    c[0], c[1] = c[1], false_lit
                first = c[0]
                if lv[first + off] == 1:
                    ws[j] = ci
                    j += 1
                    continue
                for k in range(2, len(c)):
                    lk = c[k]
                    if lv[lk + off] != -1:
                        c[1], c[k] = lk, false_lit
                        watches[lk + off].append(ci)
                        break
                else:
                    ws[j] = ci
                    j += 1
                    if lv[first + off] == -1:
                        while i < n:
                            ws[j] = ws[i]
                            i += 1
                            j += 1
                        del ws[j:]
                        return True
                    self._assign(first)
            del ws[j:]
        return False

    # -- database ----------------------------------------------------------------
    def add(self, lits: Sequence[int]) -> None:
        if self.inconsistent:
            return
        c = list(dict.fromkeys(lits))
        if not c:
            self.inconsistent = True
            return
        ci = len(self.clauses)
        self.clauses.append(c)
        self.index.setdefault(tuple(sorted(c)), []).append(ci)
        lv, off = self.lv, self.off
        if len(c) == 1:
            v = lv[c[0] + off]
            if v == -1:
                self.inconsistent = True
            elif v == 0:
                self._assign(c[0])
                if self._propagate():
                    self.inconsistent = True
            return
        c.sort(key=lambda x: -lv[x + off])  # true, then unassigned, then false
        self.watches[c[0] + off].append(ci)
        self.watches[c[1] + off].append(ci)
        if lv[c[0] + off] == -1:
            self.inconsistent = True
        elif lv[c[0] + off] == 0 and lv[c[1] + off] == -1:
            self._assign(c[0])
            if self._propagate():
                self.inconsistent = True

    def delete(self, lits: Sequence[int]) -> str:
        """Delete one copy of a clause: returns "deleted", "ignored" or "missing"."""
        key = tuple(sorted(set(lits)))
        ids = self.index.get(key)
        if not ids:
            return "missing"
        ci = ids[-1]
        c = self.clauses[ci]
        lv, off = self.lv, self.off
        if len(c) == 1:
            return "ignored"  # unit clauses are top-level facts (drat-trim does the same)
        # A clause that is the reason of a top-level literal: one true, all others false.
        n_true = sum(1 for x in c if lv[x + off] == 1)
        n_false = sum(1 for x in c if lv[x + off] == -1)
        if n_true == 1 and n_false == len(c) - 1:
            return "ignored"
        ids.pop()
        self.clauses[ci] = None
        return "deleted"

    def rup(self, lits: Sequence[int]) -> bool:
        if self.inconsistent:
            return True
        lv, off = self.lv, self.off
        save = len(self.trail)
        conflict = False
        for x in lits:
            v = lv[x + off]
            if v == 1:
                conflict = True
                break
            if v == 0:
                self._assign(-x)
        if not conflict:
            conflict = self._propagate()
        self._backtrack(save)
        return conflict

    def rat(self, lits: Sequence[int]) -> bool:
        if not lits:
            return False
        pivot = lits[0]
        rest = list(lits)
        for c in self.clauses:
            if c is None or -pivot not in c:
                continue
            resolvent = rest + [x for x in c if x != -pivot]
            if not self.rup(resolvent):
                return False
        return True


def check_drat(
    formula: Iterable[Iterable[int]],
    proof,
    *,
    max_size: int | None = 20_000_000,
    time_limit: float | None = None,
) -> DratResult:
    """Check that a DRAT ``proof`` refutes ``formula``.

    Parameters
    ----------
    formula : iterable of iterable of int
        The clauses the solver was given (DIMACS literals).
    proof : list of str, str, bytes or path
        Text or binary DRAT (see :func:`parse_drat`).
    max_size : int or None
        Size guard: total literals of formula plus proof above which the check is
        ``skipped`` (pure Python is slow; a proof of millions of lemmas would take hours).
    time_limit : float or None
        Seconds after which the check stops with status ``unknown`` (reading the formula and
        the proof count).

    Returns
    -------
    DratResult

    Examples
    --------
    A fresh variable may be defined by RAT lemmas (extended resolution):

    >>> check_drat([[1, 2], [-1, 2], [1, -2], [-1, -2]], ["3 1 0", "-3 -1 0", "1 0", "0"]).status
    'verified'
    """
    t0 = time.perf_counter()

    def out_of_time() -> bool:
        return time_limit is not None and time.perf_counter() - t0 > time_limit

    def stopped(doing: str, **counts) -> DratResult:
        return DratResult("unknown", f"time limit of {time_limit:.3g} s reached while {doing}",
                          time_s=time.perf_counter() - t0, **counts)

    clauses: list[list[int]] = []
    for c in formula:
        clauses.append(list(map(int, c)))
        if len(clauses) % 4096 == 0 and out_of_time():
            return stopped(f"reading the formula ({len(clauses):,} clauses read)")
    try:
        steps = parse_drat(proof)
    except (ValueError, UnicodeDecodeError, IndexError) as exc:
        return DratResult("failed", f"unreadable proof: {exc}", time_s=time.perf_counter() - t0)
    size = sum(len(c) for c in clauses) + sum(len(s[1]) for s in steps)
    if max_size is not None and size > max_size:
        return DratResult(
            "skipped",
            f"formula plus proof have {size:,} literals, over the {max_size:,} the checker takes",
            lemmas=sum(1 for d, _ in steps if not d),
            time_s=time.perf_counter() - t0,
        )
    if out_of_time():
        return stopped("reading the proof")
    n_vars = 0
    for c in clauses:
        for x in c:
            n_vars = max(n_vars, abs(x))
    for _, c in steps:
        for x in c:
            n_vars = max(n_vars, abs(x))
    chk = _Checker(n_vars)
    for i, c in enumerate(clauses, 1):
        chk.add(c)
        if i % 4096 == 0 and out_of_time():
            return stopped(f"loading the formula into the checker ({i:,} of {len(clauses):,} clauses)")
    lemmas = deletions = rats = ignored = 0

    def result(status: str, reason: str) -> DratResult:
        return DratResult(status, reason, lemmas, deletions, rats, ignored, time.perf_counter() - t0)

    for step, (is_del, lits) in enumerate(steps, 1):
        if chk.inconsistent:
            break
        if step % 256 == 0 and out_of_time():
            return result("unknown", f"time limit of {time_limit:.3g} s reached while checking the proof "
                                     f"(step {step:,} of {len(steps):,})")
        if is_del:
            deletions += 1
            if chk.delete(lits) == "ignored":
                ignored += 1
            continue
        lemmas += 1
        if not chk.rup(lits):
            if not chk.rat(lits):
                shown = " ".join(map(str, lits[:12])) + (" ..." if len(lits) > 12 else "")
                return result("failed", f"lemma {lemmas} (proof line {step}: {shown} 0) is neither RUP nor RAT")
            rats += 1
        chk.add(lits)
    if not chk.inconsistent:
        return result("failed", "the proof never derives the empty clause")
    return result(
        "verified",
        f"DRAT proof of {lemmas} lemmas ({deletions} deletions) checked",
    )
