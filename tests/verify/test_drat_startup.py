"""The compiled DRAT kernels load without scipy.linalg (numba's BLAS probe), and numba's linear
algebra still works afterwards in the same process (verify.drat._numba_numpy_without_scipy)."""

import subprocess
import sys

import pytest

_SCRIPT = """
import sys
import numpy as np
from tilesolve.verify.drat import check_drat
assert check_drat([[1], [-1]], ["0"], kernels="compiled").verified
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


@pytest.mark.slow
def test_kernels_load_without_scipy_linalg_and_numba_keeps_blas():
    proc = subprocess.run([sys.executable, "-c", _SCRIPT], capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0 and proc.stdout.strip() == "ok", proc.stderr[-2000:]
