"""Exact counts of the Wang tilings of rectangles, cylinders and tori by a transfer matrix.

A row of ``w`` tiles whose horizontal neighbours match is a transition from the word of its
``N`` colours (length ``w``) to the word of its ``S`` colours; ``T[u, v]`` is the number of
such rows (class notes Part II §8.2 reads tilings row by row the same way, and Jeandel and
Rao's transducers are the same object). With free boundary colours:

* an ``h x w`` rectangle has ``1ᵀ Tʰ 1`` tilings (any top word, any bottom word);
* a cylinder whose columns wrap (E of the last column meets W of the first) uses the rows
  whose first ``W`` colour equals their last ``E`` colour;
* a torus has ``trace(Tʰ)`` tilings (the last row's ``S`` word is the first row's ``N`` word).

The shorter side is taken as the row (the board is transposed if needed), so the words stay
short; when that orientation has too many partial rows, the other one is tried. Rows are built column by column with numpy, merging partial rows that agree on
``(N word, S word, first W, last E)``; the row vector of a rectangle is pushed ``h`` times
through ``T`` in exact Python integers; a torus keeps only the words on cycles of ``T``
(strongly connected components, networkx) and raises the dense matrix to the ``h``-th power in
float64 (exact while every entry stays below 2⁵³, checked) or, above that, modulo primes small
enough for exact float64 products, joined by the Chinese remainder theorem.

Boards with other identifications (Möbius strips, Klein bottles), masks, fixed boundary
colours or line limits are not grids of this kind: :func:`transfer_applies` says so, and the
board family counts them by SAT enumeration instead.
"""

from __future__ import annotations

import numpy as np

from tilesolve.errors import InvalidProblem, MethodNotApplicable
from tilesolve.progress import SILENT, Progress

__all__ = ["MAX_STATES", "transfer_applies", "count_grid", "count_problem"]

#: Most partial rows (or row words) a count builds before it refuses.
MAX_STATES = 4_000_000
_EXACT_FLOAT = float(2 ** 53)
#: Most row words on cycles a torus count raises as a dense matrix (128 MiB of float64).
_MAX_WORDS = 4096


def transfer_applies(problem) -> str | None:
    """``None`` when the transfer method counts ``problem``, else the reason it does not."""
    board = problem.board
    spec = board.grid_spec
    if spec is None:
        return f"a {board.kind} board is not cut from a grid"
    if spec.wrap_rows == "twist" or spec.wrap_cols == "twist":
        return f"a {board.kind} board has a twisted identification"
    if not board.mask_of().all():
        return "the board has holes (a mask)"
    if problem.boundary is not None and (np.asarray(problem.boundary) >= 0).any():
        return "boundary colours are fixed"
    if problem.max_h is not None or problem.max_v is not None:
        return "line limits apply"
    return None


def _rows(nesw: np.ndarray, k: int, width: int, cyclic: bool, deadline=None, progress: Progress = SILENT):
    """Every row of ``width`` matching tiles, merged by ``(N word, S word)``: arrays
    ``(u, v, count)`` with words coded base ``k`` (first cell most significant)."""
    if width * np.log2(max(k, 2)) >= 62:
        raise InvalidProblem(f"rows of {width} cells over {k} colours are too long for the transfer method "
                             f"({k}^{width} words); count a smaller board or use method 'enumerate'")
    n, e, s, w = (nesw[:, i].astype(np.int64) for i in range(4))
    # multiplicities in int64 while no count can reach 2**62 (at most len(tiles)**width), else exact objects
    ctype = np.int64 if width * np.log2(max(len(nesw), 2)) < 62 else object
    # a partial row as one int64 key (u, v, first W, last E) while k**(2 width + 2) fits, else a 4-column key
    flat = (2 * width + 2) * np.log2(max(k, 2)) < 62
    u, v, h0, h, c = n.copy(), s.copy(), w.copy(), e.copy(), np.ones(len(nesw), dtype=ctype)
    if not cyclic:
        h0 = np.zeros_like(h0)
    order = np.argsort(w, kind="stable")  # tiles grouped by their W colour
    first = np.searchsorted(w[order], np.arange(k))
    deg = np.bincount(w, minlength=k)
    with progress.task("counting: building row words", total=width - 1, unit="column") as bar:
        for j in range(1, width):
            if deadline is not None:
                deadline.check(f"building rows (column {j + 1} of {width})")
            reps = deg[h]
            total = int(reps.sum())
            if total > MAX_STATES:
                raise InvalidProblem(f"too many partial rows ({total:,} at column {j + 1} of {width}) for the "
                                     f"transfer method; count a smaller board")
            left = np.repeat(np.arange(len(h)), reps)
            within = np.arange(total) - np.repeat(np.cumsum(reps) - reps, reps)
            right = order[first[h][left] + within]
            u, v, h0, h, c = u[left] * k + n[right], v[left] * k + s[right], h0[left], e[right], c[left]
            if flat:
                kw = k ** (j + 1)
                key, inv = np.unique(((u * kw + v) * k + h0) * k + h, return_inverse=True)
                h, rest = key % k, key // k
                h0, rest = rest % k, rest // k
                v, u = rest % kw, rest // kw
            else:
                key, inv = np.unique(np.stack([u, v, h0, h], axis=1), axis=0, return_inverse=True)
                u, v, h0, h = key[:, 0], key[:, 1], key[:, 2], key[:, 3]
            merged = np.zeros(len(key), dtype=ctype)
            np.add.at(merged, inv.reshape(-1), c)
            c = merged
            bar.advance()
    if cyclic:
        keep = h0 == h
        u, v, c = u[keep], v[keep], c[keep]
    key, inv = np.unique(np.stack([u, v], axis=1), axis=0, return_inverse=True)
    counts = np.zeros(len(key), dtype=ctype)
    np.add.at(counts, inv.reshape(-1), c)
    return key[:, 0], key[:, 1], counts.astype(object)


def _trace_power(rows_u, rows_v, counts, height: int, deadline=None, progress: Progress = SILENT) -> int:
    """``trace(T^height)`` of the sparse word-to-word matrix, exactly."""
    import networkx as nx

    g = nx.DiGraph()
    g.add_edges_from(zip(rows_u.tolist(), rows_v.tolist()))
    on_cycle = set()
    for comp in nx.strongly_connected_components(g):
        if len(comp) > 1 or g.has_edge(next(iter(comp)), next(iter(comp))):
            on_cycle |= comp
    if not on_cycle:
        return 0
    words = np.array(sorted(on_cycle), dtype=np.int64)
    keep = np.isin(rows_u, words) & np.isin(rows_v, words)
    a, b = np.searchsorted(words, rows_u[keep]), np.searchsorted(words, rows_v[keep])
    m = len(words)
    if m > _MAX_WORDS:
        raise InvalidProblem(f"the torus has {m:,} row words on cycles (a dense {m:,}x{m:,} matrix); the transfer "
                             f"method takes at most {_MAX_WORDS:,}: count a smaller torus")
    t = np.zeros((m, m))
    np.add.at(t, (a, b), counts[keep].astype(float))
    # float64 repeated squaring; exact while every entry stays below 2**53 (integers)
    result, base, e, exact = None, t, height, True
    with progress.task("counting: torus matrix power", total=height.bit_length(), unit="squaring") as bar:
        while e:
            if deadline is not None:
                deadline.check("raising the torus transfer matrix to its power")
            if e & 1:
                result = base if result is None else result @ base
                exact &= bool(result.max() < _EXACT_FLOAT)
            e >>= 1
            if e:
                base = base @ base
                exact &= bool(base.max() < _EXACT_FLOAT)
            bar.advance()
    if exact:
        return int(round(float(np.trace(result))))
    # above 2**53: the trace modulo primes small enough that float64 products stay exact,
    # joined by the Chinese remainder theorem; the count is at most n_rows^height
    bits = height * float(np.log2(max(float(counts[keep].sum()), 2.0))) + 2
    p_max = int((_EXACT_FLOAT / m) ** 0.5)
    if p_max < 1000:
        raise InvalidProblem(f"the torus has {m:,} row words on cycles; too many for exact transfer counting")
    residues, primes, prod = [], [], 1
    n_primes = -(-int(bits) // int(np.log2(p_max))) + 1  # about: each prime adds log2(p) bits
    with progress.task("counting: matrix power modulo primes", total=n_primes, unit="prime") as primes_done:
        for p in _primes_below(p_max):
            if prod.bit_length() > bits:
                break
            tp = np.zeros((m, m))
            np.add.at(tp, (a, b), np.array([int(x) % p for x in counts[keep]], dtype=float))
            tp = np.fmod(tp, p)
            residues.append(_trace_power_mod(tp, height, p, deadline))
            primes.append(p)
            prod *= p
            primes_done.advance()
    total = 0
    for r, p in zip(residues, primes):  # CRT
        q = prod // p
        total += r * q * pow(q, -1, p)
    return total % prod


def _primes_below(n: int):
    """Primes below ``n``, largest first (trial division; ``n`` is at most a few million)."""
    for p in range(n - 1, 2, -1):
        if p % 2 and all(p % d for d in range(3, int(p ** 0.5) + 1, 2)):
            yield p


def _trace_power_mod(t: np.ndarray, height: int, p: int, deadline=None) -> int:
    result, base, e = None, t, height
    while e:
        if deadline is not None:
            deadline.check("raising the torus transfer matrix to its power")
        if e & 1:
            result = base if result is None else np.fmod(result @ base, p)
        e >>= 1
        if e:
            base = np.fmod(base @ base, p)
    return int(np.fmod(np.trace(result), p))


def count_grid(tileset, rows: int, cols: int, *, wrap_rows: bool = False, wrap_cols: bool = False,
               deadline=None, progress: Progress = SILENT) -> int:
    """The number of tilings of a ``rows x cols`` grid by ``tileset`` (free boundary), exactly.

    Parameters
    ----------
    tileset : WangTileSet
    rows, cols : int
    wrap_rows : bool
        The S legs of the last row meet the N legs of row 0.
    wrap_cols : bool
        The E legs of the last column meet the W legs of column 0.
    deadline : Deadline, optional
        Checked between steps (raises :class:`~tilesolve.deadline.TimeLimitReached`).
    progress : Progress, optional
        Shown per column while the row words are built, then per row (or per squaring of a
        torus's matrix) (:mod:`tilesolve.progress`).

    Examples
    --------
    >>> from tilesolve.model.board import WangTileSet
    >>> two = WangTileSet([[0, 0, 0, 0], [1, 1, 1, 1]], 2)  # each tile only meets itself
    >>> count_grid(two, 3, 4), count_grid(two, 3, 4, wrap_rows=True, wrap_cols=True)
    (2, 2)
    """
    rows, cols = int(rows), int(cols)
    if rows < 1 or cols < 1:
        raise InvalidProblem(f"a grid needs at least one row and column, got {rows}x{cols}")
    nesw = tileset.tiles
    # rows along the shorter side first; the transpose (new N, E, S, W = old W, S, E, N) is the
    # other orientation, tried when the first has too many partial rows
    ways = [(nesw, rows, cols, wrap_rows, wrap_cols), (nesw[:, [3, 2, 1, 0]], cols, rows, wrap_cols, wrap_rows)]
    ways.sort(key=lambda way: way[2])
    for i, (nesw, rows, cols, wrap_rows, wrap_cols) in enumerate(ways):
        try:
            u, v, c = _rows(nesw, tileset.n_colors, cols, wrap_cols, deadline, progress)
            break
        except InvalidProblem:
            if i == len(ways) - 1 or rows == cols and np.array_equal(ways[0][0], ways[1][0]):
                raise
    if wrap_rows:
        return _trace_power(u, v, c, rows, deadline, progress)
    words, inv = np.unique(np.concatenate([u, v]), return_inverse=True)
    a, b = inv[: len(u)], inv[len(u):]
    x = np.ones(len(words), dtype=object)  # free top boundary: every N word once
    with progress.task("counting: rows", total=rows, unit="row") as bar:
        for i in range(rows):
            if deadline is not None:
                deadline.check(f"counting row {i + 1} of {rows}")
            y = np.zeros(len(words), dtype=object)
            np.add.at(y, b, x[a] * c)
            x = y
            bar.advance()
    return int(x.sum())


def count_problem(problem, deadline=None, progress: Progress = SILENT) -> int:
    """:func:`count_grid` for a :class:`~tilesolve.model.board.BoardProblem`; raises
    :class:`~tilesolve.errors.MethodNotApplicable` where :func:`transfer_applies` says no."""
    why = transfer_applies(problem)
    if why is not None:
        raise MethodNotApplicable(f"the transfer method counts free rectangles, cylinders and tori; {why}")
    spec = problem.board.grid_spec
    return count_grid(problem.tileset, spec.rows, spec.cols, wrap_rows=spec.wrap_rows == "plain",
                      wrap_cols=spec.wrap_cols == "plain", deadline=deadline, progress=progress)
