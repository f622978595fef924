"""``tilesolve aperiodic check``: squares and periods of a Wang tile set, with certificates.

::

    tilesolve aperiodic check TILES | --tiles TILES [--format F] | --builtin NAME
                              --max-square N --max-period N [--shears] [--workers K] [--cluster ADDR]
                              [--proof-dir DIR] [--time-limit S] [--cache FILE] [--seed S] -o report.json
"""

from __future__ import annotations

import click

from tilesolve.cli import options as opt
from tilesolve.cli.aperiodic_census import census
from tilesolve.cli.aperiodic_tiling import tiling
from tilesolve.cli.common import progress_wanted, say
from tilesolve.cli.outputs import OutputFile, Outputs
from tilesolve.cli.wang_count import load_tileset, tileset_options
from tilesolve.errors import InvalidProblem

__all__ = ["aperiodic"]


@click.group(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.EXIT_HELP,
             short_help="Aperiodicity checks of Wang tile sets: squares, tori, lattice periods, certified.")
def aperiodic() -> None:
    """Aperiodicity checks of Wang tile sets (class notes Part II §8.2), every answer a certificate;
    windows of tilings by the built-in aperiodic sets (aperiodic tiling)."""


@aperiodic.command(context_settings=opt.CONTEXT_SETTINGS, epilog=opt.READER_HELP)
@click.argument("tiles", required=False, type=click.Path(dir_okay=False), metavar="[TILES]")
@tileset_options
@click.option("--max-square", type=click.IntRange(0), default=0, show_default=True, metavar="N",
              help="Find the largest n <= N with a tiled n x n square (free boundary).")
@click.option("--max-period", type=click.IntRange(0), default=0, show_default=True, metavar="N",
              help="Check every torus p x q, 1 <= p, q <= N.")
@click.option("--method", type=click.Choice(["auto", "sat", "transducer", "lattice"]), default="auto",
              show_default=True,
              help="sat: squares by bisection and every (sheared) torus by SAT; transducer: Jeandel-Rao "
                   "transducers T^k up to k = max period (or max square), emptiness certified by SAT; lattice: "
                   "every lattice of periods of index (cells of one period) <= max period, smallest first, until "
                   "one is tiled (witnesses only). auto: sat.")
@click.option("--shears", is_flag=True, help="Also every sheared torus: the horizontal wrap shifted by s rows, 0 < s < p.")
@click.option("--workers", type=click.IntRange(1, 256), default=None, metavar="K",
              help="Local worker processes of the period sweep [default: 2, both cores].")
@click.option("--cluster", default=None, metavar="ADDR",
              help="Run the period sweep on this Dask scheduler (e.g. tcp://host:8786); needs "
                   "pip install \"tilesolve[cluster]\".")
@click.option("--proof-dir", type=click.Path(file_okay=False), default=None, metavar="DIR",
              help="Write the CNF and checked DRAT proof of every refutation to DIR (unsat-<digest>.cnf, .drat).")
@click.option("--cache", type=click.Path(dir_okay=False), default=None, metavar="FILE",
              help="Results file of decided lattices, appended to as lattices are decided; the DRAT proofs of its "
                   "refutations are kept in FILE.proofs/. A later run uses a cached verdict only once re-checked (a "
                   "witness by the verifier, a refutation's proof against the re-derived CNF); others are decided "
                   "again [default: REPORT.cache.jsonl next to -o].")
@click.option("--square-search", type=click.Choice(["phase", "portfolio", "race", "markov", "grams"]), default="race",
              show_default=True,
              help="How squares are searched. phase: the full formula in one process, CaDiCaL's first value of "
                   "every tile false and its saved phases (the seed changes nothing); portfolio: squares above 40 "
                   "on two processes, the full formula and one guided by a 30x30 tiling, with the seed's random "
                   "phases (the route before); race: that portfolio with its full formula searched as phase "
                   "does; markov (jeandel-rao and labbe-u19 only): the race with the guided run replaced by the "
                   "full formula phased by the constructive route's window (the witness's method says which run "
                   "found it: sat or sat markov-phased); grams: the race with the guided run restricted to the "
                   "runs of up to 4 tiles along the rows and columns of a 100x100 witness of the phase search "
                   "(squares above 100; the witness's method: sat or sat gram-guided). A refutation has its "
                   "checked proof in every case.")
@click.option("--every-board", is_flag=True,
              help="Decide every lattice up to --max-period; by default the sweep stops at the first tiled torus "
                   "(it decides the verdict) and the lattices left are undecided.")
@opt.time_limit_opt
@opt.seed_opt
@click.option("-o", "--output", type=OutputFile("json"), metavar="REPORT.json",
              help="Write the report JSON here ('-' for stdout).")
@click.pass_context
def check(ctx, tiles, tiles_path, tiles_format, builtin, method, max_square, max_period, shears, workers, cluster,
          proof_dir, cache, square_search, every_board, time_limit, seed, output) -> None:
    """Check a tile set's squares and periods; write a report of certificates.

    The tile set is a file (TILES or --tiles, in any format of --format, as every Wang command
    reads it) or a built-in set.

    A tiled square or torus is a witness (verified before it is written); a refuted one has a
    DRAT proof checked by tilesolve's checker; boards left by a time limit are "undecided".
    The report says what was checked and never calls a set aperiodic from search alone; its
    verdict is periodic (a tiled torus), finite (a refuted square: the set tiles no plane), open
    (every board decided, neither found) or undecided. Exit 0 with a decided verdict, 3 when it
    is undecided (a board left undecided that the verdict needed).

    \b
    Examples:
      tilesolve aperiodic check --builtin jeandel-rao --max-square 20 --max-period 3 --seed 1 -o jr.json
      tilesolve aperiodic check --builtin periodic-7-30 --max-period 2 --shears --workers 1 -o p.json --proof-dir proofs
      tilesolve aperiodic check --builtin finite-jv7 --method transducer --max-square 12 -o t.json
      tilesolve aperiodic check --builtin periodic-10-35 --method lattice --max-period 35 -o p35.json
      tilesolve verify jr.json
    """
    from tilesolve.families import aperiodic as facade
    from tilesolve.family import write_solution

    if tiles is not None and tiles_path is not None:
        raise InvalidProblem("give the tile-set file once: TILES or --tiles FILE")
    if max_square == 0 and max_period == 0:
        raise InvalidProblem("nothing to check: give --max-square N and/or --max-period N")
    if workers is not None and cluster is not None:
        raise InvalidProblem("--workers runs local processes and --cluster a Dask cluster: give one of them")
    tileset, notes = load_tileset(tiles if tiles is not None else tiles_path, tiles_format, builtin)
    for note in notes:
        click.echo(f"tilesolve: warning: {note}", err=True)
    info = None
    if builtin is not None:
        from tilesolve.io.builtin_tilesets import load

        info = load(builtin)[1]
    problem = facade.AperiodicProblem(tileset, max_square, max_period, shears, builtin, info)
    outs = Outputs(output)
    if cache is None and output and output != "-":
        cache = output + ".cache.jsonl"
    sol = facade.solve(problem, method=method, seed=seed, time_limit=time_limit, progress=progress_wanted(), workers=workers,
                       cluster=cluster, options={"proof_dir": proof_dir, "cache": cache, "every_board": every_board,
                                                 "square_search": square_search})
    with outs.commit(sol):
        if output:
            write_solution(output, problem, sol)
    rep = sol.report
    if not output or output != "-":
        click.echo(rep.conclusion)
        if rep.literature:
            click.echo(f"Literature: {rep.literature}")
    say(f"{problem.describe()}: verdict {rep.verdict}; {sol.method} route, "
        f"{sum(c.status == 'tiles' for c in rep.periods)} periods "
        f"tiled, {sum(c.status == 'refuted' for c in rep.periods)} refuted, {len(rep.undecided)} undecided, "
        f"in {sol.time_s:.2f} s (seed {sol.seed})")
    for note in sol.notes:
        say(f"  note: {note}")
    if outs.files:
        say(f"  wrote {', '.join(outs.files)}")
    ctx.exit(sol.status.exit_code)


@aperiodic.command(name="verify", context_settings=opt.CONTEXT_SETTINGS,
                   epilog=opt.READER_HELP)
@click.argument("report", type=click.Path(dir_okay=False))
@click.option("--proof-dir", type=click.Path(file_okay=False, exists=True), default=None, metavar="DIR",
              help="Re-check every refutation's DRAT proof (the .drat files 'check --proof-dir' wrote) against the "
                   "CNF re-derived from the report's tile set and board.")
@click.option("--workers", type=click.IntRange(1, 256), default=2, show_default=True, metavar="K",
              help="Local worker processes that share the re-checking of many refutations.")
@opt.max_cnf_option("Re-derive no CNF estimated (before encoding) above SIZE of DIMACS text (e.g. 512M, 8G): "
                     "such a refutation is reported as not confirmed.")
@click.pass_context
def verify_report(ctx, report, proof_dir, workers, max_cnf) -> None:
    """Re-check a report: every witness on its board, every refutation's CNF re-derived from the
    report's tile set and board (its SHA-256 must be the recorded one), and with --proof-dir every
    DRAT proof against that CNF.

    The details come first, one line each; the last line is the one verdict, "ok: ..." only when
    every check passed. Exit 0 when every claim holds, 1 when one is false or a proof is missing.

    \b
    Examples:
      tilesolve aperiodic check --builtin periodic-7-30 --max-period 2 --workers 1 -o p.json --proof-dir proofs
      tilesolve aperiodic verify p.json --proof-dir proofs
    """
    from tilesolve.family import read_document, verify_file

    fam, codec, _ = read_document(report)
    if fam.name != "aperiodic":
        raise InvalidProblem(f"{report} is a {codec.format} file, not an aperiodicity report")
    result = verify_file(report, proof_dir, workers=workers, max_cnf=max_cnf, progress=progress_wanted())
    for line in result.lines[1:] + result.lines[:1]:
        click.echo(line)
    ctx.exit(result.exit_code)


aperiodic.add_command(tiling)
aperiodic.add_command(census)
