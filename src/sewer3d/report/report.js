// The report's map views (embedded into index.html at build time): the texture and the heat
// map as zoomable, pannable canvases sharing one view, with station (m) and clock (h) axes.
(function () {
  'use strict';
  const metaElement = document.getElementById('map-data');
  if (!metaElement) return;
  const meta = JSON.parse(metaElement.textContent);
  const left = 44, bottom = 22;
  let view = { u0: 0, u1: 1, v0: 0, v1: 1 };  // visible part of the pictures, 0..1

  const stationM = (u) => (meta.station0_mm + u * (meta.station1_mm - meta.station0_mm)) / 1000;
  const clockH = (v) => v * meta.turn_fraction * 12;

  function niceStep(span, count, steps) {
    const raw = span / count;
    for (const s of steps) if (s >= raw) return s;
    const decade = Math.pow(10, Math.floor(Math.log10(raw)));
    for (const m of [1, 2, 5, 10]) if (m * decade >= raw) return m * decade;
    return raw;
  }

  function draw(canvas, image) {
    const dpr = window.devicePixelRatio || 1;
    const w = canvas.clientWidth, h = canvas.clientHeight;
    if (canvas.width !== Math.round(w * dpr)) canvas.width = Math.round(w * dpr);
    if (canvas.height !== Math.round(h * dpr)) canvas.height = Math.round(h * dpr);
    const g = canvas.getContext('2d');
    g.setTransform(dpr, 0, 0, dpr, 0, 0);
    g.fillStyle = '#fff';
    g.fillRect(0, 0, w, h);
    const pw = w - left, ph = h - bottom;
    const sx = view.u0 * image.naturalWidth, sw = (view.u1 - view.u0) * image.naturalWidth;
    const sy = view.v0 * image.naturalHeight, sh = (view.v1 - view.v0) * image.naturalHeight;
    g.imageSmoothingEnabled = pw / sw < 3;
    g.drawImage(image, sx, sy, sw, sh, left, 0, pw, ph);
    g.fillStyle = '#222';
    g.strokeStyle = '#222';
    g.font = '11px sans-serif';
    const s0 = stationM(view.u0), s1 = stationM(view.u1);
    const ss = niceStep(s1 - s0, 10, []);
    g.textAlign = 'center';
    for (let s = Math.ceil(s0 / ss) * ss; s <= s1; s += ss) {
      const x = left + (s - s0) / (s1 - s0) * pw;
      if (x > w - 24) continue;
      g.fillRect(x, ph, 1, 4);
      g.fillText(s.toFixed(Math.max(0, -Math.floor(Math.log10(ss) + 1e-9))), x, ph + 15);
    }
    const c0 = clockH(view.v0), c1 = clockH(view.v1);
    const cs = niceStep(c1 - c0, 8, [0.25, 0.5, 1, 2, 3, 6]);
    g.textAlign = 'right';
    for (let c = Math.ceil(c0 / cs) * cs; c <= c1; c += cs) {
      const y = (c - c0) / (c1 - c0) * ph;
      g.fillRect(left - 4, y, 4, 1);
      const label = c % 12 === 0 ? 12 : c % 12;
      g.fillText(label + ' h', left - 6, Math.min(Math.max(y + 4, 10), ph));
    }
    g.textAlign = 'left';
    g.fillText('m', w - 12, ph + 15);
  }

  const views = [];
  const redraw = () => views.forEach((v) => v.image.complete && draw(v.canvas, v.image));

  function toView(canvas, event) {  // mouse → picture coordinates (0..1)
    const r = canvas.getBoundingClientRect();
    const fx = (event.clientX - r.left - left) / (r.width - left);
    const fy = (event.clientY - r.top) / (r.height - bottom);
    return { u: view.u0 + fx * (view.u1 - view.u0), v: view.v0 + fy * (view.v1 - view.v0), fx, fy };
  }

  function clampView() {
    const du = Math.min(1, view.u1 - view.u0), dv = Math.min(1, view.v1 - view.v0);
    view.u0 = Math.min(Math.max(view.u0, 0), 1 - du); view.u1 = view.u0 + du;
    view.v0 = Math.min(Math.max(view.v0, 0), 1 - dv); view.v1 = view.v0 + dv;
  }

  function attach(canvas) {
    let drag = null;
    canvas.addEventListener('wheel', (e) => {
      e.preventDefault();
      const p = toView(canvas, e);
      const k = Math.pow(1.2, e.deltaY / 100);
      const du = Math.max((view.u1 - view.u0) * k, 1e-4), dv = Math.max((view.v1 - view.v0) * k, 1e-4);
      view = { u0: p.u - p.fx * du, u1: p.u - p.fx * du + du, v0: p.v - p.fy * dv, v1: p.v - p.fy * dv + dv };
      clampView();
      redraw();
    }, { passive: false });
    canvas.addEventListener('mousedown', (e) => { drag = { x: e.clientX, y: e.clientY, view: { ...view } }; });
    window.addEventListener('mouseup', () => { drag = null; });
    canvas.addEventListener('mousemove', (e) => {
      const p = toView(canvas, e);
      const readout = document.getElementById('map-readout');
      if (readout && p.fx >= 0 && p.fy >= 0 && p.fy <= 1) {
        const c = clockH(p.v) % 12;
        readout.textContent = 'station ' + stationM(p.u).toFixed(3) + ' m, clock ' +
          (c < 0.05 ? 12 : c).toFixed(1) + ' h';
      }
      if (!drag) return;
      const r = canvas.getBoundingClientRect();
      const du = (e.clientX - drag.x) / (r.width - left) * (drag.view.u1 - drag.view.u0);
      const dv = (e.clientY - drag.y) / (r.height - bottom) * (drag.view.v1 - drag.view.v0);
      view = { u0: drag.view.u0 - du, u1: drag.view.u1 - du, v0: drag.view.v0 - dv, v1: drag.view.v1 - dv };
      clampView();
      redraw();
    });
    canvas.addEventListener('dblclick', () => { view = { u0: 0, u1: 1, v0: 0, v1: 1 }; redraw(); });
  }

  for (const box of document.querySelectorAll('.mapview')) {
    const canvas = box.querySelector('canvas'), image = box.querySelector('img');
    views.push({ canvas, image });
    attach(canvas);
    image.addEventListener('load', redraw);
  }
  window.addEventListener('resize', redraw);
  redraw();
})();
