"""Imported once by the studio's forkserver: die with the server, then load every family, run
its warm hook (:attr:`tilesolve.family.Family.warm`, e.g. compiled kernels) and one whole
studio solve of each (solve, verify, file, both pictures), so that each solve process forked
from it finds every module imported and every kernel compiled (see :mod:`tilesolve.studio.jobs`,
which sets ``PARENT_ENV`` to the server's process id for the forkserver; anywhere else, e.g. a
doctest run importing every module, importing this module does nothing)."""

from __future__ import annotations

import os

from tilesolve import family
from tilesolve.engine.portfolio import _die_with_parent
from tilesolve.errors import TilesolveError
from tilesolve.studio.jobs import PARENT_ENV
from tilesolve.studio.worker import picture, pose, solve_request, warm_families


def _warm() -> None:
    warm_families()
    for fam in family.families():
        if fam.form is None:
            continue
        try:
            solve_request(fam.name, {"seed": 0}, "auto", 30)
            _, values, problem, options = pose(fam.name, {"seed": 0})
            sol = family.solve(problem, seed=0, time_limit=30, options=options)
            if sol.status.has_tiling:
                picture(problem, sol, "png")
        except TilesolveError:  # warming is best effort; a real solve reports the error
            continue


if os.environ.get(PARENT_ENV):
    _die_with_parent(int(os.environ[PARENT_ENV]))
    os.environ[PARENT_ENV] = str(os.getpid())  # the workers forked from here die with this process
    _warm()
