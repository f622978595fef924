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


_COMMANDS = """
import json, sys
from tilesolve.family import registry
registry.SCAN_CACHE, registry.COMMAND_CACHE = {scan!r}, {commands!r}
found = registry.commands()
facades = sorted(m for m in sys.modules if m.startswith("tilesolve.families."))
print(json.dumps([found, facades]))
"""


def test_the_families_commands_come_from_the_cache_without_importing_a_facade(tmp_path):
    """`tilesolve sample` (a command not named like its family) loaded every facade to be found;
    the second run reads the commands from the cache and imports none, with the same answer as
    loading every family."""
    code = _COMMANDS.format(scan=str(tmp_path / "entry_points.json"), commands=str(tmp_path / "commands.json"))
    runs = [json.loads(subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                                      check=True).stdout) for _ in range(2)]
    (first, loaded), (second, none) = runs
    assert first == second and first == {t.split(":")[1]: t for f in registry.families() for t in f.commands}
    assert {"sample", "wall", "pack", "dappled"} <= set(first)
    assert "tilesolve.families.poisson" in loaded and none == []


def test_a_changed_facade_is_loaded_again_for_its_commands(monkeypatch, tmp_path):
    """A cache entry recorded for another version of a facade's file (here: another size) is not
    used: the families are loaded and the cache rewritten with the file as it is."""
    cache = tmp_path / "commands.json"
    monkeypatch.setattr(registry, "COMMAND_CACHE", str(cache))
    eps = registry._entry_points()
    stale = {ep.value: {"source": [s[0], s[1] + 1, s[2]], "commands": ["tilesolve.cli.nowhere:gone"]}
             for ep in eps for s in [registry._source(ep)]}
    cache.write_text(json.dumps(stale))
    monkeypatch.setattr(registry, "_REGISTRY", {})  # nothing loaded yet in this "process"
    monkeypatch.setattr(registry, "_LOADED", False)
    found = registry.commands()
    assert "gone" not in found and "sample" in found
    assert json.loads(cache.read_text())[eps[0].value]["source"] == registry._source(eps[0])
