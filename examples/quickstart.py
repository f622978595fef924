"""Solve a dappled tiling, check it independently, and draw it.

Run from anywhere::

    python examples/quickstart.py            # writes ./quickstart.svg and .json
    python examples/quickstart.py OUT_DIR

The same as ``tilesolve dappled solve --size 24x16 --cond H0=2 --cond V1=3 --seed 7
-o quickstart.json --svg quickstart.svg``.
"""

import sys
from pathlib import Path

from tilesolve.families import dappled
from tilesolve.io.dappled_json import write_solution
from tilesolve.io.svg import write_svg
from tilesolve.model import DappledProblem
from tilesolve.verify import dappled_violations

out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path.cwd()
out.mkdir(parents=True, exist_ok=True)

# 24 columns x 16 rows, tiles {0, 1}: no horizontal run of tile 0 longer than 2,
# no vertical run of tile 1 longer than 3 (Kaji et al., Dappled tiling, Def. 1.1).
problem = DappledProblem.from_strings("24x16", ["H0=2", "V1=3"])
solution = dappled.solve(problem, seed=7)

violations = dappled_violations(problem, solution.tiling)  # independent checker
assert not violations, violations

write_solution(out / "quickstart.json", problem, solution)
write_svg(out / "quickstart.svg", solution.tiling, problem=problem,
          notes=[f"{solution.status.value} by {solution.method}, seed 7"])
print(f"{solution.status.value} by {solution.method} in {solution.time_s:.3f} s -> {out / 'quickstart.svg'}")
