"""tilesolve: a tiling studio backed by SAT and constraint solvers."""

__version__ = "0.1.0"
