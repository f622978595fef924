"""The command-line reference of the documentation site and the man pages, both generated from
tilesolve's click commands (:data:`tilesolve.cli.group.main_group`), so neither can drift from
``--help``.

:func:`cli_markdown` writes one section per command with its ``--help`` text, exactly as a
terminal of :data:`WIDTH` columns shows it; :func:`write_man_pages` writes ``tilesolve.1`` and
one page per subcommand (``tilesolve-dappled-solve.1``) with click-man.

Examples
--------
>>> paths = [" ".join(path) for path, _ in commands()]
>>> "tilesolve dappled solve" in paths and paths[0] == "tilesolve"
True
"""

from __future__ import annotations

from pathlib import Path
from typing import Iterator

import click

#: The terminal width the help texts are formatted for: click wraps them at 80 columns (its
#: ``max_content_width``) on any terminal this wide or wider.
WIDTH = 100


def _root() -> click.Group:
    from tilesolve.cli.group import main_group

    return main_group


def commands() -> Iterator[tuple[tuple[str, ...], click.Context]]:
    """Every command of ``tilesolve``, depth first in the order ``--help`` lists them: its path
    (``("tilesolve", "dappled", "solve")``) and a click context to format its help with."""

    def context(cmd: click.Command, name: str, parent: click.Context | None) -> click.Context:
        # as make_context, without parsing; click leaves a terminal's last two columns free
        settings = {"terminal_width": WIDTH - 2, **cmd.context_settings}
        return click.Context(cmd, info_name=name, parent=parent, **settings)

    def walk(ctx: click.Context, path: tuple[str, ...]):
        yield path, ctx
        cmd = ctx.command
        if isinstance(cmd, click.Group):
            for name in cmd.list_commands(ctx):
                yield from walk(context(cmd.get_command(ctx, name), name, ctx), path + (name,))

    yield from walk(context(_root(), "tilesolve", None), ("tilesolve",))


def cli_markdown() -> str:
    """The command-line reference page: a heading per command (nested as the commands are) and
    its ``--help`` text verbatim."""
    out = [
        "# Command-line reference",
        "",
        "Every command of `tilesolve`, with the text its `--help` prints. This page is generated "
        "from the commands themselves when the site is built, as is the [man page](man.md).",
        "",
    ]
    for path, ctx in commands():
        level = min(len(path) + 1, 6)
        out += [f"{'#' * level} {' '.join(path)}", "", "```text", ctx.get_help().rstrip(), "```", ""]
    return "\n".join(out)


def _roff(text: str) -> str:
    """``text`` as roff: backslashes and hyphens escaped, other characters than ASCII written as
    ``\\[uXXXX]``, control characters at a line's start neutralised."""
    text = text.replace("\\", "\\e").replace("-", "\\-")
    text = "".join(c if c.isascii() else f"\\[u{ord(c):04X}]" for c in text)
    lines = []
    for line in text.splitlines():
        lines.append("\\&" + line if line.startswith((".", "'")) else line)
    return "\n".join(lines)


def man_page() -> str:
    """``tilesolve.1``: the whole command line in one man page (section 1): the synopsis, then
    every command's ``--help`` text, preformatted, under its own subsection."""
    from tilesolve import __version__

    root = _root()
    out = [
        f'.TH TILESOLVE 1 "" "tilesolve {__version__}" "User Commands"',
        ".SH NAME",
        "tilesolve \\- " + _roff(root.help.strip().splitlines()[0].partition(": ")[2]),
        ".SH SYNOPSIS",
        ".B tilesolve",
        "[OPTIONS] COMMAND [ARGS]...",
        ".SH COMMANDS",
        "Every command with the text its \\fB\\-\\-help\\fR prints.",
    ]
    for path, ctx in commands():
        out += [f'.SS "{" ".join(path)}"', ".nf", _roff(ctx.get_help().rstrip()), ".fi"]
    out += [
        ".SH SHELL COMPLETION",
        "Bash: add \\fBeval \"$(_TILESOLVE_COMPLETE=bash_source tilesolve)\"\\fR to \\fI~/.bashrc\\fR;",
        "zsh: \\fBzsh_source\\fR in \\fI~/.zshrc\\fR; fish: \\fBfish_source\\fR.",
    ]
    return "\n".join(out) + "\n"


def write_man_page(target: Path) -> Path:
    """Write :func:`man_page` to ``target/tilesolve.1`` (the folder is created if missing)."""
    target.mkdir(parents=True, exist_ok=True)
    path = target / "tilesolve.1"
    path.write_text(man_page(), encoding="utf-8")
    return path
