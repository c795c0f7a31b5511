"use strict";
// The live microscope's page. It asks the server (`petroscope serve`) for a view's five stage harmonics and
// composes the picture at the stage angle on every frame: I(φ) = c0 + c1 cos 2φ + s1 sin 2φ + c2 cos 4φ +
// s2 sin 4φ per linear colour channel, at the point the stage has turned under each pixel (docs/browser.md;
// the library's compose_at_stage in include/petroscope/api/stage_harmonics.hpp is the reference).

const $ = (id) => document.getElementById(id);
const HARMONICS_MAGIC = 0x31485350;  // "PSH1"
const CHANNELS = 15;                  // 5 harmonics × linear sRGB
const CACHE_LIMIT = 12;               // views kept (a 512² view is 15.7 MB)
const PREVIEW_FIGURE_PX = 128;        // a conoscopic figure's first, quick picture

const state = { stageDeg: 0, pick: null, view: null, viewKey: "", dirty: true, numbers: null };
const stats = { frames: 0, composeMs: [], views: [] };  // views: each shown, its time and whether it was held
window.petroscope = { state, stats, ready: false, prefetching: false };  // what the browser tests read

// ---- the view's query ------------------------------------------------------------------------------

function specimenParams() {
  const params = new URLSearchParams();
  if (document.querySelector('input[name="specimen"]:checked').value === "section") {
    params.set("section", $("section").value);
    if ($("section").value === "random") params.set("seed", $("seed").value || "1");
    if ($("section-thickness").value !== "") params.set("thickness_um", $("section-thickness").value);
    if (state.pick) { params.set("x", state.pick.x); params.set("y", state.pick.y); }
  } else {
    params.set("mineral", $("mineral").value);
    if ($("euler").value.trim() !== "") {
      params.set("euler", $("euler").value.trim());
    } else {
      params.set("cut", $("cut").value);
      params.set("tilt_deg", $("tilt").value || "0");
      params.set("azimuth_deg", $("azimuth").value || "0");
    }
    params.set("thickness_um", $("crystal-thickness").value || "30");
  }
  params.set("handedness", $("handedness").value);
  if (document.querySelector('input[name="light"]:checked').value === "mono") params.set("wavelength_nm", $("wavelength").value);
  return params;
}

/// The query of a view; `variant` overrides the analyzer or the plate (for prefetching).
function viewQuery(variant = {}, sizePx = 512) {
  const params = specimenParams();
  const bertrand = $("bertrand").checked;
  params.set("optics", bertrand ? "conoscope" : "orthoscope");
  if (!bertrand) {
    params.delete("x"); params.delete("y");  // the whole section: the pick matters to the Bertrand view only
    if ($("condenser").value !== "0") params.set("condenser_na", $("condenser").value);
  } else {
    params.set("size_px", sizePx);
  }
  params.set("polarizer", $("polarizer").checked ? "in" : "out");
  const analyzerIn = variant.analyzer ?? $("analyzer").checked;
  params.set("analyzer", analyzerIn ? "in" : "out");
  const plate = variant.plate ?? $("plate").value;
  params.set("plate", plate);
  if (plate === "wedge") params.set("wedge_position", $("wedge").value);
  if (document.querySelector('input[name="light"]:checked').value === "white") params.set("illuminant", $("illuminant").value);
  return params.toString();
}

// ---- fetching and caching views ---------------------------------------------------------------------

const cache = new Map();  // query → Promise of a decoded view
let foregroundPending = 0;

function decodeHarmonics(buffer) {
  const header = new Uint32Array(buffer, 0, 4);
  if (header[0] !== HARMONICS_MAGIC) throw new Error("the server's view is not in the expected format");
  const width = header[1], height = header[2];
  return {
    width, height, bilinear: header[3] === 1,
    outside: new Float32Array(buffer, 16, CHANNELS),
    coefficients: new Float32Array(buffer, 16 + 4 * CHANNELS, width * height * CHANNELS),
  };
}

async function fetchView(query) {
  const response = await fetch("api/view?" + query);
  if (!response.ok) throw new Error((await response.json()).error);
  return decodeHarmonics(await response.arrayBuffer());
}

/// The view for `query`, fetched once; the least recently used views make room for new ones.
function view(query) {
  let promise = cache.get(query);
  if (promise === undefined) {
    promise = fetchView(query);
    promise.catch(() => cache.delete(query));
  }
  cache.delete(query);
  cache.set(query, promise);  // the Map's order is the order of use
  while (cache.size > CACHE_LIMIT) cache.delete(cache.keys().next().value);
  return promise;
}

/// Shows the current view: from the cache at once, else (a figure) a quick small one first, then the full one.
async function refresh() {
  const started = performance.now();
  const query = viewQuery();
  const cached = cache.has(query);
  state.viewKey = query;
  window.petroscope.ready = false;
  foregroundPending++;
  setStatus("computing…");
  try {
    if (!cache.has(query) && $("bertrand").checked) {
      const preview = await view(viewQuery({}, PREVIEW_FIGURE_PX));
      if (state.viewKey === query) show(preview);
    }
    const full = await view(query);
    if (state.viewKey !== query) return;
    show(full);
    stats.views.push({ ms: performance.now() - started, cached });
    setStatus("ready");
    window.petroscope.ready = true;
  } catch (error) {
    if (state.viewKey === query) setStatus("error: " + error.message);
  } finally {
    foregroundPending--;
  }
  prefetchVariants();
}

function show(decoded) {
  state.view = decoded;
  state.dirty = true;
}

/// While nothing else is asked, the views one click away from the current one: the analyzer toggled, the
/// other plates. The current view is looked at again after every fetch, so a change meanwhile is followed.
let prefetching = false;
async function prefetchVariants() {
  if (prefetching) return;
  prefetching = window.petroscope.prefetching = true;
  for (;;) {
    if (foregroundPending > 0) break;  // the view being fetched calls this again once shown
    const variants = [{ analyzer: !$("analyzer").checked }, { plate: "gypsum" }, { plate: "mica" }, { plate: "none" }];
    const missing = variants.map((variant) => viewQuery(variant)).find((query) => !cache.has(query));
    if (missing === undefined) break;
    try { await view(missing); } catch (error) { break; }
  }
  prefetching = window.petroscope.prefetching = false;
}

// ---- composing a frame ---------------------------------------------------------------------------------

// Linear value → 8-bit sRGB code (IEC 61966-2-1), tabulated finely enough to be within one code.
const LUT_SIZE = 16384;
const srgbCode = new Uint8ClampedArray(LUT_SIZE + 1);
for (let k = 0; k <= LUT_SIZE; k++) {
  const v = k / LUT_SIZE;
  srgbCode[k] = Math.round(255 * (v <= 0.0031308 ? 12.92 * v : 1.055 * Math.pow(v, 1 / 2.4) - 0.055));
}
function encode(linear) { return srgbCode[Math.round(Math.min(Math.max(linear, 0), 1) * LUT_SIZE)]; }

let linearFrame = new Float32Array(0);

/// The colour of every source pixel at stage φ (linear sRGB), and of the field outside it.
function harmonicsAt(decoded, phiRad) {
  const basis = [1, Math.cos(2 * phiRad), Math.sin(2 * phiRad), Math.cos(4 * phiRad), Math.sin(4 * phiRad)];
  const count = decoded.width * decoded.height;
  if (linearFrame.length !== count * 3) linearFrame = new Float32Array(count * 3);
  const c = decoded.coefficients;
  for (let p = 0, q = 0, o = 0; p < count; p++, q += CHANNELS, o += 3) {
    for (let ch = 0; ch < 3; ch++) {
      linearFrame[o + ch] = c[q + ch] + basis[1] * c[q + 3 + ch] + basis[2] * c[q + 6 + ch] + basis[3] * c[q + 9 + ch] + basis[4] * c[q + 12 + ch];
    }
  }
  const outside = [0, 0, 0];
  for (let j = 0; j < 5; j++) for (let ch = 0; ch < 3; ch++) outside[ch] += basis[j] * decoded.outside[3 * j + ch];
  return outside;
}

/// The picture at stage φ into `pixels` (RGBA, width × height): pixel (column, row) shows the unturned
/// picture at R(−φ)·(x, y), x to the E and y to the N from the centre, as compose_at_stage does.
function compose(decoded, stageDeg, pixels) {
  const phi = stageDeg * Math.PI / 180;
  const outside = harmonicsAt(decoded, phi);
  const { width, height, bilinear } = decoded;
  const cos = Math.cos(phi), sin = Math.sin(phi), cx = width / 2, cy = height / 2;
  const sample = (col, row, ch) => (col < 0 || row < 0 || col >= width || row >= height) ? outside[ch] : linearFrame[(row * width + col) * 3 + ch];
  for (let row = 0, out = 0; row < height; row++) {
    const y = cy - (row + 0.5);
    for (let column = 0; column < width; column++, out += 4) {
      const x = column + 0.5 - cx;
      const sourceColumn = cos * x + sin * y + cx, sourceRow = cy - (-sin * x + cos * y);
      for (let ch = 0; ch < 3; ch++) {
        let value;
        if (!bilinear) {
          value = sample(Math.floor(sourceColumn), Math.floor(sourceRow), ch);
        } else {
          const u = sourceColumn - 0.5, v = sourceRow - 0.5, x0 = Math.floor(u), y0 = Math.floor(v), fx = u - x0, fy = v - y0;
          value = (1 - fx) * (1 - fy) * sample(x0, y0, ch) + fx * (1 - fy) * sample(x0 + 1, y0, ch) +
                  (1 - fx) * fy * sample(x0, y0 + 1, ch) + fx * fy * sample(x0 + 1, y0 + 1, ch);
        }
        pixels[out + ch] = encode(value);
      }
      pixels[out + 3] = 255;
    }
  }
}

const canvas = $("view");
const context = canvas.getContext("2d", { willReadFrequently: true });
const scratch = document.createElement("canvas");
const scratchContext = scratch.getContext("2d");

function frame() {
  if (state.dirty && state.view) {
    const started = performance.now();
    const decoded = state.view;
    if (scratch.width !== decoded.width || scratch.height !== decoded.height) { scratch.width = decoded.width; scratch.height = decoded.height; }
    const image = scratchContext.createImageData(decoded.width, decoded.height);
    compose(decoded, state.stageDeg, image.data);
    scratchContext.putImageData(image, 0, 0);
    context.imageSmoothingEnabled = decoded.bilinear;
    context.drawImage(scratch, 0, 0, canvas.width, canvas.height);
    stats.frames++;
    stats.composeMs.push(performance.now() - started);
    if (stats.composeMs.length > 600) stats.composeMs.shift();
    state.dirty = false;
  }
  requestAnimationFrame(frame);
}

// ---- the stage ---------------------------------------------------------------------------------------

function setStage(degrees) {
  state.stageDeg = ((degrees % 360) + 360) % 360;
  $("stage").value = state.stageDeg.toFixed(1);
  $("stage-readout").textContent = "stage " + state.stageDeg.toFixed(1) + "°";
  state.dirty = true;
  showNumbers();
}

/// The pointer's angle about the field's centre, counter-clockwise from E as the observer sees it.
function pointerAngleDeg(event) {
  const box = canvas.getBoundingClientRect();
  return Math.atan2(box.top + box.height / 2 - event.clientY, event.clientX - box.left - box.width / 2) * 180 / Math.PI;
}

let drag = null;
canvas.addEventListener("pointerdown", (event) => {
  drag = { startAngle: pointerAngleDeg(event), startStage: state.stageDeg, x: event.clientX, y: event.clientY, moved: false };
  canvas.setPointerCapture(event.pointerId);
});
canvas.addEventListener("pointermove", (event) => {
  if (!drag) return;
  if (Math.hypot(event.clientX - drag.x, event.clientY - drag.y) > 3) drag.moved = true;
  if (drag.moved) setStage(drag.startStage + pointerAngleDeg(event) - drag.startAngle);
});
canvas.addEventListener("pointerup", (event) => {
  if (drag && !drag.moved) pickAt(event);
  drag = null;
});
document.addEventListener("keydown", (event) => {
  if (event.target.tagName === "INPUT" || event.target.tagName === "SELECT") return;
  const step = event.shiftKey ? 45 : 1;
  if (event.key === "ArrowLeft") setStage(state.stageDeg + step);        // counter-clockwise
  else if (event.key === "ArrowRight") setStage(state.stageDeg - step);  // clockwise
  else return;
  event.preventDefault();
});

/// Picks the grain under a click: the section pixel the turned stage puts there.
function pickAt(event) {
  const decoded = state.view;
  if (!decoded || $("bertrand").checked || !document.querySelector('input[name="specimen"][value="section"]').checked) return;
  const box = canvas.getBoundingClientRect();
  const column = (event.clientX - box.left) / box.width * decoded.width, row = (event.clientY - box.top) / box.height * decoded.height;
  const phi = state.stageDeg * Math.PI / 180, cx = decoded.width / 2, cy = decoded.height / 2;
  const x = column - cx, y = cy - row;
  const sourceColumn = Math.floor(Math.cos(phi) * x + Math.sin(phi) * y + cx), sourceRow = Math.floor(cy - (-Math.sin(phi) * x + Math.cos(phi) * y));
  if (sourceColumn < 0 || sourceRow < 0 || sourceColumn >= decoded.width || sourceRow >= decoded.height) return;
  state.pick = { x: sourceColumn, y: sourceRow };
  loadNumbers();
}

// ---- the numbers beside the picture ---------------------------------------------------------------------

async function loadNumbers() {
  const params = specimenParams();
  const response = await fetch("api/grain?" + params.toString());
  const numbers = await response.json();
  state.numbers = response.ok ? numbers : null;
  if (!response.ok) setStatus("error: " + numbers.error);
  showNumbers();
}

function showNumbers() {
  const n = state.numbers, list = $("numbers");
  list.replaceChildren();
  $("grain-where").textContent = "";
  if (!n) return;
  $("grain-where").textContent = (n.label !== undefined ? n.label + ", " : "") + n.mineral;
  const fixed = (value, digits) => value === null ? "—" : Number(value).toFixed(digits);
  const extinction = n.extinction_stage_deg === null ? "none: no birefringence along the axis"
    : [0, 1, 2, 3].map((k) => (n.extinction_stage_deg + 90 * k).toFixed(1) + "°").join(", ");
  const rows = [
    ["thickness", fixed(n.thickness_um, 1) + " µm"],
    ["retardation", fixed(n.retardation_nm, 0) + " nm at " + n.wavelength_nm + " nm"],
    ["birefringence here", fixed(n.birefringence_in_section, 4)],
    ["slow direction now", n.slow_azimuth_deg === null ? "—" : (((n.slow_azimuth_deg + state.stageDeg) % 180 + 180) % 180).toFixed(1) + "° from E"],
    ["extinction at stage", extinction],
    ["mineral's nγ − nα", fixed(n.mineral_birefringence, 4)],
    ["2V", n.two_v_deg === null ? "— (isotropic mineral)" : fixed(n.two_v_deg, 1) + "°"],
    ["optic sign", n.optic_sign || "—"],
    ["form (optically active)", n.handedness === null ? "— (inactive mineral)" : n.handedness + "-handed"],
  ];
  for (const [term, value] of rows) {
    const dt = document.createElement("dt"), dd = document.createElement("dd");
    dt.textContent = term;
    dd.textContent = value;
    list.append(dt, dd);
  }
}

// ---- saving --------------------------------------------------------------------------------------------

function download(blob, name) {
  const link = document.createElement("a");
  link.href = URL.createObjectURL(blob);
  link.download = name;
  link.click();
  setTimeout(() => URL.revokeObjectURL(link.href), 1000);
}

function saveImage() {
  const sidecar = {
    program: "petroscope serve",
    view: Object.fromEntries(new URLSearchParams(state.viewKey)),
    stage_deg: state.stageDeg,
    grain: state.numbers,
    image: "8-bit sRGB, the view composed from its stage harmonics (docs/browser.md)",
  };
  canvas.toBlob((blob) => download(blob, "petroscope-view.png"), "image/png");
  download(new Blob([JSON.stringify(sidecar, null, 2)], { type: "application/json" }), "petroscope-view.json");
}

// ---- a section of the user's own -------------------------------------------------------------------------

/// Sends a section's description (the .txt) and grain maps; the server answers with the name to view it by.
async function sendSection(files) {
  const form = new FormData();
  for (const file of files) form.append(file.name.endsWith(".txt") ? "description" : "map", file, file.name);
  setStatus("reading the section…");
  const response = await fetch("api/section", { method: "POST", body: form });
  const answer = await response.json();
  if (!response.ok) { setStatus("error: " + answer.error); return; }
  const option = document.createElement("option");
  option.value = answer.section;
  option.textContent = answer.name + " (yours)";
  $("section").append(option);
  $("section").value = answer.section;
  document.querySelector('input[name="specimen"][value="section"]').checked = true;
  specimenChanged();
}

// ---- wiring ----------------------------------------------------------------------------------------------

function setStatus(text) { $("status").textContent = text; }

function fillSelect(select, values, chosen) {
  for (const value of values) {
    const option = document.createElement("option");
    option.value = option.textContent = value;
    select.append(option);
  }
  if (chosen) select.value = chosen;
}

function specimenChanged() {
  const section = document.querySelector('input[name="specimen"]:checked').value === "section";
  $("section-controls").hidden = !section;
  $("crystal-controls").hidden = section;
  $("seed-label").hidden = $("section").value !== "random";
  state.pick = null;
  refresh();
  loadNumbers();
}

async function start() {
  const catalog = await (await fetch("api/catalog")).json();
  fillSelect($("section"), catalog.sections, "granite");
  fillSelect($("mineral"), catalog.minerals.map((m) => m.name), "calcite");
  fillSelect($("cut"), catalog.cuts, "optic-axis");
  for (const id of ["section", "seed", "section-thickness", "mineral", "cut", "tilt", "azimuth", "euler", "crystal-thickness", "handedness"]) {
    $(id).addEventListener("change", specimenChanged);
  }
  for (const input of document.querySelectorAll('input[name="specimen"]')) input.addEventListener("change", specimenChanged);
  for (const id of ["polarizer", "analyzer", "plate", "wedge", "condenser", "bertrand", "illuminant"]) $(id).addEventListener("change", refresh);
  $("plate").addEventListener("change", () => { $("wedge-label").hidden = $("plate").value !== "wedge"; });
  for (const input of document.querySelectorAll('input[name="light"]')) input.addEventListener("change", () => { refresh(); loadNumbers(); });
  $("wavelength").addEventListener("input", () => { $("wavelength-readout").textContent = $("wavelength").value + " nm"; });
  $("wavelength").addEventListener("change", () => { refresh(); loadNumbers(); });
  $("stage").addEventListener("change", () => setStage(Number($("stage").value) || 0));
  $("save").addEventListener("click", saveImage);
  $("section-files").addEventListener("change", () => sendSection([...$("section-files").files]));
  $("field").addEventListener("dragover", (event) => event.preventDefault());
  $("field").addEventListener("drop", (event) => { event.preventDefault(); sendSection([...event.dataTransfer.files]); });
  specimenChanged();
  requestAnimationFrame(frame);
}

start().catch((error) => setStatus("error: " + error.message));
