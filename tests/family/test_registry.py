"""The registry of families (tilesolve.family.registry): loaded once from the entry points, and
whole for every thread that reads it while another one is still loading it."""

from __future__ import annotations

import subprocess
import sys
import textwrap

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
