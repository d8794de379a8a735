"use strict";
// inbetween view: draws the figures of the embedded data (docs/formats.md, "The view page").
(function () {
  const data = JSON.parse(document.getElementById("inbetween-data").textContent);
  const $ = (id) => document.getElementById(id);

  // Base64 of little-endian floats, read as such on any platform.
  function floats(b64, size) {
    const bin = atob(b64);
    const view = new DataView(new ArrayBuffer(bin.length));
    for (let i = 0; i < bin.length; i++) view.setUint8(i, bin.charCodeAt(i));
    const n = bin.length / size;
    const out = size === 4 ? new Float32Array(n) : new Float64Array(n);
    for (let i = 0; i < n; i++) out[i] = size === 4 ? view.getFloat32(4 * i, true) : view.getFloat64(8 * i, true);
    return out;
  }

  const frames = data.frames;
  const points = data.points;
  const times = floats(data.times, 8);
  const figures = data.figures.map((f) => ({ source: f.source, pos: floats(f.positions, 4) }));
  const cmp = data.compared;
  const errors = cmp ? floats(cmp.errors, 8) : null;
  const keyed = cmp ? new Set(cmp.keyed) : new Set();
  const colours = ["#0072B2", "#D55E00"];

  const state = {
    frame: 0, playing: false, overlay: !!data.overlay, showB: true,
    az: 0, el: 0, up: data.up, speed: 1, clock: 0, last: 0,
  };
  // The initial state from the address's fragment:
  // #frame=N&b=hidden&overlay=1&view=side&up=z&az=30&el=10&play=1
  // `view` first and `az`, `el` then, in whatever order they come: they turn the view chosen.
  const fragment = new Map(location.hash.replace(/^#/, "").split("&").map((part) => part.split("=")));
  for (const [k, v] of fragment) {
    if (k === "frame" && isFinite(+v)) state.frame = Math.max(0, Math.min(frames - 1, Math.floor(+v)));
    if (k === "b") state.showB = v !== "hidden";
    if (k === "overlay") state.overlay = v === "1";
    if (k === "up" && (v === "y" || v === "z")) state.up = v;
    if (k === "view" && ["front", "side", "top"].includes(v)) { setView(v); $("view").value = v; }
    if (k === "play") state.autoplay = v === "1";
  }
  const turn = (k) => (fragment.has(k) && isFinite(+fragment.get(k)) ? (+fragment.get(k) * Math.PI) / 180 : null);
  if (turn("az") !== null) state.az = turn("az");
  if (turn("el") !== null) state.el = turn("el");

  function setView(v) {
    state.az = v === "side" ? Math.PI / 2 : 0;
    state.el = v === "top" ? Math.PI / 2 - 1e-6 : 0;
  }

  // A world point as seen: up made y, turned by the azimuth about up, tilted by the elevation.
  function project(x, y, z) {
    if (state.up === "z") { const t = y; y = z; z = -t; }
    const ca = Math.cos(state.az), sa = Math.sin(state.az);
    const x1 = ca * x - sa * z, z1 = sa * x + ca * z;
    const ce = Math.cos(state.el), se = Math.sin(state.el);
    return [x1, ce * y - se * z1];
  }

  // The scale and centre that fit the box of every figure over the clip in a panel.
  function fit(w, h) {
    const lo = data.box.min, hi = data.box.max;
    let x0 = Infinity, x1 = -Infinity, y0 = Infinity, y1 = -Infinity;
    for (let i = 0; i < 8; i++) {
      const p = project(i & 1 ? hi[0] : lo[0], i & 2 ? hi[1] : lo[1], i & 4 ? hi[2] : lo[2]);
      x0 = Math.min(x0, p[0]); x1 = Math.max(x1, p[0]);
      y0 = Math.min(y0, p[1]); y1 = Math.max(y1, p[1]);
    }
    const s = 0.9 * Math.min(w / Math.max(x1 - x0, 1e-9), h / Math.max(y1 - y0, 1e-9));
    return { s, cx: (x0 + x1) / 2, cy: (y0 + y1) / 2 };
  }

  function sized(canvas) {
    const r = window.devicePixelRatio || 1;
    const w = Math.max(1, Math.round(canvas.clientWidth * r));
    const h = Math.max(1, Math.round(canvas.clientHeight * r));
    if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
    return r;
  }

  function drawFigures() {
    const canvas = $("figures");
    const r = sized(canvas);
    const g = canvas.getContext("2d");
    g.clearRect(0, 0, canvas.width, canvas.height);
    const shown = figures.filter((_, i) => i === 0 || state.showB);
    const panels = state.overlay || shown.length === 1 ? 1 : shown.length;
    const pw = canvas.width / panels, ph = canvas.height;
    const f = fit(pw, ph);
    shown.forEach((fig, i) => {
      const ox = (state.overlay ? 0 : i) * pw + pw / 2, oy = ph / 2;
      const at = (p) => {
        const base = (state.frame * points + p) * 3;
        const q = project(fig.pos[base], fig.pos[base + 1], fig.pos[base + 2]);
        return [ox + f.s * (q[0] - f.cx), oy - f.s * (q[1] - f.cy)];
      };
      if (i === 0 || !state.overlay) floor(g, ox, oy, f, r);
      const b = figures.indexOf(fig) === 1;
      g.strokeStyle = colours[b ? 1 : 0];
      g.fillStyle = g.strokeStyle;
      // Over A, B is drawn thinner and a little transparent, so that A shows where they part.
      g.globalAlpha = b && state.overlay ? 0.85 : 1;
      g.lineWidth = (b && state.overlay ? 1.75 : 3) * r;
      g.lineCap = "round";
      g.beginPath();
      for (let p = 0; p < points; p++) {
        const from = data.point_from[p];
        if (from < 0) continue;
        const a = at(from), b = at(p);
        g.moveTo(a[0], a[1]);
        g.lineTo(b[0], b[1]);
      }
      g.stroke();
      for (let p = 0; p < points; p++) {
        const a = at(p);
        g.beginPath();
        g.arc(a[0], a[1], 2.5 * r, 0, 2 * Math.PI);
        g.fill();
      }
      g.globalAlpha = 1;
      g.font = `${13 * r}px system-ui, sans-serif`;
      const label = (i === 0 ? "A: " : "B: ") + fig.source;
      g.fillText(label, (state.overlay ? 0 : i) * pw + 8 * r, (state.overlay ? 18 + 18 * i : 18) * r);
    });
  }

  // The floor of the box (its lowest face along up), so that the panels read as one space.
  function floor(g, ox, oy, f, r) {
    const lo = data.box.min, hi = data.box.max;
    const u = state.up === "z" ? 2 : 1;
    const a = u === 1 ? 2 : 1;
    const corners = [[lo[0], lo[a]], [hi[0], lo[a]], [hi[0], hi[a]], [lo[0], hi[a]]].map(([x, o]) => {
      const p = [x, 0, 0];
      p[u] = lo[u];
      p[a] = o;
      const q = project(p[0], p[1], p[2]);
      return [ox + f.s * (q[0] - f.cx), oy - f.s * (q[1] - f.cy)];
    });
    g.strokeStyle = "#ccc";
    g.lineWidth = r;
    g.beginPath();
    corners.forEach((c, i) => (i ? g.lineTo(c[0], c[1]) : g.moveTo(c[0], c[1])));
    g.closePath();
    g.stroke();
  }

  const fmt = (x) => (x === 0 ? "0" : Math.abs(x) >= 1e4 || Math.abs(x) < 1e-3 ? x.toExponential(3) : x.toPrecision(4));
  const t0 = times[0], t1 = times[frames - 1];
  // The curve's scale: its largest value or the tolerance (1 for a curve of zeros), and a tenth
  // of headroom above.
  const scale = errors ? Math.max(cmp.largest, data.tolerance || 0) || 1 : 1;
  const top = scale * 1.1;

  function drawCurve() {
    const canvas = $("curve");
    if (!errors) { canvas.hidden = true; return; }
    const r = sized(canvas);
    const g = canvas.getContext("2d");
    const w = canvas.width, h = canvas.height;
    const left = 56 * r, right = 10 * r, above = 10 * r, below = 22 * r;
    const x = (t) => left + (t1 > t0 ? (t - t0) / (t1 - t0) : 0.5) * (w - left - right);
    const y = (v) => h - below - (v / top) * (h - above - below);
    g.clearRect(0, 0, w, h);
    g.font = `${11 * r}px system-ui, sans-serif`;
    g.fillStyle = "#666";
    g.strokeStyle = "#ddd";
    g.lineWidth = r;
    g.beginPath();
    g.moveTo(left, y(0)); g.lineTo(w - right, y(0));
    g.moveTo(left, y(scale)); g.lineTo(w - right, y(scale));
    g.stroke();
    g.fillText(fmt(scale), 4 * r, y(scale) + 4 * r);
    g.fillText("0", 4 * r, y(0) + 4 * r);
    g.fillText(`${fmt(t0)} s`, left, h - 6 * r);
    const end = `${fmt(t1)} s`;
    g.fillText(end, w - right - g.measureText(end).width, h - 6 * r);
    // B's keyed frames: ticks under the axis.
    g.strokeStyle = "#999";
    g.beginPath();
    for (const k of keyed) { g.moveTo(x(times[k]), y(0)); g.lineTo(x(times[k]), y(0) + 6 * r); }
    g.stroke();
    if (data.tolerance) {
      g.strokeStyle = "#c00";
      g.setLineDash([6 * r, 4 * r]);
      g.beginPath();
      g.moveTo(left, y(data.tolerance)); g.lineTo(w - right, y(data.tolerance));
      g.stroke();
      g.setLineDash([]);
    }
    g.strokeStyle = colours[1];
    g.lineWidth = 1.5 * r;
    g.beginPath();
    for (let k = 0; k < frames; k++) (k ? g.lineTo : g.moveTo).call(g, x(times[k]), y(Math.min(errors[k], top)));
    g.stroke();
    if (data.tolerance) {
      g.fillStyle = "#c00";
      for (let k = 0; k < frames; k++) if (errors[k] > data.tolerance) g.fillRect(x(times[k]) - 2 * r, y(Math.min(errors[k], top)) - 2 * r, 4 * r, 4 * r);
    }
    g.fillStyle = "#666";
    const legend = "world displacement per frame" + (data.tolerance ? " · dashed: tolerance" : "") + " · ticks: B's keys";
    g.fillText(legend, w - right - g.measureText(legend).width, above + 2 * r);
    g.strokeStyle = "#222";
    g.beginPath();
    g.moveTo(x(times[state.frame]), above); g.lineTo(x(times[state.frame]), y(0));
    g.stroke();
  }

  function readout() {
    // The frame from 0, as the fragment's `frame` and `diff --per-frame` number it.
    let text = `frame ${state.frame} (0–${frames - 1}) · ${fmt(times[state.frame])} s`;
    if (errors) text += ` · displacement ${fmt(errors[state.frame])}` + (keyed.has(state.frame) ? " · B keyed" : "");
    $("readout").textContent = text;
    $("slider").value = String(state.frame);
    document.body.dataset.frame = String(state.frame);
  }

  function draw() { drawFigures(); drawCurve(); readout(); }

  function facts() {
    const unit = data.unit_meters === 1 ? " m" : data.unit_meters ? ` units (1 unit = ${data.unit_meters} m)` : " units";
    const b = data.box, ext = [0, 1, 2].map((i) => fmt(b.max[i] - b.min[i])).join(" × ");
    const parts = [];
    const span = (cls, text) => { const s = document.createElement("span"); s.className = cls; s.textContent = text; return s; };
    const p = $("facts");
    p.append(span("a", "A"), `: ${figures[0].source}`);
    if (figures[1]) p.append(" · ", span("b", "B"), `: ${figures[1].source} (${cmp.keys} keys, ${keyed.size} of ${frames} frames keyed)`);
    if (cmp && cmp.b_skeleton_differs) p.append(" · B's own skeleton differs from A's: B is drawn and measured on A's");
    parts.push(`skeleton: ${data.joints.length} joints, ${points} points, height ${fmt(data.height)}${unit}, box over the clip ${ext}`);
    if (cmp) parts.push(`largest displacement ${fmt(cmp.largest)} at ${fmt(cmp.largest_time)} s` + (cmp.worst_track && cmp.largest > 0 ? ` (track ${cmp.worst_track})` : ""));
    if (data.tolerance) {
      const over = errors ? errors.filter((e) => e > data.tolerance).length : 0;
      parts.push(`tolerance ${fmt(data.tolerance)}` + (errors ? `: ${over} frame${over === 1 ? "" : "s"} beyond` : ""));
    }
    if (data.shell != null) parts.push(`shell ${fmt(data.shell)}`);
    p.append(document.createElement("br"), parts.join(" · "));
  }

  function tick(now) {
    if (!state.playing) return;
    const dt = state.last ? (now - state.last) / 1000 : 0;
    state.last = now;
    state.clock += dt * state.speed;
    if (state.clock > t1) state.clock = t0 + ((state.clock - t0) % Math.max(t1 - t0, 1e-9));
    let lo = 0, hi = frames - 1;
    while (lo < hi) { const mid = (lo + hi + 1) >> 1; if (times[mid] <= state.clock) lo = mid; else hi = mid - 1; }
    state.frame = lo;
    draw();
    requestAnimationFrame(tick);
  }

  function play(on) {
    state.playing = on;
    $("play").textContent = on ? "Pause" : "Play";
    if (on) { state.clock = times[state.frame]; state.last = 0; requestAnimationFrame(tick); }
  }

  function seek(k) { state.frame = Math.max(0, Math.min(frames - 1, k)); if (state.playing) state.clock = times[state.frame]; draw(); }

  document.title = `${data.title} · inbetween view`;
  $("title").textContent = data.title;
  facts();
  const slider = $("slider");
  slider.max = String(frames - 1);
  slider.addEventListener("input", () => seek(+slider.value));
  $("play").addEventListener("click", () => play(!state.playing));
  $("overlay").checked = state.overlay;
  $("overlay").addEventListener("change", (e) => { state.overlay = e.target.checked; draw(); });
  $("show-b").checked = state.showB;
  $("show-b").addEventListener("change", (e) => { state.showB = e.target.checked; draw(); });
  if (figures.length < 2) { $("show-b-label").hidden = true; $("overlay").parentElement.hidden = true; }
  $("speed").addEventListener("change", (e) => { state.speed = +e.target.value; });
  $("view").addEventListener("change", (e) => { setView(e.target.value); draw(); });
  $("up").value = state.up;
  $("up").addEventListener("change", (e) => { state.up = e.target.value; draw(); });
  const fig = $("figures");
  let drag = null;
  fig.addEventListener("pointerdown", (e) => { drag = [e.clientX, e.clientY, state.az, state.el]; fig.setPointerCapture(e.pointerId); });
  fig.addEventListener("pointermove", (e) => {
    if (!drag) return;
    state.az = drag[2] + (e.clientX - drag[0]) * 0.01;
    state.el = Math.max(-Math.PI / 2 + 1e-6, Math.min(Math.PI / 2 - 1e-6, drag[3] + (e.clientY - drag[1]) * 0.01));
    draw();
  });
  // A drag ends where the pointer is lifted or the browser takes it (pointercancel); touch
  // drags turn the figures and move along the curve rather than scroll (touch-action: none).
  for (const end of ["pointerup", "pointercancel"]) fig.addEventListener(end, () => { drag = null; });
  const curve = $("curve");
  const toFrame = (e) => {
    const rect = curve.getBoundingClientRect();
    const t = t0 + ((e.clientX - rect.left - 56) / Math.max(rect.width - 66, 1)) * (t1 - t0);
    let best = 0;
    for (let k = 0; k < frames; k++) if (Math.abs(times[k] - t) < Math.abs(times[best] - t)) best = k;
    seek(best);
  };
  curve.addEventListener("pointerdown", (e) => { toFrame(e); curve.setPointerCapture(e.pointerId); curve.onpointermove = toFrame; });
  for (const end of ["pointerup", "pointercancel"]) curve.addEventListener(end, () => { curve.onpointermove = null; });
  document.addEventListener("keydown", (e) => {
    if (e.target.tagName === "SELECT" || e.target.tagName === "INPUT" && e.target.type !== "range") return;
    if (e.key === " ") { e.preventDefault(); play(!state.playing); }
    if (e.key === "ArrowRight") { e.preventDefault(); seek(state.frame + 1); }
    if (e.key === "ArrowLeft") { e.preventDefault(); seek(state.frame - 1); }
  });
  window.addEventListener("resize", draw);
  // What the page computed, for a reader of its DOM (the tests): the displacement per frame as
  // JSON numbers (shortest round trip of the float64 values).
  $("values").textContent = JSON.stringify({ frames, errors: errors ? Array.from(errors) : null, keyed: Array.from(keyed) });
  window.inbetweenView = { data, times, figures, errors, state, seek, draw };
  draw();
  if (state.autoplay) play(true);
  document.body.dataset.ready = "1";
})();
