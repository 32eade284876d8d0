// The page: a region, up to four species, a site and an age; the trees drawn side by side at
// that age, their growth charts, the year's table, benefit and cost bars, the site's
// conflicts, and downloads. Everything comes from the JSON API under /api/.
//
// Timings the browser test reads are kept in `window.sylva`: when the first trees were drawn
// (ms since navigation started) and, for each age drawn, how long after the slider stopped.

import * as THREE from '/vendor/three.min.js';
import { Street } from '/scene.js';
import { QUANTITIES, lineChart, barChart } from '/charts.js';
import { ask, askJson, waitingText } from '/ask.js';

const COLOURS = ['#2f7d4f', '#c0612b', '#3b6fb6', '#8e4fa8'];
// Detail levels of /api/tree.glb: 0 every twig and leaf; each next level about half the
// triangles, leaf area kept (Weber & Penn's degradation); the last, each crown drawn as one
// closed surface out to its outer leaves (a leaf shell), which a computer drawing WebGL on its
// CPU fills several times faster than separate leaves. The page starts at the coarsest, so
// that the first trees come quickly, and moves one level at a time to keep a frame within
// FRAME_MS: a GPU soon draws the whole trees, a computer drawing WebGL on its CPU a thinner
// crown that still turns smoothly. A level found too slow is not gone back to (`floor`), so
// the page does not swing between two levels.
const DETAIL_NAMES = ['every twig and leaf', 'half the twigs and leaves', 'a quarter of the twigs and leaves',
  'an eighth of the twigs and leaves', 'leaf shells (each crown one surface, out to its outer leaves)'];
const COARSEST = DETAIL_NAMES.length - 1;
const FRAME_MS = [25, 100];
// `?detail=N` in the address pins the level (0 to COARSEST): for a computer whose frame times
// mislead, and for the browser test to time one level.
const PINNED = (() => {
  const d = Number(new URLSearchParams(location.search).get('detail') ?? NaN);
  return Number.isInteger(d) && d >= 0 && d <= COARSEST ? d : null;
})();
let detail = PINNED ?? COARSEST;
let floor = 0;
const MAX_SPECIES = 4;
const $ = (id) => document.getElementById(id);

const timing = { firstTreeMs: null, ageDraws: [], requests: 0, tables: 0, shownAge: null };
window.sylva = timing;

const state = {
  regions: [], species: [], sites: [],
  region: 'InlVal', site: 'narrow', chosen: [], age: 20,
  // 'typical': i-Tree Streets' figures at the grown DBH, at its usual positions around
  // buildings (the site menu's first choice); 'site': the grown tree's own on `site`.
  basis: 'typical',
  // Whether the site's pruning regime cuts the trees (on a site only: the typical position
  // has no street to prune for).
  pruning: true,
  growth: new Map(),   // code -> growth JSON (all ages)
};

// The tree the page asks for: cut by the site's pruning cycles, or never cut.
function treeQuery(extra) {
  const cut = state.basis === 'site' && state.pruning;
  return query({ site: state.site, pruning: cut ? 'on' : 'off', ...extra });
}

// The account the table and bars show: the typical position's, with the year's costs, or the
// grown tree's own on the site.
function account(st) {
  if (state.basis !== 'typical' || !st.typical) return st;
  return {
    ...st, value_usd: st.typical.value_usd, net_usd: st.typical.net_usd,
    planted_net_usd: st.typical.planted_net_usd, conflicts: [],
  };
}
const street = new Street($('scene'));
window.sylvaStreet = street;
const loader = new THREE.GLTFLoader();
const glbs = new Map();  // url -> Promise of a glTF scene (the last 40 kept)

async function getJson(url) {
  timing.requests++;
  return askJson(url, waitBusy);
}

// The server is busy with n growths: the page says so (see ask.js).
function waitBusy(n) {
  status(waitingText(n));
  timing.waits = (timing.waits ?? 0) + 1;
}

// Answers asked for before they are needed (the page's first species list and growth tables
// go out at once with its first trees), each handed over once.
const early = new Map();
function askEarly(url) { early.set(url, getJson(url)); }
function json(url) {
  const asked = early.get(url);
  if (!asked) return getJson(url);
  early.delete(url);
  return asked;
}

function query(extra) {
  const p = new URLSearchParams({ region: state.region, ...extra });
  return p.toString();
}

function status(text) { $('status').textContent = text || ''; }

// ---- choosing -------------------------------------------------------------------------

async function chooseRegion(code, keep) {
  state.region = code;
  state.species = await json(`/api/species?${query({})}`);
  const known = new Set(state.species.map((s) => s.code));
  state.chosen = (keep || state.chosen).filter((c) => known.has(c));
  if (state.chosen.length === 0) state.chosen = state.species.slice(0, 2).map((s) => s.code);
  state.growth.clear();
  await refresh();
}

function renderChips() {
  const box = $('chosen');
  box.textContent = '';
  state.chosen.forEach((code, i) => {
    const s = state.species.find((x) => x.code === code);
    const chip = document.createElement('span');
    chip.className = 'chip';
    chip.style.background = COLOURS[i];
    chip.title = `${s.scientific} (${s.code}), data for ages ${s.ages[0]} to ${s.ages[1]}`;
    chip.append(s.common);
    const x = document.createElement('button');
    x.type = 'button';
    x.textContent = '×';
    x.setAttribute('aria-label', `Remove ${s.common}`);
    x.onclick = () => { state.chosen.splice(i, 1); refresh(); };
    chip.append(x);
    box.append(chip);
  });
  $('search').disabled = state.chosen.length >= MAX_SPECIES;
  $('search').placeholder = state.chosen.length >= MAX_SPECIES
    ? 'Four species at most: remove one to add another'
    : 'Add a species: common or scientific name, or code';
}

function searchMatches(text) {
  const t = text.trim().toLowerCase();
  if (!t) return [];
  return state.species.filter((s) => !state.chosen.includes(s.code) &&
    (s.common.toLowerCase().includes(t) || s.scientific.toLowerCase().includes(t) ||
     s.code.toLowerCase() === t || s.code.toLowerCase().startsWith(t))).slice(0, 30);
}

function showMatches() {
  const list = $('matches');
  const found = searchMatches($('search').value);
  list.textContent = '';
  list.hidden = found.length === 0;
  found.forEach((s, i) => {
    const li = document.createElement('li');
    li.setAttribute('role', 'option');
    li.dataset.code = s.code;
    if (i === 0) li.setAttribute('aria-selected', 'true');
    li.innerHTML = `${s.common} <small><i>${s.scientific}</i> ${s.code}</small>`;
    li.onmousedown = (e) => { e.preventDefault(); addSpecies(s.code); };
    list.append(li);
  });
}

function addSpecies(code) {
  if (state.chosen.length >= MAX_SPECIES || state.chosen.includes(code)) return;
  state.chosen.push(code);
  $('search').value = '';
  $('matches').hidden = true;
  refresh();
}

// ---- the age range and the slider -----------------------------------------------------

function ageRange() {
  let lo = 1, hi = 200;
  for (const code of state.chosen) {
    const s = state.species.find((x) => x.code === code);
    lo = Math.max(lo, s.ages[0]);
    hi = Math.min(hi, s.ages[1]);
  }
  return [lo, Math.max(lo, hi)];
}

function setAge(age) {
  const [lo, hi] = ageRange();
  state.age = Math.min(hi, Math.max(lo, Math.round(age)));
  $('age').value = state.age;
  $('age-label').textContent = `age ${state.age}`;
  $('table-title').textContent = `At ${state.age} years`;
}

// ---- drawing ------------------------------------------------------------------------------

let drawing = 0;   // the latest request for trees; older ones give way
let drawnKey = null;  // the trees and street on the screen

async function drawTrees(stoppedAt) {
  const ticket = ++drawing;
  const age = state.age;
  const urls = state.chosen.map((code) => `/api/tree.glb?${treeQuery({ species: code, age, detail })}`);
  const scenes = await Promise.all(urls.map(loadGlb)).catch((e) => { status(e.message); return null; });
  if (!scenes || ticket !== drawing) return;
  timing.treesLoadedMs ??= performance.now();
  layoutStreet();
  // The same trees in the same street are on the screen already (the growth tables came
  // before the trees and laid the street out).
  const shown = `${urls.join()}|${street.streetKey}`;
  if (shown === drawnKey && stoppedAt == null) return;
  drawnKey = shown;
  const frame = street.setTrees(scenes.map((s) => s.clone()));
  (timing.frames ??= []).push([detail, Math.round(frame), street.triangles()]);
  placeLabels();
  // How long the browser was busy with this first frame: see the level's choice below.
  const busy = frame + street.pendingMs;
  const now = performance.now();
  if (timing.firstTreeMs === null) timing.firstTreeMs = now;
  if (stoppedAt != null) timing.ageDraws.push({ age, ms: now - stoppedAt, frame, busy, detail });
  timing.shownAge = age;
  status('');
  // Keep the next frames within FRAME_MS: one level coarser or finer, and redraw this age.
  // What is judged is how long the browser was busy with the first frame of new trees: the
  // frame, which uploads them as every new age must, and the charts of the age drawn before
  // it. A level that keeps that short keeps the slider quick too (judged by the frame alone,
  // a computer without a GPU went down to every twig and leaf on young trees, and new ages
  // of 30 to 50 years then took 400-500 ms).
  if (busy > FRAME_MS[1]) floor = Math.min(COARSEST, Math.max(floor, detail + 1));
  let next = busy > FRAME_MS[1] ? floor : busy < FRAME_MS[0] ? Math.max(floor, detail - 1) : detail;
  if (PINNED != null) next = PINNED;
  timing.detail = detail;
  $('detail').textContent = `Drawn with ${DETAIL_NAMES[detail]} (a frame takes ${frame.toFixed(0)} ms here).`;
  if (next !== detail && ticket === drawing) {
    detail = next;
    drawTrees(null);
  }
}

function loadGlb(url) {
  if (!glbs.has(url)) {
    timing.requests++;
    const get = async () => {
      const r = await ask(url, waitBusy);
      if (!r.ok) throw new Error((await r.json()).error);
      return r.arrayBuffer();
    };
    const p = get().then((buf) => loader.parseAsync(buf, '')).then((gltf) => gltf.scene);
    p.catch(() => glbs.delete(url));
    glbs.set(url, p);
    if (glbs.size > 40) glbs.delete(glbs.keys().next().value);
  }
  return glbs.get(url);
}

function layoutStreet() {
  const site = state.sites.find((s) => s.key === state.site).site;
  const region = state.regions.find((r) => r.code === state.region);
  // Slots wide enough for each species' widest crown in its data, so trees never overlap.
  let widest = 4, tallest = 6;
  for (const code of state.chosen) {
    const g = state.growth.get(code);
    if (!g) continue;
    for (const r of g.rows) {
      widest = Math.max(widest, r.measured.crown_diameter, r.model.crown_diameter);
      tallest = Math.max(tallest, r.measured.height, r.model.height);
    }
  }
  street.setStreet(site, state.chosen.length, widest * 1.05 + 1, region.latitude ?? 37.6, tallest);
}

function placeLabels() {
  const box = $('labels');
  box.textContent = '';
  state.chosen.forEach((code, i) => {
    const s = state.species.find((x) => x.code === code);
    const [x, y, visible] = street.project(street.slots[i] ?? 0, -1.5, 0);
    if (!visible) return;
    const div = document.createElement('div');
    div.style.left = `${x}px`;
    div.style.top = `${Math.min(y + 6, $('scene').clientHeight - 40)}px`;
    div.style.borderLeft = `4px solid ${COLOURS[i]}`;
    div.textContent = s.common;
    box.append(div);
  });
}
street.onDraw = () => { if (street.slots.length) placeLabels(); };

function row(code) {
  const g = state.growth.get(code);
  return g && g.rows.find((r) => r.age === state.age);
}

function drawNumbers() {
  const series = state.chosen.map((code, i) => ({ colour: COLOURS[i], rows: state.growth.get(code)?.rows || [] }));
  for (const canvas of document.querySelectorAll('#charts canvas')) {
    lineChart(canvas, canvas.dataset.q, series, state.age);
  }
  const f = (v, d = 1) => (v == null ? '–' : Number(v).toFixed(d));
  const typical = state.basis === 'typical';
  const head = ['Species', 'Height m', 'DBH cm', 'Crown m', 'Leaf area m²', 'CO₂ stored kg',
    'CO₂ taken up kg/yr', 'Rain held m³', 'Cooling kWh', 'Air quality $/yr', 'Net $/yr', 'Planted $/yr', 'In the way'];
  const lines = state.chosen.map((code, i) => {
    const s = state.species.find((x) => x.code === code);
    const r = row(code);
    if (!r) return `<tr><td style="color:${COLOURS[i]}">${s.common}</td><td colspan="12">growing…</td></tr>`;
    const st = account(r.street);
    const t = r.street.typical;
    let conflicts = typical ? 'no site' : st.conflicts.map((c) => c.kind.replace('_', ' ')).join(', ') || 'nothing';
    // A year a pruning cycle fell due: what the crews cut, and what it cost.
    const p = !typical && st.pruning;
    if (p && p.removal_cuts + p.reduction_cuts > 0) {
      conflicts += `<br><small title="${p.reasons.join(', ')}">pruned: ${p.removal_cuts + p.reduction_cuts} cuts, ` +
        `${f(p.leaf_removed_m2, 0)} m² leaf, $${f(p.cost_usd, 0)}</small>`;
    }
    // At typical position the flows are i-Tree's at this DBH; on a site, the grown tree's own.
    const flows = typical && t
      ? [t.co2_sequestered_kg, t.stormwater_m3, t.electricity_kwh]
      : [st.co2_sequestered_kg, st.interception_m3, st.cooling_kwh];
    return `<tr><td style="color:${COLOURS[i]}"><b>${s.common}</b></td>` +
      `<td>${f(r.model.height)} <small>(${f(r.measured.height)})</small></td>` +
      `<td>${f(r.model.dbh)} <small>(${f(r.measured.dbh)})</small></td>` +
      `<td>${f(r.model.crown_diameter)} <small>(${f(r.measured.crown_diameter)})</small></td>` +
      `<td>${f(r.model.leaf_area, 0)}</td><td>${f(st.co2_stored_kg, 0)}</td>` +
      `<td>${f(flows[0])}</td><td>${f(flows[1], 2)}</td>` +
      `<td>${f(flows[2], 0)}</td><td>${f(st.value_usd.air_quality, 0)}</td>` +
      `<td>${f(st.net_usd, 0)}</td>` +
      `<td>${f(st.planted_net_usd, 0)}<br><small>${f(100 * st.alive_share, 0)}% alive</small></td>` +
      `<td>${conflicts}</td></tr>`;
  });
  const basis = typical
    ? 'Benefits at typical position: i-Tree Streets\' figures for the species at the grown DBH.'
    : 'Benefits of the grown tree on this site.';
  $('table').innerHTML = `<tr>${head.map((h) => `<th>${h}</th>`).join('')}</tr>${lines.join('')}` +
    `<tr><td colspan="13" class="note">Grown tree, with the measured equation in brackets. ${basis} ` +
    'Net $/yr is a living tree\'s; planted $/yr is per tree planted, weighted by the share of the trees planted still standing ' +
    '(5% die a year while establishing, then fewer, to the tree guides\' share alive at 40 years).</td></tr>';
  const items = state.chosen.map((code, i) => {
    const s = state.species.find((x) => x.code === code);
    const r = row(code);
    return r && { label: s.common, colour: COLOURS[i], street: account(r.street) };
  }).filter(Boolean);
  barChart($('bars'), items);
  const missing = new Set();
  for (const code of state.chosen) for (const m of state.growth.get(code)?.missing || []) missing.add(m);
  $('missing').textContent = missing.size ? `Not counted: ${[...missing].join('; ')}.` : '';
}

function drawConflicts() {
  const [lo, hi] = ageRange();
  const marks = $('marks');
  marks.textContent = '';
  if (state.basis === 'typical') {
    // No site, no conflicts: the typical position is a spread of positions, not a street.
    $('conflicts').innerHTML = '<p class="note">Typical position: no site, so no conflicts. Choose a site above to see them.</p>';
    $('site-pictures').textContent = '';
    return;
  }
  const parts = [];
  state.chosen.forEach((code, i) => {
    const g = state.growth.get(code);
    const s = state.species.find((x) => x.code === code);
    if (!g) return;
    const items = g.first_conflicts.map((c) => `${c.kind.replace('_', ' ')} at ${c.age}`);
    // What the conflicts cost over every age shown, by who paid, and where the species does
    // not suit the site (the library's words: sylva::street::rank::unsuited).
    const costs = (g.conflict_costs || []).map((c) => `${c.conflict} $${Math.round(c.usd)} (${c.payer})`);
    const suits = (g.does_not_suit || []).length
      ? `<br><b>Does not suit this site</b>: ${g.does_not_suit.join('; ')}`
      : '<br>Suits this site.';
    parts.push(`<li style="color:${COLOURS[i]}"><b>${s.common}</b>: ${items.join(', ') || 'none in its data'}` +
      `${costs.length ? `<br><small>Per tree planted over these ages: ${costs.join(', ')}</small>` : ''}${suits}</li>`);
    for (const c of g.first_conflicts) {
      if (c.age < lo || c.age > hi) continue;
      const m = document.createElement('span');
      m.style.left = `${((c.age - lo) / Math.max(1, hi - lo)) * 100}%`;
      m.style.background = COLOURS[i];
      m.title = `${s.common}: first ${c.kind.replace('_', ' ')} conflict at ${c.age}`;
      marks.append(m);
    }
  });
  const label = state.sites.find((s) => s.key === state.site).label;
  $('conflicts').innerHTML = `<p class="note">${label}.</p><ul>${parts.join('')}</ul>`;
  drawSitePictures();
}

// Each tree on its site at the slider's age (across the street, and from above; red: what is
// in the way), fetched once the slider has rested for a moment.
let siteTimer = null;
function drawSitePictures() {
  clearTimeout(siteTimer);
  siteTimer = setTimeout(() => {
    const box = $('site-pictures');
    box.textContent = '';
    for (const code of state.chosen) {
      const img = document.createElement('img');
      img.alt = `${code} on the site at ${state.age} years`;
      img.src = `/api/site.png?${treeQuery({ species: code, age: state.age })}`;
      box.append(img);
    }
  }, 300);
}

function drawDownloads() {
  const a = (href, text) => `<a href="${href}" download>${text}</a>`;
  const all = state.chosen.join(',');
  const links = [
    a(`/api/compare.png?${treeQuery({ species: all, age: state.age })}`, 'Comparison picture (PNG)'),
    a(`/api/table.csv?${treeQuery({ species: all })}`, 'Table (CSV)'),
  ];
  for (const code of state.chosen) {
    links.push(a(`/api/tree.glb?${treeQuery({ species: code, age: state.age })}`, `${code} at ${state.age} (GLB)`));
    links.push(a(`/api/plan.svg?${treeQuery({ species: code, age: state.age })}`, `${code} plan symbol (SVG)`));
  }
  $('downloads').innerHTML = links.join(' ');
}

function drawAll() {
  drawNumbers();
  drawConflicts();
  drawDownloads();
}

// What changes with the slider's age alone.
function drawAge() {
  drawNumbers();
  drawDownloads();
  drawSitePictures();
}

// ---- loading ------------------------------------------------------------------------------

async function refresh() {
  renderChips();
  timing.tables = 0;
  if (state.chosen.length === 0) {
    street.setTrees([]);
    drawnKey = null;
    $('labels').textContent = '';
    drawAll();
    status('Add a species to begin: type part of its name above.');
    return;
  }
  const [lo, hi] = ageRange();
  $('age').min = lo;
  $('age').max = hi;
  setAge(state.age);
  const chosen = state.chosen.slice();
  status('Growing the trees…');
  const trees = drawTrees(null);
  drawAll();
  await Promise.all(chosen.map(async (code) => {
    const key = treeQuery({ species: code });
    if (state.growth.get(code)?.key !== key) {
      const g = await json(`/api/growth?${key}`);
      g.key = key;
      state.growth.set(code, g);
      drawAll();
    }
  })).catch((e) => status(e.message));
  timing.tables = state.chosen.filter((c) => state.growth.get(c)?.key === treeQuery({ species: c })).length;
  await trees;
  layoutStreet();
  drawTrees(null);
}

let playing = null;
function play() {
  if (playing) { clearInterval(playing); playing = null; $('play').innerHTML = '&#9654;'; return; }
  const [lo, hi] = ageRange();
  if (state.age >= hi) setAge(lo);
  $('play').innerHTML = '&#10074;&#10074;';
  playing = setInterval(async () => {
    const [, top] = ageRange();
    if (state.age >= top) { play(); return; }
    setAge(state.age + 1);
    drawAge();
    await drawTrees(null);
  }, 600);
}

async function start() {
  // The trees the page opens on are fetched at once, beside the lists it needs first.
  const url = new URLSearchParams(location.search);
  const wanted = (url.get('species') || 'PLAC,PICH').split(',').filter(Boolean);
  if (url.get('age')) state.age = Number(url.get('age'));
  state.region = url.get('region') || 'InlVal';
  for (const code of wanted) loadGlb(`/api/tree.glb?${treeQuery({ species: code, age: state.age, detail })}`).catch(() => {});
  askEarly(`/api/species?${query({})}`);
  for (const code of wanted) askEarly(`/api/growth?${treeQuery({ species: code })}`);
  const [regions, sites] = await Promise.all([getJson('/api/regions'), getJson('/api/sites')]);
  // The city view, where the server was given cities (`sylva serve --city DIR`).
  getJson('/api/cities').then((c) => { $('city-link').hidden = c.cities.length === 0; }).catch(() => {});
  state.regions = regions;
  state.sites = sites;
  // A provisional street, drawn once to compile the shaders while the trees download.
  const region = regions.find((r) => r.code === state.region);
  street.setStreet(sites[0].site, wanted.length, 12, region?.latitude ?? 37.6, 12);
  timing.warmMs = street.warm();
  $('region').innerHTML = regions.map((r) =>
    `<option value="${r.code}">${r.city}: ${r.name} (${r.code}, ${r.species} species)</option>`).join('');
  // The typical position first: the account a planner without a site reads.
  $('site').innerHTML = '<option value="typical">Typical position (i-Tree Streets, no site)</option>' +
    sites.map((s) => `<option value="${s.key}">${s.label}</option>`).join('');
  $('region').onchange = (e) => chooseRegion(e.target.value, []);
  $('site').onchange = (e) => {
    // The typical position reads the same growth as the first site (its accounts carry it)
    // and draws that street as a backdrop.
    state.basis = e.target.value === 'typical' ? 'typical' : 'site';
    if (state.basis === 'site') state.site = e.target.value;
    $('pruning').disabled = state.basis === 'typical';
    street.streetKey = null;
    refresh();
  };
  $('pruning').disabled = state.basis === 'typical';
  $('pruning').onchange = (e) => {
    state.pruning = e.target.checked;
    refresh();
  };
  $('search').oninput = showMatches;
  $('search').onkeydown = (e) => {
    if (e.key === 'Enter') {
      const first = $('matches').querySelector('li');
      if (first) addSpecies(first.dataset.code);
    }
  };
  $('search').onblur = () => { $('matches').hidden = true; };
  let lastInput = 0;
  $('age').oninput = (e) => {
    lastInput = performance.now();
    setAge(Number(e.target.value));
    drawAge();
    drawTrees(lastInput);
  };
  $('play').onclick = play;
  $('region').value = state.region;
  await chooseRegion(state.region, wanted);
}

start().catch((e) => status(`Could not start: ${e.message}`));
