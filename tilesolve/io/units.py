"""Sizes and counts in words, for messages (no numpy: the CLI imports this at start-up)."""

from __future__ import annotations

__all__ = ["human_bytes", "big"]


def human_bytes(n: int) -> str:
    """``1.5 GiB``-style size for messages.

    >>> human_bytes(3 << 29), human_bytes(512)
    ('1.5 GiB', '512 bytes')
    """
    for unit, size in (("TiB", 2**40), ("GiB", 2**30), ("MiB", 2**20), ("KiB", 2**10)):
        if n >= size:
            return f"{big(n / size, '.1f')} {unit}"
    return f"{n} bytes"


def big(n: float, fmt: str = ",") -> str:
    """A count for messages: ``1,998,000`` (``fmt``), or ``2.0e+24`` once it is absurd."""
    return format(n, fmt) if n < 1e13 else f"{n:.1e}"
