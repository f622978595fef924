"""The ``tilesolve`` command line: :mod:`tilesolve.cli.main` is the console script's entry point, :mod:`tilesolve.cli.group` holds the click group, one module per command."""
