"""Memory and speed of wall pictures written as PNG (004 §3.2; issue 10: a 20,000 x 20,000 wall
written to PNG with peak memory <= 1 GiB).

Each case runs in a fresh Python process, so that its peak resident size (``ru_maxrss``) is
its own, and writes a real file in a temporary folder (its size is printed):

``streamed``
    :func:`tilesolve.families.wall_render.write_wall_png`: a band of cell rows at a time (wall_window
    with a one-cell halo, the maps, the board verifier on the band, pypng's row writer), as
    ``tilesolve wall --png`` runs it;
``stream-nv``
    the same without the board verifier (``verify=False``), to show what the verifier costs.
``whole``
    the baseline, same run: the whole window at once (``wall_window`` of the region with its
    halo, ``wall_maps`` of all of it, pixels, then pypng from the full pixel array), no
    verifier; only at sizes whose arrays fit in memory.

The table shows cells, pixels, wall and CPU seconds, peak RSS, throughput (million pixels a
CPU second) and, for streamed cases, the ratio of memory and CPU time to the whole-array write
of the same size.

``--verify-cost`` measures what the board verifier costs the whole command (issue 19):
``tilesolve wall --region 0,0,SxS --max-line 2 --png w.png`` with ``--no-verify`` and with the
default ``--verify``, each a child process (CPU time user + sys and peak RSS from ``os.wait4``,
the run of least CPU of ``--repeat`` after one warm-up run of each), and prints the ratio
verified / unverified and the verification's share, (verified - unverified) / unverified.

Usage::

    python benchmarks/bench_wall_png.py                  # 2000^2 and 5000^2 all ways, 20000^2 streamed
    python benchmarks/bench_wall_png.py --quick          # 1000^2 and 2000^2 both ways
    python benchmarks/bench_wall_png.py --verify-cost    # wall --png 6000^2, verified beside --no-verify
    python benchmarks/bench_wall_png.py --verify-cost --full   # the same at 20000^2 (minutes)

Goal (issue 19): verification <= 1x generation, i.e. the verified run <= 2x the unverified one.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time

from _measure import best_child  # noqa: E402 - benchmarks/ is on sys.path

COLORS, MAX_LINE, SEED, KIND = 3, 2, 7, "id"


def run_case(mode: str, side: int, ppc: int, path: str) -> dict:
    """One case, in this process (the child): seconds and peak RSS."""
    import numpy as np

    from tilesolve.constructive.walls import wall_window
    from tilesolve.families.wall_render import wall_map_pixels, write_wall_png

    wall_window(0, 0, 4, 4, colors=COLORS, max_line=MAX_LINE, seed=SEED)  # numba compile, not timed
    t, cpu = time.perf_counter(), time.process_time()
    if mode in ("streamed", "stream-nv"):
        write_wall_png(path, (0, 0, side, side), colors=COLORS, max_line=MAX_LINE, seed=SEED, kind=KIND, ppc=ppc,
                       verify=mode == "streamed")
    else:
        import png

        from tilesolve.io.wall_png import brick_palette

        legs = wall_window(-1, -1, side + 2, side + 2, colors=COLORS, max_line=MAX_LINE, seed=SEED)
        pixels = wall_map_pixels(legs, KIND, colors=COLORS, ppc=ppc, origin=(0, 0))
        del legs
        writer = png.Writer(pixels.shape[1], pixels.shape[0], palette=brick_palette(), bitdepth=8, compression=6)
        with open(path, "wb") as f:
            writer.write_packed(f, (row.tobytes() for row in np.asarray(pixels)))
    secs, cpu = time.perf_counter() - t, time.process_time() - cpu
    return {"secs": secs, "cpu": cpu, "rss": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024,
            "bytes": os.path.getsize(path)}


def child(mode: str, side: int, ppc: int) -> dict:
    with tempfile.TemporaryDirectory() as d:
        out = subprocess.run([sys.executable, __file__, "--child", mode, str(side), str(ppc), os.path.join(d, "w.png")],
                             check=True, capture_output=True, text=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def verify_cost(side: int, repeat: int) -> None:
    """``tilesolve wall --png`` verified beside ``--no-verify`` (module docstring)."""
    exe = os.path.join(os.path.dirname(sys.executable), "tilesolve")
    base = [exe, "wall", "--region", f"0,0,{side}x{side}", "--max-line", str(MAX_LINE), "--seed", str(SEED),
            "--png", "w.png"]
    cells = side * side
    print(f"wall --png {side}x{side} = {cells:,} cells, n = {MAX_LINE}, default px per cell; best CPU of {repeat}")
    print(f"{'run':<14}{'wall s':>8}{'cpu s':>8}{'sys s':>8}{'RSS MiB':>9}{'Mcells/cpu s':>13}{'file MiB':>9}"
          f"{'cpu ratio':>10}{'verify share':>13}")
    runs = {}
    with tempfile.TemporaryDirectory() as d:
        for flag in ("--no-verify", "--verify"):  # warm-up: bytecode and numba caches
            best_child(base[:3] + ["0,0,64x64"] + base[4:] + [flag], 1, cwd=d)
        for flag in ("--no-verify", "--verify"):
            runs[flag] = best_child(base + [flag], repeat, cwd=d), os.path.getsize(os.path.join(d, "w.png")) / 2**20
    plain = runs["--no-verify"][0]
    for flag, (r, mib) in runs.items():
        share = (r.cpu - plain.cpu) / plain.cpu
        print(f"{flag:<14}{r.wall:>8.1f}{r.cpu:>8.2f}{r.sys:>8.2f}{r.rss_mib:>9.0f}{cells / r.cpu / 1e6:>13.1f}"
              f"{mib:>9.1f}{r.cpu / plain.cpu:>10.2f}{share:>13.2f}")
    print("cpu ratio: over --no-verify; verify share: (verified - unverified) / unverified CPU; "
          "goal (issue 19): share <= 1 (ratio <= 2)")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--child", nargs=4, metavar=("MODE", "SIDE", "PPC", "PATH"))
    ap.add_argument("--verify-cost", action="store_true", help="wall --png verified beside --no-verify")
    ap.add_argument("--full", action="store_true", help="--verify-cost at 20000^2 rather than 6000^2")
    ap.add_argument("--repeat", type=int, default=2, help="--verify-cost: runs of each, the least CPU kept")
    args = ap.parse_args()
    if args.verify_cost:
        verify_cost(20000 if args.full else 6000, args.repeat)
        return
    if args.child:
        mode, side, ppc, path = args.child
        print(json.dumps(run_case(mode, int(side), int(ppc), path)))
        return
    sides = [1000, 2000] if args.quick else [2000, 5000]
    cases = [(mode, side) for side in sides for mode in ("whole", "stream-nv", "streamed")]
    if not args.quick:
        cases += [("stream-nv", 20000), ("streamed", 20000)]
    ppc = 1
    print(f"{KIND} map, {COLORS} colours, n = {MAX_LINE}, {ppc} px per cell; each case in a fresh process, "
          "writing a real file")
    print(f"{'mode':<10}{'cells':>14}{'pixels':>14}{'time s':>9}{'cpu s':>8}{'peak RSS MiB':>14}{'Mpx/s cpu':>10}"
          f"{'file MiB':>10}{'RSS ratio':>11}{'cpu ratio':>11}")
    whole: dict[int, dict] = {}
    for mode, side in cases:
        r = child(mode, side, ppc)
        px = side * side * ppc * ppc
        ratio = ""
        if mode != "whole" and side in whole:
            b = whole[side]
            ratio = f"{r['rss'] / b['rss']:>11.2f}{r['cpu'] / b['cpu']:>11.2f}"
        if mode == "whole":
            whole[side] = r
        print(f"{mode:<10}{side * side:>14,}{px:>14,}{r['secs']:>9.1f}{r['cpu']:>8.1f}{r['rss'] / 2**20:>14.0f}"
              f"{px / r['cpu'] / 1e6:>10.2f}{r['bytes'] / 2**20:>10.1f}{ratio}", flush=True)
    print("ratios: streamed / whole at the same size (RSS, CPU time; on a shared machine CPU time is the "
          "better measure of one core's work); 'streamed' includes the board verifier, "
          "'stream-nv' does not; 'whole' cannot hold 20000^2 (about 2 GiB of legs and pixels)")


if __name__ == "__main__":
    main()
