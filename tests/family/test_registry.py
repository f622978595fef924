"""The registry of families (tilesolve.family.registry): loaded once from the entry points, and
whole for every thread that reads it while another one is still loading it."""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap

from tilesolve.family import registry

#: Thread A starts loading the entry points and is held inside the first one; thread B asks for
#: the families meanwhile. B must wait for the whole registry, not get the families loaded so far
#: (the studio's warm-up thread and its first request: "unknown family 'packing'").
RACE = textwrap.dedent("""
    import threading
    from tilesolve.family import families, registry

    entered, go = threading.Event(), threading.Event()
    load = registry._load_entry

    def held(ep):
        entered.set()
        go.wait()
        load(ep)

    registry._load_entry = held
    a = threading.Thread(target=families)
    a.start()
    entered.wait()
    seen = []
    b = threading.Thread(target=lambda: seen.append(sorted(f.name for f in families())))
    b.start()
    b.join(0.5)  # with the bug, B has already answered with a part of the registry
    go.set()
    a.join()
    b.join()
    print(" ".join(seen[0]))
""")


def test_a_thread_reading_the_registry_while_another_loads_it_sees_every_family():
    out = subprocess.run([sys.executable, "-c", RACE], capture_output=True, text=True, check=True)
    names = out.stdout.split()
    assert {"aperiodic", "board", "dappled", "packing", "stochastic"} <= set(names), names


def _scan_cache(monkeypatch, tmp_path, key_of):
    """Point the registry at a cache file of this test holding one made-up entry point, recorded
    under this process's sys.path with the key ``key_of(real key)``; the registry module."""
    cache = tmp_path / "entry_points.json"
    monkeypatch.setattr(registry, "SCAN_CACHE", str(cache))
    key = [registry._installed(entry) for entry in sys.path]
    made_up = [["madeup", "tilesolve.families.dappled:FAMILY"]]
    cache.write_text(json.dumps([[json.dumps(sys.path), {"key": key_of(key), "entry_points": made_up}]]))
    return registry


def test_the_scan_of_the_entry_points_comes_from_the_cache_while_nothing_was_installed(monkeypatch, tmp_path):
    registry = _scan_cache(monkeypatch, tmp_path, lambda key: key)
    assert [ep.name for ep in registry._entry_points()] == ["madeup"]


def test_the_entry_points_are_scanned_again_after_an_installation(monkeypatch, tmp_path):
    """A cache written when the installed packages were others (here: one more .dist-info) is not
    used; the scan replaces it."""
    registry = _scan_cache(monkeypatch, tmp_path, lambda key: [k + [["other-1.0.dist-info", 1]]
                                                               if isinstance(k, list) else k for k in key])
    names = [ep.name for ep in registry._entry_points()]
    assert "madeup" not in names and {"aperiodic", "board", "dappled", "packing", "stochastic"} <= set(names)
    assert [ep.name for ep in registry._entry_points()] == names  # now from the rewritten cache


def test_a_second_command_does_not_scan_the_installed_packages(tmp_path):
    """importlib.metadata (more than a small solve costs to import) is loaded only to fill the cache
    (kept in a temporary folder here, so that the test holds on a read-only installation too)."""
    cache = str(tmp_path / "entry_points.json")
    code = ("import sys\nfrom tilesolve.family import families, registry\n"
            f"registry.SCAN_CACHE = {cache!r}\n"
            "families()\nprint('importlib.metadata' in sys.modules)")
    runs = [subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.strip()
            for _ in range(2)]
    assert runs == ["True", "False"]


def test_families_come_in_entry_point_order_whatever_was_imported_first():
    """A process that imported one facade first (registering it first) lists the families in the
    same order as the console script does (the --help test compared the two)."""
    code = ("import tilesolve.families.stochastic, tilesolve.families.packing\n"
            "from tilesolve import family\n"
            "print(' '.join(f.name for f in family.families()))")
    late = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.split()
    fresh = subprocess.run([sys.executable, "-c", code.split("\n", 1)[1]], capture_output=True, text=True,
                           check=True).stdout.split()
    assert late == fresh and late.index("packing") > late.index("board")
