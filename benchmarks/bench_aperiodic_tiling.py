"""The whole ``tilesolve aperiodic tiling`` command beside its kernel (issue 20, §1).

For each built-in set asked (default: jeandel-rao, tiled by the Markov partition, and kari-14,
by balanced rows) and each square window of side S (default 100 and 1000; ``--big`` adds
10,000), measured in the same run, each a child process (CPU time user + sys and peak RSS from
``os.wait4``; the run of least CPU of ``--repeat`` after one warm-up run of each):

- the kernel alone: the CPU time of one call of ``markov_window`` / ``balanced_window`` in a
  process that has already made one (best of 3 calls);
- the kernel in a process: import and one call (``python -c``);
- the command ``tilesolve aperiodic tiling --builtin B --region 0,0,SxS --seed 1 -o t.json
  --png t.png``: the window tiled, verified by the grid verifier, written as JSON and drawn as
  PNG (default scale: about 1024 px on the longer side, at least 4 px a tile). At S = 10,000 the
  command writes the PNG only (the JSON would be 133 MB; ``--big-json`` writes it too).

The ratios are the command's CPU over the kernel's alone and over the kernel in a process.

Usage::

    python benchmarks/bench_aperiodic_tiling.py                  # S = 100, 1000; jeandel-rao, kari-14
    python benchmarks/bench_aperiodic_tiling.py --big            # and S = 10,000 (PNG only)
    python benchmarks/bench_aperiodic_tiling.py --builtin labbe-u19 --sizes 300

Goal (issue 20): a window of 10^4 x 10^4 tiles costs <= 1 s in process (the kernel).
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile

from _measure import best, best_child  # noqa: E402 - benchmarks/ is on sys.path

SEED = 1
#: Each built-in set's kernel: (module, function).
KERNELS = {"jeandel-rao": ("markov", "markov_window"), "labbe-u19": ("markov", "markov_window"),
           "kari-14": ("balanced", "balanced_window"), "kari-culik-13": ("balanced", "balanced_window")}


def _call(name: str, side: int) -> str:
    module, function = KERNELS[name]
    return (f"from tilesolve.constructive.{module} import {function} as k; from tilesolve.model.window import Window; "
            f"k({name!r}, Window(0, 0, {side}, {side}), {SEED})")


def kernel_child(name: str, side: int) -> None:
    """In a child: the CPU seconds of the best of 3 calls of the kernel (after one), as JSON."""
    from importlib import import_module

    from tilesolve.model.window import Window

    module, function = KERNELS[name]
    kernel = getattr(import_module(f"tilesolve.constructive.{module}"), function)
    window = Window(0, 0, side, side)
    kernel(name, window, SEED)
    _, cpu, _ = best(lambda: kernel(name, window, SEED), 3)
    print(json.dumps({"kernel_cpu": cpu}))


def rows(name: str, side: int, repeat: int, json_too: bool) -> None:
    """The three measures of one set and side (module docstring)."""
    exe = os.path.join(os.path.dirname(sys.executable), "tilesolve")
    anchor = [sys.executable, "-c", _call(name, side)]
    kernel = [sys.executable, os.path.abspath(__file__), "--kernel-child", name, str(side)]
    outputs = ["-o", "t.json", "--png", "t.png"] if json_too else ["--png", "t.png"]
    command = [exe, "aperiodic", "tiling", "--builtin", name, "--region", f"0,0,{side}x{side}", "--seed", str(SEED),
               *outputs]
    tiles = side * side
    with tempfile.TemporaryDirectory() as d:
        for argv in (anchor, kernel, command):
            best_child(argv, 1, cwd=d)  # warm-up: bytecode and numba caches
        base = best_child(anchor, repeat, cwd=d)
        k_cpu = min(json.loads(best_child(kernel, 1, cwd=d).stdout.strip().splitlines()[-1])["kernel_cpu"]
                    for _ in range(repeat))
        run = best_child(command, repeat, cwd=d)
        sizes = {f: os.path.getsize(os.path.join(d, f)) / 2**20 for f in ("t.json", "t.png")
                 if os.path.exists(os.path.join(d, f))}
    files = " + ".join(f"{mib:.1f}" for mib in sizes.values())
    what = " ".join(outputs)
    print(f"{name:<14}{side:>7}  {'kernel, the call alone':<34}{'':>8}{k_cpu:>8.3f}{'':>9}"
          f"{tiles / max(k_cpu, 1e-9) / 1e6:>13.3g}{'':>14}{1:>9.2f}{'':>10}")
    for label, r, mib in (("kernel in a process", base, ""), (f"command {what}", run, files)):
        print(f"{name:<14}{side:>7}  {label:<34}{r.wall:>8.2f}{r.cpu:>8.2f}{r.rss_mib:>9.0f}"
              f"{tiles / r.cpu / 1e6:>13.3g}{mib:>14}{r.cpu / max(k_cpu, 1e-9):>9.1f}{r.cpu / base.cpu:>10.2f}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--builtin", action="append", choices=sorted(KERNELS), help="a built-in set (repeatable)")
    ap.add_argument("--sizes", type=int, nargs="+", default=[100, 1000], metavar="S", help="window sides")
    ap.add_argument("--big", action="store_true", help="also S = 10,000 (PNG only)")
    ap.add_argument("--big-json", action="store_true", help="with --big, write the JSON at S = 10,000 too")
    ap.add_argument("--repeat", type=int, default=3, help="runs of each child (least CPU kept)")
    ap.add_argument("--kernel-child", nargs=2, metavar=("NAME", "SIDE"), help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.kernel_child:
        kernel_child(args.kernel_child[0], int(args.kernel_child[1]))
        return
    names = args.builtin or ["jeandel-rao", "kari-14"]
    sides = list(args.sizes) + ([10_000] if args.big else [])
    print(f"tilesolve aperiodic tiling beside its kernel, seed {SEED}; best CPU of {args.repeat} (child processes)")
    print(f"{'set':<14}{'side':>7}  {'run':<34}{'wall s':>8}{'cpu s':>8}{'RSS MiB':>9}{'Mtiles/cpu s':>13}"
          f"{'files MiB':>14}{'/ kernel':>9}{'/ process':>10}")
    for name in names:
        for side in sides:
            rows(name, side, args.repeat if side < 10_000 else 1, side < 10_000 or args.big_json)


if __name__ == "__main__":
    main()
