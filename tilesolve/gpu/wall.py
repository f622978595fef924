"""The procedural wall of Derouet-Jourdan, Salvati and Jonchier as a shader (004 §4.2-4.3, App. B, §5.2).

Edge colours
------------
The GLSL function ``wall_tile`` is :class:`tilesolve.constructive.walls` ``_ScalarWall.tile``
written out for the GPU: the FNV-1a/xorshift64* hashes of 004 §4.2 on 64-bit integers (kept
as pairs of 32-bit words so that one source serves OpenGL 4.5 and WebGL2, products by
``umulExtended`` or, in GLSL ES 3.00, from 16-bit halves; the paper fell back to float hashes
for lack of integers, §5.2), the multiply-shift reductions, procedural dappling (§4.3) and the
2x2 block solver of App. B (its table, :data:`~tilesolve.constructive.walls.APPENDIX_B`,
compiled into the shader). Every cell's leg colours ``(N, E, S, W)`` equal
:func:`~tilesolve.constructive.walls.wall_window` bit for bit, anywhere on the 63-bit lattice:
coordinates are the picture's origin (64-bit, from the CPU) plus small non-negative offsets,
so every modulo the shader takes is of a non-negative 32-bit number.

Bricks
------
Leg colour ``c`` puts the brick edge crossing that side of the cell at ``(c + 1) / (nc + 1)``
of it (as :mod:`tilesolve.io.svg_board` draws walls): a horizontal tile (``W = E``) has a
horizontal mortar line across the cell and two half vertical ones, a vertical tile the converse.
Each brick holds exactly one lattice point (the corners of the four cells around it), which
serves as the brick's id; its rectangle is fixed by the four edges that meet at that point,
two of them legs of the fragment's cell and two of the cell diagonally across the point. The
``data`` pass writes per fragment the brick, the distance to the brick's border (in cells) and
the UV of the fragment in the brick's rectangle (004 Fig. 10, Cartesian).

Two looks (:data:`LOOKS`) colour the bricks. ``brick`` (the default) is 004's: mortar near the
border, otherwise a red brick varied by a fourth hash stream of the brick id (004 Fig. 9 b),
bevelled. ``board`` is the look of every other wall picture, the board pictures of
:func:`tilesolve.io.board_png.brick_image` (the studio's view tiles among them), pixel for pixel
at one sample a pixel: their palette, :func:`tilesolve.io.board_png.picture_palette` (a colour per
brick, :func:`tilesolve.io.wall_png.brick_palette`'s or a palette chosen in the studio, dark
mortar), as a 256 x 1 texture (``u_palette``), and their geometry: each edge at its position
rounded to a whole pixel (half to even, kept inside the cell), mortar lines
``max(1, round(cell_px / 10))`` pixels wide, a brick's colour the bricks' one hash
(:func:`tilesolve.model.brick_colour.brick_colour_index`) of its id. With several samples a
pixel, each sample is shaded at its own position, against edges nudged 1/256 px from their exact
place towards the rounded one (so that every pixel centre falls where the board picture puts it).

Passes
------
``per_fragment=False`` (default): a first pass computes, one fragment per cell, each cell's legs
(an RGBA8UI texture) and, for the cell's SW lattice point, the four edges that meet there and
the point's colour hash (an RG32UI texture); the second pass shades each pixel from two
fetches, its cell's legs and its brick's point (the ``board`` look's colours need the legs
only). ``per_fragment=True`` evaluates ``wall_tile`` in every fragment (twice: the cell and
its diagonal neighbour), as 004 §5.2 describes. Both give the same picture. Multisampling
renders into a multisample target with per-sample shading and resolves it; the sample counts
are those the context allows (Mesa llvmpipe: 1, 2, 4).

In the browser
--------------
:func:`webgl_wall` hands the studio (``static/webgl.js``) these very shaders as GLSL ES 3.00
(WebGL2) in the ``board`` look: the same source behind a ``#version 300 es`` header with the
precisions ES asks for, the uniforms of a seed and colouring, and the palette. The page places
the window itself (``u_origin``, ``u_local0``, ``u_dres``, ``u_offset`` and ``u_first``,
computed as :class:`WallRenderer` does).
"""

from __future__ import annotations

import numpy as np

from tilesolve.constructive.hashes import FnvXorshift, check_int, check_window
from tilesolve.constructive.walls import APPENDIX_B, SOURCES, dappling_period
from tilesolve.errors import InvalidProblem
from tilesolve.gpu.context import gpu_context, max_render_size, release
from tilesolve.gpu.texture import DIV_GLSL
from tilesolve.gpu.picture import assemble_bands, pass_layout
from tilesolve.io.board_png import picture_palette
from tilesolve.io.wall_png import MORTAR, N_BRICK_COLOURS

__all__ = ["LOOKS", "SAMPLE_COUNTS", "WallRenderer", "allowed_samples", "webgl_wall"]

#: How the bricks are coloured: ``brick`` (004 Fig. 9 b: red bricks varied by a hash of the brick,
#: light mortar, a bevel; the default of ``tilesolve render wall``) or ``board`` (the board
#: pictures, :func:`tilesolve.io.board_png.brick_image`: a colour of
#: :func:`~tilesolve.io.wall_png.brick_palette` per brick, dark mortar; the studio's).
LOOKS = ("brick", "board")
#: The sample counts of 004 Table 1 (and 4, which llvmpipe offers).
SAMPLE_COUNTS = (1, 2, 4, 8, 16, 32)
#: Extra cells around a pass: the dappling neighbours two cells away and the brick's diagonal cell.
_MARGIN = 4
#: Texture units of the second pass: the first pass's two targets, the palette.
_UNITS = {"u_cells": 0, "u_points": 1, "u_palette": 2}


def _option_glsl() -> str:
    """App. B as GLSL constants: ``NOPT[case]`` and ``OPT[3 * case + option]`` (indices into :data:`SOURCES`)."""
    nopt, opt = [], []
    for case in range(16):
        fills = APPENDIX_B[format(case, "04b")]
        nopt.append(len(fills))
        for k in range(3):
            f = fills[k] if k < len(fills) else fills[0]
            opt.append("ivec4(" + ", ".join(str(SOURCES.index(s)) for s in f) + ")")
    return (f"const uint NOPT[16] = uint[16]({', '.join(f'{n}u' for n in nopt)});\n"
            f"const ivec4 OPT[48] = ivec4[48]({', '.join(opt)});\n")


_HEADER = "#version 450\n"
#: The same shaders as GLSL ES 3.00 (WebGL2): ES has no default precision for these.
_ES_HEADER = ("#version 300 es\nprecision highp float;\nprecision highp int;\nprecision highp usampler2D;\n"
              "precision highp sampler2D;\n")

WALL_GLSL = """
uniform uvec2 u_basis[4];    // FNV-1a states after seed and stream (streams 0 H, 1 V, 2 option, 3 colour)
uniform uvec2 u_origin[2];   // the 64-bit cell (I0, J0) of local (0, 0); I0, J0 are multiples of 4
uniform uint u_nc;           // colours nc
uniform int u_p;             // dappling period P (0: no limit)
uniform bool u_fixed;        // odd max_line: one checkerboard type
uniform int u_dres;          // (I0 - J0) % P + P * pad, so that u_dres + i - j >= 0 for local i, j

""" + _option_glsl() + """
// FNV-1a over the 32-bit words of x and y, then xorshift64* (004 §4.2); the high 32 bits.
// 64-bit values are (lo, hi) word pairs, so that the same source compiles as GLSL 4.50 and as
// GLSL ES 3.00 (WebGL2, which has no 64-bit integers); ES 3.00 has no umulExtended either, so
// there 32 x 32-bit products are made of 16-bit halves. uint arithmetic wraps modulo 2**32 in both.
uvec2 mul32(uint a, uint b) {   // a * b as (lo, hi)
#ifdef GL_ES
    uint a0 = a & 0xFFFFu, a1 = a >> 16, b0 = b & 0xFFFFu, b1 = b >> 16;
    uint p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0;
    uint mid = (p00 >> 16) + (p01 & 0xFFFFu) + (p10 & 0xFFFFu);
    return uvec2((mid << 16) | (p00 & 0xFFFFu), a1 * b1 + (p01 >> 16) + (p10 >> 16) + (mid >> 16));
#else
    uint hi, lo;
    umulExtended(a, b, hi, lo);
    return uvec2(lo, hi);
#endif
}

uvec2 mul64(uvec2 a, uvec2 b) { uvec2 p = mul32(a.x, b.x); return uvec2(p.x, p.y + a.x * b.y + a.y * b.x); }

// One FNV-1a step on the word w: (h ^ w) * 0x100000001B3, the prime being 2**40 + 0x1B3.
uvec2 fnv(uvec2 h, uint w) { uint l = h.x ^ w; uvec2 p = mul32(l, 0x1B3u); return uvec2(p.x, p.y + h.y * 0x1B3u + (l << 8)); }

// o + i with i sign-extended to 64 bits.
uvec2 add64(uvec2 o, int i) { uint lo = o.x + uint(i); return uvec2(lo, o.y + uint(lo < o.x) + (i < 0 ? 0xFFFFFFFFu : 0u)); }

uint raw(int k, int i, int j) {
    uvec2 x = add64(u_origin[0], i), y = add64(u_origin[1], j);
    uvec2 h = fnv(fnv(fnv(fnv(u_basis[k], x.x), x.y), y.x), y.y);
    h ^= uvec2((h.x >> 12) | (h.y << 20), h.y >> 12);
    h ^= uvec2(h.x << 25, (h.y << 25) | (h.x >> 7));
    h ^= uvec2((h.x >> 27) | (h.y << 5), h.y >> 27);
    return mul64(h, uvec2(0x4F6CDD1Du, 0x2545F491u)).y;   // xorshift64*'s multiplier 0x2545F4914F6CDD1D
}

uint reduce(uint r, uint k) { return mul32(r, k).y; }

uint d1(uint r, uint c) { uint m = reduce(r, u_nc - 1u); return m < c ? m : m + 1u; }

uint d2(uint r, uint c1, uint c2) {
    if (c1 == c2) return d1(r, c1);
    uint m = reduce(r, u_nc - 2u), lo = min(c1, c2), hi = max(c1, c2);
    return m < lo ? m : (m < hi - 1u ? m + 1u : m + 2u);
}

bool diagonal(int i, int j) {   // block (i, j) is a checkerboard
    if (u_p == 2) return true;
    if (u_p < 2) return false;
    int a = u_dres + i - j;
    return a - u_p * floor_div(ivec2(a, 0), u_p).x == 0;
}

uint hc(int i, int j) { return reduce(raw(0, i, j), u_nc); }
uint vc(int i, int j) { return reduce(raw(1, i, j), u_nc); }

uint h1(int i, int j) {   // h'(i, j), even j
    uint r = raw(0, i, j);
    if (u_p == 2) return (j & 3) == 0 ? reduce(r, u_nc) : d2(r, hc(i, j - 2), hc(i, j + 2));
    if (u_p > 2 && diagonal(i & ~1, j)) return d1(r, hc(i, j + 2));
    return reduce(r, u_nc);
}

uint v1(int i, int j) {   // v'(i, j), even i
    uint r = raw(1, i, j);
    if (u_p == 2) return (i & 3) == 0 ? reduce(r, u_nc) : d2(r, vc(i - 2, j), vc(i + 2, j));
    if (u_p > 2 && diagonal(i, j & ~1)) return d1(r, vc(i + 2, j));
    return reduce(r, u_nc);
}

// Leg colours (N, E, S, W) of local cell (i, j): the 2x2 block, its App. B case and filling.
uvec4 wall_tile(int i, int j) {
    int bi = i & ~1, bj = j & ~1;
    uint o[8] = uint[8](v1(bi, bj + 1), v1(bi + 2, bj + 1), h1(bi, bj), h1(bi, bj + 2),
                        v1(bi, bj), v1(bi + 2, bj), h1(bi + 1, bj), h1(bi + 1, bj + 2));
    int c = 8 * int(o[3] == o[2]) + 4 * int(o[6] == o[7]) + 2 * int(o[0] == o[1]) + int(o[4] == o[5]);
    uint option = (u_fixed && diagonal(bi, bj)) ? 0u : reduce(raw(2, bi, bj), NOPT[c]);
    ivec4 s = OPT[3 * c + int(option)];
    bool east = (i & 1) == 1, north = (j & 1) == 1;
    // Slot 0 vt1 (helper vd2T), 1 hl1 (hd2L), 2 vb1 (vd2B), 3 hr1 (hd2R): only the two this cell needs.
    uint a, b;
    if (!north) {
        a = s.z < 8 ? o[s.z] : d2(raw(1, bi + 1, bj), o[4], o[5]);                 // vb1
        b = east ? (s.w < 8 ? o[s.w] : d2(raw(0, bi + 1, bj + 1), o[6], o[7]))      // hr1
                 : (s.y < 8 ? o[s.y] : d2(raw(0, bi, bj + 1), o[3], o[2]));         // hl1
        return east ? uvec4(b, o[5], o[6], a) : uvec4(b, a, o[2], o[4]);
    }
    a = s.x < 8 ? o[s.x] : d2(raw(1, bi + 1, bj + 1), o[0], o[1]);                  // vt1
    b = east ? (s.w < 8 ? o[s.w] : d2(raw(0, bi + 1, bj + 1), o[6], o[7]))          // hr1
             : (s.y < 8 ? o[s.y] : d2(raw(0, bi, bj + 1), o[3], o[2]));             // hl1
    return east ? uvec4(o[7], o[1], b, a) : uvec4(o[3], a, b, o[0]);
}
"""

_VERTEX = _HEADER + """in vec2 in_pos;
void main() { gl_Position = vec4(in_pos, 0.0, 1.0); }
"""

#: First pass: one fragment per cell (local cell = fragment + u_first): its legs, and for its SW
#: lattice point (I, J) the four edges that meet there, H[I-1, J], H[I, J], V[I, J], V[I, J-1]
#: (one byte each: they bound the brick of that point), and the point's colour hash.
_CELLS_GLSL = """
uniform ivec2 u_first;
layout(location = 0) out uvec4 f_legs;
layout(location = 1) out uvec2 f_point;
void main() {
    ivec2 c = ivec2(gl_FragCoord.xy) + u_first;
    uvec4 ur = wall_tile(c.x, c.y), ll = wall_tile(c.x - 1, c.y - 1);
    f_legs = ur;
    f_point = uvec2(ll.x | (ur.z << 8) | (ur.w << 16) | (ll.y << 24), raw(3, c.x, c.y));
}
"""


def _picture_glsl() -> str:
    """The board pictures' colours (:func:`tilesolve.io.board_png.brick_image`) as GLSL: their
    brick hash (:func:`tilesolve.model.brick_colour.brick_colour_index`, on 32-bit word pairs) as a palette index,
    and their edges and mortar lines in pixels."""
    n = N_BRICK_COLOURS
    return f"const uint N_BRICK = {n}u;   // colours\n" \
           f"const int MORTAR = {MORTAR};\n" + """
uvec2 shr64(uvec2 h, int k) { return uvec2((h.x >> k) | (h.y << (32 - k)), h.y >> k); }   // 0 < k < 32

// The board pictures' colour of the brick whose top-left corner lies in local cell (i, j): the
// bricks' one hash (tilesolve.model.brick_colour.brick_colour_index) of its id, the lattice point
// (i + 1, j): x 0x9E3779B97F4A7C15 ^ y 0xC2B2AE3D27D4EB4F, splitmix64's finaliser, then the
// multiply-shift of the high word onto N_BRICK colours.
uint brick_index(int i, int j) {
    uvec2 h = mul64(add64(u_origin[0], i + 1), uvec2(0x7F4A7C15u, 0x9E3779B9u))
            ^ mul64(add64(u_origin[1], j), uvec2(0x27D4EB4Fu, 0xC2B2AE3Du));
    h = mul64(h ^ shr64(h, 30), uvec2(0x1CE4E5B9u, 0xBF58476Du));
    h = mul64(h ^ shr64(h, 27), uvec2(0x133111EBu, 0x94D049BBu));
    h ^= shr64(h, 31);
    return reduce(h.y, N_BRICK);
}

int round_half_even(int num, int den) {   // num / den rounded half to even (num >= 0, den > 0)
    int q = num / den, twice = 2 * (num - q * den);
    return q + ((twice > den || (twice == den && (q & 1) == 1)) ? 1 : 0);
}

// Where leg colour c puts its brick edge on a side of s pixels, counted from the side's start:
// (c + 1) s / (nc + 1) rounded to a whole pixel r (half to even) and kept in [1, s - 1] as the
// board pictures place it, as a position strictly within half a pixel of r, 1/256 px from the
// exact one towards r: so a pixel centre lies before it exactly when its pixel lies before r.
float edge_px(uint c, int s) {
    int den = int(u_nc) + 1, num = (int(c) + 1) * s, r = round_half_even(num, den);
    float e = float(r) + float(num - r * den) / float(den) * (255.0 / 256.0);
    return min(max(e, 1.0), float(s - 1));
}

// The palette index of the point `at` (pixels from the top-left corner) of local cell c, legs t,
// in a cell of s pixels: mortar on a line, else the colour of its brick.
int picture_index(uvec4 t, ivec2 c, vec2 at, int s) {
    int th = max(1, round_half_even(s, 10));
    float lo = float(th / 2), hi = float(th - th / 2);
    vec4 e = vec4(edge_px(t.x, s), edge_px(t.y, s), edge_px(t.z, s), edge_px(t.w, s));   // N, E, S, W
    bvec4 on = bvec4(at.x >= e.x - lo && at.x < e.x + hi, at.y >= e.y - lo && at.y < e.y + hi,
                     at.x >= e.z - lo && at.x < e.z + hi, at.y >= e.w - lo && at.y < e.w + hi);
    bool top, left, mortar;
    if (t.w == t.y) {   // horizontal tile: a line across at W = E, half lines at N (above) and S
        top = at.y < e.w;
        left = top ? at.x < e.x : at.x < e.z;
        mortar = on.w || (top ? on.x : on.z);
    } else {            // vertical tile: a line down at N = S, half lines at W (left) and E
        left = at.x < e.x;
        top = left ? at.y < e.w : at.y < e.y;
        mortar = on.x || (left ? on.w : on.y);
    }
    return mortar ? MORTAR : int(brick_index(c.x - int(left), c.y + int(top)));
}
"""

#: Second pass (or the only one, with PER_FRAGMENT): the bricks, per fragment or per sample, in
#: the look of 004 or, with BOARD, of the board pictures.
_SHADE_GLSL = """
uniform int u_cell_px;       // pixels per cell side
uniform ivec2 u_offset;      // this pass's lower-left pixel in the picture
uniform ivec2 u_local0;      // local cell of the picture's SW cell
uniform float u_mortar;      // half width of the mortar, in cells (004's look)
uniform usampler2D u_cells;  // first pass: legs of local cells u_first + texel
uniform usampler2D u_points; // first pass: edges and colour hash of the lattice point u_first + texel
uniform sampler2D u_palette; // 256 x 1: the board pictures' palette (tilesolve.io.board_png.picture_palette)
uniform ivec2 u_first;
layout(location = 0) out vec4 f_colour;
#ifdef DATA
layout(location = 1) out ivec2 f_brick;   // the brick's lattice point, relative to the picture's SW cell
layout(location = 2) out vec4 f_geom;     // distance to the border (cells), u, v, 1 if horizontal tile
#endif

uvec4 legs(ivec2 c) {
#ifdef PER_FRAGMENT
    return wall_tile(c.x, c.y);
#else
    return texelFetch(u_cells, c - u_first, 0);
#endif
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy) + u_offset;
    ivec2 cell = floor_div(p, u_cell_px);
#ifdef SAMPLES
    vec2 sub = gl_SamplePosition;
#else
    vec2 sub = vec2(0.5);
#endif
    ivec2 in_cell = p - cell * u_cell_px;
    vec2 f = (vec2(in_cell) + sub) / float(u_cell_px);   // in the cell, from its SW corner
    ivec2 c = cell + u_local0;
    uvec4 t = legs(c);
    float k = float(u_nc + 1u);
    vec4 pos = (vec4(t) + 1.0) / k;   // where each leg's brick edge crosses its side
    bool horizontal = t.w == t.y;
    float ft = 1.0 - f.y;            // from the top of the cell, as the legs' positions count
    bool upper, right;
    if (horizontal) {
        upper = ft < pos.w;
        right = f.x >= (upper ? pos.x : pos.z);
    } else {
        right = f.x >= pos.x;
        upper = ft < (right ? pos.y : pos.w);
    }
    ivec2 corner = ivec2(right ? 1 : 0, upper ? 1 : 0);   // the brick's lattice point: c + corner
    // Edges at the point (I, J): H[I-1, J], H[I, J], V[I, J], V[I, J-1]; its colour hash.
    uint hl, hr, vt, vb, shade;
#ifdef PER_FRAGMENT
    uvec4 u = legs(c + 2 * corner - 1);                    // the cell diagonally across the point
    if (corner.x == corner.y) {   // this cell and its neighbour are LL and UR
        uvec4 ll = corner.x == 1 ? t : u, ur = corner.x == 1 ? u : t;
        hl = ll.x; hr = ur.z; vt = ur.w; vb = ll.y;
    } else {                      // UL and LR
        uvec4 ul = corner.x == 1 ? t : u, lr = corner.x == 1 ? u : t;
        hl = ul.z; hr = lr.x; vt = ul.y; vb = lr.w;
    }
    shade = raw(3, c.x + corner.x, c.y + corner.y);
#else
    uvec2 point = texelFetch(u_points, c + corner - u_first, 0).xy;
    hl = point.x & 255u; hr = (point.x >> 8) & 255u; vt = (point.x >> 16) & 255u; vb = point.x >> 24;
    shade = point.y;
#endif
    vec2 q = f - vec2(corner);                            // relative to the lattice point
    vec2 lo = vec2(-1.0 + (float(hl) + 1.0) / k, -(float(vb) + 1.0) / k);
    vec2 hi = vec2((float(hr) + 1.0) / k, 1.0 - (float(vt) + 1.0) / k);
    vec2 uv = (q - lo) / (hi - lo);
    float dist = min(min(q.x - lo.x, hi.x - q.x), min(q.y - lo.y, hi.y - q.y));
    ivec2 brick = c + corner - u_local0;
#ifdef BOARD
    vec2 at = vec2(float(in_cell.x) + sub.x, float(u_cell_px - in_cell.y) - sub.y);   // from the top-left, px
    f_colour = texelFetch(u_palette, ivec2(picture_index(t, c, at, u_cell_px), 0), 0);
#else
    vec3 base = vec3(0.60, 0.27, 0.17) * (0.75 + 0.45 * float(shade >> 24) / 255.0)
              + vec3(0.06, 0.03, 0.0) * float((shade >> 16) & 255u) / 255.0;
    float edge = smoothstep(u_mortar, u_mortar + 0.06, dist);
    vec3 mortar = vec3(0.78, 0.76, 0.72);
    f_colour = vec4(mix(mortar, base * (0.8 + 0.2 * smoothstep(0.0, 0.25, dist)), edge), 1.0);
#endif
#ifdef DATA
    f_brick = brick;
    f_geom = vec4(dist, uv, horizontal ? 1.0 : 0.0);
#endif
}
"""


def _fragment(kind: str, *, per_fragment: bool = False, samples: bool = False, look: str = "brick",
              header: str | None = None) -> str:
    """The fragment shader of a pass: ``cells`` (first pass), ``colour`` or ``data`` (second) in
    the ``look`` of :data:`LOOKS`, behind ``header`` (by default :data:`_HEADER`, GLSL 4.50)."""
    header = _HEADER if header is None else header
    if kind == "cells":
        return header + DIV_GLSL + WALL_GLSL + _CELLS_GLSL
    defines = "#define PER_FRAGMENT\n" if per_fragment else ""
    if kind == "data":
        defines += "#define DATA\n"
    if kind == "colour" and samples:
        defines += "#define SAMPLES\n"
    if look == "board":
        return header + defines + "#define BOARD\n" + DIV_GLSL + WALL_GLSL + _picture_glsl() + _SHADE_GLSL
    return header + defines + DIV_GLSL + WALL_GLSL + _SHADE_GLSL


def _wall_params(colors, max_line, seed) -> tuple[int, int, bool, int]:
    """``(colours, dappling period, fixed, seed)`` of a wall, checked (one-line errors)."""
    nc = check_int(colors, "colors", 3)
    if nc > 127:
        raise InvalidProblem(f"tilesolve draws walls with at most 127 colours, got {nc}")
    seed = check_int(seed, "seed", 0)
    if seed >= 1 << 64:
        raise InvalidProblem(f"seed must be below 2**64, got {seed}")
    return nc, dappling_period(max_line), max_line is not None and int(max_line) % 2 == 1, seed


def _palette(colours=None) -> np.ndarray:
    """``(1, 256, 4)`` uint8 RGBA of the ``u_palette`` texture: the board pictures' palette
    (:func:`tilesolve.io.board_png.picture_palette`, their bricks in ``colours`` when given)."""
    rgb = np.asarray(picture_palette(colours), dtype=np.uint8)
    return np.concatenate([rgb, np.full((len(rgb), 1), 255, np.uint8)], axis=1)[None]


def webgl_wall(*, colors: int = 3, max_line: int | None = None, seed: int = 0, colours=None) -> dict:
    """The wall's shaders as GLSL ES 3.00 for WebGL2, in the board pictures' look (the studio's
    view tiles), and the uniforms that hold for every window.

    Returns
    -------
    dict
        ``vertex``, and the fragment shaders ``cells`` (first pass), ``colour`` and ``data``
        (second pass, as :class:`WallRenderer` draws them with one sample per pixel): this
        module's GLSL behind a ``#version 300 es`` header and the precisions ES asks for.
        ``uniforms``: ``u_basis`` (the four streams' FNV-1a states as eight 32-bit words, low
        word first), ``u_nc``, ``u_p``, ``u_fixed``. ``palette``: the 256 ``[r, g, b]`` texels
        of ``u_palette`` (:func:`tilesolve.io.board_png.picture_palette` of ``colours``: the board
        pictures' colours, their bricks in ``colours`` when given, as the studio's view tiles in
        a chosen palette). ``margin``: the cells a pass reaches south-west of the picture.

    Examples
    --------
    >>> w = webgl_wall(colors=3, max_line=4, seed=2)
    >>> w["colour"].splitlines()[0], w["uniforms"]["u_p"], len(w["uniforms"]["u_basis"])
    ('#version 300 es', 4, 8)
    """
    nc, period, fixed, seed = _wall_params(colors, max_line, seed)
    basis = [w for k in range(4) for w in _uvec2(FnvXorshift(seed, k).basis)]
    return {"vertex": _ES_HEADER + _VERTEX.removeprefix(_HEADER),
            **{kind: _fragment(kind, look="board", header=_ES_HEADER) for kind in ("cells", "colour", "data")},
            "uniforms": {"u_basis": basis, "u_nc": nc, "u_p": period, "u_fixed": fixed},
            "palette": _palette(colours)[0, :, :3].tolist(), "margin": _MARGIN}


def allowed_samples(ctx=None) -> tuple[int, ...]:
    """The sample counts of :data:`SAMPLE_COUNTS` this context can render (llvmpipe: 1, 2, 4)."""
    ctx = ctx or gpu_context()
    return tuple(s for s in SAMPLE_COUNTS if s <= max(1, int(ctx.max_samples)))


def _uvec2(v: int) -> tuple[int, int]:
    v &= (1 << 64) - 1
    return v & 0xFFFFFFFF, v >> 32


class WallRenderer:
    """Renders pictures of the procedural wall (004) on the GPU.

    Pixel ``(px, py)`` of a ``W x H`` picture (``py`` from the top) lies in cell
    ``(x0 + px // cell_px, y0 + (H - 1 - py) // cell_px)`` of
    :func:`~tilesolve.constructive.walls.wall_window` (``j`` grows northwards).

    Examples
    --------
    >>> from tilesolve.constructive.walls import wall_window
    >>> r = WallRenderer(colors=3, max_line=4, seed=2, origin=(-7, 3))
    >>> bool((r.cell_legs(10, 6) == wall_window(-7, 3, 10, 6, colors=3, max_line=4, seed=2)).all())
    True
    """

    def __init__(self, *, colors: int = 3, max_line: int | None = None, seed: int = 0, origin=(0, 0),
                 cell_px: int = 32, samples: int = 1, per_fragment: bool = False, look: str = "brick",
                 mortar: float = 0.04) -> None:
        self.nc, self.period, self.fixed, self.seed = _wall_params(colors, max_line, seed)
        x0, y0 = origin
        self.x0, self.y0, _, _ = check_window(x0, y0, 1, 1, what="wall window")
        self.cell_px = check_int(cell_px, "cell size", 1)
        self.per_fragment = bool(per_fragment)
        if look not in LOOKS:
            raise InvalidProblem(f"look must be one of {', '.join(LOOKS)}, got {look!r}")
        self.look, self.mortar = look, float(mortar)
        self.ctx = gpu_context()
        self.max_pass = max_render_size(self.ctx)
        s = check_int(samples, "samples", 1)
        if s not in SAMPLE_COUNTS:
            raise InvalidProblem(f"samples must be one of {', '.join(map(str, SAMPLE_COUNTS))}, got {s}")
        allowed = allowed_samples(self.ctx)
        if s not in allowed:
            raise InvalidProblem(f"this OpenGL context ({self.ctx.info['GL_RENDERER']}) renders at most "
                                 f"{allowed[-1]} samples per pixel; got {s}")
        self.samples = s
        self.basis = [FnvXorshift(self.seed, k).basis for k in range(4)]
        # Local cell coordinates start at a multiple of 4 a margin south-west of the picture.
        self.i0 = self.x0 - _MARGIN - self.x0 % 4
        self.j0 = self.y0 - _MARGIN - self.y0 % 4
        self.local0 = (self.x0 - self.i0, self.y0 - self.j0)
        if self.x0 + (1 << 31) >= 1 << 62 or self.y0 + (1 << 31) >= 1 << 62:
            raise InvalidProblem("the wall picture must stay inside |cell coordinates| < 2**62")
        self._quad = self.ctx.buffer(np.array([-1, -1, 1, -1, -1, 1, 1, 1], dtype="f4").tobytes())
        self._palette = self.ctx.texture((256, 1), 4, _palette().tobytes())
        self._palette.filter = (self.ctx.NEAREST, self.ctx.NEAREST)
        self._programs: dict = {}

    def _program(self, kind: str):
        if kind not in self._programs:
            src = _fragment(kind, per_fragment=self.per_fragment, samples=self.samples > 1, look=self.look)
            prog = self.ctx.program(vertex_shader=_VERTEX, fragment_shader=src)
            if "u_basis" in prog:  # the compiler drops what a pass does not use (streams, uniforms)
                basis = prog["u_basis"]
                basis.value = [_uvec2(b) for b in self.basis[:basis.array_length]]
            p = max(self.period, 1)
            values = {"u_origin": [_uvec2(self.i0), _uvec2(self.j0)], "u_nc": self.nc, "u_p": self.period,
                      "u_fixed": self.fixed, "u_dres": (self.i0 - self.j0) % p + p * -(-(1 << 16) // p),
                      "u_cell_px": self.cell_px, "u_local0": self.local0, "u_mortar": self.mortar, **_UNITS}
            for name, value in values.items():
                if name in prog:
                    prog[name].value = value
            self._programs[kind] = (prog, self.ctx.vertex_array(prog, [(self._quad, "2f", "in_pos")]))
        return self._programs[kind]

    def _check_pass(self, width, height) -> tuple[int, int]:
        w, h = check_int(width, "width", 1), check_int(height, "height", 1)
        if w > self.max_pass or h > self.max_pass:
            raise InvalidProblem(f"one render pass is at most {self.max_pass} px each way; got {w}x{h}")
        if (w // self.cell_px + 2 * _MARGIN) >= 1 << 15 or (h // self.cell_px + 2 * _MARGIN) >= 1 << 15:
            raise InvalidProblem("one render pass covers at most 32,000 cells each way")
        return w, h

    def cell_legs(self, cols: int, rows: int) -> np.ndarray:
        """``(rows, cols, 4)`` int8 legs ``(N, E, S, W)`` of the picture's cells, row 0 at the top
        (the first pass alone; :func:`~tilesolve.constructive.walls.wall_window`'s layout)."""
        w, h = self._check_pass(cols, rows)
        tex = self.ctx.texture((w, h), 4, dtype="u1")
        fbo = self.ctx.framebuffer(color_attachments=[tex])
        try:
            self._cells(fbo, self.local0)
            out = np.frombuffer(fbo.read(components=4, dtype="u1"), dtype=np.uint8).reshape(h, w, 4)
            return out[::-1].astype(np.int8)
        finally:
            fbo.release()
            tex.release()

    def _cells(self, fbo, first) -> None:
        prog, vao = self._program("cells")
        prog["u_first"].value = tuple(first)
        fbo.use()
        vao.render(mode=self.ctx.TRIANGLE_STRIP)

    def _cells_target(self, w: int, h: int):
        n = (min(self.max_pass, (w - 1) // self.cell_px + 4), min(self.max_pass, (h - 1) // self.cell_px + 4))
        return self.ctx.framebuffer(color_attachments=[self.ctx.texture(n, 4, dtype="u1"),
                                                       self.ctx.texture(n, 2, dtype="u4")])

    def _pass(self, kind: str, fbo, offset, cells_fbo=None) -> None:
        """Shade the picture's pixels ``offset + [0, fbo.size)`` (GL coordinates) into ``fbo``."""
        prog, vao = self._program(kind)
        ox, oy = offset
        first = (ox // self.cell_px + self.local0[0] - 1, oy // self.cell_px + self.local0[1] - 1)
        if cells_fbo is not None:
            self._cells(cells_fbo, first)
            cells_fbo.color_attachments[0].use(_UNITS["u_cells"])
            cells_fbo.color_attachments[1].use(_UNITS["u_points"])
        self._palette.use(_UNITS["u_palette"])
        prog["u_offset"].value = (ox, oy)
        if "u_first" in prog:
            prog["u_first"].value = first
        fbo.use()
        vao.render(mode=self.ctx.TRIANGLE_STRIP)

    def data(self, width: int, height: int) -> dict:
        """One sample per pixel, row 0 at the top: ``colour`` (H, W, 4) uint8, ``brick`` (H, W, 2)
        int32 lattice point of the brick relative to the picture's SW cell, ``distance``, ``u``,
        ``v`` (float32, cells and brick fractions) and ``horizontal`` (bool, the cell's tile)."""
        w, h = self._check_pass(width, height)
        texs = [self.ctx.texture((w, h), 4), self.ctx.texture((w, h), 2, dtype="i4"),
                self.ctx.texture((w, h), 4, dtype="f4")]
        fbo = self.ctx.framebuffer(color_attachments=texs)
        cells = None if self.per_fragment else self._cells_target(w, h)
        try:
            self._pass("data", fbo, (0, 0), cells)
            colour = np.frombuffer(fbo.read(components=4, attachment=0), np.uint8).reshape(h, w, 4)
            brick = np.frombuffer(fbo.read(components=2, attachment=1, dtype="i4"), np.int32).reshape(h, w, 2)
            geom = np.frombuffer(fbo.read(components=4, attachment=2, dtype="f4"), np.float32).reshape(h, w, 4)
        finally:
            fbo.release()
            for t in texs:
                t.release()
            if cells is not None:
                release(cells)
        geom = geom[::-1]
        return {"colour": colour[::-1].copy(), "brick": brick[::-1].copy(), "distance": geom[..., 0].copy(),
                "u": geom[..., 1].copy(), "v": geom[..., 2].copy(), "horizontal": geom[..., 3] > 0.5}

    def _targets(self, w: int, h: int):
        """``(draw target, resolved target or None)`` of a ``w x h`` pass."""
        if self.samples == 1:
            return self.ctx.simple_framebuffer((w, h), components=4), None
        ms = self.ctx.framebuffer(color_attachments=[self.ctx.renderbuffer((w, h), 4, samples=self.samples)])
        return ms, self.ctx.simple_framebuffer((w, h), components=4)

    def frame(self, width: int, height: int):
        """A render target and a function drawing one frame (the picture's lower-left pass) into it."""
        w, h = self._check_pass(width, height)
        target, resolved = self._targets(w, h)
        cells = None if self.per_fragment else self._cells_target(w, h)

        def draw() -> None:
            self._pass("colour", target, (0, 0), cells)
            if resolved is not None:
                self.ctx.copy_framebuffer(resolved, target)

        return resolved or target, draw

    def bands(self, width: int, height: int):
        """The picture as ``(rows, width, 4)`` uint8 RGBA bands from the top (passes as in
        :meth:`tilesolve.gpu.texture.TextureMapper.bands`)."""
        w, h, pass_w, band_h = pass_layout(width, height, self.max_pass)
        self._check_pass(pass_w, band_h)
        cells = None if self.per_fragment else self._cells_target(pass_w, band_h)
        made: dict = {}

        def read_pass(left, bottom, pw, bh):
            if (pw, bh) not in made:
                made[(pw, bh)] = self._targets(pw, bh)
            target, resolved = made[(pw, bh)]
            self._pass("colour", target, (left, bottom), cells)
            if resolved is not None:
                self.ctx.copy_framebuffer(resolved, target)
            return np.frombuffer((resolved or target).read(components=4), np.uint8).reshape(bh, pw, 4)

        try:
            yield from assemble_bands(w, h, pass_w, band_h, read_pass)
        finally:
            for pair in made.values():
                for f in pair:
                    if f is not None:
                        release(f)
            if cells is not None:
                release(cells)

    def image(self, width: int, height: int) -> np.ndarray:
        """The whole picture, ``(height, width, 4)`` uint8, row 0 at the top."""
        return np.concatenate(list(self.bands(width, height)), axis=0)
