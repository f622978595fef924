"""The independent DRAT checker (tilesolve.verify.drat): accepts solver proofs, rejects corruption.

Definitions: Wetzler, Heule, Hunt, *DRAT-trim* (SAT 2014): RUP, RAT on the first literal,
deletions. Used for the dappled paper's §6 item 7 / Example 6.2 certificates.
"""

from __future__ import annotations

import ast
import itertools
import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from pysat.solvers import Solver

from clitools import SCRIPT
from tilesolve.verify import _drat_kernels as K
from tilesolve.verify import drat as D
from tilesolve.verify.drat import check_drat, parse_drat


def php(n: int) -> list[list[int]]:
    """Pigeonhole: n pigeons, n - 1 holes (unsatisfiable, needs a real proof)."""
    v = lambda i, j: i * (n - 1) + j + 1  # noqa: E731
    cls = [[v(i, j) for j in range(n - 1)] for i in range(n)]
    for j in range(n - 1):
        for a, b in itertools.combinations(range(n), 2):
            cls.append([-v(a, j), -v(b, j)])
    return cls


def proof_of(clauses, solver="cadical153"):
    with Solver(name=solver, bootstrap_with=clauses, with_proof=True) as s:
        assert s.solve() is False
        return s.get_proof()


@pytest.fixture(scope="module")
def php6():
    f = php(6)
    return f, proof_of(f)


@pytest.mark.parametrize("solver", ["cadical153", "cadical195", "glucose4", "lingeling", "maplecm"])
def test_accepts_real_solver_proofs(solver):
    f = php(6)
    r = check_drat(f, proof_of(f, solver))
    assert r.verified, r.reason
    assert r.lemmas > 0


def test_rejects_a_truncated_proof(php6):
    f, proof = php6
    r = check_drat(f, proof[: len(proof) // 4])
    assert r.status == "failed"
    assert "empty clause" in r.reason
    r = check_drat(f, [line for line in proof if line != "0"])  # only the final "0" dropped
    assert r.status == "failed" and "the proof has no empty clause" in r.reason


def test_rejects_an_invented_lemma(php6):
    f, proof = php6
    # "pigeon 0 sits in hole 0" is neither implied by unit propagation nor RAT
    r = check_drat(f, ["1 0"] + list(proof), lemmas="all")
    assert r.status == "failed"
    assert r.reason.startswith("lemma 1 ")
    assert check_drat(f, ["1 0"] + list(proof), engine="forward").reason.startswith("lemma 1 ")


@pytest.mark.slow
def test_rejects_a_lemma_with_a_flipped_literal(php6):
    f, proof = php6
    lemmas = [i for i, line in enumerate(proof) if not line.startswith("d") and len(line.split()) > 2]
    caught = 0
    for i in lemmas[:10]:
        bad = list(proof)
        lits = bad[i].split()
        lits[0] = str(-int(lits[0]))
        bad[i] = " ".join(lits)
        r = check_drat(f, bad)
        if r.status == "failed":
            caught += 1
        else:  # a flipped lemma may still be implied; then the proof stays valid
            assert r.verified
    assert caught > 0


def test_satisfiable_formula_cannot_be_refuted():
    r = check_drat([[1, 2], [-1, 2]], ["2 0", "0"])
    assert r.status == "failed"


def test_rat_lemmas_extend_with_fresh_variables():
    f = [[1, 2], [-1, 2], [1, -2], [-1, -2]]
    r = check_drat(f, ["3 0", "1 0", "0"], lemmas="all")  # "3": fresh, so RAT but not RUP
    assert r.verified and r.rat_lemmas >= 1


def test_deletions_are_honoured():
    # after deleting the only clause that makes "1" RUP, the lemma must fail
    f = [[1, 2], [1, -2], [-1, 3], [-1, -3]]
    assert check_drat(f, ["1 0", "0"]).verified
    r = check_drat(f, ["d 1 -2 0", "1 0", "0"])
    assert r.status == "failed" and r.deletions == 1


def test_binary_and_text_formats_agree(tmp_path):
    f = php(5)
    text = proof_of(f)
    # encode the same proof in binary DRAT and read it back from a file
    out = bytearray()
    for line in text:
        toks = line.split()
        delete = toks[0] == "d"
        out.append(0x64 if delete else 0x61)
        for t in toks[1:-1] if delete else toks[:-1]:
            x = int(t)
            u = 2 * abs(x) + (x < 0)
            while u > 127:
                out.append((u & 0x7F) | 0x80)
                u >>= 7
            out.append(u)
        out.append(0)
    path = tmp_path / "proof.drat"
    path.write_bytes(bytes(out))
    assert parse_drat(path) == parse_drat(text)
    assert check_drat(f, path).verified


def test_time_guard_gives_unknown():
    r = check_drat(php(8), proof_of(php(8)), time_limit=0.0)
    assert r.status == "unknown" and r.reason.startswith("time limit of 0 s reached while")


def test_checker_imports_no_solver():
    src = pathlib.Path(__file__).resolve().parents[2] / "tilesolve" / "verify" / "drat.py"
    tree = ast.parse(src.read_text())
    names = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom):
            names.add(node.module or "")
    assert not any(n.startswith(("pysat", "ortools", "tilesolve.engine", "tilesolve.encodings")) for n in names)


# --------------------------------------------------------------------------- kernels
@st.composite
def watch_ops(draw):
    """A sequence of pushes and removals on a few watch lists (entries: ``node << 32 | 7``)."""
    n_lists = draw(st.integers(1, 6))
    ops, live, node = [], [], 0
    for _ in range(draw(st.integers(0, 120))):
        if live and draw(st.booleans()):
            lst, nd = live.pop(draw(st.integers(0, len(live) - 1)))
            ops.append(("remove", lst, nd))
        else:
            lst = draw(st.integers(0, n_lists - 1))
            ops.append(("push", lst, node))
            live.append((lst, node))
            node += 1
    return n_lists, ops


@pytest.mark.slow
@settings(max_examples=60, deadline=None)
@given(watch_ops())
def test_watch_lists_in_one_pool_keep_their_entries(case):
    """Watch vectors moved and compacted in their pool hold what a list per literal holds."""
    n_lists, ops = case
    live = np.cumsum([1 if op == "push" else -1 for op, _, _ in ops])
    most = int(live.max(initial=0))  # the most entries at once
    wl = np.zeros((n_lists + 1, 3), np.int64)
    pool = np.zeros(3 * most + 2 * n_lists + 6, np.int64)  # the least room that always suffices
    model: list[list[int]] = [[] for _ in range(n_lists)]
    for op, lst, nd in ops:
        if op == "push":
            K.w_push(wl, pool, lst, nd << 32 | 7)
            model[lst].append(nd)
        else:
            K.w_remove(wl, pool, lst, nd)
            i = model[lst].index(nd)
            model[lst][i] = model[lst][-1]
            model[lst].pop()
        for i in range(n_lists):
            start, n = wl[i, 0], wl[i, 1]
            assert n <= wl[i, 2] and start + n <= wl[n_lists, 0] <= pool.size
            assert [int(e) >> 32 for e in pool[start:start + n]] == model[i]


@st.composite
def unsat_formulas(draw):
    """A random unsatisfiable 3-CNF with a CaDiCaL proof, and maybe a tampered copy of it."""
    n = draw(st.integers(8, 30))
    lit = st.integers(1, n).flatmap(lambda v: st.sampled_from([v, -v]))
    clauses = draw(st.lists(st.lists(lit, min_size=2, max_size=3), min_size=5 * n, max_size=9 * n))
    clauses += [[v, w] for v, w in zip(range(1, n), range(2, n + 1))] + [[-1, -n], [1, n], [-2, -3]]
    with Solver(name="cadical153", bootstrap_with=clauses, with_proof=True) as s:
        if s.solve() is not False:
            clauses += [[v] for v in range(1, n + 1)] + [[-v for v in range(1, n + 1)]]
            with Solver(name="cadical153", bootstrap_with=clauses, with_proof=True) as s2:
                assert s2.solve() is False
                return clauses, list(s2.get_proof())
        proof = list(s.get_proof())
    lemmas = [i for i, line in enumerate(proof) if not line.startswith("d") and line.strip() != "0"]
    if lemmas and draw(st.booleans()):
        i = draw(st.sampled_from(lemmas))
        toks = proof[i].split()
        toks[0] = str(-int(toks[0]))
        proof[i] = " ".join(toks)
    return clauses, proof


@pytest.mark.slow
@settings(max_examples=40, deadline=None)
@given(unsat_formulas(), st.sampled_from(["core", "all"]))
def test_compiled_and_interpreted_kernels_give_the_same_verdicts(case, lemmas):
    """Both paths run the same kernels: the same verdict, lemmas checked and core; and with
    every lemma checked, the verdict of the forward reference engine."""
    clauses, proof = case
    a = check_drat(clauses, proof, kernels="plain", lemmas=lemmas)
    b = check_drat(clauses, proof, kernels="compiled", lemmas=lemmas)
    assert (a.status, a.reason, a.checked, a.rat_lemmas) == (b.status, b.reason, b.checked, b.rat_lemmas)
    if a.verified:
        assert a.core.tolist() == b.core.tolist()
    if lemmas == "all":
        assert a.verified == check_drat(clauses, proof, engine="forward").verified


# ------------------------------------------------------------ interpreted or compiled kernels
COMPILED = object()  # what the stand-in for the compilation returns


@pytest.fixture
def choice(monkeypatch):
    """A process that has compiled and interpreted nothing yet; ``choice(cached)`` says whether
    numba's cache holds the kernels, and compiling returns COMPILED."""
    monkeypatch.setattr(D, "_COMPILED", None)
    monkeypatch.setattr(D, "_PLAIN_WORK", 0)
    monkeypatch.setattr(D, "_compile", lambda: COMPILED)

    def cached(ready: bool) -> None:
        monkeypatch.setattr(D, "_cache_may_hold_kernels", lambda: ready)
        monkeypatch.setattr(D, "_kernel_cache", lambda: (ready, None))

    return cached


def test_a_warm_cache_is_loaded_from_compile_from(choice):
    choice(True)
    assert D._kernels(D.COMPILE_FROM - 1) is K
    assert D._kernels(D.COMPILE_FROM) is COMPILED
    assert D._kernels(1) is COMPILED  # once loaded, always


def test_interpreted_work_adds_up_to_the_threshold(choice):
    choice(True)
    half = D.COMPILE_FROM // 2 + 1
    assert D._kernels(half) is K
    assert D._kernels(half) is COMPILED  # the ski-rental rule: a loop of small checks ends compiled


def test_a_cold_cache_compiles_only_for_large_work(choice):
    choice(False)
    assert D._kernels(D.COLD_COMPILE_FROM - 1) is K  # the first check after an install: no compilation
    assert D._kernels(D.COLD_COMPILE_FROM, time_limit=1.0) is K  # no time to compile
    assert D._kernels(D.COLD_COMPILE_FROM) is COMPILED
    assert D._kernels(0, "plain") is K


def test_forced_paths(choice):
    choice(False)
    assert D._kernels(10**9, "plain") is K
    assert D._kernels(0, "compiled") is COMPILED


def test_a_check_that_outlasts_its_estimate_goes_on_compiled(monkeypatch, php6):
    """Charged what it costs (here: any time is a lot of work), an interpreted check switches to
    the compiled kernels between two calls, with the verdict of the interpreted kernels alone."""
    f, proof = php6
    alone = check_drat(f, proof, kernels="plain", lemmas="all")
    real = D._compile
    compiled = []
    monkeypatch.setattr(D, "_COMPILED", None)
    monkeypatch.setattr(D, "_PLAIN_WORK", 0)
    monkeypatch.setattr(D, "_compile", lambda: compiled.append(1) or real())
    monkeypatch.setattr(D, "UNIT_S", 1e-12)
    r = check_drat(f, proof, lemmas="all")  # a small proof: it starts interpreted
    assert compiled == [1] and D._COMPILED is not None
    assert (r.status, r.reason, r.checked, r.rat_lemmas) == (alone.status, alone.reason, alone.checked,
                                                             alone.rat_lemmas)
    assert r.core.tolist() == alone.core.tolist()


def _python(code: str, cache: pathlib.Path) -> list[str]:
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache))
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True)
    return out.stdout.split()


@pytest.mark.slow
def test_the_cold_cache_is_seen_without_importing_numba(tmp_path):
    """The quick look finds the cache where numba writes it (an empty NUMBA_CACHE_DIR, then the
    same folder once the kernels are compiled), without importing numba."""
    look = ("import sys; from tilesolve.verify import drat as D; "
            "print(D._cache_may_hold_kernels(), 'numba' in sys.modules)")
    assert _python(look, tmp_path) == ["False", "False"]
    assert _python("from tilesolve.verify import drat as D; D._kernels(0, 'compiled'); "
                   "print(D._kernel_cache()[0])", tmp_path) == ["True"]
    assert _python(look, tmp_path) == ["True", "False"]


def test_a_tiny_proof_after_install_compiles_nothing(tmp_path):
    """The README's unsat Wang packing with an empty numba cache: the proof is checked by the
    interpreted kernels, and no kernel is compiled into the cache."""
    cache = tmp_path / "numba"
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache))
    proc = subprocess.run([SCRIPT, "pack", "--kind", "wang", "--colors", "3", "--method", "sat", "--fix", "0,0,5",
                           "--fix", "0,1,7", "-o", str(tmp_path / "w.json")], env=env, capture_output=True, text=True)
    assert proc.returncode == 1, proc.stderr
    assert "DRAT proof checked by tilesolve.verify.drat" in proc.stdout + proc.stderr
    assert not list(cache.rglob("_drat_kernels.*"))


@given(st.lists(st.tuples(st.booleans(), st.lists(st.integers(-10**6, 10**6).filter(bool), min_size=1, max_size=6)),
                max_size=20))
@settings(max_examples=60, deadline=None)
def test_drat_bytes_reads_back_as_written(steps):
    steps = steps + [(False, [])]  # the empty clause ends a proof
    sizes = np.array([len(c) for _, c in steps], np.int64)
    lits = np.array([x for _, c in steps for x in c], np.int64)
    dels = np.array([d for d, _ in steps], np.int8)
    text = D.drat_bytes(lits, sizes, dels)
    assert parse_drat(text) == [(d, c) for d, c in steps]
    assert text.endswith(b"0\n") and b"\n\n" not in text
