"""A certificate binds the problem, not only the files; caches are not evidence (issue 17, parts 1-2).

Every unsat answer and every refuted board records its named encoding (name, version, options);
``tilesolve verify`` re-derives the CNF from the problem the file states and checks the proof
against that formula. Each test below forges a file, a proof directory or a cache the way an
adversary would, through the real console script, and expects a refusal; honest files of every
family still verify.
"""

from __future__ import annotations

import hashlib
import json
import shutil

import pytest
from clitools import one_line_error, run

from tilesolve.families.aperiodic import AperiodicProblem, build_report
from tilesolve.engine.aperiodic import sweep
from tilesolve.family import solution_text
from tilesolve.io.builtin_tilesets import load
from tilesolve.model.aperiodic import Certificate
from tilesolve.model.board import WangTileSet
from tilesolve.model.run import RunOptions
from tilesolve.model.solution import Solution, Status

NOT_ENCODING = "the CNF is not the encoding of this problem"
#: N, E, S, W: tile i has N = W = i, E = S = i + 1 (mod 3): it tiles the torus 3x3 and, of the
#: 3x1 tori, only the one with shear 1.
DIAGONAL = [[i, (i + 1) % 3, (i + 1) % 3, i] for i in range(3)]


def _unsat_dappled(tmp_path, name="u.json", size="3x3", proofs="proofs"):
    """An honest unsat dappled file and its proof directory, made by the CLI."""
    proc = run("dappled", "solve", "--size", size, "--cond", "H0=1", "--count", "1=0", "-o", name,
               "--proof-dir", proofs, cwd=tmp_path)
    assert proc.returncode == 1, proc.stderr
    return json.loads((tmp_path / name).read_text())


def _write(tmp_path, name, doc):
    (tmp_path / name).write_text(json.dumps(doc))


def _proof_files(folder, cnf: bytes, drat: bytes) -> dict:
    """Write a CNF and a proof under the name tilesolve gives them; the digests to record."""
    c, d = hashlib.sha256(cnf).hexdigest(), hashlib.sha256(drat).hexdigest()
    folder.mkdir(exist_ok=True)
    name = f"unsat-{c[:16]}-{d[:8]}"
    (folder / f"{name}.cnf").write_bytes(cnf)
    (folder / f"{name}.drat").write_bytes(drat)
    return {"cnf_sha256": c, "drat_sha256": d, "proof_name": name}


# ------------------------------------------------------------------------------ unsat files
@pytest.mark.slow
def test_honest_unsat_rechecked_and_without_proofs_says_not_rechecked(tmp_path):
    _unsat_dappled(tmp_path)
    proc = run("verify", "u.json", "--proof-dir", "proofs", cwd=tmp_path)
    assert proc.returncode == 0, proc.stdout
    assert proc.stdout.startswith("ok: u.json: unsat re-checked") and "encoding dappled-cnf v1" in proc.stdout
    proc = run("verify", "u.json", cwd=tmp_path)
    assert proc.returncode == 1
    assert "the unsat claim was NOT re-checked" in proc.stdout and "--proof-dir DIR" in proc.stdout
    assert not proc.stdout.startswith("ok:")


@pytest.mark.slow
def test_satisfiable_problem_pointed_at_a_trivial_cnf_is_refused(tmp_path):
    """The issue's reproduction: a satisfiable 6x5 {H0=2, V1=2} problem whose stats point at
    ``p cnf 1 2 / 1 0 / -1 0`` and the proof ``0``."""
    doc = _unsat_dappled(tmp_path)
    doc.update(size={"rows": 5, "cols": 6}, conditions=["H0=2", "V1=2"])
    doc.pop("counts", None)
    doc["stats"].update(_proof_files(tmp_path / "forged", b"p cnf 1 2\n1 0\n-1 0\n", b"0\n"))
    _write(tmp_path, "f.json", doc)
    for extra in (["--proof-dir", "forged"], []):
        proc = run("verify", "f.json", *extra, cwd=tmp_path)
        assert proc.returncode == 1 and NOT_ENCODING in proc.stdout, proc.stdout
        assert not proc.stdout.startswith("ok:")


@pytest.mark.slow
def test_swapped_cnfs_and_proofs_are_refused(tmp_path):
    a = _unsat_dappled(tmp_path, "a.json", "3x3")
    b = _unsat_dappled(tmp_path, "b.json", "4x2")
    # a's problem with b's (honest, checked) certificate
    keys = ("cnf_sha256", "drat_sha256", "proof_name")
    a_with_b = dict(a, stats={**a["stats"], **{k: b["stats"][k] for k in keys}})
    _write(tmp_path, "ab.json", a_with_b)
    proc = run("verify", "ab.json", "--proof-dir", "proofs", cwd=tmp_path)
    assert proc.returncode == 1 and NOT_ENCODING in proc.stdout
    # the CNF file in the proof directory swapped for b's, under a's name
    name_a, name_b = a["stats"]["proof_name"], b["stats"]["proof_name"]
    shutil.copy(tmp_path / "proofs" / f"{name_b}.cnf", tmp_path / "proofs" / f"{name_a}.cnf")
    proc = run("verify", "a.json", "--proof-dir", "proofs", cwd=tmp_path)
    assert proc.returncode == 1 and NOT_ENCODING in proc.stdout and "differs from the CNF re-derived" in proc.stdout
    # b's proof under a's name: its digest is not the one a records
    (tmp_path / "proofs" / f"{name_a}.cnf").unlink()
    shutil.copy(tmp_path / "proofs" / f"{name_b}.drat", tmp_path / "proofs" / f"{name_a}.drat")
    proc = run("verify", "a.json", "--proof-dir", "proofs", cwd=tmp_path)
    assert proc.returncode == 1 and "differs from the recorded" in proc.stdout


@pytest.mark.slow
def test_a_proof_is_checked_against_the_rederived_formula_not_the_file(tmp_path):
    """A forger who records the digest of the real CNF and writes a trivially unsat CNF file
    under that name, with the proof ``0``: the proof fails on the re-derived formula."""
    doc = _unsat_dappled(tmp_path)
    doc.update(size={"rows": 5, "cols": 6}, conditions=["H0=2", "V1=2"])
    doc.pop("counts", None)
    from tilesolve.encodings.registry import encode
    from tilesolve.model.dappled import DappledProblem
    from tilesolve.verify.drat import dimacs_bytes

    cnf = dimacs_bytes(encode("dappled-cnf", DappledProblem.from_strings("6x5", ["H0=2", "V1=2"])).hard)
    stats = _proof_files(tmp_path / "forged", cnf, b"0\n")
    (tmp_path / "forged" / f"{stats['proof_name']}.cnf").unlink()
    doc["stats"].update(stats)
    _write(tmp_path, "f.json", doc)
    proc = run("verify", "f.json", "--proof-dir", "forged", cwd=tmp_path)
    assert proc.returncode == 1 and "failed against the re-derived CNF" in proc.stdout, proc.stdout


@pytest.mark.slow
@pytest.mark.parametrize("encoding,message", [
    ({"name": "dappled-cnf", "version": 0, "options": {"card_encoding": "auto"}},
     "proof made with encoding dappled-cnf v0; this version encodes v1: re-solve to re-certify"),
    ({"name": "dappled-cnf-2030", "version": 1, "options": {}},
     "proof made with encoding dappled-cnf-2030 v1; this tilesolve has no encoding of that name"),
    ({"name": "wang-board-cnf", "version": 2, "options": {}}, "encodes board problems, not a DappledProblem"),
    ({"name": "dappled-cnf", "version": 1, "options": {"card_encoding": "totalizer", "x": 1}}, "has no option 'x'"),
    (None, "records no named encoding"),
])
def test_changed_or_unknown_encodings_are_refused_plainly(tmp_path, encoding, message):
    doc = _unsat_dappled(tmp_path)
    if encoding is None:
        del doc["stats"]["encoding"]
    else:
        doc["stats"]["encoding"] = encoding
    _write(tmp_path, "v.json", doc)
    for extra in (["--proof-dir", "proofs"], []):
        proc = run("verify", "v.json", *extra, cwd=tmp_path)
        assert proc.returncode == 1 and message in proc.stdout and "Traceback" not in proc.stderr, proc.stdout


@pytest.mark.slow
def test_export_dimacs_writes_the_formula_verify_rederives(tmp_path):
    doc = _unsat_dappled(tmp_path)
    problem = {k: v for k, v in doc.items() if k in ("version", "size", "n_tiles", "conditions", "cyclic", "counts")}
    _write(tmp_path, "p.json", {**problem, "format": "tilesolve/dappled-problem"})
    assert run("export", "dimacs", "p.json", "-o", "p.cnf", cwd=tmp_path).returncode == 0
    exported = [ln for ln in (tmp_path / "p.cnf").read_text().splitlines() if not ln.startswith(("c", "p"))]
    stored = (tmp_path / "proofs" / f"{doc['stats']['proof_name']}.cnf").read_text().splitlines()[1:]
    assert exported == stored


#: One problem per named encoding and the SHA-256 of its CNF at the version named: a change to
#: an encoder (or to the model code it reads) that changes a CNF fails here; raise the
#: encoding's version in ``tilesolve.encodings.registry.ENCODINGS`` and record the new digest,
#: so that files certified with the old CNF are refused as "re-solve to re-certify".
PINNED = {
    "dappled-cnf": (1, "85b9eb80a3dfba99eef215ee3aa7ba82e53a42b5499bc587ff8a63524f8a7bf1"),
    "wang-board-cnf": (2, "e9b9278995d9e734bd7b78fd37990f18f0b5c9be34a52d4af5d8932a40ee93e2"),
    "packing-cnf": (1, "65f997450a660d5c665c6e3c1084b1b5a16c82e86c866830002fe818d2bc3e29"),
    "wang-tiles-cnf": (1, "b2d5e77873f3807a1c4bb149c95c6d1e8375b2cedd411f8401d0ea1a37186e83"),
    "shapes-tile-cnf": (1, "12eb0ba6e239fd971c3af177b264cd335ab799a1173606ad52d6fb07ca5636d7"),
    "shapes-corona-cnf": (1, "1439edb3bc8682ad35f186202313348ff26f1c0ecb16ac2f90dd582cad4907ee"),
}


def test_every_named_encoding_is_deterministic_and_pinned_to_its_version():
    from tilesolve.encodings.registry import ENCODINGS, encode
    from tilesolve.engine.aperiodic import board_problem
    from tilesolve.model.board import Board, BoardProblem
    from tilesolve.model.dappled import DappledProblem
    from tilesolve.model.packing import PackingProblem
    from tilesolve.model.shapes import ShapesProblem, parse_ascii, parse_cells
    from tilesolve.verify.drat import dimacs_bytes

    problems = {
        "dappled-cnf": DappledProblem.from_strings("5x4", ["H0=2", "V1=2"], cyclic=True, counts=["1=6..9"]),
        "wang-board-cnf": BoardProblem(Board.mobius(4, 3), WangTileSet.brick(3), max_h=2),
        "packing-cnf": PackingProblem("corner", 2, fixed=((0, 0, 3),)),
        "wang-tiles-cnf": board_problem(WangTileSet(DIAGONAL, 3), "torus 3x2 shear 1"),
        "shapes-tile-cnf": ShapesProblem("tile", (parse_ascii("##\n##\n#.", "omino"),), lattice=((5, 0), (2, 1))),
        "shapes-corona-cnf": ShapesProblem("classify", (parse_cells("0,0 0,1 0,2 0,3 1,-1 1,3", "hex"),)),
    }
    assert set(problems) == set(ENCODINGS) == set(PINNED)
    for name, problem in problems.items():
        digests = {hashlib.sha256(dimacs_bytes(encode(name, problem).hard)).hexdigest() for _ in range(2)}
        assert digests == {PINNED[name][1]} and ENCODINGS[name].version == PINNED[name][0], name


# ------------------------------------------------------------------------- every family
@pytest.mark.slow
def test_honest_unsat_of_every_route_verifies_and_a_relabel_is_refused(tmp_path):
    (tmp_path / "lonely.json").write_text(json.dumps({"order": "NESW", "colors": 2, "tiles": [[0, 1, 0, 0]]}))
    runs = {
        "board.json": ["wang", "solve", "--tiles", "lonely.json", "--board", "torus:2x1", "--boundary", "free"],
        "pins.json": ["pack", "--kind", "corner", "--colors", "2", "--fix", "0,0,0", "--fix", "0,1,15"],
        "lift.json": ["pack", "--kind", "wang", "--colors", "3", "--method", "lift", "--fix", "0,0,5", "--fix", "0,1,7"],
        "cpsat.json": ["dappled", "solve", "--size", "4x4", "--cond", "H0=1", "--count", "1=0", "--method", "cpsat"],
        "maxsat.json": ["dappled", "solve", "--size", "4x4", "--cond", "H0=1", "--count", "1=0", "--method", "maxsat"],
    }
    for out, args in runs.items():
        proc = run(*args, "-o", out, "--proof-dir", "proofs", cwd=tmp_path)
        assert proc.returncode == 1, (out, proc.stderr)
        proc = run("verify", out, "--proof-dir", "proofs", cwd=tmp_path)
        assert proc.returncode == 0 and proc.stdout.startswith(f"ok: {out}: unsat re-checked"), (out, proc.stdout)
    # a packing's pins changed: the same certificate no longer encodes the problem
    doc = json.loads((tmp_path / "pins.json").read_text())
    doc["fixed"] = [[0, 0, 0], [0, 1, 14]]
    _write(tmp_path, "pins2.json", doc)
    proc = run("verify", "pins2.json", "--proof-dir", "proofs", cwd=tmp_path)
    assert proc.returncode == 1 and NOT_ENCODING in proc.stdout, proc.stdout


# --------------------------------------------------------------------------------- reports
def _lines_end_with_one_verdict(stdout: str) -> str:
    lines = stdout.rstrip("\n").splitlines()
    assert all(ln.startswith("  ") for ln in lines[:-1]) and not lines[-1].startswith(" "), stdout
    return lines[-1]


@pytest.mark.slow
def test_relabelled_lattice_with_another_boards_proof_is_refused(tmp_path):
    """The issue's reproduction: periodic-8-20's "torus 7x6 shear 6" (which tiles) relabelled
    refuted with the 1x1 torus's proof, by a careful forger who also rewrites the conclusion
    (the report keeps the witness of the 14x6 torus with shear 6, so it still covers what it says)."""
    tileset, info = load("periodic-8-20")
    problem = AperiodicProblem(tileset, 0, 14, shears=True, name="periodic-8-20", info=info)
    from tilesolve.engine.certificates import writing_proofs

    with writing_proofs(tmp_path / "proofs"):
        certs, _ = sweep(tileset, ["torus 1x1", "torus 7x6 shear 6", "torus 14x6 shear 6"],
                         RunOptions(seed=1, workers=1), stop_at_witness=False)
    assert [c.status for c in certs] == ["refuted", "tiles", "tiles"]

    def report(periods):
        rep = build_report(problem, (), None, periods)
        return json.loads(solution_text(problem, Solution(rep.status, None, "sat", None, 1, 0.0, report=rep)))

    _write(tmp_path, "r.json", report(certs))
    proc = run("aperiodic", "verify", "r.json", "--proof-dir", "proofs", cwd=tmp_path)
    assert proc.returncode == 0 and _lines_end_with_one_verdict(proc.stdout).startswith("ok: r.json"), proc.stdout
    doc = report([certs[0], Certificate(certs[1].board, "refuted", None, "sat", certs[0].evidence), certs[2]])
    _write(tmp_path, "f.json", doc)
    for args in (["verify", "f.json"], ["verify", "f.json", "--proof-dir", "proofs"],
                 ["aperiodic", "verify", "f.json", "--proof-dir", "proofs"], ["aperiodic", "verify", "f.json"]):
        proc = run(*args, cwd=tmp_path)
        assert proc.returncode == 1 and NOT_ENCODING in proc.stdout, (args, proc.stdout)
        assert "torus 7x6 shear 6" in proc.stdout and not proc.stdout.startswith("ok:")
    verdict = _lines_end_with_one_verdict(proc.stdout)
    assert verdict.startswith("f.json: the file's claims are false")
    # the relabel alone, the conclusion left as it was, is a false conclusion too
    doc = report(certs)
    doc["periods"][1].update(status="refuted", tiling=None, evidence=doc["periods"][0]["evidence"])
    _write(tmp_path, "c.json", doc)
    proc = run("aperiodic", "verify", "c.json", "--proof-dir", "proofs", cwd=tmp_path)
    assert proc.returncode == 1 and "the conclusion is not what the certificates prove" in proc.stdout
    # a refutation by a route that left no proof ("magic") is no refutation either
    doc = report([certs[0], Certificate(certs[1].board, "refuted", None, "magic", {"trust": "me"}), certs[2]])
    _write(tmp_path, "m.json", doc)
    proc = run("aperiodic", "verify", "m.json", "--proof-dir", "proofs", cwd=tmp_path)
    assert proc.returncode == 1 and "records no named encoding" in proc.stdout
    assert not _lines_end_with_one_verdict(proc.stdout).startswith("ok:")


@pytest.mark.slow
def test_a_report_claims_no_more_than_its_certificates(tmp_path):
    """Without a witness, a sweep's report must hold every lattice it counts; dropping one, or
    claiming more in words, is refused."""
    (tmp_path / "lonely.json").write_text(json.dumps({"order": "NESW", "colors": 2, "tiles": [[0, 1, 0, 0]]}))
    assert run("aperiodic", "check", "lonely.json", "--max-period", "2", "--workers", "1", "-o", "r.json",
               cwd=tmp_path).returncode == 0
    doc = json.loads((tmp_path / "r.json").read_text())
    assert [c["status"] for c in doc["periods"]] == ["refuted"] * 4
    _write(tmp_path, "d.json", dict(doc, periods=doc["periods"][:3]))
    proc = run("verify", "d.json", cwd=tmp_path)
    assert proc.returncode == 1 and "the periods are not every lattice of this check" in proc.stdout
    _write(tmp_path, "w.json", dict(doc, conclusion="The set is aperiodic."))
    proc = run("verify", "w.json", cwd=tmp_path)
    assert proc.returncode == 1 and "the conclusion is not what the certificates prove" in proc.stdout


@pytest.mark.slow
def test_transducer_emptiness_certificate_is_rederived(tmp_path):
    (tmp_path / "lonely.json").write_text(json.dumps({"order": "NESW", "colors": 2, "tiles": [[0, 1, 0, 0]]}))
    proc = run("aperiodic", "check", "lonely.json", "--method", "transducer", "--max-square", "3", "-o", "t.json",
               "--proof-dir", "proofs", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    doc = json.loads((tmp_path / "t.json").read_text())
    assert [(c["board"], c["method"]) for c in doc["squares"]] == [("rectangle 1x2", "sat+transducer")]
    proc = run("aperiodic", "verify", "t.json", "--proof-dir", "proofs", cwd=tmp_path)
    assert proc.returncode == 0 and "1 refutation(s) re-checked" in _lines_end_with_one_verdict(proc.stdout)
    _write(tmp_path, "u.json", dict(doc, status="unsat"))  # a report relabelled as an unsat answer
    proc = run("verify", "u.json", "--proof-dir", "proofs", cwd=tmp_path)
    assert proc.returncode == 1 and "NOT confirmed" in proc.stdout and not proc.stdout.startswith("ok:")
    doc["squares"][0]["board"] = "square 1x1"  # relabelled: the 1x1 square is tiled
    _write(tmp_path, "f.json", doc)
    proc = run("aperiodic", "verify", "f.json", "--proof-dir", "proofs", cwd=tmp_path)
    assert proc.returncode == 1 and NOT_ENCODING in proc.stdout
    assert not _lines_end_with_one_verdict(proc.stdout).startswith("ok:")


@pytest.mark.slow
def test_report_with_a_three_colour_tile_is_one_error_line(tmp_path):
    (tmp_path / "lonely.json").write_text(json.dumps({"order": "NESW", "colors": 2, "tiles": [[0, 1, 0, 0]]}))
    assert run("aperiodic", "check", "lonely.json", "--max-period", "1", "-o", "r.json", cwd=tmp_path).returncode == 0
    doc = json.loads((tmp_path / "r.json").read_text())
    doc["tileset"]["tiles"][0] = [0, 1, 0]
    _write(tmp_path, "bad.json", doc)
    for cmd in (["verify"], ["aperiodic", "verify"]):
        assert "4 integer colours" in one_line_error(run(*cmd, "bad.json", cwd=tmp_path))


# ---------------------------------------------------------------------------------- caches


@pytest.mark.slow
def test_forged_cache_lines_are_decided_again_and_proofs_written_for_cached_refutations(tmp_path):
    (tmp_path / "d.json").write_text(json.dumps({"order": "NESW", "colors": 3, "tiles": DIAGONAL}))
    args = ["aperiodic", "check", "d.json", "--max-period", "3", "--shears", "--workers", "1", "--every-board"]
    assert run(*args, "-o", "r.json", cwd=tmp_path).returncode == 0  # no --proof-dir: the cache keeps the proofs
    cache = tmp_path / "r.json.cache.jsonl"
    lines = [json.loads(ln) for ln in cache.read_text().splitlines()]
    by_board = {ln["board"]: ln for ln in lines}
    assert by_board["torus 3x1 shear 1"]["status"] == "tiles" and by_board["torus 1x1"]["status"] == "refuted"
    # forgeries: a tiled lattice relabelled refuted with another board's proof, a witness
    # whose tiles are changed, a refutation whose proof is swapped for another board's
    forged = dict(by_board["torus 3x1 shear 1"], status="refuted", tiling=None, method="sat",
                  evidence=by_board["torus 1x1"]["evidence"])
    bad_witness = dict(by_board["torus 3x3"], status="tiles", tiling=[[0, 0, 0]] * 3)
    swapped = dict(by_board["torus 2x2"], evidence=by_board["torus 1x2"]["evidence"])
    with cache.open("a") as f:
        for rec in (forged, bad_witness, swapped):
            f.write(json.dumps(rec) + "\n")
    proc = run(*args, "-o", "r2.json", "--cache", "r.json.cache.jsonl", "--proof-dir", "proofs", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert "3 cache line(s) not confirmed and decided again" in proc.stderr
    doc = json.loads((tmp_path / "r2.json").read_text())
    periods = {c["board"]: c for c in doc["periods"]}
    assert periods["torus 3x1 shear 1"]["status"] == "tiles" and "cache_rejected" in periods["torus 3x1 shear 1"][
        "evidence"]
    assert periods["torus 3x3"]["evidence"].get("cached") is not True
    assert periods["torus 2x2"]["status"] == "refuted" and "cache_rejected" in periods["torus 2x2"]["evidence"]
    cached = [c for c in doc["periods"] if c["evidence"].get("cached")]
    assert cached and all(c["evidence"]["cache_check"] in ("witness re-verified",
                                                           "proof re-checked against the re-derived CNF")
                          for c in cached)
    # every refutation reported has its CNF and proof in --proof-dir, cached or not
    refuted = [c for c in doc["periods"] if c["status"] == "refuted"]
    assert any(c["evidence"].get("cached") for c in refuted)
    for c in refuted:
        name = c["evidence"]["proof_name"]
        assert (tmp_path / "proofs" / f"{name}.cnf").exists() and (tmp_path / "proofs" / f"{name}.drat").exists()
    proc = run("aperiodic", "verify", "r2.json", "--proof-dir", "proofs", cwd=tmp_path)
    assert proc.returncode == 0 and f"{len(refuted)} refutation(s) re-checked" in proc.stdout, proc.stdout


@pytest.mark.slow
def test_a_cache_without_its_proofs_is_not_evidence(tmp_path):
    (tmp_path / "d.json").write_text(json.dumps({"order": "NESW", "colors": 3, "tiles": DIAGONAL}))
    args = ["aperiodic", "check", "d.json", "--max-period", "2", "--workers", "1"]
    assert run(*args, "-o", "r.json", cwd=tmp_path).returncode == 0
    shutil.rmtree(tmp_path / "r.json.cache.jsonl.proofs")
    proc = run(*args, "-o", "r2.json", "--cache", "r.json.cache.jsonl", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    doc = json.loads((tmp_path / "r2.json").read_text())
    refuted = [c for c in doc["periods"] if c["status"] == "refuted"]
    assert refuted and not any(c["evidence"].get("cached") for c in refuted)
    assert all("no proof" in c["evidence"]["cache_rejected"] or "missing proof file" in c["evidence"]["cache_rejected"]
               for c in refuted)


def test_sweep_api_without_a_witness_check_uses_no_cached_witness(tmp_path):
    ws = WangTileSet(DIAGONAL, 3)
    names = ["torus 1x1", "torus 3x1 shear 1"]
    cache = tmp_path / "c.jsonl"
    # Both boards decided (the sweep would otherwise stop at the tiled one, the larger, first).
    sweep(ws, names, RunOptions(seed=1, workers=1), cache=cache, stop_at_witness=False)
    again, _ = sweep(ws, names, RunOptions(seed=1, workers=1), cache=cache, stop_at_witness=False)
    assert again[0].evidence.get("cached") and not again[1].evidence.get("cached")
    assert "was not re-verified" in again[1].evidence["cache_rejected"]


@pytest.mark.slow
def test_many_refutations_rechecked_on_worker_processes(tmp_path):
    from tilesolve.engine.certificates import PARALLEL_RECHECK_MIN

    problem = AperiodicProblem(WangTileSet(DIAGONAL, 3), 0, 4, shears=True)
    from tilesolve.families.aperiodic import solve

    s = solve(problem, seed=1, workers=1, options={"proof_dir": tmp_path / "proofs"})
    _write(tmp_path, "r.json", json.loads(solution_text(problem, s)))
    refuted = s.stats["periods_refuted"]
    assert refuted >= PARALLEL_RECHECK_MIN
    proc = run("aperiodic", "verify", "r.json", "--proof-dir", "proofs", "--workers", "2", cwd=tmp_path)
    assert proc.returncode == 0 and f"{refuted} refutation(s) re-checked" in _lines_end_with_one_verdict(proc.stdout)
    drat = sorted((tmp_path / "proofs").glob("*.drat"))[-1]
    drat.write_text("0\n")
    proc = run("aperiodic", "verify", "r.json", "--proof-dir", "proofs", "--workers", "2", cwd=tmp_path)
    assert proc.returncode == 1 and "differs from the recorded" in proc.stdout
    assert not _lines_end_with_one_verdict(proc.stdout).startswith("ok:")


def test_an_unsat_found_by_a_portfolio_worker_still_gets_its_proof_files(tmp_path, monkeypatch):
    """A worker process writes no proof files; the run asked for them decides the unsat again here."""
    from tilesolve import family
    from tilesolve.families import packing
    from tilesolve.engine import portfolio
    from tilesolve.engine.packing import solve_sat
    from tilesolve.model.packing import PackingProblem

    def in_a_worker(route, problem, run, **kw):  # what a worker hands back: digests, no files written here
        import contextvars

        return contextvars.Context().run(solve_sat, problem, run)

    monkeypatch.setattr(portfolio, "escalate", in_a_worker)
    problem = PackingProblem("corner", 2, fixed=((0, 0, 0), (0, 1, 15)))
    with family.writing_proofs(tmp_path / "proofs"):
        s = packing.solve(problem, method="sat", seed=3)
    assert s.status is Status.UNSAT and "decided again here" in " ".join(s.notes)
    assert (tmp_path / "proofs" / f"{s.stats['proof_name']}.drat").exists()
    family.write_solution(tmp_path / "u.json", problem, s)
    proc = run("verify", "u.json", "--proof-dir", "proofs", cwd=tmp_path)
    assert proc.returncode == 0 and proc.stdout.startswith("ok: u.json: unsat re-checked"), proc.stdout
