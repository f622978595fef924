"""The registry of families: the only list of them. Facades :func:`register` their family;
the entry points under :data:`ENTRY_POINT_GROUP` make sure every facade is imported.

The scan of the entry points is cached (:data:`SCAN_CACHE`): importing :mod:`importlib.metadata`
alone costs more than a small command's whole solve. The cache holds while ``sys.path`` is the
same and holds the same ``.dist-info`` (and ``.egg-info``) entries, each with the same
modification time (installing, upgrading, reinstalling or removing a package writes or removes
its own); otherwise the entry points are scanned again and the cache rewritten. Where the
package's folder cannot be written they are scanned every time. The families' commands are
cached beside it (:func:`commands`), so that a command finds its module without importing the
facades.
"""

from __future__ import annotations

import importlib
import json
import os
import sys
import threading
from typing import Any, Iterable, NamedTuple

from tilesolve.errors import InternalError, InvalidProblem
from tilesolve.family.contract import Codec, Demo, Family

__all__ = [
    "ENTRY_POINT_GROUP",
    "register",
    "unregister",
    "families",
    "commands",
    "get",
    "family_of",
    "codec_of",
    "iter_demos",
    "backend_report",
]


#: Entry-point group under which packages declare their families.
ENTRY_POINT_GROUP = "tilesolve.families"


#: The cached scan of the entry points (see the module docstring).
SCAN_CACHE = os.path.join(os.path.dirname(__file__), "__pycache__", "entry_points.json")
#: How many ``sys.path`` lists the cache keeps a scan for (the oldest is dropped).
_SCANS_KEPT = 8
#: Each family's commands, cached (see :func:`commands`).
COMMAND_CACHE = os.path.join(os.path.dirname(__file__), "__pycache__", "commands.json")

_REGISTRY: dict[str, Family] = {}
#: Each entry point's place in :func:`_entry_points` (by name): the order :func:`families`
#: gives, whichever facade a process happened to import first.
_ORDER: dict[str, int] = {}
_LOADED = False
#: Held while the entry points load: another thread asking for the families waits for them all
#: (a server's warm-up thread and its first request); the loading thread itself, re-entered by
#: a facade that reads the registry while it is imported, goes on with those loaded so far.
_LOADING = threading.RLock()
_loading_now = False


def register(family: Family) -> Family:
    """Add ``family`` to the registry (a name registered twice is an error).

    Facade modules call it when imported; the entry points make sure they are imported.
    """
    old = _REGISTRY.get(family.name)
    if old is not None and old is not family:
        raise InvalidProblem(f"a family named {family.name!r} is registered already")
    taken = {c.format for f in _REGISTRY.values() if f is not old for c in f.codecs}
    clash = taken & {c.format for c in family.codecs}
    if clash:
        raise InvalidProblem(f"file format {sorted(clash)[0]!r} belongs to another family")
    _REGISTRY[family.name] = family
    return family


def unregister(name: str) -> None:
    """Remove a family (tests register throw-away families and remove them)."""
    _REGISTRY.pop(name, None)


def _load_builtin() -> None:
    """Load the families declared under :data:`ENTRY_POINT_GROUP` (once; other threads wait)."""
    global _LOADED, _loading_now
    if _LOADED:
        return
    with _LOADING:
        if _LOADED or _loading_now:
            return
        _loading_now = True
        try:
            for i, ep in enumerate(_entry_points()):
                _ORDER.setdefault(ep.name, i)
                if ep.name not in _REGISTRY:
                    _load_entry(ep)
        finally:
            _loading_now = False
            _LOADED = True


class EntryPoint(NamedTuple):
    """One entry point of :data:`ENTRY_POINT_GROUP`: ``name = module:attribute``."""

    name: str
    value: str

    def load(self) -> Any:
        """Import the module and return the attribute (as :meth:`importlib.metadata.EntryPoint.load`)."""
        module, _, attr = self.value.partition(":")
        obj = importlib.import_module(module.strip())
        for part in filter(None, attr.strip().split(".")):
            obj = getattr(obj, part)
        return obj


def _entry_points() -> list[EntryPoint]:
    """The entry points of :data:`ENTRY_POINT_GROUP`, by name: from :data:`SCAN_CACHE` while it
    holds, else scanned (and cached). The cache keeps a scan for each of the last
    :data:`_SCANS_KEPT` ``sys.path`` lists (the console script's, ``python -c``'s, ...)."""
    path, key = json.dumps(sys.path), [_installed(entry) for entry in sys.path]
    try:
        scans = dict(_read_json(SCAN_CACHE, []))
    except (ValueError, TypeError):
        scans = {}  # an unreadable cache
    scan = scans.get(path)
    if isinstance(scan, dict) and scan.get("key") == key:
        return [EntryPoint(name, value) for name, value in scan["entry_points"]]
    from importlib.metadata import entry_points

    found = sorted(EntryPoint(ep.name, ep.value) for ep in entry_points(group=ENTRY_POINT_GROUP))
    scans.pop(path, None)
    scans[path] = {"key": key, "entry_points": found}
    _write_json(SCAN_CACHE, list(scans.items())[-_SCANS_KEPT:])  # a read-only installation: scanned every time
    return found


def _installed(path: str) -> list | int | None:
    """What :mod:`importlib.metadata` would read in a ``sys.path`` entry (``""``: the working
    folder), as a cache key: each ``.dist-info``/``.egg-info`` entry with its modification time
    (ns; reinstalling writes it anew); a file (a zip), its own time; ``None`` if absent."""
    try:
        if not os.path.isdir(path or "."):
            return os.stat(path).st_mtime_ns
        with os.scandir(path or ".") as it:
            return sorted([e.name, e.stat().st_mtime_ns] for e in it if e.name.endswith((".dist-info", ".egg-info")))
    except OSError:
        return None


def _load_entry(ep: EntryPoint) -> None:
    """Import one entry point's family (its facade registers it) and record it."""
    fam = ep.load()
    if not isinstance(fam, Family):
        raise InternalError(f"entry point {ep.value} is not a tilesolve Family")
    _REGISTRY.setdefault(fam.name, fam)


def families() -> list[Family]:
    """Every registered family: those of the entry points in their order (by name), then any
    registered otherwise, in registration order."""
    _load_builtin()
    return sorted(_REGISTRY.values(), key=lambda f: _ORDER.get(f.name, len(_ORDER)))


def commands() -> dict[str, str]:
    """Every family's commands, name -> ``"module:attribute"`` (a command two families name is
    the later family's, in the order of :func:`families`).

    A command that is not named like its family (``sample``, ``wall``) would otherwise load every
    facade to be found. The commands of the entry points' families are therefore cached
    (:data:`COMMAND_CACHE`), each under its entry point and its facade's source file (path,
    size, modification time): while every entry point's facade is unchanged, they are read from
    there and no facade is imported; otherwise every family is loaded and the cache rewritten.
    A family built in another file than its entry point's module is not watched there: after
    editing that file, reinstall."""
    eps = _entry_points()
    cached = _read_json(COMMAND_CACHE, {})
    cached = cached if isinstance(cached, dict) else {}
    lists: list | None = []
    for ep in eps:
        fam = _REGISTRY.get(ep.name)
        if fam is not None:
            lists.append(list(fam.commands))
            continue
        hit = cached.get(ep.value)
        if not isinstance(hit, dict) or hit.get("source") != _source(ep) or hit.get("source") is None:
            lists = None
            break
        lists.append(hit["commands"])
    if lists is None:
        fams = families()
        lists = [list(fam.commands) for fam in fams]
        by_name = {fam.name: fam for fam in fams}
        _write_json(COMMAND_CACHE, {ep.value: {"source": _source(ep), "commands": list(by_name[ep.name].commands)}
                                    for ep in eps if ep.name in by_name})
    else:
        named = {ep.name for ep in eps}
        lists += [list(fam.commands) for fam in _REGISTRY.values() if fam.name not in named]
    return {t.split(":")[1]: t for targets in lists for t in targets}


def _source(ep: EntryPoint) -> list | None:
    """The entry point's module file, its size and modification time (ns); None if unknown."""
    import importlib.util

    try:
        spec = importlib.util.find_spec(ep.value.partition(":")[0].strip())
        st = os.stat(spec.origin)
    except (ImportError, ValueError, AttributeError, TypeError, OSError):
        return None
    return [spec.origin, st.st_size, st.st_mtime_ns]


def _read_json(path: str, default: Any) -> Any:
    try:
        with open(path, encoding="utf-8") as fh:
            return json.load(fh)
    except (OSError, ValueError):
        return default


def _write_json(path: str, value: Any) -> None:
    """Write ``value`` to ``path`` whole or not at all (a read-only installation: not at all)."""
    tmp = f"{path}.{os.getpid()}.tmp"
    try:
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(tmp, "w", encoding="utf-8") as fh:
            json.dump(value, fh)
        os.replace(tmp, path)
    except OSError:
        try:
            os.remove(tmp)
        except OSError:
            pass


def get(name: str) -> Family:
    """The family called ``name`` (only its own entry point is loaded, if it is not registered yet)."""
    if name in _REGISTRY:
        return _REGISTRY[name]
    if not _LOADED:
        for ep in _entry_points():
            if ep.name == name:
                _load_entry(ep)
        if name in _REGISTRY:
            return _REGISTRY[name]
    _load_builtin()
    try:
        return _REGISTRY[name]
    except KeyError:
        raise InvalidProblem(f"unknown family {name!r}; known: {', '.join(_REGISTRY)}") from None


def family_of(problem: Any) -> Family:
    """The family whose problem type ``problem`` is."""
    for fam in list(_REGISTRY.values()):  # usually registered already, by importing its facade
        if isinstance(problem, fam.problem_type):
            return fam
    for fam in families():
        if isinstance(problem, fam.problem_type):
            return fam
    raise InvalidProblem(f"no tilesolve family solves a {type(problem).__name__}")


def codec_of(fmt: str) -> tuple[Family, Codec]:
    """The family and codec of a file format name."""
    for fam in families():
        for c in fam.codecs:
            if c.format == fmt:
                return fam, c
    known = sorted(c.format for f in families() for c in f.codecs)
    raise InvalidProblem(f"unknown format {fmt!r}; this tilesolve reads {', '.join(known)}")


def iter_demos() -> Iterable[tuple[Family, Demo]]:
    """Every family's demos, family by family."""
    for fam in families():
        for d in fam.demos:
            yield fam, d


def backend_report() -> tuple[list[tuple[str, ...]], list[tuple[str, ...]], bool]:
    """What ``tilesolve backends`` prints: ``(backend rows, route rows, a required backend is
    missing)``; backend rows are (name, kind, installed, version or reason, used by), route
    rows (family, route, what it does)."""
    from tilesolve.engine.backends import OTHER_BACKENDS, dist_version, probe, sat_backends

    rows = []
    pysat = f"python-sat {dist_version('python-sat')}"
    sat = sat_backends()
    for name, ok, used_by in sat:
        rows.append((name, "SAT", "yes" if ok else "no", pysat if ok else "not in this python-sat build", used_by))
    missing = not any(ok for _, ok, _ in sat)
    for b in OTHER_BACKENDS:
        ok, info = probe(b)
        missing |= not ok and not b.optional
        rows.append((b.name, b.kind, "yes" if ok else ("no (optional)" if b.optional else "NO"), info, b.used_by))
    routes = [(fam.name, route, fam.route_help.get(route, "")) for fam in families() for route in fam.routes]
    return rows, routes, missing
