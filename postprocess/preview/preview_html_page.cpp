// The preview page as one raw string: no network, no external script.
#include "postprocess/preview/preview_html_page.h"

namespace strand::post {

const std::string& html_page_template() {
  static const std::string kPage = R"(<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>@TITLE@ - Strand preview</title>
<style>
html,body{margin:0;height:100%;font:13px sans-serif;background:#fff}
#bar{position:fixed;top:0;left:0;right:0;padding:6px 10px;background:#f0f0f0;border-bottom:1px solid #ccc;z-index:1}
#bar label{margin-right:14px}#legend span{display:inline-block;margin-right:10px}
#legend i{display:inline-block;width:12px;height:12px;margin-right:3px;vertical-align:middle}
canvas{position:absolute;top:0;left:0;cursor:grab}
#status{color:#555;margin-left:10px}
</style></head><body>
<div id="bar"><b>@TITLE@</b>
<label>layer <input id="layer" type="range" min="0" max="0" value="0"> <span id="layerText"></span></label>
<label><input id="only" type="checkbox"> this layer only</label>
<label><input id="travel" type="checkbox"> travel</label>
<label>colour <select id="colour"><option value="feature">feature</option><option value="layer">layer</option></select></label>
<button id="fit">fit</button> <span id="legend"></span> <span id="status">loading</span></div>
<canvas id="view"></canvas>
<script id="scene" type="application/json">@DATA@</script>
<script>
"use strict";
const statusEl = document.getElementById('status');
window.addEventListener('error', e => { statusEl.textContent = 'error: ' + e.message; });
const scene = JSON.parse(document.getElementById('scene').textContent);
const canvas = document.getElementById('view'), ctx = canvas.getContext('2d');
const layerIn = document.getElementById('layer'), onlyIn = document.getElementById('only');
const travelIn = document.getElementById('travel'), colourIn = document.getElementById('colour');
const dim = scene.dim, nLayersAll = scene.layers.length, nLayers = Math.max(1, nLayersAll);
layerIn.max = nLayers - 1; layerIn.value = nLayers - 1;
const mm = v => String(+v.toFixed(3));
function layerColour(l) {  // as post::layer_colour: blue (first layer) to red (last)
  const t = nLayersAll > 1 ? l / (nLayersAll - 1) : 0, c = v => Math.round(255 * v);
  return 'rgb(' + c(0.15 + 0.8 * t) + ',' + c(0.3 + 0.3 * (1 - Math.abs(2 * t - 1))) + ',' + c(0.95 - 0.8 * t) + ')';
}
const colourOf = p => p.t ? '#888' : (colourIn.value === 'layer' ? layerColour(Math.max(p.l, 0)) : scene.colours[p.f]);
function shown(p) {
  const top = +layerIn.value;
  return !(p.l > top || (onlyIn.checked && p.l !== top) || (p.t && !travelIn.checked));
}
function barTop() { return document.getElementById('bar').offsetHeight; }
function scaleBar(pxPerMm) {  // 1, 2 or 5 x 10^k mm, about a fifth of the window
  const target = canvas.width / pxPerMm / 5, p = Math.pow(10, Math.floor(Math.log10(target)));
  const len = [5, 2, 1].map(m => m * p).find(v => v <= target) || p, px = len * pxPerMm, y = canvas.height - 20;
  ctx.strokeStyle = '#222'; ctx.lineWidth = 2; ctx.beginPath();
  ctx.moveTo(20, y - 6); ctx.lineTo(20, y); ctx.lineTo(20 + px, y); ctx.lineTo(20 + px, y - 6); ctx.stroke();
  ctx.fillStyle = '#222'; ctx.font = '13px sans-serif'; ctx.fillText(mm(len) + ' mm', 28 + px, y);
}
// Bounds of the part: deposits on layers (this layer only: on that layer); purge lines
// before the first layer and travels are left out. [lo..., hi...] in `dim` coordinates.
function partBounds() {
  const top = +layerIn.value, lo = new Array(dim).fill(Infinity), hi = new Array(dim).fill(-Infinity);
  for (const p of scene.paths) {
    if (p.t || p.l < 0 || (onlyIn.checked && p.l !== top)) continue;
    for (let i = 0; i < p.p.length; i += dim) {
      for (let k = 0; k < dim; k++) { lo[k] = Math.min(lo[k], p.p[i + k]); hi[k] = Math.max(hi[k], p.p[i + k]); }
    }
  }
  return lo[0] === Infinity ? scene.bounds : lo.concat(hi);
}
let view = {scale: 1, x: 0, y: 0};  // 2D: px = x + scale * mm
function fit2d() {
  const top = barTop(), b = partBounds(), w = canvas.width, h = canvas.height - top - 30;
  const s = Math.min(w / Math.max(b[2] - b[0], 1e-3), h / Math.max(b[3] - b[1], 1e-3)) * 0.9;
  view = {scale: s, x: w / 2 - s * (b[0] + b[2]) / 2, y: top + h / 2 + s * (b[1] + b[3]) / 2};
}
function draw2d() {
  const top = +layerIn.value;
  let n = 0;
  for (const p of scene.paths) {
    if (!shown(p)) continue;
    ctx.strokeStyle = colourOf(p);
    ctx.lineWidth = p.t ? 1 : Math.max(1, scene.width * view.scale);
    ctx.globalAlpha = (onlyIn.checked || p.l === top || p.t) ? 1 : 0.55;
    ctx.beginPath();
    for (let i = 0; i < p.p.length; i += 2) {
      const x = view.x + view.scale * p.p[i], y = view.y - view.scale * p.p[i + 1];
      if (i === 0) ctx.moveTo(x, y); else ctx.lineTo(x, y);
    }
    ctx.stroke(); n++;
  }
  ctx.globalAlpha = 1;
  scaleBar(view.scale);
  return n;
}
// 3D: orthographic camera orbiting the part's centre c; yaw about z, pitch above the horizon.
const deg = Math.PI / 180;
let cam = {yaw: -35 * deg, pitch: 30 * deg, scale: 1, x: 0, y: 0, c: [0, 0, 0]};
for (const kv of location.hash.slice(1).split('&')) {  // #yaw=A&pitch=B&layer=N&only=1
  const [k, v] = kv.split('=');
  if ((k === 'yaw' || k === 'pitch') && isFinite(+v)) cam[k] = +v * deg;
  if (k === 'layer' && isFinite(+v)) layerIn.value = Math.max(0, Math.min(nLayers - 1, Math.round(+v)));
  if (k === 'only') onlyIn.checked = v === '1';
}
function basis() {
  const cy = Math.cos(cam.yaw), sy = Math.sin(cam.yaw), cp = Math.cos(cam.pitch), sp = Math.sin(cam.pitch);
  const r = [cy, sy, 0], v = [cp * sy, -cp * cy, sp];  // right, towards the viewer
  return {r, v, u: [v[1] * r[2] - v[2] * r[1], v[2] * r[0] - v[0] * r[2], v[0] * r[1] - v[1] * r[0]]};
}
function fit3d() {  // the part's box, seen from the current angle, fills the window
  const top = barTop(), b = partBounds(), w = canvas.width, h = canvas.height - top - 30, {r, u} = basis();
  cam.c = [(b[0] + b[3]) / 2, (b[1] + b[4]) / 2, (b[2] + b[5]) / 2];
  let ex = 1e-3, ey = 1e-3;
  for (let k = 0; k < 8; k++) {
    const d = [0, 1, 2].map(i => ((k >> i) & 1 ? b[i + 3] : b[i]) - cam.c[i]);
    ex = Math.max(ex, Math.abs(d[0] * r[0] + d[1] * r[1] + d[2] * r[2]));
    ey = Math.max(ey, Math.abs(d[0] * u[0] + d[1] * u[1] + d[2] * u[2]));
  }
  cam.scale = 0.9 * Math.min(w / (2 * ex), h / (2 * ey)); cam.x = w / 2; cam.y = top + h / 2;
}
function projector() {
  const {r, u, v} = basis(), c = cam.c, s = cam.scale;
  return (a, i) => {
    const dx = a[i] - c[0], dy = a[i + 1] - c[1], dz = a[i + 2] - c[2];
    return [cam.x + s * (dx * r[0] + dy * r[1] + dz * r[2]), cam.y - s * (dx * u[0] + dy * u[1] + dz * u[2]),
            dx * v[0] + dy * v[1] + dz * v[2]];
  };
}
// Substrate triangles projected and binned on a grid of 8 px cells, for the depth test.
function substrateView(P) {
  const sub = scene.substrate || {v: [], t: []}, q = [];
  for (let i = 0; i < sub.v.length; i += 3) q.push(P(sub.v, i));
  const cols = Math.ceil(canvas.width / 8), rows = Math.ceil(canvas.height / 8), grid = new Map();
  for (let t = 0; t < sub.t.length; t += 3) {
    const a = q[sub.t[t]], b = q[sub.t[t + 1]], c = q[sub.t[t + 2]];
    const c0 = Math.max(0, Math.floor(Math.min(a[0], b[0], c[0]) / 8)), c1 = Math.min(cols - 1, Math.floor(Math.max(a[0], b[0], c[0]) / 8));
    const r0 = Math.max(0, Math.floor(Math.min(a[1], b[1], c[1]) / 8)), r1 = Math.min(rows - 1, Math.floor(Math.max(a[1], b[1], c[1]) / 8));
    for (let rr = r0; rr <= r1; rr++) for (let cc = c0; cc <= c1; cc++) {
      const key = rr * cols + cc;
      if (!grid.has(key)) grid.set(key, []);
      grid.get(key).push(t);
    }
  }
  const behind = (x, y, z) => {
    for (const t of grid.get(Math.floor(y / 8) * cols + Math.floor(x / 8)) || []) {
      const a = q[sub.t[t]], b = q[sub.t[t + 1]], c = q[sub.t[t + 2]];
      const area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
      if (Math.abs(area) < 1e-12) continue;
      const wb = ((x - a[0]) * (c[1] - a[1]) - (y - a[1]) * (c[0] - a[0])) / area;
      const wc = ((b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0])) / area;
      if (wb >= 0 && wc >= 0 && wb + wc <= 1 && (1 - wb - wc) * a[2] + wb * b[2] + wc * c[2] > z) return true;
    }
    return false;
  };
  return {q, sub, behind};
}
function drawSubstrate(S) {  // translucent, one fill per shade so facets show no seams
  const {v} = basis(), n = scene.substrateNormals, buckets = new Map();
  for (let t = 0; t < S.sub.t.length; t += 3) {
    const f = n[t] * v[0] + n[t + 1] * v[1] + n[t + 2] * v[2];
    const key = (f >= 0 ? 1 : -1) * Math.round(Math.abs(f) * 6);
    if (!buckets.has(key)) buckets.set(key, []);
    buckets.get(key).push(t);
  }
  for (const [key, list] of buckets) {
    const l = Math.round(150 + 12 * Math.abs(key) - (key < 0 ? 30 : 0));
    ctx.fillStyle = 'rgba(' + l + ',' + (l + 6) + ',' + (l + 16) + ',0.32)';
    ctx.beginPath();
    for (const t of list) {
      const a = S.q[S.sub.t[t]], b = S.q[S.sub.t[t + 1]], c = S.q[S.sub.t[t + 2]];
      ctx.moveTo(a[0], a[1]); ctx.lineTo(b[0], b[1]); ctx.lineTo(c[0], c[1]); ctx.closePath();
    }
    ctx.fill();
  }
}
// Runs of each shown path split where it passes behind the substrate: far runs, then the
// translucent substrate over them, then near runs.
function draw3d() {
  const P = projector(), S = substrateView(P), far = [], near = [];
  let n = 0;
  for (const p of scene.paths) {
    if (!shown(p)) continue;
    n++;
    const pts = [];
    for (let i = 0; i < p.p.length; i += 3) pts.push(P(p.p, i));
    let run = null, runFar = null;
    for (let i = 0; i + 1 < pts.length; i++) {
      const a = pts[i], b = pts[i + 1], isFar = S.behind((a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2);
      if (!run || runFar !== isFar) {
        run = {p, pts: [a]}; runFar = isFar; (isFar ? far : near).push(run);
      }
      run.pts.push(b);
    }
  }
  const stroke = runs => {
    for (const r of runs) {
      ctx.strokeStyle = colourOf(r.p); ctx.lineWidth = r.p.t ? 1 : Math.max(1, scene.width * cam.scale);
      ctx.beginPath(); ctx.moveTo(r.pts[0][0], r.pts[0][1]);
      for (let i = 1; i < r.pts.length; i++) ctx.lineTo(r.pts[i][0], r.pts[i][1]);
      ctx.stroke();
    }
  };
  stroke(far); drawSubstrate(S); stroke(near);
  scaleBar(cam.scale);
  return n;
}
function draw() {
  const top = +layerIn.value;
  ctx.fillStyle = '#fff'; ctx.fillRect(0, 0, canvas.width, canvas.height);
  ctx.lineCap = 'round'; ctx.lineJoin = 'round';
  const n = dim === 3 ? draw3d() : draw2d();
  const z = nLayersAll ? scene.layers[top] : 0;
  document.getElementById('layerText').textContent = top + ' (' + scene.layerValue + ' ' + mm(z) + ' mm)';
  statusEl.textContent = 'drawn: ' + n + ' paths, layers ' + (onlyIn.checked ? top : 0) + '-' + top +
      (dim === 3 ? ' (3D orbit view)' : '');
}
let pending = false;
function redraw() { if (!pending) { pending = true; requestAnimationFrame(() => { pending = false; draw(); }); } }
const fit = () => (dim === 3 ? fit3d() : fit2d());
function resize() { canvas.width = window.innerWidth; canvas.height = window.innerHeight; }
let drag = null;
canvas.addEventListener('mousedown', e => { drag = {x: e.clientX, y: e.clientY, pan: e.shiftKey || dim === 2}; });
window.addEventListener('mouseup', () => { drag = null; });
canvas.addEventListener('mousemove', e => {
  if (!drag) return;
  const dx = e.clientX - drag.x, dy = e.clientY - drag.y, v = dim === 3 ? cam : view;
  drag.x = e.clientX; drag.y = e.clientY;
  if (drag.pan) { v.x += dx; v.y += dy; } else {
    cam.yaw -= dx * 0.01; cam.pitch = Math.max(-89 * deg, Math.min(89 * deg, cam.pitch + dy * 0.01));
  }
  redraw();
});
canvas.addEventListener('wheel', e => {
  e.preventDefault();
  const k = Math.exp(-e.deltaY * 0.0015), v = dim === 3 ? cam : view;
  v.x = e.clientX - k * (e.clientX - v.x); v.y = e.clientY - k * (e.clientY - v.y);
  v.scale *= k; redraw();
}, {passive: false});
for (const el of [travelIn, colourIn]) el.addEventListener('input', redraw);
layerIn.addEventListener('input', () => { if (onlyIn.checked) fit(); redraw(); });
onlyIn.addEventListener('input', () => { fit(); redraw(); });
document.getElementById('fit').addEventListener('click', () => { fit(); redraw(); });
window.addEventListener('resize', () => { resize(); redraw(); });
const legend = document.getElementById('legend');
scene.features.concat(scene.substrate ? ['substrate'] : []).forEach((f, i) => {
  const s = document.createElement('span'), sw = document.createElement('i');
  sw.style.background = i < scene.features.length ? scene.colours[i] : '#a4abb8';
  s.appendChild(sw); s.appendChild(document.createTextNode(f)); legend.appendChild(s);
});
resize(); fit(); draw();
</script></body></html>
)";
  return kPage;
}

}  // namespace strand::post
