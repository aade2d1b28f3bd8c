// The HTML preview page: scene data as inline JSON plus a small canvas viewer.
#include "postprocess/preview/preview_html.h"

#include <nlohmann/json.hpp>

#include "machines/gcode_format.h"

namespace strand::post {

namespace {

const char* kPage = R"(<!DOCTYPE html>
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
const layerIn = document.getElementById('layer'), onlyIn = document.getElementById('only'), travelIn = document.getElementById('travel');
const colourIn = document.getElementById('colour');
function layerColour(l) {  // as post::layer_colour: blue (first layer) to red (last)
  const t = nLayersAll > 1 ? l / (nLayersAll - 1) : 0, c = v => Math.round(255 * v);
  return 'rgb(' + c(0.15 + 0.8 * t) + ',' + c(0.3 + 0.3 * (1 - Math.abs(2 * t - 1))) + ',' + c(0.95 - 0.8 * t) + ')';
}
function scaleBar() {  // 1, 2 or 5 x 10^k mm, about a fifth of the window
  const target = canvas.width / view.scale / 5, p = Math.pow(10, Math.floor(Math.log10(target)));
  const mm = [5, 2, 1].map(m => m * p).find(v => v <= target) || p, px = mm * view.scale, y = canvas.height - 20;
  ctx.strokeStyle = '#222'; ctx.lineWidth = 2; ctx.beginPath();
  ctx.moveTo(20, y - 6); ctx.lineTo(20, y); ctx.lineTo(20 + px, y); ctx.lineTo(20 + px, y - 6); ctx.stroke();
  ctx.fillStyle = '#222'; ctx.font = '13px sans-serif'; ctx.fillText(mm + ' mm', 28 + px, y);
}
const nLayers = Math.max(1, scene.layers.length), nLayersAll = scene.layers.length;
layerIn.max = nLayers - 1; layerIn.value = nLayers - 1;
let view = {scale: 1, x: 0, y: 0};
function fit() {
  const top = document.getElementById('bar').offsetHeight, bottom = 30;  // tool bar, scale bar
  const b = scene.bounds, w = canvas.width, h = canvas.height - top - bottom;
  const s = Math.min(w / Math.max(b[2] - b[0], 1e-3), h / Math.max(b[3] - b[1], 1e-3)) * 0.9;
  view = {scale: s, x: w / 2 - s * (b[0] + b[2]) / 2, y: top + h / 2 + s * (b[1] + b[3]) / 2};
}
function draw() {
  const top = +layerIn.value, only = onlyIn.checked, travel = travelIn.checked;
  ctx.fillStyle = '#fff'; ctx.fillRect(0, 0, canvas.width, canvas.height);
  ctx.lineCap = 'round'; ctx.lineJoin = 'round';
  let n = 0;
  for (const p of scene.paths) {
    if (p.l > top || (only && p.l !== top) || (p.t && !travel)) continue;
    ctx.strokeStyle = p.t ? '#888' : (colourIn.value === 'layer' ? layerColour(p.l) : scene.colours[p.f]);
    ctx.lineWidth = p.t ? 1 : Math.max(1, scene.width * view.scale);
    ctx.globalAlpha = (only || p.l === top || p.t) ? 1 : 0.55;
    ctx.beginPath();
    for (let i = 0; i < p.p.length; i += 2) {
      const x = view.x + view.scale * p.p[i], y = view.y - view.scale * p.p[i + 1];
      if (i === 0) ctx.moveTo(x, y); else ctx.lineTo(x, y);
    }
    ctx.stroke(); n++;
  }
  ctx.globalAlpha = 1;
  scaleBar();
  const z = scene.layers.length ? scene.layers[top] : 0;
  document.getElementById('layerText').textContent = top + ' (z ' + z + ' mm)';
  statusEl.textContent = 'drawn: ' + n + ' paths, layers ' + (only ? top : 0) + '-' + top;
}
function resize() { canvas.width = window.innerWidth; canvas.height = window.innerHeight; }
let drag = null;
canvas.addEventListener('mousedown', e => { drag = {x: e.clientX - view.x, y: e.clientY - view.y}; });
window.addEventListener('mouseup', () => { drag = null; });
canvas.addEventListener('mousemove', e => { if (drag) { view.x = e.clientX - drag.x; view.y = e.clientY - drag.y; draw(); } });
canvas.addEventListener('wheel', e => {
  e.preventDefault();
  const k = Math.exp(-e.deltaY * 0.0015);
  view.x = e.clientX - k * (e.clientX - view.x); view.y = e.clientY - k * (e.clientY - view.y);
  view.scale *= k; draw();
}, {passive: false});
for (const el of [layerIn, onlyIn, travelIn, colourIn]) el.addEventListener('input', draw);
document.getElementById('fit').addEventListener('click', () => { fit(); draw(); });
window.addEventListener('resize', () => { resize(); draw(); });
const legend = document.getElementById('legend');
scene.features.forEach((f, i) => {
  const s = document.createElement('span'), sw = document.createElement('i');
  sw.style.background = scene.colours[i]; s.appendChild(sw); s.appendChild(document.createTextNode(f)); legend.appendChild(s);
});
resize(); fit(); draw();
</script></body></html>
)";

std::string escape_html(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '<') o += "&lt;";
    else if (c == '>') o += "&gt;";
    else if (c == '&') o += "&amp;";
    else if (c == '"') o += "&quot;";
    else o += c;
  }
  return o;
}

void replace_all(std::string& s, const std::string& what, const std::string& with) {
  for (auto at = s.find(what); at != std::string::npos; at = s.find(what, at + with.size())) s.replace(at, what.size(), with);
}

// Numbers written with 3 decimals as raw JSON (G-code precision, stable bytes).
std::string scene_json(const PreviewScene& s) {
  std::string out = "{\"paths\":[";
  std::vector<slicer::Feature> used;
  for (std::size_t i = 0; i < s.paths.size(); ++i) {
    const auto& p = s.paths[i];
    if (!p.travel && std::find(used.begin(), used.end(), p.feature) == used.end()) used.push_back(p.feature);
  }
  std::sort(used.begin(), used.end());
  for (std::size_t i = 0; i < s.paths.size(); ++i) {
    const auto& p = s.paths[i];
    const auto f = std::find(used.begin(), used.end(), p.feature) - used.begin();
    out += std::string(i ? "," : "") + "{\"l\":" + std::to_string(std::max(p.layer, 0)) + ",\"t\":" +
           (p.travel ? "1" : "0") + ",\"f\":" + std::to_string(p.travel ? 0 : f) + ",\"p\":[";
    for (std::size_t k = 0; k < p.points_mm.size(); ++k) {
      out += (k ? "," : "") + machines::fmt_xyz(p.points_mm[k].x()) + "," + machines::fmt_xyz(p.points_mm[k].y());
    }
    out += "]}";
  }
  nlohmann::json meta;
  meta["layers"] = s.layer_z_mm;
  meta["bounds"] = {s.min_mm.x(), s.min_mm.y(), s.max_mm.x(), s.max_mm.y()};
  meta["width"] = s.bead_width_mm > 0 ? s.bead_width_mm : 0.4;
  meta["features"] = nlohmann::json::array();
  meta["colours"] = nlohmann::json::array();
  for (const auto f : used) {
    meta["features"].push_back(slicer::to_string(f));
    meta["colours"].push_back(hex_colour(feature_colour(f)));
  }
  if (used.empty()) meta["colours"].push_back("#888888");
  const std::string rest = meta.dump();
  return out + "]," + rest.substr(1);
}

}  // namespace

std::string render_html(const PreviewScene& scene, const std::string& title) {
  std::string page = kPage;
  std::string data = scene_json(scene);
  replace_all(data, "</", "<\\/");  // keep the JSON from closing its script element
  replace_all(page, "@TITLE@", escape_html(title));
  replace_all(page, "@DATA@", data);
  return page;
}

}  // namespace strand::post
