"""Speed of the Markov-partition codings (Jeandel-Rao, U19) over square windows.

Times :func:`tilesolve.constructive.markov.markov_window` in process (compiled kernels loaded
first, threads on every core this process may use) on squares of side 10^2, 10^3, 10^4, and in
the same run two baselines:

* ``np.zeros``: allocating and filling a uint8 array of the same size, the floor any window
  costs;
* ``numpy pip``: a plain point-in-polygon coding with numpy, vectorised over the points and
  looping over the polygons (the points reduced modulo the lattice in float64, then one
  half-plane test per polygon edge), on sides 10^2 and 10^3 (at 10^4 its temporaries would
  need tens of GiB). Its tiles are compared with the window's.

At side 10^4 the coding runs on one thread and on every core. Prints wall and CPU seconds
(best of ``--repeat``), tiles per second, the peak traced memory
of one call (tracemalloc: the output, 1 byte a tile, and the scratch), and the ratios
baseline / coding of the wall times.

Usage::

    python benchmarks/bench_markov.py            # sides 100, 1000, 10000
    python benchmarks/bench_markov.py --quick    # sides 100, 1000

Goal (issue 20): a 10^4 x 10^4 window in <= 1 s in process.
"""

from __future__ import annotations

import argparse

import numpy as np

from _measure import best, peak_mib  # noqa: E402 - benchmarks/ is on sys.path

SEED = 1


def numpy_pip(name: str, x0: int, y0: int, side: int) -> np.ndarray:
    """The baseline: float64 point-in-polygon over every cell, row 0 at the top."""
    from tilesolve.constructive.markov import partition, start_point

    part = partition(name)
    px, py = (float(v) for v in start_point(name, SEED))
    lx, ly, sx, hx, hy = (float(getattr(part, f)) for f in ("lx", "ly", "sx", "hx", "hy"))
    ys = np.arange(y0 + side - 1, y0 - 1, -1, dtype=np.float64)[:, None]
    xs = np.arange(x0, x0 + side, dtype=np.float64)[None, :]
    y = py + ys * hy + 0 * xs
    x = px + xs * hx + 0 * ys
    ell = np.floor(y / ly)
    y = y - ell * ly
    x = x - ell * sx
    x = x - np.floor(x / lx) * lx
    out = np.full(x.shape, 255, np.uint8)
    for tile, vs, _ in part.atoms:
        inside = np.ones(x.shape, bool)
        pts = [(float(a), float(b)) for a, b in vs]
        for (ax, ay), (bx, by) in zip(pts, pts[1:] + pts[:1]):
            inside &= (bx - ax) * (y - ay) - (by - ay) * (x - ax) >= 0
        out[inside] = tile
    return out


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    from tilesolve.constructive._markov_kernels import KERNELS
    from tilesolve.constructive import markov
    from tilesolve.constructive.markov import NAMES, markov_window
    from tilesolve.model.window import Window

    KERNELS.compiled()  # numba's compile or cache load, outside the timings
    for name in NAMES:
        markov_window(name, Window(0, 0, 64, 64), SEED)
    sides = [100, 1000] if args.quick else [100, 1000, 10000]
    cores = markov._cores()
    print(f"markov_window, seed {SEED}, {cores} core(s); best of {args.repeat}")
    print(f"{'partition':<12}{'side':>6}{'tiles':>13}{'threads':>8}{'wall s':>8}{'cpu s':>7}{'Mtiles/s':>9}"
          f"{'peak MiB':>9}{'zeros s':>8}{'ratio':>6}{'pip s':>7}{'ratio':>6}{'same':>5}")
    for name in NAMES:
        for side in sides:
            x0, y0 = -side // 2, 12345
            window = Window(x0, y0, side, side)
            tz, _, _ = best(lambda: np.zeros((side, side), np.uint8) + 1, args.repeat)
            for threads in sorted({1, cores}) if side >= 10000 else [cores]:
                markov._cores = lambda: threads
                t, cpu, grid = best(lambda: markov_window(name, window, SEED), args.repeat)
                peak = peak_mib(lambda: markov_window(name, window, SEED))
                pip = ""
                if side <= 1000:
                    tp, _, base = best(lambda: numpy_pip(name, x0, y0, side), 1)
                    pip = f"{tp:>7.3f}{tp / t:>6.0f}{'yes' if np.array_equal(base, grid) else 'NO':>5}"
                print(f"{name:<12}{side:>6}{side * side:>13,}{threads:>8}{t:>8.3f}{cpu:>7.3f}"
                      f"{side * side / t / 1e6:>9.0f}{peak:>9.1f}{tz:>8.3f}{tz / t:>6.2f}{pip}")
    print("ratios: baseline wall / coding wall (zeros: the floor, below 1; pip: the plain numpy coding)")


if __name__ == "__main__":
    main()
