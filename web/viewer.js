// Strand's 3D toolpath viewer (issue 34): three.js over the layer blocks of
// postprocess/preview/viewer_data.h. Bundled with three.js by esbuild at build time and
// embedded in the strand binary: `strand serve` serves it at /assets/viewer.js for
// /view/{id}, `strand preview -o x.html` inlines it with the data. No network but the
// server's own API.
//
// The page holds <div id="viewer">, with either data-index="/api/jobs/N/view" (layers from
// data-index + "/layers?from=A&to=B") or the inline scripts #strand-view-index (JSON) and
// #strand-view-blocks (base64 of every layer's block).
import * as THREE from "three";
import { OrbitControls } from "three/addons/controls/OrbitControls.js";

const TRAVEL = 128;
const CHUNK_BYTES = 16 << 20;  // at most this much per request for layers

const css = `
#viewer{display:flex;gap:12px;align-items:stretch;min-height:0}
#viewer .sv-canvas{flex:1 1 auto;min-width:0;position:relative;background:#f4f5f7;border:1px solid #ccd;min-height:420px}
#viewer .sv-canvas canvas{display:block;width:100%;height:100%}
#viewer .sv-side{flex:0 0 290px;display:flex;flex-direction:column;gap:6px;font:13px/1.4 system-ui,sans-serif}
#viewer .sv-side label{display:flex;flex-direction:column;gap:2px}
#viewer .sv-side input[type=range]{width:100%}
#viewer .sv-row{display:flex;gap:14px;align-items:center;flex-wrap:wrap}
#viewer .sv-row label{flex-direction:row;align-items:center;gap:4px}
#viewer table{border-collapse:collapse;width:100%}
#viewer th{text-align:left;font-weight:normal;color:#555;padding:1px 6px 1px 0}
#viewer td{text-align:right;font-variant-numeric:tabular-nums}
#viewer .sv-legend span{display:inline-block;width:10px;height:10px;margin:0 4px 0 8px;vertical-align:-1px}
#viewer .sv-legend{font-size:12px}
#viewer #status{color:#555;font-size:12px}
@media (max-width:720px){#viewer{flex-direction:column}#viewer .sv-side{flex:none}#viewer .sv-canvas{min-height:320px}}
`;

function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  for (const c of children) e.append(c);
  return e;
}

// Where the data comes from: the server, or the page itself.
function serverSource(indexUrl) {
  return {
    async index() {
      const r = await fetch(indexUrl);
      const j = await r.json();
      if (!r.ok) throw new Error(j.error || r.statusText);
      return j;
    },
    async layers(from, to) {
      const r = await fetch(`${indexUrl}/layers?from=${from}&to=${to}`);
      if (!r.ok) throw new Error((await r.json()).error || r.statusText);
      return r.arrayBuffer();
    },
  };
}

function inlineSource(indexScript, blocksScript) {
  let all = null;
  return {
    async index() { return JSON.parse(indexScript.textContent); },
    async layers(from, to) {
      if (!all) {
        const text = atob(blocksScript.textContent.replace(/\s+/g, ""));
        all = new Uint8Array(text.length);
        for (let i = 0; i < text.length; ++i) all[i] = text.charCodeAt(i);
      }
      const L = this.idx.layers;
      return all.buffer.slice(L[from].offset, L[to].offset + L[to].bytes);
    },
  };
}

// One layer's block (viewer_data.h) as typed arrays over `buffer` from byte `at`.
function decodeBlock(buffer, at, n) {
  return {
    n,
    pos: new Float32Array(buffer, at, 6 * n),
    feed: new Float32Array(buffer, at + 24 * n, n),
    flow: new Float32Array(buffer, at + 28 * n, n),
    line: new Uint32Array(buffer, at + 32 * n, n),
    kind: new Uint8Array(buffer, at + 36 * n, n),
    tool: new Uint8Array(buffer, at + 37 * n, n),
  };
}

function fmt(v, digits) { return Number(v).toFixed(digits); }
function duration(s) {
  s = Math.round(s);
  return s >= 3600 ? `${Math.floor(s / 3600)}h ${Math.floor(s / 60) % 60}m ${s % 60}s`
       : s >= 60 ? `${Math.floor(s / 60)}m ${s % 60}s` : `${s} s`;
}
// Blue (slow, little) to red (fast, much).
function ramp(t, out, o) {
  t = Math.min(1, Math.max(0, t));
  out[o] = 40 + 215 * t;
  out[o + 1] = 80 + 120 * (1 - Math.abs(2 * t - 1));
  out[o + 2] = 240 - 200 * t;
}

class Viewer {
  constructor(root, source) {
    this.root = root;
    this.source = source;
    this.t0 = performance.now();
    this.build();
  }

  build() {
    document.head.append(el("style", {}, css));
    const c = (this.canvasBox = el("div", { class: "sv-canvas" }));
    const side = el("div", { class: "sv-side" });
    this.from = el("input", { type: "range", id: "layer-from", min: 0, max: 0, value: 0, "aria-label": "first layer shown" });
    this.to = el("input", { type: "range", id: "layer-to", min: 0, max: 0, value: 0, "aria-label": "last layer shown" });
    this.move = el("input", { type: "range", id: "move", min: 0, max: 0, value: 0, "aria-label": "move within the last layer" });
    this.colour = el("select", { id: "colour" },
      el("option", { value: "feature" }, "feature"), el("option", { value: "speed" }, "speed"),
      el("option", { value: "flow" }, "flow (E per mm)"));
    this.travel = el("input", { type: "checkbox", id: "travel" });
    this.fromLabel = el("span", { id: "from-label" });
    this.toLabel = el("span", { id: "to-label" });
    this.moveLabel = el("span", { id: "move-label" });
    this.stats = el("table", { id: "stats" });
    this.legend = el("div", { class: "sv-legend", id: "legend" });
    this.status = el("div", { id: "status" }, "loading...");
    side.append(
      el("label", {}, el("span", {}, "from layer ", this.fromLabel), this.from),
      el("label", {}, el("span", {}, "to layer ", this.toLabel), this.to),
      el("label", {}, el("span", {}, "move ", this.moveLabel), this.move),
      el("div", { class: "sv-row" }, el("label", {}, "colour by", this.colour),
         el("label", {}, this.travel, "travel moves")),
      this.legend, this.stats, this.status);
    this.root.append(c, side);
    for (const e of [this.from, this.to]) e.addEventListener("input", () => this.onLayers(e));
    this.move.addEventListener("input", () => this.update());
    this.colour.addEventListener("change", () => { this.paint(); this.update(); });
    this.travel.addEventListener("change", () => this.update());
  }

  async load() {
    const idx = (this.idx = this.source.idx = await this.source.index());
    const L = idx.layers;
    this.blocks = new Array(L.length);
    for (let a = 0; a < L.length;) {
      let b = a;
      while (b + 1 < L.length && L[b + 1].offset + L[b + 1].bytes - L[a].offset <= CHUNK_BYTES) ++b;
      this.status.textContent = `loading layers ${a}-${b} of ${L.length}...`;
      const buf = await this.source.layers(a, b);
      for (let l = a; l <= b; ++l) this.blocks[l] = decodeBlock(buf, L[l].offset - L[a].offset, L[l].segments);
      a = b + 1;
    }
    this.setupScene();
    this.from.max = this.to.max = L.length - 1;
    this.to.value = L.length - 1;
    this.onLayers(this.to);
  }

  // Deposits and travels each in one geometry, layer after layer, so a layer range is a
  // draw range; starts[l] is layer l's first segment in each.
  setupScene() {
    const idx = this.idx;
    let nd = 0, nt = 0;
    for (const b of this.blocks) for (let i = 0; i < b.n; ++i) (b.kind[i] & TRAVEL) ? ++nt : ++nd;
    const make = (n) => ({ pos: new Float32Array(6 * n), col: new Uint8Array(6 * n), starts: [] });
    const dep = (this.dep = make(nd)), trav = (this.trav = make(nt));
    let d = 0, t = 0;
    for (const b of this.blocks) {
      dep.starts.push(d); trav.starts.push(t);
      for (let i = 0; i < b.n; ++i) {
        const into = (b.kind[i] & TRAVEL) ? trav : dep;
        const k = into === dep ? d++ : t++;
        into.pos.set(b.pos.subarray(6 * i, 6 * i + 6), 6 * k);
      }
    }
    dep.starts.push(d); trav.starts.push(t);
    // Multisampling only for small files: software WebGL (headless, no GPU) draws a million
    // segments several times slower with it.
    const r = (this.renderer = new THREE.WebGLRenderer({ antialias: idx.segments <= 200000, preserveDrawingBuffer: true }));
    r.setPixelRatio(window.devicePixelRatio || 1);
    this.canvasBox.append(r.domElement);
    const scene = (this.scene = new THREE.Scene());
    scene.background = new THREE.Color(0xf4f5f7);
    const lines = (g, colour) => {
      const geo = new THREE.BufferGeometry();
      geo.setAttribute("position", new THREE.BufferAttribute(g.pos, 3));
      geo.setAttribute("color", new THREE.BufferAttribute(g.col, 3, true));
      const m = new THREE.LineSegments(geo, new THREE.LineBasicMaterial({ vertexColors: true }));
      m.frustumCulled = false;
      scene.add(m);
      g.geo = geo; g.mesh = m;
      if (colour) g.col.fill(colour);
    };
    lines(dep);
    lines(trav, 170);
    const [lo, hi] = [new THREE.Vector3(...idx.bounds.min), new THREE.Vector3(...idx.bounds.max)];
    const centre = lo.clone().add(hi).multiplyScalar(0.5);
    const size = Math.max(hi.clone().sub(lo).length(), 1);
    // The substrate, or a slice's part, translucent and not writing depth: the paths inside
    // and behind it stay visible.
    const translucent = (m, opacity) => {
      const g = new THREE.BufferGeometry();
      g.setAttribute("position", new THREE.Float32BufferAttribute(m.v, 3));
      g.setIndex(m.t);
      g.computeVertexNormals();
      const mesh = new THREE.Mesh(g, new THREE.MeshLambertMaterial({ color: 0x8899aa, transparent: true, opacity, depthWrite: false, side: THREE.DoubleSide }));
      scene.add(mesh, new THREE.AmbientLight(0xffffff, 1.5), new THREE.DirectionalLight(0xffffff, 1.5));
      return mesh;
    };
    if (idx.part) {  // with a check box to take it away
      const part = translucent(idx.part, 0.2);  // lighter: the paths fill it
      const box = el("input", { type: "checkbox", id: "part-mesh", checked: "" });
      box.addEventListener("change", () => { part.visible = box.checked; this.render(); });
      this.travel.parentElement.after(el("label", {}, box, "part mesh"));
    }
    if (idx.substrate) {
      translucent(idx.substrate, 0.3);
    } else {  // the bed: a grid under the part
      const grid = new THREE.GridHelper(size * 1.2, 12, 0xb0b4bc, 0xd4d7dd);
      grid.rotation.x = Math.PI / 2;
      grid.position.set(centre.x, centre.y, lo.z);
      scene.add(grid);
    }
    this.nozzle = new THREE.Mesh(new THREE.SphereGeometry(Math.max(size / 150, 0.2), 12, 8), new THREE.MeshBasicMaterial({ color: 0x000000 }));
    scene.add(this.nozzle);
    const cam = (this.camera = new THREE.PerspectiveCamera(40, 1, size / 1000, size * 20));
    cam.up.set(0, 0, 1);
    cam.position.copy(centre).add(new THREE.Vector3(0.4, -0.75, 0.7).multiplyScalar(size));
    this.controls = new OrbitControls(cam, r.domElement);
    this.controls.target.copy(centre);
    this.controls.update();
    this.controls.addEventListener("change", () => this.render());
    new ResizeObserver(() => this.resize()).observe(this.canvasBox);
    this.resize();
    this.paint();
  }

  resize() {
    const w = this.canvasBox.clientWidth, h = this.canvasBox.clientHeight;
    if (!w || !h) return;
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.render();
  }

  // Deposit colours by the chosen mode; the legend says what they mean.
  paint() {
    if (!this.dep) return;
    const idx = this.idx, mode = this.colour.value, col = this.dep.col;
    const fc = idx.feature_colours.map((h) => [1, 3, 5].map((i) => parseInt(h.substr(i, 2), 16)));
    const rgb = [0, 0, 0];
    const used = new Set(), usedPens = new Set();
    const penCode = idx.features.indexOf("pen");
    const pens = idx.pens && idx.pens.map((p) => [1, 3, 5].map((i) => parseInt(p.colour.substr(i, 2), 16)));
    let k = 0;
    for (const b of this.blocks) {
      for (let i = 0; i < b.n; ++i) {
        if (b.kind[i] & TRAVEL) continue;
        if (mode === "feature") {
          const pen = pens && b.kind[i] === penCode;
          const c = (pen ? pens[Math.min(b.tool[i], pens.length - 1)] : fc[b.kind[i]]) || [0, 0, 0];
          if (pen) usedPens.add(Math.min(b.tool[i], pens.length - 1));
          rgb[0] = c[0]; rgb[1] = c[1]; rgb[2] = c[2];
          used.add(b.kind[i]);
        } else if (mode === "speed") {
          ramp(idx.feed_max > 0 ? b.feed[i] / idx.feed_max : 0, rgb, 0);
        } else {
          ramp(idx.flow_max > 0 ? b.flow[i] / idx.flow_max : 0, rgb, 0);
        }
        col.set(rgb, 6 * k); col.set(rgb, 6 * k + 3);
        ++k;
      }
    }
    this.dep.geo.attributes.color.needsUpdate = true;
    this.legend.replaceChildren();
    const key = (c, text) => this.legend.append(el("span", { style: `background:${c}` }), text);
    if (mode === "feature") {
      for (const f of [...used].sort((a, b) => a - b)) {
        if (pens && f === penCode) for (const p of [...usedPens].sort((a, b) => a - b)) key(idx.pens[p].colour, idx.pens[p].name);
        else key(idx.feature_colours[f], idx.features[f]);
      }
    } else {
      const max = mode === "speed" ? `${fmt(idx.feed_max, 0)} mm/min` : `${fmt(idx.flow_max, 4)} E/mm`;
      key("rgb(40,80,240)", "0"); key("rgb(255,80,40)", max);
    }
  }

  onLayers(moved) {
    let a = +this.from.value, b = +this.to.value;
    if (a > b) { if (moved === this.from) this.to.value = b = a; else this.from.value = a = b; }
    this.move.max = this.blocks[b].n;
    this.move.value = this.blocks[b].n;
    this.update();
  }

  // Draw ranges for layers [from, to) plus the first `move` segments of layer `to`.
  update() {
    if (!this.dep) return;
    const a = +this.from.value, b = +this.to.value, m = +this.move.value, blk = this.blocks[b];
    let nd = 0, nt = 0;
    for (let i = 0; i < m; ++i) (blk.kind[i] & TRAVEL) ? ++nt : ++nd;
    const range = (g, extra) => g.geo.setDrawRange(2 * g.starts[a], 2 * (g.starts[b] - g.starts[a] + extra));
    range(this.dep, nd);
    range(this.trav, nt);
    this.trav.mesh.visible = this.travel.checked;
    const L = this.idx.layers, lb = L[b], v = this.idx.layer_value;
    this.fromLabel.textContent = `${a} (${v} ${fmt(L[a].z, 3)} mm)`;
    this.toLabel.textContent = `${b} (${v} ${fmt(lb.z, 3)} mm)`;
    this.moveLabel.textContent = `${m} of ${blk.n}`;
    if (m > 0) {
      const i = m - 1;
      this.nozzle.position.set(blk.pos[6 * i + 3], blk.pos[6 * i + 4], blk.pos[6 * i + 5]);
      this.moveLabel.textContent += ` (line ${blk.line[i]}, ${(blk.kind[i] & TRAVEL) ? "travel" : this.idx.features[blk.kind[i]]}` +
        (blk.feed[i] > 0 ? `, F${fmt(blk.feed[i], 0)}` : "") + (blk.flow[i] > 0 ? `, ${fmt(blk.flow[i], 5)} E/mm` : "") + ")";
    }
    this.nozzle.visible = m > 0 && m < blk.n;
    let strands = 0, len = 0, time = 0, e = 0;
    for (let l = a; l <= b; ++l) { strands += L[l].strands; len += L[l].deposit_length_mm; time += L[l].time_s; e += L[l].e; }
    const row = (id, name, one, all) => el("tr", {}, el("th", {}, name), el("td", { id }, one), el("td", {}, all));
    this.stats.replaceChildren(
      el("tr", {}, el("th", {}, ""), el("td", {}, `layer ${b}`), el("td", {}, a === b ? "" : `layers ${a}-${b}`)),
      row("stat-z", v, `${fmt(lb.z, 3)} mm`, ""),
      row("stat-moves", "moves", String(lb.moves), ""),
      row("stat-strands", "strands", String(lb.strands), a === b ? "" : String(strands)),
      row("stat-length", "length", `${fmt(lb.deposit_length_mm, 1)} mm`, a === b ? "" : `${fmt(len, 1)} mm`),
      row("stat-time", `time (${this.idx.time})`, duration(lb.time_s), a === b ? "" : duration(time)),
      // a valve or pressure machine writes no E: say so rather than show 0
      this.idx.flow_max > 0 ? row("stat-e", "E", fmt(lb.e, 3), a === b ? "" : fmt(e, 3))
        : row("stat-e", "E", "none", a === b ? "" : "(no E in this file)"));
    this.render();
  }

  // One frame per animation frame however many changes asked for it; `firstFrame` resolves
  // when the first one is on the screen (read back, so the GPU has finished it).
  render() {
    if (!this.renderer || this.pending) return;
    this.pending = true;
    requestAnimationFrame(() => {
      this.pending = false;
      this.renderer.render(this.scene, this.camera);
      if (this.onFrame) {
        const gl = this.renderer.getContext();
        gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
        this.onFrame();
        this.onFrame = null;
      }
    });
  }
}

async function main() {
  const root = document.getElementById("viewer");
  if (!root) return;
  const url = root.dataset.index;
  const source = url ? serverSource(url)
    : inlineSource(document.getElementById("strand-view-index"), document.getElementById("strand-view-blocks"));
  const v = new Viewer(root, source);
  window.strandViewer = v;
  try {
    const frame = new Promise((resolve) => { v.onFrame = resolve; });
    await v.load();
    await frame;
    const ms = performance.now() - v.t0;
    v.status.textContent = `drawn: ${v.idx.segments} segments, layers 0-${v.idx.layers.length - 1} in ${Math.round(ms)} ms` +
      (v.idx.part_note ? `; ${v.idx.part_note}` : "");
    v.status.dataset.ms = String(Math.round(ms));
  } catch (e) {
    v.status.textContent = `error: ${e.message}`;
  }
}

main();
