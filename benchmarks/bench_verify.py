"""Speed of the independent verifiers, against the previous algorithms in the same run.

Dappled: the tilings of Algorithm 1 (dappled paper §2) for ``L = {H_0^2, V_1^2}`` on
square grids, checked by :func:`tilesolve.verify.dappled_violations` (sliding-window ANDs
in row blocks) and by the previous checker, copied below as the baseline (run lengths
built one column at a time in int64). Boards: a linear-algorithm tiling (brick paper §4)
of a board with holes, checked by :func:`tilesolve.verify.board_violations` and by the
previous join check (2-D fancy indexing), also copied below. Then the dappled API
(:func:`tilesolve.families.dappled.solve`, which verifies its answer) against its kernel
(:func:`tilesolve.constructive.dappled.make_dappled`).

Times are the best of ``--repeat`` runs (one core); peak memory is tracemalloc's peak of
one further run. Goals (issue "Cost around the solver"): >= 100 M cells/s for the dappled
verifier at 4096x4096, and the API within 2x of the kernel there.

Usage::

    python benchmarks/bench_verify.py           # dappled 1024^2, 2048^2, 4096^2; boards 1000^2
    python benchmarks/bench_verify.py --quick   # dappled 1024^2; boards 316^2
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from _measure import peak_mib  # noqa: E402 - benchmarks/ is on sys.path


# ----------------------------------------------------------------------------- baselines
def old_run_lengths(member: np.ndarray, axis: str, cyclic: bool) -> np.ndarray:
    """The previous ``tilesolve.verify.dappled.run_lengths`` (a Python loop over columns)."""
    m = member if axis == "H" else member.T
    rows, cols = m.shape
    width = 2 * cols if cyclic else cols
    src = np.concatenate([m, m], axis=1) if cyclic else m
    run = np.zeros((rows, width), dtype=np.int64)
    prev = np.zeros(rows, dtype=np.int64)
    for c in range(width):
        prev = np.where(src[:, c], prev + 1, 0)
        run[:, c] = prev
    out = run[:, cols:] if cyclic else run
    if cyclic:
        full = m.all(axis=1)
        out = np.where(full[:, None], np.iinfo(np.int64).max, out)
    return out if axis == "H" else out.T


def old_dappled_bad_cells(tiling: np.ndarray, problem) -> int:
    """The previous condition check: run lengths, then a comparison with the limit array."""
    t = np.asarray(tiling)
    bad = int(((t < 0) | (t >= problem.n_tiles)).sum())
    rows, cols = t.shape
    for cond in problem.conditions:
        run = old_run_lengths(np.isin(t, cond.tiles), cond.axis, problem.cyclic)
        limit = cond.limit_array(rows, cols).astype(np.int64)
        bad += len(np.argwhere((limit > 0) & (run > limit)))
    return bad


def old_board_join_mismatches(tiling: np.ndarray, board) -> int:
    """The previous join check of ``board_violations`` (2-D fancy indexing)."""
    t = np.asarray(tiling).astype(np.int64)
    nc, nl = board.nbr_cell, board.nbr_leg
    a_idx, legs = np.nonzero(nc >= 0)
    b_idx, b_legs = nc[a_idx, legs], nl[a_idx, legs]
    first = (a_idx * 4 + legs) <= (b_idx * 4 + b_legs)
    return int((first & (t[a_idx, legs] != t[b_idx, b_legs])).sum())


# ----------------------------------------------------------------------------- measuring
def best(fn, repeat: int) -> tuple[float, object]:
    out, t_best = None, np.inf
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        t_best = min(t_best, time.perf_counter() - t)
    return t_best, out


def row(what, size, cells, t_old, t_new, m_old, m_new, note=""):
    print(f"{what:<18} {size:>10} {t_old:>9.3f} {t_new:>9.3f} {cells / t_new / 1e6:>10.0f} "
          f"{m_old:>9.1f} {m_new:>9.1f} {t_old / t_new:>7.1f}x  {note}")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    from tilesolve.constructive.brick import solve_linear
    from tilesolve.constructive.dappled import make_dappled
    from tilesolve.model.board import Board, BoardProblem, WangTileSet, random_boundary
    from tilesolve.model.dappled import DappledProblem
    from tilesolve.verify.board import board_violations
    from tilesolve.verify.dappled import dappled_violations

    print(f"{'verifier':<18} {'size':>10} {'old s':>9} {'new s':>9} {'new Mc/s':>10} "
          f"{'old MiB':>9} {'new MiB':>9} {'speedup':>8}")
    sizes = [1024] if args.quick else [1024, 2048, 4096]
    kernels = {}
    for s in sizes:
        p = DappledProblem.from_strings(f"{s}x{s}", ["H0=2", "V1=2"])
        t_kernel, tiling = best(lambda: make_dappled(p, seed=1), args.repeat)
        kernels[s] = (p, t_kernel)
        t_new, v = best(lambda: dappled_violations(p, tiling), args.repeat)
        t_old, n_old = best(lambda: old_dappled_bad_cells(tiling, p), 1)
        assert v == [] and n_old == 0
        row("dappled H0^2,V1^2", f"{s}x{s}", s * s, t_old, t_new,
            peak_mib(lambda: old_dappled_bad_cells(tiling, p)), peak_mib(lambda: dappled_violations(p, tiling)),
            f"kernel {t_kernel:.3f} s")
    bs = 316 if args.quick else 1000
    warm = Board.rect(4, 4)
    solve_linear(BoardProblem(warm, WangTileSet.brick(3)), seed=0)  # numba compile or cache load
    b = Board.with_holes(bs, bs, bs * bs // 400, 12, seed=1)
    bp = BoardProblem(b, WangTileSet.brick(3), random_boundary(b, 3, seed=1))
    t_solve, sol = best(lambda: solve_linear(bp, seed=1), 1)
    t_new, v = best(lambda: board_violations(bp, sol.tiling), args.repeat)
    t_old, n_old = best(lambda: old_board_join_mismatches(sol.tiling, b), args.repeat)
    assert v == [] and n_old == 0
    row("board joins+all", f"{bs}x{bs}", b.n_cells, t_old, t_new,
        peak_mib(lambda: old_board_join_mismatches(sol.tiling, b)), peak_mib(lambda: board_violations(bp, sol.tiling)),
        f"old = joins only; linear solve {t_solve:.3f} s")
    try:
        from tilesolve.families import dappled as api
    except ImportError as exc:  # the facade is being rewired
        print(f"API row skipped: {exc}")
        return
    s = max(kernels) if args.quick else 4096
    p, t_kernel = kernels[s]
    t_api, sol = best(lambda: api.solve(p, seed=1), args.repeat)
    print(f"\ndappled API {s}x{s}: solve {t_api:.3f} s, kernel {t_kernel:.3f} s, "
          f"api / kernel = {t_api / t_kernel:.2f} (goal <= 2), method {sol.method}")


if __name__ == "__main__":
    main()
