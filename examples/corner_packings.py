"""Corner tile packings (2D de Bruijn tori) for every C from 2 to 8, each drawn as SVG.

Run from anywhere::

    python examples/corner_packings.py             # writes corner-packings/corner-C.svg
    python examples/corner_packings.py OUT_DIR

Odd C use the triangular-shift de Bruijn construction (class notes §5.5; proof in
``tilesolve.constructive.packing.corner_packing_odd``); even C the ``lift`` search: a packing
over C/2 colours repeated over the torus plus a binary layer found by SAT. C = 8 is 4,096
tiles on a 64x64 torus (timings in README, "Performance"); the notes' backtracking needed
280 CPU-days for C = 4.
Every packing is checked by the independent verifier before it is drawn. The CLI
equivalent of one picture is ``tilesolve pack --kind corner --colors 6 --seed 1 --svg c6.svg``.
"""

import sys
import time
from pathlib import Path

from tilesolve.families import packing
from tilesolve.io.svg_packing import write_packing_svg
from tilesolve.model.packing import PackingProblem
from tilesolve.verify.packing import packing_violations

if __name__ == "__main__":  # a search portfolio's worker processes re-import this file
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path("corner-packings")
    out.mkdir(parents=True, exist_ok=True)
    for c in range(2, 9):
        t0 = time.perf_counter()
        s = packing.solve(PackingProblem("corner", c), seed=1)
        assert s.tiling is not None and not packing_violations(PackingProblem("corner", c), s.tiling)
        path = out / f"corner-{c}.svg"
        write_packing_svg(path, s.tiling, "corner", c, title=f"corner packing, C={c} ({s.method})")
        print(f"C={c}: {s.tiling.shape[0]}x{s.tiling.shape[1]} by {s.method} in {time.perf_counter() - t0:.2f} s"
              f" -> {path}")
