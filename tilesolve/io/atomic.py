"""Atomic file writes (DESIGN.md, "Files"): an interrupted run never leaves a half-written file.

Data for a regular file goes to a temporary file in the destination's own directory (so the
final :func:`os.replace` is a rename within one file system, which POSIX and Windows make
atomic), is flushed to disk, and only then replaces the destination. On any exception,
including ``KeyboardInterrupt``, the temporary file is removed and the destination is
untouched.

Three kinds of destination are not renamed over:

* ``"-"`` is standard output;
* an existing file that is not a regular file (``/dev/null``, a terminal, a FIFO, a socket)
  is opened and written directly: renaming over it would replace the device or pipe with
  a regular file;
* everything else (a regular file, or a new name) is written atomically; a symbolic link is
  followed, so the file it points to is replaced and the link kept.

:func:`commit_together` groups the writes of one run: inside it nothing reaches its
destination until the block ends cleanly, and then every file is committed; if the block
raises, no destination is touched (all-or-nothing for a command's outputs).

A temporary is named ``.<name>.<pid>.<random>.part``. A process killed without a chance to
clean up (SIGKILL, power loss) leaves it behind; the next write to the same destination
removes such leftovers once they are older than :data:`STALE_AFTER_S` and their writer
process is gone.
"""

from __future__ import annotations

import contextlib
import contextvars
import os
import re
import shutil
import stat
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path
from typing import IO, Iterator

__all__ = [
    "atomic_write",
    "write_text_atomic",
    "write_bytes_atomic",
    "commit_together",
    "probe_writable",
    "remove_temporaries",
    "STALE_AFTER_S",
]

#: A leftover temporary is removed when it is older than this (seconds) and its writer is gone.
STALE_AFTER_S = 60.0

_PART = re.compile(r"\.(\d+)\.[A-Za-z0-9_]+\.part\Z")

#: Temporaries of this process that exist now (not yet renamed or removed).
_live: set[str] = set()


@dataclass
class _Pending:
    """A finished write waiting for :func:`commit_together` to commit it."""

    tmp: str  # the temporary holding the data
    dest: str  # the destination ("-" for standard output)
    direct: bool  # copy into the destination (stdout, device, FIFO) instead of renaming


_group: contextvars.ContextVar[list[_Pending] | None] = contextvars.ContextVar("tilesolve_atomic_group", default=None)


def _umask() -> int:
    # os.umask can only be read by setting it; restore it at once.
    mask = os.umask(0)
    os.umask(mask)
    return mask


def _target(path: str | os.PathLike) -> str:
    """The file a write to ``path`` should reach: a symbolic link is followed, not replaced."""
    p = str(path)
    return os.path.realpath(p) if p != "-" and os.path.islink(p) else p


def _is_direct(path: str) -> bool:
    """True for stdout (``"-"``) and for existing files that are not regular files."""
    if path == "-":
        return True
    try:
        return not stat.S_ISREG(os.stat(path).st_mode)
    except (FileNotFoundError, NotADirectoryError):
        return False


def _pid_alive(pid: int) -> bool:
    if pid == os.getpid() or os.name == "nt":  # Windows' os.kill(pid, 0) would terminate it
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OSError):
        return True  # another user's process, or a platform that cannot tell: keep its file
    return True


def _sweep(directory: Path, name: str) -> None:
    """Remove leftover temporaries of ``name`` whose writer is gone (see the module docstring)."""
    prefix = f".{name}."
    now = time.time()
    with contextlib.suppress(OSError):
        for entry in os.scandir(directory):
            if not entry.name.startswith(prefix):
                continue
            m = _PART.fullmatch(entry.name[len(prefix) - 1:])
            if not m:
                continue
            with contextlib.suppress(OSError):
                if entry.is_file(follow_symlinks=False) and now - entry.stat(follow_symlinks=False).st_mtime > STALE_AFTER_S \
                        and not _pid_alive(int(m.group(1))):
                    os.unlink(entry.path)


def _mkstemp(dest: Path) -> tuple[int, str]:
    directory = dest.parent if str(dest.parent) else Path(".")
    _sweep(directory, dest.name)
    fd, tmp = tempfile.mkstemp(prefix=f".{dest.name}.{os.getpid()}.", suffix=".part", dir=directory)
    _live.add(tmp)
    return fd, tmp


def _discard(tmp: str) -> None:
    with contextlib.suppress(OSError):
        os.unlink(tmp)
    _live.discard(tmp)


def probe_writable(path: str | os.PathLike) -> None:
    """Raise :class:`OSError` unless :func:`atomic_write` can write ``path``.

    Standard output (``"-"``) always can; an existing device, FIFO or socket must be
    writable; otherwise a temporary is created in the destination's directory and removed
    again (permission bits alone do not tell, e.g. for root in ``/proc``).
    """
    p = _target(path)
    if p == "-":
        return
    if _is_direct(p):
        if not os.access(p, os.W_OK):
            raise PermissionError(13, "permission denied", p)
        return
    fd, tmp = _mkstemp(Path(p))
    os.close(fd)
    _discard(tmp)


def remove_temporaries() -> None:
    """Remove every temporary this process has open (for a signal handler's clean-up)."""
    for tmp in list(_live):
        _discard(tmp)


@contextlib.contextmanager
def _direct(path: str, mode: str, kwargs: dict) -> Iterator[IO]:
    if path == "-":
        sys.stdout.flush()
        stream = sys.stdout.buffer if "b" in mode else sys.stdout
        yield stream
        stream.flush()
        return
    with open(path, mode, **kwargs) as f:
        yield f


@contextlib.contextmanager
def atomic_write(path: str | os.PathLike, mode: str = "w", *, encoding: str | None = "utf-8") -> Iterator[IO]:
    """Open a file that replaces ``path`` when the ``with`` block ends cleanly.

    ``"-"`` writes to standard output; an existing non-regular file (a device, a FIFO) is
    written directly. Inside :func:`commit_together`, the data waits in a temporary until
    the group commits.

    Parameters
    ----------
    path : str or path-like
        Destination. Its directory must exist.
    mode : {"w", "wb"}
        Text or binary.
    encoding : str, optional
        Text encoding (ignored in binary mode).

    Examples
    --------
    >>> import tempfile, os
    >>> d = tempfile.mkdtemp()
    >>> with atomic_write(os.path.join(d, "a.txt")) as f:
    ...     _ = f.write("hello")
    >>> with open(os.path.join(d, "a.txt")) as f:
    ...     f.read()
    'hello'
    >>> os.listdir(d)
    ['a.txt']
    """
    if mode not in ("w", "wb"):
        raise ValueError(f"atomic_write supports modes 'w' and 'wb', not {mode!r}")
    kwargs = {} if "b" in mode else {"encoding": encoding, "newline": "\n"}
    dest = _target(path)
    direct = _is_direct(dest)
    group = _group.get()
    if direct and group is None:
        with _direct(dest, mode, kwargs) as f:
            yield f
        return
    if direct:
        # Spooled in the system's temporary directory (never next to a device) until the commit.
        fd, tmp = tempfile.mkstemp(prefix=f".tilesolve.{os.getpid()}.", suffix=".part")
        _live.add(tmp)
    else:
        fd, tmp = _mkstemp(Path(dest))
    try:
        # mkstemp creates the file 0600; give it the permissions a plain open() would.
        with contextlib.suppress(OSError):
            os.chmod(tmp, 0o666 & ~_umask())
        with os.fdopen(fd, mode, **kwargs) as f:
            fd = -1  # now owned by f
            yield f
            f.flush()
            if not direct:
                os.fsync(f.fileno())
        if group is not None:
            group.append(_Pending(tmp, dest, direct))
        else:
            os.replace(tmp, dest)
            _live.discard(tmp)
    except BaseException:
        if fd >= 0:
            with contextlib.suppress(OSError):
                os.close(fd)
        _discard(tmp)
        raise


@contextlib.contextmanager
def commit_together() -> Iterator[None]:
    """Commit every :func:`atomic_write` of the block together when it ends cleanly.

    Nothing reaches a destination before the block ends; if it raises, every temporary is
    removed and no destination is touched. At the end, direct destinations (stdout,
    devices, FIFOs) are written first, since they can fail (a closed pipe, a full
    device); regular files are renamed last, which cannot fail once their temporaries exist.

    Examples
    --------
    >>> import tempfile, os
    >>> d = tempfile.mkdtemp()
    >>> try:
    ...     with commit_together():
    ...         write_text_atomic(os.path.join(d, "a.txt"), "a")
    ...         raise RuntimeError("the second file failed")
    ... except RuntimeError:
    ...     pass
    >>> os.listdir(d)
    []
    """
    pending: list[_Pending] = []
    token = _group.set(pending)
    try:
        yield
    except BaseException:
        for p in pending:
            _discard(p.tmp)
        raise
    finally:
        _group.reset(token)
    try:
        for p in pending:
            if p.direct:
                with open(p.tmp, "rb") as src, _direct(p.dest, "wb", {}) as out:
                    shutil.copyfileobj(src, out)
                _discard(p.tmp)
        for p in pending:
            if not p.direct:
                os.replace(p.tmp, p.dest)
                _live.discard(p.tmp)
    finally:
        for p in pending:
            if p.tmp in _live:
                _discard(p.tmp)


def write_text_atomic(path: str | os.PathLike, text: str, *, encoding: str = "utf-8") -> None:
    """Write ``text`` to ``path`` atomically (``"-"``: standard output)."""
    with atomic_write(path, "w", encoding=encoding) as f:
        f.write(text)


def write_bytes_atomic(path: str | os.PathLike, data: bytes) -> None:
    """Write ``data`` to ``path`` atomically (``"-"``: standard output)."""
    with atomic_write(path, "wb") as f:
        f.write(data)
