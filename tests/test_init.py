"""The package's import-time set-up (tilesolve/__init__.py): numba's cache folder."""

import os
import subprocess
import sys

import tilesolve


def test_numba_gets_a_temporary_cache_where_package_and_home_are_read_only(monkeypatch, tmp_path):
    monkeypatch.setenv("NUMBA_CACHE_DIR", "")  # restored (or removed) after the test
    monkeypatch.delenv("NUMBA_CACHE_DIR")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    monkeypatch.setattr(os, "access", lambda path, mode: False)
    tilesolve._numba_cache_fallback()
    chosen = os.environ["NUMBA_CACHE_DIR"]
    assert os.path.basename(chosen).startswith("tilesolve-numba-")


def test_numba_cache_is_left_alone_where_it_can_be_written(monkeypatch, tmp_path):
    monkeypatch.setenv("NUMBA_CACHE_DIR", "")  # restored (or removed) after the test
    monkeypatch.delenv("NUMBA_CACHE_DIR")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))  # exists and is writable: numba's own choice
    real_access = os.access
    monkeypatch.setattr(os, "access", lambda path, mode: path != os.path.dirname(tilesolve.__file__)
                        and real_access(path, mode))
    tilesolve._numba_cache_fallback()
    assert "NUMBA_CACHE_DIR" not in os.environ
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "mine"))
    monkeypatch.setattr(os, "access", lambda path, mode: False)
    tilesolve._numba_cache_fallback()
    assert os.environ["NUMBA_CACHE_DIR"] == str(tmp_path / "mine")  # the user's setting wins


def test_a_kernel_compiles_and_caches_in_the_fallback_folder(tmp_path):
    """Through numba itself: a cached kernel of tilesolve compiles with NUMBA_CACHE_DIR as the
    fallback sets it, and its cache files land there."""
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path))
    code = "from tilesolve.constructive._wall_map_kernels import colour_of_vertex\ncolour_of_vertex(1, 2, 3)"
    subprocess.run([sys.executable, "-c", code], env=env, check=True, timeout=600, capture_output=True)
    assert any(p.suffix == ".nbi" for p in tmp_path.rglob("*"))
