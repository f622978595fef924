"""Tile-based texture mapping with corner tiles on the GPU (class notes §5.3-5.4; Wei 2004).

The atlas
---------
The ``C**4`` tiles of the complete corner set over ``C`` colours are laid out as a *corner
tile packing* (§5.5.3, :func:`tilesolve.families.packing.solve`): a ``C**2 x C**2`` toroidal
arrangement in which touching corners have the same colour. Texture filtering reads texels
of the neighbouring tiles of the atlas; because the packing is a valid tiling and the texels
near a tile's border depend on its corner colours only, those texels are the ones any valid
neighbour would show, so bilinear and mipmapped filtering across tile borders is seamless
(§5.4: "this configuration must also be a valid tiling"; the atlas wraps toroidally).

:func:`synthesize_atlas` builds the tile images from an example image by the corner-patch
construction of Ng et al. (§5.3, Fig. 5.1): one random square patch of the example per corner
colour, each tile the four quarter patches of its corner colours (Fig. 5.1 b-c), and the
cross-shaped seam covered by a new diamond-shaped patch of the example inside the tile's
inscribed circle (Fig. 5.1 d), its border optimised by a graph cut (Kwatra et al. 2003,
:func:`graph_cut`: the minimum-error boundary between the new patch and the quarters). Each
patch is placed where it fits best, as image quilting places its blocks (Efros & Freeman 2001):
a corner patch where its edges continue the others' where the tiles' middle lines reach their
borders, the new patch where it matches the quarters around the seam (a random one of the close
fits, so tiles differ). The border of each tile is untouched, which is what makes the tiles fit.
A tile must hold a few of the example's structures (bricks, :func:`structure_size`): a smaller one
is synthesised at twice or four times its size and averaged down (:func:`synthesis_scale`), so
the texture shows the example smaller rather than stripes and broken mortar.

The shader
----------
Per fragment (§5.4): the tile coordinates and the coordinates inside the tile; the tile by the
direct stochastic corner tiling (§3.3.1): corners ``h(x+1, y+1), h(x+1, y), h(x, y), h(x, y+1)``
of the long-period hash (§3.4.3), integer arithmetic on the permutation tables fetched with
``texelFetch`` from unsigned integer textures; the tile's place in the packing from a second
integer texture; then one ``textureLod`` lookup in the mipmapped atlas, at the mip level of
the picture's scale (atlas texels per picture pixel), which is what a ``textureGrad`` with the
continuous texture coordinates' derivatives would pick: the derivatives of the atlas
coordinates jump at tile borders, so hardware derivatives cannot be used there. The tile of
every fragment equals :func:`tilesolve.constructive.stochastic.direct_corner` bit for bit, at
any origin of the 63-bit lattice (the origin enters as its residue modulo each table size).

By default the hash runs once per tile: a first pass renders one fragment per tile of the
picture and writes the tile's place in the atlas into an integer texture, and the second pass
fetches it for each pixel. ``two_pass=False`` evaluates the hash in every fragment (§5.4 as
written); both draw the same pixels.

Pictures larger than one render pass (the context's maximum viewport) are drawn band by band
and streamed to the PNG file.

In the browser and on the CPU
-----------------------------
:func:`webgl_texture` hands the studio (``static/webgl.js``) the one-pass shader (and the tile-id
shader) as GLSL ES 3.00 for WebGL2, with the hash tables, the packing and the atlas; the page
builds the row tables of each pass itself, as :func:`row_table` does. :func:`texture_window`
draws a window on the CPU (the studio's server tiles, the fallback): each tile the atlas's tile
image, one texel a pixel when ``tile_px`` is the atlas's tile, which is what the shader samples
there (mip level 0, texel centres); at other sizes each tile image is box-filtered, where the GPU
filters the atlas's mipmaps trilinearly (the same tiles, colours within the filters' difference).
"""

from __future__ import annotations

import os

import numpy as np

from tilesolve._random import rng_from_seed
from tilesolve.constructive.hashes import check_int, check_window
from tilesolve.constructive.stochastic import make_hash
from tilesolve.errors import InvalidProblem
from tilesolve.gpu.context import gpu_context, max_render_size, release
from tilesolve.gpu.picture import assemble_bands, pass_layout

__all__ = ["MAX_COLORS", "MAX_ATLAS", "HASH_GLSL", "hash_tables", "row_table", "Atlas", "check_atlas", "corner_packing", "synthesize_atlas", "graph_cut",
           "structure_size", "synthesis_scale", "read_example", "example_patches", "Quilter", "PassRenderer", "TextureMapper",
           "texture_window", "webgl_texture"]

#: Largest ``C`` of an atlas (``C**4 = 4096`` tiles).
MAX_COLORS = 8
#: Largest atlas side in texels: the texture size every OpenGL 4.5 context supports.
MAX_ATLAS = 16384

_VERTEX = """
#version 450
in vec2 in_pos;
void main() { gl_Position = vec4(in_pos, 0.0, 1.0); }
"""

#: ``p / n`` for ``p >= 0``, exact: a float quotient corrected by one step (integer division
#: is slow on CPU rasterisers, which have no vector instruction for it).
DIV_GLSL = """
ivec2 floor_div(ivec2 p, int n) {
    ivec2 t = ivec2((vec2(p) + 0.5) / float(n));
    t -= ivec2(greaterThan(t * n, p));
    t += ivec2(lessThanEqual((t + 1) * n, p));
    return t;
}
"""

#: The direct stochastic corner tiling (§3.3.1) on the long-period hash (§3.4.2-3.4.3).
#: The hash is evaluated from *row tables* as the compiled CPU kernels do: per column of tiles
#: ``P_i[x % N_i]``, per row ``y % N_i`` (four tables in each RGBA32UI texel), so no integer
#: division is left in the shader: ``h = red[sum_i twice_i[P_i[x % N_i] + y % N_i]]``.
HASH_GLSL = DIV_GLSL + """
uniform usampler2D u_perm;   // row i: table i written twice (P_i[(a + b) % N_i] = row[a + b])
uniform usampler2D u_px;     // column k, rows 0/1: P_i[(X + k) % N_i] for tables 0-3 / 4-7
uniform usampler2D u_ym;     // column k, rows 0/1: (Y + k) % N_i, Y the pass's first tile row
uniform usampler2D u_red;    // red[s] = (s % N_j) % C
uniform uint u_colors;       // C
uniform int u_tile_px;       // output pixels per tile side
uniform ivec2 u_offset;      // pixel offset of this render pass in the whole picture (>= 0)
uniform ivec2 u_first;       // the pass's first tile (X, Y), relative to the picture's origin tile

uint corner_hash(uvec4 xa, uvec4 xb, uvec4 ya, uvec4 yb) {
    uvec4 a = xa + ya, b = xb + yb;
    uint s = texelFetch(u_perm, ivec2(a.x, 0), 0).r + texelFetch(u_perm, ivec2(a.y, 1), 0).r
           + texelFetch(u_perm, ivec2(a.z, 2), 0).r + texelFetch(u_perm, ivec2(a.w, 3), 0).r
           + texelFetch(u_perm, ivec2(b.x, 4), 0).r + texelFetch(u_perm, ivec2(b.y, 5), 0).r
           + texelFetch(u_perm, ivec2(b.z, 6), 0).r + texelFetch(u_perm, ivec2(b.w, 7), 0).r;
    return texelFetch(u_red, ivec2(int(s), 0), 0).r;
}

// Pixel -> the tile (eq. 2.5 index c_NE c_SE c_SW c_NW) and the pixel's place inside it.
ivec2 tile_of(out uint tile, out ivec2 local) {
    ivec2 p = ivec2(gl_FragCoord.xy) + u_offset;
    ivec2 t = floor_div(p, u_tile_px);
    local = t - u_first;
    uvec4 xa0 = texelFetch(u_px, ivec2(local.x, 0), 0), xb0 = texelFetch(u_px, ivec2(local.x, 1), 0);
    uvec4 xa1 = texelFetch(u_px, ivec2(local.x + 1, 0), 0), xb1 = texelFetch(u_px, ivec2(local.x + 1, 1), 0);
    uvec4 ya0 = texelFetch(u_ym, ivec2(local.y, 0), 0), yb0 = texelFetch(u_ym, ivec2(local.y, 1), 0);
    uvec4 ya1 = texelFetch(u_ym, ivec2(local.y + 1, 0), 0), yb1 = texelFetch(u_ym, ivec2(local.y + 1, 1), 0);
    uint ne = corner_hash(xa1, xb1, ya1, yb1), se = corner_hash(xa1, xb1, ya0, yb0);
    uint sw = corner_hash(xa0, xb0, ya0, yb0), nw = corner_hash(xa0, xb0, ya1, yb1);
    tile = ((ne * u_colors + se) * u_colors + sw) * u_colors + nw;
    return p - t * u_tile_px;
}
"""

_FRAGMENT_IDS = """
#version 450
""" + HASH_GLSL + """
out uint f_tile;
void main() { uint tile; ivec2 local; tile_of(tile, local); f_tile = tile; }
"""

_LOOKUP_GLSL = """
uniform usampler2D u_where;  // tile -> (column, row from the bottom) in the packing
uniform sampler2D u_atlas;   // the packed tile images, mipmapped, wrapping toroidally
uniform int u_grid;          // C * C
uniform float u_lod;         // log2(atlas tile / tile_px): the mip level of an unscaled picture
vec4 lookup(uvec2 where, ivec2 inside, int tile_px) {
    vec2 uv = (vec2(where) + (vec2(inside) + 0.5) / float(tile_px)) / float(u_grid);
    return textureLod(u_atlas, uv, u_lod);
}
"""

#: One pass: every fragment evaluates the tiling hash of its tile (§5.4 as written).
_FRAGMENT_DIRECT = """
#version 450
""" + HASH_GLSL + _LOOKUP_GLSL + """
out vec4 f_colour;
void main() {
    uint tile;
    ivec2 local;
    ivec2 inside = tile_of(tile, local);
    f_colour = lookup(texelFetch(u_where, ivec2(int(tile), 0), 0).xy, inside, u_tile_px);
}
"""

#: First of two passes: one fragment per tile, writing the tile's place in the atlas.
_FRAGMENT_PLACES = """
#version 450
""" + HASH_GLSL + """
uniform usampler2D u_where;
out uvec2 f_place;
void main() { uint tile; ivec2 local; tile_of(tile, local); f_place = texelFetch(u_where, ivec2(int(tile), 0), 0).xy; }
"""

#: Second of two passes: each fragment fetches its tile's place (``places``) and samples the atlas.
_FRAGMENT_TWO_PASS = """
#version 450
""" + DIV_GLSL + _LOOKUP_GLSL + """
uniform usampler2D u_places; // the pass's tiles' places in the atlas, (0, 0) = u_first
uniform int u_tile_px;
uniform ivec2 u_offset;
uniform ivec2 u_first;
out vec4 f_colour;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy) + u_offset;
    ivec2 t = floor_div(p, u_tile_px);
    f_colour = lookup(texelFetch(u_places, t - u_first, 0).xy, p - t * u_tile_px, u_tile_px);
}
"""


# ------------------------------------------------------------------------------------ hash tables
def hash_tables(colors: int, seed, hash: str = "long"):
    """What :data:`HASH_GLSL` reads of the lattice hash of ``colors`` colours (§3.4).

    Returns
    -------
    (tables, perm, red)
        ``tables``: eight int64 permutation tables (unused slots hold a table of size 1, always
        0, so the shader sums eight fetches); ``perm``: ``(8, 2 max N_i)`` uint32, each table
        written twice (``u_perm``); ``red``: uint32 ``(s % N_j) % C`` for every sum ``s`` of
        table entries (``u_red``).
    """
    hsh = make_hash(hash, colors, seed)
    found = getattr(hsh, "tables", None) or (hsh.table,)
    if len(found) > 8:
        raise InvalidProblem("the shader takes at most 8 permutation tables")
    tables = [np.asarray(t, dtype=np.int64) for t in found] + [np.zeros(1, np.int64)] * (8 - len(found))
    sizes = [int(t.size) for t in tables]
    perm = np.zeros((8, 2 * max(sizes)), dtype=np.uint32)
    for i, t in enumerate(tables):
        perm[i, :2 * t.size] = np.concatenate([t, t])
    red = (np.arange(sum(sizes) + 1) % int(hsh.range) % colors).astype(np.uint32)
    return tables, perm, red


def row_table(tables, base: int, count: int, x_axis: bool) -> np.ndarray:
    """``(2, count, 4)`` uint32 row tables of the lattice columns (``x_axis``: ``P_i[(base + k) % N_i]``,
    ``u_px``) or rows (``(base + k) % N_i``, ``u_ym``) ``base .. base + count - 1``, tables 0-3 in
    row 0 and 4-7 in row 1; ``base`` anywhere on the 63-bit lattice (Python integers)."""
    k = np.arange(count, dtype=np.int64)
    out = np.empty((2, count, 4), dtype=np.uint32)
    for i, t in enumerate(tables):
        res = (base % t.size + k) % t.size
        out[i // 4, :, i % 4] = t[res] if x_axis else res
    return out


# ------------------------------------------------------------------------------------ atlas
def corner_packing(colors: int, *, seed: int = 0) -> np.ndarray:
    """A verified corner tile packing of ``C**2 x C**2`` tiles (§5.5.3), row 0 at the top."""
    from tilesolve.model.packing import PackingProblem
    from tilesolve.families.packing import solve

    c = _check_colors(colors)
    return np.asarray(solve(PackingProblem("corner", c), seed=seed, workers=1).tiling, dtype=np.int64)


def _check_colors(colors) -> int:
    c = check_int(colors, "colors", 2)
    if c > MAX_COLORS:
        raise InvalidProblem(f"tile-based texture mapping uses at most {MAX_COLORS} colours ({MAX_COLORS**4} tiles), "
                             f"got {c}")
    return c


def check_atlas(colors, tile) -> tuple[int, int]:
    """``(C, tile)`` checked: ``2 <= C <= MAX_COLORS``, an even tile of at least 8 texels, and an
    atlas (``C**2`` tiles a side) of at most :data:`MAX_ATLAS` texels a side."""
    c = _check_colors(colors)
    t = check_int(tile, "tile size", 8)
    if t % 2:
        raise InvalidProblem(f"the tile size must be even (quarter patches), got {t}")
    if c * c * t > MAX_ATLAS:
        raise InvalidProblem(f"an atlas of {c * c} x {c * c} tiles of {t} px is {c * c * t} px wide, more than the "
                             f"{MAX_ATLAS} px every OpenGL 4.5 texture may have: use a smaller tile or fewer colours")
    return c, t


def read_example(path: str | os.PathLike) -> np.ndarray:
    """The example image as ``(H, W, 4)`` uint8 RGBA; one-line :class:`InvalidProblem` when unreadable
    (:func:`tilesolve.io.images.read_rgba`)."""
    from tilesolve.io.images import read_rgba

    return read_rgba(path)


def synthesize_atlas(example, grid, colors: int, *, tile: int = 64, seed: int = 0) -> np.ndarray:
    """The tile images of the packing ``grid``, synthesised from ``example`` (§5.3, Ng et al.).

    Parameters
    ----------
    example : array_like
        ``(H, W, 3 or 4)`` uint8 image, at least ``tile`` pixels each way.
    grid : array_like
        A corner packing (:func:`corner_packing`), eq. 2.5 tile numbers, row 0 at the top.
    tile : int
        Tile side in pixels (even, at least 8); synthesised at :func:`synthesis_scale` times
        that and averaged down.
    seed : int
        Chooses the corner patches and the centre patches.

    Returns
    -------
    numpy.ndarray
        ``(rows * tile, cols * tile, 4)`` uint8 RGBA atlas, row 0 at the top.

    Examples
    --------
    >>> ex = np.random.default_rng(0).integers(0, 256, (40, 50, 3), dtype=np.uint8)
    >>> g = corner_packing(2)
    >>> a = synthesize_atlas(ex, g, 2, tile=16, seed=1)
    >>> a.shape
    (64, 64, 4)
    >>> # seamless: texels along the shared edge of two touching tiles are those of one patch
    >>> bool((a[15, 16:32] == a[16, 16:32]).all()) or bool((a[:, 15] != a[:, 16]).any())
    True
    """
    c, t = check_atlas(colors, tile)
    example_patches(example, t, seed)  # checks the example
    rng = rng_from_seed(seed)
    g = np.asarray(grid, dtype=np.int64)
    quilt = Quilter(example, t, _cut_regions)
    big, h = quilt.big, quilt.big // 2
    corner = _corner_patches(quilt.example, c, big, rng)
    atlas = np.empty((g.shape[0] * t, g.shape[1] * t, 4), dtype=np.uint8)
    for (r, q), k in np.ndenumerate(g):
        nw, sw, se, ne = k % c, (k // c) % c, (k // c**2) % c, k // c**3
        img = np.empty((big, big, 4), dtype=np.float32)
        img[:h, :h] = corner[nw][h:, h:]  # the patch centred on each corner, cut by the tile
        img[:h, h:] = corner[ne][h:, :h]
        img[h:, :h] = corner[sw][:h, h:]
        img[h:, h:] = corner[se][:h, :h]
        atlas[r * t:(r + 1) * t, q * t:(q + 1) * t] = quilt(img, rng)
    return atlas


class Quilter:
    """The last step of a tile's synthesis from ``example`` (RGB or RGBA uint8), shared by the
    corner tiles and the Wang tiles (:mod:`tilesolve.gpu.wang_texture`): a tile of ``tile``
    texels is put together at :attr:`big` ``= tile * scale`` texels (:func:`synthesis_scale`)
    from patches that meet along seams; calling the quilter covers the seams with a new patch of
    the example, the one that best matches the tile between its border and the seams
    (:func:`_patch_matcher`), cut in by :func:`graph_cut` and blended one texel wide, never on
    the border; then it averages each ``scale x scale`` block, giving the ``(tile, tile, 4)``
    uint8 tile.

    ``regions(big, border=scale)`` gives the ``(keep, cover)`` masks: the border the new patch
    must leave (``scale`` texels deep, one texel of the tile) and the seams it must cover.
    """

    def __init__(self, example, tile: int, regions) -> None:
        ex = np.asarray(example, dtype=np.float32)
        self.example = np.dstack([ex, np.full(ex.shape[:2], 255, np.float32)]) if ex.shape[2] == 3 else ex
        self.tile = tile
        self.scale = synthesis_scale(example, tile)
        self.big = tile * self.scale
        self.keep, self.cover = regions(self.big, border=self.scale)
        self._best = _patch_matcher(self.example, self.big, ~(self.keep | self.cover))

    def __call__(self, img: np.ndarray, rng) -> np.ndarray:
        new = self._best(img, rng)
        inside = graph_cut(img, new, self.keep, self.cover)
        # the cut's pixels themselves: the mean of the two patches, one pixel wide, never the border
        alpha = np.where(self.keep, 0.0, (inside + _shifted_mean(inside)) / 2)[..., None]
        t, s = self.tile, self.scale
        return np.rint((img * (1.0 - alpha) + new * alpha).reshape(t, s, t, s, 4).mean(axis=(1, 3))).astype(np.uint8)


#: The autocorrelation of an example's luminance below which two texels are taken as
#: unrelated (:func:`structure_size`).
_UNRELATED = 0.25
#: How many structure sizes a synthesised tile spans at least (:func:`synthesis_scale`): with
#: fewer, a tile holds about one brick, and the four corner patches and the new patch cannot
#: join their mortar lines inside it (stripes and broken fragments).
STRUCTURES_PER_TILE = 3
#: The largest side a tile is synthesised at when it is enlarged (:func:`synthesis_scale`).
MAX_SYNTHESIS_TILE = 128


def structure_size(example) -> int:
    """The size of the example's structure in pixels (the bricks of a wall): the least lag at
    which the autocorrelation of its luminance, the mean of the x and y directions (circular),
    falls below :data:`_UNRELATED` (1 for noise).

    Examples
    --------
    >>> noise = np.random.default_rng(0).integers(0, 256, (64, 64, 3), dtype=np.uint8)
    >>> structure_size(noise)
    1
    >>> stripes = np.repeat(np.repeat(np.indices((8, 8)).sum(axis=0) % 2, 16, 0), 16, 1) * 255
    >>> # a chequerboard of 16 px squares: the autocorrelation 1 - lag / 8 is 1/4 at lag 6
    >>> structure_size(np.dstack([stripes] * 3).astype(np.uint8)) in (6, 7)
    True
    """
    ex = np.asarray(example, dtype=np.float64)
    luma = ex[..., :3] @ np.array([0.299, 0.587, 0.114])
    luma -= luma.mean()
    power = np.abs(np.fft.rfft2(luma)) ** 2
    ac = np.fft.irfft2(power, s=luma.shape)
    if ac[0, 0] <= 0:
        return 1  # a flat example
    n = min(luma.shape) // 2
    mean = (ac[0, :n] + ac[:n, 0]) / (2 * ac[0, 0])
    below = np.flatnonzero(mean < _UNRELATED)
    return int(below[0]) if below.size else n


def synthesis_scale(example, tile: int) -> int:
    """The factor ``s`` (a power of two) by which a tile of ``tile`` texels is synthesised larger
    and then averaged down: the least with ``tile * s`` at least :data:`STRUCTURES_PER_TILE`
    times :func:`structure_size`, within :data:`MAX_SYNTHESIS_TILE` (or ``tile``, if larger) and
    the example's size. With ``s > 1`` the texture shows the example at ``1 / s`` of its size.

    Examples
    --------
    >>> noise = np.random.default_rng(0).integers(0, 256, (64, 64, 3), dtype=np.uint8)
    >>> synthesis_scale(noise, 16)
    1
    >>> stripes = np.repeat(np.repeat(np.indices((8, 8)).sum(axis=0) % 2, 16, 0), 16, 1) * 255
    >>> synthesis_scale(np.dstack([stripes] * 3).astype(np.uint8), 16)  # 3 x 6 px > 16
    2
    """
    ex = np.asarray(example)
    most = min(max(tile, MAX_SYNTHESIS_TILE), ex.shape[0], ex.shape[1])
    need = STRUCTURES_PER_TILE * structure_size(ex)
    s = 1
    while tile * s < need and tile * s * 2 <= most:
        s *= 2
    return s


#: How close to the best a patch position must fit to be chosen, as a share of the way from the
#: best fit to the median one: a random one of the close fits is taken, as image quilting does,
#: so that the tiles differ from one another and from seed to seed.
TOLERANCE = 0.1


def _pick(cost: np.ndarray, rng, avoid=()) -> tuple[int, int]:
    """A random position among those whose ``cost`` is within :data:`TOLERANCE` of the least,
    at least half a patch away from the positions ``avoid`` (``(r, q, t)``)."""
    cost = cost.astype(np.float64)
    yy, xx = np.mgrid[0:cost.shape[0], 0:cost.shape[1]]
    for r, q, t in avoid:
        cost[(np.abs(yy - r) < t // 2) & (np.abs(xx - q) < t // 2)] = np.inf
    finite = cost[np.isfinite(cost)]
    lo, mid = float(finite.min()), float(np.median(finite))
    close = np.flatnonzero(cost.ravel() <= lo + TOLERANCE * (mid - lo))
    r, q = np.unravel_index(int(close[rng.integers(close.size)]), cost.shape)
    return int(r), int(q)


def _columns_cost(ex: np.ndarray, t: int, column: np.ndarray, at: int, band: slice) -> np.ndarray:
    """For every ``t x t`` patch position ``(r, q)`` of ``ex``: the squared RGB difference of
    ``column`` (``(t, 3)``) and the patch's column ``at``, over the patch's rows ``band``."""
    from numpy.lib.stride_tricks import sliding_window_view

    rows = ex.shape[0] - t + 1
    cols = ex.shape[1] - t + 1
    win = sliding_window_view(ex[:, at:at + cols, :3], t, axis=0)[..., band]  # (rows, cols, 3, band)
    return ((win - column[band].T[None, None]) ** 2).sum(axis=(2, 3))[:rows]


#: Half the rows of a corner patch's edge columns (and columns of its edge rows) matched against
#: the other patches: the new patch covers the tile's middle lines but for their ends at the tile's
#: border, so only the few texels about a corner patch's middle row (the tile's edge) stay exposed.
EXPOSED = 3


def _corner_patches(example: np.ndarray, colors: int, t: int, rng) -> list[np.ndarray]:
    """One ``t x t`` patch per corner colour, each placed where it best fits the patches chosen
    before it and itself where two corner patches meet: a tile's quarters abut across its
    middle lines, so that the east column of one patch lies beside the west column of any other,
    and the south row above the north row. The new patch covers those lines (:func:`_cut_regions`)
    except where they reach the tile's border, at a patch's middle row and column, so the fit is
    measured there (:data:`EXPOSED` texels each side): an example with a structure (mortar lines)
    then gets patches whose structure continues across the tiles' edges, as image quilting places
    its blocks (Efros & Freeman 2001), and the patches are free to differ inside, which they must
    for the texture to vary (a fit over whole columns prefers patches that repeat themselves: a
    straight mortar line through every patch, stripes in the texture)."""
    from numpy.lib.stride_tricks import sliding_window_view

    ex = _structure(example)
    exT = np.ascontiguousarray(ex.transpose(1, 0, 2))
    band = slice(t // 2 - EXPOSED, t // 2 + EXPOSED)
    win = sliding_window_view(ex[..., :3], (t, t), axis=(0, 1))  # (rows, cols, 3, t, t)
    self_cost = (((win[..., band, -1] - win[..., band, 0]) ** 2).sum(axis=(2, 3))
                 + ((win[..., -1, band] - win[..., 0, band]) ** 2).sum(axis=(2, 3)))
    chosen: list[np.ndarray] = []
    places: list[tuple[int, int, int]] = []
    for _ in range(colors):
        cost = self_cost.copy()
        for p in chosen:
            cost += _columns_cost(ex, t, p[:, -1, :3], 0, band) + _columns_cost(ex, t, p[:, 0, :3], t - 1, band)
            cost += (_columns_cost(exT, t, p[-1, :, :3], 0, band)
                     + _columns_cost(exT, t, p[0, :, :3], t - 1, band)).T
        r, q = _pick(cost, rng, places)
        places.append((r, q, t))
        chosen.append(ex[r:r + t, q:q + t].copy())
    return [example[r:r + t, q:q + t].copy() for r, q, _ in places]


def _patch_matcher(ex: np.ndarray, t: int, free: np.ndarray):
    """A function ``best(base, rng)``: the patch of ``ex`` that best matches ``base`` where the
    cut may run (``free``), by the sum of squared RGB differences at every patch position
    (correlations by FFT; the example's own terms computed once), one of the close fits
    (:func:`_pick`)."""
    h, w = ex.shape[0], ex.shape[1]
    shape = (h + t - 1, w + t - 1)  # no wrap-around

    def correlate(spectrum, kernel):
        full = np.fft.irfft2(spectrum * np.fft.rfft2(kernel[::-1, ::-1], s=shape), s=shape)
        return full[t - 1:h, t - 1:w]

    channels = [ex[..., k].astype(np.float64) for k in range(3)]
    spectra = [np.fft.rfft2(e, s=shape) for e in channels]
    mask = free.astype(np.float64)
    own = correlate(np.fft.rfft2(sum(e * e for e in channels), s=shape), mask)

    def best(base: np.ndarray, rng) -> np.ndarray:
        cost = own - 2 * sum(correlate(f, base[..., k] * mask) for k, f in enumerate(spectra))
        r, q = _pick(cost, rng)
        return ex[r:r + t, q:q + t].copy()

    return best


def _structure(ex: np.ndarray) -> np.ndarray:
    """The example's luminance in its three colour channels: where patches meet, its structure
    (light mortar between darker bricks) matters more than each brick's own colour."""
    luma = ex[..., :3] @ np.array([0.299, 0.587, 0.114], dtype=np.float32)
    return np.repeat(luma[..., None], 3, axis=2)


def _cut_regions(t: int, border: int = 1) -> tuple[np.ndarray, np.ndarray]:
    """``(keep, cover)`` boolean ``(t, t)`` masks of a tile: ``keep`` lies outside the circle
    inscribed in the tile, ``border`` texels deep at the middle of each edge (the tile's border,
    set by the corner colours alone, §5.3), ``cover`` is the cross where the four quarter patches
    meet and a disc at the centre, which the new patch must cover (Ng et al., Fig. 5.1 d)."""
    h = t / 2
    yy, xx = np.mgrid[0:t, 0:t].astype(np.float32) + 0.5
    radius = np.hypot(yy - h, xx - h)
    keep = radius > h - border
    cross = (np.abs(yy - h) < 1.0) | (np.abs(xx - h) < 1.0)
    cover = ((cross & (radius < h - border - 2.0)) | (radius < 0.2 * t)) & ~keep
    return keep, cover


def graph_cut(old: np.ndarray, new: np.ndarray, keep: np.ndarray, cover: np.ndarray) -> np.ndarray:
    """Where the ``new`` patch goes over ``old``: the minimum-error boundary of Kwatra et al.
    (2003), the ``(t, t)`` boolean mask, true on ``cover`` and false on ``keep``, whose boundary
    has the least cost: a pair of neighbouring pixels ``s, u`` cut apart costs
    ``|old(s) - new(s)| + |old(u) - new(u)|`` (RGB, L1) divided by the edge strength between them,
    ``|old(s) - old(u)| + |new(s) - new(u)|`` plus a constant (Kwatra et al., §3.3: seams hide
    along edges, a cut runs beside a mortar line rather than across a brick's face); a minimum
    s-t cut (:func:`scipy.sparse.csgraph.maximum_flow`; integer capacities, so the same cut
    everywhere).
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import breadth_first_order, maximum_flow

    t = old.shape[0]
    n = t * t
    o, w = old[..., :3].reshape(n, 3), new[..., :3].reshape(n, 3)
    err = np.abs(o - w).sum(axis=1)
    ids = np.arange(n).reshape(t, t)
    a = np.concatenate([ids[:, :-1].ravel(), ids[:-1, :].ravel()])
    b = np.concatenate([ids[:, 1:].ravel(), ids[1:, :].ravel()])
    edge = np.abs(o[a] - o[b]).sum(axis=1) + np.abs(w[a] - w[b]).sum(axis=1)
    # + 1: the shortest of equal cuts
    cap = (np.rint(_CUT_SCALE * (err[a] + err[b]) / (edge + _CUT_SCALE)) + 1).astype(np.int32)
    source, sink, big = n, n + 1, np.int32(1 << 28)
    src = np.flatnonzero(cover.ravel())
    snk = np.flatnonzero(keep.ravel())
    rows = np.concatenate([a, b, np.full(src.size, source), snk])
    cols = np.concatenate([b, a, src, np.full(snk.size, sink)])
    caps = np.concatenate([cap, cap, np.full(src.size + snk.size, big, dtype=np.int32)])
    graph = coo_matrix((caps, (rows, cols)), shape=(n + 2, n + 2)).tocsr()
    flow = maximum_flow(graph, source, sink).flow
    residual = graph - flow
    residual.data = np.where(residual.data > 0, 1, 0).astype(np.int32)
    residual.eliminate_zeros()
    reached = breadth_first_order(residual, source, directed=True, return_predecessors=False)
    inside = np.zeros(n + 2, dtype=bool)
    inside[reached] = True
    return inside[:n].reshape(t, t)


#: The edge strength (RGB, L1, 0-255 a channel) at which a seam's cost is halved
#: (:func:`graph_cut`); also the costs' fixed-point scale.
_CUT_SCALE = 16.0


def _shifted_mean(mask: np.ndarray) -> np.ndarray:
    """The mean of ``mask`` over each pixel's four neighbours (edge pixels repeat)."""
    m = np.pad(mask.astype(np.float32), 1, mode="edge")
    return (m[:-2, 1:-1] + m[2:, 1:-1] + m[1:-1, :-2] + m[1:-1, 2:]) / 4


def example_patches(example, size: int, seed, *, what: str = "one tile"):
    """A function ``patch(n)`` drawing random ``n x n`` float32 RGBA patches of ``example``.

    ``example`` is an ``(H, W, 3 or 4)`` uint8 image of at least ``size`` pixels each way
    (``what``, named in the refusal); the patches come from ``seed``'s stream, in the order drawn.
    """
    ex = np.asarray(example, dtype=np.uint8)
    if ex.ndim != 3 or ex.shape[2] not in (3, 4):
        raise InvalidProblem(f"the example must be an RGB or RGBA image, got an array of shape {ex.shape}")
    if ex.shape[2] == 3:
        ex = np.dstack([ex, np.full(ex.shape[:2], 255, dtype=np.uint8)])
    eh, ew = ex.shape[:2]
    if eh < size or ew < size:
        raise InvalidProblem(f"the example image ({ew}x{eh} px) is smaller than {what} ({size}x{size} px): "
                             "use a smaller --tile")
    rng = rng_from_seed(seed)

    def patch(n: int) -> np.ndarray:
        r, q = int(rng.integers(eh - n + 1)), int(rng.integers(ew - n + 1))
        return ex[r:r + n, q:q + n].astype(np.float32)

    return patch


class Atlas:
    """A packed tile atlas: the packing ``grid``, its image, and ``colors``, ``tile``."""

    def __init__(self, grid, image, colors: int) -> None:
        self.grid = np.asarray(grid, dtype=np.int64)
        self.image = np.asarray(image, dtype=np.uint8)
        self.colors = _check_colors(colors)
        rows, cols = self.grid.shape
        if rows != cols or rows != self.colors**2 or sorted(self.grid.ravel()) != list(range(self.colors**4)):
            raise InvalidProblem(f"the atlas grid must hold the {self.colors**4} corner tiles once each, "
                                 f"{self.colors**2} x {self.colors**2}")
        if self.image.ndim != 3 or self.image.shape[0] != self.image.shape[1] or self.image.shape[0] % rows:
            raise InvalidProblem("the atlas image must be square and a whole number of tiles")
        self.tile = self.image.shape[0] // rows

    @classmethod
    def from_example(cls, example, colors: int, *, tile: int = 64, seed: int = 0) -> "Atlas":
        """Pack (:func:`corner_packing`) and synthesise (:func:`synthesize_atlas`) from an example image."""
        grid = corner_packing(colors, seed=seed)
        return cls(grid, synthesize_atlas(example, grid, colors, tile=tile, seed=seed), colors)

    def where(self) -> np.ndarray:
        """``(C**4, 2)`` uint32: each tile's (column, row counted from the bottom) in the packing."""
        rows = self.grid.shape[0]
        out = np.empty((self.colors**4, 2), dtype=np.uint32)
        r, q = np.divmod(np.arange(self.grid.size), rows)
        out[self.grid.ravel(), 0] = q
        out[self.grid.ravel(), 1] = rows - 1 - r
        return out


# ------------------------------------------------------------------------------------ passes
class PassRenderer:
    """What the GPU pictures share: integer textures, a full-screen quad, and pictures of any
    size drawn in render passes of at most :attr:`max_pass` pixels each way.

    A subclass sets ``ctx``, ``max_pass`` and ``_quad`` (:meth:`_setup`) and draws a pass with
    ``_pass(fbo, offset, scratch)``: the picture's pixels ``offset + [0, fbo.size)`` (GL
    coordinates, y up) into ``fbo``, with ``scratch`` from :meth:`_scratch` (a render target the
    passes reuse, or ``None``).
    """

    def _setup(self) -> None:
        self.ctx = gpu_context()
        self.max_pass = max_render_size(self.ctx)
        self._quad = self.ctx.buffer(np.array([-1, -1, 1, -1, -1, 1, 1, 1], dtype="f4").tobytes())

    def _vertex_array(self, fragment_shader: str):
        """``(program, vertex array)`` of a fragment shader over the full-screen quad."""
        prog = self.ctx.program(vertex_shader=_VERTEX, fragment_shader=fragment_shader)
        return prog, self.ctx.vertex_array(prog, [(self._quad, "2f", "in_pos")])

    def _int_texture(self, a: np.ndarray, components: int):
        """An unsigned integer texture (read with ``texelFetch`` through a ``usampler2D``)."""
        a = np.ascontiguousarray(a, dtype=np.uint32)
        tex = self.ctx.texture((a.shape[1], a.shape[0]), components, a.tobytes(), dtype="u4")
        tex.filter = (self.ctx.NEAREST, self.ctx.NEAREST)
        return tex

    def _check_pass(self, width, height) -> tuple[int, int]:
        w, h = check_int(width, "width", 1), check_int(height, "height", 1)
        if w > self.max_pass or h > self.max_pass:
            raise InvalidProblem(f"one render pass is at most {self.max_pass} px each way; got {w}x{h}")
        return w, h

    def _scratch(self, w: int, h: int):
        """A render target reused by the passes of at most ``w x h`` pixels (none by default)."""
        return None

    def _pass(self, fbo, offset, scratch) -> None:
        raise NotImplementedError

    def frame(self, width: int, height: int):
        """A render target and a function drawing one frame of the picture's lower-left pass into it."""
        w, h = self._check_pass(width, height)
        scratch = self._scratch(w, h)
        fbo = self.ctx.simple_framebuffer((w, h), components=4)

        def draw() -> None:
            self._pass(fbo, (0, 0), scratch)

        return fbo, draw

    def bands(self, width: int, height: int):
        """The picture as ``(rows, width, 4)`` uint8 bands from the top.

        Each render pass is at most :func:`max_render_size` pixels each way (and about 16
        million pixels); wider pictures take several passes per band.
        """
        w, h, pass_w, band_h = pass_layout(width, height, self.max_pass)
        scratch = self._scratch(pass_w, band_h)
        fbos: dict = {}

        def read_pass(left, bottom, pw, bh):
            if (pw, bh) not in fbos:
                fbos[(pw, bh)] = self.ctx.simple_framebuffer((pw, bh), components=4)
            fbo = fbos[(pw, bh)]
            self._pass(fbo, (left, bottom), scratch)
            return np.frombuffer(fbo.read(components=4), dtype=np.uint8).reshape(bh, pw, 4)

        try:
            yield from assemble_bands(w, h, pass_w, band_h, read_pass)
        finally:
            for fbo in fbos.values():
                release(fbo)
            if scratch is not None:
                release(scratch)

    def image(self, width: int, height: int) -> np.ndarray:
        """The whole picture, ``(height, width, 4)`` uint8, row 0 at the top."""
        return np.concatenate(list(self.bands(width, height)), axis=0)


# ------------------------------------------------------------------------------------ renderer
class TextureMapper(PassRenderer):
    """Renders windows of the infinite non-periodic texture of an :class:`Atlas` (§5.4).

    Pixel ``(px, py)`` of a ``W x H`` picture (``py`` from the top) whose SW tile is
    ``(x0, y0)`` lies in tile ``(x0 + px // tile_px, y0 + (H - 1 - py) // tile_px)`` of the
    direct stochastic corner tiling of ``colors`` colours, ``seed`` and ``hash``
    (:func:`~tilesolve.constructive.stochastic.direct_corner` coordinates).

    ``two_pass=True`` (default) first renders the tiles of the picture, one fragment per tile,
    into an integer texture, then the picture, each fragment fetching its tile; ``False``
    evaluates the tiling hash in every fragment of the picture (one pass). Both give the same
    pixels.

    Examples
    --------
    >>> from tilesolve.constructive.stochastic import direct_corner
    >>> m = TextureMapper(colors=2, seed=3, origin=(-5, 7))
    >>> ids = m.tile_ids(6, 4)
    >>> bool((ids == direct_corner(-5, 7, 6, 4, colors=2, seed=3)).all())
    True
    """

    def __init__(self, atlas: Atlas | None = None, *, colors: int | None = None, seed: int = 0,
                 origin=(0, 0), tile_px: int | None = None, hash: str = "long", two_pass: bool = True) -> None:
        if atlas is None and colors is None:
            raise InvalidProblem("a texture mapper needs an atlas or a number of colours")
        self.atlas = atlas
        self.colors = _check_colors(atlas.colors if atlas is not None else colors)
        x0, y0 = origin
        self.x0, self.y0, _, _ = check_window(x0, y0, 1, 1)
        self.tile_px = check_int(tile_px if tile_px is not None else (atlas.tile if atlas else 1), "tile size", 1)
        self.two_pass = bool(two_pass)
        self.tables, perm, red = hash_tables(self.colors, seed, hash)
        self.sizes = [int(t.size) for t in self.tables]
        self._setup()
        self._perm = self._int_texture(perm, 1)
        self._red = self._int_texture(red[None, :], 1)
        self._programs: dict = {}
        self._rows: dict = {}
        if atlas is not None:
            import moderngl

            img = np.ascontiguousarray(atlas.image[::-1])  # GL rows run from the bottom
            self._atlas = self.ctx.texture((img.shape[1], img.shape[0]), 4, img.tobytes())
            self._atlas.build_mipmaps()
            self._atlas.filter = (moderngl.LINEAR_MIPMAP_LINEAR, moderngl.LINEAR)
            self._atlas.repeat_x = self._atlas.repeat_y = True
            self._where = self._int_texture(atlas.where()[None, :, :], 2)

    def _row_tables(self, first: int, count: int, x_axis: bool):
        """Row tables of ``count`` tile columns (``x_axis``) or rows from tile ``first`` of the picture."""
        key = (x_axis, first, count)
        if key not in self._rows:
            if len(self._rows) > 16:
                for tex in self._rows.values():
                    tex.release()
                self._rows.clear()
            base = (self.x0 if x_axis else self.y0) + first
            self._rows[key] = self._int_texture(row_table(self.tables, base, count, x_axis), 4)
        return self._rows[key]

    def _program(self, kind: str):
        if kind not in self._programs:
            src = {"ids": _FRAGMENT_IDS, "direct": _FRAGMENT_DIRECT, "places": _FRAGMENT_PLACES,
                   "two_pass": _FRAGMENT_TWO_PASS}[kind]
            prog, vao = self._vertex_array(src)
            units = {"u_perm": 0, "u_px": 1, "u_ym": 2, "u_red": 3, "u_where": 4, "u_atlas": 5, "u_places": 6}
            for name, unit in units.items():
                if name in prog:
                    prog[name].value = unit
            if "u_colors" in prog:
                prog["u_colors"].value = self.colors
            if "u_grid" in prog:
                prog["u_grid"].value = self.colors**2
            if "u_lod" in prog:
                prog["u_lod"].value = float(np.log2(self.atlas.tile / self.tile_px))
            self._programs[kind] = (prog, vao)
        return self._programs[kind]

    def _draw(self, kind: str, fbo, offset, tile_px: int, first, count, places=None) -> None:
        """One pass into ``fbo``; ``offset`` is its lower-left pixel, ``first``/``count`` its tiles."""
        prog, vao = self._program(kind)
        prog["u_offset"].value = tuple(offset)
        prog["u_first"].value = tuple(first)
        prog["u_tile_px"].value = tile_px
        fbo.use()
        if kind != "two_pass":  # the passes that hash
            self._perm.use(0)
            self._row_tables(first[0], count[0] + 1, True).use(1)
            self._row_tables(first[1], count[1] + 1, False).use(2)
            self._red.use(3)
        if kind != "ids":
            self._where.use(4)
            self._atlas.use(5)
        if places is not None:
            places.use(6)
        vao.render(mode=self.ctx.TRIANGLE_STRIP)

    def _need_atlas(self) -> None:
        if self.atlas is None:
            raise InvalidProblem("this texture mapper has no atlas (made with colors= only): pass an Atlas")

    def tile_ids(self, width: int, height: int) -> np.ndarray:
        """``(height, width)`` uint32 tile of each pixel, row 0 at the top, hashed per fragment."""
        w, h = self._check_pass(width, height)
        tex = self.ctx.texture((w, h), 1, dtype="u4")
        fbo = self.ctx.framebuffer(color_attachments=[tex])
        try:
            n = ((w - 1) // self.tile_px + 1, (h - 1) // self.tile_px + 1)
            self._draw("ids", fbo, (0, 0), self.tile_px, (0, 0), n)
            return np.frombuffer(fbo.read(components=1, dtype="u4"), dtype=np.uint32).reshape(h, w)[::-1].copy()
        finally:
            fbo.release()
            tex.release()

    def _pass(self, fbo, offset, ids_fbo) -> None:
        """Draw the picture's pixels ``offset + [0, fbo.size)`` (GL coordinates) into ``fbo``."""
        (ox, oy), (w, h), t = offset, fbo.size, self.tile_px
        first = (ox // t, oy // t)
        count = ((ox + w - 1) // t - first[0] + 1, (oy + h - 1) // t - first[1] + 1)
        if not self.two_pass:
            self._draw("direct", fbo, offset, t, first, count)
            return
        self._draw("places", ids_fbo, first, 1, first, count)
        self._draw("two_pass", fbo, offset, t, first, count, places=ids_fbo.color_attachments[0])

    def _scratch(self, w: int, h: int):
        """The tiles' places: one texel per tile of a pass of at most ``w x h`` pixels."""
        self._need_atlas()
        t = self.tile_px
        n = (min(self.max_pass, (w - 1) // t + 2), min(self.max_pass, (h - 1) // t + 2))
        return self.ctx.framebuffer(color_attachments=[self.ctx.texture(n, 2, dtype="u4")])


# ------------------------------------------------------------------------------------ browser, CPU
#: The shaders as GLSL ES 3.00 (WebGL2): ES has no default precision for these.
_ES_HEADER = ("#version 300 es\nprecision highp float;\nprecision highp int;\nprecision highp usampler2D;\n"
              "precision highp sampler2D;\n")


def _es(source: str) -> str:
    """A shader of this module (``#version 450``) as GLSL ES 3.00: the same source behind :data:`_ES_HEADER`."""
    body = source.lstrip("\n")
    assert body.startswith("#version 450\n")
    return _ES_HEADER + body.removeprefix("#version 450\n")


def webgl_texture(atlas: Atlas, *, seed=0, hash: str = "long") -> dict:
    """The one-pass texture shader (:class:`TextureMapper` with ``two_pass=False``) as GLSL ES 3.00
    for WebGL2, and what it reads, for the studio's view (``static/webgl.js``).

    Returns
    -------
    dict
        ``vertex``; fragment shaders ``colour`` (the picture) and ``ids`` (each pixel's tile,
        eq. 2.5, into an R32UI target); ``tables`` (the eight permutation tables, from which the
        page builds ``u_px`` and ``u_ym`` for each pass as :func:`row_table` does), ``perm`` and
        ``red`` (:func:`hash_tables`), ``where`` (:meth:`Atlas.where`), ``atlas`` (the atlas
        image's RGBA bytes, row 0 at the top, base64: no image decoder between it and the
        texture), ``atlas_size`` (its side in texels), ``tile`` (texels a tile side), ``colors``.

    Examples
    --------
    >>> ex = np.random.default_rng(0).integers(0, 256, (40, 40, 3), dtype=np.uint8)
    >>> at = Atlas(corner_packing(2), synthesize_atlas(ex, corner_packing(2), 2, tile=8), 2)
    >>> w = webgl_texture(at, seed=4)
    >>> w["colour"].splitlines()[0], w["tile"], len(w["tables"]), len(w["where"])
    ('#version 300 es', 8, 8, 16)
    """
    import base64

    tables, perm, red = hash_tables(atlas.colors, seed, hash)
    return {"vertex": _es(_VERTEX), "colour": _es(_FRAGMENT_DIRECT), "ids": _es(_FRAGMENT_IDS),
            "tables": [t.tolist() for t in tables], "perm": perm.tolist(), "red": red.tolist(),
            "where": atlas.where().tolist(),
            "atlas": base64.b64encode(np.ascontiguousarray(atlas.image).tobytes()).decode("ascii"),
            "atlas_size": int(atlas.image.shape[0]), "tile": atlas.tile, "colors": atlas.colors}


def texture_window(atlas: Atlas, x0: int, y0: int, cols: int, rows: int, *, seed=0, hash: str = "long",
                   tile_px: int | None = None) -> np.ndarray:
    """The texture's window of ``cols x rows`` tiles with SW tile ``(x0, y0)``, drawn on the CPU.

    Each tile (:func:`~tilesolve.constructive.stochastic.direct_corner`, the shader's tiles) is
    its image in the atlas. With ``tile_px`` the atlas's tile (the default) these are the pixels
    :class:`TextureMapper` and the studio's WebGL2 view draw (mip level 0, each pixel a texel's
    centre); with fewer pixels a tile, each tile image is box-filtered to ``tile_px`` (the GPU
    filters the atlas's mipmaps instead: the same tiles, colours within the filters' difference).

    Returns
    -------
    numpy.ndarray
        ``(rows * tile_px, cols * tile_px, 4)`` uint8 RGBA, row 0 at the top.

    Examples
    --------
    >>> ex = np.random.default_rng(0).integers(0, 256, (40, 40, 3), dtype=np.uint8)
    >>> at = Atlas(corner_packing(2), synthesize_atlas(ex, corner_packing(2), 2, tile=8), 2)
    >>> texture_window(at, -3, 5, 4, 2, seed=1).shape
    (16, 32, 4)
    """
    from tilesolve.constructive.stochastic import direct_corner

    t = atlas.tile
    s = t if tile_px is None else check_int(tile_px, "tile size", 1)
    if s > t:
        raise InvalidProblem(f"a CPU texture draws at most one pixel a texel ({t} px a tile), got {s}")
    tiles = direct_corner(x0, y0, cols, rows, colors=atlas.colors, seed=seed, hash=hash)
    g = atlas.grid.shape[0]
    where = atlas.where().astype(np.int64)
    blocks = atlas.image.reshape(g, t, g, t, 4).transpose(0, 2, 1, 3, 4)  # (grid row from the top, column, t, t, 4)
    images = blocks[g - 1 - where[:, 1], where[:, 0]]  # (C**4, t, t, 4): tile k's image
    if s != t:
        from PIL import Image

        images = np.stack([np.asarray(Image.fromarray(im, "RGBA").resize((s, s), Image.BOX)) for im in images])
    pic = images[np.asarray(tiles, dtype=np.int64)]  # (rows, cols, s, s, 4)
    return np.ascontiguousarray(pic.transpose(0, 2, 1, 3, 4).reshape(rows * s, cols * s, 4))
