"""The documentation site (mkdocs.yml, docs/): the man page and shell completion (fast), and the
whole site built with ``--strict`` (slow): a gallery picture per family, a tutorial per family,
every command in the command-line reference."""

from __future__ import annotations

import importlib.util
import re
import subprocess
import sys
from html import unescape
from pathlib import Path

import pytest

from clitools import ENV, SCRIPT
from tilesolve.family import families

ROOT = Path(__file__).resolve().parents[1]


def _reference():
    """docs/hooks/reference.py (the hooks are loaded by path, as MkDocs loads them)."""
    spec = importlib.util.spec_from_file_location("docs_reference", ROOT / "docs" / "hooks" / "reference.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _help_commands(*path: str) -> list[tuple[str, ...]]:
    """Every command path below ``tilesolve PATH`` as the console script's ``--help`` lists them."""
    proc = subprocess.run([SCRIPT, *path, "--help"], capture_output=True, text=True, env=ENV)
    assert proc.returncode == 0, proc.stderr
    found = [tuple(path)]
    in_list = False
    for line in proc.stdout.splitlines():
        if re.match(r"^(Commands|Family commands|Tools):$", line.strip()) and not line.startswith("    "):
            in_list = True
            continue
        m = re.match(r"^  ([a-z][a-z0-9-]*)(  |$)", line)
        if in_list and m:
            found += _help_commands(*path, m.group(1))
        elif in_list and line and not line.startswith("   "):
            in_list = False
    return found


def test_reference_and_man_page_have_every_command():
    reference = _reference()
    proc = subprocess.run([SCRIPT, "--help"], capture_output=True, text=True, env=ENV)
    top = {m.group(1) for m in re.finditer(r"^  ([a-z][a-z0-9-]*)  ", proc.stdout, re.M)}
    paths = {path for path, _ in reference.commands()}
    assert {p[1] for p in paths if len(p) == 2} == top
    assert ("tilesolve", "dappled", "solve") in paths and ("tilesolve", "export", "dimacs") in paths
    markdown, man = reference.cli_markdown(), reference.man_page()
    for path in paths:
        assert re.search(rf"^#+ {' '.join(path)}$", markdown, re.M), path
        assert '.SS "%s"' % " ".join(path) in man, path


def test_the_reference_shows_each_command_help_verbatim():
    proc = subprocess.run([SCRIPT, "dappled", "solve", "--help"], capture_output=True, text=True, env=ENV)
    assert proc.returncode == 0
    markdown = _reference().cli_markdown()
    section = markdown.split("## tilesolve dappled\n", 1)[1].split("### tilesolve dappled solve\n", 1)[1]
    shown = section.split("```text\n", 1)[1].split("\n```", 1)[0]
    assert shown == proc.stdout.rstrip()


def test_man_page_is_written_and_renders_without_warnings(tmp_path):
    path = _reference().write_man_page(tmp_path / "man")
    assert path == tmp_path / "man" / "tilesolve.1"
    text = path.read_text(encoding="utf-8")
    assert text.startswith(".TH TILESOLVE 1 ")
    assert text.isascii()  # other characters are written as roff escapes
    assert not re.search(r"^[.'](?!TH|SH|SS|nf|fi|B )", text, re.M)  # no help line read as a request
    proc = subprocess.run(  # groff: scripts/test.sh installs it (Debian's groff-base) when missing
        ["groff", "-man", "-ww", "-Tutf8", str(path)], capture_output=True, text=True)
    assert proc.returncode == 0 and proc.stderr == "", proc.stderr
    assert "tilesolve dappled solve --size 12x8" in proc.stdout.replace("\u2010", "-")


@pytest.mark.parametrize("shell, marker", [
    ("bash", "complete -o nosort -F _tilesolve_completion tilesolve"),
    ("zsh", "compdef _tilesolve_completion tilesolve"),
    ("fish", "complete --no-files --command tilesolve"),
])
def test_console_script_prints_the_completion_script(shell, marker):
    proc = subprocess.run([SCRIPT], capture_output=True, text=True,
                          env=dict(ENV, _TILESOLVE_COMPLETE=f"{shell}_source"))
    assert proc.returncode == 0, proc.stderr
    assert marker in proc.stdout
    assert proc.stderr == ""


@pytest.mark.parametrize("words, cword, expected", [
    ("tilesolve dap", 1, "plain,dappled"),
    ("tilesolve dappled so", 2, "plain,solve"),
    ("tilesolve dappled solve --cy", 3, "plain,--cyclic"),
    ("tilesolve pack --kind ", 3, "plain,corner\nplain,wang"),
])
def test_console_script_completes_commands_options_and_choices(words, cword, expected):
    env = dict(ENV, _TILESOLVE_COMPLETE="bash_complete", COMP_WORDS=words, COMP_CWORD=str(cword))
    proc = subprocess.run([SCRIPT], capture_output=True, text=True, env=env)
    assert proc.returncode == 0, proc.stderr
    assert sorted(proc.stdout.split()) == expected.split("\n")


@pytest.fixture(scope="module")
def site(tmp_path_factory) -> Path:
    """The site built with ``--strict`` (warnings are errors) into a temporary folder. Its pages
    are ``NAME.html`` files (the offline plugin: the site works from ``file://``)."""
    site = tmp_path_factory.mktemp("docs") / "site"
    proc = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "-d", str(site)], cwd=ROOT,
                          capture_output=True, text=True, env=dict(ENV, NO_MKDOCS_2_WARNING="1"))
    assert proc.returncode == 0, proc.stderr[-5000:]
    assert "WARNING" not in proc.stderr, proc.stderr[-5000:]
    return site


def _sections(html: str) -> dict[str, str]:
    """The ``<h2>`` sections of a page by their id."""
    parts = re.split(r'<h2 id="([^"]+)"', html)
    return dict(zip(parts[1::2], parts[2::2]))


@pytest.mark.slow
def test_gallery_has_a_picture_of_every_family(site):
    sections = _sections((site / "gallery.html").read_text(encoding="utf-8"))
    names = [f.name for f in families()]
    assert set(names) <= set(sections), set(names) - set(sections)
    for name in names:
        pictures = re.findall(r'<img[^>]* src="([^"]+)"', sections[name])
        assert pictures, name
        for src in pictures:
            picture = (site / unescape(src)).resolve()
            assert picture.is_file() and picture.stat().st_size > 100, (name, src)


@pytest.mark.slow
def test_site_has_a_tutorial_per_family_with_its_outputs(site):
    for fam in families():
        page = site / "tutorials" / f"{fam.name}.html"
        html = page.read_text(encoding="utf-8")
        assert "tilesolve-run" not in html, fam.name  # every run block was replaced by its run
        assert "$ tilesolve " in unescape(re.sub(r"<[^>]+>", "", html)), fam.name
    for picture in re.findall(r'<img[^>]* src="([^"]+)"',
                              (site / "tutorials" / "dappled.html").read_text(encoding="utf-8")):
        assert (site / "tutorials" / unescape(picture)).resolve().is_file(), picture


@pytest.mark.slow
def test_site_reference_lists_every_command_and_ships_the_man_page(site):
    html = (site / "cli.html").read_text(encoding="utf-8")
    headings = {unescape(re.sub(r"<[^>]+>", "", h)).strip().rstrip("¶").strip()
                for h in re.findall(r"<h[2-6][^>]*>(.*?)</h[2-6]>", html, re.S)}
    listed = {" ".join(("tilesolve", *p)) for p in _help_commands()}
    assert listed <= headings, listed - headings
    assert (site / "man" / "tilesolve.1").read_text(encoding="utf-8").startswith(".TH TILESOLVE 1 ")
    api = (site / "api" / "families.html").read_text(encoding="utf-8")
    assert "tilesolve.families.dappled" in api


def test_gallery_sections_are_families():
    import yaml

    extra = yaml.safe_load((ROOT / "docs" / "hooks" / "gallery.yml").read_text(encoding="utf-8"))
    assert set(extra) <= {f.name for f in families()}
    assert all({"file", "caption", "command"} <= set(item) for items in extra.values() for item in items)


@pytest.mark.slow
def test_gallery_shows_poisson_disks_a_stippled_image_and_the_spectra(site):
    sections = _sections((site / "gallery.html").read_text(encoding="utf-8"))
    shown = {name: re.findall(r'<img[^>]* src="gallery/([^"]+)"', sections[name]) for name in ("poisson", "stipple")}
    assert {"poisson-window.svg", "poisson-spectrum.svg"} <= set(shown["poisson"])
    assert {"stipple.svg", "stipple-gradient.svg", "importance-spectrum.svg"} <= set(shown["stipple"])
    for name in ("poisson-window.svg", "stipple-gradient.svg"):  # thousands of dots
        assert (site / "gallery" / name).stat().st_size > 50_000, name
    for name in ("poisson-spectrum.svg", "importance-spectrum.svg"):  # the curves
        assert (site / "gallery" / name).read_text(encoding="utf-8").count("<polyline") >= 4, name
    page = (site / "tutorials" / "stipple.html").read_text(encoding="utf-8")
    assert "$ tilesolve sample stipple " in unescape(re.sub(r"<[^>]+>", "", page))
