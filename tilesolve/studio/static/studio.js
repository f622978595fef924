// tilesolve studio page: every form is built from the family's fields (GET /api/families),
// no family is special-cased here.
"use strict";
const $ = (id) => document.getElementById(id);
const studio = window.studio = { timings: {}, families: [], fam: null, extents: {}, grids: {}, cells: null,
                                 job: null, result: null };
const PALETTE = ["#f4f1de", "#e07a5f", "#3d405b", "#81b29a", "#f2cc8f", "#6d597a", "#b56576", "#355070",
                 "#eaac8b", "#43aa8b"];
const VIEW_N = 32, CELL = 8;           // view tile: VIEW_N x VIEW_N cells, CELL css px per cell at zoom 1

async function api(path, body) {
  const opts = body === undefined ? {} : { method: "POST", headers: { "Content-Type": "application/json" },
                                           body: JSON.stringify(body) };
  const r = await fetch(path, opts);
  const doc = await r.json();
  if (!r.ok) throw new Error(doc.error || r.statusText);
  return doc;
}

function showError(msg) { $("error").textContent = msg ? "error: " + msg : ""; }

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
      if (f.low !== null && f.kind !== "text") input.min = f.low;
      if (f.high !== null && f.kind !== "text" && f.kind !== "size") input.max = f.high;
      input.value = f.default === null ? "" : f.default;
      input.placeholder = f.default === null ? "none" : "";
    }
    input.name = f.name; input.id = "field-" + f.name; input.dataset.kind = f.kind;
    input.addEventListener("change", formChanged);
    label.appendChild(input);
    form.appendChild(label);
  }
  $("method").innerHTML = "";
  for (const m of studio.fam.methods) {
    const o = new Option(m, m); o.title = studio.fam.route_help[m] || ""; $("method").add(o);
  }
  const gf = $("grid-field"); gf.innerHTML = "";
  for (const f of studio.fam.fields) if (f.kind === "cells") gf.add(new Option(f.label, f.name));
  studio.grids = {}; studio.cells = null;
  $("editor").hidden = gf.options.length === 0;
  $("view-panel").hidden = !studio.fam.view;
  formChanged();
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

let checkSeq = 0;
async function formChanged() {
  const seq = ++checkSeq;
  resetView();
  try {
    const doc = await api("/api/check", request());
    if (seq !== checkSeq) return;
    showError("");
    $("describe").textContent = doc.describe;
    studio.extents = doc.cells;
    for (const [name, [rows, cols]] of Object.entries(doc.cells)) {
      const g = studio.grids[name];
      if (g && (g.length !== rows || g[0].length !== cols)) delete studio.grids[name];
    }
    if (studio.cells && (!doc.cells[$("grid-field").value] ||
        studio.cells.length !== doc.cells[$("grid-field").value][0])) studio.cells = null;
    drawGrid();
  } catch (e) { if (seq === checkSeq) showError(e.message); }
}

// ------------------------------------------------------------------ editing grids
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

function cellPx(rows, cols) { return Math.max(2, Math.min(24, Math.floor(384 / Math.max(rows, cols)))); }

function drawGrid() {
  fillBrushes();
  const name = $("grid-field").value, ext = studio.extents[name], cv = $("grid");
  if (!ext) { cv.width = cv.height = 0; return; }
  const [rows, cols] = ext, px = cellPx(rows, cols), g = studio.grids[name], ctx = cv.getContext("2d");
  cv.width = cols * px; cv.height = rows * px;
  for (let r = 0; r < rows; r++) for (let c = 0; c < cols; c++) {
    const v = g ? g[r][c] : -1;
    if (v >= 0) { ctx.globalAlpha = 1; ctx.fillStyle = PALETTE[v % PALETTE.length]; }
    else if (studio.cells && studio.cells[r] && studio.cells[r][c] !== undefined) {
      ctx.globalAlpha = 0.35; ctx.fillStyle = PALETTE[studio.cells[r][c] % PALETTE.length];
    } else { ctx.globalAlpha = 1; ctx.fillStyle = "#fff"; }
    ctx.fillRect(c * px, r * px, px, px);
    if (v >= 0 && px >= 6) { ctx.strokeStyle = "#000"; ctx.globalAlpha = 1; ctx.strokeRect(c * px + .5, r * px + .5, px - 1, px - 1); }
    const shown = v >= 0 ? v : (studio.cells && studio.cells[r] ? studio.cells[r][c] : undefined);
    if (shown !== undefined && px >= 16 && ext[3] > 9) {   // many values: write the number
      ctx.globalAlpha = v >= 0 ? 1 : 0.5; ctx.fillStyle = "#000"; ctx.font = `${Math.floor(px / 2.2)}px sans-serif`;
      ctx.textAlign = "center"; ctx.textBaseline = "middle"; ctx.fillText(String(shown), (c + .5) * px, (r + .5) * px);
    }
  }
  ctx.globalAlpha = 1;
}

function paintAt(ev) {
  const name = $("grid-field").value, ext = studio.extents[name];
  if (!ext) return;
  const [rows, cols] = ext, px = cellPx(rows, cols), rect = $("grid").getBoundingClientRect();
  const c = Math.floor((ev.clientX - rect.left) / px), r = Math.floor((ev.clientY - rect.top) / px);
  if (r < 0 || c < 0 || r >= rows || c >= cols) return;
  if (!studio.grids[name]) studio.grids[name] = Array.from({ length: rows }, () => new Array(cols).fill(-1));
  const b = $("brush").value;
  studio.grids[name][r][c] = b === "solution" ? (studio.cells ? studio.cells[r][c] : -1) : Number(b);
  drawGrid();
}

function setupEditor() {
  let down = false;
  $("grid").addEventListener("mousedown", (e) => { down = true; paintAt(e); });
  $("grid").addEventListener("mousemove", (e) => { if (down) paintAt(e); });
  window.addEventListener("mouseup", () => { if (down) { down = false; formChanged(); } });
  $("grid-field").addEventListener("change", drawGrid);
  $("grid-clear").addEventListener("click", () => { delete studio.grids[$("grid-field").value]; formChanged(); });
  $("grid-upload").addEventListener("change", async (e) => {
    const file = e.target.files[0], name = $("grid-field").value, ext = studio.extents[name];
    if (!file || !ext) return;
    const [rows, cols, lo, hi] = ext, img = await createImageBitmap(file);
    const cv = document.createElement("canvas"); cv.width = cols; cv.height = rows;
    const ctx = cv.getContext("2d"); ctx.drawImage(img, 0, 0, cols, rows);
    const px = ctx.getImageData(0, 0, cols, rows).data, levels = Math.min(hi - lo + 1, 10);
    studio.grids[name] = Array.from({ length: rows }, (_, r) => Array.from({ length: cols }, (_, c) => {
      const i = 4 * (r * cols + c), y = (0.299 * px[i] + 0.587 * px[i + 1] + 0.114 * px[i + 2]) / 256;
      return lo + Math.min(levels - 1, Math.floor(y * levels));
    }));
    e.target.value = "";
    formChanged();
  });
}

// ------------------------------------------------------------------ solving
async function solve() {
  studio.timings.click = performance.now();
  showError(""); $("verdict").textContent = ""; $("exports").hidden = true;
  $("solve").disabled = true; $("cancel").disabled = false; $("progress").hidden = false;
  $("status").textContent = "solving…";
  try {
    const { id } = await api("/api/solve", request());
    studio.job = id; studio.lastJob = id;
    await follow(id);
    const job = await api(`/api/jobs/${id}`);
    if (job.state === "done") showResult(job.result);
    else if (job.state === "cancelled") $("status").textContent = `cancelled after ${job.elapsed_s.toFixed(1)} s`;
    else { $("status").textContent = ""; showError(job.error); }
  } catch (e) { $("status").textContent = ""; showError(e.message); }
  finally { $("solve").disabled = false; $("cancel").disabled = true; $("progress").hidden = true; studio.job = null; }
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

function showResult(res) {
  studio.result = res;
  const pic = $("picture"); pic.innerHTML = "";
  const shown = () => { studio.timings.lastSolveMs = performance.now() - studio.timings.click; };
  if (res.picture && res.picture.format === "svg") { pic.innerHTML = res.picture.data; shown(); }
  else if (res.picture) {
    const img = new Image(); img.onload = shown; img.alt = res.describe;
    img.src = "data:image/png;base64," + res.picture.data; pic.appendChild(img);
  } else shown();
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
  studio.cells = res.cells;
  drawGrid();
  if (res.cells && $("brush").querySelector("option[value=solution]")) $("brush").value = "solution";
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

// ------------------------------------------------------------------ infinite view
const view = studio.view = { x: 0, y: 0, zoom: 1, tiles: new Map(), range: "", values: "" };

function resetView() {
  view.tiles.clear(); $("tiles").innerHTML = ""; view.range = "";
  if (!studio.fam || !studio.fam.view) return;
  const values = Object.fromEntries(Object.entries(formValues()).filter(
    ([k]) => !studio.fam.fields.some(f => f.name === k && f.kind === "cells")));
  values.seed = values.seed === undefined ? 0 : values.seed;   // one seed for every window
  view.values = encodeURIComponent(JSON.stringify(values));
  requestAnimationFrame(drawView);
}

function drawView() {
  if (!studio.fam || !studio.fam.view) return;
  const vp = $("viewport"), w = vp.clientWidth, h = vp.clientHeight, T = VIEW_N * CELL;
  $("tiles").style.transform = `scale(${view.zoom}) translate(${-view.x}px, ${-view.y}px)`;
  const i0 = Math.floor(view.x / T), j0 = Math.floor(view.y / T);
  const i1 = Math.floor((view.x + w / view.zoom) / T), j1 = Math.floor((view.y + h / view.zoom) / T);
  if (i1 - i0 > 24 || j1 - j0 > 24) return;           // zoomed out too far: keep what is shown
  const range = `${i0},${j0},${i1},${j1}`;
  if (range === view.range) return;                   // the same tiles: the transform was enough
  view.range = range;
  for (let i = i0; i <= i1; i++) for (let j = j0; j <= j1; j++) {
    const key = i + "," + j;
    if (view.tiles.has(key)) continue;
    const img = new Image(T, T);
    img.style.left = i * T + "px"; img.style.top = j * T + "px"; img.style.width = img.style.height = T + "px";
    img.onerror = () => { $("view-info").textContent = "a view tile failed: check the form"; };
    img.src = `/api/view/${studio.fam.name}.png?x=${i * VIEW_N}&y=${-(j + 1) * VIEW_N}&n=${VIEW_N}` +
              `&values=${view.values}`;
    $("tiles").appendChild(img); view.tiles.set(key, img);
  }
  if (view.tiles.size > 600) {                          // forget tiles far from the window
    for (const [key, img] of view.tiles) {
      const [i, j] = key.split(",").map(Number);
      if (i < i0 - 4 || i > i1 + 4 || j < j0 - 4 || j > j1 + 4) { img.remove(); view.tiles.delete(key); }
    }
  }
  $("view-info").textContent = `cells x ${Math.floor(view.x / CELL)}, y ${-Math.floor(view.y / CELL)}, zoom ${view.zoom.toFixed(2)}`;
}

function setupView() {
  const vp = $("viewport");
  let drag = null, pending = false;
  const redraw = () => { if (!pending) { pending = true; requestAnimationFrame(() => { pending = false; drawView(); }); } };
  vp.addEventListener("mousedown", (e) => { drag = { x: e.clientX, y: e.clientY }; vp.style.cursor = "grabbing"; });
  window.addEventListener("mousemove", (e) => {
    if (!drag) return;
    view.x -= (e.clientX - drag.x) / view.zoom; view.y -= (e.clientY - drag.y) / view.zoom;
    drag = { x: e.clientX, y: e.clientY }; redraw();
  });
  window.addEventListener("mouseup", () => { drag = null; vp.style.cursor = "grab"; });
  vp.addEventListener("wheel", (e) => {
    e.preventDefault();
    const r = vp.getBoundingClientRect(), mx = e.clientX - r.left, my = e.clientY - r.top;
    const z = Math.min(8, Math.max(0.125, view.zoom * Math.exp(-e.deltaY / 500)));
    view.x += mx / view.zoom - mx / z; view.y += my / view.zoom - my / z; view.zoom = z; redraw();
  }, { passive: false });
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
async function start() {
  const { families } = await api("/api/families");
  studio.families = families;
  for (const f of families) $("family").add(new Option(f.name, f.name));
  const pick = () => {
    studio.fam = families.find(f => f.name === $("family").value);
    $("family-title").textContent = studio.fam.title;
    $("picture").innerHTML = ""; $("verdict").textContent = ""; $("status").textContent = "";
    $("exports").hidden = true; studio.result = null;
    buildForm();
  };
  $("family").addEventListener("change", pick);
  $("method").addEventListener("change", formChanged);
  $("seed").addEventListener("change", formChanged);
  $("solve").addEventListener("click", solve);
  $("cancel").addEventListener("click", cancel);
  $("copy-command").addEventListener("click", async () => {
    try { await navigator.clipboard.writeText($("command").textContent); } catch (e) { /* the text is shown */ }
  });
  setupEditor(); setupView();
  pick();
  document.body.dataset.ready = "1";
}
start().catch((e) => showError(e.message));
