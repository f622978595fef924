"""CP-SAT parameter choices that once aborted the whole process (checked in a subprocess)."""

import subprocess
import sys

CODE = """
import numpy as np
from tilesolve.families import dappled
from tilesolve.model.dappled import DappledProblem
p = DappledProblem.from_strings("2x2", ["H0=2", "V0=1"], n_tiles=3, fixed=np.array([[0, 2], [0, 0]]))
for seed in range(20):
    s = dappled.solve(p, method="cpsat", seed=seed)
    assert s.status.value == "unsat", s
print("ok")
"""


def test_seeded_cpsat_on_a_model_decided_by_propagation_does_not_abort():
    proc = subprocess.run([sys.executable, "-c", CODE], capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0 and proc.stdout.strip() == "ok", proc.stderr[-2000:]
