// The jobs page: the list follows /api/jobs/stream (server-sent events) and
// falls back to polling /api/jobs; no reload.
"use strict";

// A job is the Job message as JSON (driver/jobs/job_json.h): the scene is in its
// request, "ended" is a phase from DONE on, an ETA < 0 is unknown.
const ENDED = new Set(["DONE", "FAILED", "CANCELLED"]);
function jobEnded(job) { return ENDED.has(job.phase); }
function jobScene(job) {
  const s = job.request.scene || {};
  return s.builtin !== undefined ? s.builtin : s.uploaded ? s.uploaded.file_name : "";
}

function fmtSeconds(s) {
  if (s === null || s === undefined || s < 0) return "–";
  s = Math.max(0, Math.round(s));
  return s >= 3600 ? `${Math.floor(s / 3600)}h${String(Math.floor(s / 60) % 60).padStart(2, "0")}m`
       : s >= 60 ? `${Math.floor(s / 60)}m${String(s % 60).padStart(2, "0")}s` : `${s}s`;
}

function cell(row, cls, text) {
  let td = row.querySelector("td." + cls);
  if (!td) { td = document.createElement("td"); td.className = cls; row.appendChild(td); }
  if (text !== undefined && td.textContent !== String(text)) td.textContent = text;
  return td;
}

async function cancelJob(id, button) {
  button.disabled = true;
  const res = await fetch(`/api/jobs/${id}/cancel`, { method: "POST", headers: { "X-Wavebake": "1" } });
  if (!res.ok) {
    const body = await res.json().catch(() => ({ error: res.statusText }));
    alert(`cancel job ${id}: ${body.error}`);
    button.disabled = false;
  }
}

function renderJobs(jobs) {
  const body = document.querySelector("#jobs tbody");
  document.getElementById("empty").hidden = jobs.length > 0;
  const keep = new Set();
  jobs.forEach((job, i) => {
    const id = `job-${job.id}`;
    keep.add(id);
    let row = document.getElementById(id);
    if (!row) {
      row = document.createElement("tr");
      row.id = id;
      const a = document.createElement("a");
      a.href = `/jobs/${job.id}`;
      a.textContent = job.id;
      cell(row, "id").appendChild(a);
      cell(row, "scene"); cell(row, "phase");
      const bar = document.createElement("div"); bar.className = "bar";
      bar.appendChild(document.createElement("div"));
      cell(row, "progress").appendChild(bar);
      cell(row, "tasks"); cell(row, "rate"); cell(row, "eta"); cell(row, "error");
      const button = document.createElement("button");
      button.className = "cancel"; button.textContent = "cancel";
      button.addEventListener("click", () => cancelJob(job.id, button));
      cell(row, "actions").appendChild(button);
    }
    if (body.children[i] !== row) body.insertBefore(row, body.children[i] || null);
    cell(row, "scene", `${jobScene(job)} ${job.request.layout} N=${job.request.light_res}`);
    const phase = cell(row, "phase", job.phase);
    phase.className = `phase phase-${job.phase}`;
    const frac = job.tasks_total > 0 ? job.tasks_done / job.tasks_total : 0;
    row.querySelector(".bar > div").style.width = `${(100 * frac).toFixed(1)}%`;
    cell(row, "tasks", `${job.tasks_done}/${job.tasks_total}`);
    cell(row, "rate", (job.rays_per_second / 1e6).toFixed(2));
    cell(row, "eta", jobEnded(job) ? (job.phase === "DONE" ? "0s" : "–") : fmtSeconds(job.eta_seconds));
    cell(row, "error", job.error);
    row.querySelector("button.cancel").hidden = jobEnded(job);
  });
  for (const row of [...body.children]) if (!keep.has(row.id)) row.remove();
}

function setLink(text) { document.getElementById("link").textContent = text; }

function poll() {
  setLink("polling");
  const tick = async () => {
    try {
      const res = await fetch("/api/jobs", { cache: "no-store" });
      if (res.ok) renderJobs(await res.json());
    } catch (e) { setLink("offline"); }
    setTimeout(tick, 1000);
  };
  tick();
}

function follow() {
  if (!window.EventSource) return poll();
  const source = new EventSource("/api/jobs/stream");
  let opened = false;
  source.addEventListener("open", () => { opened = true; setLink("live"); });
  source.addEventListener("jobs", (e) => renderJobs(JSON.parse(e.data)));
  source.addEventListener("error", () => {
    if (!opened) { source.close(); poll(); } else setLink("reconnecting…");
  });
}

document.addEventListener("DOMContentLoaded", follow);
