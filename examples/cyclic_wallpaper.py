"""A cyclic dappled tiling repeated 3 x 3: the copies meet without breaking a condition.

Run from anywhere::

    python examples/cyclic_wallpaper.py            # writes ./wallpaper.svg and .png
    python examples/cyclic_wallpaper.py OUT_DIR

With ``cyclic=True`` runs wrap around both edges (Kaji et al., Dappled tiling, §3.2), so
the tile can fill the plane. The CLI equivalent is ``tilesolve dappled solve --size 12x12
--cond H0=2,V1=2 --cyclic --seed 2 --svg wallpaper.svg --repeat 3``.
"""

import sys
from pathlib import Path

import numpy as np

from tilesolve.families import dappled
from tilesolve.io.png import write_png
from tilesolve.io.svg import write_svg
from tilesolve.model import DappledProblem
from tilesolve.verify import dappled_violations

out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path.cwd()
out.mkdir(parents=True, exist_ok=True)

problem = DappledProblem.from_strings("12x12", ["H0=2", "V1=2"], cyclic=True)
solution = dappled.solve(problem, seed=2)
assert not dappled_violations(problem, solution.tiling)

# The 3 x 3 repetition, as a plain (non-cyclic) problem, is dappled too.
big = np.tile(solution.tiling, (3, 3))
plain = DappledProblem.from_strings("36x36", ["H0=2", "V1=2"])
assert not dappled_violations(plain, big)

write_svg(out / "wallpaper.svg", solution.tiling, problem=problem, repeat=3,
          notes=[f"{solution.status.value} by {solution.method}, seed 2"])
write_png(out / "wallpaper.png", solution.tiling, repeat=3, scale=8)
print(f"{solution.method}: {out / 'wallpaper.svg'}, {out / 'wallpaper.png'}")
