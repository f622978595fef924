"""The procedural object distribution function (class notes §6.6.2) as a fragment shader.

Per pixel, as :func:`tilesolve.constructive.poisson.object_distribution` does on the CPU: the
closest point of the tiled Poisson disk distribution (direct stochastic corner tiling, §3.3.1,
random access), whether the pixel lies within its Poisson disk, the pixel in the disk's frame,
the point's id and the distance to it. Every pixel equals the CPU's: the same closest point,
id (cell and rank); ``local`` and ``closest`` computed with the CPU's double precision
operations in the same order (bit for bit on llvmpipe; OpenGL promises IEEE double division
nowhere), and ``distance`` (hence ``inside``) numpy's ``hypot`` of the pixel's offset from the
point, which the shader returns (GLSL has no ``hypot``, and ``sqrt(x*x + y*y)`` is an ulp off
it at times).

The cells
---------
What a cell of the tiling holds depends on its four corner colours only (the corner tiles at
its corners, the edge tiles along its sides and its interior tile, §4.3): one of ``C**4``
*configurations*, the corner tile's eq. 2.5 number. :func:`cell_points` lists each
configuration's points in lexicographic order (the CPU's rank), each as its tile's origin in
the cell (0 or 1 each way) and its coordinates in its tile's frame, the float64 bits the CPU
adds; they go to integer textures, a configuration a row.

The passes
----------
1. One fragment per cell of the picture and a ring of cells around it: the configuration,
   hashed with the long-period hash of the texture mapper (:data:`tilesolve.gpu.texture.HASH_GLSL`:
   the origin enters as residues of the permutation tables, so any origin of the 63-bit
   lattice; 32-bit integers only).
2. One fragment per pixel: its own cell, then the four beside it and the four diagonal ones,
   each skipped when the pixel lies farther from it than the closest point so far (the notes'
   largest empty circle, §6.6.2.1, measured per pixel); in a cell, whose points are sorted
   lexicographically (§6.6.2.1), a binary search finds the pixel's x, and the scan goes east and
   then west from there, each way until a point lies farther in x than the closest so far; the
   search ends at a point closer than the disk radius (no other can be closer, §6.6.2.1). Distances in double precision (OpenGL
   4.0's ``double``, which llvmpipe has), so the closest point is the CPU's. The pixel's
   position in its cell comes per column and per row from the CPU, as the float64 bits the CPU
   evaluates at.

Pictures larger than one render pass are evaluated pass by pass.
"""

from __future__ import annotations

import numpy as np

from tilesolve.constructive.hashes import check_int, check_window
from tilesolve.errors import InternalError, InvalidProblem
from tilesolve.gpu.picture import pass_layout
from tilesolve.gpu.texture import _FRAGMENT_IDS, PassRenderer, hash_tables, row_table
from tilesolve.model.poisson import PoissonTileSet
from tilesolve.model.window import Window

__all__ = ["PASS_PIXELS", "cell_points", "ObjectMapper", "objects"]

#: Most pixels a render pass evaluates (its four targets take 64 bytes a pixel).
PASS_PIXELS = 1 << 22

#: The search: the pixel's cell and its eight neighbours, configurations from pass 1.
_FRAGMENT_OBJECTS = """
#version 450
uniform usampler2D u_cols;   // pixel column of the pass: f.x (double bits), own cell in u_cells, own cell from the origin
uniform usampler2D u_rows;   // the same for the pixel row (f.y)
uniform usampler2D u_cells;  // cell -> configuration (pass 1), (0, 0) the cell SW of the pass's first
uniform usampler2D u_count;  // configuration -> points in the cell
uniform usampler2D u_frame;  // (rank, configuration): the point in its tile's frame, x and y as double bits
uniform usampler2D u_org;    // (rank, configuration): its tile's origin in the cell, x + 2 y
uniform uvec2 u_r;           // the disk radius (double bits)
layout(location = 0) out ivec4 o_id;       // cell of the closest point (from the origin), rank (-1: none)
layout(location = 1) out uvec4 o_local;    // local x, y (double bits)
layout(location = 2) out uvec4 o_closest;  // closest point from the origin x, y (double bits)
layout(location = 3) out uvec4 o_offset;   // the pixel less the closest point x, y (double bits)

const ivec2 ORDER[9] = ivec2[9](ivec2(0, 0), ivec2(-1, 0), ivec2(1, 0), ivec2(0, -1), ivec2(0, 1),
                                ivec2(-1, -1), ivec2(1, -1), ivec2(-1, 1), ivec2(1, 1));

// Point i of configuration cfg in the frame of the pixel's cell, its cell at d from the pixel's.
dvec2 point(int i, int cfg, ivec2 d) {
    uvec4 w = texelFetch(u_frame, ivec2(i, cfg), 0);
    uint o = texelFetch(u_org, ivec2(i, cfg), 0).r;
    return dvec2(d + ivec2(int(o & 1u), int(o >> 1))) + dvec2(packDouble2x32(w.xy), packDouble2x32(w.zw));
}

double gap(int d, double f) { return d < 0 ? f : (d > 0 ? 1.0LF - f : 0.0LF); }

void main() {
    ivec2 pix = ivec2(gl_FragCoord.xy);
    uvec4 col = texelFetch(u_cols, ivec2(pix.x, 0), 0), row = texelFetch(u_rows, ivec2(pix.y, 0), 0);
    dvec2 f = dvec2(packDouble2x32(col.xy), packDouble2x32(row.xy));
    ivec2 k = ivec2(col.z, row.z);
    double r = packDouble2x32(u_r), r2 = r * r;
    double best = 4.0LF;  // farther than one tile side: the CPU refuses it too
    ivec2 bcell = ivec2(0);
    int brank = -1;
    dvec2 bp = dvec2(0.0LF);
    for (int n = 0; n < 9 && best >= r2; n++) {
        ivec2 d = ORDER[n];
        double gx = gap(d.x, f.x), gy = gap(d.y, f.y);
        if (gx * gx + gy * gy >= best) continue;
        int cfg = int(texelFetch(u_cells, k + d, 0).r);
        int cnt = int(texelFetch(u_count, ivec2(cfg, 0), 0).r);
        int lo = 0, hi = cnt;  // the first point not west of the pixel: the points are sorted by x
        while (lo < hi) {
            int mid = (lo + hi) >> 1;
            if (point(mid, cfg, d).x < f.x) lo = mid + 1; else hi = mid;
        }
        // from there east, then west, each way until a point lies farther in x than the closest so far
        for (int step = 1; step >= -1; step -= 2) {
            for (int i = step > 0 ? lo : lo - 1; i >= 0 && i < cnt && best >= r2; i += step) {
                dvec2 p = point(i, cfg, d), e = f - p;
                if (e.x * e.x >= best) break;
                double d2 = e.x * e.x + e.y * e.y;
                if (d2 < best) {  // below r2: within the disk, the closest point (§6.6.2.1)
                    best = d2;
                    bp = p;
                    bcell = d;
                    brank = i;
                }
            }
        }
    }
    dvec2 e = f - bp, local = e / r;
    ivec2 own = ivec2(int(col.w), int(row.w));
    dvec2 closest = dvec2(own) + bp;
    o_id = ivec4(own + bcell, brank, 0);
    o_local = uvec4(unpackDouble2x32(local.x), unpackDouble2x32(local.y));
    o_closest = uvec4(unpackDouble2x32(closest.x), unpackDouble2x32(closest.y));
    o_offset = uvec4(unpackDouble2x32(e.x), unpackDouble2x32(e.y));
}
"""


def cell_points(tileset: PoissonTileSet) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The points of a cell of any tiling with ``tileset``, for each of its ``C**4`` configurations.

    Returns
    -------
    (counts, origin, frame)
        ``counts[t]``: the points of a cell whose corner tile is ``t`` (eq. 2.5); ``origin[t, i]``
        (int64, 0 or 1 each way) and ``frame[t, i]`` (float64): the ``i``-th point in
        lexicographic order, as its tile's origin in the cell and its coordinates in that tile's
        frame (their sum is the point in the cell, as :func:`tilesolve.constructive.poisson.place_tiles`
        gives them).
    """
    from tilesolve.constructive.poisson import place_tiles

    c = tileset.problem.colors
    parts = []
    for t in range(c**4):
        ne, se, sw, nw = t // c**3, t // c**2 % c, t // c % c, t % c
        offsets, frame, _, _ = place_tiles(tileset, np.array([[sw, se], [nw, ne]]))
        pts = offsets + frame
        keep = ((pts >= 0) & (pts < 1)).all(axis=1)
        order = np.lexsort((pts[keep, 1], pts[keep, 0]))
        parts.append((offsets[keep][order].astype(np.int64), frame[keep][order]))
    counts = np.array([len(o) for o, _ in parts], dtype=np.int64)
    k = max(1, int(counts.max()))
    origin = np.zeros((len(parts), k, 2), np.int64)
    frame = np.zeros((len(parts), k, 2))
    for t, (o, f) in enumerate(parts):
        origin[t, :len(o)], frame[t, :len(f)] = o, f
    return counts, origin, frame


def _bits(a: np.ndarray) -> np.ndarray:
    """float64 values as pairs of uint32 words (low, high), as ``packDouble2x32`` takes them."""
    return np.ascontiguousarray(a, dtype=np.float64).view(np.uint32).reshape(*np.shape(a), 2)


def _axis(first: int, count: int, px: int) -> tuple[np.ndarray, np.ndarray]:
    """Pixels ``first .. first + count - 1`` along an axis: their centres' cells and their
    positions in them, as :func:`tilesolve.families.poisson.objects` computes them."""
    v = (np.arange(first, first + count, dtype=np.int64) + 0.5) / px
    cell = np.floor(v).astype(np.int64)
    return cell, v - cell


class ObjectMapper(PassRenderer):
    """The object distribution function of ``tileset`` on the GPU, at ``px`` pixels a tile.

    Pixel ``(i, j)`` of a ``W x H`` picture (``j`` from the top) is evaluated at
    ``origin + ((i + 0.5) / px, (H - j - 0.5) / px)`` (tile units, y north), the tiling that of
    :func:`~tilesolve.constructive.poisson.object_distribution` with ``seed`` and ``hash``.

    Examples
    --------
    >>> from tilesolve.constructive.poisson import build_tiles
    >>> from tilesolve.model.poisson import PoissonTilesProblem
    >>> ts = build_tiles(PoissonTilesProblem(1, 16, 0.7), seed=1)
    >>> out = ObjectMapper(ts, px=8, seed=2, origin=(-3, 2**40)).evaluate(16, 8)
    >>> out["id"].shape, bool(out["inside"].any()), float(out["distance"].max()) < 1
    ((8, 16, 3), True, True)
    """

    def __init__(self, tileset: PoissonTileSet, *, px: int, seed=None, origin=(0, 0), hash: str = "long") -> None:
        if not isinstance(tileset, PoissonTileSet):
            raise InvalidProblem(f"expected a PoissonTileSet, got {type(tileset).__name__}")
        self.tileset = tileset
        self.px = check_int(px, "pixels a tile", 1)
        self.x0, self.y0, _, _ = check_window(origin[0], origin[1], 1, 1, what="origin")
        self.colors = tileset.problem.colors
        self.radius = tileset.problem.distance / 2
        self.tables, perm, red = hash_tables(self.colors, seed, hash)
        counts, org, frame = cell_points(tileset)
        self._setup()
        if org.shape[1] > self.max_pass or len(counts) > self.max_pass:
            raise InvalidProblem(f"a cell of {org.shape[1]} points is more than a texture row of {self.max_pass}")
        self._perm = self._int_texture(perm, 1)
        self._red = self._int_texture(red[None, :], 1)
        self._count = self._int_texture(counts[None, :], 1)
        self._org = self._int_texture(org[..., 0] + 2 * org[..., 1], 1)
        self._frame = self._int_texture(_bits(frame).reshape(len(counts), -1, 4), 4)
        self._ids = self._vertex_array(_FRAGMENT_IDS)
        self._search = self._vertex_array(_FRAGMENT_OBJECTS)
        units = {"u_perm": 0, "u_px": 1, "u_ym": 2, "u_red": 3, "u_cols": 4, "u_rows": 5, "u_cells": 6,
                 "u_count": 7, "u_frame": 8, "u_org": 9}
        for prog, _ in (self._ids, self._search):
            for name, unit in units.items():
                if name in prog:
                    prog[name].value = unit
        ids = self._ids[0]
        ids["u_colors"].value = self.colors
        ids["u_tile_px"].value = 1
        ids["u_offset"].value = (0, 0)
        ids["u_first"].value = (0, 0)
        self._search[0]["u_r"].value = tuple(int(v) for v in _bits(np.array(self.radius)))

    def _configurations(self, cx: np.ndarray, cy: np.ndarray):
        """Pass 1: the configuration of every cell from ``cx[0] - 1`` to ``cx[-1] + 1`` (and rows
        likewise), relative to the origin, into an integer texture (``(0, 0)`` the first)."""
        nx, ny = int(cx[-1] - cx[0]) + 3, int(cy[-1] - cy[0]) + 3
        textures = [self._int_texture(row_table(self.tables, self.x0 + int(cx[0]) - 1, nx + 1, True), 4),
                    self._int_texture(row_table(self.tables, self.y0 + int(cy[0]) - 1, ny + 1, False), 4)]
        out = self.ctx.texture((nx, ny), 1, dtype="u4")
        fbo = self.ctx.framebuffer(color_attachments=[out])
        try:
            fbo.use()
            self._perm.use(0)
            textures[0].use(1)
            textures[1].use(2)
            self._red.use(3)
            self._ids[1].render(mode=self.ctx.TRIANGLE_STRIP)
        finally:
            fbo.release()
            for t in textures:
                t.release()
        return out

    def _axis_texture(self, first: int, count: int):
        cell, f = _axis(first, count, self.px)
        a = np.empty((1, count, 4), np.uint32)
        a[0, :, :2] = _bits(f)
        a[0, :, 2] = cell - cell[0] + 1
        a[0, :, 3] = cell  # pixels lie east and north of the origin: cells >= 0
        return cell, self._int_texture(a, 4)

    def _evaluate_pass(self, left: int, bottom: int, w: int, h: int) -> list[np.ndarray]:
        """The pixels ``[left, left + w) x [bottom, bottom + h)`` (GL's y up) as the four
        render targets' arrays, bottom row first."""
        cx, cols = self._axis_texture(left, w)
        cy, rows = self._axis_texture(bottom, h)
        cells = self._configurations(cx, cy)
        targets = [self.ctx.texture((w, h), 4, dtype=dt) for dt in ("i4", "u4", "u4", "u4")]
        fbo = self.ctx.framebuffer(color_attachments=targets)
        try:
            fbo.use()
            for tex, unit in ((self._count, 7), (self._frame, 8), (self._org, 9), (cols, 4), (rows, 5), (cells, 6)):
                tex.use(unit)
            self._search[1].render(mode=self.ctx.TRIANGLE_STRIP)
            return [np.frombuffer(fbo.read(components=4, attachment=i, dtype=dt), dtype=np.int32 if i == 0 else
                                  np.uint32).reshape(h, w, 4) for i, dt in enumerate(("i4", "u4", "u4", "u4"))]
        finally:
            fbo.release()
            for t in targets + [cols, rows, cells]:
                t.release()

    def evaluate(self, width: int, height: int) -> dict:
        """The function at every pixel of a ``width x height`` picture whose SW corner is the origin.

        Returns
        -------
        dict
            :func:`~tilesolve.constructive.poisson.object_distribution`'s arrays, each shaped
            ``(height, width, ...)``, row 0 at the top: ``inside``, ``closest`` and ``id``
            relative to the origin, ``distance``, ``local``.
        """
        w, h, pass_w, _ = pass_layout(width, height, self.max_pass)
        band_h = max(1, min(self.max_pass, h, PASS_PIXELS // pass_w))
        out = {"inside": np.zeros((h, w), bool), "closest": np.zeros((h, w, 2)), "distance": np.zeros((h, w)),
               "local": np.zeros((h, w, 2)), "id": np.zeros((h, w, 3), np.int64)}
        for bottom in range(0, h, band_h):
            bh = min(band_h, h - bottom)
            rows = slice(h - bottom - bh, h - bottom)
            for left in range(0, w, pass_w):
                pw = min(pass_w, w - left)
                ident, local, closest, offset = (a[::-1] for a in self._evaluate_pass(left, bottom, pw, bh))
                e = _doubles(offset)
                d = np.hypot(e[..., 0], e[..., 1])
                if (ident[..., 2] < 0).any() or (d > 1).any():
                    raise InternalError("a point of evaluation lies farther than one tile side from every point "
                                        "of the set")
                cols = slice(left, left + pw)
                out["id"][rows, cols] = ident[..., :3]
                out["local"][rows, cols] = _doubles(local)
                out["closest"][rows, cols] = _doubles(closest)
                out["distance"][rows, cols] = d
        out["inside"] = out["distance"] < self.radius
        return out


def _doubles(words: np.ndarray) -> np.ndarray:
    """uint32 words, (low, high) pairs along the last axis, as float64 values: ``(..., 2k) -> (..., k)``."""
    return np.ascontiguousarray(words, dtype=np.uint32).view(np.float64)


def objects(ts: PoissonTileSet, window: Window, px: int, *, seed: int | None = None) -> dict:
    """:func:`tilesolve.families.poisson.objects` on the GPU: the function at the centres of the
    ``px`` pixels a tile of ``window`` (rows from the top), the same arrays."""
    return ObjectMapper(ts, px=px, seed=seed, origin=(window.x0, window.y0)).evaluate(window.width * px,
                                                                                       window.height * px)
