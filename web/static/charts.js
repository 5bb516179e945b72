// Small SVG charts for the job page: vertical bars over an index axis, and
// horizontal labelled bars. Plain DOM; no library.
"use strict";

const SVG_NS = "http://www.w3.org/2000/svg";

function svgEl(name, attrs, parent) {
  const el = document.createElementNS(SVG_NS, name);
  for (const [k, v] of Object.entries(attrs || {})) el.setAttribute(k, v);
  if (parent) parent.appendChild(el);
  return el;
}

function svgText(parent, x, y, text, anchor) {
  const t = svgEl("text", { x, y, "text-anchor": anchor || "start" }, parent);
  t.textContent = text;
  return t;
}

// counts[i] as bars labelled by i (e.g. columns per depth).
function barChart(container, counts, { width = 300, height = 160, color = "#2f81f7", xLabel = "" } = {}) {
  container.replaceChildren();
  const svg = svgEl("svg", { width, height, viewBox: `0 0 ${width} ${height}` }, container);
  const left = 34, bottom = 28, top = 8, right = 6;
  const w = width - left - right, h = height - top - bottom;
  const max = Math.max(1, ...counts);
  const step = w / Math.max(1, counts.length);
  counts.forEach((c, i) => {
    const bh = h * c / max;
    const bar = svgEl("rect", { x: left + i * step + 1, y: top + h - bh, width: Math.max(1, step - 2), height: bh, fill: color }, svg);
    svgEl("title", {}, bar).textContent = `${i}: ${c}`;
    if (counts.length <= 20 || i % Math.ceil(counts.length / 20) === 0) svgText(svg, left + (i + 0.5) * step, top + h + 12, String(i), "middle");
  });
  svgText(svg, left - 4, top + 8, String(max), "end");
  svgText(svg, left - 4, top + h, "0", "end");
  svgText(svg, left + w / 2, height - 3, xLabel, "middle");
  return svg;
}

// [[label, value], ...] as horizontal bars with their values.
function hbarChart(container, items, { width = 360, row = 16, color = "#8250df", unit = "" } = {}) {
  container.replaceChildren();
  const height = items.length * row + 8;
  const svg = svgEl("svg", { width, height, viewBox: `0 0 ${width} ${height}` }, container);
  const left = 120, right = 70, w = width - left - right;
  const max = Math.max(1, ...items.map(([, v]) => v));
  items.forEach(([label, v], i) => {
    const y = 4 + i * row;
    svgText(svg, left - 4, y + row - 5, label, "end");
    svgEl("rect", { x: left, y: y + 2, width: Math.max(1, w * v / max), height: row - 4, fill: color }, svg);
    svgText(svg, left + w * v / max + 4, y + row - 5, `${v.toLocaleString()}${unit}`);
  });
  return svg;
}
