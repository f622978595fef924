"""Reading a picture file: the one reader of the commands that take an image (a stipple's
density, a Wang texture's example, a recursive-Wang density or background), with one-line
errors.

Pillow decodes every format it knows; this module adds the size cap, checked from the header
before the pixels are decoded, and turns Pillow's exceptions into one line naming the file.

>>> import os, tempfile
>>> from PIL import Image
>>> folder = tempfile.mkdtemp()
>>> Image.new("L", (3, 2), 128).save(os.path.join(folder, "g.png"))
>>> read_rgba(os.path.join(folder, "g.png")).shape
(2, 3, 4)
>>> read_rgba(os.path.join(folder, "g.png"), max_pixels=5)
Traceback (most recent call last):
...
tilesolve.errors.InvalidProblem: ...g.png: the image has 6 pixels; at most 5
"""

from __future__ import annotations

import os

import numpy as np

from tilesolve.errors import InvalidProblem

__all__ = ["read_rgba"]


def read_rgba(path: str | os.PathLike, max_pixels: int | None = None) -> np.ndarray:
    """The picture at ``path`` as an ``(H, W, 4)`` uint8 RGBA array, row 0 the top row.

    Parameters
    ----------
    path : str or os.PathLike
        Any file Pillow reads.
    max_pixels : int, optional
        Refuse a picture of more pixels (read from its header, before decoding); without it,
        Pillow's own decompression-bomb limit still applies.

    Raises
    ------
    InvalidProblem
        One line naming the file: no such file, a directory, permission denied, too many
        pixels, or not a readable image (with Pillow's reason).
    """
    from PIL import Image, UnidentifiedImageError
    from PIL.Image import DecompressionBombError

    name = os.fspath(path)
    try:
        with Image.open(name) as img:
            if max_pixels is not None and img.width * img.height > max_pixels:
                raise InvalidProblem(f"{name}: the image has {img.width * img.height:,} pixels; at most {max_pixels:,}")
            return np.asarray(img.convert("RGBA"), dtype=np.uint8)
    except InvalidProblem:
        raise  # the size cap's own message (InvalidProblem is a ValueError, caught below otherwise)
    except FileNotFoundError:
        raise InvalidProblem(f"{name}: no such file") from None
    except IsADirectoryError:
        raise InvalidProblem(f"{name}: is a directory, not an image") from None
    except PermissionError:
        raise InvalidProblem(f"{name}: permission denied") from None
    except DecompressionBombError:
        raise InvalidProblem(f"{name}: the image has more pixels than Pillow's safety limit") from None
    except (UnidentifiedImageError, OSError, ValueError, SyntaxError) as exc:
        raise InvalidProblem(f"{name}: not a readable image ({' '.join(str(exc).split())[:120]})") from None
