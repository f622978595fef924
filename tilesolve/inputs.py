"""The input limit: how every file a user hands tilesolve is read (issue 17, "readers never
read without bound").

Solutions, problems, reports, tile sets, masks, text grids and DRAT proofs are all read through
:func:`read_input`, so no file, pipe or device is read past the limit. It lives in the base
layer so that every layer that reads a user's file (``io`` readers, the ``engine``'s proof
re-checks) uses the same limit and the same messages.
"""

from __future__ import annotations

import os
import re

from tilesolve.errors import InvalidProblem

__all__ = ["read_input", "read_input_text", "max_input_bytes", "parse_byte_size", "MAX_INPUT_ENV",
           "DEFAULT_MAX_INPUT"]

#: The environment variable that sets the input limit (``tilesolve --max-input`` sets it too).
MAX_INPUT_ENV = "TILESOLVE_MAX_INPUT"
#: Most bytes read from one input file by default: 256 MiB, more than the largest file
#: tilesolve writes within the CLI's limits (a window of 2^26 tiles as an encoded array).
DEFAULT_MAX_INPUT = 256 << 20
_UNITS = {"": 1, "K": 1 << 10, "M": 1 << 20, "G": 1 << 30, "T": 1 << 40}
_SIZE_RE = re.compile(r"\s*(\d+)\s*([KMGT]?)(?:I?B)?\s*", re.IGNORECASE)


def parse_byte_size(text: str) -> int:
    """A size in bytes from ``"512"``, ``"64K"``, ``"300M"``, ``"2G"`` or ``"1GiB"`` (binary units).

    >>> parse_byte_size("300M"), parse_byte_size("2GiB"), parse_byte_size("4096")
    (314572800, 2147483648, 4096)
    """
    m = _SIZE_RE.fullmatch(str(text))
    if not m or int(m.group(1)) == 0:
        raise InvalidProblem(f"input limit {text!r}: expected a positive size such as 4096, 300M or 2G")
    return int(m.group(1)) * _UNITS[m.group(2).upper()]


def max_input_bytes() -> int:
    """The most bytes a reader takes from one input file: ``$TILESOLVE_MAX_INPUT`` (a
    :func:`parse_byte_size` size), else :data:`DEFAULT_MAX_INPUT`."""
    value = os.environ.get(MAX_INPUT_ENV)
    if value is None or not value.strip():
        return DEFAULT_MAX_INPUT
    try:
        return parse_byte_size(value)
    except InvalidProblem as exc:
        raise InvalidProblem(f"{MAX_INPUT_ENV}: {exc}") from None


def read_input(path: str | os.PathLike, what: str = "") -> bytes:
    """The bytes of an input file, read through the input limit (:func:`max_input_bytes`).

    Every reader of user files comes here, so no file, pipe or device (``/dev/zero``, a
    pipe of ``yes``) is read past the limit: at most limit + 1 bytes are ever held.

    Parameters
    ----------
    path : path-like
    what : str
        How error messages name the file (``"mask "``: "cannot read mask FILE").

    Raises
    ------
    InvalidProblem
        The file is missing, a directory, unreadable, or larger than the limit.
    """
    limit = max_input_bytes()
    try:
        with open(path, "rb") as fh:
            data = fh.read(limit + 1)
    except FileNotFoundError:
        raise InvalidProblem(f"cannot read {what}{path}: no such file") from None
    except IsADirectoryError:
        raise InvalidProblem(f"cannot read {what}{path}: it is a directory") from None
    except OSError as exc:
        raise InvalidProblem(f"cannot read {what}{path}: {(exc.strerror or str(exc)).lower()}") from None
    if len(data) > limit:
        raise InvalidProblem(
            f"{path}: the input is larger than the input limit of {_mib(limit)}; raise it with "
            f"tilesolve --max-input SIZE or {MAX_INPUT_ENV}=SIZE (e.g. 2G)"
        )
    return data


def _mib(n: int) -> str:
    return f"{n / 2**20:g} MiB" if n >= 1 << 20 else f"{n} bytes"


def read_input_text(path: str | os.PathLike, what: str = "") -> str:
    """:func:`read_input` decoded as UTF-8 (one-line error when it is not UTF-8 text)."""
    try:
        return read_input(path, what).decode("utf-8")
    except UnicodeDecodeError:
        raise InvalidProblem(f"cannot read {what}{path}: not a UTF-8 text file") from None
