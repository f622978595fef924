"""The dappled kernels give the same tiling interpreted and compiled (see ``constructive/_jit.py``),
and small problems do not import numba."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from tilesolve.constructive import _dappled_kernels as K
from tilesolve.constructive import _jit
from tilesolve.constructive.dappled import algorithm1, algorithm2, make_dappled, remark34, trivial
from tilesolve.model import DappledProblem


def _both(monkeypatch, run):
    """``run()`` on the plain path and on the compiled path."""
    out = []
    for mode in ("plain", "compiled"):
        monkeypatch.setattr(K.KERNELS, "mode", mode)
        out.append(run())
    return out


def _shapes(rng, n):
    return [(int(rng.integers(1, 30)), int(rng.integers(1, 30))) for _ in range(n)]


def test_algorithm1_plain_equals_compiled(monkeypatch):
    rng = np.random.default_rng(11)
    for shape in _shapes(rng, 60):
        g0 = rng.integers(0, 2, size=shape)
        if rng.random() < 0.5:
            p, q = rng.choice([0, 2, 3, 4], size=2), rng.choice([0, 2, 3, 4], size=2)
        else:  # per-cell limits (§3.1)
            p = rng.choice([0, 2, 3, 5], size=(2,) + shape)
            q = rng.choice([0, 2, 3, 5], size=(2,) + shape)
        for order in ("row", "col"):
            a, b = _both(monkeypatch, lambda: algorithm1(g0, p, q, order=order))
            assert a.dtype == b.dtype and np.array_equal(a, b)


def test_cyclic_routes_plain_equal_compiled(monkeypatch):
    rng = np.random.default_rng(12)
    for rows, cols in _shapes(rng, 60):
        rows, cols = rows + 3, cols + 3
        g0 = rng.integers(0, 2, size=(rows, cols))
        order = ("row", "col")[int(rng.integers(2))]
        p, q = rng.choice([0, 3, 4, 6], size=2), rng.choice([0, 3, 4, 6], size=2)
        a, b = _both(monkeypatch, lambda: algorithm2(g0, p, q, order=order))
        assert np.array_equal(a, b)
        p2, q2 = int(rng.integers(2, 5)), int(rng.integers(2, 5))
        recheck = bool(rng.integers(2))
        a, b = _both(monkeypatch, lambda: remark34(g0, p2, q2, order=order, recheck=recheck))
        assert np.array_equal(a, b)


def test_trivial_plain_equals_compiled_same_seed(monkeypatch):
    rng = np.random.default_rng(13)
    for shape in _shapes(rng, 60):
        n = int(rng.integers(3, 7))
        g0 = rng.integers(0, n, size=shape)
        seed = int(rng.integers(2**31))
        cyclic = bool(rng.integers(2)) and min(shape) >= 2
        if cyclic:
            p, q = rng.choice([0, 2, 3], size=n), rng.choice([0, 2, 3], size=n)
        else:
            p, q = rng.choice([0, 1, 2], size=(n,) + shape), rng.choice([0, 1, 2], size=(n,) + shape)
        a, b = _both(monkeypatch, lambda: trivial(g0, n, p, q, cyclic=cyclic, seed=seed))
        assert np.array_equal(a, b)


def test_make_dappled_same_seed_same_output_on_both_paths(monkeypatch):
    for conds, cyclic, n in ((["H0=2", "V1=2"], False, 2), (["H0=2", "V1=2"], True, 2),
                             (["H0=3", "H1=3", "V0=3", "V1=3"], True, 2), (["H0=1", "V2=2"], False, 3)):
        prob = DappledProblem.from_strings("37x23", conds, cyclic=cyclic, n_tiles=n)
        for seed in range(5):
            a, b = _both(monkeypatch, lambda: make_dappled(prob, seed=seed))
            assert np.array_equal(a, b)


def test_small_problem_does_not_import_numba():
    code = (
        "import sys\n"
        "from tilesolve.constructive import make_dappled\n"
        "from tilesolve.model import DappledProblem\n"
        "g = make_dappled(DappledProblem.from_strings('100x100', ['H0=2', 'V1=2']), seed=1)\n"
        "print(g.shape, 'numba' in sys.modules)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "(100, 100) False"


# --------------------------------------------------------------------------- the mechanism
@_jit.kernel()
def _toy_step(x):
    return x * 3 + 1


@_jit.kernel()
def _toy_sum(a):
    s = 0
    for v in a:
        s += _toy_step(v)
    return s


def test_compiled_namespace_calls_compiled_helpers():
    ks = _jit.Kernels(globals(), threshold=100)
    a = np.arange(10, dtype=np.int64)
    assert ks.pick(10) is sys.modules[__name__] and not ks.loaded
    comp = ks.compiled()
    assert comp._toy_sum(a) == _toy_sum(a) == 145
    # nopython mode typed the kernel (a plain-function helper would be a typing error), and its
    # globals are the compiled copy, where the helper is a dispatcher
    assert comp._toy_sum.signatures
    assert comp._toy_sum.py_func.__globals__["_toy_step"] is comp._toy_step
    assert hasattr(comp._toy_step, "py_func") and comp._toy_step.py_func is not _toy_step
    assert _toy_sum is globals()["_toy_sum"] and not hasattr(_toy_sum, "signatures")


def test_pick_follows_the_ski_rental_rule(monkeypatch):
    ks = _jit.Kernels(globals(), threshold=100)
    monkeypatch.setattr(ks, "_compile", lambda: "compiled")
    assert ks.pick(60) is sys.modules[__name__]
    assert ks.pick(60) == "compiled"  # 120 cells of plain work so far
    assert ks.pick(1) == "compiled"  # loaded: stays compiled
    fresh = _jit.Kernels(globals(), threshold=100)
    monkeypatch.setattr(fresh, "_compile", lambda: "compiled")
    assert fresh.pick(100) == "compiled"
    fresh.mode = "plain"
    assert fresh.pick(10**9) is sys.modules[__name__]
    fresh.mode = "bogus"
    with pytest.raises(ValueError, match="mode"):
        fresh.pick(1)


def test_u32_and_rng_agree_on_both_paths():
    comp = _jit.Kernels(vars(_jit), threshold=0).compiled()
    for x in (-(2**31), -1, 0, 1, 2**31 - 1):
        assert _jit.u32(np.int32(x)) == comp.u32(np.int32(x)) == x % 2**32
    s1, s2 = _jit.seed_state(12345), comp.seed_state(12345)
    assert [int(_jit.rand32(s1)) for _ in range(50)] == [int(comp.rand32(s2)) for _ in range(50)]


def test_brick_linear_plain_equals_compiled(monkeypatch):
    from tilesolve.constructive import _brick_kernels as BK
    from tilesolve.constructive.brick import solve_linear
    from tilesolve.errors import MethodNotApplicable
    from tilesolve.model.board import Board, BoardProblem, WangTileSet, parse_board_spec, random_boundary

    rng = np.random.default_rng(14)
    boards = [Board.random_holes(int(rng.integers(1, 20)), int(rng.integers(1, 20)), float(rng.random() * 0.5),
                                 seed=int(rng.integers(2**31))) for _ in range(30)]
    boards += [parse_board_spec(f"{kind}:{int(rng.integers(2, 12))}x{int(rng.integers(2, 12))}")
               for kind in ("rect", "torus", "cylinder", "mobius", "klein") for _ in range(3)]
    for board in boards:
        k = int(rng.choice([3, 4]))
        beta = random_boundary(board, k, seed=int(rng.integers(2**31)))
        beta[rng.random(beta.size) < 0.3] = -1
        prob = BoardProblem(board, WangTileSet.brick(k), beta)
        seed = int(rng.integers(2**31))
        out = []
        for mode in ("plain", "compiled"):
            monkeypatch.setattr(BK.KERNELS, "mode", mode)
            try:
                sol = solve_linear(prob, seed=seed)
                out.append((sol.status, None if sol.tiling is None else sol.tiling.tolist(), sol.reason))
            except MethodNotApplicable as e:
                out.append(str(e))
        assert out[0] == out[1]
