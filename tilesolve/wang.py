"""Former name of :mod:`tilesolve.board` (Wang tilings of boards), kept importable for now.

The name "wang" belongs to the stochastic Wang/corner tiling family that comes next; new code
imports :mod:`tilesolve.board`.
"""

from tilesolve.board import *  # noqa: F401,F403
from tilesolve.board import __all__  # noqa: F401
