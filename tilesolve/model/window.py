"""A window of the infinite plane: where a finite grid of cells sits, as data.

The random-access generators (procedural walls, 004 §3.2; stochastic tilings, class notes
ch. 3) give a window of an infinite tiling. A file that holds such a window says where it is with
a :class:`Window`, never in a note: its bottom-left cell ``(x0, y0)``, its size ``width x
height`` in cells, and the direction of the y axis. The grid in the file is stored row by row
from the top, so with ``y_up`` (the default, as in the papers' figures) row ``r`` holds the cells
of ``y = y0 + height - 1 - r``.

The CLI reads a window from ``--region X0,Y0,WxH`` (:func:`parse_region`), sizes width first,
like every size a user types (``rect:WxH``, ``torus:WxH``).

>>> w = parse_region("-40,12,64x40")
>>> w
Window(x0=-40, y0=12, width=64, height=40, y_up=True)
>>> w.cell(0, 0), w.cell(39, 63)
((-40, 51), (23, 12))
>>> Window.from_dict(w.to_dict()) == w
True
"""

from __future__ import annotations

import numbers
import re
from dataclasses import dataclass
from typing import Any, Mapping

from tilesolve.errors import InvalidProblem

__all__ = ["Window", "OnWindow", "parse_region", "MAX_COORDINATE"]

#: Coordinates of a window stay within +-2**62, so ``x0 + width`` never leaves int64.
MAX_COORDINATE = 1 << 62

_REGION = re.compile(r"\s*([+-]?\d+)\s*,\s*([+-]?\d+)\s*,\s*(\d+)\s*[xX×]\s*(\d+)\s*")


@dataclass(frozen=True)
class Window:
    """``width x height`` cells of the plane whose bottom-left cell is ``(x0, y0)``.

    Parameters
    ----------
    x0, y0 : int
        The bottom-left cell (the cell of least x and least y).
    width, height : int
        Columns and rows, each at least 1.
    y_up : bool
        Whether y grows upwards (row 0 of the grid is then the top row, ``y0 + height - 1``).
    """

    x0: int
    y0: int
    width: int
    height: int
    y_up: bool = True

    def __post_init__(self) -> None:
        for name in ("x0", "y0", "width", "height"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, numbers.Integral):
                raise InvalidProblem(f"window {name} must be an integer, got {v!r}")
            object.__setattr__(self, name, int(v))
        if self.width < 1 or self.height < 1:
            raise InvalidProblem(f"window size must be positive, got {self.width}x{self.height} (WxH)")
        for v in (self.x0, self.y0, self.x0 + self.width, self.y0 + self.height):
            if abs(v) > MAX_COORDINATE:
                raise InvalidProblem(f"window {self.describe()} leaves the lattice tilesolve addresses "
                                     "(coordinates within +-2**62)")
        if not isinstance(self.y_up, bool):
            raise InvalidProblem(f"window y_up must be true or false, got {self.y_up!r}")

    @classmethod
    def of(cls, value: Any) -> "Window":
        """``value`` as a window: a :class:`Window` as it is, or ``(x0, y0, width, height)``
        with y growing upwards.

        >>> Window.of((3, -2, 4, 5))
        Window(x0=3, y0=-2, width=4, height=5, y_up=True)
        >>> Window.of((3, -2, 4))
        Traceback (most recent call last):
        ...
        tilesolve.errors.InvalidProblem: a window is (x0, y0, width, height), got (3, -2, 4)
        """
        if isinstance(value, cls):
            return value
        try:
            x0, y0, width, height = value
        except (TypeError, ValueError):
            raise InvalidProblem(f"a window is (x0, y0, width, height), got {value!r}") from None
        return cls(x0, y0, width, height)

    @property
    def shape(self) -> tuple[int, int]:
        """``(rows, cols)`` of the window's grid: ``(height, width)``."""
        return self.height, self.width

    def cell(self, row: int, col: int) -> tuple[int, int]:
        """The plane coordinates ``(x, y)`` of the grid cell in ``row`` (from the top), ``col``."""
        y = self.y0 + self.height - 1 - row if self.y_up else self.y0 + row
        return self.x0 + col, y

    def describe(self) -> str:
        """One line for people: ``x -40..23, y 12..51 (y grows upwards)``."""
        way = "upwards" if self.y_up else "downwards"
        return (f"x {self.x0}..{self.x0 + self.width - 1}, y {self.y0}..{self.y0 + self.height - 1} "
                f"(y grows {way})")

    def caption(self) -> str:
        """The line a picture of the window carries: where it is and which cell is its top-left.

        >>> Window(-40, 12, 64, 40).caption()
        'window x -40..23, y 12..51 (y grows upwards); top-left cell x -40, y 51'
        """
        x, y = self.cell(0, 0)
        return f"window {self.describe()}; top-left cell x {x}, y {y}"

    def to_dict(self) -> dict[str, Any]:
        """The JSON form: ``{"x0", "y0", "width", "height", "y_up"}``."""
        return {"x0": self.x0, "y0": self.y0, "width": self.width, "height": self.height, "y_up": self.y_up}

    @classmethod
    def from_dict(cls, d: Any) -> "Window":
        """Read :meth:`to_dict`'s form (``y_up`` defaults to true); anything else is an
        :class:`~tilesolve.errors.InvalidProblem`."""
        if not isinstance(d, Mapping):
            raise InvalidProblem(f"a window is an object with x0, y0, width, height; got {type(d).__name__}")
        unknown = set(d) - {"x0", "y0", "width", "height", "y_up"}
        if unknown:
            raise InvalidProblem(f"unknown window field {sorted(unknown)[0]!r}")
        missing = [k for k in ("x0", "y0", "width", "height") if k not in d]
        if missing:
            raise InvalidProblem(f"window has no {missing[0]!r}")
        return cls(d["x0"], d["y0"], d["width"], d["height"], d.get("y_up", True))


class OnWindow:
    """The grid of a problem whose answer is a window of the plane (its ``window`` attribute)."""

    window: Window

    @property
    def shape(self) -> tuple[int, int]:
        """``(rows, cols)`` of the window's grid: ``(height, width)``."""
        return self.window.shape

    @property
    def n_cells(self) -> int:
        return self.window.width * self.window.height


def parse_region(text: str) -> Window:
    """``--region X0,Y0,WxH``: the window whose bottom-left cell is ``(X0, Y0)``, W columns, H rows.

    >>> parse_region("-8,3,16x4")
    Window(x0=-8, y0=3, width=16, height=4, y_up=True)
    """
    m = _REGION.fullmatch(str(text))
    if m is None:
        raise InvalidProblem(f"cannot read region {text!r}: expected X0,Y0,WxH, e.g. -40,12,64x40 "
                             "(bottom-left cell x -40, y 12; 64 columns, 40 rows)")
    x0, y0, w, h = (int(g) for g in m.groups())
    return Window(x0, y0, w, h)
