"""Compiled kernels load without scipy.linalg (numba's BLAS probe, which cost every command
that runs a kernel more CPU than its cached kernels), and numba's linear algebra still works
afterwards in the same process (:mod:`tilesolve._numba`)."""

import subprocess
import sys

import pytest

_SCRIPT = """
import sys
import numpy as np
{load}
assert "scipy.linalg" not in sys.modules, "loading the kernels imported scipy.linalg"
import numba
import numba.np.arraymath as arraymath
assert arraymath._HAVE_BLAS
@numba.njit
def dot(a, b):
    return np.dot(a, b)
a = np.arange(6.0).reshape(2, 3)
assert np.array_equal(dot(a, a.T), a @ a.T)
print("ok")
"""

_LOADS = {
    "drat": ('from tilesolve.verify.drat import check_drat\n'
             'assert check_drat([[1], [-1]], ["0"], kernels="compiled").verified'),
    "lattice": ('from tilesolve.constructive.stochastic import direct_corner\n'
                'assert direct_corner(0, 0, 3, 2, colors=2, seed=1).shape == (2, 3)'),
}


@pytest.mark.slow
@pytest.mark.parametrize("kernels", sorted(_LOADS))
def test_kernels_load_without_scipy_linalg_and_numba_keeps_blas(kernels):
    script = _SCRIPT.format(load=_LOADS[kernels])
    proc = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0 and proc.stdout.strip() == "ok", proc.stderr[-2000:]
