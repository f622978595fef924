"""Imported once by the studio's forkserver: load every family and compile its kernels, so
each solve process forked from it starts warm (see :mod:`tilesolve.studio.jobs`)."""

from __future__ import annotations

from tilesolve import family


def _warm() -> None:
    for fam in family.families():
        if fam.form is None:
            continue
        try:
            values = fam.form.values({"seed": 0})
            problem, options = fam.form.build(values)
            family.solve(problem, seed=0, time_limit=30, options=options)
        except Exception:  # noqa: BLE001 - warming is best effort; a real solve reports any error
            continue


_warm()
