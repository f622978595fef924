"""Imported once by the studio's forkserver: load every family, compile its kernels and run
one whole studio solve of each (solve, verify, file, both pictures), so that each solve
process forked from it finds every module imported and every kernel compiled (see
:mod:`tilesolve.studio.jobs`)."""

from __future__ import annotations

from tilesolve import family
from tilesolve.errors import TilesolveError
from tilesolve.studio.worker import compiled_kernels, picture, pose, solve_request


def _warm() -> None:
    compiled_kernels()
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


_warm()
