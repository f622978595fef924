"""``tilesolve aperiodic census``: every small Wang tile set, up to symmetry, classified with its certificate.

::

    tilesolve aperiodic census --tiles N --colors K [--max-square N] [--max-period N]
                               [--workers W | --cluster ADDR] [--time-limit S] [--resume] -o census.jsonl
"""

from __future__ import annotations

import click

from tilesolve.cli import options as opt
from tilesolve.cli.common import progress_wanted, say
from tilesolve.cli.outputs import OutputFile, interrupt_received, interruption
from tilesolve.errors import InvalidProblem

__all__ = ["census"]


@click.command(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
               short_help="Classify every set of N Wang tiles over K colours: finite, periodic or undecided.")
@click.option("--tiles", "n_tiles", type=click.IntRange(1, 16), required=True, metavar="N",
              help="Tiles in a set (distinct tiles).")
@click.option("--colors", "colours", type=click.IntRange(1, 8), required=True, metavar="K",
              help="At most K colours on each axis (horizontal edges and vertical edges).")
@click.option("--max-square", type=click.IntRange(1, 64), default=12, show_default=True, metavar="N",
              help="Largest square searched for a finite set.")
@click.option("--max-period", type=click.IntRange(1, 64), default=12, show_default=True, metavar="N",
              help="Transducers T^k up to k = max(this, --max-square): tori of that height at most.")
@click.option("--workers", type=click.IntRange(1, 256), default=None, metavar="W",
              help="Local worker processes [default: 2, both cores].")
@click.option("--cluster", default=None, metavar="ADDR",
              help="Run on this Dask scheduler (e.g. tcp://host:8786); needs pip install \"tilesolve[cluster]\".")
@click.option("--resume", is_flag=True,
              help="Continue the census in -o: its records are kept once their certificates are re-checked, the "
                   "other sets are classified.")
@click.option("--proof-dir", type=click.Path(file_okay=False), default=None, metavar="DIR",
              help="Write the CNF and checked DRAT proof of every refutation to DIR.")
@opt.time_limit_opt
@click.option("-o", "--output", type=OutputFile("jsonl", allow_dash=False), required=True, metavar="CENSUS.jsonl",
              help="The census file: a header line, then one JSON record a set, appended as sets are classified.")
@click.pass_context
def census(ctx, n_tiles, colours, max_square, max_period, workers, cluster, resume, proof_dir, time_limit,
           output) -> None:
    """Classify every set of N distinct Wang tiles over at most K colours per axis, one set per
    class of colour relabellings, turns and mirrors: finite (the largest tiled square, a verified
    witness, and the next square refuted with a checked DRAT proof), periodic (a tiled torus,
    verified) or undecided within the bounds.

    Records are appended to the census file as they come; a census stopped by Ctrl-C, a time
    limit or a lost worker continues with --resume. Prints the count of each class and every
    undecided set. Exit 0 when every set is finite or periodic, 3 when one is undecided or was
    not reached.

    \b
    Examples:
      tilesolve aperiodic census --tiles 3 --colors 2 -o c.jsonl
      tilesolve aperiodic census --tiles 3 --colors 3 --workers 2 -o c3.jsonl --resume
    """
    from tilesolve.families.aperiodic_census import census as run_census
    from tilesolve.family import run_deadline
    from tilesolve.model.run import RunOptions

    if workers is not None and cluster is not None:
        raise InvalidProblem("--workers runs local processes and --cluster a Dask cluster: give one of them")
    run = RunOptions(seed=0, deadline=run_deadline(time_limit), progress=progress_wanted(), workers=workers,
                     cluster=cluster)
    try:
        result = run_census(n_tiles, colours, run, output, max_square=max_square, max_period=max_period,
                            resume=resume, proof_dir=proof_dir)
    except KeyboardInterrupt:  # caught outside the census's own check for it
        _kept(ctx, output)
    except Exception:  # noqa: BLE001 - the consequence of a Ctrl-C (numpy, for one, turns it into a TypeError)
        if not interrupt_received():
            raise
        _kept(ctx, output)
    if result.interrupted:
        _kept(ctx, output)
    counts = result.counts()
    click.echo(f"census of {result.n_sets} sets of {n_tiles} tiles over at most {colours} colours per axis (up to "
               f"symmetry; squares up to {max_square}, transducers up to {max(max_square, max_period)} rows): "
               + ", ".join(f"{v} {c}" for c, v in counts.items()))
    for rec in result.undecided:
        click.echo(f"undecided: {rec['tiles']} ({rec['why']})")
    say(f"  {result.resumed} record(s) resumed from {output} (certificates re-checked); {result.seconds:.2f} s")
    say(f"  wrote {output}")
    ctx.exit(0 if result.complete else 3)


def _kept(ctx, output) -> None:
    """End an interrupted census (exit 130, or 143 for SIGTERM). The census file is appended to
    as sets are decided, so its records are kept for --resume: not the generic "no file was
    written"."""
    code, what = interruption()
    click.echo(f"tilesolve: {what}: the records decided so far are kept in {output}; --resume continues", err=True)
    ctx.exit(code)
