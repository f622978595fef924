"""tilesolve: a tiling studio backed by SAT and constraint solvers."""

import os

__version__ = "0.1.0"


def _numba_cache_fallback() -> None:
    """Give numba a cache folder where it would find none.

    The compiled kernels are cached (``numba.njit(cache=True)``) next to their sources, or,
    where the package is read-only, in the user's cache folder (``$XDG_CACHE_HOME/numba`` or
    ``~/.cache/numba``); where neither can be written numba refuses to compile a cached
    kernel at all. Then ``NUMBA_CACHE_DIR`` is set, unless the user set it, to a folder of this
    user's in the temporary folder (kept between runs, so later runs load the compiled code
    instead of compiling again; worker processes inherit it). Checked with two ``os.access``
    calls at import, before numba is loaded.
    """
    if "NUMBA_CACHE_DIR" in os.environ or os.access(os.path.dirname(__file__), os.W_OK):
        return
    user = os.path.join(os.environ.get("XDG_CACHE_HOME") or os.path.expanduser("~/.cache"), "numba")
    while not os.path.exists(user) and os.path.dirname(user) != user:  # the nearest folder that exists
        user = os.path.dirname(user)
    if os.access(user, os.W_OK):
        return
    import tempfile

    user_id = os.getuid() if hasattr(os, "getuid") else os.getpid()
    os.environ["NUMBA_CACHE_DIR"] = os.path.join(tempfile.gettempdir(), f"tilesolve-numba-{user_id}")


_numba_cache_fallback()
