"""The census of small Wang tile sets (:mod:`tilesolve.families.aperiodic_census`): every
record's certificate checked; local workers and Dask agree; a stopped census resumes."""

from __future__ import annotations

import json

import numpy as np
import pytest

from tilesolve.deadline import Deadline
from tilesolve.errors import InvalidProblem
from tilesolve.families.aperiodic_census import CENSUS_FORMAT, census, classify
from tilesolve.model.aperiodic import AperiodicProblem, Certificate
from tilesolve.model.board import WangTileSet
from tilesolve.model.run import RunOptions
from tilesolve.verify.aperiodic import witness_violations


def _check(rec: dict, k: int) -> None:
    """A record's certificates, checked with the family's verifier (witnesses) and its proof's digests."""
    ts = WangTileSet(np.asarray(rec["tiles"]), k)
    problem = AperiodicProblem(ts, 12, 12)
    if rec["class"] == "periodic":
        assert witness_violations(problem, Certificate(rec["torus"], "tiles", np.asarray(rec["tiling"]))) == []
    elif rec["class"] == "finite":
        n = rec["largest_square"]
        assert witness_violations(problem, Certificate(f"square {n}x{n}", "tiles", np.asarray(rec["tiling"]))) == []
        ref = rec["refutation"]
        assert ref["board"] == f"square {n + 1}x{n + 1}" and ref["cnf_sha256"] and ref["drat_sha256"]
        assert ref["checker"] == "tilesolve.verify.drat" and ref["encoding"]


def test_classify_gives_checked_certificates():
    free = classify([0], 2, 12, 12, Deadline(None))  # the tile of one colour everywhere
    assert (free["class"], free["torus"], free["tiling"]) == ("periodic", "torus 1x1", [[0]])
    # N=0 and S=1 on one tile: no 2x2 square (rows never stack), a 1x1 one
    number = int(np.ravel_multi_index((0, 0, 1, 0), (2,) * 4))
    stuck = classify([number], 2, 12, 12, Deadline(None))
    assert (stuck["class"], stuck["largest_square"]) == ("finite", 1)
    for rec in (free, stuck):
        _check(rec, 2)
    late = classify([number], 2, 12, 12, Deadline(0))
    assert late["class"] == "undecided" and "time limit" in late["why"]


def test_census_classifies_every_set_and_resumes(tmp_path):
    out = tmp_path / "c.jsonl"
    full = census(3, 2, RunOptions(seed=0, workers=1), out, max_square=8, max_period=8)
    assert full.complete and full.n_sets == 36 and full.counts() == {"finite": 7, "periodic": 29, "undecided": 0,
                                                                      "not reached": 0}
    for rec in full.records:
        _check(rec, 2)
    lines = out.read_text().splitlines()
    assert json.loads(lines[0])["format"] == CENSUS_FORMAT and len(lines) == 37
    # a stopped run: nine records, one of them a finite set forged as periodic, then a line cut short
    finite = next(line for line in lines[1:] if json.loads(line)["class"] == "finite")
    others = [line for line in lines[1:] if line != finite]
    forged = {**json.loads(finite), "class": "periodic", "torus": "torus 1x1", "tiling": [[0]]}
    # a finite set tiles no torus: the verifier rejects the forged witness
    out.write_text("\n".join(lines[:1] + others[:8] + [json.dumps(forged), others[8][:25]]) + "\n")
    again = census(3, 2, RunOptions(seed=0, workers=1), out, max_square=8, max_period=8, resume=True)
    assert again.resumed == 8 and again.complete
    assert [(r["set"], r["class"]) for r in again.records] == [(r["set"], r["class"]) for r in full.records]
    assert len(out.read_text().splitlines()) == 37
    # the kept proofs are what a resumed refutation rests on: without them the finite sets are decided again
    import shutil

    shutil.rmtree(str(out) + ".proofs")
    third = census(3, 2, RunOptions(seed=0, workers=1), out, max_square=8, max_period=8, resume=True)
    assert third.resumed == 29 and third.complete and third.counts() == full.counts()
    with pytest.raises(InvalidProblem, match="not a census of these sets"):
        census(2, 2, RunOptions(seed=0, workers=1), out, resume=True)


@pytest.mark.slow
def test_census_on_a_dask_cluster_and_local_workers_agree(tmp_path):
    import distributed

    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0") as lc:
        dask = census(3, 2, RunOptions(seed=0, cluster=lc.scheduler_address), tmp_path / "d.jsonl")
    pool = census(3, 2, RunOptions(seed=0, workers=2), tmp_path / "p.jsonl")
    assert dask.complete and pool.complete
    assert [(r["set"], r["class"]) for r in dask.records] == [(r["set"], r["class"]) for r in pool.records]


@pytest.mark.slow
def test_census_agrees_with_the_transfer_matrix_counts(tmp_path):
    """An independent route: the transfer-matrix counter finds tilings of each periodic set's
    torus and of each finite set's largest square, and none of the square above it."""
    from tilesolve.constructive.wang_count import count_grid

    result = census(3, 2, RunOptions(seed=0, workers=1), tmp_path / "c.jsonl", max_square=6, max_period=6)
    assert result.complete
    for rec in result.records:
        ts = WangTileSet(np.asarray(rec["tiles"]), 2)
        if rec["class"] == "periodic":
            rows, cols = np.asarray(rec["tiling"]).shape
            assert count_grid(ts, rows, cols, wrap_rows=True, wrap_cols=True) > 0, rec["set"]
        else:
            n = rec["largest_square"]
            assert count_grid(ts, n, n) > 0 and count_grid(ts, n + 1, n + 1) == 0, rec["set"]
