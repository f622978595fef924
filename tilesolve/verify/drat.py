"""tilesolve's own DRAT proof checker: backward, core-first, compiled; no size cut-off.

When a SAT solver says "unsatisfiable", tilesolve keeps the solver's DRAT proof and checks
it here, so that an ``unsat`` answer (e.g. the dappled paper's Example 6.2, §6 item 7) is a
certificate rather than a claim. The checker is written from the definition of DRAT
(Wetzler, Heule, Hunt, *DRAT-trim: Efficient checking and trimming using expressive
clausal proofs*, SAT 2014):

* a lemma ``C`` is accepted if it is **RUP** — unit propagation on ``F and not C``
  reaches a conflict — or, failing that, **RAT** on its first literal ``l``: for every
  clause ``D`` of ``F`` containing ``-l`` the resolvent ``C | (D - {-l})`` is RUP;
* accepted lemmas are added to ``F``; ``d`` lines delete clauses from ``F``;
* the proof is valid when it contains the empty clause and the empty clause is RUP where it
  stands (a proof without its final ``0`` line is rejected, unless unit propagation on the
  formula alone refutes it: then there is nothing to prove, as dratify also holds).

Two engines check the same rules:

``"backward"`` (the default)
    drat-trim's method (§4 of the paper): a forward pass adds lemmas with top-level unit
    propagation until the formula is refuted by propagation; a backward pass checks only the
    lemmas the refutation uses, marking from the final conflict back (core-first
    propagation, two watched literals). Lemmas nothing uses are not checked, as in
    drat-trim: they cannot make the refutation wrong. ``lemmas="all"`` checks every lemma.
    The loops (:mod:`tilesolve.verify._drat_kernels`) run compiled by numba on large proofs
    and interpreted on small ones, with the same verdicts: from :data:`COMPILE_FROM` units of
    work when numba's cache holds the compiled kernels, from :data:`COLD_COMPILE_FROM` when
    they would first have to compile (the first check after an install).
``"forward"``
    A plain-Python forward checker that checks every lemma in order (the reference the
    backward engine is tested against, and the baseline of ``benchmarks/bench_drat.py``).

Like drat-trim, deletions of unit clauses and of clauses that are currently the reason of a
top-level unit are ignored (keeping a clause can only make RUP easier and RAT harder, so
ignoring a deletion never accepts an invalid proof). The checker imports nothing from the
solvers or encodings it checks.

A proof is bound to its formula by :func:`cnf_sha256`, the SHA-256 of the formula written
by :func:`dimacs_bytes` (the exact bytes ``--proof-dir`` stores next to the proof).

Examples
--------
>>> f = [[1, 2], [1, -2], [-1, 2], [-1, -2]]
>>> check_drat(f, ["1 0", "0"]).verified
True
>>> check_drat(f + [[3, 4]], ["-3 0", "1 0", "0"]).verified  # "-3" is not used: not checked
True
>>> r = check_drat(f + [[3, 4]], ["-3 0", "1 0", "0"], lemmas="all")
>>> r.status, r.reason
('failed', 'lemma 1 (proof line 1: -3 0) is neither RUP nor RAT')
"""

from __future__ import annotations

import glob
import hashlib
import os
import sys
import threading
import time
import types
import warnings
from dataclasses import dataclass, field
from typing import Iterable, Sequence

import numpy as np

from tilesolve.verify import _drat_kernels as K

__all__ = ["DratResult", "check_drat", "parse_drat", "proof_arrays", "dimacs_bytes", "cnf_sha256", "formula_arrays",
           "read_dimacs", "drat_bytes",
           "check_proof_files",
           "COMPILE_FROM", "COLD_COMPILE_FROM", "PROOF_WEIGHT", "ENGINES"]

ENGINES = ("backward", "forward")

#: Work of a check, in formula literals, that one proof literal costs the interpreted kernels
#: (measured on Jeandel-Rao torus proofs: ~11 us a formula literal, 100-180 us a proof literal).
PROOF_WEIGHT = 10

#: Work (formula literals + :data:`PROOF_WEIGHT` x proof literals, summed over this process's
#: interpreted checks) from which the compiled kernels are used when numba's cache holds them:
#: importing numba and loading the cache costs about half a second of CPU, what the interpreted
#: kernels spend on some 50k formula literals.
COMPILE_FROM = 50_000

#: Work from which the kernels are compiled when numba's cache does not hold them yet (the first
#: check after an install): compiling costs 5-7 s of CPU, what the interpreted kernels spend on
#: some 500k units of work (~12 us a unit); buying at half that price, since a command that
#: checks one proof this large usually checks more (``aperiodic check`` of finite-jv7: 335k,
#: then 286k). Below it a check runs interpreted and leaves the cache empty, so a small proof
#: never pays the compilation (the unsat C = 3 Wang packing of the README: 139k).
COLD_COMPILE_FROM = 250_000

#: CPU seconds the interpreted kernels spend on a unit of work (measured: about 12 us). A check
#: that runs interpreted longer than its estimate says is charged what it has cost (:class:`_Rent`).
UNIT_S = 12e-6

#: Seconds a kernel call may take between two deadline checks (the steps per call adapt).
_SLICE_S = 0.05


class _Slices:
    """Proof steps per kernel call: doubled while calls are quick, halved when slow."""

    def __init__(self) -> None:
        self.steps = 256
        self.t = time.perf_counter()

    def next(self) -> int:
        return self.steps

    def done(self) -> None:
        now = time.perf_counter()
        took, self.t = now - self.t, now
        if took < _SLICE_S / 4:
            self.steps = min(self.steps * 2, 1 << 20)
        elif took > _SLICE_S:
            self.steps = max(self.steps // 2, 16)


@dataclass(frozen=True)
class DratResult:
    """Verdict of :func:`check_drat`.

    Attributes
    ----------
    status : {"verified", "failed", "unknown"}
        ``verified``: the proof refutes the formula; ``failed``: a lemma is neither RUP
        nor RAT, or the proof has no empty clause, or its empty clause is not RUP;
        ``unknown``: the time limit stopped the check.
    reason : str
        One line for humans.
    lemmas, deletions, rat_lemmas, ignored_deletions : int
        Counts of proof steps seen (``rat_lemmas``: lemmas accepted as RAT only).
    checked : int
        Lemmas checked (the ones the refutation uses, or all with ``lemmas="all"``).
    core : numpy.ndarray or None
        Indices of the formula clauses the refutation uses (backward engine, verified).
    used : numpy.ndarray or None
        Indices of the proof steps (lines, deletions counted) whose lemmas the refutation uses
        and the check accepted (backward engine, verified): these lines, in order, and the empty
        clause make a proof of their own (a *trimmed* proof, as drat-trim's core-first mode writes).
    trivial : bool
        The formula is refuted by unit propagation alone: no lemma is needed.
    engine : str
    time_s : float
    """

    status: str
    reason: str
    lemmas: int = 0
    deletions: int = 0
    rat_lemmas: int = 0
    ignored_deletions: int = 0
    checked: int = 0
    core: np.ndarray | None = field(default=None, repr=False, compare=False)
    trivial: bool = False
    engine: str = "backward"
    time_s: float = 0.0
    used: np.ndarray | None = field(default=None, repr=False, compare=False)

    @property
    def verified(self) -> bool:
        return self.status == "verified"


# ----------------------------------------------------------------------------- formulas
def formula_arrays(formula) -> tuple[np.ndarray, np.ndarray, list[tuple[str, int, int]]]:
    """Flatten a formula into ``(literals, sizes, blocks)``.

    ``formula`` is a list of clauses, ``(literals, sizes)`` arrays (as :func:`read_dimacs`
    gives), an object with ``clauses`` (PySAT's CNF) or one with
    ``blocks`` of labelled clauses (each with ``label`` and a 2-D ``lits`` array or a
    ``ragged`` list, as tilesolve's encodings build them). ``blocks`` lists
    ``(label, first clause, count)`` (one unlabelled block for plain lists).
    """
    parts: list[np.ndarray] = []
    sizes: list[np.ndarray] = []
    blocks: list[tuple[str, int, int]] = []
    n = 0

    def ragged(cls, label):
        nonlocal n
        cls = [list(c) for c in cls]
        sz = np.fromiter((len(c) for c in cls), np.int64, len(cls))
        flat = np.fromiter((int(x) for c in cls for x in c), np.int64, int(sz.sum()))
        parts.append(flat)
        sizes.append(sz)
        blocks.append((label, n, len(cls)))
        n += len(cls)

    if isinstance(formula, tuple) and len(formula) == 2 and isinstance(formula[0], np.ndarray):
        lits, sz = formula  # already flat, as read_dimacs gives it
        return np.asarray(lits, np.int64), np.asarray(sz, np.int64), [("", 0, len(sz))]
    if hasattr(formula, "blocks"):
        for b in formula.blocks:
            if getattr(b, "lits", None) is not None:
                a = np.asarray(b.lits, np.int64)
                parts.append(a.reshape(-1))
                sizes.append(np.full(a.shape[0], a.shape[1], np.int64))
                blocks.append((str(b.label), n, a.shape[0]))
                n += a.shape[0]
            else:
                ragged(b.ragged, str(b.label))
    else:
        ragged(formula.clauses if hasattr(formula, "clauses") else formula, "")
    lits = np.concatenate(parts) if parts else np.zeros(0, np.int64)
    sz = np.concatenate(sizes) if sizes else np.zeros(0, np.int64)
    return lits, sz, blocks


def dimacs_bytes(formula) -> bytes:
    """The formula in DIMACS CNF, exactly as :func:`cnf_sha256` hashes it.

    One header ``p cnf V C`` (``V`` the largest variable), then one clause per line ending in
    `` 0``; ASCII, ``\\n`` line ends, no comments.

    >>> dimacs_bytes([[1, -2], [2]])
    b'p cnf 2 2\\n1 -2 0\\n2 0\\n'
    """
    lits, sizes, _ = formula_arrays(formula)
    n_vars = int(np.abs(lits).max()) if lits.size else 0
    return f"p cnf {n_vars} {len(sizes)}\n".encode("ascii") + _lines_bytes(lits, sizes)


def drat_bytes(lits: np.ndarray, sizes: np.ndarray, dels: np.ndarray) -> bytes:
    """DRAT text of proof steps (as :func:`proof_arrays` gives them), one a line, a deletion's
    line starting with ``d``: the text :func:`proof_arrays` reads back.

    >>> drat_bytes(np.array([1, -2, 3]), np.array([2, 1, 0]), np.array([0, 1, 0]))
    b'1 -2 0\\nd 3 0\\n0\\n'
    """
    return _lines_bytes(np.asarray(lits, np.int64), np.asarray(sizes, np.int64), np.asarray(dels) != 0)


def _lines_bytes(lits: np.ndarray, sizes: np.ndarray, dels: np.ndarray | None = None) -> bytes:
    """One line per clause, its literals and ``0`` (``d`` first where ``dels``), in ASCII."""
    tok = np.insert(lits, np.cumsum(sizes), 0)  # each clause ends in 0
    if tok.size == 0:
        return b""
    # decimal digits written with numpy: one pass per digit position
    neg = tok < 0
    v = np.abs(tok)
    nd = np.ones(tok.size, np.int64)
    x = v // 10
    while x.any():
        nd += x > 0
        x //= 10
    pre = np.zeros(tok.size, np.int64)  # "d " before a deletion's first token
    if dels is not None and dels.any():
        pre[(np.cumsum(sizes + 1) - sizes - 1)[dels]] = 2
    off = np.zeros(tok.size + 1, np.int64)
    np.cumsum(pre + neg + nd + 1, out=off[1:])
    buf = np.empty(int(off[-1]), np.uint8)
    at = off[:-1][pre > 0]
    buf[at], buf[at + 1] = ord("d"), ord(" ")
    first = off[:-1] + pre + neg
    buf[(first - 1)[neg]] = ord("-")
    for k in range(int(nd.max())):
        m = nd > k
        buf[first[m] + nd[m] - 1 - k] = 48 + (v[m] // 10**k) % 10
    buf[off[1:] - 1] = np.where(tok == 0, ord("\n"), ord(" "))
    return buf.tobytes()


def read_dimacs(data: bytes) -> tuple[np.ndarray, np.ndarray]:
    """``(literals, sizes)`` of a DIMACS CNF text (comments and the header are skipped).

    >>> lits, sizes = read_dimacs(b"c demo\\np cnf 2 2\\n1 -2 0\\n2 0\\n")
    >>> lits.tolist(), sizes.tolist()
    ([1, -2, 2], [2, 1])
    """
    body = _strip_lines(bytes(data), (b"c", b"p", b"%"))
    if body.translate(None, b"0123456789- \t\r\n"):
        raise ValueError("not a DIMACS CNF file")
    toks = _numbers(body)
    if toks.size and toks[-1] != 0:
        raise ValueError("the last clause does not end with 0")
    zeros = np.flatnonzero(toks == 0)
    sizes = np.diff(np.concatenate(([-1], zeros))) - 1
    return toks[toks != 0], sizes.astype(np.int64)


def check_proof_files(directory, name: str, cnf_sha256: str, drat_sha256: str | None = None,
                      time_limit: float | None = None) -> tuple[bool, list[str]]:
    """Re-check ``<name>.cnf`` and ``<name>.drat`` in ``directory`` against recorded digests.

    Returns ``(ok, lines)``: the CNF's SHA-256 must equal ``cnf_sha256`` (and the proof's
    ``drat_sha256`` when given), and the proof must refute the CNF (:func:`check_drat`).
    """
    lines: list[str] = []
    paths = [os.path.join(os.fspath(directory), name + ext) for ext in (".cnf", ".drat")]
    missing = [p for p in paths if not os.path.isfile(p)]
    if missing:
        return False, [f"missing proof file {missing[0]}"]
    with open(paths[0], "rb") as fh:
        cnf = fh.read()
    with open(paths[1], "rb") as fh:
        proof = fh.read()
    got = hashlib.sha256(cnf).hexdigest()
    if got != cnf_sha256:
        return False, [f"{paths[0]}: SHA-256 {got[:16]}... differs from the recorded {cnf_sha256[:16]}..."]
    lines.append(f"{paths[0]}: SHA-256 matches the recorded {cnf_sha256[:16]}...")
    if drat_sha256 is not None:
        got = hashlib.sha256(proof).hexdigest()
        if got != drat_sha256:
            return False, lines + [f"{paths[1]}: SHA-256 {got[:16]}... differs from the recorded {drat_sha256[:16]}..."]
        lines.append(f"{paths[1]}: SHA-256 matches the recorded {drat_sha256[:16]}...")
    try:
        formula = read_dimacs(cnf)
    except (ValueError, UnicodeDecodeError) as exc:
        return False, lines + [f"{paths[0]}: {exc}"]
    r = check_drat(formula, proof, time_limit=time_limit)
    lines.append(f"{paths[1]}: {r.status}: {r.reason} ({len(formula[1])} clauses, {r.time_s:.3g} s)")
    return r.verified, lines


def cnf_sha256(formula) -> str:
    """SHA-256 (hex) of :func:`dimacs_bytes` of ``formula``: what a proof is bound to.

    >>> cnf_sha256([[1], [-1]])[:12]
    'ac42a371b5a1'
    """
    return hashlib.sha256(dimacs_bytes(formula)).hexdigest()


# ----------------------------------------------------------------------------- proofs
_DEL = 4611686018427387903  # stands for a "d" while numpy reads the numbers


def _proof_data(proof) -> tuple[bytes, bool]:
    """The proof's bytes, and whether they are binary DRAT."""
    is_path = isinstance(proof, os.PathLike) or (
        isinstance(proof, str) and "\n" not in proof and not proof.strip().endswith(" 0") and os.path.isfile(proof)
    )
    if is_path:
        with open(proof, "rb") as fh:
            proof = fh.read()
    if isinstance(proof, (bytes, bytearray)):
        data = bytes(proof)
        return data, data[:1] in (b"a", b"d") and any(b > 127 or b == 0 for b in data[:64])
    if isinstance(proof, str):
        return proof.encode("ascii"), False
    return "\n".join(line if isinstance(line, str) else line.decode("ascii") for line in proof).encode("ascii"), False


def _strip_lines(data: bytes, prefixes: tuple[bytes, ...]) -> bytes:
    """``data`` without the lines that start (after blanks) with one of ``prefixes``."""
    if not any(p in data for p in prefixes):
        return data
    return b"\n".join(ln for ln in data.splitlines() if not ln.lstrip().startswith(prefixes))


def _numbers(text: bytes) -> np.ndarray:
    """The blank-separated integers of ``text`` (already checked to hold nothing else)."""
    if not text.strip():
        return np.zeros(0, np.int64)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return np.fromstring(text, dtype=np.int64, sep=" ")


def proof_arrays(proof) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(literals, sizes, is_deletion)`` of every proof line, read by numpy."""
    data, binary = _proof_data(proof)
    if binary:
        steps = _parse_binary(data)
        sizes = np.fromiter((len(c) for _, c in steps), np.int64, len(steps))
        lits = np.fromiter((x for _, c in steps for x in c), np.int64, int(sizes.sum()))
        return lits, sizes, np.fromiter((d for d, _ in steps), np.int8, len(steps))
    text = _strip_lines(data, (b"c",))
    bad = text.translate(None, b"0123456789-d \t\r\n")
    if bad:
        raise ValueError(f"unexpected character {chr(bad[0])!r}")
    toks = _numbers(text.replace(b"d", b" %d " % _DEL))
    if toks.size and toks[-1] != 0:
        raise ValueError("the last proof line does not end with 0")
    is_d = toks == _DEL
    zeros = np.flatnonzero(toks == 0)
    starts = np.concatenate(([0], zeros[:-1] + 1)) if zeros.size else zeros
    dels = np.zeros(zeros.size, np.int8)
    if is_d.any():
        where = np.flatnonzero(is_d)
        clause_of = np.searchsorted(zeros, where)
        # (``clause_of`` rises with ``where``: two "d" on one line repeat a value)
        if not np.array_equal(where, starts[clause_of]) or (np.diff(clause_of) == 0).any():
            raise ValueError("a 'd' that does not start a proof line")
        dels[clause_of] = 1
    keep = ~is_d & (toks != 0)
    sizes = (zeros - starts - dels).astype(np.int64)
    return toks[keep], sizes, dels


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

    >>> parse_drat(["1 2 0", "d 1 2 0", "0"])
    [(False, [1, 2]), (True, [1, 2]), (False, [])]
    """
    lits, sizes, dels = proof_arrays(proof)
    flat = lits.tolist()
    out, i = [], 0
    for d, n in zip(dels.tolist(), sizes.tolist()):
        out.append((bool(d), flat[i:i + n]))
        i += n
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


# ----------------------------------------------------------------------------- kernels
_COMPILED: types.SimpleNamespace | None = None
_LOCK = threading.Lock()
_PLAIN_WORK = 0  # work the interpreted kernels have done in this process (the ski-rental rule)


#: Seconds of time limit below which a first compilation (no numba cache yet) is not started.
_COMPILE_S = 60.0

def _kernel_funcs() -> dict[str, types.FunctionType]:
    return {k: v for k, v in vars(K).items() if isinstance(v, types.FunctionType) and v.__module__ == K.__name__}


def _kernel_cache() -> tuple[bool, str | None]:
    """Whether numba's cache holds every kernel of this source, and a lock file beside it.

    The first run after an install compiles the kernels (several seconds); the lock makes the
    processes of a sweep compile them once, in one process, the others loading that cache.
    """
    from numba.core.caching import FunctionCache

    try:
        files = [FunctionCache(f)._cache_file for f in _kernel_funcs().values()]
        ready = all(os.path.isfile(f._index_path) and os.path.getmtime(f._index_path) >= os.path.getmtime(K.__file__)
                    for f in files)
        return ready, os.path.join(files[0]._cache_path, "tilesolve-drat-compile.lock")
    except (AttributeError, OSError, IndexError, RuntimeError):  # another numba's layout, or no cache directory
        return False, None


def _cache_may_hold_kernels() -> bool:
    """False when no numba cache file of the kernels lies where numba writes them (looked for
    without importing numba, which costs about 0.4 s): then the cache is surely cold.

    The places are numba's: ``NUMBA_CACHE_DIR``, else ``__pycache__`` beside the source or the
    user-wide cache (``$XDG_CACHE_HOME/numba``). True once numba is imported (the exact look,
    :func:`_kernel_cache`, is then cheap) or when a file is found."""
    if "numba" in sys.modules:
        return True
    base = os.environ.get("NUMBA_CACHE_DIR")
    if base:
        places = [os.path.join(base, "*")]
    else:
        user = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
        places = [os.path.join(os.path.dirname(K.__file__), "__pycache__"), os.path.join(user, "numba", "*")]
    stem = glob.escape(os.path.splitext(os.path.basename(K.__file__))[0])
    return any(glob.glob(os.path.join(place, f"{stem}.*.nbi")) for place in places)


def _compile() -> types.SimpleNamespace:
    from tilesolve._numba import numba

    ns = dict(vars(K))
    funcs = _kernel_funcs()
    for name, func in funcs.items():
        clone = types.FunctionType(func.__code__, ns, func.__name__, func.__defaults__, func.__closure__)
        clone.__qualname__ = func.__qualname__
        # kernels that only kernels call need no wrapper for Python callers (a third less compile time)
        inner = {} if name in K.ENTRIES else {"no_cpython_wrapper": True, "no_cfunc_wrapper": True}
        ns[name] = numba.njit(cache=True, _nrt=False, **inner)(clone)
    # One version of each kernel, typed by its parameters' names (callees first, as the module
    # defines them): no version per constant argument, which would double the compile time.
    kinds = {"int": numba.int64, "flag": numba.boolean, "int8s": numba.int8[::1], "int64s": numba.int64[::1],
             "table": numba.int64[:, ::1]}
    for name, func in funcs.items():
        code = func.__code__
        ns[name].compile(tuple(kinds[K.PARAMS.get(a, "int")] for a in code.co_varnames[:code.co_argcount]))
        ns[name].disable_compile()
    return types.SimpleNamespace(**{k: v for k, v in ns.items() if not k.startswith("__")})


def _kernels(work: int, mode: str = "auto", time_limit: float | None = None):
    """The kernel namespace: the module itself (interpreted) or its numba-compiled copy.

    ``auto`` interprets a check while the work of this process's interpreted checks, this one
    included, stays under :data:`COMPILE_FROM`, or under :data:`COLD_COMPILE_FROM` while numba's
    cache does not hold the kernels; also when a short ``time_limit`` leaves no room to compile
    them (the interpreted loops stop on time). Otherwise the first process to need the kernels
    compiles them, under a file lock, and the others wait for its cache."""
    global _COMPILED, _PLAIN_WORK
    if mode == "plain":
        return K
    with _LOCK:
        if _COMPILED is not None:
            return _COMPILED
        total = _PLAIN_WORK + work
        ready, lock_path = False, None
        if mode == "auto":
            if total >= COMPILE_FROM and (total >= COLD_COMPILE_FROM or _cache_may_hold_kernels()):
                ready, lock_path = _kernel_cache()
            if not ready and (total < COLD_COMPILE_FROM or (time_limit is not None and time_limit < _COMPILE_S)):
                _PLAIN_WORK = total
                return K
        else:
            ready, lock_path = _kernel_cache()
        try:
            import fcntl

            fh = open(lock_path, "a") if lock_path and not ready else None
        except (ImportError, OSError):
            fh = None
        try:
            if fh is not None:  # wait while another process compiles them, then load its cache
                fcntl.flock(fh, fcntl.LOCK_EX)
            _COMPILED = _compile()
        finally:
            if fh is not None:
                fh.close()
        return _COMPILED


class _Rent:
    """The kernels of one check, re-chosen as it runs: a check that the interpreted kernels run
    for longer than its work estimate says adds what it has cost beyond it (in units of
    :data:`UNIT_S`) to this process's interpreted work each time its cost doubles, and goes on
    with the compiled kernels once :func:`_kernels` chooses them (they work on the same arrays,
    with the same results)."""

    def __init__(self, work: int, mode: str, time_limit: float | None) -> None:
        self.k = _kernels(work, mode, time_limit)
        self.charged = work
        self.renting = self.k is K and mode == "auto"
        self.t0 = time.process_time()

    def kernels(self, time_limit: float | None):
        """The namespace for the next kernel call."""
        if self.renting:
            extra = int((time.process_time() - self.t0) / UNIT_S) - self.charged
            if extra >= max(self.charged, 1):
                self.charged += extra
                self.k = _kernels(extra, "auto", time_limit)
                self.renting = self.k is K
        return self.k


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


def _codes(lits: np.ndarray) -> np.ndarray:
    return 2 * np.abs(lits) + (lits < 0)


def _shown(lits: Sequence[int]) -> str:
    lits = list(lits)
    return " ".join(map(str, lits[:12])) + (" ..." if len(lits) > 12 else "")


def check_drat(
    formula: Iterable[Iterable[int]],
    proof,
    *,
    time_limit: float | None = None,
    engine: str = "backward",
    lemmas: str = "core",
    kernels: str = "auto",
) -> DratResult:
    """Check that a DRAT ``proof`` refutes ``formula``, whatever its size.

    Parameters
    ----------
    formula
        The clauses the solver was given (see :func:`formula_arrays`).
    proof : list of str, str, bytes or path
        Text or binary DRAT (see :func:`parse_drat`).
    time_limit : float or None
        Seconds after which the check stops with status ``unknown`` (reading the formula and
        the proof count).
    engine : {"backward", "forward"}
        See the module docstring.
    lemmas : {"core", "all"}
        Backward engine: check the lemmas the refutation uses, or every lemma before the
        refutation (the forward engine always checks all).
    kernels : {"auto", "plain", "compiled"}
        Backward engine: interpreted or numba-compiled loops (``auto``: by size).

    Returns
    -------
    DratResult

    Examples
    --------
    A fresh variable may be defined by RAT lemmas (extended resolution):

    >>> check_drat([[1, 2], [-1, 2], [1, -2], [-1, -2]], ["3 1 0", "-3 -1 0", "1 0", "0"]).status
    'verified'
    >>> check_drat([[1], [-1]], ["0"]).trivial
    True
    """
    if engine not in ENGINES:
        raise ValueError(f"engine must be one of {ENGINES}, got {engine!r}")
    if lemmas not in ("core", "all"):
        raise ValueError(f"lemmas must be 'core' or 'all', got {lemmas!r}")
    t0 = time.perf_counter()

    def elapsed() -> float:
        return time.perf_counter() - t0

    def out_of_time() -> bool:
        return time_limit is not None and elapsed() > time_limit

    def stopped(doing: str, **counts) -> DratResult:
        return DratResult("unknown", f"time limit of {time_limit:.3g} s reached while {doing}",
                          engine=engine, time_s=elapsed(), **counts)

    f_lits, f_sizes, _ = formula_arrays(formula)
    if out_of_time():
        return stopped("reading the formula")
    try:
        p_lits, p_sizes, p_del = proof_arrays(proof)
    except (ValueError, UnicodeDecodeError, IndexError) as exc:
        return DratResult("failed", f"unreadable proof: {exc}", engine=engine, time_s=elapsed())
    if out_of_time():
        return stopped("reading the proof")
    if engine == "forward":
        return _check_forward(f_lits, f_sizes, p_lits, p_sizes, p_del, t0, time_limit)

    n_f, n_s = len(f_sizes), len(p_sizes)
    n_cl = n_f + n_s
    codes = _codes(np.concatenate((f_lits, p_lits)))
    size = np.concatenate((f_sizes, p_sizes))
    # each clause is stored as [clause number, size, literals...]; start[c]: its first literal
    start = np.zeros(n_cl + 1, np.int64)
    np.cumsum(size + 2, out=start[1:])
    start += 2
    lits = np.empty(codes.size + 2 * n_cl, np.int64)
    lits[start[:n_cl] - 2] = np.arange(n_cl)
    lits[start[:n_cl] - 1] = size
    lits[np.arange(codes.size) + 2 * np.repeat(np.arange(1, n_cl + 1), size)] = codes
    is_del = p_del
    n_lemmas = int(n_s - is_del.sum())
    n_dels = int(is_del.sum())
    pivot = np.full(n_s, -1, np.int64)
    nonempty = p_sizes > 0
    pivot[nonempty] = lits[start[n_f:n_cl][nonempty]]
    n_vars = int(codes.max() >> 1) if codes.size else 0
    L = 2 * n_vars + 2
    work = int(f_lits.size) + PROOF_WEIGHT * int(p_lits.size)
    def left() -> float | None:
        return None if time_limit is None else time_limit - elapsed()

    rent = _Rent(work, kernels, left())
    k = rent.k
    taut = np.zeros(n_cl, np.int8)
    chash = np.zeros(n_cl, np.int64)
    mark = np.full(L, -1, np.int64)
    k.prepare(lits, start, size, taut, chash, mark, n_cl)
    mark.fill(-1)
    active = np.zeros(n_cl, np.int8)
    core = np.zeros(n_cl, np.int8)
    val = np.zeros(L, np.int8)
    reason = np.full(n_vars + 1, -1, np.int64)
    tpos = np.zeros(n_vars + 1, np.int64)
    trail = np.zeros(n_vars + 1, np.int64)
    st = np.array([0, 0, 0, -1], np.int64)
    # watch lists, two per literal code (core, others), in blocks of one pool: row ``i`` of
    # ``wl`` is list i's (start, length, room), the last row's start is the pool's end. The
    # pool holds six entries per watch of every clause that can be active (the formula and
    # the lemmas) and eight per list: compacting (live blocks only) then always frees more
    # than half of it.
    n_watches = 2 * (n_f + n_lemmas)
    n_lists = 2 * L
    wl = np.zeros((n_lists + 1, 3), np.int64)
    pool = np.zeros(6 * n_watches + 8 * n_lists + 16, np.int64)
    cap = 1 << max(4, int(2 * n_cl).bit_length())
    ht_key = np.zeros(cap, np.int64)
    ht_head = np.full(cap, -1, np.int64)
    same_prev = np.full(n_cl, -1, np.int64)
    tl_before = np.zeros(n_s, np.int64)
    target = np.full(n_s, -1, np.int64)
    counts = np.array([-1, -1, 0, 0, -1], np.int64)
    done = np.zeros(n_vars + 1, np.int8)
    seen = np.zeros(n_vars + 1, np.int8)
    stack = np.zeros(max(n_vars + 1, int(size.max(initial=0))) * 2 + 2, np.int64)

    def result(status: str, reason_: str, checked: int = 0, rats: int = 0, core_ids=None,
               trivial: bool = False, used=None) -> DratResult:
        return DratResult(status, reason_, n_lemmas, n_dels, rats, int(counts[2]), checked, core_ids, trivial,
                          "backward", elapsed(), used)

    # forward pass: until unit propagation refutes the formula
    refuted = 0
    j = -1
    slices = _Slices()
    while not refuted and j < n_s:
        j1 = min(n_s, max(j, 0) + slices.next())
        k = rent.kernels(left())
        refuted = k.forward(n_f, n_s, is_del, lits, start, size, taut, chash, active, val, reason, tpos, trail, st,
                            wl, pool, core, ht_key, ht_head, same_prev, mark, tl_before, target, counts, j, j1)
        if counts[4] >= 0:
            line = int(counts[4]) + 1
            return result("failed", f"the empty clause (proof line {line}) is not RUP: unit propagation "
                                    "does not refute the formula there")
        j = j1
        slices.done()
        if out_of_time():
            return result("unknown", f"time limit of {time_limit:.3g} s reached while checking the proof "
                                     f"(forward pass, step {j:,} of {n_s:,})")
    if not refuted:
        return result("failed", "the proof never derives the empty clause")
    confl_step = int(counts[1])
    later = np.flatnonzero((is_del[confl_step + 1:] == 0) & (p_sizes[confl_step + 1:] == 0))
    if later.size == 0 and confl_step >= 0:
        return result("failed", "the proof has no empty clause (unit propagation refutes the formula after "
                                f"proof line {confl_step + 1}, but the proof never says so)")
    # backward pass from the conflict
    k = rent.kernels(left())
    k.analyze(int(counts[0]), -1, 0, lits, start, size, taut, active, wl, pool, reason, tpos, trail, st, core,
              done, seen, stack)
    if lemmas == "all":
        k.mark_all(n_f, n_s, is_del, lits, start, size, taut, active, wl, pool, core)
    st[1] = st[2] = st[0]
    st[3] = -1
    out = np.zeros(4, np.int64)
    j = confl_step + 1
    while j > 0:
        j1 = max(0, j - slices.next())
        k = rent.kernels(left())
        j = k.backward(n_f, is_del, pivot, lits, start, size, taut, active, val, reason, tpos, trail, st, wl,
                       pool, core, done, seen, stack, tl_before, target, out, j, j1)
        slices.done()
        if out[0] != K.OK:
            step = int(out[1])
            number = int((is_del[: step + 1] == 0).sum())
            first = int(p_sizes[:step].sum())
            shown = _shown(p_lits[first:first + p_sizes[step]].tolist())
            return result("failed", f"lemma {number} (proof line {step + 1}: {shown} 0) is neither RUP nor RAT",
                          int(out[2]), int(out[3]))
        if out_of_time():
            return result("unknown", f"time limit of {time_limit:.3g} s reached while checking the proof "
                                     f"(backward pass, {int(out[2]):,} lemmas checked, step {j:,} to go)",
                          int(out[2]), int(out[3]))
    checked = int(out[2])
    core_ids = np.flatnonzero(core[:n_f])
    trivial = confl_step < 0 or checked == 0
    if trivial:
        why = (f"unit propagation on {core_ids.size} input clause(s) refutes the formula; "
               f"the proof's {n_lemmas} lemma(s) are not needed")
    else:
        why = (f"DRAT proof checked: {checked} of {n_lemmas} lemma(s) used and checked "
               f"({int(out[3])} by RAT), resting on {core_ids.size} of {n_f} input clauses")
    used = np.flatnonzero(core[n_f:n_f + confl_step + 1] & (is_del[:confl_step + 1] == 0))
    return result("verified", why, checked, int(out[3]), core_ids, trivial, used)


def _split(lits: np.ndarray, sizes: np.ndarray) -> list[list[int]]:
    flat = lits.tolist()
    out, i = [], 0
    for n in sizes.tolist():
        out.append(flat[i:i + n])
        i += n
    return out


def _check_forward(f_lits, f_sizes, p_lits, p_sizes, p_del, t0: float, time_limit: float | None) -> DratResult:
    """The forward engine: every lemma checked in order, plain Python."""
    clauses = _split(f_lits, f_sizes)
    steps = list(zip(p_del.astype(bool).tolist(), _split(p_lits, p_sizes)))
    n_vars = int(max(np.abs(f_lits).max(initial=0), np.abs(p_lits).max(initial=0)))

    def elapsed() -> float:
        return time.perf_counter() - t0

    def out_of_time() -> bool:
        return time_limit is not None and elapsed() > time_limit

    chk = _Checker(n_vars)
    for i, c in enumerate(clauses, 1):
        chk.add(c)
        if i % 4096 == 0 and out_of_time():
            return DratResult("unknown", f"time limit of {time_limit:.3g} s reached while loading the formula "
                                         f"into the checker ({i:,} of {len(clauses):,} clauses)",
                              engine="forward", time_s=elapsed())
    lemmas = deletions = rats = ignored = 0
    trivial = chk.inconsistent

    def result(status: str, reason: str) -> DratResult:
        return DratResult(status, reason, lemmas, deletions, rats, ignored, lemmas, None, trivial, "forward",
                          elapsed())

    for step, (is_del, lits) in enumerate(steps, 1):
        if step % 256 == 0 and out_of_time():
            return result("unknown", f"time limit of {time_limit:.3g} s reached while checking the proof "
                                     f"(step {step:,} of {len(steps):,})")
        if is_del:
            deletions += 1
            if not chk.inconsistent and chk.delete(lits) == "ignored":
                ignored += 1
            continue
        lemmas += 1
        if not lits:
            if chk.inconsistent or chk.rup(lits):
                return result("verified", f"DRAT proof of {lemmas} lemmas ({deletions} deletions) checked, "
                                          "every lemma")
            return result("failed", f"the empty clause (proof line {step}) is not RUP: unit propagation "
                                    "does not refute the formula there")
        if chk.inconsistent:
            continue
        if not chk.rup(lits):
            if not chk.rat(lits):
                return result("failed", f"lemma {lemmas} (proof line {step}: {_shown(lits)} 0) is neither RUP "
                                        "nor RAT")
            rats += 1
        chk.add(lits)
    if trivial:
        return result("verified", "unit propagation on the input clauses refutes the formula; no lemma is needed")
    if chk.inconsistent:
        return result("failed", "the proof has no empty clause (unit propagation refutes the formula, but the "
                                "proof never says so)")
    return result("failed", "the proof never derives the empty clause")
