"""The studio's WebGL2 view (static/webgl.js) in headless Chromium: the GPU path's wall shaders
(:func:`tilesolve.gpu.wall.webgl_wall`, GLSL ES 3.00 on Chromium's SwiftShader) give the CPU's wall.

What is compared, read back from the browser with ``gl.readPixels``:

* every cell's leg colours ``(N, E, S, W)`` (the first pass): equal to
  :func:`tilesolve.constructive.walls.wall_window`, exactly, at small and at 2**61 origins;
* every pixel's brick (the lattice point whose brick it lies in) and tile orientation: equal to
  :func:`tilesolve.constructive.wall_maps.wall_maps`, exactly; distance and UV within 1e-5 cells;
* the colours: the board pictures' look (the studio's view tiles: their palette, a colour per
  brick and dark mortar, and their geometry), the same as the desktop GPU path's in that look
  (:class:`WallRenderer`, Mesa llvmpipe) pixel for pixel -- and in the studio's own view, after
  a pan, the window the page says it drew; at 24 px a cell (the server's tiles at one device
  pixel a pixel) the same pixels as the view drawn from the server's tiles;
* a lost WebGL context (``WEBGL_lose_context``): the view falls back to the server's tiles under
  a note, and is drawn by WebGL2 again, the same pixels, once the context is restored.

The test browser's WebGL2 is SwiftShader, a software rasteriser, on which the page starts with
the "WebGL2" box unticked (the server's tiles come sooner); the tests tick it. Without WebGL2
(``--disable-webgl2``), or with the box unticked, the view is the server's tiles.
"""

from __future__ import annotations

import base64
import json
import os

import numpy as np
import pytest

from tests.studio.browsing import pan_view
from tilesolve.constructive.wall_maps import wall_maps
from tilesolve.constructive.walls import orientation, wall_window
from tilesolve.gpu.wall import WallRenderer, webgl_wall

#: Every test here drives Chromium: slow.
pytestmark = pytest.mark.slow

CHROMIUM = "/usr/bin/chromium"
#: WebGL2 without a GPU: ANGLE on SwiftShader (Chromium's software Vulkan).
SWIFTSHADER = ["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader"]
HUGE = 2**61 + 12345

#: Draw the wall of ``config`` (webgl_wall's dict) with picture SW cell (x0, y0) on a canvas of
#: its own; read back the colours, the first pass's legs and, when float targets can be drawn,
#: the data pass (bricks, geometry), as base64 of the raw arrays (GL rows, bottom first).
READ = """([config, x0, y0, cellPx, w, h]) => {
  const cv = document.createElement("canvas"); cv.width = w; cv.height = h;
  const gl = cv.getContext("webgl2", { antialias: false, alpha: false, preserveDrawingBuffer: true });
  const b64 = (a) => { const u = new Uint8Array(a.buffer); let s = "";
                       for (let i = 0; i < u.length; i += 8192) s += String.fromCharCode(...u.subarray(i, i + 8192));
                       return btoa(s); };
  const read = (fbo, attachment, nx, ny, format, type, Array_) => {
    gl.bindFramebuffer(gl.FRAMEBUFFER, fbo); if (fbo) gl.readBuffer(attachment);
    const out = new Array_(nx * ny * 4); gl.readPixels(0, 0, nx, ny, format, type, out); return b64(out); };
  const wall = new studioWebGL.Wall(gl); wall.use(config);
  wall.draw(x0, y0, 0, 0, cellPx, w, h);
  const c = wall.cells, out = { nx: c.nx, ny: c.ny,
    colour: read(null, null, w, h, gl.RGBA, gl.UNSIGNED_BYTE, Uint8Array),
    legs: read(c.fbo, gl.COLOR_ATTACHMENT0, c.nx, c.ny, gl.RGBA_INTEGER, gl.UNSIGNED_INT, Uint32Array) };
  if (gl.getExtension("EXT_color_buffer_float")) {
    const tex = (internal, format, type) => { const t = gl.createTexture(); gl.bindTexture(gl.TEXTURE_2D, t);
      gl.texStorage2D(gl.TEXTURE_2D, 1, internal, w, h); return t; };
    const fbo = gl.createFramebuffer(); gl.bindFramebuffer(gl.FRAMEBUFFER, fbo);
    [tex(gl.RGBA8), tex(gl.RG32I), tex(gl.RGBA32F)].forEach((t, k) =>
      gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0 + k, gl.TEXTURE_2D, t, 0));
    gl.drawBuffers([gl.COLOR_ATTACHMENT0, gl.COLOR_ATTACHMENT1, gl.COLOR_ATTACHMENT2]);
    wall.draw(x0, y0, 0, 0, cellPx, w, h, "data", fbo);
    out.brick = read(fbo, gl.COLOR_ATTACHMENT1, w, h, gl.RGBA_INTEGER, gl.INT, Int32Array);
    out.geom = read(fbo, gl.COLOR_ATTACHMENT2, w, h, gl.RGBA, gl.FLOAT, Float32Array);
  }
  out.error = gl.getError();
  return out;
}"""


def _array(doc, key, dtype, w, h) -> np.ndarray:
    """A read-back array as ``(h, w, 4)``, row 0 at the top."""
    return np.frombuffer(base64.b64decode(doc[key]), dtype=dtype).reshape(h, w, 4)[::-1]


@pytest.fixture(scope="module")
def playwright_():
    from playwright import sync_api as playwright

    assert os.path.exists(CHROMIUM), f"the browser tests need Debian's chromium at {CHROMIUM} (.ci/run installs it)"
    with playwright.sync_playwright() as p:
        yield p


@pytest.fixture(scope="module")
def gl_page(playwright_, server):
    b = playwright_.chromium.launch(executable_path=CHROMIUM, headless=True, args=SWIFTSHADER)
    page = b.new_page(viewport={"width": 1400, "height": 1000})
    page.set_default_timeout(180_000)  # SwiftShader compiles the wall's shaders in seconds, more on a busy machine
    page.goto(server + "/")
    page.wait_for_selector("body[data-ready='1']")
    yield page
    b.close()


def test_the_test_browser_has_webgl2_on_a_software_rasteriser(gl_page):
    assert gl_page.evaluate("studioWebGL.gl.getParameter(studioWebGL.gl.VERSION)").startswith("WebGL 2.0")
    assert "SwiftShader" in gl_page.evaluate("studioWebGL.renderer")
    # a software rasteriser: the server's tiles unless the box is ticked
    assert gl_page.is_enabled("#view-webgl") and not gl_page.is_checked("#view-webgl")


@pytest.mark.parametrize("colors,max_line,seed,origin,cell", [
    (3, 3, 0, (0, 0), 8),
    (3, None, 5, (-37, -11), 12),
    (4, 4, 7, (HUGE, -HUGE), 10),
    (5, 2, 2, (123456789, -987654321), 7),
    (3, 1, 11, (-5, 3), 9),
])
def test_the_browser_draws_the_cpu_wall(gl_page, colors, max_line, seed, origin, cell):
    w, h = 23 * cell, 13 * cell
    config = webgl_wall(colors=colors, max_line=max_line, seed=seed)
    doc = gl_page.evaluate(READ, [config, str(origin[0]), str(origin[1]), cell, w, h])
    assert doc["error"] == 0
    # the first pass: texel (tx, ty) holds cell (x0 - 1 + tx, y0 - 1 + ty)
    nx, ny = doc["nx"], doc["ny"]
    legs = _array(doc, "legs", np.uint32, nx, ny)
    cpu = wall_window(origin[0] - 1, origin[1] - 1, nx, ny, colors=colors, max_line=max_line, seed=seed)
    assert np.array_equal(legs, cpu)
    assert "brick" in doc, "the data pass needs float render targets (EXT_color_buffer_float)"
    halo = wall_window(origin[0] - 1, origin[1] - 1, 25, 15, colors=colors, max_line=max_line, seed=seed)
    m = wall_maps(halo, colors, cell, origin=origin)
    brick, geom = _array(doc, "brick", np.int32, w, h), _array(doc, "geom", np.float32, w, h)
    assert np.array_equal(brick[..., 0] + np.int64(origin[0]), m.vx)
    assert np.array_equal(brick[..., 1] + np.int64(origin[1]), m.vy)
    assert np.array_equal(geom[..., 3] > 0.5, np.repeat(np.repeat(orientation(halo[1:-1, 1:-1]), cell, 0), cell, 1))
    assert np.allclose(geom[..., 0], m.distance, atol=1e-5)
    assert np.allclose(geom[..., 1], m.u, atol=1e-5) and np.allclose(geom[..., 2], m.v, atol=1e-5)
    colour = _array(doc, "colour", np.uint8, w, h)
    # the desktop GPU path (Mesa llvmpipe in CI, as in tests/gpu)
    desktop = WallRenderer(colors=colors, max_line=max_line, seed=seed, origin=origin, cell_px=cell,
                           look="board").image(w, h)
    assert np.array_equal(colour, desktop)


def test_the_studio_view_is_drawn_by_webgl_and_is_the_wall(gl_page):
    page = gl_page
    page.select_option("#family", "board")
    page.check("#view-webgl")
    page.fill("#field-colors", "4")
    page.dispatch_event("#field-colors", "change")
    page.fill("#seed", "9")
    page.dispatch_event("#seed", "change")
    page.locator("#viewport").scroll_into_view_if_needed()
    pan_view(page, -333, -171, steps=4)
    page.mouse.wheel(0, -300)  # zoom in: whole pixels a cell, the pan an odd number of them
    page.wait_for_function("studioWebGL.state.drawn && !studioWebGL.state.pending && "
                           "document.getElementById('view-info').textContent.includes('drawn by WebGL2')")
    page.wait_for_timeout(300)  # the wheel's redraw
    drawn, values = page.evaluate("[studioWebGL.state.drawn, decodeURIComponent(studio.view.values)]")
    assert page.is_visible("#view-gl") and page.is_hidden("#view-loading")
    assert page.evaluate("studio.view.wanted.length") == 0  # no server tile asked for
    assert json.loads(values)["seed"] == 9 and json.loads(values)["colors"] == 4
    assert drawn["ox"] or drawn["oy"]
    w, h, ox, oy = drawn["width"], drawn["height"], drawn["ox"], drawn["oy"]
    colour = _gl_view(page)
    assert colour.shape == (h, w, 4)
    # the board form's view: the wall of its colours, lines of at most 3 (the form's default), its seed
    desktop = WallRenderer(colors=4, max_line=3, seed=9, origin=(drawn["x0"], drawn["y0"]),
                           cell_px=drawn["cellPx"], look="board").image(w + ox, h + oy)
    assert np.array_equal(colour, desktop[:h, ox:ox + w])


def _gl_view(page) -> np.ndarray:
    """The studio's WebGL2 view as drawn, ``(h, w, 4)`` RGBA, row 0 at the top."""
    doc = page.evaluate("""() => { const gl = studioWebGL.gl, w = gl.drawingBufferWidth, h = gl.drawingBufferHeight,
        out = new Uint8Array(w * h * 4); gl.bindFramebuffer(gl.FRAMEBUFFER, null);
        gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, out);
        let s = ""; for (let i = 0; i < out.length; i += 8192) s += String.fromCharCode(...out.subarray(i, i + 8192));
        return { w, h, c: btoa(s) }; }""")
    return _array(doc, "c", np.uint8, doc["w"], doc["h"])


def _tiles_view(page) -> np.ndarray:
    """The studio's view as drawn from the server's tiles (its 2D canvas), ``(h, w, 4)`` RGBA."""
    doc = page.evaluate("""() => { const cv = document.getElementById("view-canvas"),
        d = cv.getContext("2d").getImageData(0, 0, cv.width, cv.height);
        let s = "";
        for (let i = 0; i < d.data.length; i += 8192) s += String.fromCharCode(...d.data.subarray(i, i + 8192));
        return { w: cv.width, h: cv.height, c: btoa(s) }; }""")
    return np.frombuffer(base64.b64decode(doc["c"]), dtype=np.uint8).reshape(doc["h"], doc["w"], 4)


#: Every server tile the view wants is drawn.
TILES_DRAWN = "studio.view.wanted.length > 0 && studio.view.missing === 0 && studio.view.inflight === 0"
#: The view is drawn by WebGL2.
GL_DRAWN = ("studioWebGL.state.drawn && !studioWebGL.state.pending && "
            "document.getElementById('view-info').textContent.includes('drawn by WebGL2')")


def _board_view_at_24_px(page, box: bool) -> None:
    """The board's view (5 colours, seed 4) at zoom 3: 24 px a cell, the server's level-0 tiles
    (24 px a cell) drawn one pixel a pixel; ``box``: the "WebGL2" box ticked."""
    page.select_option("#family", "board")
    page.fill("#field-colors", "5")
    page.dispatch_event("#field-colors", "change")
    page.fill("#seed", "4")
    page.dispatch_event("#seed", "change")
    page.set_checked("#view-webgl", box)
    page.locator("#viewport").scroll_into_view_if_needed()
    assert page.evaluate("window.devicePixelRatio") == 1
    page.evaluate("Object.assign(studio.view, { x: -301, y: 97, zoom: 3 }); drawView()")


def test_the_webgl2_view_is_the_server_tiles_view_pixel_for_pixel(gl_page):
    page = gl_page
    _board_view_at_24_px(page, box=False)
    page.wait_for_function(TILES_DRAWN)
    assert page.evaluate("studio.view.level") == 0 and page.is_hidden("#view-gl")
    tiles = _tiles_view(page)
    page.check("#view-webgl")
    page.wait_for_function(GL_DRAWN)
    assert page.evaluate("studioWebGL.state.drawn.cellPx") == 24
    gl = _gl_view(page)
    assert gl.shape == tiles.shape
    differ = np.any(gl != tiles, axis=2)
    print(f"\nWebGL2 view vs the server's tiles, {gl.shape[1]}x{gl.shape[0]} px: {np.count_nonzero(differ)} differ")
    assert not differ.any()


def test_a_lost_context_falls_back_to_the_server_tiles_until_it_is_restored(gl_page):
    page = gl_page
    _board_view_at_24_px(page, box=True)
    page.wait_for_function(GL_DRAWN)
    before = _gl_view(page)
    assert page.is_hidden("#view-webgl-lost")
    page.evaluate("window.loseContext = studioWebGL.gl.getExtension('WEBGL_lose_context'); loseContext.loseContext()")
    page.wait_for_function(f"studioWebGL.state.lost && {TILES_DRAWN}")
    assert page.is_visible("#view-webgl-lost") and "context lost" in page.text_content("#view-webgl-lost")
    assert page.is_hidden("#view-gl") and "-cell tiles" in page.text_content("#view-info")
    assert np.array_equal(_tiles_view(page), before)  # the same picture, from the server
    page.evaluate("loseContext.restoreContext()")
    page.wait_for_function(f"!studioWebGL.state.lost && {GL_DRAWN}")
    assert page.is_hidden("#view-webgl-lost") and page.is_visible("#view-gl")
    assert np.array_equal(_gl_view(page), before)


def test_the_box_switches_between_webgl2_and_the_server_tiles(gl_page):
    page = gl_page
    page.select_option("#family", "board")
    page.locator("#viewport").scroll_into_view_if_needed()
    page.check("#view-webgl")
    page.wait_for_function("document.getElementById('view-info').textContent.includes('drawn by WebGL2')")
    assert page.is_visible("#view-gl")
    page.uncheck("#view-webgl")
    page.wait_for_function("studio.view.wanted.length > 0 && studio.view.missing === 0 && studio.view.inflight === 0")
    assert page.is_hidden("#view-gl")
    assert "-cell tiles" in page.text_content("#view-info")


def test_without_webgl2_the_view_is_the_server_tiles(playwright_, server):
    b = playwright_.chromium.launch(executable_path=CHROMIUM, headless=True, args=["--no-sandbox", "--disable-webgl2"])
    try:
        page = b.new_page(viewport={"width": 1400, "height": 1000})
        page.set_default_timeout(180_000)
        page.goto(server + "/")
        page.wait_for_selector("body[data-ready='1']")
        assert page.evaluate("studioWebGL.gl") is None
        assert page.is_disabled("#view-webgl") and not page.is_checked("#view-webgl")
        page.select_option("#family", "board")
        page.locator("#viewport").scroll_into_view_if_needed()
        page.wait_for_function("studio.view.wanted.length > 0 && studio.view.missing === 0 && "
                               "studio.view.inflight === 0")
        assert page.is_hidden("#view-gl")
        assert page.evaluate("studio.view.wanted.every(t => t.state === 'ready' && t.img.naturalWidth > 0)")
    finally:
        b.close()


def test_a_chosen_palette_colours_the_wall_view_in_both_paths(gl_page):
    # issue 22: one palette everywhere. A preset chosen on the page recolours the wall view as
    # drawn from the server's tiles and as drawn by WebGL2: the same pixels in both, every brick
    # the chosen colour of its index (brick colour i -> preset[i % 8]), the mortar kept.
    from tilesolve.io.board_png import picture_palette
    from tilesolve.io.wall_png import MORTAR, N_BRICK_COLOURS

    page = gl_page
    _board_view_at_24_px(page, box=False)
    page.wait_for_function(TILES_DRAWN)
    own = _tiles_view(page)
    try:
        page.select_option("#palette-preset", "viridis")
        chosen = [tuple(int(c[i:i + 2], 16) for i in (1, 3, 5)) for c in page.evaluate("studio.colours.slice(0, 8)")]
        assert page.evaluate("studio.view.palette") == ",".join("%02X%02X%02X" % c for c in chosen)
        page.wait_for_function(TILES_DRAWN)
        tiles = _tiles_view(page)
        # the pictures' own brick colours, each mapped to the preset's colour of its index
        pal = picture_palette()
        assert len(set(pal[:N_BRICK_COLOURS])) == N_BRICK_COLOURS
        lut = {pal[i]: chosen[i % len(chosen)] for i in range(N_BRICK_COLOURS)}
        lut[pal[MORTAR]] = pal[MORTAR]
        key = lambda a: a[..., 0].astype(np.int64) << 16 | a[..., 1].astype(np.int64) << 8 | a[..., 2]  # noqa: E731
        src, dst = np.array([key(np.array(k)) for k in lut]), np.array([key(np.array(v)) for v in lut.values()])
        own_key = key(own)
        assert np.isin(own_key, src).all()
        order = np.argsort(src)
        want = dst[order][np.searchsorted(src[order], own_key)]
        assert np.array_equal(key(tiles), want)
        used = {tuple(c) for c in tiles[..., :3].reshape(-1, 3).tolist()}
        assert used == set(chosen) | {pal[MORTAR]}
        page.check("#view-webgl")
        page.wait_for_function(GL_DRAWN)
        gl = _gl_view(page)
        assert gl.shape == tiles.shape and np.array_equal(gl, tiles)
    finally:
        page.select_option("#palette-preset", index=0)
        page.uncheck("#view-webgl")


# ------------------------------------------------------------------- the texture look
#: Draw the texture of ``config`` (webgl_texture's dict) with picture SW tile (x0, y0) on a canvas
#: of its own; read back the colours and each pixel's tile (the "ids" shader into an R32UI target).
READ_TEXTURE = """([config, x0, y0, cellPx, w, h]) => {
  const cv = document.createElement("canvas"); cv.width = w; cv.height = h;
  const gl = cv.getContext("webgl2", { antialias: false, alpha: false, preserveDrawingBuffer: true });
  const b64 = (a) => { const u = new Uint8Array(a.buffer); let s = "";
                       for (let i = 0; i < u.length; i += 8192) s += String.fromCharCode(...u.subarray(i, i + 8192));
                       return btoa(s); };
  const tex = new studioWebGL.Texture(gl); tex.use(config);
  tex.draw(x0, y0, 0, 0, cellPx, w, h);
  const colour = new Uint8Array(w * h * 4); gl.bindFramebuffer(gl.FRAMEBUFFER, null);
  gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, colour);
  const t = gl.createTexture(); gl.bindTexture(gl.TEXTURE_2D, t); gl.texStorage2D(gl.TEXTURE_2D, 1, gl.R32UI, w, h);
  const fbo = gl.createFramebuffer(); gl.bindFramebuffer(gl.FRAMEBUFFER, fbo);
  gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, t, 0);
  tex.draw(x0, y0, 0, 0, cellPx, w, h, "ids", fbo);
  const ids = new Uint32Array(w * h * 4); gl.bindFramebuffer(gl.FRAMEBUFFER, fbo);
  gl.readPixels(0, 0, w, h, gl.RGBA_INTEGER, gl.UNSIGNED_INT, ids);
  return { colour: b64(colour), ids: b64(ids), error: gl.getError() };
}"""


@pytest.fixture(scope="module")
def texture_atlas():
    """The studio's texture atlas of 3 colours, seed 3 (the texture views' example and tile)."""
    from tilesolve.gpu.texture import Atlas
    from tilesolve.studio.views import TEXTURE_TILE, texture_example

    return Atlas.from_example(texture_example(), 3, tile=TEXTURE_TILE, seed=3)


@pytest.mark.parametrize("origin", [(0, 0), (-37, 11), (HUGE, -HUGE)])
def test_the_browser_draws_the_cpu_texture(gl_page, texture_atlas, origin):
    # the texture look: at one texel a pixel (24 px a tile, mip level 0, texel centres) the
    # browser's pixels are the CPU's (texture_window, the server's tiles) exactly; at any size
    # every pixel's tile is the CPU's direct corner tiling (the integer hashes) exactly
    from tilesolve.constructive.stochastic import direct_corner
    from tilesolve.gpu.texture import texture_window, webgl_texture

    config = webgl_texture(texture_atlas, seed=3)
    cols, rows = 11, 6
    doc = gl_page.evaluate(READ_TEXTURE, [config, str(origin[0]), str(origin[1]), 24, cols * 24, rows * 24])
    assert doc["error"] == 0
    colour = _array(doc, "colour", np.uint8, cols * 24, rows * 24)
    cpu = texture_window(texture_atlas, origin[0], origin[1], cols, rows, seed=3)
    differ = np.any(colour != cpu, axis=2)
    print(f"\nWebGL2 texture vs the CPU's, {cols * 24}x{rows * 24} px: {np.count_nonzero(differ)} differ")
    assert not differ.any()
    tiles = direct_corner(origin[0], origin[1], 40, 17, colors=3, seed=3)
    doc = gl_page.evaluate(READ_TEXTURE, [config, str(origin[0]), str(origin[1]), 7, 40 * 7, 17 * 7])
    ids = _array(doc, "ids", np.uint32, 40 * 7, 17 * 7)[..., 0]
    assert np.array_equal(ids, np.repeat(np.repeat(tiles, 7, 0), 7, 1))


def _texture_view_at_24_px(page, box: bool) -> None:
    """The stochastic family's view (corner tiles, 3 colours, seed 3) in the texture look at zoom 3:
    24 px a tile, the server's level-0 tiles one pixel a pixel; ``box``: the "WebGL2" box ticked."""
    page.select_option("#family", "stochastic")
    page.select_option("#field-kind", "corner")
    page.fill("#field-colors", "3")
    page.dispatch_event("#field-colors", "change")
    page.fill("#seed", "3")
    page.dispatch_event("#seed", "change")
    page.set_checked("#view-webgl", box)
    page.check("#view-texture")
    page.locator("#viewport").scroll_into_view_if_needed()
    page.evaluate("Object.assign(studio.view, { x: -301, y: 97, zoom: 3 }); drawView()")


def test_the_texture_view_is_the_same_pixels_from_webgl2_and_from_the_server(gl_page):
    page = gl_page
    try:
        _texture_view_at_24_px(page, box=False)
        assert page.is_visible("#view-texture-label") and page.evaluate("studio.view.look") == "texture"
        page.wait_for_function(TILES_DRAWN)
        assert page.evaluate("studio.view.level") == 0 and page.is_hidden("#view-gl")
        tiles = _tiles_view(page)
        page.check("#view-webgl")
        page.wait_for_function(GL_DRAWN + " && studioWebGL.state.kind === 'texture'")
        assert page.evaluate("studioWebGL.state.drawn.cellPx") == 24
        gl = _gl_view(page)
        assert gl.shape == tiles.shape
        differ = np.any(gl != tiles, axis=2)
        print(f"\nWebGL2 texture view vs the server's tiles, {gl.shape[1]}x{gl.shape[0]} px: "
              f"{np.count_nonzero(differ)} differ")
        assert not differ.any()
        # a lost context: the server's texture tiles, the same pixels, until it is restored
        page.evaluate("window.loseContext = studioWebGL.gl.getExtension('WEBGL_lose_context'); loseContext.loseContext()")
        page.wait_for_function(f"studioWebGL.state.lost && {TILES_DRAWN}")
        assert np.array_equal(_tiles_view(page), gl)
        page.evaluate("loseContext.restoreContext()")
        page.wait_for_function(f"!studioWebGL.state.lost && {GL_DRAWN} && studioWebGL.state.kind === 'texture'")
        assert np.array_equal(_gl_view(page), gl)
        # unticked "Texture": the family's own picture tiles, which have no shader
        page.uncheck("#view-texture")
        page.wait_for_function(TILES_DRAWN)
        assert page.evaluate("studioWebGL.state.kind") is None and page.is_hidden("#view-gl")
        assert not np.array_equal(_tiles_view(page), gl)
    finally:
        page.uncheck("#view-texture")
        page.uncheck("#view-webgl")
    page.select_option("#family", "board")
    assert page.is_hidden("#view-texture-label")  # a wall has no texture look
