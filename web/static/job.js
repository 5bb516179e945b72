// One job: summary, timeline of its task leases per worker, and for a DONE
// job its store statistics and the relight view: on the browser's GPU when
// it has WebGL2 with float targets and blending and the store is one the
// GPU path draws (web/views/job_gpu.h: the 4D store decoded by view_4d.js, only
// the kept lights fetched per change, no frame requests); otherwise frames
// relit by the server as the controls move (at most one request in flight,
// the latest wins).
"use strict";

const jobId = location.pathname.split("/").pop();
const KIND_COLOURS = { BAKE_TILE: "#2f81f7", TRANSFORM_COLUMNS: "#d4a72c", FINALIZE: "#1a7f37" };
// A job is the Job message as JSON (driver/jobs/job_json.h): the scene is in its
// request, "ended" is a phase from DONE on, an ETA < 0 is unknown.
const ENDED = new Set(["DONE", "FAILED", "CANCELLED"]);
function jobEnded(job) { return ENDED.has(job.phase); }
function jobScene(job) {
  const s = job.request.scene || {};
  return s.builtin !== undefined ? s.builtin : s.uploaded ? s.uploaded.file_name : "";
}

async function getJSON(url) {
  const res = await fetch(url, { cache: "no-store" });
  const body = await res.json().catch(() => ({}));
  if (!res.ok) throw new Error(body.error || res.statusText);
  return body;
}

function setSummary(id, pairs) {
  const dl = document.getElementById(id);
  dl.replaceChildren();
  for (const [k, v] of pairs) {
    const dt = document.createElement("dt"); dt.textContent = k;
    const dd = document.createElement("dd"); dd.textContent = v;
    dd.dataset.key = k;
    dl.append(dt, dd);
  }
}

function renderJob(job) {
  document.getElementById("job-id").textContent = job.id;
  const elapsed = job.started_ms ? ((jobEnded(job) ? job.finished_ms : Date.now()) - job.started_ms) / 1000 : 0;
  setSummary("summary", [
    ["phase", job.phase],
    ["scene", `${jobScene(job)} (${job.request.layout}, N=${job.request.light_res})`],
    ["tasks", `${job.tasks_done}/${job.tasks_total} (${job.tiles} tiles, ${job.groups} groups, 1 finalize), ${job.leased_tasks} leased`],
    ["rays", `${job.rays_traced.toLocaleString()} of ~${job.rays_estimate.toLocaleString()}, ${(job.rays_per_second / 1e6).toFixed(2)} Mrays/s`],
    ["elapsed", `${elapsed.toFixed(1)} s`],
    ["ETA", jobEnded(job) ? (job.phase === "DONE" ? "0 s" : "–") : (job.eta_seconds < 0 ? "–" : `${Math.round(job.eta_seconds)} s`)],
    ["store", job.store_path],
    ["error", job.error || "–"],
  ]);
}

// Lease intervals per worker from the events, drawn as lanes.
function renderTimeline(events, job) {
  const box = document.getElementById("timeline");
  if (!events.length) { box.replaceChildren(); return; }
  const t0 = events[0].unix_ms;
  const t1 = jobEnded(job) ? events[events.length - 1].unix_ms : Date.now();
  const open = new Map(), bars = [], phases = [], workers = new Set();
  let retries = 0;
  const perKind = { BAKE_TILE: 0, TRANSFORM_COLUMNS: 0, FINALIZE: 0 };
  for (const e of events) {
    const key = `${e.task_kind}:${e.task_index}`;
    if (e.kind === "PHASE") phases.push([e.unix_ms, e.phase]);
    if (e.kind === "TASK_LEASED") { open.set(key, e); workers.add(e.worker); }
    if (e.kind === "TASK_DONE" || e.kind === "TASK_FAILED" || e.kind === "LEASE_EXPIRED") {
      const start = open.get(key);
      if (start) bars.push({ start: start.unix_ms, end: e.unix_ms, worker: start.worker, kind: e.task_kind, ok: e.kind === "TASK_DONE" });
      open.delete(key);
      if (e.kind === "TASK_DONE") perKind[e.task_kind]++; else retries++;
    }
  }
  for (const s of open.values()) bars.push({ start: s.unix_ms, end: t1, worker: s.worker, kind: s.task_kind, ok: true, running: true });
  const lanes = [...workers].sort((a, b) => Number(a) - Number(b));
  document.getElementById("timeline-note").textContent =
    `${perKind.BAKE_TILE} tiles, ${perKind.TRANSFORM_COLUMNS} column groups, ${perKind.FINALIZE} finalize done; ` +
    `${retries} retries (failed or expired leases); workers: ${lanes.length}`;
  const width = 900, lane = 18, left = 70, top = 18;
  const height = top + lanes.length * lane + 24;
  box.replaceChildren();
  const svg = svgEl("svg", { width, height, viewBox: `0 0 ${width} ${height}` }, box);
  const span = Math.max(1, t1 - t0), w = width - left - 10;
  const x = (t) => left + w * (t - t0) / span;
  lanes.forEach((id, i) => svgText(svg, left - 6, top + i * lane + 12, `worker ${id}`, "end"));
  for (const b of bars) {
    const r = svgEl("rect", { x: x(b.start), y: top + lanes.indexOf(b.worker) * lane + 2, width: Math.max(1, x(b.end) - x(b.start)), height: lane - 4,
                              fill: KIND_COLOURS[b.kind] || "#999", stroke: b.ok ? "none" : "#cf222e", "stroke-width": 2, opacity: b.running ? 0.5 : 1 }, svg);
    svgEl("title", {}, r).textContent = `${b.kind} ${((b.end - b.start) / 1000).toFixed(2)} s${b.ok ? "" : " (failed)"}`;
  }
  for (const [t, phase] of phases) {
    svgEl("line", { x1: x(t), x2: x(t), y1: 4, y2: height - 20, stroke: "#8c959f", "stroke-dasharray": "3 3" }, svg);
    svgText(svg, x(t) + 2, 12, phase.toLowerCase());
  }
  svgText(svg, left, height - 6, "0 s");
  svgText(svg, width - 10, height - 6, `${(span / 1000).toFixed(1)} s`, "end");
}

function renderStore(store) {
  const s = store.stats || {}, bytes = s.bytes || {};
  document.getElementById("store-section").hidden = false;
  setSummary("store-summary", [
    ["format", store.format],
    ["grid", `${store.width}×${store.height} (${store.layout})`],
    ["lights", `N=${store.light_res}, ${store.columns} columns`],
    ["kept", `${(s.nnz || 0).toLocaleString()} coefficients, ${(s.kept_per_column || 0).toFixed(1)} per column`],
    ["bits", `${(bytes.bits_per_value || 0).toFixed(2)} per value, ${(bytes.bits_per_position || 0).toFixed(2)} per position`],
    ["size", `${(bytes.transport || 0).toLocaleString()} bytes, ${(bytes.compression_ratio || 0).toFixed(1)}× smaller than float32`],
    ["matrix error", `${(100 * (s.matrix_rel_rms || 0)).toFixed(2)} % relative RMS`],
  ]);
  barChart(document.getElementById("depth-chart"), s.depth_histogram || [], { xLabel: "depth" });
  barChart(document.getElementById("bits-chart"), s.column_bits_histogram || [], { xLabel: "bits", color: "#d4a72c" });
  hbarChart(document.getElementById("bytes-chart"), Object.entries(bytes.arrays || {}).sort((a, b) => b[1] - a[1]));
}

// The relight view's controls; returns the query of their current values.
function relightControls(store, probes) {
  document.getElementById("relight-section").hidden = false;
  document.getElementById("picture-kind").textContent = store.picture;
  const select = document.getElementById("probe");
  for (const name of probes) select.appendChild(new Option(name, name));
  // Terms in powers of two, then all of them.
  const maxTerms = store.columns, choices = [];
  for (let n = 1; n < maxTerms; n *= 2) choices.push(n);
  choices.push(maxTerms);
  const termsOf = (i) => choices[Math.min(choices.length - 1, i)];
  const terms = document.getElementById("terms");
  terms.max = choices.length - 1;
  terms.value = Math.max(0, choices.indexOf(Math.min(256, maxTerms)));
  return () => {
    const q = new URLSearchParams({ probe: select.value, rotate: document.getElementById("rotate").value,
                                    terms: termsOf(Number(terms.value)), exposure: document.getElementById("exposure").value });
    document.getElementById("rotate-value").textContent = `${q.get("rotate")}°`;
    document.getElementById("terms-value").textContent = `${q.get("terms")} of ${maxTerms}`;
    document.getElementById("exposure-value").textContent = q.get("exposure");
    return q.toString();
  };
}
const RELIGHT_CONTROLS = ["probe", "rotate", "terms", "exposure"];

// The relight view on the GPU; false (nothing shown) when this browser or
// this store cannot have it, and the server's frames take over.
async function startGpuRelight(store, probes) {
  const G = window.WavebakeGL;
  if (!G || !window.WavebakeColumnMode || store.picture === "vertex colours") return false;
  const canvas = document.getElementById("relight-gpu");
  const gl = canvas.getContext("webgl2", { antialias: false, preserveDrawingBuffer: true });
  if (!gl || !gl.getExtension("EXT_color_buffer_float") || !gl.getExtension("EXT_float_blend")) return false;
  const W = store.width, H = store.height, base = `/api/jobs/${jobId}/gpu/`;
  let mode, display, ctx;
  try {
    const cells = await G.getBytes(base + "cells.bin");
    ctx = { W, H, maxSize: gl.getParameter(gl.MAX_TEXTURE_SIZE), vao: gl.createVertexArray(),
            cellTex: G.texture(gl, gl.RGBA32F, gl.RGBA, gl.FLOAT, W, H, new Float32Array(cells.buffer)),
            columnsBase: base, lightsUrl: (q) => `${base}lights?${q}` };
    ctx.frameTex = G.texture(gl, gl.RGBA32F, gl.RGBA, gl.FLOAT, W, H, null);
    ctx.frameFbo = G.framebuffer(gl, ctx.frameTex);
    const shown = await G.program(gl, "fullscreen.vert", "display.frag");
    mode = await window.WavebakeColumnMode(gl, ctx);
    display = (exposure) => {
      gl.bindVertexArray(ctx.vao);
      gl.bindFramebuffer(gl.FRAMEBUFFER, null);
      gl.viewport(0, 0, W, H);
      gl.disable(gl.BLEND);
      gl.useProgram(shown);
      G.bindTextures(gl, [ctx.frameTex]);
      gl.uniform1i(gl.getUniformLocation(shown, "u_frame"), 0);
      gl.uniform1f(gl.getUniformLocation(shown, "u_scale"), Math.pow(2, exposure));
      gl.uniform1i(gl.getUniformLocation(shown, "u_height"), H);
      gl.drawArrays(gl.TRIANGLES, 0, 3);
    };
  } catch (e) {
    console.log(`relight on the GPU: ${e.message}; the server's frames instead`);
    return false;
  }
  canvas.width = W;
  canvas.height = H;
  canvas.hidden = false;
  document.getElementById("relight").hidden = true;
  const query = relightControls(store, probes);
  const stats = document.getElementById("relight-stats");
  const device = () => {
    const ext = gl.getExtension("WEBGL_debug_renderer_info");
    return ext ? gl.getParameter(ext.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER);
  };
  // The lighting changes with probe, rotation and terms; exposure redraws only.
  let inFlight = false, wanted = null, lit = null, frames = 0;
  window.wavebakeFrames = 0;
  const draw = async () => {
    if (inFlight || wanted === null) return;
    const q = new URLSearchParams(wanted);
    const exposure = Number(q.get("exposure"));
    q.delete("exposure");
    const lighting = q.toString();
    if (lighting === lit) {
      display(exposure);
      canvas.dataset.query = wanted;
      return;
    }
    inFlight = true;
    const shownQuery = wanted;
    try {
      const start = performance.now();
      const what = await mode.relight(lighting);
      display(exposure);
      gl.finish();
      lit = lighting;
      canvas.dataset.query = shownQuery;
      window.wavebakeFrames = ++frames;
      stats.textContent = `GPU (${device()}) · ${what} · ${(performance.now() - start).toFixed(1)} ms a frame`;
    } catch (e) {
      stats.textContent = `relight on the GPU: ${e.message}`;
      lit = lighting;  // do not retry a failing query in a loop
    } finally {
      inFlight = false;
      if (wanted !== shownQuery) draw();
    }
  };
  const changed = () => { wanted = query(); draw(); };
  for (const id of RELIGHT_CONTROLS) {
    for (const type of ["input", "change"]) document.getElementById(id).addEventListener(type, changed);
  }
  canvas.dataset.gpu = "1";
  changed();
  return true;
}

// The relight view's frame loop on the server.
function startRelight(store, probes) {
  const canvas = document.getElementById("relight");
  const stats = document.getElementById("relight-stats");
  // While the controls move each frame skips the comparison with every
  // wavelet light (it costs a full relight); once they rest, the same frame
  // is asked again with it.
  let inFlight = false, wanted = null, drawn = null, compared = null, error = null, frames = 0;
  const recent = [];  // times of the last frames: the rate while the controls move
  window.wavebakeFrames = 0;

  const query = relightControls(store, probes);
  const request = async () => {
    if (inFlight || (wanted === drawn && wanted === compared)) return;
    inFlight = true;
    const q = wanted, compare = q === drawn;  // a second look at a resting frame
    try {
      const res = await fetch(`/api/jobs/${jobId}/relight?${q}&compare=${compare ? 1 : 0}`, { cache: "no-store" });
      if (!res.ok) throw new Error((await res.json().catch(() => ({}))).error || res.statusText);
      const w = Number(res.headers.get("X-Width")), h = Number(res.headers.get("X-Height"));
      const pixels = new Uint8ClampedArray(await res.arrayBuffer());
      if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
      canvas.getContext("2d").putImageData(new ImageData(pixels, w, h), 0, 0);
      drawn = q;
      canvas.dataset.query = q;
      window.wavebakeFrames = ++frames;
      if (compare) { compared = q; error = res.headers.get("X-Rel-Rms-All"); }
      recent.push(performance.now());
      if (recent.length > 20) recent.shift();
      const fps = recent.length > 1 ? 1000 * (recent.length - 1) / (recent[recent.length - 1] - recent[0]) : 0;
      const errorText = compared === drawn ? `${(100 * Number(error)).toFixed(2)} %` : "…";
      stats.textContent = `${res.headers.get("X-Terms")} lights · server frame ${Number(res.headers.get("X-Frame-Ms")).toFixed(2)} ms · ` +
        `error ${errorText} vs all ${res.headers.get("X-Columns")} · ${fps.toFixed(0)} frames/s`;
      canvas.dataset.compared = compared === drawn ? "1" : "0";
    } catch (e) {
      stats.textContent = `relight: ${e.message}`;
      drawn = compared = q;  // do not retry a failing query in a loop
    } finally {
      inFlight = false;
      request();
    }
  };
  const changed = () => { wanted = query(); request(); };
  for (const id of RELIGHT_CONTROLS) {
    for (const type of ["input", "change"]) document.getElementById(id).addEventListener(type, changed);
  }
  changed();
}

async function refresh() {
  let job;
  try {
    job = await getJSON(`/api/jobs/${jobId}`);
    document.getElementById("link").textContent = jobEnded(job) ? "" : "live";
    renderJob(job);
    renderTimeline((await getJSON(`/api/jobs/${jobId}/events`)).events, job);
  } catch (e) {
    document.getElementById("link").textContent = e.message;
    return setTimeout(refresh, 2000);
  }
  if (!jobEnded(job)) return setTimeout(refresh, 1000);
  if (job.phase !== "DONE") return;
  try {
    const store = await getJSON(`/api/jobs/${jobId}/store`);
    renderStore(store);
    const probes = (await getJSON("/api/probes")).probes;
    if (!(await startGpuRelight(store, probes))) startRelight(store, probes);
  } catch (e) {
    document.getElementById("store-section").hidden = false;
    setSummary("store-summary", [["store", e.message]]);
  }
}

document.addEventListener("DOMContentLoaded", refresh);
