// tilesolve studio: the infinite view of the procedural wall, and the texture look of a corner
// tiling's view, drawn on the page's own GPU by the GPU path's shaders (tilesolve/gpu/wall.py and
// tilesolve/gpu/texture.py, served as GLSL ES 3.00 by GET /api/webgl/{family}; the texture's
// tiles are the CPU's direct corner tiling, hash for hash, and at one texel a pixel its pixels are
// the server's texture tiles').
// Their integer hashes are the CPU's (tilesolve/constructive/walls.py), so every cell's edge
// colours, and with them every brick, are those of the server's wall; the shaders colour the
// bricks as the server's view tiles do (the board pictures' palette, served with them as a
// texture, and their geometry), so both views of one region are the same pixels. studio.js draws
// the server's view tiles instead when WebGL2 is missing, when the view has no shader, when a
// shader fails, while the page's WebGL context is lost (a note says so; the view comes back
// with the context), or when the "WebGL2" box is unticked. The box starts unticked on a software
// rasteriser (SwiftShader, llvmpipe: headless browsers, machines without a GPU driver), where
// the server's tiles come sooner: there the first frame waits seconds for the shaders to
// compile, and a zoomed-out frame (a cell a pixel) takes seconds more.
"use strict";
window.studioWebGL = (() => {
  // state.wall: what draws the view (a Wall or a Texture), null for the server's tiles
  const state = { wall: null, seq: 0, pending: false, error: "", drawn: null, lost: false, kind: null };
  let made = null, madeTexture = null;         // the one Wall and the one Texture of the page's context

  const mod = (a, n) => ((a % n) + n) % n;     // floor modulo (BigInt or Number)
  const words = (v) => { const u = BigInt.asUintN(64, v); return [Number(u & 0xFFFFFFFFn), Number(u >> 32n)]; };

  function link(gl, vertex, fragment) {
    const p = gl.createProgram();
    for (const [type, src] of [[gl.VERTEX_SHADER, vertex], [gl.FRAGMENT_SHADER, fragment]]) {
      const s = gl.createShader(type);
      gl.shaderSource(s, src); gl.compileShader(s);
      if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error("shader: " + gl.getShaderInfoLog(s));
      gl.attachShader(p, s); gl.deleteShader(s);
    }
    gl.bindAttribLocation(p, 0, "in_pos"); gl.linkProgram(p);
    if (!gl.getProgramParameter(p, gl.LINK_STATUS)) throw new Error("program: " + gl.getProgramInfoLog(p));
    return p;
  }

  function texture(gl, internal, format, type, w, h, data = null) {
    const t = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, t);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);   // integer textures: NEAREST or incomplete
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    gl.texImage2D(gl.TEXTURE_2D, 0, internal, w, h, 0, format, type, data);
    return t;
  }

  // The two passes of WallRenderer (tilesolve/gpu/wall.py) on one WebGL2 context: ``cells`` (a
  // fragment per cell: its legs, RGBA8UI, and its SW lattice point, RG32UI), then a pass per pixel
  // coloured from the palette (256 x 1 RGBA8).
  class Wall {
    constructor(gl) {
      this.gl = gl; this.config = null; this.programs = {}; this.cells = null; this.palette = null;
      gl.bindVertexArray(gl.createVertexArray());
      gl.bindBuffer(gl.ARRAY_BUFFER, gl.createBuffer());
      gl.bufferData(gl.ARRAY_BUFFER, new Float32Array([-1, -1, 1, -1, -1, 1, 1, 1]), gl.STATIC_DRAW);
      gl.enableVertexAttribArray(0); gl.vertexAttribPointer(0, 2, gl.FLOAT, false, 0, 0);
    }

    // A new seed or colouring: the served shaders, compiled now so that a failure shows at once.
    // A new palette alone (the page's chosen colours) only replaces the palette texture.
    use(config) {
      const gl = this.gl, rgba = new Uint8Array(256 * 4).fill(255);
      const same = this.config && ["vertex", "cells", "colour", "data"].every(k => this.config[k] === config[k]) &&
                   JSON.stringify(this.config.uniforms) === JSON.stringify(config.uniforms);
      if (this.palette) gl.deleteTexture(this.palette);
      config.palette.forEach((rgb, k) => rgba.set(rgb, 4 * k));
      this.palette = texture(gl, gl.RGBA8, gl.RGBA, gl.UNSIGNED_BYTE, 256, 1, rgba);
      gl.bindTexture(gl.TEXTURE_2D, null);
      if (same) { this.config = config; return; }
      for (const p of Object.values(this.programs)) gl.deleteProgram(p);
      this.config = config; this.programs = {};
      this.program("cells"); this.program("colour");
    }

    program(kind) {
      if (!this.programs[kind]) {
        const gl = this.gl, u = this.config.uniforms, p = link(gl, this.config.vertex, this.config[kind]);
        const at = (name) => gl.getUniformLocation(p, name);   // null (a no-op) where the compiler dropped it
        gl.useProgram(p);
        gl.uniform2uiv(at("u_basis"), new Uint32Array(u.u_basis));
        gl.uniform1ui(at("u_nc"), u.u_nc); gl.uniform1i(at("u_p"), u.u_p); gl.uniform1i(at("u_fixed"), u.u_fixed ? 1 : 0);
        gl.uniform1i(at("u_cells"), 0); gl.uniform1i(at("u_points"), 1); gl.uniform1i(at("u_palette"), 2);
        this.programs[kind] = p;
      }
      return this.programs[kind];
    }

    // Local cells start at a multiple of 4, `margin` cells south-west of the picture's SW cell
    // (x0, y0) (BigInt): the 64-bit origin as words, the local SW cell, and u_dres (WallRenderer).
    locate(x0, y0) {
      const m = BigInt(this.config.margin), P = BigInt(Math.max(this.config.uniforms.u_p, 1));
      const i0 = x0 - m - mod(x0, 4n), j0 = y0 - m - mod(y0, 4n);
      return { origin: [...words(i0), ...words(j0)], local0: [Number(x0 - i0), Number(y0 - j0)],
               dres: Number(mod(i0 - j0, P) + P * ((65536n + P - 1n) / P)) };
    }

    cellTargets(nx, ny) {
      const gl = this.gl;
      if (this.cells && this.cells.nx === nx && this.cells.ny === ny) return this.cells;
      if (this.cells) { gl.deleteFramebuffer(this.cells.fbo); gl.deleteTexture(this.cells.legs); gl.deleteTexture(this.cells.points); }
      const legs = texture(gl, gl.RGBA8UI, gl.RGBA_INTEGER, gl.UNSIGNED_BYTE, nx, ny);
      const points = texture(gl, gl.RG32UI, gl.RG_INTEGER, gl.UNSIGNED_INT, nx, ny);
      const fbo = gl.createFramebuffer();
      gl.bindFramebuffer(gl.FRAMEBUFFER, fbo);
      gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, legs, 0);
      gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT1, gl.TEXTURE_2D, points, 0);
      gl.drawBuffers([gl.COLOR_ATTACHMENT0, gl.COLOR_ATTACHMENT1]);
      this.cells = { nx, ny, legs, points, fbo };
      return this.cells;
    }

    // Shade the pixels (ox, oy) + [0, w) x [0, h) of the picture whose SW cell is (x0, y0), cells
    // `cellPx` pixels a side, into `target` (null: the canvas) with the program `kind`
    // ("colour", or "data" into a framebuffer of three attachments), as WallRenderer._pass does.
    draw(x0, y0, ox, oy, cellPx, w, h, kind = "colour", target = null) {
      const gl = this.gl, at = this.locate(BigInt(x0), BigInt(y0));
      const first = [Math.floor(ox / cellPx) + at.local0[0] - 1, Math.floor(oy / cellPx) + at.local0[1] - 1];
      const cells = this.cellTargets(Math.floor((ox + w - 1) / cellPx) - Math.floor(ox / cellPx) + 3,
                                     Math.floor((oy + h - 1) / cellPx) - Math.floor(oy / cellPx) + 3);
      const place = (p) => {
        gl.useProgram(p);
        const loc = (name) => gl.getUniformLocation(p, name);
        gl.uniform2uiv(loc("u_origin"), new Uint32Array(at.origin)); gl.uniform1i(loc("u_dres"), at.dres);
        gl.uniform2i(loc("u_first"), first[0], first[1]); gl.uniform2i(loc("u_local0"), at.local0[0], at.local0[1]);
        gl.uniform1i(loc("u_cell_px"), cellPx); gl.uniform2i(loc("u_offset"), ox, oy);
      };
      gl.bindFramebuffer(gl.FRAMEBUFFER, cells.fbo);
      gl.viewport(0, 0, cells.nx, cells.ny);
      place(this.program("cells"));
      gl.drawArrays(gl.TRIANGLE_STRIP, 0, 4);
      gl.bindFramebuffer(gl.FRAMEBUFFER, target);
      gl.viewport(0, 0, w, h);
      gl.activeTexture(gl.TEXTURE0); gl.bindTexture(gl.TEXTURE_2D, cells.legs);
      gl.activeTexture(gl.TEXTURE1); gl.bindTexture(gl.TEXTURE_2D, cells.points);
      gl.activeTexture(gl.TEXTURE2); gl.bindTexture(gl.TEXTURE_2D, this.palette);
      place(this.program(kind));
      gl.drawArrays(gl.TRIANGLE_STRIP, 0, 4);
      for (const unit of [gl.TEXTURE2, gl.TEXTURE1, gl.TEXTURE0]) {
        gl.activeTexture(unit); gl.bindTexture(gl.TEXTURE_2D, null);
      }
    }
  }

  // The corner-tile texture of the GPU path (TextureMapper of tilesolve/gpu/texture.py in one
  // pass) on one WebGL2 context: the hash's tables (R32UI), the tiles' places in the packing
  // (RG32UI), the atlas (RGBA8, mipmapped, wrapping as the packing does), and per pass the row
  // tables of its tile columns and rows (RGBA32UI, built here as row_table builds them).
  class Texture {
    constructor(gl) {
      this.gl = gl; this.config = null; this.programs = {}; this.textures = {};
      gl.bindVertexArray(gl.createVertexArray());
      gl.bindBuffer(gl.ARRAY_BUFFER, gl.createBuffer());
      gl.bufferData(gl.ARRAY_BUFFER, new Float32Array([-1, -1, 1, -1, -1, 1, 1, 1]), gl.STATIC_DRAW);
      gl.enableVertexAttribArray(0); gl.vertexAttribPointer(0, 2, gl.FLOAT, false, 0, 0);
      this.vao = gl.getParameter(gl.VERTEX_ARRAY_BINDING);
    }

    use(config) {
      const gl = this.gl, c = config;
      for (const p of Object.values(this.programs)) gl.deleteProgram(p);
      for (const t of Object.values(this.textures)) gl.deleteTexture(t);
      const flat = (rows) => new Uint32Array(rows.flat(2));
      const bytes = Uint8Array.from(atob(c.atlas), (ch) => ch.charCodeAt(0));
      const n = c.atlas_size, up = new Uint8Array(bytes.length), row = 4 * n;
      for (let y = 0; y < n; y++) up.set(bytes.subarray((n - 1 - y) * row, (n - y) * row), y * row);   // GL rows from the bottom
      this.textures = {
        perm: texture(gl, gl.R32UI, gl.RED_INTEGER, gl.UNSIGNED_INT, c.perm[0].length, 8, flat(c.perm)),
        red: texture(gl, gl.R32UI, gl.RED_INTEGER, gl.UNSIGNED_INT, c.red.length, 1, new Uint32Array(c.red)),
        where: texture(gl, gl.RG32UI, gl.RG_INTEGER, gl.UNSIGNED_INT, c.where.length, 1, flat(c.where)),
        atlas: texture(gl, gl.RGBA8, gl.RGBA, gl.UNSIGNED_BYTE, n, n, up),
      };
      gl.generateMipmap(gl.TEXTURE_2D);                // the atlas, bound last
      gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.LINEAR_MIPMAP_LINEAR);
      gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
      gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.REPEAT);
      gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.REPEAT);
      gl.bindTexture(gl.TEXTURE_2D, null);
      this.config = c; this.programs = {};
      this.program("colour");
    }

    program(kind) {
      if (!this.programs[kind]) {
        const gl = this.gl, p = link(gl, this.config.vertex, this.config[kind]);
        const at = (name) => gl.getUniformLocation(p, name);
        gl.useProgram(p);
        ["u_perm", "u_px", "u_ym", "u_red", "u_where", "u_atlas"].forEach((name, unit) => gl.uniform1i(at(name), unit));
        gl.uniform1ui(at("u_colors"), this.config.colors); gl.uniform1i(at("u_grid"), this.config.colors ** 2);
        this.programs[kind] = p;
      }
      return this.programs[kind];
    }

    // (2, count, 4) row tables of tile columns (xAxis: P_i[(base + k) % N_i]) or rows ((base + k) % N_i).
    rows(base, count, xAxis) {
      const out = new Uint32Array(2 * count * 4);
      this.config.tables.forEach((t, i) => {
        const r = Number(mod(base, BigInt(t.length)));
        for (let k = 0; k < count; k++) {
          const res = (r + k) % t.length;
          out[(i >> 2) * count * 4 + 4 * k + (i & 3)] = xAxis ? t[res] : res;
        }
      });
      return texture(this.gl, this.gl.RGBA32UI, this.gl.RGBA_INTEGER, this.gl.UNSIGNED_INT, count, 2, out);
    }

    // Shade the pixels (ox, oy) + [0, w) x [0, h) of the picture whose SW tile is (x0, y0), tiles
    // `cellPx` pixels a side, into `target` (null: the canvas) with the program `kind` ("colour",
    // or "ids" into an R32UI target), as TextureMapper._pass does with two_pass=False.
    draw(x0, y0, ox, oy, cellPx, w, h, kind = "colour", target = null) {
      const gl = this.gl, p = this.program(kind), T = this.textures;
      const first = [Math.floor(ox / cellPx), Math.floor(oy / cellPx)];
      const count = [Math.floor((ox + w - 1) / cellPx) - first[0] + 1, Math.floor((oy + h - 1) / cellPx) - first[1] + 1];
      const px = this.rows(BigInt(x0) + BigInt(first[0]), count[0] + 1, true);
      const ym = this.rows(BigInt(y0) + BigInt(first[1]), count[1] + 1, false);
      gl.bindVertexArray(this.vao);
      gl.bindFramebuffer(gl.FRAMEBUFFER, target);
      gl.viewport(0, 0, w, h);
      gl.useProgram(p);
      const loc = (name) => gl.getUniformLocation(p, name);
      gl.uniform2i(loc("u_offset"), ox, oy); gl.uniform2i(loc("u_first"), first[0], first[1]);
      gl.uniform1i(loc("u_tile_px"), cellPx); gl.uniform1f(loc("u_lod"), Math.log2(this.config.tile / cellPx));
      [T.perm, px, ym, T.red, T.where, T.atlas].forEach((t, unit) => { gl.activeTexture(gl.TEXTURE0 + unit); gl.bindTexture(gl.TEXTURE_2D, t); });
      gl.drawArrays(gl.TRIANGLE_STRIP, 0, 4);
      for (let unit = 5; unit >= 0; unit--) { gl.activeTexture(gl.TEXTURE0 + unit); gl.bindTexture(gl.TEXTURE_2D, null); }
      gl.deleteTexture(px); gl.deleteTexture(ym);
    }
  }

  // The canvas over the view's 2D canvas, and its context (null without WebGL2).
  function canvas() {
    let cv = document.getElementById("view-gl");
    if (!cv) {
      cv = document.createElement("canvas"); cv.id = "view-gl";
      cv.style.cssText = "position: absolute; inset: 0; width: 100%; height: 100%; display: none";
      document.getElementById("view-canvas").after(cv);
    }
    return cv;
  }

  const gl = canvas().getContext("webgl2", { antialias: false, alpha: false, preserveDrawingBuffer: true });
  const info = gl && gl.getExtension("WEBGL_debug_renderer_info");
  const renderer = gl ? gl.getParameter(info ? info.UNMASKED_RENDERER_WEBGL : gl.RENDERER) : "";
  const software = /SwiftShader|llvmpipe|softpipe|software/i.test(renderer);

  // The "WebGL2" box of the view panel: `changed` (studio.js's resetView) when it is ticked or
  // not, and when the context is lost or restored. A lost context loses every program, texture
  // and framebuffer: the view is the server's tiles, under a note, until the browser restores
  // the context; then the shaders are fetched and compiled again.
  function setup(changed) {
    const box = document.createElement("label");
    box.id = "view-webgl-label";
    box.title = !gl ? "this browser has no WebGL2: the view is drawn from the server's tiles"
      : `draw the view here with the GPU path's shaders (unticked: the server's tiles)${software
        ? `; ${renderer} is a software rasteriser, slower than the server's tiles` : ""}`;
    box.innerHTML = `<input id="view-webgl" type="checkbox"${!gl ? " disabled" : software ? "" : " checked"}> WebGL2`;
    const note = document.createElement("span");
    note.id = "view-webgl-lost"; note.setAttribute("role", "status"); note.hidden = true;
    note.style.cssText = "position: absolute; left: .6em; top: .6em; background: #fff4d6; color: #5c4100; " +
      "border: 1px solid #e0b84a; padding: .25em .7em; border-radius: 6px; font-size: .88em";
    note.textContent = "WebGL2 context lost: showing the server's tiles until the browser restores it";
    document.getElementById("view-info").before(box);
    document.getElementById("viewport").append(note);
    box.firstChild.addEventListener("change", changed);
    if (!gl) return;
    canvas().addEventListener("webglcontextlost", (e) => {
      e.preventDefault();                      // ask the browser to restore it
      state.lost = true; state.wall = made = madeTexture = null; state.pending = false; state.drawn = null;
      changed();
    });
    canvas().addEventListener("webglcontextrestored", () => { state.lost = false; changed(); });
  }

  // The view of family `name` for the form values `values` (URL-encoded JSON) in the colours
  // `palette` (RRGGBB,...; "" for the pictures' own): fetch its shaders (if it has some) and
  // compile them. Resolves when known; until then draw() draws nothing.
  async function configure(name, values, palette = "", look = "picture") {
    const seq = ++state.seq;
    state.wall = null; state.error = ""; state.pending = false; state.kind = null;
    const box = document.getElementById("view-webgl");
    if (!gl || state.lost || (box && !box.checked)) return;
    state.pending = true;
    try {
      const r = await fetch(`/api/webgl/${name}?values=${values}${palette ? `&palette=${palette}` : ""}` +
                            (look !== "picture" ? `&look=${look}` : ""));
      const doc = await r.json();
      if (seq !== state.seq || gl.isContextLost()) return;
      if (r.ok && doc.kind === "wall") {
        state.wall = made = made || new Wall(gl);
        state.wall.use(doc);
      } else if (r.ok && doc.kind === "texture") {
        state.wall = madeTexture = madeTexture || new Texture(gl);
        state.wall.use(doc);
      }
      if (state.wall) state.kind = doc.kind;
    } catch (e) {
      if (seq === state.seq) { state.error = e.message; state.wall = null; }
    } finally {
      if (seq === state.seq) state.pending = false;
    }
  }

  // Draw studio.js's view (x, y: its top-left in CSS px at zoom 1, `cell` px a cell; w x h CSS
  // px, dpr device px each) with whole device pixels per cell. False: draw the server's tiles.
  function draw(view, cell, w, h, dpr) {
    const cv = canvas(), box = document.getElementById("view-webgl"), note = document.getElementById("view-webgl-lost");
    if (note) note.hidden = !(state.lost && box && box.checked);
    // While the shaders load, the last WebGL2 picture stays; with none on show (the first one,
    // or after a lost context) the server's tiles are drawn meanwhile.
    if (state.pending) return cv.style.display === "block";
    if (!state.wall) { cv.style.display = "none"; return false; }
    const W = Math.round(w * dpr), H = Math.round(h * dpr);
    if (cv.width !== W || cv.height !== H) { cv.width = W; cv.height = H; }
    // device pixel (GX + px, GY + py) of the plane, y down; cell x = floor(gx / cpx), y = -floor(gy / cpx) - 1
    const cpx = Math.max(1, Math.round(cell * view.zoom * dpr));
    const GX = Math.round(view.x * cpx / cell), GY = Math.round(view.y * cpx / cell), M = -GY - H;
    const x0 = Math.floor(GX / cpx), y0 = Math.floor(M / cpx);
    try {
      state.wall.draw(x0, y0, GX - x0 * cpx, M - y0 * cpx, cpx, W, H);
    } catch (e) {
      state.error = e.message; state.wall = null; cv.style.display = "none"; return false;
    }
    cv.style.display = "block";
    state.drawn = { x0, y0, ox: GX - x0 * cpx, oy: M - y0 * cpx, cellPx: cpx, width: W, height: H };
    return true;
  }

  return { state, setup, configure, draw, gl, renderer, Wall, Texture };
})();
