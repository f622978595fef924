"""The ``tilesolve`` command line: :mod:`tilesolve.cli.main` holds the click group, one module per command."""
