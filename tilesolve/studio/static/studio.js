// tilesolve studio page: every form is built from the family's fields (GET /api/families),
// no family is special-cased here. The tile colours come from the server (the palette of the SVG
// and PNG writers, tilesolve/io/svg.py); a palette chosen here recolours the editor, the picture
// and the exported pictures alike, and the infinite view: its server tiles and its WebGL2 wall
// are asked for in the chosen colours (`palette=`), the wall's bricks taking them in turn.
"use strict";
const $ = (id) => document.getElementById(id);
const studio = window.studio = { timings: {}, families: [], fam: null, extents: {}, grids: {}, cells: null,
                                 job: null, result: null, palette: null, colours: null };
const VIEW_N = 32, CELL = 8;           // view tiles: VIEW_N << level cells, CELL css px per cell at zoom 1
const MAX_LEVEL = 2;                   // the server draws windows of at most 128 cells a side
const TEXTURE_ZOOM = 24 / CELL;        // one texel a CSS px: the texture look's tiles are 24 texels (views.TEXTURE_TILE)
const SWATCHES = 8;

async function api(path, body) {
  const opts = body === undefined ? {} : { method: "POST", headers: { "Content-Type": "application/json" },
                                           body: JSON.stringify(body) };
  const r = await fetch(path, opts);
  const doc = await r.json();
  if (!r.ok) throw new Error(doc.error || r.statusText);
  return doc;
}

function showError(msg) { $("error").textContent = msg ? "error: " + msg : ""; }

// ------------------------------------------------------------------ palettes
// Colour-blind-safe presets: Okabe & Ito (the pictures' own, from the server), Paul Tol's
// "bright", and viridis sampled at eight points; tiles past a preset's list keep the server's colours.
const PRESET_PALETTES = {
  "Okabe–Ito (pictures' own)": null,
  "Tol bright": ["#4477AA", "#EE6677", "#228833", "#CCBB44", "#66CCEE", "#AA3377", "#BBBBBB", "#222222"],
  "viridis": ["#440154", "#46327E", "#365C8D", "#277F8E", "#1FA187", "#4AC16D", "#A0DA39", "#FDE725"],
};

function setPalette(list) {
  const base = studio.palette.tiles;
  studio.colours = base.map((c, k) => (list && k < list.length ? list[k] : c).toUpperCase());
  drawSwatches(); drawGrid(); recolourPicture();
  if (studio.fam && viewPalette() !== view.palette) resetView();
}
const tileColour = (k) => (k < 0 ? studio.palette.free : studio.colours[k % studio.colours.length]);
const recoloured = () => studio.colours.some((c, k) => c !== studio.palette.tiles[k].toUpperCase());

// The view's colours: the swatches' (RRGGBB,...) when a palette is chosen, "" for the pictures' own.
const viewPalette = () => (recoloured() ? studio.colours.slice(0, SWATCHES).map(c => c.slice(1)).join(",") : "");

function drawSwatches() {
  const box = $("swatches"); box.innerHTML = "";
  for (let k = 0; k < SWATCHES; k++) {
    const b = document.createElement("button"); b.type = "button"; b.textContent = k;
    b.style.background = studio.colours[k]; b.title = `tile ${k}: ${studio.colours[k]}`;
    b.addEventListener("click", () => {
      const input = document.createElement("input"); input.type = "color"; input.value = studio.colours[k];
      input.addEventListener("input", () => {
        const list = studio.colours.slice(0, SWATCHES); list[k] = input.value; setPalette(list);
      });
      input.click();
    });
    box.appendChild(b);
  }
}

function rgbOf(hex) { const v = parseInt(hex.slice(1), 16); return [v >> 16 & 255, v >> 8 & 255, v & 255]; }

// The picture in the chosen palette: an SVG's fills are swapped; a PNG is redrawn on a canvas
// with its pixels mapped colour for colour.
const paletteMap = () => new Map(studio.palette.tiles.map((c, k) => [c.toUpperCase(), studio.colours[k]]));

function recolourSvg(svg, map) {
  for (const el of svg.querySelectorAll("[fill]")) {
    const orig = el.dataset.fill || el.getAttribute("fill").toUpperCase();
    if (!map.has(orig)) continue;
    el.dataset.fill = orig; el.setAttribute("fill", map.get(orig));
  }
}

function recolouredCanvas(img, map) {
  const cv = document.createElement("canvas"); cv.width = img.naturalWidth; cv.height = img.naturalHeight;
  const ctx = cv.getContext("2d"); ctx.drawImage(img, 0, 0);
  const data = ctx.getImageData(0, 0, cv.width, cv.height), px = new Uint32Array(data.data.buffer);
  const lut = new Map();
  for (const [from, to] of map) {
    const [r, g, b] = rgbOf(from), [r2, g2, b2] = rgbOf(to);
    lut.set((255 << 24 | b << 16 | g << 8 | r) >>> 0, (255 << 24 | b2 << 16 | g2 << 8 | r2) >>> 0);
  }
  for (let i = 0; i < px.length; i++) { const v = lut.get(px[i]); if (v !== undefined) px[i] = v; }
  ctx.putImageData(data, 0, 0);
  return cv;
}

function recolourPicture() {
  const res = studio.result, pic = $("picture");
  if (!res || !res.picture) return;
  if (res.picture.format === "svg") {
    const svg = pic.querySelector("svg");
    if (svg) recolourSvg(svg, paletteMap());
    return;
  }
  const img = studio.pictureImage;
  if (!img) return;
  let target = pic.querySelector("img, canvas");
  if (!recoloured()) { if (target !== img) { pic.replaceChildren(img); } return; }
  const cv = recolouredCanvas(img, paletteMap());
  cv.setAttribute("aria-label", img.alt);
  pic.replaceChildren(cv);
}

// Exports of the picture in the chosen palette are made here: the shown picture itself, or, in the
// other format, the server's file (the CLI's) recoloured the same way; in the pictures' own palette
// they are the server's files.
async function exportPicture(fmt, ev) {
  if (!recoloured() || !studio.result || !studio.result.picture) return;
  ev.preventDefault();
  const pic = $("picture"), map = paletteMap();
  let blob;
  if (studio.result.picture.format === fmt) {
    blob = fmt === "svg" ? new Blob([pic.querySelector("svg").outerHTML], { type: "image/svg+xml" })
                         : await new Promise((ok) => pic.querySelector("canvas").toBlob(ok, "image/png"));
  } else {
    const r = await fetch($("export-" + fmt).href);
    if (!r.ok) { showError(`export ${fmt}: ${r.status} ${(await r.text()).slice(0, 300)}`); return; }
    if (fmt === "svg") {
      const doc = new DOMParser().parseFromString(await r.text(), "image/svg+xml");
      recolourSvg(doc.documentElement, map);
      for (const el of doc.querySelectorAll("[data-fill]")) el.removeAttribute("data-fill");
      blob = new Blob([new XMLSerializer().serializeToString(doc)], { type: "image/svg+xml" });
    } else {
      const img = new Image(), url = URL.createObjectURL(await r.blob());
      img.src = url; await img.decode(); URL.revokeObjectURL(url);
      blob = await new Promise((ok) => recolouredCanvas(img, map).toBlob(ok, "image/png"));
    }
  }
  const a = document.createElement("a"); a.href = URL.createObjectURL(blob);
  a.download = `${studio.result.family}-${studio.result.seed}.${fmt}`; a.click();
  setTimeout(() => URL.revokeObjectURL(a.href), 10000);
}

// ------------------------------------------------------------------ pan and zoom
// A painter ({active(), down(e), move(e), up()}) takes the left button while it is active: then
// the middle button or Shift+drag pans.
class PanZoom {
  constructor(stage, content, { onChange = () => {}, maxZoom = 64, painter = null } = {}) {
    Object.assign(this, { stage, content, onChange, maxZoom, painter, z: 1, x: 0, y: 0 });
    let drag = null, stroke = false;
    const painting = () => this.painter !== null && this.painter.active();
    stage.addEventListener("pointerdown", (e) => {
      if ((e.button !== 0 && e.button !== 1) || e.target.closest("button")) return;
      if (e.button === 1) e.preventDefault();   // no autoscroll
      stage.setPointerCapture(e.pointerId);
      if (e.button === 0 && !e.shiftKey && painting()) { stroke = true; this.painter.down(e); return; }
      drag = { x: e.clientX, y: e.clientY }; stage.classList.add("dragging");
    });
    stage.addEventListener("pointermove", (e) => {
      if (stroke) { this.painter.move(e); return; }
      if (!drag) return;
      this.x += e.clientX - drag.x; this.y += e.clientY - drag.y; drag = { x: e.clientX, y: e.clientY }; this.apply();
    });
    const end = () => {
      if (stroke) { stroke = false; this.painter.up(); }
      drag = null; stage.classList.remove("dragging");
    };
    stage.addEventListener("pointerup", end); stage.addEventListener("pointercancel", end);
    stage.addEventListener("wheel", (e) => {
      e.preventDefault();
      const r = stage.getBoundingClientRect();
      this.zoomAt(Math.exp(-e.deltaY / 400), e.clientX - r.left, e.clientY - r.top);
    }, { passive: false });
    stage.addEventListener("dblclick", () => { if (!painting()) this.fit(); });
    stage.addEventListener("keydown", (e) => {
      const r = stage.getBoundingClientRect();
      if (e.key === "+" || e.key === "=") this.zoomAt(1.25, r.width / 2, r.height / 2);
      else if (e.key === "-") this.zoomAt(0.8, r.width / 2, r.height / 2);
      else if (e.key === "0") this.fit();
    });
    for (const b of stage.querySelectorAll("[data-zoom]")) b.addEventListener("click", () => {
      const r = stage.getBoundingClientRect(), k = b.dataset.zoom;
      if (k === "fit") this.fit(); else this.zoomAt(k === "in" ? 1.25 : 0.8, r.width / 2, r.height / 2);
    });
  }
  size() {                              // the picture's own size, in CSS px
    const el = this.content.firstElementChild;
    if (!el) return [0, 0];
    if (el instanceof SVGSVGElement) {
      const w = el.width.baseVal.value, h = el.height.baseVal.value;
      if (w && h) return [w, h];
      const vb = el.viewBox.baseVal; return vb ? [vb.width, vb.height] : [0, 0];
    }
    return [el.naturalWidth || el.width || 0, el.naturalHeight || el.height || 0];
  }
  fit() {
    const [w, h] = this.size(), W = this.stage.clientWidth, H = this.stage.clientHeight;
    if (!w || !h) return;
    this.z = Math.min((W - 24) / w, (H - 24) / h, 8);
    this.x = (W - w * this.z) / 2; this.y = (H - h * this.z) / 2; this.apply();
  }
  zoomAt(f, mx, my) {
    const z = Math.min(this.maxZoom, Math.max(0.02, this.z * f));
    this.x = mx - (mx - this.x) * z / this.z; this.y = my - (my - this.y) * z / this.z; this.z = z; this.apply();
  }
  apply() {
    this.content.style.transform = `translate(${this.x}px, ${this.y}px) scale(${this.z})`;
    this.content.style.imageRendering = this.z >= 1 ? "pixelated" : "auto";
    this.onChange(this);
  }
}

// ------------------------------------------------------------------ the form
function buildForm() {
  const form = $("form");
  form.innerHTML = "";
  for (const f of studio.fam.fields) {
    if (f.kind === "cells") continue;
    const label = document.createElement("label");
    label.title = f.help + (f.option ? " (" + f.option + ")" : "");
    label.innerHTML = `<span class="name"></span>`;
    label.firstChild.textContent = f.label;
    let input;
    if (f.kind === "choice") {
      input = document.createElement("select");
      for (const c of f.choices) input.add(new Option(c, c));
      input.value = f.default;
    } else if (f.kind === "bool") {
      input = document.createElement("input"); input.type = "checkbox"; input.checked = !!f.default;
    } else {
      input = document.createElement("input");
      input.type = (f.kind === "int" || f.kind === "float") ? "number" : "text";
      if (f.kind === "int") input.step = "1";
      if (f.kind === "float") input.step = "any";
      if (f.low !== null && f.kind !== "text") input.min = f.low;
      if (f.high !== null && f.kind !== "text" && f.kind !== "size") input.max = f.high;
      input.value = f.default === null ? "" : f.default;
      input.placeholder = f.default === null ? "none" : "";
    }
    input.name = f.name; input.id = "field-" + f.name; input.dataset.kind = f.kind; input.dataset.label = f.label;
    input.addEventListener("change", formChanged);
    label.appendChild(input); label.dataset.field = f.name;
    form.appendChild(label);
  }
  $("method").innerHTML = "";
  for (const m of studio.fam.methods) {
    const o = new Option(m, m); o.title = studio.fam.route_help[m] || ""; $("method").add(o);
  }
  const gf = $("grid-field"); gf.innerHTML = "";
  for (const f of studio.fam.fields) if (f.kind === "cells") gf.add(new Option(f.label, f.name));
  studio.grids = {}; studio.cells = null; undoStack.length = 0; redoStack.length = 0;
  studio.sketch = null; drawEdges();
  $("view-panel").hidden = !studio.fam.view;
  showApplicable();
}

// A field applies under any one of its conditions (Field.when: {other field: values}, all of
// them holding), or always; the others are hidden (the server takes their defaults).
const applies = (f, v) => !f.when.length || f.when.some((c) => Object.entries(c).every(([k, vs]) => vs.includes(v[k])));

function showApplicable() {
  const v = formValues(), gf = $("grid-field");
  for (const f of studio.fam.fields) {
    const on = applies(f, v);
    if (f.kind === "cells") { const o = gf.querySelector(`option[value="${f.name}"]`); o.hidden = o.disabled = !on; }
    else $("form").querySelector(`label[data-field="${f.name}"]`).hidden = !on;
  }
  if (gf.selectedOptions.length && gf.selectedOptions[0].disabled) {
    const next = [...gf.options].find((o) => !o.disabled);
    if (next) gf.value = next.value;
  }
  $("editor").hidden = ![...gf.options].some((o) => !o.disabled);
  if ($("editor").hidden) setPaintMode(false);
}

function formValues() {
  const v = {};
  for (const f of studio.fam.fields) {
    if (f.kind === "cells") { if (studio.grids[f.name]) v[f.name] = studio.grids[f.name]; continue; }
    const el = $("field-" + f.name);
    if (f.kind === "bool") v[f.name] = el.checked;
    else if (f.kind === "int" || f.kind === "float") v[f.name] = el.value === "" ? null : Number(el.value);
    else v[f.name] = el.value;
  }
  if ($("seed").value !== "") v.seed = Number($("seed").value);
  return v;
}

function request() {
  const r = { family: studio.fam.name, values: formValues(), method: $("method").value };
  if ($("time-limit").value !== "") r.time_limit = Number($("time-limit").value);
  return r;
}

// The field an error message names is marked: "LABEL (NAME) must ..." (the form's checks) or, in
// the CLI's own messages, the field whose label's first word comes first ("cannot read condition");
// the description is cleared and marked invalid, so that it never shows the last valid problem.
function markInvalid(message) {
  $("describe").textContent = "invalid problem: fix the marked field";
  $("describe").dataset.state = "invalid";
  const els = [...$("form").elements].filter((el) => el.dataset.label);
  const stem = (el) => el.dataset.label.split(/[\s(]/)[0].replace(/s$/, "").toLowerCase();
  let hit = els.find((el) => message.includes(`(${el.name})`) || message.startsWith(el.dataset.label));
  if (!hit) {
    const at = (el) => { const m = new RegExp(`\\b${stem(el)}`, "i").exec(message); return m ? m.index : Infinity; };
    hit = els.reduce((best, el) => (at(el) < (best ? at(best) : Infinity) ? el : best), null);
  }
  for (const el of els) el.setAttribute("aria-invalid", el === hit ? "true" : "false");
}

let checkSeq = 0;
async function formChanged() {
  const seq = ++checkSeq;
  showApplicable(); resetView(); saveState(false);
  try {
    const doc = await api("/api/check", request());
    if (seq !== checkSeq) return;
    showError("");
    for (const el of $("form").elements) el.setAttribute("aria-invalid", "false");
    $("describe").textContent = doc.describe; $("describe").dataset.state = "ok";
    studio.extents = doc.cells; studio.sketch = doc.sketch; drawEdges();
    for (const [name, [rows, cols]] of Object.entries(doc.cells)) {
      const g = studio.grids[name];
      if (g && (g.length !== rows || g[0].length !== cols)) delete studio.grids[name];
    }
    const ext = doc.cells[$("grid-field").value];
    if (studio.cells && (!ext || studio.cells.rows !== ext[0] || studio.cells.cols !== ext[1])) studio.cells = null;
    drawGrid();
  } catch (e) { if (seq === checkSeq) { showError(e.message); markInvalid(e.message); } }
}

// ------------------------------------------------------------------ editing grids
const undoStack = [], redoStack = [];       // painted grids before each stroke (undo), and undone ones (redo)
const snapshot = () => JSON.stringify(studio.grids);

function fillBrushes() {
  const name = $("grid-field").value, ext = studio.extents[name];
  const b = $("brush"), keep = b.value; b.innerHTML = "";
  if (!ext) return;
  if (studio.cells) b.add(new Option("the solution's tile", "solution"));
  b.add(new Option("clear (-1)", "-1"));
  const [, , lo, hi] = ext;
  for (let t = lo; t <= Math.min(hi, lo + 63); t++) b.add(new Option(String(t), String(t)));
  if ([...b.options].some(o => o.value === keep)) b.value = keep;
}

function cellPx(rows, cols) { return Math.max(1, Math.min(32, Math.floor(1024 / Math.max(rows, cols)))); }
const solutionCell = (r, c) => studio.cells.data[r * studio.cells.cols + c];

// One pixel per cell on a small canvas, scaled up without smoothing: any size draws in milliseconds.
function drawGrid() {
  fillBrushes();
  const name = $("grid-field").value, ext = studio.extents[name], cv = $("grid");
  if (!ext || !studio.colours) { cv.width = cv.height = 0; return; }
  const [rows, cols] = ext, px = cellPx(rows, cols), g = studio.grids[name];
  const sol = studio.cells && studio.cells.rows === rows && studio.cells.cols === cols;
  const small = document.createElement("canvas"); small.width = cols; small.height = rows;
  const sctx = small.getContext("2d"), img = sctx.createImageData(cols, rows), d = img.data;
  const rgb = studio.colours.map(rgbOf), free = [255, 255, 255];
  for (let r = 0; r < rows; r++) {
    const row = g ? g[r] : null;
    for (let c = 0; c < cols; c++) {
      const v = row ? row[c] : -1, i = 4 * (r * cols + c);
      let col = free, a = 255;
      if (v >= 0) col = rgb[v % rgb.length];
      else if (sol) { const s = solutionCell(r, c); if (s >= 0) { col = rgb[s % rgb.length]; a = 90; } }
      d[i] = col[0]; d[i + 1] = col[1]; d[i + 2] = col[2]; d[i + 3] = a;
    }
  }
  sctx.putImageData(img, 0, 0);
  cv.width = cols * px; cv.height = rows * px;
  const ctx = cv.getContext("2d");
  ctx.fillStyle = "#fff"; ctx.fillRect(0, 0, cv.width, cv.height);
  ctx.imageSmoothingEnabled = false; ctx.drawImage(small, 0, 0, cv.width, cv.height);
  if (g && px >= 6) {                  // fixed cells outlined, so that any colour reads on white
    ctx.strokeStyle = "#000"; ctx.lineWidth = 1;
    for (let r = 0; r < rows; r++) for (let c = 0; c < cols; c++)
      if (g[r][c] >= 0) ctx.strokeRect(c * px + .5, r * px + .5, px - 1, px - 1);
  }
  if (px >= 16 && ext[3] > 9) {        // many values: write the number
    ctx.font = `${Math.floor(px / 2.2)}px sans-serif`; ctx.textAlign = "center"; ctx.textBaseline = "middle";
    for (let r = 0; r < rows; r++) for (let c = 0; c < cols; c++) {
      const v = g ? g[r][c] : -1, shown = v >= 0 ? v : (sol ? solutionCell(r, c) : undefined);
      if (shown === undefined) continue;
      ctx.globalAlpha = v >= 0 ? 1 : 0.5; ctx.fillStyle = "#000"; ctx.fillText(String(shown), (c + .5) * px, (r + .5) * px);
    }
    ctx.globalAlpha = 1;
  }
}

function paintAt(ev) {
  const name = $("grid-field").value, ext = studio.extents[name];
  if (!ext) return;
  const [rows, cols] = ext, px = cellPx(rows, cols), rect = $("grid").getBoundingClientRect();
  const k = $("grid").width / rect.width;          // the canvas may be shown narrower than it is
  const c = Math.floor((ev.clientX - rect.left) * k / px), r = Math.floor((ev.clientY - rect.top) * k / px);
  if (r < 0 || c < 0 || r >= rows || c >= cols) return;
  if (!studio.grids[name]) studio.grids[name] = Array.from({ length: rows }, () => new Array(cols).fill(-1));
  const b = $("brush").value;
  studio.grids[name][r][c] = b === "solution" ? (studio.cells ? solutionCell(r, c) : -1) : Number(b);
  drawGrid();
}

function restore(from, to) {
  if (!from.length) return;
  to.push(snapshot()); studio.grids = JSON.parse(from.pop()); formChanged();
}
const undo = () => restore(undoStack, redoStack), redo = () => restore(redoStack, undoStack);

// Paint mode: the stage shows the painted grid (the solution's tiles faint under it) in place of
// the picture, with the same pan and zoom; the left button paints (studio.stage's painter).
function setPaintMode(on) {
  if (!studio.stage || studio.painting === on) return;
  studio.painting = on;
  $("paint-mode").setAttribute("aria-pressed", String(on));
  $("stage").classList.toggle("painting", on);
  $("paint").hidden = !on; $("picture").hidden = on;
  studio.stage.content = on ? $("paint") : $("picture");
  $("stage-empty").hidden = on || !!(studio.result && studio.result.picture);
  drawGrid(); studio.stage.fit();
}

const painter = {
  active: () => studio.painting,
  down(e) { undoStack.push(snapshot()); redoStack.length = 0; paintAt(e); },
  move: paintAt,
  up: () => formChanged(),
};

function setupEditor() {
  studio.painting = false;
  $("paint-mode").addEventListener("click", () => setPaintMode(!studio.painting));
  $("grid-field").addEventListener("change", () => { drawGrid(); if (studio.painting) studio.stage.fit(); });
  $("grid-undo").addEventListener("click", undo);
  $("grid-redo").addEventListener("click", redo);
  $("grid-clear").addEventListener("click", () => {
    undoStack.push(snapshot()); redoStack.length = 0; delete studio.grids[$("grid-field").value]; formChanged();
  });
  $("grid-upload").addEventListener("change", async (e) => {
    const file = e.target.files[0], name = $("grid-field").value, ext = studio.extents[name];
    if (!file || !ext) return;
    const [rows, cols, lo, hi] = ext, img = await createImageBitmap(file);
    const cv = document.createElement("canvas"); cv.width = cols; cv.height = rows;
    const ctx = cv.getContext("2d"); ctx.drawImage(img, 0, 0, cols, rows);
    const px = ctx.getImageData(0, 0, cols, rows).data, levels = Math.min(hi - lo + 1, 10);
    undoStack.push(snapshot()); redoStack.length = 0;
    studio.grids[name] = Array.from({ length: rows }, (_, r) => Array.from({ length: cols }, (_, c) => {
      const i = 4 * (r * cols + c), y = (0.299 * px[i] + 0.587 * px[i + 1] + 0.114 * px[i + 2]) / 256;
      return lo + Math.min(levels - 1, Math.floor(y * levels));
    }));
    e.target.value = "";
    formChanged();
  });
}

// ------------------------------------------------------------------ live edge editor
// A family whose tile has shaped edges (Form.sketch: the tile's sides, each an affine map of an
// edge class's unit frame (0,0)-(1,0)) gets a drawing of its tile here. Each class's points are
// dragged on the first side of that class, under its constraint: J free, U mirror-symmetric in
// x = 1/2, S symmetric by a half-turn about (1/2, 0), I straight (no points). The class's text
// field follows; the picture's tile (its SVG draws one tile path, placed by <use>) is redrawn
// at once from the same outline the server builds (constructive/isohedral.py, prototile: done
// here too so that a drag redraws at frame rate), and the server solves, verifies and draws the
// tiling again when the drag pauses or ends.
const SVGNS = "http://www.w3.org/2000/svg";
const EDGE_COLOURS = ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00"];
const round3 = (v) => Math.round(v * 1000) / 1000;
const clamp = (v, lo, hi) => Math.min(hi, Math.max(lo, v));

// "", "line", "line:X,Y/X,Y" or "bezier:X,Y/X,Y" as {kind, points}; null when unreadable.
function parseShape(text) {
  const m = /^\s*(line|bezier)?\s*(?::(.*))?$/.exec(text);
  if (!m || (!m[1] && m[2] !== undefined)) return null;
  const points = m[2] ? m[2].split("/").map((p) => p.split(",").map((v) => (v.trim() === "" ? NaN : Number(v)))) : [];
  if (points.some((p) => p.length !== 2 || !p.every(Number.isFinite))) return null;
  return { kind: m[1] || "line", points };
}
const formatShape = (s) => (s.points.length ? `${s.kind}:` + s.points.map(([x, y]) => `${x},${y}`).join("/") : s.kind);

// The shape's path from (0,0) to (1,0); a Bézier chain as `chords` chords per cubic.
function edgePath(s, chords) {
  const pts = [[0, 0], ...s.points, [1, 0]];
  if (s.kind === "line") return pts;
  const out = [];
  for (let k = 0; k + 3 < pts.length; k += 3) for (let i = 0; i < chords; i++) {
    const t = i / chords, b = [(1 - t) ** 3, 3 * t * (1 - t) ** 2, 3 * t * t * (1 - t), t ** 3];
    out.push([0, 1].map((d) => b.reduce((acc, w, j) => acc + w * pts[k + j][d], 0)));
  }
  out.push([1, 0]);
  return out;
}
const mapPoint = (m, [x, y]) => [m[0][0] * x + m[0][1] * y + m[0][2], m[1][0] * x + m[1][1] * y + m[1][2]];
function unmapPoint(m, [X, Y]) {
  const [[a, b, c], [d, e, f]] = m, det = a * e - b * d, u = X - c, v = Y - f;
  return [(e * u - b * v) / det, (a * v - d * u) / det];
}

function edgeShapes(sk) { return sk.edges.map((e) => parseShape($("field-" + e.field).value)); }

// The tile's outline: each side's shape mapped onto it, reversed where said, without its last point.
function tileOutline(sk, shapes) {
  if (shapes.some((s) => s === null)) return null;
  const out = [];
  for (const side of sk.sides) {
    const pts = edgePath(shapes[side.edge], sk.chords).map((p) => mapPoint(side.map, p));
    if (side.reverse) pts.reverse();
    out.push(...pts.slice(0, -1));
  }
  return out;
}

// The partner a point's constraint gives (U: mirror in x = 1/2; S: half-turn about (1/2, 0)).
const partner = (kind, [x, y]) => (kind === "U" ? [round3(1 - x), y] : [round3(1 - x), round3(-y)]);

function movePoint(s, kind, i, q) {
  q = [round3(clamp(q[0], -3, 4)), round3(clamp(q[1], -4, 4))];   // the model's box: |coordinate| <= 4
  const j = s.points.length - 1 - i;
  if (kind === "U" || kind === "S") {
    if (i === j) q = kind === "U" ? [0.5, q[1]] : [0.5, 0];
    else s.points[j] = partner(kind, q);
  }
  s.points[i] = q;
}

function segmentDistance([px, py], [ax, ay], [bx, by]) {
  const dx = bx - ax, dy = by - ay, len = dx * dx + dy * dy;
  const t = len ? clamp(((px - ax) * dx + (py - ay) * dy) / len, 0, 1) : 0;
  return Math.hypot(px - ax - t * dx, py - ay - t * dy);
}

// A polyline point at q on its nearest segment, with its partner on the mirror segment (U, S).
function insertPoint(s, kind, q) {
  q = [round3(clamp(q[0], -3, 4)), round3(clamp(q[1], -4, 4))];
  const P = s.points, n = P.length, path = [[0, 0], ...P, [1, 0]];
  let seg = 0;
  for (let t = 1; t <= n; t++) if (segmentDistance(q, path[t], path[t + 1]) < segmentDistance(q, path[seg], path[seg + 1])) seg = t;
  if (kind === "J") { P.splice(seg, 0, q); return; }
  if (2 * seg === n) { P.splice(seg, 0, kind === "U" ? [0.5, q[1]] : [0.5, 0]); return; }   // the middle segment
  let a = q, b = partner(kind, q);
  if (seg > n - seg) { seg = n - seg; [a, b] = [b, a]; }
  s.points = [...P.slice(0, seg), a, ...P.slice(seg, n - seg), b, ...P.slice(n - seg)];
}

function removePoint(s, kind, i) {
  const j = s.points.length - 1 - i;
  s.points = s.points.filter((_, k) => k !== i && (kind === "J" || k !== j));
}

function svgEl(tag, attrs, parent) {
  const el = document.createElementNS(SVGNS, tag);
  for (const [k, v] of Object.entries(attrs)) el.setAttribute(k, v);
  if (parent) parent.appendChild(el);
  return el;
}
const pointsAttr = (pts) => pts.map(([x, y]) => `${x},${y}`).join(" ");

function drawEdges() {
  const sk = studio.sketch, svg = $("edge-editor");
  $("edges").hidden = !sk;
  if (!sk) return;
  const shapes = edgeShapes(sk), outline = tileOutline(sk, shapes);
  // the view: the straight tile's corners with room around them for the edges' points
  const corners = sk.sides.map((side) => mapPoint(side.map, [0, 0]));
  const xs = corners.map((p) => p[0]), ys = corners.map((p) => p[1]);
  const wide = Math.max(...xs) - Math.min(...xs), high = Math.max(...ys) - Math.min(...ys), pad = 0.4 * Math.max(wide, high);
  const w = wide + 2 * pad, h = high + 2 * pad;
  svg.setAttribute("viewBox", `${Math.min(...xs) - pad} ${-Math.max(...ys) - pad} ${w} ${h}`);
  const unit = Math.max(w / (svg.clientWidth || 320), h / (svg.clientHeight || 280));   // a CSS pixel in the tile's units
  svg.replaceChildren();
  const g = svgEl("g", { transform: "scale(1 -1)" }, svg);
  studio.edgeFrame = g;
  if (outline) svgEl("polygon", { points: pointsAttr(outline), fill: "#e9eef5", stroke: "none" }, g);
  const seen = new Set();
  sk.sides.forEach((side, k) => {
    const shape = shapes[side.edge], kind = sk.edges[side.edge].kind, colour = EDGE_COLOURS[side.edge % EDGE_COLOURS.length];
    if (!shape) return;
    const pts = edgePath(shape, sk.chords).map((p) => mapPoint(side.map, p));
    svgEl("polyline", { points: pointsAttr(pts), fill: "none", stroke: colour, "stroke-width": 2 * unit,
                        "stroke-dasharray": kind === "I" ? `${4 * unit} ${3 * unit}` : "none" }, g);
    if (seen.has(side.edge)) return;   // the first side of its class carries the points
    seen.add(side.edge);
    const mid = mapPoint(side.map, [0.5, 0]);
    const label = svgEl("text", { x: mid[0], y: -mid[1], "font-size": 12 * unit, fill: colour, "text-anchor": "middle",
                                  "font-weight": 600, "pointer-events": "none" }, svg);
    label.textContent = `${side.edge} ${kind}`;
    if (kind === "I") return;
    if (shape.kind === "line") {
      const hit = svgEl("polyline", { points: pointsAttr(pts), fill: "none", stroke: "transparent",
                                      "stroke-width": 12 * unit, class: "hit" }, g);
      hit.dataset.side = k;
    } else {
      const ctrl = [[0, 0], ...shape.points, [1, 0]].map((p) => mapPoint(side.map, p));
      svgEl("polyline", { points: pointsAttr(ctrl), fill: "none", stroke: colour, "stroke-opacity": 0.5,
                          "stroke-width": unit, "stroke-dasharray": `${3 * unit} ${3 * unit}` }, g);
    }
    shape.points.forEach((p, i) => {
      const [cx, cy] = mapPoint(side.map, p);
      const c = svgEl("circle", { cx, cy, r: 6 * unit, fill: colour, stroke: "#fff", "stroke-width": 1.5 * unit, class: "handle" }, g);
      c.dataset.side = k; c.dataset.i = i;
    });
  });
}

// A changed shape: its text field, the editor, the picture's tile at once, the server's tiling soon.
function commitShape(edge, shape) {
  $("field-" + studio.sketch.edges[edge].field).value = formatShape(shape);
  drawEdges();
  const outline = tileOutline(studio.sketch, edgeShapes(studio.sketch));
  const tile = $("picture").querySelector("svg path#tile");
  if (outline && tile && studio.result && studio.result.family === studio.fam.name)
    tile.setAttribute("d", "M" + outline.map(([x, y]) => `${x.toFixed(6)} ${y.toFixed(6)}`).join(" L") + " Z");
  resolveSoon();
}

let resolveTimer = null;
function resolveSoon(ms = 400) {
  clearTimeout(resolveTimer);
  resolveTimer = setTimeout(async () => {
    if (studio.job) { resolveSoon(ms); return; }
    studio.keepView = true;
    try { await solve(); } finally { studio.keepView = false; }
  }, ms);
}

function setupEdgeEditor() {
  const svg = $("edge-editor");
  let drag = null;
  const at = (e) => {   // the pointer in the tile's coordinates
    const p = svg.createSVGPoint(); p.x = e.clientX; p.y = e.clientY;
    const q = p.matrixTransform(studio.edgeFrame.getScreenCTM().inverse()); return [q.x, q.y];
  };
  const target = (e) => {
    const side = studio.sketch.sides[Number(e.target.dataset.side)], edge = side.edge;
    return { side, edge, kind: studio.sketch.edges[edge].kind, shape: edgeShapes(studio.sketch)[edge] };
  };
  svg.addEventListener("pointerdown", (e) => {
    if (!e.target.classList.contains("handle") || e.button !== 0) return;
    drag = { ...target(e), i: Number(e.target.dataset.i) };
    svg.setPointerCapture(e.pointerId);
  });
  svg.addEventListener("pointermove", (e) => {
    if (!drag) return;
    drag.moved = true;
    movePoint(drag.shape, drag.kind, drag.i, unmapPoint(drag.side.map, at(e)));
    commitShape(drag.edge, drag.shape);
  });
  const end = () => { if (drag && drag.moved) { formChanged(); resolveSoon(0); } drag = null; };
  svg.addEventListener("pointerup", end); svg.addEventListener("pointercancel", end);
  svg.addEventListener("dblclick", (e) => {
    const hit = e.target.classList;
    if (!hit.contains("handle") && !hit.contains("hit")) return;
    const t = target(e);
    if (t.shape.kind !== "line") return;
    if (hit.contains("handle")) removePoint(t.shape, t.kind, Number(e.target.dataset.i));
    else insertPoint(t.shape, t.kind, unmapPoint(t.side.map, at(e)));
    commitShape(t.edge, t.shape); formChanged();
  });
}

// ------------------------------------------------------------------ solving
function clearResult() {
  studio.result = null; studio.pictureImage = null;
  $("picture").innerHTML = ""; $("verdict").textContent = ""; $("window-caption").textContent = "";
  $("exports").hidden = true; $("stage-empty").hidden = !!studio.painting; delete $("status").dataset.status;
}

async function solve() {
  studio.timings.click = performance.now();
  showError("");
  $("solve").disabled = true; $("cancel").disabled = false; $("progress").hidden = false;
  $("progress").removeAttribute("value");
  $("status").textContent = "solving…"; delete $("status").dataset.status;
  if (!studio.keepView) $("picture").style.opacity = .35;   // an edge editor's redraw keeps the picture as it is
  try {
    const { id } = await api("/api/solve", request());
    studio.job = id; studio.lastJob = id;
    await follow(id);
    $("status").textContent = "fetching the result…";
    const job = await api(`/api/jobs/${id}`);
    if (job.state === "done") {
      $("status").textContent = "drawing the picture…";
      await showResult(job.result);
    } else if (job.state === "cancelled") { clearResult(); $("status").textContent = `cancelled after ${job.elapsed_s.toFixed(1)} s`; }
    else { clearResult(); $("status").textContent = ""; showError(job.error); }
  } catch (e) { clearResult(); $("status").textContent = ""; showError(e.message); }
  finally {
    $("picture").style.opacity = 1;
    $("solve").disabled = false; $("cancel").disabled = true; $("progress").hidden = true; studio.job = null;
  }
}

// The solve's progress, streamed by the server (Server-Sent Events) until the job ends.
function follow(id) {
  return new Promise((resolve, reject) => {
    const events = new EventSource(`/api/jobs/${id}/events`);
    events.onmessage = (e) => {
      const job = JSON.parse(e.data);
      if (job.state === "running") showProgress(job);
      else { events.close(); resolve(job); }
    };
    events.onerror = () => { events.close(); reject(new Error("lost the connection to the studio server")); };
  });
}

// "solving… 3.2 s of 10 s · periods 12/40 boards, 2 tiled, 10 refuted, 0 undecided"; the bar shows
// the innermost task with a known total, else the time limit, else it is indeterminate.
function showProgress(job) {
  const limit = job.time_limit ? ` of ${job.time_limit} s` : "";
  const tasks = job.progress.map((t) => {
    const count = t.unit === null ? "" : t.total === null ? ` ${t.done} ${t.unit}s` : ` ${t.done}/${t.total} ${t.unit}s`;
    const eta = t.eta_s === null ? "" : `, about ${Math.ceil(t.eta_s)} s left`;
    return `${t.label}${count}${t.note ? ": " + t.note : ""}${eta}`;
  });
  const lines = [`solving… ${job.elapsed_s.toFixed(1)} s${limit}`, ...(job.announce ? [job.announce] : []), ...tasks];
  $("status").textContent = lines.join(" · ");
  const known = job.progress.filter((t) => t.total).pop();
  if (known) { $("progress").max = known.total; $("progress").value = known.done; }
  else if (job.time_limit) { $("progress").max = job.time_limit; $("progress").value = job.elapsed_s; }
  else $("progress").removeAttribute("value");
}

// A packed grid (tilesolve/studio/worker.py, packed_cells) as {rows, cols, data: typed array}.
function unpackCells(p) {
  if (!p) return null;
  const bytes = Uint8Array.from(atob(p.data), (ch) => ch.charCodeAt(0)).buffer;
  const T = { int8: Int8Array, int16: Int16Array, int32: Int32Array }[p.dtype];
  return { rows: p.rows, cols: p.cols, data: new T(bytes) };
}
studio.cellRows = () => studio.cells && Array.from({ length: studio.cells.rows },
  (_, r) => Array.from(studio.cells.data.subarray(r * studio.cells.cols, (r + 1) * studio.cells.cols)));

async function showResult(res) {
  studio.result = res;
  const pic = $("picture");
  $("stage-empty").hidden = true;
  if (res.picture && res.picture.format === "svg") { pic.innerHTML = res.picture.data; studio.pictureImage = null; }
  else if (res.picture) {
    const img = new Image(); img.alt = res.describe;
    img.src = "data:image/png;base64," + res.picture.data;
    await img.decode();
    studio.pictureImage = img; pic.replaceChildren(img);
  } else { pic.innerHTML = ""; studio.pictureImage = null; $("stage-empty").hidden = false; }
  recolourPicture();
  if (!studio.keepView) studio.stage.fit();
  studio.timings.lastSolveMs = performance.now() - studio.timings.click;
  const obj = res.objective === null ? "" : `, distance ${res.objective}`;
  const run = `${res.method}, seed ${res.seed}, ${res.time_s.toFixed(3)} s`;
  // A report (an aperiodicity check) is shown in its own words: its verdict, not a solver status.
  $("status").textContent = res.report ? `${res.report.title}: ${res.report.verdict} (by ${run})`
                                       : `${res.status} by ${run}${obj}`;
  $("status").dataset.status = res.status;
  const lines = [res.describe, ...(res.report ? ["conclusion: " + res.report.conclusion] : []),
                 ...res.verdict.map(l => "verify: " + l)];
  if (res.reason && !res.report) lines.push((res.status === "unsat" ? "why: " : "stopped: ") + res.reason);
  else if (res.reason) lines.push("undecided: " + res.reason);
  for (const n of res.notes) lines.push("note: " + n);
  for (const [k, v] of Object.entries(res.stats)) lines.push(`${k}: ${v}`);
  $("verdict").textContent = lines.join("\n");
  $("window-caption").textContent = res.window ? windowCaption(res.window) : "";
  $("export-json").href = `/api/jobs/${studio.lastJob}/solution.json`;
  for (const f of ["svg", "png"]) {
    $("export-" + f).href = `/api/jobs/${studio.lastJob}/picture.${f}`;
    $("export-" + f).hidden = !res.picture || !studio.fam.pictures.includes(f);  // the formats its family draws
  }
  $("command").textContent = res.command;
  $("exports").hidden = false;
  studio.cells = unpackCells(res.cells);
  drawGrid();
  if (studio.cells && $("brush").querySelector("option[value=solution]")) $("brush").value = "solution";
  $("seed").value = res.seed; saveState(true);
}

// The coordinates of a solution's window of the plane, from its data (model/window.py).
function windowCaption(w) {
  const top = w.y_up ? w.y0 + w.height - 1 : w.y0, bottom = w.y_up ? w.y0 : w.y0 + w.height - 1;
  return `window of the plane: x ${w.x0}..${w.x0 + w.width - 1} left to right, ` +
         `y ${top}..${bottom} top to bottom (y grows ${w.y_up ? "upwards" : "downwards"})`;
}

async function cancel() {
  if (studio.job) { try { await api(`/api/jobs/${studio.job}/cancel`, {}); } catch (e) { showError(e.message); } }
}

// ------------------------------------------------------------------ shareable state
// The page's problem lives in the address: family, values (painted grids too, while small), method,
// seed, time limit, and "go" once solved; opening the address poses (and solves) it again.
const MAX_STATE = 60000;
function saveState(solved) {
  if (!studio.fam || studio.applying) return;
  const r = request(), state = { f: r.family, v: r.values, m: r.method };
  if (r.time_limit !== undefined) state.t = r.time_limit;
  if (solved) state.go = 1;
  let text = JSON.stringify(state);
  if (text.length > MAX_STATE) {
    for (const f of studio.fam.fields) if (f.kind === "cells") delete state.v[f.name];
    text = JSON.stringify(state);
  }
  window.history.replaceState(null, "", "#" + new URLSearchParams({ s: text }).toString());
}

function readState() {
  try { const s = new URLSearchParams(location.hash.slice(1)).get("s"); return s ? JSON.parse(s) : null; }
  catch (e) { return null; }
}

// Pose a problem on the page: {family, values, method, seed, time_limit}; solve it with go.
async function applyState(st, go) {
  const fam = studio.families.find(f => f.name === st.f);
  if (!fam) { showError(`no family ${st.f} in this studio`); return; }
  studio.applying = true;
  try {
    $("family").value = fam.name; pickFamily();
    const v = st.v || {};
    for (const f of fam.fields) {
      if (!(f.name in v)) continue;
      if (f.kind === "cells") { studio.grids[f.name] = v[f.name]; continue; }
      const el = $("field-" + f.name);
      if (f.kind === "bool") el.checked = !!v[f.name]; else el.value = v[f.name] === null ? "" : v[f.name];
    }
    $("seed").value = v.seed === undefined || v.seed === null ? "" : v.seed;
    if (st.m) $("method").value = st.m;
    $("time-limit").value = st.t === undefined ? "" : st.t;
  } finally { studio.applying = false; }
  await formChanged();
  if (go) await solve();
}

// ------------------------------------------------------------------ gallery
// One-click problems from the papers; a preset names its family and is shown where the family is.
const PRESETS = [
  { label: "Dappled 64×48", f: "dappled", v: { size: "64x48", seed: 1 } },
  { label: "Wall of Fig. 22 (n = 4)", f: "board", v: { size: "48x32", max_h: 4, max_v: 4, seed: 1 } },
  { label: "Corner packing C = 2", f: "packing", v: { kind: "corner", colors: 2, seed: 1 } },
  { label: "Wang packing C = 3", f: "packing", v: { kind: "wang", colors: 3, seed: 1 } },
  { label: "Jeandel–Rao window", f: "aperiodic-window", v: { seed: 1 } },
  { label: "Jeandel–Rao report", f: "aperiodic", v: { seed: 1 } },
  { label: "Texture (corner tiles)", f: "stochastic", v: { kind: "corner", size: "96x64", seed: 3 } },
  { label: "Penrose rhombs", f: "substitution", v: { kind: "p3", seed: 1 } },
  { label: "Pentomino tiling", f: "shapes", v: { seed: 1 } },
  { label: "Isohedral IH41", f: "isohedral", v: { seed: 1 } },
  { label: "Poisson disk tiles C = 2", f: "poisson", v: { seed: 1 } },
  { label: "Stippled ramp", f: "stipple", v: { seed: 1 } },
];

function buildGallery() {
  const box = $("presets"); box.innerHTML = "";
  for (const p of PRESETS) {
    if (!studio.families.some(f => f.name === p.f)) continue;
    const b = document.createElement("button"); b.type = "button"; b.textContent = p.label;
    b.dataset.preset = p.label;
    b.addEventListener("click", () => applyState(p, true));
    box.appendChild(b);
  }
}

// ------------------------------------------------------------------ infinite view
// The view of a corner tiling has a second look, "Texture" (the box shown for the families whose
// view has it, `texture` in GET /api/families): the GPU path's corner-tile texture of the same
// tiles, from the server's tiles or drawn here by WebGL2 as the wall is.
// A canvas drawn from square tiles of the plane, VIEW_N << level cells each (coarser levels when
// zoomed out); a tile not yet loaded shows the best loaded level over it, or a hatch, and the
// loading sign counts what is on its way. Every tile is drawn at the same scale, edges rounded
// to whole pixels, so no band differs and no gap opens.
const view = studio.view = { x: 0, y: 0, zoom: 1, cache: new Map(), inflight: 0, values: "", gen: 0,
                             missing: 0, rects: [], failed: 0, palette: "", look: "picture" };
const MAX_INFLIGHT = 4;

function resetView() {
  // nothing of the new view is drawn until the next frame: no tile wanted yet (the old list
  // would say "all drawn" meanwhile, and a pump would fetch tiles of the old view)
  view.cache.clear(); view.gen++; view.inflight = 0; view.failed = 0; view.wanted = []; view.missing = 0;
  if (!studio.fam || !studio.fam.view) return;
  const values = Object.fromEntries(Object.entries(formValues()).filter(
    ([k]) => !studio.fam.fields.some(f => f.name === k && f.kind === "cells")));
  values.seed = values.seed === undefined ? 0 : values.seed;   // one seed for every window
  view.values = encodeURIComponent(JSON.stringify(values));
  view.palette = viewPalette();
  $("view-texture-label").hidden = !studio.fam.texture;
  view.look = studio.fam.texture && $("view-texture").checked ? "texture" : "picture";
  if (window.studioWebGL) studioWebGL.configure(studio.fam.name, view.values, view.palette, view.look).then(() => requestAnimationFrame(drawView));
  requestAnimationFrame(drawView);
}

function levelFor(zoom) {
  const want = Math.ceil(Math.log2(160 / (VIEW_N * CELL * zoom)));
  return Math.max(0, Math.min(MAX_LEVEL, want));
}

function tileAt(level, i, j) {
  const key = `${level}:${i}:${j}`;
  let t = view.cache.get(key);
  if (!t) { t = { level, i, j, key, state: "wanted", tries: 0, img: null, used: 0 }; view.cache.set(key, t); }
  return t;
}

function fetchTile(t) {
  const n = VIEW_N << t.level, gen = view.gen, img = new Image();
  t.state = "loading"; view.inflight++;
  img.onload = () => { if (gen !== view.gen) return; t.img = img; t.state = "ready"; view.inflight--; pump(); drawView(); };
  img.onerror = () => {
    if (gen !== view.gen) return;
    view.inflight--; t.tries++;
    t.state = t.tries < 3 ? "wanted" : "failed";
    if (t.state === "failed") { view.failed++; $("view-info").textContent = "a view tile failed: check the form"; }
    setTimeout(() => { pump(); drawView(); }, 300 * t.tries);
  };
  img.src = `/api/view/${studio.fam.name}.png?x=${t.i * n}&y=${-(t.j + 1) * n}&n=${n}&values=${view.values}` +
            (view.palette ? `&palette=${view.palette}` : "") + (view.look === "texture" ? "&look=texture" : "");
}

function pump() {
  for (const t of view.wanted || []) {
    if (view.inflight >= MAX_INFLIGHT) break;
    if (t.state === "wanted") fetchTile(t);
  }
}

function hatch(ctx) {
  if (!view.pattern) {
    const p = document.createElement("canvas"); p.width = p.height = 12;
    const c = p.getContext("2d"); c.fillStyle = "#eef0f3"; c.fillRect(0, 0, 12, 12);
    c.strokeStyle = "#cfd5dd"; c.lineWidth = 2; c.beginPath(); c.moveTo(0, 12); c.lineTo(12, 0); c.stroke();
    view.pattern = ctx.createPattern(p, "repeat");
  }
  return view.pattern;
}

function drawView() {
  if (!studio.fam || !studio.fam.view || $("view-panel").hidden) return;
  const cv = $("view-canvas"), dpr = window.devicePixelRatio || 1;
  const w = cv.clientWidth, h = cv.clientHeight;
  if (cv.width !== Math.round(w * dpr) || cv.height !== Math.round(h * dpr)) { cv.width = Math.round(w * dpr); cv.height = Math.round(h * dpr); }
  const ctx = cv.getContext("2d");
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  ctx.clearRect(0, 0, w, h);
  if (window.studioWebGL && studioWebGL.draw(view, CELL, w, h, dpr)) {   // drawn here by the GPU path's shaders
    view.wanted = []; view.missing = 0; $("view-loading").hidden = true;
    $("view-info").textContent = `cells x ${Math.floor(view.x / CELL)}, y ${-Math.floor(view.y / CELL)}, ` +
      `zoom ${view.zoom.toFixed(2)}, drawn by WebGL2`;
    return;
  }
  const level = levelFor(view.zoom), n = VIEW_N << level, T = n * CELL, z = view.zoom;
  const i0 = Math.floor(view.x / T), j0 = Math.floor(view.y / T);
  const i1 = Math.floor((view.x + w / z) / T), j1 = Math.floor((view.y + h / z) / T);
  const sx = (bx) => Math.round((bx - view.x) * z), sy = (by) => Math.round((by - view.y) * z);
  const wanted = []; let missing = 0; const rects = [], stamp = performance.now();
  for (let j = j0; j <= j1; j++) for (let i = i0; i <= i1; i++) {
    const t = tileAt(level, i, j); t.used = stamp; wanted.push(t);
    const x0 = sx(i * T), x1 = sx((i + 1) * T), y0 = sy(j * T), y1 = sy((j + 1) * T);
    rects.push([x0, y0, x1 - x0, y1 - y0]);
    if (t.state === "ready") { ctx.imageSmoothingEnabled = (x1 - x0) < t.img.naturalWidth; ctx.drawImage(t.img, x0, y0, x1 - x0, y1 - y0); continue; }
    missing++;
    ctx.fillStyle = hatch(ctx); ctx.fillRect(x0, y0, x1 - x0, y1 - y0);
    // the best loaded stand-in: the coarser tile that holds this one, or the finer ones inside it
    for (let L = level + 1; L <= MAX_LEVEL; L++) {
      const k = 1 << (L - level), p = view.cache.get(`${L}:${Math.floor(i / k)}:${Math.floor(j / k)}`);
      if (p && p.state === "ready") {
        const s = p.img.naturalWidth / k, ox = ((i % k) + k) % k, oy = ((j % k) + k) % k;
        ctx.imageSmoothingEnabled = false;
        ctx.drawImage(p.img, ox * s, oy * s, s, s, x0, y0, x1 - x0, y1 - y0); break;
      }
    }
    if (level > 0) for (let a = 0; a < 2; a++) for (let b = 0; b < 2; b++) {
      const c = view.cache.get(`${level - 1}:${2 * i + a}:${2 * j + b}`);
      if (c && c.state === "ready") {
        const cx0 = sx((2 * i + a) * T / 2), cy0 = sy((2 * j + b) * T / 2);
        ctx.drawImage(c.img, cx0, cy0, sx((2 * i + a + 1) * T / 2) - cx0, sy((2 * j + b + 1) * T / 2) - cy0);
      }
    }
  }
  view.wanted = wanted; view.missing = missing; view.rects = rects; view.level = level;
  pump();
  $("view-loading").hidden = missing === 0;
  $("view-loading").textContent = `loading ${missing} tile${missing === 1 ? "" : "s"}…`;
  if (view.cache.size > 400) {         // forget the tiles least recently drawn
    const old = [...view.cache.values()].filter(t => t.used !== stamp && t.state !== "loading").sort((a, b) => a.used - b.used);
    for (const t of old.slice(0, view.cache.size - 300)) view.cache.delete(t.key);
  }
  if (!view.failed) $("view-info").textContent =
    `cells x ${Math.floor(view.x / CELL)}, y ${-Math.floor(view.y / CELL)}, zoom ${view.zoom.toFixed(2)}, ` +
    `${n}×${n}-cell tiles`;
}

function setupView() {
  const vp = $("viewport");
  if (window.studioWebGL) studioWebGL.setup(resetView);
  $("view-texture").addEventListener("change", () => {
    // further out than one texel a pixel the texture's mortar lines (a texel or two) fall between pixels and
    // its bricks read as red noise: ticking the box zooms in to that scale, about the view's centre
    if ($("view-texture").checked && view.zoom < TEXTURE_ZOOM) {
      const r = vp.getBoundingClientRect(), mx = r.width / 2, my = r.height / 2;
      view.x += mx / view.zoom - mx / TEXTURE_ZOOM; view.y += my / view.zoom - my / TEXTURE_ZOOM; view.zoom = TEXTURE_ZOOM;
    }
    resetView();
  });
  let drag = null, pending = false;
  const redraw = () => { if (!pending) { pending = true; requestAnimationFrame(() => { pending = false; drawView(); }); } };
  vp.addEventListener("pointerdown", (e) => { drag = { x: e.clientX, y: e.clientY }; vp.style.cursor = "grabbing"; vp.setPointerCapture(e.pointerId); });
  vp.addEventListener("pointermove", (e) => {
    if (!drag) return;
    view.x -= (e.clientX - drag.x) / view.zoom; view.y -= (e.clientY - drag.y) / view.zoom;
    drag = { x: e.clientX, y: e.clientY }; redraw();
  });
  const end = () => { drag = null; vp.style.cursor = "grab"; };
  vp.addEventListener("pointerup", end); vp.addEventListener("pointercancel", end);
  vp.addEventListener("wheel", (e) => {
    e.preventDefault();
    const r = vp.getBoundingClientRect(), mx = e.clientX - r.left, my = e.clientY - r.top;
    const z = Math.min(8, Math.max(0.125, view.zoom * Math.exp(-e.deltaY / 500)));
    view.x += mx / view.zoom - mx / z; view.y += my / view.zoom - my / z; view.zoom = z; redraw();
  }, { passive: false });
  window.addEventListener("resize", redraw);
}

// Pan for `ms` milliseconds, one step per animation frame; the redraw rate in frames per second.
studio.measurePan = (ms, dx = 6) => new Promise((done) => {
  let frames = 0; const t0 = performance.now();
  const step = (t) => {
    view.x += dx; drawView(); frames++;
    if (t - t0 < ms) requestAnimationFrame(step); else done(frames * 1000 / (performance.now() - t0));
  };
  requestAnimationFrame(step);
});

// ------------------------------------------------------------------ start
function pickFamily() {
  studio.fam = studio.families.find(f => f.name === $("family").value);
  $("family-title").textContent = studio.fam.title;
  clearResult(); $("status").textContent = ""; $("describe").textContent = "";
  buildForm();
}

function shortcuts(e) {
  const mod = e.ctrlKey || e.metaKey, typing = /^(INPUT|SELECT|TEXTAREA)$/.test(e.target.tagName);
  if (mod && e.key === "Enter") { e.preventDefault(); if (!$("solve").disabled) solve(); }
  else if (e.key === "Escape" && studio.job) cancel();
  else if (mod && !typing && (e.key === "z" || e.key === "Z")) { e.preventDefault(); (e.shiftKey ? redo : undo)(); }
  else if (mod && !typing && e.key === "y") { e.preventDefault(); redo(); }
  else if (!mod && !e.altKey && !typing && (e.key === "p" || e.key === "P") && !$("editor").hidden) setPaintMode(!studio.painting);
}

async function start() {
  const { families, palette } = await api("/api/families");
  studio.palette = palette;
  // friendly families first: the pictures a newcomer reads at once
  const order = ["dappled", "board", "stochastic", "isohedral", "substitution", "shapes", "packing"];
  const rank = (f) => { const k = order.indexOf(f.name); return k < 0 ? order.length : k; };
  studio.families = families.slice().sort((a, b) => rank(a) - rank(b));
  for (const f of studio.families) $("family").add(new Option(f.name, f.name));
  for (const name of Object.keys(PRESET_PALETTES)) $("palette-preset").add(new Option(name, name));
  $("palette-preset").addEventListener("change", () => setPalette(PRESET_PALETTES[$("palette-preset").value]));
  setPalette(null);
  $("family").addEventListener("change", () => { pickFamily(); formChanged(); });
  $("method").addEventListener("change", formChanged);
  $("seed").addEventListener("change", formChanged);
  $("time-limit").addEventListener("change", formChanged);
  $("solve").addEventListener("click", solve);
  $("cancel").addEventListener("click", cancel);
  $("copy-command").addEventListener("click", async () => {
    try { await navigator.clipboard.writeText($("command").textContent); $("copy-command").textContent = "Copied"; }
    catch (e) { /* the text is shown */ }
    setTimeout(() => { $("copy-command").textContent = "Copy as CLI command"; }, 1500);
  });
  for (const f of ["svg", "png"]) $("export-" + f).addEventListener("click", (e) => exportPicture(f, e));
  document.addEventListener("keydown", shortcuts);
  window.addEventListener("hashchange", () => { const st = readState(); if (st) applyState(st, !!st.go); });
  studio.stage = new PanZoom($("stage"), $("picture"), { painter });
  setupEditor(); setupEdgeEditor(); setupView(); buildGallery();
  const shared = readState();
  if (shared) await applyState(shared, !!shared.go);
  else { pickFamily(); await formChanged(); await solve(); }   // pictures first: the page opens on one
  document.body.dataset.ready = "1";
}
start().catch((e) => showError(e.message));
