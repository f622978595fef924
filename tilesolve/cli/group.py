"""The ``tilesolve`` click group: one short module per command (rasterio ``rio`` style); the
console script's entry point, :func:`tilesolve.cli.main.main`, hands every command line but
``--version`` to :func:`run`.

Commands load lazily: the generic commands (:data:`GENERIC`: verify, draw, demo, export,
backends) serve every family through the registry (:mod:`tilesolve.family`); each family names
its own command groups (``Family.commands``, ``"module:attribute"``, the attribute being the
command's name). ``tilesolve --help`` lists the family commands first (the registry's), then
these tools. A command that serves no one family (a tool) goes in :data:`GENERIC`. Nothing is
imported before a command runs.

Every :class:`~tilesolve.errors.TilesolveError` becomes one line ``tilesolve: error: ...`` on
stderr and its ``exit_code``, and so does every usage error (exit 2); any other exception is a
bug: one line ``tilesolve: error: internal error: ...`` and exit 70, never a traceback. Ctrl-C
exits 130 and SIGTERM 143. Outputs are checked before any work and written together at the end
(:mod:`tilesolve.cli.outputs`), so bad input or an interruption leaves no file.
"""

from __future__ import annotations

import contextlib
import importlib
import logging
import os
import sys

import click

from tilesolve import __version__
from tilesolve.cli.common import CliError, usage_error
from tilesolve.cli.options import CONTEXT_SETTINGS, EXIT_HELP
from tilesolve.cli.outputs import interrupt_received, interruption, sigterm_as_interrupt
from tilesolve.errors import InternalError, TilesolveError
from tilesolve.io.atomic import remove_temporaries

__all__ = ["main_group", "run", "GENERIC"]


class TilesolveGroup(click.Group):
    """A click group that turns library errors into one-line messages and exit codes."""

    def invoke(self, ctx: click.Context):
        try:
            return super().invoke(ctx)
        except click.exceptions.NoArgsIsHelpError:
            raise  # a bare command group: its help, not an error
        except click.UsageError as exc:
            raise usage_error(exc) from None
        except TilesolveError as exc:
            raise CliError(str(exc), exc.exit_code) from None
        except KeyboardInterrupt:
            ctx.exit(_interrupted())
        except BrokenPipeError:  # e.g. `tilesolve ... | head`
            _quiet_stdout()
            ctx.exit(1)
        except OSError as exc:
            where = f"{exc.filename}: " if exc.filename else ""
            raise CliError(f"{where}{(exc.strerror or str(exc)).lower()}", 2) from None
        except (OverflowError, MemoryError) as exc:
            what = "a number is too large" if isinstance(exc, OverflowError) else "out of memory"
            raise CliError(f"{what} for this problem; try smaller sizes or numbers", 2) from None
        except (click.ClickException, click.exceptions.Exit, click.Abort):
            raise
        except SystemError as exc:  # Ctrl-C inside a compiled (numba) kernel comes back wrapped in one
            if isinstance(exc.__cause__, KeyboardInterrupt) or interrupt_received():
                ctx.exit(_interrupted())
            raise _internal(exc) from None
        except Exception as exc:  # noqa: BLE001 - any other exception is a bug: exit 70, one line
            if interrupt_received():  # the interruption's consequence (see interrupt_received)
                ctx.exit(_interrupted())
            raise _internal(exc) from None

    def list_commands(self, ctx: click.Context) -> list[str]:
        return list(_family_commands()) + list(GENERIC)  # families first, in registry order

    def format_commands(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        """Two sections: the families' commands (from the registry, in its order), then the tools."""
        sections = (("Family commands", list(_family_commands())), ("Tools", list(GENERIC)))
        width = max(len(name) for _, names in sections for name in names)
        for title, names in sections:
            commands = [(name, self.get_command(ctx, name)) for name in names]
            rows = [(name, cmd.get_short_help_str(formatter.width - 6 - width))
                    for name, cmd in commands if cmd is not None and not cmd.hidden]
            with formatter.section(title):
                formatter.write_dl(rows)

    def get_command(self, ctx: click.Context, name: str):
        target = GENERIC.get(name) or _family_command(name)
        if target is None:
            return None
        module, attr = target.split(":")
        return _verbosity_options(getattr(importlib.import_module(module), attr))


def _verbosity_options(cmd: click.Command) -> click.Command:
    """``cmd`` and its subcommands with ``-v``/``-q`` of their own (``tilesolve pack ... -q``),
    counted with those given before the command."""
    if not any(p.name == "quiet" for p in cmd.params):
        cmd.params += [click.Option(["-v", "--verbose"], count=True, expose_value=False, callback=_counted(1),
                                    help="More output (-v before the command counts too)."),
                       click.Option(["-q", "--quiet"], count=True, expose_value=False, callback=_counted(-1),
                                    help="Less output: no summary or progress on stderr (-q before the command counts too).")]
    for sub in getattr(cmd, "commands", {}).values():
        _verbosity_options(sub)
    return cmd


def _counted(sign: int):
    def callback(ctx: click.Context, param: click.Parameter, count: int) -> None:
        if count:
            root = ctx.find_root()
            _set_verbosity(root, root.ensure_object(dict).get("verbosity", 0) + sign * count)

    return callback


def _set_verbosity(ctx: click.Context, level: int) -> None:
    """``-v`` count minus ``-q`` count so far: kept for :func:`tilesolve.cli.common.verbosity`,
    and the log level (-q: errors; default: warnings; -v: info; -vv: debug)."""
    ctx.ensure_object(dict)["verbosity"] = level
    logging.basicConfig(stream=sys.stderr, format="tilesolve: %(levelname)s: %(message)s")
    logging.getLogger().setLevel(
        {-1: logging.ERROR, 0: logging.WARNING, 1: logging.INFO}.get(max(-1, min(level, 2)), logging.DEBUG))


#: Commands that serve every family through the registry: name -> "module:attribute".
GENERIC = {
    "verify": "tilesolve.cli.verify:verify",
    "draw": "tilesolve.cli.draw:draw",
    "export": "tilesolve.cli.export:export",
    "demo": "tilesolve.cli.demo:demo",
    "backends": "tilesolve.cli.backends:backends",
    "crosscheck": "tilesolve.cli.crosscheck:crosscheck",
    "render": "tilesolve.cli.render:render",
    "gpu": "tilesolve.cli.render:gpu",
    "wall-lines": "tilesolve.cli.wall_lines:wall_lines",
    "studio": "tilesolve.cli.studio:studio",
}


def _family_command(name: str) -> str | None:
    """The "module:attribute" of family command ``name`` (from the registry's cache of the
    families' commands: no facade is imported to find it)."""
    return _family_commands().get(name)


def _family_commands() -> dict[str, str]:
    """Every family's commands, name -> "module:attribute" (cached by the registry)."""
    from tilesolve.family import commands

    return commands()


@click.group(
    cls=TilesolveGroup,
    context_settings=CONTEXT_SETTINGS,
    epilog=EXIT_HELP,
)
@click.option("-v", "--verbose", count=True, help="More output (-vv: debug log).")
@click.option("-q", "--quiet", count=True, help="Less output: no summary or progress on stderr.")
@click.option("--max-input", metavar="SIZE", default=None,
              help="Read input files up to SIZE bytes (e.g. 512M, 2G; default 256M, or $TILESOLVE_MAX_INPUT); "
              "larger files, pipes and devices are refused.")
@click.version_option(__version__, "--version", prog_name="tilesolve", message="%(prog)s %(version)s")
@click.pass_context
def main_group(ctx: click.Context, verbose: int, quiet: int, max_input: str | None) -> None:
    """tilesolve: a tiling studio backed by SAT and constraint solvers.

    \b
    Start with:
      tilesolve demo                                    pictures of a few showcase problems
      tilesolve dappled solve --size 12x8 --cond H0=2 --cond V1=2 --svg t.svg
      tilesolve dappled solve --help                    options and condition syntax
    """
    _set_verbosity(ctx, verbose - quiet)
    if max_input is not None:
        from tilesolve.inputs import MAX_INPUT_ENV, parse_byte_size

        try:
            os.environ[MAX_INPUT_ENV] = str(parse_byte_size(max_input))
        except TilesolveError as exc:
            raise click.BadParameter(str(exc), param_hint="'--max-input'") from None


def _internal(exc: BaseException) -> CliError:
    """An unexpected exception as the one-line internal error of exit 70 (no file is left)."""
    remove_temporaries()
    logging.getLogger("tilesolve").debug("internal error", exc_info=exc)
    return CliError(str(InternalError(f"{type(exc).__name__}: {exc}")), InternalError.exit_code)


def _interrupted() -> int:
    """Ctrl-C (exit 130) or SIGTERM (exit 143): no file of this run is left."""
    remove_temporaries()
    code, what = interruption()
    click.echo(f"tilesolve: {what} (no file was written)", err=True)
    return code


def _quiet_stdout() -> None:
    """Standard output is a closed pipe: let the interpreter exit without flushing into it."""
    with contextlib.suppress(OSError, ValueError):
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())


def run(argv: list[str] | None, started: float | None = None) -> int:
    """Run one command line (``None``: ``sys.argv``); returns the exit code.

    Every error is one line ``tilesolve: error: ...`` (exit 2 for usage, 70 for an internal
    error); Ctrl-C exits 130 and SIGTERM 143, both leaving no file of this run. ``started``
    (a :func:`time.perf_counter` reading) is where a ``--time-limit`` counts from
    (:func:`tilesolve.cli.options.time_limit_opt`); ``None``: from the run's own beginning.
    """
    try:
        with sigterm_as_interrupt():
            rv = main_group.main(args=argv, prog_name="tilesolve", standalone_mode=False, obj={"started": started})
    except click.exceptions.NoArgsIsHelpError as exc:
        exc.show()
        return exc.exit_code
    except click.UsageError as exc:
        usage_error(exc).show()
        return 2
    except click.ClickException as exc:
        exc.show()
        return exc.exit_code
    except (click.Abort, KeyboardInterrupt):
        return _interrupted()
    except BrokenPipeError:
        _quiet_stdout()
        return 1
    except Exception as exc:  # noqa: BLE001 - raised outside a command (option parsing, help)
        err = _internal(exc)
        err.show()
        return err.exit_code
    return rv if isinstance(rv, int) else 0

