"""The family registry and the one solve pipeline (DESIGN.md, "Families and their contract").

A *family* is one kind of tiling question (dappled tilings, Wang tilings of boards, tile
packings, ...). Each family writes its layer modules (``model/``, ``constructive/``,
``encodings/``, ``verify/``, ``io/``, ``cli/``), declares one :class:`Family` record in its
facade module (``tilesolve/families/<family>.py``), and registers it once, under the entry-point group
``tilesolve.families`` in ``pyproject.toml``::

    [project.entry-points."tilesolve.families"]
    dappled = "tilesolve.families.dappled:FAMILY"

(or, at run time, with :func:`register`). Everything generic reads the registry: the solve
pipeline below, ``tilesolve verify`` (:func:`verify_file`), ``draw``, ``demo``,
``export dimacs``, ``backends`` and the CLI's command list. Adding a family edits no shared
list. ``docs/ADDING_A_FAMILY.md`` walks through it.

Routes
------
Every route of every family has one signature, ``route(problem, run) -> Solution``, where
``run`` is a :class:`RunOptions`: the resolved seed, the :class:`~tilesolve.deadline.Deadline`
of the whole run, progress, solver, workers, cluster, and the family's own options. A user's
``method=callable`` has the same signature.

The pipeline (:func:`solve`) is written once: look the method up (``"auto"`` asks the
family), draw and record a seed when none is given, show progress, fall back to the
family's fallback route when ``auto``'s choice does not apply or its output fails
verification, verify every tiling with the family's independent checker, and stamp the
provenance (method, seed, time, notes).

Modules
-------
:mod:`~tilesolve.family.contract`
    :class:`Family`, :class:`Codec`, :class:`Demo` and the route signature.
:mod:`~tilesolve.family.forms`
    :class:`Form` and :class:`Field`: a problem posed from the studio's form and as a command line.
:mod:`~tilesolve.family.registry`
    :func:`register`, :func:`get`, :func:`families`, :func:`family_of`, :func:`codec_of`.
:mod:`~tilesolve.family.pipeline`
    :func:`solve`, :func:`run_route`, :func:`count`.
:mod:`~tilesolve.family.verification`, :mod:`~tilesolve.family.files`, :mod:`~tilesolve.family.drawing`
    ``tilesolve verify``, reading and writing solution files, pictures.
:mod:`~tilesolve.family.seeds`
    The seed every run draws and records.

Every public name is imported from here: ``from tilesolve.family import solve, Family``.

Examples
--------
>>> from tilesolve.model.dappled import DappledProblem
>>> s = solve(DappledProblem.from_strings("6x4", ["H0=2", "V1=2"]), seed=3)
>>> s.status.value, s.seed
('sat', 3)
>>> sorted(f.name for f in families())[:4]
['aperiodic', 'aperiodic-window', 'board', 'dappled']
"""

from tilesolve.family.contract import Codec, Demo, Family, Route
from tilesolve.family.drawing import draw_solution, render
from tilesolve.family.files import read_document, solution_text, write_solution
from tilesolve.family.forms import Field, Form, form_size
from tilesolve.family.pipeline import (
    count,
    interrupted,
    raise_if_interrupted,
    run_deadline,
    run_route,
    solve,
    writing_proofs,
)
from tilesolve.family.registry import (
    ENTRY_POINT_GROUP,
    backend_report,
    codec_of,
    commands,
    families,
    family_of,
    get,
    iter_demos,
    register,
    unregister,
)
from tilesolve.family.seeds import draw_seed
from tilesolve.family.verification import (
    DEFAULT_MAX_CNF,
    FileReport,
    cnf_estimate,
    cnf_size_refusal,
    verify_document,
    verify_file,
)
from tilesolve.model.run import RunOptions

__all__ = [
    "RunOptions",
    "Route",
    "Codec",
    "Demo",
    "Field",
    "Form",
    "form_size",
    "cnf_estimate",
    "cnf_size_refusal",
    "DEFAULT_MAX_CNF",
    "Family",
    "register",
    "unregister",
    "families",
    "commands",
    "get",
    "family_of",
    "codec_of",
    "solve",
    "count",
    "draw_seed",
    "interrupted",
    "raise_if_interrupted",
    "read_document",
    "verify_document",
    "verify_file",
    "write_solution",
    "solution_text",
    "backend_report",
    "render",
    "iter_demos",
    "draw_solution",
    "ENTRY_POINT_GROUP",
    "run_route",
    "run_deadline",
    "writing_proofs",
    "FileReport",
]
