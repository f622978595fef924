"""MkDocs hooks (``hooks:`` in mkdocs.yml): the pages made by running tilesolve while the site is
built, so that every command shown runs as written and every picture is the one it makes.

- **Run blocks.** A fenced block whose info string is ``tilesolve-run`` holds shell commands, one
  a line. Each page's blocks run in order, in a fresh empty folder of the page's own, through the
  installed console script; the block becomes a ``console`` block with each command and what it
  printed (stdout and stderr). A command must exit 0, or the code its trailing comment names
  (``... # unsat: exit 1``); otherwise the build fails. The pictures the commands write
  (``.svg``, ``.png``) are published beside the page: ``tutorials/dappled.md`` shows ``t.svg``
  as ``![...](dappled/t.svg)``.
- **Tutorials.** One page a family of the registry (:func:`tilesolve.family.families`), in its
  order, at ``tutorials/<family>.md``; a family without a written page gets one made from its
  demos and its commands' ``--help``. Other pages in ``tutorials/`` follow.
- **Gallery.** ``tilesolve demo`` draws every family's demos; ``hooks/gallery.yml`` adds
  commands for the families that need more (or have no demo). A family of the registry without
  a picture, or a key of ``gallery.yml`` that is no family, fails the build.
- **Docstrings.** The docstrings' reStructuredText roles (``:class:`~tilesolve.family.Family```)
  are shown as code (``Family``), in the API pages and everywhere else.
- **Reference.** The command-line reference (``cli.md``) and the man page (``man/tilesolve.1``)
  are generated from the click commands (:mod:`reference`); the API pages of the families
  (``api/families.md``) from the registry's entry points.

The commands run in ``$TILESOLVE_DOCS_WORK`` when it is set (kept, for a look at what they
wrote), else in a temporary folder removed after the build.
"""

from __future__ import annotations

import importlib.metadata
import logging
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

import yaml
from markdown import Extension
from markdown.preprocessors import Preprocessor
from mkdocs.exceptions import PluginError
from mkdocs.plugins import event_priority
from mkdocs.structure.files import File, Files

sys.path.insert(0, str(Path(__file__).parent))
import reference  # noqa: E402  (beside this file; MkDocs loads hooks by path)

log = logging.getLogger("mkdocs.hooks.tilesolve")

HERE = Path(__file__).parent
ROLE = re.compile(r":(?:class|func|meth|attr|mod|data|exc|obj|ref|doc):`(~?)([^`]+)`")
RUN_BLOCK = re.compile(r"^```tilesolve-run[^\n]*\n(.*?)^```[ \t]*$", re.M | re.S)
EXPECTED_EXIT = re.compile(r"#.*\bexit (\d+)\s*$")
PICTURES = (".svg", ".png")
#: Lines of a command's output shown on the page; the rest is counted.
MAX_LINES = 30
#: A guard against a hung command (a build, not a test): seconds a command may take.
COMMAND_TIMEOUT = 600

_state: dict = {}


@dataclass
class Run:
    """One command run for a page: the command, its exit code and what it printed."""

    command: str
    code: int
    output: str
    seconds: float


@dataclass
class PageRuns:
    """The runs of one page's blocks, block by block, and the pictures they wrote."""

    blocks: list[list[Run]]
    pictures: list[Path] = field(default_factory=list)


def _families():
    from tilesolve.family import families

    return list(families())


def _work() -> Path:
    return _state["work"]


def _environment() -> dict[str, str]:
    """The commands' environment: this Python's ``tilesolve`` first on the PATH, 100 columns."""
    env = dict(os.environ, COLUMNS="100")
    env["PATH"] = os.pathsep.join([str(Path(sys.executable).parent), env.get("PATH", "")])
    return env


def _commands(block: str) -> list[str]:
    """The commands of a run block: one a line (a trailing backslash continues it), blank lines
    skipped."""
    return [c.strip() for c in block.replace("\\\n", " ").splitlines() if c.strip()]


def run_commands(commands: list[str], cwd: Path, where: str) -> list[Run]:
    """Run ``commands`` in ``cwd`` with bash, in order; a command that does not exit with its
    expected code (0, or its comment's ``exit N``) fails the build, naming ``where``."""
    runs = []
    for command in commands:
        match = EXPECTED_EXIT.search(command)
        expected = int(match.group(1)) if match else 0
        started = time.perf_counter()
        try:
            proc = subprocess.run(["bash", "-c", command], cwd=cwd, env=_environment(), stdin=subprocess.DEVNULL,
                                  stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                                  timeout=COMMAND_TIMEOUT)
        except subprocess.TimeoutExpired:
            raise PluginError(f"{where}: `{command}` ran past {COMMAND_TIMEOUT} s") from None
        seconds = time.perf_counter() - started
        if proc.returncode != expected:
            raise PluginError(f"{where}: `{command}` exited {proc.returncode}, not {expected}:\n{proc.stdout[-3000:]}")
        runs.append(Run(command, proc.returncode, proc.stdout.rstrip(), seconds))
        log.debug("%s: %.1f s: %s", where, seconds, command)
    return runs


def _console(runs: list[Run]) -> str:
    """A run block's replacement: a ``console`` block of the commands and their outputs."""
    out = ["```console"]
    for r in runs:
        out.append(f"$ {r.command}")
        lines = r.output.splitlines()
        out += lines[:MAX_LINES]
        if len(lines) > MAX_LINES:
            out.append(f"... ({len(lines) - MAX_LINES} more lines)")
        if r.code:
            out.append(f"[exit {r.code}]")
    out.append("```")
    return "\n".join(out)


def _add(files: Files, config, src_uri: str, *, content: str | None = None, path: Path | None = None) -> None:
    """Add a generated page or picture to the site (replacing a file of that name)."""
    old = files.get_file_from_path(src_uri)
    if old is not None:
        files.remove(old)
    if content is not None:
        files.append(File.generated(config, src_uri, content=content))
    else:
        files.append(File.generated(config, src_uri, abs_src_path=str(path)))


def _run_page(src_uri: str, blocks: list[str]) -> PageRuns:
    """Run the blocks of one page in its own folder; list the pictures they wrote."""
    cwd = _work() / "pages" / src_uri[:-len(".md")]
    cwd.mkdir(parents=True)
    page = PageRuns([run_commands(_commands(block), cwd, src_uri) for block in blocks])
    page.pictures = sorted(p for p in cwd.rglob("*") if p.suffix in PICTURES and p.is_file())
    return page


def _tutorial_stub(fam) -> str:
    """The page of a family without a written tutorial: its demos and its commands' help."""
    names = [c.partition(":")[2] for c in fam.commands]
    out = [f"# {fam.name}", "", fam.title[:1].upper() + fam.title[1:] + ".", ""]
    if fam.demos:
        out += ["## Demos", "", f"Drawn by `tilesolve demo --family {fam.name}` (see the [gallery](../gallery.md)).", ""]
        out += [f"![{d.caption}](../gallery/{d.name}.svg)\n\n*{d.caption}*\n" for d in fam.demos]
    if names:
        out += ["## Commands", "", "```tilesolve-run", *(f"tilesolve {n} --help" for n in names), "```", ""]
    return "\n".join(out)


def _gallery(files: Files, config) -> None:
    """Draw the gallery (every family's demos and ``gallery.yml``'s commands) and write its page."""
    folder = _work() / "gallery"
    folder.mkdir()
    started = time.perf_counter()
    run_commands(["tilesolve demo --out . --seed 1"], folder, "gallery")
    extra = yaml.safe_load((HERE / "gallery.yml").read_text(encoding="utf-8")) or {}
    out = [
        "# Gallery",
        "",
        "Every picture on this page was drawn while this site was built, by the command under it, "
        "and checked by the family's verifier on the way. One section a family of the registry.",
        "",
    ]
    unknown = sorted(set(extra) - {f.name for f in _families()})
    if unknown:
        raise PluginError(f"gallery.yml: {unknown[0]!r} is no family of the registry")
    for fam in _families():
        items = [(f"{d.name}.svg", d.caption, f"tilesolve demo --family {fam.name}") for d in fam.demos]
        items += _run_items(extra.get(fam.name, []), folder, fam.name)
        items = [item for item in items if (folder / item[0]).is_file()]
        if not items:
            raise PluginError(f"gallery: family {fam.name!r} has no picture (no demo and nothing in gallery.yml)")
        out += _section(files, config, fam.name, f"{fam.title[:1].upper()}{fam.title[1:]}. "
                        f"[Tutorial](tutorials/{fam.name}.md).", items, folder)
    _add(files, config, "gallery.md", content="\n".join(out))
    log.info("gallery: %d families drawn in %.1f s", len(_families()), time.perf_counter() - started)


def _run_items(items: list[dict], folder: Path, where: str) -> list[tuple[str, str, str]]:
    """Run the commands of ``gallery.yml``'s ``items`` in ``folder``; ``(file, caption, command)``
    of each (a command that does not write its file fails the build)."""
    out = []
    for item in items:
        run_commands([item["command"]], folder, f"gallery ({where})")
        if not (folder / item["file"]).is_file():
            raise PluginError(f"gallery ({where}): `{item['command']}` did not write {item['file']}")
        out.append((item["file"], item["caption"], item["command"]))
    return out


def _section(files: Files, config, heading: str, about: str, items: list[tuple[str, str, str]],
             folder: Path) -> list[str]:
    """The gallery's section ``heading``: ``about``, then each picture with its caption and command."""
    out = [f"## {heading}", "", about, "", '<div class="gallery" markdown>', ""]
    for name, caption, command in items:
        _add(files, config, f"gallery/{name}", path=folder / name)
        out += ['<figure markdown>', "", f"![{caption}](gallery/{name})", "",
                f"<figcaption>{caption}<br><code>{_html(command)}</code></figcaption>", "", "</figure>", ""]
    return out + ["</div>", ""]


def _html(text: str) -> str:
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def _api_families() -> str:
    """The API page of the family facades: one section a registry entry point's module."""
    points = sorted(importlib.metadata.entry_points(group="tilesolve.families"), key=lambda ep: ep.name)
    out = ["# Families", "", "The facade of each family in the registry: its routes, `solve` and helpers.", ""]
    for ep in points:
        out += [f"::: {ep.value.partition(':')[0]}", ""]
    return "\n".join(out)


class SphinxRoles(Extension):
    """Show reStructuredText roles as code: ``:func:`~a.b.solve``` as ``solve``, ``:mod:`a.b```
    as ``a.b`` (after the code blocks are put aside, so their text stays as written)."""

    class _Roles(Preprocessor):
        def run(self, lines: list[str]) -> list[str]:
            return ROLE.sub(_role, "\n".join(lines)).split("\n")

    def extendMarkdown(self, md) -> None:  # noqa: N802 (Markdown's name)
        md.preprocessors.register(self._Roles(md), "sphinx_roles", 20)


def _role(m: re.Match) -> str:
    tilde, target = m.groups()
    return f"`{target.rpartition('.')[2] if tilde else target}`"


@event_priority(100)  # before mkdocstrings reads the Markdown extensions
def on_config(config):
    """Make the work folder, fill the Tutorials section of the navigation from the registry and
    add :class:`SphinxRoles` to the Markdown extensions."""
    config.markdown_extensions.append(SphinxRoles())
    kept = os.environ.get("TILESOLVE_DOCS_WORK")
    work = Path(kept) if kept else Path(tempfile.mkdtemp(prefix="tilesolve-docs-"))
    if kept and work.exists():
        shutil.rmtree(work)
    work.mkdir(parents=True, exist_ok=True)
    _state.update(work=work, kept=bool(kept), runs={}, started=time.perf_counter())
    docs = Path(config["docs_dir"])
    names = [f.name for f in _families()]
    others = sorted(p.stem for p in (docs / "tutorials").glob("*.md") if p.stem not in names and p.stem != "index")
    tutorials = ["tutorials/index.md"] + [{n: f"tutorials/{n}.md"} for n in names + others]
    for item in config["nav"]:
        if isinstance(item, dict) and "Tutorials" in item:
            item["Tutorials"] = tutorials
    return config


def on_files(files: Files, config) -> Files:
    """Generate the pages (tutorials of families without one, gallery, CLI reference, family API),
    the man page, and run every page's blocks."""
    for fam in _families():
        if files.get_file_from_path(f"tutorials/{fam.name}.md") is None:
            _add(files, config, f"tutorials/{fam.name}.md", content=_tutorial_stub(fam))
    _gallery(files, config)
    _add(files, config, "cli.md", content=reference.cli_markdown())
    _add(files, config, "man/tilesolve.1", path=reference.write_man_page(_work() / "man"))
    _add(files, config, "api/families.md", content=_api_families())
    started = time.perf_counter()
    pages = {f.src_uri: RUN_BLOCK.findall(f.content_string) for f in files.documentation_pages()}
    pages = {src: blocks for src, blocks in pages.items() if blocks}
    with ThreadPoolExecutor(max_workers=min(4, os.cpu_count() or 1)) as pool:  # pages are independent
        _state["runs"] = dict(zip(pages, pool.map(_run_page, pages, pages.values())))
    for src_uri, page in _state["runs"].items():
        folder = _work() / "pages" / src_uri[:-len(".md")]
        for picture in page.pictures:
            _add(files, config, f"{src_uri[:-len('.md')]}/{picture.relative_to(folder).as_posix()}", path=picture)
    n = sum(len(b) for page in _state["runs"].values() for b in page.blocks)
    log.info("run blocks: %d commands on %d pages in %.1f s", n, len(_state["runs"]), time.perf_counter() - started)
    return files


def on_page_markdown(markdown: str, page, config, files) -> str:
    """Replace the page's run blocks by the commands and their outputs."""
    runs = _state["runs"].get(page.file.src_uri)
    if runs is None:
        return markdown
    blocks = iter(runs.blocks)
    return RUN_BLOCK.sub(lambda _: _console(next(blocks)), markdown)


def on_post_build(config) -> None:
    """Remove the work folder unless ``$TILESOLVE_DOCS_WORK`` asked to keep it."""
    log.info("tilesolve docs: built in %.1f s", time.perf_counter() - _state["started"])
    if not _state["kept"]:
        shutil.rmtree(_work(), ignore_errors=True)

