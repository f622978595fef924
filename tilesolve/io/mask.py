"""Board masks from files: a PNG picture or a text file of ``#`` (cell) and ``.`` (hole).

Parsing mask text that is already in memory is the model's
(:func:`tilesolve.model.board.parse_mask_text`); this module reads the files and turns a
``mask:FILE`` board spec into a board (brick paper, Def. 4: a rectangle restricted to the
cells of the mask).
"""

from __future__ import annotations

import io
import os

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.inputs import read_input
from tilesolve.model.board import MAX_BOARD_CELLS, Board, parse_board_spec, parse_mask_text

__all__ = ["read_mask", "read_board_spec"]

_PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def read_mask(path: str | os.PathLike) -> np.ndarray:
    """Read a mask file as a boolean ``(rows, cols)`` array (``True`` = cell).

    A PNG's opaque pixels are cells (without an alpha channel: its dark pixels, grey
    level below 128); any other file is read as UTF-8 text of ``#`` and ``.``. The file is
    read through the input limit (:func:`tilesolve.inputs.read_input`) and a PNG's size is
    checked against :data:`~tilesolve.model.board.MAX_BOARD_CELLS` before it is decoded.

    Raises
    ------
    InvalidProblem
        The file cannot be read, is neither a PNG nor such a text, or has no cell.
    """
    data = read_input(path, "mask ")
    if data[:8] == _PNG_MAGIC:
        from PIL import Image

        try:
            img = Image.open(io.BytesIO(data))  # reads the header only: the size comes first
            if img.width * img.height > MAX_BOARD_CELLS:
                raise InvalidProblem(f"{path}: {img.width}x{img.height} pixels is too large a board "
                                     f"(at most {MAX_BOARD_CELLS} cells)")
            img.load()
        except InvalidProblem:
            raise
        except Exception as exc:  # noqa: BLE001 - any decoder failure is a bad file
            raise InvalidProblem(f"{path}: not a readable PNG ({exc})") from None
        if "A" in img.getbands() or img.info.get("transparency") is not None:
            m = np.asarray(img.convert("RGBA"))[:, :, 3] > 0
        else:
            m = np.asarray(img.convert("L")) < 128
        if not m.any():
            raise InvalidProblem(f"{path}: the PNG mask has no opaque (cell) pixels")
        return m
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        raise InvalidProblem(f"{path}: a mask must be a PNG or a text file of '#' and '.'") from None
    return parse_mask_text(text, str(path))


def read_board_spec(spec: str) -> Board:
    """A board from a command-line spec: ``mask:FILE`` reads the mask file; ``mask:ROWS`` (only
    ``#``, ``.`` and ``/``, and no such file) is the mask itself, rows top first separated by
    ``/``; anything else (``rect:WxH``, ``torus:WxH``, ...) goes to
    :func:`tilesolve.model.board.parse_board_spec`.

    Examples
    --------
    >>> read_board_spec("ring:4x3").describe()
    'ring board, 10 cells in 4x3, 20 boundary legs'
    >>> int(read_board_spec("mask:###/#.#/###").mask_of().sum())
    8
    """
    s = str(spec)
    if s.startswith("mask:"):
        rows = s[5:]
        if rows and set(rows) <= set("#./") and not os.path.exists(rows):
            return Board.mask(parse_mask_text(rows.replace("/", "\n"), "mask"))
        return Board.mask(read_mask(rows))
    return parse_board_spec(s)
