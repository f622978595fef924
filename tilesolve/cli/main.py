"""The ``tilesolve`` command: one click group, one short module per command (rasterio ``rio`` style).

Every :class:`~tilesolve.errors.TilesolveError` becomes one line ``tilesolve: error: ...`` on
stderr and its ``exit_code``; Ctrl-C before a result exits 130. Outputs are written
atomically and only after the inputs have been read and checked, so bad input leaves no file.
"""

from __future__ import annotations

import logging
import sys

import click

from tilesolve import __version__
from tilesolve.cli.common import CliError
from tilesolve.cli.options import CONTEXT_SETTINGS, EXIT_HELP
from tilesolve.errors import TilesolveError

__all__ = ["main_group", "main", "COMMANDS"]


class TilesolveGroup(click.Group):
    """A click group that turns library errors into one-line messages and exit codes."""

    def invoke(self, ctx: click.Context):
        try:
            return super().invoke(ctx)
        except TilesolveError as exc:
            raise CliError(str(exc), exc.exit_code) from None
        except KeyboardInterrupt:
            click.echo("tilesolve: interrupted (no file was written)", err=True)
            ctx.exit(130)
        except BrokenPipeError:  # e.g. `tilesolve ... | head`
            sys.stderr.close()
            ctx.exit(1)
        except OSError as exc:
            where = f"{exc.filename}: " if exc.filename else ""
            raise CliError(f"{where}{exc.strerror or exc}", 2) from None
        except MemoryError:
            raise CliError("out of memory; try a smaller grid", 2) from None

    def list_commands(self, ctx: click.Context) -> list[str]:
        return list(self.commands)  # in registration order, not alphabetical


@click.group(
    cls=TilesolveGroup,
    context_settings=CONTEXT_SETTINGS,
    epilog=EXIT_HELP,
)
@click.option("-v", "--verbose", count=True, help="More output (-vv: debug log).")
@click.option("-q", "--quiet", count=True, help="Less output: no summary on stderr.")
@click.version_option(__version__, "--version", prog_name="tilesolve", message="%(prog)s %(version)s")
@click.pass_context
def main_group(ctx: click.Context, verbose: int, quiet: int) -> None:
    """tilesolve: a tiling studio backed by SAT and constraint solvers.

    \b
    Start with:
      tilesolve demo                                    pictures of a few showcase problems
      tilesolve dappled solve --size 12x8 --cond H0=2 --cond V1=2 --svg t.svg
      tilesolve dappled solve --help                    options and condition syntax
    """
    level = verbose - quiet
    logging.basicConfig(
        stream=sys.stderr,
        level={-1: logging.ERROR, 0: logging.WARNING, 1: logging.INFO}.get(max(-1, min(level, 2)), logging.DEBUG),
        format="tilesolve: %(levelname)s: %(message)s",
    )
    ctx.obj = {"verbosity": level}


def _register() -> None:
    from tilesolve.cli.backends import backends
    from tilesolve.cli.brick import brick, wang
    from tilesolve.cli.dappled import dappled
    from tilesolve.cli.demo import demo
    from tilesolve.cli.export import export
    from tilesolve.cli.pack import pack
    from tilesolve.cli.tiles import tiles
    from tilesolve.cli.verify import verify

    for cmd in (dappled, pack, brick, wang, tiles, verify, export, demo, backends):
        main_group.add_command(cmd)


_register()

#: Registered commands by name.
COMMANDS = main_group.commands


def main(argv: list[str] | None = None) -> int:
    """Console-script entry point; returns the exit code."""
    try:
        return main_group.main(args=argv, prog_name="tilesolve", standalone_mode=True)
    except SystemExit as exc:
        code = exc.code
        return code if isinstance(code, int) else (0 if code is None else 1)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
