"""Solver backends: time limits, enumeration, counting, proofs, portfolios (DESIGN.md, "engine").

Backends are generic (clauses in, :class:`~tilesolve.engine.result.Result` out) so every
problem family reuses them: :mod:`tilesolve.engine.sat` (PySAT), :mod:`tilesolve.engine.maxsat`,
:mod:`tilesolve.engine.cpsat`, :mod:`tilesolve.engine.certificates` (checked unsat proofs),
:mod:`tilesolve.engine.routes` (the SAT route driver every family's ``sat`` route uses) and
:mod:`tilesolve.engine.portfolio` (seed portfolios on local processes or Dask). Family
modules (:mod:`tilesolve.engine.dappled`, :mod:`tilesolve.engine.packing`) hold the solver
routes of one family. Nothing is imported until used.
"""
