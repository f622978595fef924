"""Unsat certificates: tilesolve's DRAT checker against dratify on real and tampered proofs.

The corpus is generated here from tilesolve's own unsat instances (dappled Example 6.2, a
count clash, Wang boards and tori, pinned packings), so nothing large sits on disk. Each
proof is checked by :mod:`tilesolve.verify.drat` (backward/core-first, interpreted and
compiled kernels; forward) and by ``dratify`` (an independent forward checker, PyPI), and
the verdicts must agree; tampered proofs must be rejected by both. Definitions: Wetzler,
Heule, Hunt, *DRAT-trim* (SAT 2014).
"""

from __future__ import annotations

import json

import dratify
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from pysat.solvers import Solver

from tilesolve.encodings.dappled import encode_cnf
from tilesolve.encodings.packing import encode_packing
from tilesolve.encodings.wang import encode_wang
from tilesolve.engine.sat import solve_cnf
from tilesolve.model.board import Board, BoardProblem, WangTileSet
from tilesolve.model.dappled import DappledProblem, parse_condition
from tilesolve.model.packing import PackingProblem
from tilesolve.model.solution import Status
from tilesolve.verify.drat import check_drat, check_proof_files, cnf_sha256, dimacs_bytes


def counter_tiles(a: int, b: int) -> WangTileSet:
    """Wang tiles counting mod ``a`` along rows and mod ``b`` along columns: a p x q torus
    exists exactly when ``a | p`` and ``b | q`` (in one orientation or the other)."""
    tiles = [((j + 1) % b, (i + 1) % a, j, i) for i in range(a) for j in range(b)]  # N, E, S, W
    return WangTileSet(tiles, max(a, b))


def _instances():
    conds = [parse_condition("H0=2"), parse_condition("V1=2")]
    fixed = np.array([[1, -1, -1, -1], [-1, 0, -1, -1], [-1, 0, 1, 1], [-1, 0, -1, -1]])
    yield "dappled Example 6.2", encode_cnf(DappledProblem(4, 4, conditions=conds, cyclic=True, fixed=fixed)).hard
    yield "dappled count clash", encode_cnf(DappledProblem.from_strings("3x3", ["H0=1"], counts=["1=0"])).hard
    yield "dappled 5x5 cyclic", encode_cnf(DappledProblem.from_strings("5x5", ["H0=1", "V0=1", "H1=1", "V1=1"],
                                                                      cyclic=True)).hard
    yield "Wang 1x1 cross", encode_wang(BoardProblem(Board.rect(1, 1), WangTileSet.brick(3), [0, 1, 0, 1])).hard
    yield "Wang torus 4x5", encode_wang(BoardProblem(Board.torus(5, 4), counter_tiles(3, 2))).hard
    yield "Wang torus 7x4", encode_wang(BoardProblem(Board.torus(4, 7), counter_tiles(3, 3))).hard
    yield "packing pins", encode_packing(PackingProblem("corner", 2, fixed=((0, 0, 0), (0, 1, 15)))).clauses


@pytest.fixture(scope="module")
def corpus():
    out = []
    for name, formula in _instances():
        r = solve_cnf(formula, with_proof=True, seed=1)
        assert r.status is Status.UNSAT, name
        out.append((name, formula, list(r.proof)))
    return out


def dratify_ok(formula, proof) -> bool:
    cnf = dratify.parse_dimacs(dimacs_bytes(formula).decode())
    return dratify.check_proof(cnf, "".join(line + "\n" for line in proof), engine="python").ok


def test_real_proofs_pass_both_checkers(corpus):
    for name, formula, proof in corpus:
        mine = check_drat(formula, proof)
        assert mine.verified, (name, mine.reason)
        assert check_drat(formula, proof, engine="forward").verified, name
        assert dratify_ok(formula, proof), name
    assert any(not check_drat(f, p).trivial for _, f, p in corpus)  # some need real lemmas
    assert any(check_drat(f, p).trivial for _, f, p in corpus)


def _lemma_lines(proof):
    return [i for i, line in enumerate(proof) if not line.startswith("d") and line.strip() != "0"]


@pytest.mark.slow
def test_tampered_proofs_are_rejected_by_both(corpus):
    rejected = {"truncated": 0, "no empty clause": 0, "lemmas dropped": 0, "altered": 0, "invented": 0}
    for name, formula, proof in corpus:
        base = check_drat(formula, proof)
        lemmas = _lemma_lines(proof)
        tampered = [("no empty clause", [ln for ln in proof if ln.strip() != "0"]),
                    ("truncated", proof[: len(proof) // 2]),
                    ("lemmas dropped", [proof[i] for i in range(len(proof)) if i not in set(lemmas)]),
                    ("invented", ["0"] + proof)]  # an empty clause up front: not RUP unless trivial
        for i in lemmas[:8]:  # flip the first literal of a lemma
            bad = list(proof)
            toks = bad[i].split()
            toks[0] = str(-int(toks[0]))
            bad[i] = " ".join(toks)
            tampered.append(("altered", bad))
        for kind, bad in tampered:
            mine = check_drat(formula, bad, lemmas="all")
            theirs = dratify_ok(formula, bad)
            assert mine.verified == theirs, (name, kind, mine.reason)
            assert check_drat(formula, bad, engine="forward").verified == theirs, (name, kind)
            if not base.trivial and kind != "altered":
                assert not mine.verified and not check_drat(formula, bad).verified, (name, kind)
            rejected[kind] += not mine.verified
    assert all(n > 0 for n in rejected.values()), rejected


@pytest.mark.slow
def test_plain_and_compiled_kernels_agree(corpus):
    for name, formula, proof in corpus:
        a = check_drat(formula, proof, kernels="plain")
        b = check_drat(formula, proof, kernels="compiled")
        assert (a.status, a.checked, a.core.tolist()) == (b.status, b.checked, b.core.tolist()), name


@st.composite
def unsat_cnfs(draw):
    n = draw(st.integers(3, 9))
    lit = st.integers(1, n).flatmap(lambda v: st.sampled_from([v, -v]))
    clauses = draw(st.lists(st.lists(lit, min_size=1, max_size=3), min_size=4 * n, max_size=7 * n))
    with Solver(name="cadical153", bootstrap_with=clauses, with_proof=True) as s:
        if s.solve() is False:
            return clauses, list(s.get_proof())
    clauses = clauses + [[v] for v in range(1, n + 1)] + [[-v for v in range(1, n + 1)]]
    with Solver(name="cadical153", bootstrap_with=clauses, with_proof=True) as s:
        assert s.solve() is False
        return clauses, list(s.get_proof())


@pytest.mark.slow
@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(unsat_cnfs(), st.data())
def test_random_unsat_cnfs_agree_with_dratify(case, data):
    clauses, proof = case
    assert check_drat(clauses, proof).verified
    assert check_drat(clauses, proof, engine="forward").verified
    assert dratify_ok(clauses, proof)
    lines = _lemma_lines(proof)
    if not lines:
        return
    bad = list(proof)
    i = data.draw(st.sampled_from(lines))
    how = data.draw(st.sampled_from(["flip", "drop"]))
    if how == "drop":
        del bad[i]
    else:
        toks = bad[i].split()
        k = data.draw(st.integers(0, len(toks) - 2))
        toks[k] = str(-int(toks[k]))
        bad[i] = " ".join(toks)
    expect = dratify_ok(clauses, bad)
    assert check_drat(clauses, bad, lemmas="all").verified == expect
    assert check_drat(clauses, bad, engine="forward").verified == expect
    # core mode may accept a proof whose broken lemma is unused, but never rejects a valid one
    assert expect <= check_drat(clauses, bad).verified


def test_rat_lemmas_are_checked_not_trusted():
    f = [[1, 2], [-1, 2], [1, -2], [-1, -2]]
    r = check_drat(f, ["3 0", "1 0", "0"], lemmas="all")  # 3 is fresh: RAT, not RUP
    assert r.verified and r.rat_lemmas == 1
    # with the clause (-3 4) around, the resolvent (4) is not RUP: "3" is not RAT
    r = check_drat(f + [[-3, 4]], ["3 0", "1 0", "0"], lemmas="all")
    assert r.status == "failed" and r.reason.startswith("lemma 1 ")
    assert not dratify_ok(f + [[-3, 4]], ["3 0", "1 0", "0"])


def test_proof_files_round_trip(tmp_path, corpus):
    name, formula, proof = corpus[0]
    (tmp_path / "x.cnf").write_bytes(dimacs_bytes(formula))
    (tmp_path / "x.drat").write_text("".join(line + "\n" for line in proof))
    ok, lines = check_proof_files(tmp_path, "x", cnf_sha256(formula))
    assert ok and "verified" in lines[-1]
    ok, lines = check_proof_files(tmp_path, "x", "0" * 64)
    assert not ok and "differs from the recorded" in lines[0]
    (tmp_path / "x.drat").write_text("".join(line + "\n" for line in proof if line != "0"))
    assert not check_proof_files(tmp_path, "x", cnf_sha256(formula))[0]


def test_cli_proof_dir_and_verify(tmp_path):
    from click.testing import CliRunner

    from tilesolve.cli.main import main_group

    def run_cli(args):
        return CliRunner().invoke(main_group, args)

    out, proofs = tmp_path / "u.json", tmp_path / "proofs"
    r = run_cli(["dappled", "solve", "--size", "3x3", "--cond", "H0=1", "--count", "1=0", "-o", str(out),
                 "--proof-dir", str(proofs)])
    assert r.exit_code == 1, r.output
    doc = json.loads(out.read_text())
    assert "unit propagation on the input clauses refutes it" in doc["reason"] and "'count 1=0'" in doc["reason"]
    name = doc["stats"]["proof_name"]
    cnf = (proofs / f"{name}.cnf").read_bytes()
    assert doc["stats"]["cnf_sha256"] == __import__("hashlib").sha256(cnf).hexdigest()
    assert dratify.check_proof(dratify.parse_dimacs(cnf.decode()), (proofs / f"{name}.drat").read_text()).ok
    r = run_cli(["verify", str(out), "--proof-dir", str(proofs)])
    assert r.exit_code == 0 and "unsat re-checked" in r.output
    (proofs / f"{name}.drat").write_text("1 0\n")
    r = run_cli(["verify", str(out), "--proof-dir", str(proofs)])
    assert r.exit_code == 1 and "differs from the recorded" in r.output


def test_cpsat_infeasibility_is_certified_or_unknown():
    from tilesolve.families import board as wang

    p = BoardProblem(Board.rect(1, 1), WangTileSet.brick(3), [0, 1, 0, 1])
    s = wang.solve(p, method="cpsat", seed=1)
    assert s.status is Status.UNSAT and "checked" in s.reason
    assert any("certified by the 'sat' route" in n for n in s.notes)
    from tilesolve.engine.cpsat import solve_cp_model
    from tilesolve.encodings.wang import build_cpsat_wang

    cp = build_cpsat_wang(p)
    r = solve_cp_model(cp.model, cp.bools, seed=1)
    assert r.status is Status.UNKNOWN and r.reason.startswith("uncertified:")


def test_constructive_unsat_is_certified_by_the_sat_route(monkeypatch):
    from tilesolve.families import board as wang
    from tilesolve.model.solution import Solution

    p = BoardProblem(Board.rect(1, 1), WangTileSet.brick(3), [0, 1, 0, 1])
    s = wang.solve(p, method="linear", seed=1)  # the §4.2 tree solver finds the clash, SAT proves it
    assert s.status is Status.UNSAT and s.stats["proof_status"] == "verified"
    assert any("'linear' found it unsatisfiable" in n and "certified by the 'sat' route" in n for n in s.notes)
    # a certification that does not come through leaves the claim unknown, never unsat
    monkeypatch.setitem(wang.FAMILY.routes, "sat",
                        lambda problem, run: Solution(Status.UNKNOWN, None, "sat", reason="no time"))
    s = wang.solve(p, method="linear", seed=1)
    assert s.status is Status.UNKNOWN and s.reason.startswith("uncertified: 'linear' found it unsatisfiable")
