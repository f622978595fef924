"""Penrose rhomb (P3) and kite-dart (P2) tilings: Robinson-triangle substitution and de Bruijn's
pentagrid (Kaplan, class notes Part II §8.3; N. G. de Bruijn, "Algebraic theory of Penrose's
non-periodic tilings of the plane", Indag. Math. 43, 1981).

Coordinates are exact: every vertex is an element of ``Z[zeta]``, ``zeta = exp(2 pi i / 5)``,
held as four integers on the basis ``1, zeta, zeta^2, zeta^3`` (``zeta^4 = -1 - zeta - zeta^2 -
zeta^3``). The golden ratio ``phi = -(zeta^2 + zeta^3)`` is a unit of that ring
(``1/phi = phi - 1``), so deflation never leaves it. The unit of length is the rhomb edge; P2
kites and darts have long edges ``phi`` and short edges 1.

A tile is four vertices counter-clockwise, starting at its *marked* vertex, which carries the
matching rule:

* P3 (types ``0`` thin, ``1`` thick): the rhomb is two mirror Robinson triangles ``(A, B, C)``
  and ``(A', B, C)`` joined along their base ``BC``; vertex 0 is ``B``, an obtuse vertex of the
  thin rhomb and an acute vertex of the thick one.
* P2 (types ``0`` kite, ``1`` dart): vertex 0 is the kite's head or the dart's tip (the vertex
  between the two long edges); the shape alone carries the matching rule.

Substitution (§8.3, Fig. 32; the rules as in Preshing's exposition of Robinson's triangles):
a sun of ten acute triangles of legs ``phi^n`` is deflated ``n`` times; pairs of mirror
triangles that share their base become rhombs (a triangle whose partner is outside the patch
is dropped).

Pentagrid: five families of lines ``<z, zeta^j> + gamma_j in Z`` with ``sum gamma_j = 0``;
the intersection of line ``r`` of family ``j`` and line ``s`` of family ``k`` is the rhomb
``K, K + zeta^j, K + zeta^j + zeta^k, K + zeta^k`` where ``K_i = ceil(<z, zeta^i> + gamma_i)``
(``K_j = r``, ``K_k = s``). Its index ``sum K_i`` (1..4 at every vertex) places the marking.
Only the three floors per intersection are floating point; the offsets are drawn so that no
three lines meet, and an intersection within :data:`TOLERANCE` (relative) of a third line is
refused rather than guessed.

P2 from P3 (the correspondence, Grünbaum and Shephard §10.3): cut every rhomb into its two
Robinson triangles; an acute triangle ``(C, P, B)`` and the obtuse triangle ``(P, C, A)``
sharing its leg ``CP`` make the half-kite ``(A, B, C)`` (legs ``phi``); every other obtuse
triangle is a half-dart; mirror halves joined along their axis make kites and darts. It is the
inverse of one half-step of the P3 substitution, so every P3 patch gives the P2 patch of the
same region (tiles whose other half lies outside are dropped).

The two routes agree tile for tile (de Bruijn 1981; tests/constructive/test_penrose.py). A vertex
of the pentagrid tiling is ``sum K_i zeta^i`` for ``K`` in ``Z^5`` of index ``t = sum K_i`` in 1..4;
writing ``x^*`` for the conjugate ``zeta -> zeta^2`` (``K^* = sum K_i zeta^(2i)``), ``K`` is a
vertex exactly when ``K^* - Gamma`` lies in the pentagon ``W_t = {sum l_i zeta^(2i) : 0 <= l_i <= 1,
sum l_i = t}``, where ``Gamma = sum gamma_j zeta^(2j)``: the tiling depends on the offsets only
through ``Gamma`` (Part I, §1: the pattern is determined by one complex number). Hence:

* *Substitution to pentagrid* (:func:`pentagrid_of`). A point of ``Z[zeta]`` has one lift ``K``
  of index 1..4 unless its index class ``sum a_i mod 5`` is 0. A sun's vertices miss one class;
  moved by ``s`` edges along x (``s`` the shift that sends the missing class to 0), every vertex
  constrains ``Gamma`` to a translated pentagon, and any ``Gamma`` inside all of them (the centre
  of their intersection) gives offsets whose pentagrid is the moved patch, tile for tile, with the
  same markings.
* *Deflation acts on the offsets* (the theme of Part II): the pentagrid of ``gamma``, deflated once
  (:func:`deflate_rhombs`) and scaled back by ``phi``, is the pentagrid of ``-gamma / phi``.

P2 follows from P3 by the correspondence above, so the kites and darts agree as well.
"""

from __future__ import annotations

import numpy as np

from tilesolve.errors import InvalidProblem

__all__ = ["TOLERANCE", "zeta_xy", "sun", "deflate", "rhombs", "p3_substitution", "pentagrid_offsets",
           "pentagrid", "pentagrid_of", "deflate_rhombs", "p2_from_p3", "window_steps"]

#: An intersection is refused when a third grid line passes within this fraction of the
#: coordinates' size: the floats of an intersection's five values carry a rounding error of a few
#: units in the last place of that size (about 4e-16 of it), 25 times less. With a random seed the
#: chance of a refusal is about 2e-14 x size x intersections: 4e-5 for 10^6 rhombs near the
#: origin, 0.06 for 10^6 rhombs at 10^6 (the largest coordinate a problem takes).
TOLERANCE = 1e-14

_ANGLES = 2 * np.pi * np.arange(4) / 5
_RE, _IM = np.cos(_ANGLES), np.sin(_ANGLES)


def zeta_xy(v: np.ndarray) -> np.ndarray:
    """Cartesian coordinates ``(..., 2)`` of ring elements ``(..., 4)``."""
    v = np.asarray(v, dtype=np.float64)
    return np.stack([v @ _RE, v @ _IM], axis=-1)


def _times_zeta(a: np.ndarray) -> np.ndarray:
    a3 = a[..., 3:4]
    return np.concatenate([-a3, a[..., 0:3] - a3], axis=-1)


def _times_phi(a: np.ndarray) -> np.ndarray:
    z2 = _times_zeta(_times_zeta(a))
    return -(z2 + _times_zeta(z2))


def _over_phi(a: np.ndarray) -> np.ndarray:
    return _times_phi(a) - a


def _unit(d: int) -> np.ndarray:
    """``exp(i pi d / 5)`` in the ring: ``zeta^m`` for ``d = 2m``, ``-zeta^(m+3)`` for ``d = 2m + 1``."""
    one = np.array([1, 0, 0, 0], dtype=np.int64)
    m, odd = divmod(d % 10, 2)
    v = one
    for _ in range((m + 3 * odd) % 5):
        v = _times_zeta(v)
    return -v if odd else v


def sun(n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Ten acute Robinson triangles of legs ``phi^n`` around the origin, mirror by mirror:
    ``(types, A, B, C)`` with ``A`` the apex."""
    a = np.zeros((10, 4), dtype=np.int64)
    b = np.stack([_unit(i - 1) for i in range(10)])
    c = np.stack([_unit(i) for i in range(10)])
    b[0::2], c[0::2] = c[0::2].copy(), b[0::2].copy()
    for _ in range(n):
        b, c = _times_phi(b), _times_phi(c)
    return np.zeros(10, dtype=np.int8), a, b, c


def deflate(t, a, b, c):
    """One Robinson-triangle substitution: acute (type 0) into an acute and an obtuse triangle,
    obtuse (type 1) into two obtuse and an acute one; legs shrink by ``phi``."""
    acute = t == 0
    a0, b0, c0 = a[acute], b[acute], c[acute]
    p = a0 + _over_phi(b0 - a0)
    a1, b1, c1 = a[~acute], b[~acute], c[~acute]
    q = b1 + _over_phi(a1 - b1)
    r = b1 + _over_phi(c1 - b1)
    na, no = len(a0), len(a1)
    types = np.concatenate([np.zeros(na, np.int8), np.ones(na, np.int8), np.ones(2 * no, np.int8),
                            np.zeros(no, np.int8)])
    return (types, np.concatenate([c0, p, r, q, r]), np.concatenate([p, c0, c1, r, q]),
            np.concatenate([b0, a0, a1, b1, a1]))


def _rows(x: np.ndarray) -> np.ndarray:
    """Rows of an int64 array as one void value each (hashable keys for np.unique)."""
    x = np.ascontiguousarray(x)
    return x.view(np.dtype((np.void, x.dtype.itemsize * x.shape[1]))).ravel()


def _pairs(keys: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Indices ``(i, j)`` of the rows that share a key with exactly one other row."""
    _, inv, counts = np.unique(_rows(keys), return_inverse=True, return_counts=True)
    inv = inv.ravel()
    order = np.argsort(inv, kind="stable")
    starts = np.concatenate([[0], np.cumsum(counts)[:-1]])
    two = counts == 2
    return order[starts[two]], order[starts[two] + 1]


def _ccw(v: np.ndarray) -> np.ndarray:
    """Reverse ``v[:, 1:]`` where the quadrilateral is clockwise, keeping vertex 0 first."""
    xy = zeta_xy(v)
    x, y = xy[..., 0], xy[..., 1]
    area = np.sum(x * np.roll(y, -1, axis=1) - np.roll(x, -1, axis=1) * y, axis=1)
    cw = area < 0
    v[cw] = v[cw][:, [0, 3, 2, 1]]
    return v


def rhombs(t, a, b, c) -> tuple[np.ndarray, np.ndarray]:
    """P3 rhombs from Robinson triangles: mirror triangles of one type sharing their base ``BC``
    (vertex order ``B, A, C, A'`` made counter-clockwise); unpaired triangles are dropped."""
    keys = np.concatenate([t[:, None].astype(np.int64), b, c], axis=1)
    i, j = _pairs(keys)
    v = np.stack([b[i], a[i], c[i], a[j]], axis=1)
    return t[i].copy(), _ccw(v)


def window_steps(x0: float, y0: float, w: float, h: float) -> int:
    """Deflations a sun needs so that its rhombs cover the window (sun of radius ``phi^n``, inner
    radius ``0.95 phi^n``, less a boundary layer of 2)."""
    corners = np.array([[x0, y0], [x0 + w, y0], [x0, y0 + h], [x0 + w, y0 + h]], dtype=float)
    need = np.hypot(corners[:, 0], corners[:, 1]).max() + 3.0
    return max(1, int(np.ceil(np.log(need / 0.95) / np.log((1 + 5 ** 0.5) / 2))))


def _in_window(xy: np.ndarray, window) -> np.ndarray:
    x0, y0, w, h = window
    c = xy.mean(axis=1)
    return (c[:, 0] >= x0) & (c[:, 0] < x0 + w) & (c[:, 1] >= y0) & (c[:, 1] < y0 + h)


def p3_substitution(steps: int | None = None, window=None) -> tuple[np.ndarray, np.ndarray]:
    """P3 rhombs of a sun deflated ``steps`` times (unit edges), or of the sun that covers
    ``window = (x0, y0, w, h)``, keeping the rhombs whose centre lies in it."""
    n = window_steps(*window) if steps is None else steps
    tri = sun(n)
    for _ in range(n):
        tri = deflate(*tri)
    types, v = rhombs(*tri)
    if window is not None:
        keep = _in_window(zeta_xy(v), window)
        types, v = types[keep], v[keep]
    return types, v


def pentagrid_offsets(seed: int) -> np.ndarray:
    """Five offsets ``gamma_j`` in ``[0, 1)`` (the last one ``-sum`` of the others modulo 1), drawn from ``seed``."""
    g = np.random.default_rng(seed).random(4)
    return np.append(g, -g.sum())


def _pair_intersections(j, k, gamma, box):
    """``(r, s)`` of every intersection of families ``j`` and ``k`` inside ``box`` (in grid space)."""
    zx0, zx1, zy0, zy1 = box
    ej = np.array([np.cos(2 * np.pi * j / 5), np.sin(2 * np.pi * j / 5)])
    ek = np.array([np.cos(2 * np.pi * k / 5), np.sin(2 * np.pi * k / 5)])
    corners = np.array([[zx0, zy0], [zx1, zy0], [zx0, zy1], [zx1, zy1]])
    pj = corners @ ej + gamma[j]
    r = np.arange(np.ceil(pj.min()), np.floor(pj.max()) + 1)
    # line r: z = (r - gamma_j) e_j + t n_j, n_j the normal turned left; clip t to the box
    n = np.array([-ej[1], ej[0]])
    base = (r - gamma[j])[:, None] * ej
    lo = np.full(len(r), -np.inf)
    hi = np.full(len(r), np.inf)
    for axis, (b0, b1) in enumerate(((zx0, zx1), (zy0, zy1))):
        if abs(n[axis]) > 1e-12:
            t0, t1 = (b0 - base[:, axis]) / n[axis], (b1 - base[:, axis]) / n[axis]
            lo, hi = np.maximum(lo, np.minimum(t0, t1)), np.minimum(hi, np.maximum(t0, t1))
    ok = lo <= hi
    r, base, lo, hi = r[ok], base[ok], lo[ok], hi[ok]
    s0 = base @ ek + gamma[k] + lo * (n @ ek)
    s1 = base @ ek + gamma[k] + hi * (n @ ek)
    first = np.ceil(np.minimum(s0, s1)).astype(np.int64)
    count = np.maximum(np.floor(np.maximum(s0, s1)).astype(np.int64) - first + 1, 0)
    rr = np.repeat(r.astype(np.int64), count)
    offsets = np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)
    return rr, np.repeat(first, count) + offsets


def pentagrid(window, seed: int | None = None, gamma=None) -> tuple[np.ndarray, np.ndarray]:
    """The P3 rhombs of de Bruijn's pentagrid whose centre lies in ``window = (x0, y0, w, h)``.

    Random access: a rhomb is named by its intersection ``(j, k, r, s)``, so every window of
    one seed shows the same rhombs where windows overlap. ``gamma`` (five offsets, sum 0)
    overrides the seed's.

    Raises
    ------
    InvalidProblem
        An intersection lies within :data:`TOLERANCE` of a third line (a singular grid: choose
        another seed).
    """
    gamma = pentagrid_offsets(seed) if gamma is None else np.asarray(gamma, dtype=float)
    angles = 2 * np.pi * np.arange(5) / 5
    e = np.stack([np.cos(angles), np.sin(angles)], axis=1)
    c = gamma @ e
    x0, y0, w, h = window
    m = 3.0  # a vertex lies within |sum (K_i - x_i) zeta^i| < phi of 5/2 z + c
    box = ((x0 - m - c[0]) / 2.5, (x0 + w + m - c[0]) / 2.5, (y0 - m - c[1]) / 2.5, (y0 + h + m - c[1]) / 2.5)
    types, verts = [], []
    scale = max(1.0, abs(x0), abs(y0), abs(x0 + w), abs(y0 + h))
    unit = np.vstack([np.eye(4, dtype=np.int64), -np.ones((1, 4), dtype=np.int64)])  # zeta^i in the basis
    for j in range(5):
        for k in range(j + 1, 5):
            r, s = _pair_intersections(j, k, gamma, box)
            mat = np.linalg.inv(np.stack([e[j], e[k]]))
            z = np.stack([r - gamma[j], s - gamma[k]], axis=1) @ mat.T
            x = z @ e.T + gamma
            x[:, j], x[:, k] = r - 0.5, s - 0.5  # so that K_j = r, K_k = s
            ceil = np.ceil(x)
            if ceil.size and np.minimum(ceil - x, x - (ceil - 1)).min() < TOLERANCE * scale:
                raise InvalidProblem("the pentagrid of this seed has three lines through one point in the window "
                                     "(a singular grid); choose another seed")
            centre = ceil @ e + (e[j] + e[k]) / 2
            keep = (centre[:, 0] >= x0) & (centre[:, 0] < x0 + w) & (centre[:, 1] >= y0) & (centre[:, 1] < y0 + h)
            kk = ceil[keep].astype(np.int64)
            # the marked vertex is the one of index 2 or 3 at the rhomb's acute (thick) or obtuse (thin)
            # ends: K when sum K = 2, K + zeta^j + zeta^k when sum K = 1
            flip = kk.sum(axis=1) == 1
            corners = np.stack([0 * unit[j], unit[j], unit[j] + unit[k], unit[k]])
            order = [0, 1, 2, 3] if (k - j) in (1, 2) else [0, 3, 2, 1]  # counter-clockwise
            table = np.stack([corners[order], np.roll(corners, -2, axis=0)[order]])
            base = kk[:, :4] - kk[:, 4:5]
            verts.append(base[:, None, :] + table[flip.astype(np.intp)])
            types.append(np.full(len(kk), 1 if (k - j) in (1, 4) else 0, dtype=np.int8))
    return np.concatenate(types), np.concatenate(verts)


def _window_planes() -> tuple[np.ndarray, np.ndarray]:
    """The pentagons ``W_t = {sum lambda_j zeta^(2j) : 0 <= lambda_j <= 1, sum lambda_j = t}``,
    ``t = 1..4``, as half-planes ``Re(q conj(n_m)) <= h[t - 1, m]`` on the ten normals ``n_m = exp(i pi m / 5)``."""
    corners = np.array([c for c in np.ndindex(*(2,) * 5)])
    image = corners @ np.exp(4j * np.pi * np.arange(5) / 5)
    normals = np.exp(1j * np.pi * np.arange(10) / 5)
    support = (image[:, None] * np.conj(normals)).real
    return normals, np.stack([support[corners.sum(axis=1) == t].max(axis=0) for t in (1, 2, 3, 4)])


def pentagrid_of(types, v) -> tuple[np.ndarray, int]:
    """Offsets ``gamma`` and a shift ``s`` such that the P3 patch ``(types, v)`` moved by ``s`` rhomb
    edges along x is, tile for tile, the pentagrid of ``gamma`` on the same region (the module
    docstring's correspondence).

    Raises
    ------
    InvalidProblem
        No open set of offsets draws the patch (it is no patch of a Penrose tiling, or not one
        of a regular pentagrid).
    """
    points = np.unique(np.asarray(v, dtype=np.int64).reshape(-1, 4), axis=0)
    classes = np.unique(points.sum(axis=1) % 5)
    free = [s for s in range(5) if not np.isin(-s % 5, classes)]
    if not free:
        raise InvalidProblem("the patch's vertices show all five index classes: no pentagrid draws it")
    s = free[0]
    moved = points + np.array([s, 0, 0, 0])
    index = (moved.sum(axis=1) - 1) % 5 + 1  # sum K_i of the lift K = (a_0..a_3, 0) + c (1, 1, 1, 1, 1)
    star = moved @ np.exp(4j * np.pi * np.arange(4) / 5)  # sum K_i zeta^(2i): the lift's internal point
    normals, h = _window_planes()
    # star - Gamma in W_index for every vertex: Re(Gamma conj(n)) >= Re(star conj(n)) - h[index]
    low = ((star[:, None] * np.conj(normals)).real - h[index - 1]).max(axis=0)
    corners = []  # the intersection's corners: where two boundary lines meet inside every half-plane
    for a in range(10):
        for b in range(a + 1, 10):
            if a + 5 != b:
                m = np.array([[normals[a].real, normals[a].imag], [normals[b].real, normals[b].imag]])
                corners.append(complex(*np.linalg.solve(m, [low[a], low[b]])))
    corners = np.array(corners)
    inside = corners[((corners[:, None] * np.conj(normals)).real >= low - 1e-12).all(axis=1)]
    gamma_star = inside.mean() if len(inside) else 0j
    if not len(inside) or ((gamma_star * np.conj(normals)).real - low).min() <= 1e-9:
        raise InvalidProblem("no regular pentagrid draws this patch")
    return 0.4 * (gamma_star * np.exp(-4j * np.pi * np.arange(5) / 5)).real, s


def deflate_rhombs(types, v) -> tuple[np.ndarray, np.ndarray]:
    """One substitution step of a P3 patch, scaled back to unit edges: rhombs cut into Robinson
    triangles, deflated, rejoined, and every coordinate multiplied by ``phi``."""
    t, v = rhombs(*deflate(*_split(types, v)))
    return t, _times_phi(v)


def _split(types, v):
    """The two Robinson triangles ``(A, B, C)`` of each marked rhomb ``B, A, C, A'``."""
    t = np.concatenate([types, types])
    return t, np.concatenate([v[:, 1], v[:, 3]]), np.concatenate([v[:, 0], v[:, 0]]), np.concatenate([v[:, 2], v[:, 2]])


def p2_from_p3(types, v) -> tuple[np.ndarray, np.ndarray]:
    """Kites (0) and darts (1) of the same region as P3 rhombs (the correspondence in the module
    docstring); tiles whose other half lies outside the patch are dropped."""
    t, a, b, c = _split(types, v)
    acute, obtuse = np.flatnonzero(t == 0), np.flatnonzero(t == 1)
    # acute (C, P, B) + obtuse (P, C, A): the obtuse apex is the acute's B, its B the acute's apex
    keys = np.concatenate([np.concatenate([b[acute], a[acute]], axis=1), np.concatenate([a[obtuse], b[obtuse]], axis=1)])
    i, j = _pairs(keys)
    lo, hi = np.minimum(i, j), np.maximum(i, j)
    ok = (lo < len(acute)) & (hi >= len(acute))
    ac, ob = acute[lo[ok]], obtuse[hi[ok] - len(acute)]
    kite = (c[ob], c[ac], a[ac])  # half-kite (A, B, C): apex A the kite's head
    used = np.zeros(len(t), bool)
    used[ob] = True
    rest = obtuse[~used[obtuse]]
    dart = (a[rest], b[rest], c[rest])  # half-dart: apex A the dart's reflex vertex
    out_t, out_v = [], []
    # mirror half-kites share apex and the axis end; mirror half-darts share the apex and the axis end
    for code, (pa, pb, pc), axis in ((0, kite, "b"), (1, dart, "b")):
        far = pb if axis == "b" else pc
        near = pc if axis == "b" else pb
        i, j = _pairs(np.concatenate([pa, far], axis=1))
        if code == 0:
            quad = np.stack([pa[i], near[i], far[i], near[j]], axis=1)  # head, side, tail, side
        else:
            quad = np.stack([far[i], near[i], pa[i], near[j]], axis=1)  # tip, side, reflex, side
        out_t.append(np.full(len(i), code, np.int8))
        out_v.append(_ccw(quad))
    return np.concatenate(out_t), np.concatenate(out_v)
