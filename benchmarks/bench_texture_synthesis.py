"""The corner-tile texture of a wall (``render texture``, class notes §5.3): cost and look, against
the synthesis of an earlier commit, both measured in this run.

Each row is the whole command, a fresh process::

    tilesolve render texture --example bricks.png --colors 3 --tile T --size 800x600 -o t.png
    tilesolve render texture --example bricks.png --aperiodic jeandel-rao --seed 1 --tile T --size 800x600 -o t.png

with ``bricks.png`` from ``tilesolve render wall --size 256x256 --seed 5`` (the help's example),
run once with the package of ``--baseline`` (``git archive`` of that commit's ``tilesolve/``) and
once with the working tree's. Beside the cost, what the picture looks like against the wall, in
two numbers of its mortar (the light texels): ``down/across``, the mean length of the vertical
mortar runs over that of the horizontal ones, relative to the wall's (1: as in the wall; tall
stripes give far more than 1), ``mortar``, the texture's share of mortar texels over the
wall's, and ``between``, the share of texels between brick and mortar (the wall has none; blends
have many, and so has a texture averaged down from a larger synthesis, at the mortar's edges).

Usage::

    python benchmarks/bench_texture_synthesis.py                     # tiles of 32 and 64 texels, both kinds
    python benchmarks/bench_texture_synthesis.py --baseline 1e1a657 --tiles 32 --kinds corner
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

from _measure import child  # noqa: E402 - benchmarks/ is on sys.path

REPO = Path(__file__).resolve().parent.parent
#: The synthesis before the corner patches were fitted at the tiles' edges only (issue 22).
BASELINE = "abef8a8"
#: Runs the console script's entry point from the package ``PYTHONPATH`` puts first (an editable
#: install's finder, which would take the working tree's, set aside; run outside the repository,
#: whose folder ``-c`` would put first).
ENTRY = ("import sys; sys.meta_path[:] = [f for f in sys.meta_path "
         "if not getattr(f, '__module__', '').startswith('__editable__')]; "
         "from tilesolve.cli.main import main; sys.argv[0] = 'tilesolve'; main()")


#: The textures: corner tiles, and the Wang tiles of an aperiodic set.
KINDS = {"corner": ["--colors", "3"], "jeandel-rao": ["--aperiodic", "jeandel-rao", "--seed", "1"]}


def mortar_numbers(wall: np.ndarray, texture: np.ndarray) -> tuple[float, float, float]:
    """``(down/across, mortar, between)`` of ``texture`` against ``wall`` (see the module docstring)."""
    def luma(img):
        return img[..., :3].astype(np.float64) @ np.array([0.299, 0.587, 0.114])

    def light(img):
        return luma(img) > (luma(img).mean() + luma(img).max()) / 2

    def weighted_run(mask):  # runs down the columns, each texel weighting its own run
        flags = np.pad(mask, ((1, 1), (0, 0))).T.astype(np.int8).ravel()
        starts, ends = np.flatnonzero(np.diff(flags) == 1), np.flatnonzero(np.diff(flags) == -1)
        runs = (ends - starts).astype(np.float64)
        return (runs**2).sum() / runs.sum()

    w, t = light(wall), light(texture)
    shape = (weighted_run(t) / weighted_run(w)) / (weighted_run(t.T) / weighted_run(w.T))
    lw, top = luma(wall), luma(wall).max() - luma(wall).mean()
    lt = luma(texture)
    between = (lt > lw.mean() + top / 4) & (lt < lw.mean() + 3 * top / 4)
    return shape, t.mean() / w.mean(), between.mean()


def main() -> None:
    from PIL import Image

    ap = argparse.ArgumentParser()
    ap.add_argument("--size", default="800x600", help="picture size WxH (default 800x600)")
    ap.add_argument("--tiles", default="32,64", help="comma-separated tile sizes (default 32,64)")
    ap.add_argument("--kinds", default=",".join(KINDS), help=f"comma-separated textures (default {','.join(KINDS)})")
    ap.add_argument("--baseline", default=BASELINE, help=f"commit of the baseline package (default {BASELINE})")
    ap.add_argument("--repeat", type=int, default=1, help="runs per row (the fastest is kept)")
    args = ap.parse_args()
    w, h = (int(v) for v in args.size.lower().split("x"))
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        base = folder / "baseline"
        base.mkdir()
        archive = subprocess.run(["git", "-C", str(REPO), "archive", args.baseline, "tilesolve"],
                                 check=True, capture_output=True).stdout
        subprocess.run(["tar", "-x", "-C", str(base)], input=archive, check=True)
        packages = {f"baseline {args.baseline}": base, "this tree": REPO}
        run = [sys.executable, "-c", ENTRY]
        made = child(run + ["render", "wall", "--size", "256x256", "--seed", "5", "-o", str(folder / "bricks.png")],
                     cwd=folder, env=dict(os.environ, PYTHONPATH=str(REPO)))
        if made.returncode:
            raise SystemExit(f"render wall exited {made.returncode}: {made.stderr}")
        wall = np.asarray(Image.open(folder / "bricks.png"))
        load0 = os.getloadavg()
        for kind, tile in ((k, int(v)) for k in args.kinds.split(",") for v in args.tiles.split(",")):
            walls = {}
            for which, package in packages.items():
                out = folder / f"t{tile}.png"
                argv = run + ["render", "texture", "--example", str(folder / "bricks.png"), *KINDS[kind],
                              "--tile", str(tile), "--size", f"{w}x{h}", "-o", str(out)]
                env = dict(os.environ, PYTHONPATH=str(package))
                r = min((child(argv, cwd=folder, env=env) for _ in range(args.repeat)),
                        key=lambda r: r.wall)
                if r.returncode:
                    raise SystemExit(f"{which}: render texture exited {r.returncode}: {r.stderr}")
                walls[which] = r.wall
                shape, share, between = mortar_numbers(wall, np.asarray(Image.open(out)))
                rows.append((kind, tile, which, r.wall, r.cpu, r.rss_mib, w * h / r.wall,
                             walls[next(iter(packages))] / r.wall, shape, share, between))
    load1 = os.getloadavg()
    print(f"{os.cpu_count()} CPU cores; picture {w}x{h}, corner tiles C = 3; load average {load0[0]:.2f} before, "
          f"{load1[0]:.2f} after")
    print("ratio: the baseline's wall time over the row's; down/across and mortar: 1 is the wall's, between: the "
          "wall's is 0 (see the docstring)")
    print(f"{'texture':<13}{'tile':>5}  {'package':<18}{'wall s':>8}{'cpu s':>8}{'peak RSS MiB':>14}{'Mpx/s':>8}"
          f"{'ratio':>8}{'down/across':>13}{'mortar':>8}{'between':>9}")
    for kind, tile, which, wall_s, cpu_s, rss, px, ratio, shape, share, between in rows:
        print(f"{kind:<13}{tile:>5}  {which:<18}{wall_s:>8.2f}{cpu_s:>8.2f}{rss:>14.0f}{px / 1e6:>8.3f}{ratio:>7.2f}x"
              f"{shape:>13.2f}{share:>8.2f}{between:>9.3f}")


if __name__ == "__main__":
    main()
