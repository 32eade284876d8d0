// Charts drawn on plain canvases: a quantity against age for every species (the grown tree
// solid, the measured equation dashed, the slider's age marked), and the year's benefits and
// costs as bars (benefits up, costs down, the net as a dot), as Linsen et al. (2005) show them.

export const QUANTITIES = {
  height: { title: 'Height', unit: 'm' },
  dbh: { title: 'Trunk diameter (DBH)', unit: 'cm' },
  crown_diameter: { title: 'Crown diameter', unit: 'm' },
  leaf_area: { title: 'Leaf area', unit: 'm²' },
};

// A rounded step for about `n` ticks over `span`.
function step(span, n) {
  const raw = span / n;
  const p = Math.pow(10, Math.floor(Math.log10(raw)));
  for (const k of [1, 2, 2.5, 5, 10]) if (raw <= k * p) return k * p;
  return 10 * p;
}

// Sizes a canvas to its width on the page at the screen's pixel ratio, keeping the aspect
// of its width and height attributes; returns the context and the size in CSS pixels.
function prepare(canvas) {
  if (!canvas.dataset.w) { canvas.dataset.w = canvas.width; canvas.dataset.h = canvas.height; }
  const ratio = window.devicePixelRatio || 1;
  const w = canvas.clientWidth || Number(canvas.dataset.w);
  const h = (w * Number(canvas.dataset.h)) / Number(canvas.dataset.w);
  const cw = Math.round(w * ratio);
  const ch = Math.round(h * ratio);
  if (canvas.width !== cw || canvas.height !== ch) { canvas.width = cw; canvas.height = ch; }
  const g = canvas.getContext('2d');
  g.setTransform(ratio, 0, 0, ratio, 0, 0);
  g.clearRect(0, 0, w, h);
  return [g, w, h];
}

// `series`: [{ colour, rows: [{age, model: {...}, measured: {...}}] }].
export function lineChart(canvas, quantity, series, age) {
  const [g, w, h] = prepare(canvas);
  const q = QUANTITIES[quantity];
  const pad = { l: 40, r: 8, t: 20, b: 22 };
  let maxAge = 1, maxV = 0;
  for (const s of series) for (const r of s.rows) {
    maxAge = Math.max(maxAge, r.age);
    maxV = Math.max(maxV, r.model[quantity], r.measured[quantity]);
  }
  maxV = maxV > 0 ? maxV * 1.08 : 1;
  const X = (a) => pad.l + (a / maxAge) * (w - pad.l - pad.r);
  const Y = (v) => h - pad.b - (v / maxV) * (h - pad.t - pad.b);
  g.font = '11px system-ui, sans-serif';
  g.fillStyle = '#1f2a1f';
  g.fillText(`${q.title}, ${q.unit}`, pad.l, 13);
  g.strokeStyle = '#d5dbcf';
  g.fillStyle = '#66705f';
  g.lineWidth = 1;
  const vs = step(maxV, 4);
  for (let v = 0; v <= maxV; v += vs) {
    g.beginPath(); g.moveTo(pad.l, Y(v)); g.lineTo(w - pad.r, Y(v)); g.stroke();
    g.fillText(String(+v.toFixed(2)), 4, Y(v) + 4);
  }
  const as = step(maxAge, 5);
  for (let a = 0; a <= maxAge; a += as) g.fillText(String(a), X(a) - 6, h - 6);
  for (const s of series) {
    for (const [key, dash] of [['measured', [4, 3]], ['model', []]]) {
      g.setLineDash(dash);
      g.strokeStyle = s.colour;
      g.lineWidth = key === 'model' ? 2 : 1.3;
      g.beginPath();
      s.rows.forEach((r, i) => (i ? g.lineTo : g.moveTo).call(g, X(r.age), Y(r[key][quantity])));
      g.stroke();
    }
  }
  g.setLineDash([]);
  if (age != null) {
    g.strokeStyle = '#000';
    g.lineWidth = 1;
    g.beginPath(); g.moveTo(X(age), pad.t); g.lineTo(X(age), h - pad.b); g.stroke();
  }
}

// What the bars show of a year's account (`street` in the growth rows): every item of the
// library's one table of account items (`sylva::street::accounts::items`, served as
// /api/items), benefits keyed in `value_usd` and costs in `cost_usd`. A negative benefit (a
// winter heating penalty, BVOCs emitted) is drawn below the line.
// Asked once, as the module loads; nothing waits on it but the bars, which are drawn when it
// has come (a page's module graph is not held up by it).
let BENEFITS = [];
let COSTS = [];
const itemsReady = fetch('/api/items')
  .then((r) => {
    if (!r.ok) throw new Error(`/api/items: HTTP ${r.status}`);
    return r.json();
  })
  .then((items) => {
    BENEFITS = items.filter((i) => i.side === 'benefit').map((i) => [i.key, i.label, i.colour]);
    COSTS = items.filter((i) => i.side === 'cost').map((i) => [i.key, i.label, i.colour, i.payer]);
  });

// `items`: [{ label, colour, street }].
export function barChart(canvas, items) {
  if (!BENEFITS.length) {
    itemsReady.then(() => barChart(canvas, items));
    return;
  }
  const [g, w, h] = prepare(canvas);
  const pad = { l: 46, r: 150, t: 10, b: 22 };
  let top = 1, bottom = 1;
  const stacks = items.map((it) => {
    const v = it.street.value_usd || {};
    const c = it.street.cost_usd || {};
    const up = BENEFITS.map(([k, , col]) => [v[k] ?? 0, col]);
    const down = COSTS.map(([k, , col]) => [c[k] ?? 0, col]);
    const pos = up.filter(([x]) => x > 0).reduce((a, [x]) => a + x, 0);
    const neg = up.filter(([x]) => x < 0).reduce((a, [x]) => a - x, 0) + down.reduce((a, [x]) => a + x, 0);
    top = Math.max(top, pos); bottom = Math.max(bottom, neg, -it.street.net_usd);
    return { up, down, net: it.street.net_usd, label: it.label, colour: it.colour };
  });
  const span = top + bottom;
  const Y = (v) => pad.t + ((top - v) / span) * (h - pad.t - pad.b);
  const slot = (w - pad.l - pad.r) / Math.max(1, stacks.length);
  g.font = '11px system-ui, sans-serif';
  g.strokeStyle = '#d5dbcf';
  g.fillStyle = '#66705f';
  const vs = step(span, 5);
  for (let v = -Math.floor(bottom / vs) * vs; v <= top; v += vs) {
    g.beginPath(); g.moveTo(pad.l, Y(v)); g.lineTo(w - pad.r, Y(v)); g.stroke();
    g.fillText(`$${Math.round(v)}`, 2, Y(v) + 4);
  }
  g.strokeStyle = '#333';
  g.beginPath(); g.moveTo(pad.l, Y(0)); g.lineTo(w - pad.r, Y(0)); g.stroke();
  stacks.forEach((s, i) => {
    const x = pad.l + i * slot + slot * 0.2;
    const bw = slot * 0.6;
    let upTo = 0, downTo = 0;
    for (const [v, col] of s.up) {
      g.fillStyle = col;
      if (v > 0) { g.fillRect(x, Y(upTo + v), bw, Y(upTo) - Y(upTo + v)); upTo += v; }
      else if (v < 0) { g.fillRect(x, Y(downTo), bw, Y(downTo + v) - Y(downTo)); downTo += v; }
    }
    for (const [v, col] of s.down) {
      if (v <= 0) continue;
      g.fillStyle = col;
      g.fillRect(x, Y(downTo), bw, Y(downTo - v) - Y(downTo));
      downTo -= v;
    }
    g.fillStyle = '#000';
    g.beginPath(); g.arc(x + bw / 2, Y(s.net), 4, 0, 2 * Math.PI); g.fill();
    g.fillText(`net $${Math.round(s.net)}`, x + bw / 2 + 6, Y(s.net) + 4);
    g.fillStyle = s.colour;
    g.fillRect(x, h - 14, 10, 10);
    g.fillStyle = '#1f2a1f';
    g.fillText(s.label, x + 14, h - 5);
  });
  // Key.
  let ky = pad.t + 4;
  for (const [, label, col] of [...BENEFITS, ...COSTS]) {
    g.fillStyle = col;
    g.fillRect(w - pad.r + 10, ky, 10, 10);
    g.fillStyle = '#1f2a1f';
    g.fillText(label, w - pad.r + 24, ky + 9);
    ky += 15;
  }
}
