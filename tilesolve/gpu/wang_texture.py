"""Textures that never repeat: an example image over an aperiodic Wang tile set (issue 20, §1).

The tiles
---------
:meth:`WangAtlas.from_example` synthesises the tiles of a Wang set from an example image by the
construction of Cohen, Shade, Hiller and Deussen (*Wang tiles for image and texture
generation*, SIGGRAPH 2003; class notes §5.3, Fig. 5.4 a): every edge colour gets one
diamond-shaped sample of the example, a diamond per colour of the horizontal (N, S) edges and
one per colour of the vertical (E, W) edges, and a tile is the four diamonds of its N, E, S, W
colours, each centred on the midpoint of its edge and cut by the tile. The diamonds meet along
the tile's diagonals, which a new patch of the example covers, cut in by a graph cut as the
corner tiles' centre patch is (:class:`tilesolve.gpu.texture.Quilter`: the patch that best
matches the diamonds between the tile's border and the diagonals, its border the minimum-error
cut; Kwatra et al. 2003), and a tile smaller than a few of the example's structures is
synthesised larger and averaged down (:func:`tilesolve.gpu.texture.synthesis_scale`). A texel
of a tile's border away from its corners comes from its edge's diamond alone, and the tile
across that edge shows the other half of the same diamond, so matching edges meet without a
seam; at a corner two diamonds meet (the corner problem of Wang tiles, §2.6).

The tiling
----------
The tile at cell ``(x, y)`` is the tile of a window of the set's constructive route
(:mod:`tilesolve.families.aperiodic_window`, verified): the coding of a toral Z²-rotation by a
Markov partition for Jeandel-Rao and U19 (Labbé, arXiv:1903.06137), balanced rows for the
Kari and Kari-Culik sets. Since the set is aperiodic, the texture has no period. On the GPU
the fragment shader codes the Markov sets' cells itself, by point-in-polygon in the partition
in double precision (:class:`_MarkovCells`), and takes a cell it cannot decide within its error
bound from the CPU route; the Kari sets' cells are the CPU route's window, uploaded as an
integer texture.

The picture
-----------
A ``W x H`` picture grows from its SW corner, like the corner-tile textures
(:class:`tilesolve.gpu.texture.TextureMapper`): pixel ``(px, py)`` (``py`` from the top) lies
in cell ``(x0 + px // s, y0 + (H - 1 - py) // s)`` with ``s`` pixels a tile side. A pixel ``l``
pixels from its tile's W (S) side shows texel ``(2 l + 1) T // (2 s)`` from the atlas tile's W
(S) side (``T`` texels a tile side): the nearest texel, in integers. An aperiodic set has no
tile packing (a packing is a periodic tiling of a torus), so the atlas cannot be laid out for
seamless filtering across tile borders (§5.4) and the picture samples nearest texels.

:class:`WangTexture` draws the picture on the CPU (numpy gathers from the atlas) and
:class:`WangTextureMapper` on the GPU, pixel for pixel the same, band by band.
"""

from __future__ import annotations

import math

import numpy as np

from tilesolve._random import rng_from_seed
from tilesolve.constructive._markov_kernels import FLAG
from tilesolve.constructive.hashes import check_int, check_window
from tilesolve.errors import InvalidProblem
from tilesolve.gpu.texture import DIV_GLSL, MAX_ATLAS, PassRenderer, Quilter, example_patches

__all__ = ["WangAtlas", "check_tile", "check_aperiodic", "texel_of_pixel", "window_tiles", "WangTexture",
           "WangTextureMapper"]

#: Most undecided cells of a GPU pass taken from the CPU route one by one (about 8 ms each);
#: more, and the pass's whole window is (about 0.2 us a cell).
SINGLE_CELLS = 32

#: Pixels of one band of the CPU picture.
BAND_PIXELS = 1 << 22

def _cut_regions(t: int, border: int = 1) -> tuple[np.ndarray, np.ndarray]:
    """``(keep, cover)`` boolean ``(t, t)`` masks of a Wang tile: ``keep`` is its border,
    ``border`` texels deep (set by the edge colours alone), ``cover`` the diagonals where the
    four diamonds meet, short of the border, and a disc at the centre, which the new patch must
    cover (:class:`tilesolve.gpu.texture.Quilter`)."""
    yy, xx = np.mgrid[0:t, 0:t].astype(np.float32) + 0.5
    inset = np.minimum(np.minimum(yy, t - yy), np.minimum(xx, t - xx))
    keep = inset < border
    diagonals = (np.abs(yy - xx) < 1.0) | (np.abs(yy + xx - t) < 1.0)
    cover = ((diagonals & (inset > border + 2.0)) | (np.hypot(yy - t / 2, xx - t / 2) < 0.2 * t)) & ~keep
    return keep, cover


def check_tile(tile, n_tiles: int) -> int:
    """``tile`` checked: even (the diamonds are centred on the edges' midpoints), at least 8, and
    an atlas of ``n_tiles`` tiles (``ceil(sqrt(n_tiles))`` a side) of at most :data:`MAX_ATLAS` texels."""
    t = check_int(tile, "tile size", 8)
    if t % 2:
        raise InvalidProblem(f"the tile size must be even (diamonds centred on the edges' midpoints), got {t}")
    cols = math.isqrt(n_tiles - 1) + 1
    if cols * t > MAX_ATLAS:
        raise InvalidProblem(f"an atlas of {cols} x {cols} tiles of {t} px is {cols * t} px wide, more than the "
                             f"{MAX_ATLAS} px every OpenGL 4.5 texture may have: use a smaller tile")
    return t


def check_aperiodic(name: str, tile: int):
    """``(WangTileSet, route)`` of the built-in aperiodic set ``name``, which must have a
    constructive route (:func:`tilesolve.families.aperiodic_window.route_of`), with ``tile`` checked."""
    from tilesolve.families.aperiodic_window import route_of
    from tilesolve.io.builtin_tilesets import load

    route = route_of(name)
    tileset, _ = load(name)
    check_tile(tile, len(tileset))
    return tileset, route


def window_tiles(name: str, x0: int, y0: int, width: int, height: int, seed: int) -> np.ndarray:
    """Tile indices of the ``width x height`` cells from ``(x0, y0)`` of the ``seed``'s tiling
    by the aperiodic set ``name``, row 0 the top row, verified
    (:func:`tilesolve.families.aperiodic_window.tiling`)."""
    from tilesolve.families.aperiodic_window import tiling

    _, sol = tiling(name, (x0, y0, width, height), seed=seed)
    return np.asarray(sol.tiling)


def texel_of_pixel(tile_px: int, tile: int) -> np.ndarray:
    """``(tile_px,)`` int64: the texel (from a tile's W or S side) that the pixel ``l`` pixels
    from the side shows, ``(2 l + 1) tile // (2 tile_px)``, the texel under its centre."""
    s, t = check_int(tile_px, "pixels per tile", 1), check_int(tile, "tile size", 1)
    return (2 * np.arange(s, dtype=np.int64) + 1) * t // (2 * s)


class WangAtlas:
    """The tile images of a Wang set: tile ``k`` is the ``tile x tile`` block in row
    ``k // cols``, column ``k % cols`` of ``image`` (``(rows * tile, cols * tile, 4)`` uint8)."""

    def __init__(self, tiles, image) -> None:
        self.tiles = np.asarray(tiles, dtype=np.int64)
        if self.tiles.ndim != 2 or self.tiles.shape[1] != 4 or not len(self.tiles):
            raise InvalidProblem(f"a Wang atlas needs tiles as N, E, S, W colours, got shape {self.tiles.shape}")
        self.image = np.asarray(image, dtype=np.uint8)
        m = len(self.tiles)
        self.cols = math.isqrt(m - 1) + 1
        rows = -(-m // self.cols)
        if self.image.ndim != 3 or self.image.shape[2] != 4 or self.image.shape[0] % rows \
                or self.image.shape[1] != self.image.shape[0] // rows * self.cols:
            raise InvalidProblem(f"a Wang atlas of {m} tiles is an RGBA image of {rows} x {self.cols} square tiles")
        self.tile = self.image.shape[0] // rows

    @classmethod
    def from_example(cls, example, tiles, *, tile: int = 64, seed: int = 0) -> "WangAtlas":
        """The tiles ``tiles`` (``(m, 4)`` N, E, S, W colours) synthesised from ``example``
        (Cohen et al. 2003: a diamond per edge colour; see the module).

        Examples
        --------
        >>> ex = np.random.default_rng(0).integers(0, 256, (40, 50, 3), dtype=np.uint8)
        >>> at = WangAtlas.from_example(ex, [[0, 1, 1, 0], [0, 0, 1, 1], [1, 1, 0, 0]], tile=16, seed=1)
        >>> at.image.shape, at.cols
        ((32, 32, 4), 2)
        >>> # the N border away from the corners is the N colour's diamond: the same in tiles 0 and 1
        >>> top = [at.block(k)[0, 2:14] for k in range(3)]
        >>> bool((top[0] == top[1]).all()), bool((top[0] == top[2]).all())
        (True, False)
        """
        tl = np.asarray(tiles, dtype=np.int64)
        if tl.ndim != 2 or tl.shape[1] != 4 or not len(tl) or tl.min() < 0:
            raise InvalidProblem(f"Wang tiles are rows of 4 colours N, E, S, W (>= 0), got shape {tl.shape}")
        t = check_tile(tile, len(tl))
        cols = math.isqrt(len(tl) - 1) + 1
        example_patches(example, t, seed, what="a diamond sample (one tile)")  # checks the example
        quilt = Quilter(example, t, _cut_regions)
        n, h = quilt.big, quilt.big // 2
        patch = example_patches(example, n, seed, what="a diamond sample (one tile)")
        k = int(tl.max()) + 1
        horizontal = [patch(n) for _ in range(k)]  # N and S edges
        vertical = [patch(n) for _ in range(k)]  # E and W edges
        # each texel in the triangle of its nearest edge (ties: N, E, S, W), from that edge's
        # diamond: a sample of n x n texels centred on the edge's midpoint
        yy, xx = np.mgrid[0:n, 0:n] + 0.5
        side = np.argmin(np.stack([yy, n - xx, n - yy, xx]), axis=0)[..., None]
        rng = rng_from_seed(seed)
        rows = -(-len(tl) // cols)
        image = np.zeros((rows * t, cols * t, 4), dtype=np.uint8)
        for i, (north, east, south, west) in enumerate(tl):
            img = np.select([side == 0, side == 1, side == 2],
                            [np.roll(horizontal[north], -h, axis=0), np.roll(vertical[east], h, axis=1),
                             np.roll(horizontal[south], h, axis=0)], np.roll(vertical[west], -h, axis=1))
            r, q = divmod(i, cols)
            image[r * t:(r + 1) * t, q * t:(q + 1) * t] = quilt(img.astype(np.float32), rng)
        return cls(tl, image)

    def block(self, k: int) -> np.ndarray:
        """The ``tile x tile x 4`` image of tile ``k``."""
        r, q = divmod(int(k), self.cols)
        t = self.tile
        return self.image[r * t:(r + 1) * t, q * t:(q + 1) * t]

    def places(self) -> np.ndarray:
        """``(m, 2)`` uint32: each tile's block (column, row counted from the atlas's bottom)."""
        rows = self.image.shape[0] // self.tile
        r, q = np.divmod(np.arange(len(self.tiles)), self.cols)
        return np.stack([q, rows - 1 - r], axis=1).astype(np.uint32)


class _Picture:
    """What the CPU and GPU pictures share: the set, the atlas, the seed, where the picture sits."""

    def __init__(self, name: str, atlas: WangAtlas, *, seed: int = 0, origin=(0, 0), tile_px: int | None = None):
        self.name = name
        self.atlas = atlas
        self.seed = seed
        x0, y0 = origin
        self.x0, self.y0, _, _ = check_window(x0, y0, 1, 1, what="origin")
        self.tile_px = check_int(tile_px if tile_px is not None else atlas.tile, "pixels per tile", 1)
        self.texel = texel_of_pixel(self.tile_px, atlas.tile)

    def cells(self, left: int, bottom: int, width: int, height: int) -> tuple[int, int, int, int]:
        """``(first column, first row, columns, rows)`` of the cells (relative to the picture's SW
        cell) under the pixels ``[left, left + width) x [bottom, bottom + height)`` (y from the bottom)."""
        s = self.tile_px
        c0, r0 = left // s, bottom // s
        return c0, r0, (left + width - 1) // s - c0 + 1, (bottom + height - 1) // s - r0 + 1

    def window(self, c0: int, r0: int, cols: int, rows: int) -> np.ndarray:
        """The tile indices of those cells, row 0 the top row."""
        return window_tiles(self.name, self.x0 + c0, self.y0 + r0, cols, rows, self.seed)


class WangTexture(_Picture):
    """The picture on the CPU: the route's window, then one numpy gather from the atlas per band.
    """

    def pixels(self, left: int, bottom: int, width: int, height: int) -> np.ndarray:
        """``(height, width, 4)`` uint8: the pixels ``[left, left + width) x [bottom, bottom + height)``
        (y from the picture's bottom), row 0 the top row."""
        c0, r0, cols, rows = self.cells(left, bottom, width, height)
        grid = self.window(c0, r0, cols, rows)
        s, t = self.tile_px, self.atlas.tile
        x = np.arange(left, left + width, dtype=np.int64)
        y = np.arange(bottom + height - 1, bottom - 1, -1, dtype=np.int64)  # from the top
        k = grid[(rows - 1 - (y // s - r0))[:, None], (x // s - c0)[None, :]]
        block_row, block_col = np.divmod(k, self.atlas.cols)
        return self.atlas.image[block_row * t + (t - 1 - self.texel[y % s])[:, None],
                                block_col * t + self.texel[x % s][None, :]]

    def bands(self, width: int, height: int):
        """The ``width x height`` picture as ``(rows, width, 4)`` uint8 bands from the top, of
        about :data:`BAND_PIXELS` pixels each (the gather's index arrays take 16 bytes a pixel)."""
        w, h = check_int(width, "width", 1), check_int(height, "height", 1)
        band_h = max(1, BAND_PIXELS // w)
        for top in range(0, h, band_h):
            bh = min(band_h, h - top)
            yield self.pixels(0, h - top - bh, w, bh)

    def image(self, width: int, height: int) -> np.ndarray:
        """The whole picture, ``(height, width, 4)`` uint8, row 0 at the top."""
        return np.concatenate(list(self.bands(width, height)), axis=0)


# ------------------------------------------------------------------------------------ GPU
#: Each fragment: its cell, the cell's tile (``u_tiles``), the tile's block in the atlas and the texel.
_FRAGMENT_LOOKUP = """
#version 450
""" + DIV_GLSL + """
uniform usampler2D u_tiles;  // the tile of each cell of the pass, (0, 0) = u_first
uniform usampler2D u_place;  // tile -> (column, row from the bottom) of its block in the atlas
uniform usampler2D u_texel;  // pixel l of a tile side -> texel (2 l + 1) T / (2 s) of the atlas tile
uniform sampler2D u_atlas;   // the tile images, GL rows from the bottom
uniform int u_tile_px;       // s: output pixels per tile side
uniform int u_tile;          // T: atlas texels per tile side
uniform ivec2 u_offset;      // pixel offset of this pass in the whole picture (>= 0)
uniform ivec2 u_first;       // the pass's first cell, relative to the picture's SW cell
out vec4 f_colour;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy) + u_offset;
    ivec2 c = floor_div(p, u_tile_px);
    ivec2 l = p - c * u_tile_px;
    uint k = texelFetch(u_tiles, c - u_first, 0).r;
    ivec2 block = ivec2(texelFetch(u_place, ivec2(int(k), 0), 0).xy);
    ivec2 texel = ivec2(int(texelFetch(u_texel, ivec2(l.x, 0), 0).r), int(texelFetch(u_texel, ivec2(l.y, 0), 0).r));
    f_colour = texelFetch(u_atlas, block * u_tile + texel, 0);
}
"""


#: One fragment per cell: the tile of the polygon of the Markov partition (Labbé 2021) that holds
#: the cell's point, by point-in-polygon in double precision (core in OpenGL 4.0): the point is
#: inside a convex polygon when it is on the inner side of every edge; a point closer than u_tol
#: to an edge of every polygon is undecided. Only the polygons that meet the row's band (between
#: two vertex heights) are tried.
_FRAGMENT_MARKOV = """
#version 450
uniform usampler2D u_rows;    // row r of the pass: its points' y in the fundamental domain, x shift (2 x 2 words)
uniform usampler2D u_cols;    // column c of the pass: its points' x modulo lx (2 words)
uniform usampler2D u_band_of; // row r: its band
uniform dvec3 u_edges[EDGES]; // polygon a, edge e at a * SIDES + e: (nx, ny, c), unit inner normal n, n . p on the edge
uniform uvec2 u_atoms[ATOMS]; // polygon a: (edges, tile)
uniform int u_band[BANDS * (ATOMS + 1)];  // band b: its polygon count at b * (ATOMS + 1), then the polygons
uniform double u_lx;          // the fundamental domain's width
uniform double u_tol;         // the error bound of a distance to an edge
out uint f_tile;
void main() {
    ivec2 c = ivec2(gl_FragCoord.xy);
    uvec4 row = texelFetch(u_rows, ivec2(c.y, 0), 0);
    double y = packDouble2x32(row.xy);
    precise double x = packDouble2x32(texelFetch(u_cols, ivec2(c.x, 0), 0).xy) + packDouble2x32(row.zw);
    if (x >= u_lx) x -= u_lx;
    uint tile = FLAG;
    int band = int(texelFetch(u_band_of, ivec2(c.y, 0), 0).r) * (ATOMS + 1);
    for (int i = 1; i <= u_band[band]; i++) {
        int a = u_band[band + i];
        precise double least = u_tol + 1.0;
        for (int e = 0; e < int(u_atoms[a].x); e++) {
            dvec3 edge = u_edges[a * SIDES + e];
            precise double d = edge.x * x + edge.y * y - edge.z;
            least = min(least, d);
        }
        if (least > u_tol) { tile = u_atoms[a].y; break; }
    }
    f_tile = tile;
}
"""


class _MarkovCells:
    """The cells of a pass coded by the shader :data:`_FRAGMENT_MARKOV` from the polygons of
    :func:`tilesolve.constructive.markov.partition` (convex, counter-clockwise, each with its
    tile; the lattice ``<(lx, 0), (sx, ly)>``; the rotation ``(hx, hy)``), their vertices rounded
    from ``Q(φ)`` to float64 (float32 would leave a cell in about 10**4 undecided instead of one
    in about 10**8).

    Cell ``(X, Y)`` codes the point ``x0 + (X hx, Y hy)`` of the torus. The shader cannot reduce
    coordinates of up to ``2**62``, so the CPU reduces them: a row's height ``y`` in the
    fundamental domain and the shift ``-l sx`` its ``l`` wraps around the torus give its points,
    a column's ``x0 + X hx`` modulo ``lx`` its abscissa, from the exact anchors of
    :func:`~tilesolve.constructive.markov.cell_point` at the first row and column of every
    block of :data:`~tilesolve.constructive.markov.BLOCK` cells and float64 steps inside it.
    The shader adds abscissa and shift, reduces once, and finds the polygon of which the point
    is farther than :attr:`tolerance` inside every edge. A cell with none is :data:`FLAG`
    (undecided), and the mapper takes it from the CPU route. A point reduced a lattice step off
    (a wrap decided wrongly near the domain's border) lies outside the domain, so in no
    polygon: undecided too.
    """

    def __init__(self, mapper: "WangTextureMapper", name: str, seed: int) -> None:
        from tilesolve.constructive.markov import float_tolerance, partition

        self.name, self.seed, self.mapper, self.ctx = name, seed, mapper, mapper.ctx
        part = partition(name)
        self.lx, self.ly, self.sx, self.hx, self.hy = (float(getattr(part, f)) for f in ("lx", "ly", "sx", "hx", "hy"))
        counts = np.array([len(vs) for _, vs, _ in part.atoms])
        atoms, sides = len(counts), int(counts.max())
        vertices = np.array([[[float(x), float(y)] for x, y in vs + (vs[-1],) * (sides - len(vs))]
                             for _, vs, _ in part.atoms])
        e = np.arange(sides)[None, :]
        after = np.where(e + 1 < counts[:, None], e + 1, 0)  # the padding (the last vertex again) is never read
        d = np.take_along_axis(vertices, after[..., None], axis=1) - vertices
        normal = np.stack([-d[..., 1], d[..., 0]], axis=2)  # the inner side of a counter-clockwise edge
        length = np.hypot(normal[..., 0], normal[..., 1])
        normal /= np.where(length > 0, length, 1.0)[..., None]
        edges = np.concatenate([normal, (normal * vertices).sum(axis=2)[..., None]], axis=2)
        # Error of a distance n . p - c (u = 2**-53, coordinates below L): the point's x from two
        # float64 reductions and y from one (e64 each, MARKOV's float64 bound for a block) and two
        # roundings (2 u L), the vertices rounded (u L), the normal and c computed (4 u L), the
        # products and sums in the shader (4 u L); times 4 for safety.
        self.tolerance = 4 * (3 * float_tolerance(part) + 11 * 2.0 ** -53 * max(self.lx, self.ly))
        # Bands between consecutive vertex heights, each with the polygons that meet it.
        ys = vertices[..., 1]
        self.heights = np.unique(ys)
        band = np.zeros((len(self.heights) - 1, atoms + 1), np.int32)
        for b, (y0, y1) in enumerate(zip(self.heights[:-1], self.heights[1:])):
            meets = np.nonzero((ys.min(axis=1) < y1) & (ys.max(axis=1) > y0))[0]
            band[b, 0], band[b, 1:1 + len(meets)] = len(meets), meets
        source = (_FRAGMENT_MARKOV.replace("FLAG", f"{FLAG}u").replace("EDGES", str(atoms * sides))
                  .replace("ATOMS", str(atoms)).replace("SIDES", str(sides)).replace("BANDS", str(len(band))))
        prog, _ = self.program = mapper._vertex_array(source)
        prog["u_rows"].value, prog["u_cols"].value, prog["u_band_of"].value = 0, 1, 2
        prog["u_edges"].write(np.ascontiguousarray(edges, dtype=np.float64).tobytes())
        prog["u_atoms"].write(np.stack([counts, [tile for tile, _, _ in part.atoms]], axis=1).astype(np.uint32).tobytes())
        prog["u_band"].write(band.tobytes())
        prog["u_lx"].write(np.float64(self.lx).tobytes())

    def _anchor(self, x: int, y: int) -> tuple[float, float]:
        from tilesolve.constructive.markov import cell_point

        return cell_point(self.name, self.seed, x, y)

    def rows(self, x: int, y: int, n: int) -> np.ndarray:
        """``(n, 2)`` float64 per row ``y .. y + n - 1`` (``x`` the first column): the height of its
        points in the fundamental domain and the shift of their abscissae (modulo ``lx``) from
        those of row ``y``."""
        from tilesolve.constructive.markov import BLOCK

        out = np.zeros((n, 2))
        ax, _ = self._anchor(x, y)
        for b in range(0, n, BLOCK):
            m = min(BLOCK, n - b)
            bx, by = self._anchor(x, y + b)
            yr = by + np.arange(m) * self.hy
            wraps = np.floor(yr / self.ly)
            out[b:b + m, 0] = yr - wraps * self.ly
            shift = (bx - ax) - wraps * self.sx
            out[b:b + m, 1] = shift - np.floor(shift / self.lx) * self.lx
        return out

    def cols(self, x: int, y: int, n: int) -> np.ndarray:
        """``(n,)`` float64 per column ``x .. x + n - 1``: the abscissa of its point in row ``y``."""
        from tilesolve.constructive.markov import BLOCK

        out = np.zeros(n)
        for b in range(0, n, BLOCK):
            m = min(BLOCK, n - b)
            t = self._anchor(x + b, y)[0] + np.arange(m) * self.hx
            out[b:b + m] = t - np.floor(t / self.lx) * self.lx
        return out

    def code(self, x: int, y: int, cols: int, rows: int) -> np.ndarray:
        """``(rows, cols)`` uint32 tiles of the cells ``x .. x + cols - 1`` by ``y .. y + rows - 1``
        (absolute), row 0 the top row, :data:`FLAG` where the shader cannot decide."""
        ctx, mapper = self.ctx, self.mapper
        row = self.rows(x, y, rows)
        # the band of each row (any band is sound: a point is decided only inside a polygon by the margin)
        band = np.clip(np.searchsorted(self.heights, row[:, 0], side="right") - 1, 0, len(self.heights) - 2)
        textures = [mapper._int_texture(row.view(np.uint32)[None, :, :], 4),  # doubles as pairs of words
                    mapper._int_texture(self.cols(x, y, cols).view(np.uint32).reshape(1, cols, 2), 2),
                    mapper._int_texture(band[None, :], 1)]
        target = ctx.texture((cols, rows), 1, dtype="u4")
        fbo = ctx.framebuffer(color_attachments=[target])
        try:
            prog, vao = self.program
            prog["u_tol"].write(np.float64(self.tolerance).tobytes())
            fbo.use()
            for unit, tex in enumerate(textures):
                tex.use(unit)
            vao.render(mode=ctx.TRIANGLE_STRIP)
            return np.frombuffer(fbo.read(components=1, dtype="u4"), dtype=np.uint32).reshape(rows, cols)[::-1].copy()
        finally:
            for obj in [fbo, target, *textures]:
                obj.release()


class WangTextureMapper(_Picture, PassRenderer):
    """The picture on the GPU (moderngl, OpenGL 4.5 through EGL), pixel for pixel :class:`WangTexture`.

    Each render pass draws one fragment per pixel: its cell, the cell's tile from an integer
    texture of the pass's tiles (:meth:`cell_tiles`), the tile's block in the atlas, and one
    ``texelFetch`` of the texel under the pixel.
    """

    def __init__(self, name: str, atlas: WangAtlas, *, seed: int = 0, origin=(0, 0), tile_px: int | None = None):
        super().__init__(name, atlas, seed=seed, origin=origin, tile_px=tile_px)
        self._setup()
        img = np.ascontiguousarray(atlas.image[::-1])  # GL rows run from the bottom
        self._atlas = self.ctx.texture((img.shape[1], img.shape[0]), 4, img.tobytes())
        self._atlas.filter = (self.ctx.NEAREST, self.ctx.NEAREST)
        self._place = self._int_texture(atlas.places()[None, :, :], 2)
        self._texel = self._int_texture(self.texel[None, :], 1)
        prog, vao = self._lookup = self._vertex_array(_FRAGMENT_LOOKUP)
        for uniform, unit in (("u_tiles", 0), ("u_place", 1), ("u_texel", 2), ("u_atlas", 3)):
            prog[uniform].value = unit
        prog["u_tile_px"].value = self.tile_px
        prog["u_tile"].value = atlas.tile
        from tilesolve.constructive.markov import NAMES

        self._markov = _MarkovCells(self, name, seed) if name in NAMES else None
        #: Whether the shader codes the cells (the Markov sets) or the CPU route gives them.
        self.codes_in_shader = self._markov is not None
        #: Cells coded by the shader and cells it left to the CPU route, over the pictures drawn.
        self.decided = self.undecided = 0

    def cell_tiles(self, c0: int, r0: int, cols: int, rows: int) -> np.ndarray:
        """The tiles the GPU draws in those cells (relative to the picture's SW cell), row 0 the top row.

        For the Markov sets the shader codes them (:class:`_MarkovCells`) and a cell it leaves
        undecided is taken from the CPU route's window (counted in :attr:`undecided`); the
        other sets' windows come from the CPU route.
        """
        if self._markov is None:
            return self.window(c0, r0, cols, rows)
        tiles = self._markov.code(self.x0 + c0, self.y0 + r0, cols, rows)
        flagged = tiles == FLAG
        n = int(flagged.sum())
        if n > SINGLE_CELLS:
            tiles = np.where(flagged, self.window(c0, r0, cols, rows), tiles)
        else:
            for r, c in zip(*np.nonzero(flagged)):
                tiles[r, c] = self.window(c0 + int(c), r0 + rows - 1 - int(r), 1, 1)[0, 0]
        self.undecided += n
        self.decided += tiles.size - n
        return tiles

    def _pass(self, fbo, offset, scratch) -> None:
        (left, bottom), (w, h) = offset, fbo.size
        c0, r0, cols, rows = self.cells(left, bottom, w, h)
        tiles = self._int_texture(self.cell_tiles(c0, r0, cols, rows)[::-1], 1)
        try:
            prog, vao = self._lookup
            prog["u_offset"].value = (left, bottom)
            prog["u_first"].value = (c0, r0)
            fbo.use()
            tiles.use(0)
            self._place.use(1)
            self._texel.use(2)
            self._atlas.use(3)
            vao.render(mode=self.ctx.TRIANGLE_STRIP)
        finally:
            tiles.release()
