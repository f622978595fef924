"""The studio's form of the aperiodic-window family (:mod:`tilesolve.families.aperiodic_window`):
a built-in aperiodic Wang tile set and a window of the plane (``tilesolve aperiodic tiling``),
and its infinite view (windows of one seed agree where they overlap).

The form is made by :func:`form` from the facade's ``window_problem`` (the facade registers it;
this module imports nothing of the facade).

Examples
--------
>>> from tilesolve.families.aperiodic_window import FAMILY
>>> vals = FAMILY.form.values({"seed": 7})
>>> FAMILY.form.command(vals)[0]
['aperiodic', 'tiling', '--builtin', 'jeandel-rao', '--region=-16,-8,32x16']
>>> problem, method, _ = FAMILY.form.window(vals, Window(0, 0, 4, 4))
>>> problem.window.width, method
(4, 'auto')
"""

from __future__ import annotations

from tilesolve.family.forms import Field, Form, form_size
from tilesolve.model.window import Window

__all__ = ["form", "BUILTINS"]

#: The built-in sets with a constructive route (:func:`tilesolve.families.aperiodic_window.route_of`).
BUILTINS = ("jeandel-rao", "labbe-u19", "kari-14", "kari-culik-13")


def _window(values) -> Window:
    rows, cols = form_size(values["size"])
    return Window(values["x0"], values["y0"], cols, rows)


def _form_command(values) -> tuple[list[str], dict[str, str]]:
    return ["aperiodic", "tiling", "--builtin", values["builtin"],
            f"--region={values['x0']},{values['y0']},{values['size']}"], {}


def form(window_problem) -> Form:
    """The family's form; ``window_problem(name, window)`` poses a window of a built-in set."""
    return Form(
        fields=(
            Field("builtin", "choice", "tile set", "jeandel-rao", "Jeandel-Rao and Labbé's U19 (a Markov partition of "
                  "the torus), Kari's 14 and Kari-Culik's 13 tiles (balanced rows)", choices=BUILTINS, option="--builtin"),
            Field("x0", "int", "window x0", -16, "left column (y grows upwards)", low=-10**9, high=10**9, option="--region"),
            Field("y0", "int", "window y0", -8, "bottom row", low=-10**9, high=10**9, option="--region"),
            Field("size", "size", "window (WxH)", "32x16", "W columns by H rows", high=1 << 20, option="--region"),
        ),
        build=lambda values: (window_problem(values["builtin"], _window(values)), {}),
        command=_form_command,
        window=lambda values, w: (window_problem(values["builtin"], w), "auto", {}),
        time_limit=False,  # the command runs to its end (no --time-limit)
    )
