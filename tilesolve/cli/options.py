"""Option decorators and help texts shared by the commands (rasterio ``rio/options.py`` style).

Only options every family shares live here (no library import: ``tilesolve --version`` loads
nothing); each family's own options (``--method`` choices from its registry entry) live in its
command module.
"""

from __future__ import annotations

import math
from typing import Callable

import click

from tilesolve.cli.outputs import OutputFile


CONTEXT_SETTINGS = {"help_option_names": ["-h", "--help"], "max_content_width": 100}

#: Condition syntax, shown by every dappled command (``\b`` keeps click from re-wrapping).
CONDITION_HELP = """\b
Conditions (--cond, repeatable; dappled paper Def. 1.1):
  H0=2      no horizontal run of tile 0 longer than 2 cells
  V1=3      no vertical run of tile 1 longer than 3 cells
  H{0,2}=3  no horizontal run longer than 3 of cells whose tiles are in {0, 2}
  V1=inf    no limit (the paper's q = infinity)
Several may share one --cond, separated by commas or spaces: --cond "H0=2,V1=3".
Quote subsets, or the shell expands the braces: --cond 'H{0,2}=3'."""

#: Exit codes (DESIGN.md, "Errors").
EXIT_HELP = """\b
Exit codes:
  0  sat / optimal / ok
  1  unsat (proved), or the file has violations
  2  bad input or usage (one line on stderr, no file written)
  3  unknown: the time limit ran out (the unknown record is written)
  70  internal error: a bug in tilesolve (one line on stderr; please report it)
  130  interrupted (Ctrl-C): no file written, existing files untouched
  143  terminated (SIGTERM): no file written, existing files untouched"""

#: The input limit, shown by every command that reads files (tilesolve.inputs.read_input).
INPUT_HELP = """\b
Input files (and pipes or devices) are read up to 256 MiB; a larger input is refused
(exit 2). Raise the limit with tilesolve --max-input SIZE or TILESOLVE_MAX_INPUT=SIZE
(SIZE like 512M or 2G)."""

#: The epilog of a command that reads files: the input limit, then the exit codes.
READER_HELP = INPUT_HELP + "\n\n" + EXIT_HELP

TILING_FILE_HELP = (
    "a solution JSON file or a text grid (one row per line, top row first, a digit per cell)"
)


def compose(*decorators: Callable) -> Callable:
    """Apply several option decorators as one (first listed = first in --help)."""

    def wrap(f: Callable) -> Callable:
        for d in reversed(decorators):
            f = d(f)
        return f

    return wrap


# ----------------------------------------------------------------------------- problem
size_opt = click.option("--size", metavar="WxH", help="Grid size: W columns by H rows, e.g. 64x48.")
cond_opt = click.option(
    "--cond", "conditions", metavar="COND", multiple=True, help="A condition such as H0=2 (repeatable; see below)."
)
tiles_opt = click.option(
    "--tiles", "n_tiles", type=int, default=None, metavar="K", help="Number of tiles |T| (tiles 0..K-1)  [default: 2]"
)
cyclic_opt = click.option(
    "--cyclic", is_flag=True, help="Runs wrap around both edges: a tiling of the torus (dappled §3.2)."
)
fix_opt = click.option(
    "--fix",
    type=click.Path(dir_okay=False),
    metavar="FILE",
    help="Partial tiling to respect: a problem/solution JSON file or a text grid with '?' or '.' for free cells.",
)
closest_opt = click.option(
    "--closest-to",
    type=click.Path(dir_okay=False),
    metavar="FILE",
    help=f"Find the dappled tiling nearest (Hamming distance) to this tiling: {TILING_FILE_HELP}.",
)
count_opt = click.option(
    "--count",
    "counts",
    multiple=True,
    metavar="T=N",
    help="Global count of tile T: 1=8 (exactly 8 cells), 1=4..10, 1=..10, 1=4.. (repeatable).",
)
problem_file_opt = click.option(
    "--problem",
    "problem_file",
    type=click.Path(dir_okay=False),
    metavar="FILE",
    help="Read the problem from a tilesolve problem or solution JSON file instead of --size/--cond/...",
)


def problem_options(*, closest: bool = True, counts: bool = True) -> Callable:
    """All options that describe a dappled problem (see :func:`tilesolve.cli.common.build_problem`)."""
    opts = [size_opt, cond_opt, tiles_opt, cyclic_opt, fix_opt]
    if counts:
        opts.append(count_opt)
    if closest:
        opts.append(closest_opt)
    opts.append(problem_file_opt)
    return compose(*opts)


# ----------------------------------------------------------------------------- running
#: Largest count-like option value (line limits, tile numbers): far beyond any board, inside a C long.
MAX_INT = 2**31 - 1

#: A positive whole number option (a line limit, a run length).
positive_int = click.IntRange(1, MAX_INT)

#: Largest --seed: solver backends take a 32-bit signed seed.
MAX_SEED = 2**31 - 1
#: Largest --time-limit in seconds (about 115 days); beyond it timers overflow.
MAX_TIME_LIMIT = 1e7


class Seconds(click.ParamType):
    """A time limit: a finite number of seconds, > 0 and at most :data:`MAX_TIME_LIMIT`."""

    name = "seconds"

    def convert(self, value, param, ctx) -> float:  # noqa: D102 - click API
        if isinstance(value, float):
            return value
        try:
            v = float(value)
        except (TypeError, ValueError):
            self.fail(f"{value!r} is not a number of seconds", param, ctx)
        if not (math.isfinite(v) and 0 < v <= MAX_TIME_LIMIT):
            self.fail(f"{value!r} is not a number of seconds in (0, {MAX_TIME_LIMIT:.0e}]", param, ctx)
        return v


seed_opt = click.option(
    "--seed", type=click.IntRange(0, MAX_SEED), default=None, metavar="N",
    help=f"Random seed 0..{MAX_SEED}; the same seed gives the same tiling.",
)


def _time_limit_from_start(ctx: click.Context, param: click.Parameter, value: float | None) -> float | None:
    """With a time limit, the command's first run counts from where the command started (the
    process, for the console script: ``started`` in the root context's object), so that the
    whole command, start-up included, ends within the limit."""
    obj = ctx.find_root().obj
    started = obj.get("started") if isinstance(obj, dict) else None
    if value is not None and started is not None:
        from tilesolve.deadline import first_run_counted_from

        ctx.with_resource(first_run_counted_from(started))
    return value


time_limit_opt = click.option(
    "--time-limit",
    type=Seconds(),
    default=None,
    metavar="S",
    callback=_time_limit_from_start,
    help="Stop S seconds after the command started, start-up included, with status unknown (exit 3).",
)
initial_opt = click.option(
    "--initial",
    type=click.Path(dir_okay=False),
    metavar="FILE",
    help=f"Initial tiling for the constructive route (Algorithm 1 starts from it): {TILING_FILE_HELP}.",
)

# ----------------------------------------------------------------------------- outputs
output_opt = click.option(
    "-o",
    "--output",
    type=OutputFile("json"),
    metavar="OUT.json",
    help="Write the solution JSON here ('-' for stdout). With no output option the tiling is printed as text.",
)
svg_opt = click.option("--svg", type=OutputFile("svg"), metavar="OUT.svg",
                       help="Also draw the tiling as SVG ('-' for stdout).")
png_opt = click.option(
    "--png", type=OutputFile("png"), metavar="OUT.png",
    help="Also draw the tiling as PNG, for large grids ('-' for stdout).",
)
repeat_opt = click.option(
    "--repeat",
    type=click.IntRange(1, 16),
    default=1,
    show_default=True,
    metavar="N",
    help="Draw N x N copies (shows how a cyclic tiling wraps).",
)
grid_opt = click.option(
    "--grid/--no-grid", default=None, help="Draw cell borders  [default: when cells are large enough]"
)
picture_options = compose(svg_opt, png_opt, repeat_opt, grid_opt)


# ----------------------------------------------------------------------------- proofs
def _byte_size(ctx: click.Context, param: click.Parameter, value: str) -> int:
    """The option's size in bytes (``512M``, ``8G``); a one-line error names the option."""
    from tilesolve.errors import InvalidProblem
    from tilesolve.inputs import parse_byte_size

    try:
        return parse_byte_size(value)
    except InvalidProblem as exc:
        raise InvalidProblem(f"--{param.name.replace('_', '-')}: {exc}") from None


def max_cnf_option(help: str) -> Callable:
    """``--max-cnf SIZE`` (default 1 GiB of DIMACS text), given to the command in bytes."""
    return click.option("--max-cnf", metavar="SIZE", default="1G", show_default=True, callback=_byte_size,
                        help=help)


def _proof_dir(ctx: click.Context, param: click.Parameter, value: str | None) -> str | None:
    """Write the checked proofs of this command's unsat answers to ``value`` (see --proof-dir)."""
    if value is not None:
        from tilesolve.family import writing_proofs

        ctx.with_resource(writing_proofs(value))
    return value


proof_dir_opt = click.option(
    "--proof-dir",
    type=click.Path(file_okay=False),
    metavar="DIR",
    expose_value=False,
    callback=_proof_dir,
    help="Write the CNF and the checked DRAT proof of an unsat answer to DIR (unsat-<digest>.cnf, "
    ".drat) for any checker; 'tilesolve verify FILE --proof-dir DIR' re-checks them.",
)
