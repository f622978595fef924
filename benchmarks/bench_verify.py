"""Speed of the independent verifiers, against the previous algorithms in the same run.

Dappled: the tilings of Algorithm 1 (dappled paper §2) for ``L = {H_0^2, V_1^2}`` on
square grids, checked by :func:`tilesolve.verify.dappled_violations` (sliding-window ANDs
in row blocks) and by the previous checker, copied below as the baseline (run lengths
built one column at a time in int64). Then the dappled API
(:func:`tilesolve.families.dappled.solve`, which verifies its answer) against its kernel
(:func:`tilesolve.constructive.dappled.make_dappled`).

Boards (issue 19, "board verifier kernel"): :func:`tilesolve.verify.board_violations` on
valid tilings of a rectangle (linear algorithm, brick paper §4, random boundary), a rectangle
with holes (the same), a procedural brick wall with lines of at most 2 bricks (004 §3-4) and
an NPD wall on a torus (004 App. A), against the join-array checks it made before
(``tilesolve.verify.board._violations``, still the code that names violations), paired in
the same run: its two passes, each timed alone on the same tiling, ``numpy`` (whole-array
operations on the grid: what a file or a solve is checked with) and ``compiled`` (the numba
kernel, warm: what a process uses once it has checked 50M cells, e.g. the bands of a large
wall).

Times are the best of ``--repeat`` runs (one core); peak memory is tracemalloc's peak of
one further run. Goals: >= 100 M cells/s for the dappled verifier at 4096x4096, and the
API within 2x of the kernel there; >= 100 M cells/s for the board verifier on rect and mask
boards at 1000x1000 (issue 19).

Usage::

    python benchmarks/bench_verify.py           # dappled 1024^2, 2048^2, 4096^2; boards 1000^2
    python benchmarks/bench_verify.py --quick   # dappled 1024^2; boards 316^2
    python benchmarks/bench_verify.py --boards  # boards 1000^2 only
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from _measure import best as best_cpu, peak_mib  # noqa: E402 - benchmarks/ is on sys.path


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


def board_rows(side: int, repeat: int) -> None:
    """The board verifier on valid tilings of ``side x side`` boards, against its previous checks."""
    from tilesolve.constructive.brick import solve_linear
    from tilesolve.families import walls
    from tilesolve.family import solve
    from tilesolve.model.board import Board, BoardProblem, WangTileSet, random_boundary
    from tilesolve.verify import _board_kernel
    from tilesolve.verify import board as vb

    kernel = _board_kernel.compiled(_board_kernel.COMPILED_FROM)  # loaded (and compiled) before timing
    # wall-clock seconds: the process's CPU time would count the solvers' numba worker threads,
    # which spin a while after a parallel region (the walls above)
    print(f"\nboard verifier, seconds (best of {repeat}; old: 1 run); Mc/s = million cells a second")
    print(f"{'board':<30} {'cells':>9} {'old s':>7} {'numpy s':>8} {'Mc/s':>5} {'compiled s':>10} {'Mc/s':>5} "
          f"{'old MiB':>8} {'numpy MiB':>9} {'old/numpy':>9} {'old/compiled':>12}")
    cases = []
    for name, b in (("rect", Board.rect(side, side)), ("mask (holes)", Board.with_holes(side, side, side * side // 400,
                                                                                       12, seed=1))):
        p = BoardProblem(b, WangTileSet.brick(3), random_boundary(b, 3, seed=1))
        cases.append((f"{name}, random boundary", p, solve_linear(p, seed=1).tiling))
    q = walls.wall_problem(side, side, 2)
    cases.append(("wall, lines <= 2", q, solve(q, "procedural", seed=7).tiling))
    t_side = side // 2 // 12 * 12
    q = walls.npd_problem(t_side, t_side, 4)
    cases.append((f"npd torus {t_side}^2, lines <= 4", q, solve(q, "npd", seed=2).tiling))
    for what, p, t in cases:
        n = p.board.n_cells
        t_old, _, v_old = best_cpu(lambda: vb._violations(p, np.asarray(t, dtype=np.int64)), 1)
        t_comp, _, ok_comp = best_cpu(lambda: vb._compiled_clean(p, t, kernel), repeat)
        t_np, _, ok = best_cpu(lambda: vb._in_range(t, p.n_colors) and vb._grid_clean(p, t), repeat)
        assert v_old == [] and ok and ok_comp in (True, None) and vb.board_violations(p, t) == []
        m_old = peak_mib(lambda: vb._violations(p, np.asarray(t, dtype=np.int64)))
        m_np = peak_mib(lambda: vb._in_range(t, p.n_colors) and vb._grid_clean(p, t))
        comp = (f"{t_comp:>10.4f} {n / t_comp / 1e6:>5.0f}" if ok_comp else f"{'-':>10} {'-':>5}")
        ratio = f"{t_old / t_comp:>11.0f}x" if ok_comp else f"{'-':>12}"
        print(f"{what:<30} {n:>9,} {t_old:>7.3f} {t_np:>8.4f} {n / t_np / 1e6:>5.0f} {comp} {m_old:>8.1f} {m_np:>9.1f} "
              f"{t_old / t_np:>8.0f}x {ratio}")
    print("compiled: the kernel of tilesolve.verify._board_kernel (no identified sides; used once a process has "
          f"checked {_board_kernel.COMPILED_FROM:,} cells); numpy: the whole-array pass (every grid board)")
    print("goal: >= 100 M cells/s on rect and mask boards")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--boards", action="store_true", help="the board rows only")
    args = ap.parse_args()
    if args.boards:
        board_rows(316 if args.quick else 1000, args.repeat)
        return
    from tilesolve.constructive.dappled import make_dappled
    from tilesolve.model.dappled import DappledProblem
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
    board_rows(bs, args.repeat)
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
