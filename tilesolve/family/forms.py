"""How a family's problem is posed from a form (``tilesolve studio``) and as a command line."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable, Mapping

from tilesolve.errors import InternalError, InvalidProblem
from tilesolve.family.seeds import check_seed, draw_seed
from tilesolve.model.solution import Solution

__all__ = ["Field", "Form", "form_size", "MAX_FORM_CELLS"]


@dataclass(frozen=True)
class Field:
    """One parameter of a family's problem, as the studio's form shows it.

    Attributes
    ----------
    name : str
        Key of the value in the form's values (a JSON object).
    kind : str
        ``"int"``, ``"float"``, ``"text"``, ``"bool"``, ``"choice"`` (one of ``choices``) or
        ``"size"`` (``"WxH"`` text, at most ``high`` cells) or ``"cells"``: a grid the user
        paints, sent as a list of rows of ints (``-1`` = unset).
    label, help : str
        What the form shows.
    default
        The value a new form starts with (``None``: empty).
    low, high : float, optional
        Limits of ``int``/``float`` values (checked again by :meth:`Form.values`).
    choices : tuple of str
        For ``choice``.
    option : str, optional
        The CLI option that takes this value (``"--size"``): the studio's "copy as CLI command".
    extent : callable, optional
        ``cells`` only: ``extent(values) -> (rows, cols, low, high)``, the grid's shape and its
        cell values' range for the other values of the form.
    when : tuple of dict
        When the field applies (the studio hides it otherwise): under any one of these
        conditions, each a mapping ``{other field's name: the values under which it applies}``
        that all hold; empty: always. A field that does not apply takes its default (:meth:`Form.values`).
    """

    name: str
    kind: str
    label: str
    default: Any = None
    help: str = ""
    low: float | None = None
    high: float | None = None
    choices: tuple[str, ...] = ()
    option: str | None = None
    extent: Callable[[Mapping[str, Any]], tuple[int, int, int, int]] | None = None
    when: tuple[Mapping[str, tuple], ...] = ()

    def public(self) -> dict:
        """The field as JSON for the page (without the callables)."""
        out = {k: getattr(self, k) for k in ("name", "kind", "label", "default", "help", "low", "high",
                                              "choices", "option")}
        out["when"] = [{name: list(vals) for name, vals in cond.items()} for cond in self.when]
        return out

    def applies(self, values: Mapping[str, Any]) -> bool:
        """Whether the field applies to the form's ``values`` (:attr:`when`).

        >>> Field("steps", "int", "steps", when=({"patch": ("steps",)},)).applies({"patch": "window"})
        False
        """
        return not self.when or any(all(values.get(k) in vals for k, vals in cond.items()) for cond in self.when)


@dataclass(frozen=True)
class Form:
    """How a family's problem is posed from a form (the studio) and as a command line.

    Attributes
    ----------
    fields : tuple of Field
    build : callable
        ``build(values) -> (problem, options)``: the problem (and the ``options`` of
        :func:`solve`) for checked values; raises :class:`InvalidProblem` with the CLI's messages.
        ``values`` holds every field (defaults filled in) and ``"seed"`` (an int, drawn when
        not given: problems with random parts, e.g. a random boundary, use it).
    command : callable
        ``command(values) -> (words, files)``: the words of the ``tilesolve`` command (after
        ``tilesolve``) that poses the same problem, without seed, method and output options,
        and the files it reads (``{name: text}``, e.g. painted cells as a text grid, or
        ``{name: words}``: the ``tilesolve`` command that writes the file, e.g. a tile set's
        ``build`` before the window command that reads it).
    window : callable, optional
        Families with an infinite plane: ``window(values, w) -> (problem, method, options)``,
        the problem of the window ``w`` (a :class:`~tilesolve.model.window.Window`, y growing
        upwards) of the plane, for the studio's pan-and-zoom view.
    cells : callable, optional
        ``cells(problem, solution) -> 2-D int array``: the solution per cell, in the values
        of the form's ``cells`` fields (clicking a cell of the picture fixes it to this value).
    time_limit : bool
        Whether :attr:`command`'s command takes ``--time-limit`` (the studio's copied command
        keeps the page's time limit where it does).
    sketch : callable, optional
        Families whose tile has edges the user shapes (the studio's live edge editor):
        ``sketch(values) -> dict``, JSON-ready: ``{"edges": [{"field", "kind"}, ...]}`` one per
        edge class (the ``text`` field that holds its shape, its constraint J, U, S or I),
        ``"sides"``: the tile's sides in outline order, each ``{"edge": class, "map": 2x3 affine
        map from the class's unit frame (0, 0)-(1, 0) onto the side, "reverse": bool}``, and
        ``"chords"``: chords per cubic Bézier piece. The outline is each side's shape mapped,
        reversed where said, without its last point.
    """

    fields: tuple[Field, ...]
    build: Callable[[Mapping[str, Any]], tuple[Any, Mapping[str, Any]]]
    command: Callable[[Mapping[str, Any]], tuple[list[str], dict[str, str]]]
    window: Callable[..., tuple[Any, str, Mapping[str, Any]]] | None = None
    cells: Callable[[Any, Solution], Any] | None = None
    time_limit: bool = True
    sketch: Callable[[Mapping[str, Any]], dict] | None = None

    def values(self, given: Mapping[str, Any]) -> dict[str, Any]:
        """``given`` checked against the fields (types, limits, choices), defaults filled in.

        Unknown keys and values of the wrong type raise :class:`InvalidProblem` (one line
        naming the field). ``cells`` grids are checked for shape by :attr:`Field.extent`. A
        field that does not apply to the other values (:attr:`Field.when`) takes its default.
        """
        if not isinstance(given, Mapping):
            raise InvalidProblem("form values must be a JSON object")
        names = {f.name for f in self.fields} | {"seed"}
        extra = sorted(set(given) - names)
        if extra:
            raise InvalidProblem(f"unknown field {extra[0]!r}; fields are {', '.join(sorted(names))}")
        out: dict[str, Any] = {}
        for f in self.fields:
            out[f.name] = _field_value(f, given.get(f.name, f.default))
        for f in self.fields:  # a field that does not apply keeps its default, whatever was given
            if not f.applies(out):
                out[f.name] = _field_value(f, f.default)
        seed = given.get("seed")
        out["seed"] = draw_seed() if seed is None else check_seed(seed)
        for f in self.fields:
            if f.kind == "cells" and out[f.name] is not None:
                rows, cols, lo, hi = f.extent(out)
                grid = out[f.name]
                if len(grid) != rows or any(len(r) != cols for r in grid):
                    raise InvalidProblem(f"{f.label}: the grid must be {cols}x{rows} (WxH) for these values")
                bad = [v for r in grid for v in r if v != -1 and not lo <= v <= hi]
                if bad:
                    raise InvalidProblem(f"{f.label}: cell value {bad[0]} is outside {lo}..{hi} (-1 = unset)")
        return out


def form_size(text: str) -> tuple[int, int]:
    """``(rows, cols)`` of a checked ``size`` field value ``"WxH"``."""
    w, h = (int(v) for v in text.lower().split("x"))
    return h, w


#: Most cells a painted ``cells`` field may hold (checked before the grid is read).
MAX_FORM_CELLS = 1 << 20


def _field_value(f: Field, v: Any) -> Any:
    """One field's value, checked (see :meth:`Form.values`)."""
    if v is None:
        return None
    what = f"{f.label} ({f.name})"
    if f.kind in ("int", "float"):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or (f.kind == "int" and int(v) != v):
            raise InvalidProblem(f"{what} must be {'a whole number' if f.kind == 'int' else 'a number'}, got {v!r}")
        v = int(v) if f.kind == "int" else float(v)
        if (f.low is not None and v < f.low) or (f.high is not None and v > f.high):
            raise InvalidProblem(f"{what} must be in {f.low:g}..{f.high:g}, got {v}")
        return v
    if f.kind == "bool":
        if not isinstance(v, bool):
            raise InvalidProblem(f"{what} must be true or false, got {v!r}")
        return v
    if f.kind == "size":
        import re

        m = re.fullmatch(r"\s*(\d{1,9})\s*[xX×]\s*(\d{1,9})\s*", v) if isinstance(v, str) else None
        if m is None:
            raise InvalidProblem(f"{what} must be WxH (columns x rows), e.g. 16x12, got {v!r}")
        w, h = int(m.group(1)), int(m.group(2))
        if w < 1 or h < 1:
            raise InvalidProblem(f"{what} must be at least 1x1, got {w}x{h}")
        if f.high is not None and w * h > f.high:
            raise InvalidProblem(f"{what} {w}x{h} has {w * h:,} cells; at most {int(f.high):,} here")
        return f"{w}x{h}"
    if f.kind in ("text", "choice"):
        if not isinstance(v, str) or len(v) > 10_000:
            raise InvalidProblem(f"{what} must be a short text")
        if f.kind == "choice" and v not in f.choices:
            raise InvalidProblem(f"{what} must be one of {', '.join(f.choices)}, got {v!r}")
        return v
    if f.kind == "cells":
        if not isinstance(v, list) or not all(isinstance(r, list) for r in v):
            raise InvalidProblem(f"{what} must be a list of rows")
        if sum(len(r) for r in v) > MAX_FORM_CELLS:
            raise InvalidProblem(f"{what} has more than {MAX_FORM_CELLS:,} cells")
        if not all(isinstance(x, int) and not isinstance(x, bool) for r in v for x in r):
            raise InvalidProblem(f"{what} must hold whole numbers")
        return v
    raise InternalError(f"field {f.name!r} has unknown kind {f.kind!r}")
