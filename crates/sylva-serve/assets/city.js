// The city view: the tiles `sylva city` wrote, drawn by 3d-tiles-renderer on three.js, one
// tileset per epoch swapped in place by the slider; a click opens a tree's card (its row of the
// tile's property table, then its species' growth and yearly accounts from the street page's
// API); filters dim the trees they leave out; the city's report beside it.
//
// Everything comes from /api/cities and the city's own files under /city/NAME/. What the
// browser test reads is kept in `window.sylvaCity`.

import * as T from '/vendor/city.min.js';
import { lineChart, barChart } from '/charts.js';
import { askJson, waitingText } from '/ask.js';
import { softwareGl } from '/gl.js';
import { extentOf, drawGround } from '/city-ground.js';
import { epochTable, esc } from '/city-report.js';
import {
  prepare, rowOf, trees, paint, share, combine, forget, ownBytes, Batches, setSpeciesColours, PALETTE, OTHER_SPECIES, solidAt, LEFT_OUT,
} from '/city-trees.js';

const $ = (id) => document.getElementById(id);
const probe = { firstTreesMs: null, shownEpoch: null, clicks: [], problems: [] };
window.sylvaCity = probe;

const DIM = new T.Color(0.22, 0.22, 0.22);
const LIT = new T.Color(1, 1, 1);

const state = {
  cities: [], edges: [], basemap: null,
  city: null,        // the chosen city's entry of /api/cities
  frame: null,       // its tileset frame (ECEF) to the page's (east, up, south)
  epoch: 0,
  tilesets: new Map(),  // epoch index -> TilesRenderer
  filter: { species: '', dbh: '', condition: '', benefit: 0 },
  report: null,
};

// ---- the scene ------------------------------------------------------------------------------

const canvas = $('scene');
// A browser drawing WebGL on its CPU (no GPU) fills every pixel itself, every sample of it
// under multisampling: it draws without, at half a pixel per CSS pixel, and asks the tiles for
// a coarser level, so that the city still turns smoothly. (A 100,000-tree city on 2 cores
// turned at 7-8 frames a second at 0.6 with a draw per bark and per leaves, 10 with one per
// tree, 10-12 at 0.5; below 0.5 it gains nothing: the rest is the draws and the page's own
// compositing.)
const software = softwareGl();
probe.software = software;
const renderer = new T.WebGLRenderer({ canvas, antialias: !software });
renderer.outputColorSpace = T.SRGBColorSpace;
renderer.setPixelRatio(software ? 0.5 : Math.min(window.devicePixelRatio || 1, 2));
// `?error=N` in the address pins the tiles' error target in pixels (for a computer whose
// drawing misleads the page, and for timing one setting).
const ERROR_TARGET = (() => {
  const n = Number(new URLSearchParams(location.search).get('error') ?? NaN);
  return Number.isFinite(n) && n > 0 ? n : software ? 64 : 12;
})();
// Each grown tree's mesh file is fetched once and shared by every tile that draws it
// (`share` in city-trees.js); a city's files hold some 0.4 GB of them at 100,000 trees.
T.Cache.enabled = true;
const scene = new T.Scene();
scene.background = new T.Color('#cfdde6');
scene.add(new T.HemisphereLight('#f4f7ff', '#5b6650', 1.6));
const sun = new T.DirectionalLight('#fff6e8', 1.8);
sun.position.set(0.4, 1, 0.3);
scene.add(sun);
const camera = new T.PerspectiveCamera(45, 1, 1, 30000);
const controls = new T.MapControls(camera, canvas);
controls.maxPolarAngle = Math.PI * 0.47;
controls.screenSpacePanning = false;
const ground = new T.Group();
scene.add(ground);

let dirty = true;
const redraw = () => { dirty = true; };
controls.addEventListener('change', redraw);

function resize() {
  const w = canvas.clientWidth, h = canvas.clientHeight;
  if (!w || !h) return;
  renderer.setSize(w, h, false);
  camera.aspect = w / h;
  camera.updateProjectionMatrix();
  for (const t of state.tilesets.values()) t.setResolutionFromRenderer(camera, renderer);
  redraw();
}
new ResizeObserver(resize).observe(canvas);

// Frames drawn, for the browser test's rate (each frame's time since the last drawn).
const frames = [];
probe.frames = frames;
const batches = new Batches(scene);
const drawnSize = new T.Vector2();
const spent = { update: 0, gather: 0, render: 0, loads: 0, calls: 0 };
probe.spent = spent;
function loop(now) {
  requestAnimationFrame(loop);
  const tiles = state.tilesets.get(state.epoch);
  const t0 = performance.now();
  if (tiles) {
    camera.updateMatrixWorld();
    tiles.update();
    spent.update += performance.now() - t0;
    // The epoch is shown once every tile the view asks for is loaded and drawn.
    if (probe.shownEpoch == null && !tiles.isLoading && tiles.loadProgress === 1 && tiles.stats.visible > 0) {
      probe.shownEpoch = state.city.epochs[state.epoch].years;
      probe.shownMs = performance.now();
    }
  }
  if (!dirty) return;
  dirty = false;
  const t1 = performance.now();
  if (tiles) {
    const view = new T.Matrix4().multiplyMatrices(camera.projectionMatrix, camera.matrixWorldInverse);
    renderer.getDrawingBufferSize(drawnSize);
    const pixels = drawnSize.y / (2 * Math.tan((camera.fov * Math.PI) / 360));
    spent.calls = batches.fill(tiles.group, view, { position: camera.position, pixels });
  }
  const t2 = performance.now();
  spent.gather += t2 - t1;
  renderer.render(scene, camera);
  spent.render += performance.now() - t2;
  frames.push(now);
  if (frames.length > 600) frames.splice(0, 300);
}
requestAnimationFrame(loop);

// ---- the city's tiles --------------------------------------------------------------------------

// Every tileset of a city shares the frame `sylva city` made at the middle of its trees: its
// root transform takes local east-north-up metres to the Earth's (ECEF). The page draws in
// those local metres, turned so that up is three.js's y.
function pageFrame(rootTransform) {
  const toLocal = new T.Matrix4().fromArray(rootTransform).invert();
  const upIsY = new T.Matrix4().set(1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1);
  return upIsY.multiply(toLocal);
}

function dbhClass(dbh) {
  let c = 0;
  while (c < state.edges.length && state.edges[c] <= dbh) c++;
  return c;
}

function shown(row) {
  const f = state.filter;
  if (f.species && row.species !== f.species) return false;
  if (f.dbh !== '' && dbhClass(row.dbh_cm) !== Number(f.dbh)) return false;
  // A tile written before condition was read has no such column: every tree not recorded.
  if (f.condition && (row.condition || 'none') !== f.condition) return false;
  return (row.typical_benefits_usd_per_year || 0) >= f.benefit;
}

function colourTrees(root) {
  const f = state.filter;
  const all = !f.species && f.dbh === '' && !f.condition && !(f.benefit > 0);
  root.traverse((o) => {
    if (!o.isInstancedMesh && !(o.isPoints && o.name.startsWith(LEFT_OUT))) return;
    if (all && !o.userData.sylva?.painted) return;
    paint(o, all ? null : shown, DIM);
    o.userData.sylva.painted = !all;
  });
}

// The species of the trees of the tiles loaded so far (a tile's trees are counted at each of
// its levels: the order, not the count, is what the colours need), as the report lists them.
const counted = new Map();
function countSpecies(model) {
  model.traverse((o) => {
    if (!o.isInstancedMesh) return;
    for (const [row] of trees(o)) {
      if (!row) continue;
      const s = counted.get(row.species) || { code: row.species, common: row.common_name || row.species, trees: 0 };
      s.trees++;
      counted.set(row.species, s);
    }
  });
  return [...counted.values()];
}

function tilesetOf(index) {
  if (state.tilesets.has(index)) return state.tilesets.get(index);
  const epoch = state.city.epochs[index];
  const tiles = new T.TilesRenderer(epoch.tileset);
  tiles.registerPlugin(new T.GLTFExtensionsPlugin({ metadata: true }));
  // Pixels of error allowed before a finer tile is asked for: more on a CPU-drawn page, which
  // then draws a street's trees at the coarsest level from a few hundred metres.
  tiles.errorTarget = ERROR_TARGET;
  // The tile cache counts each tile's own bytes (its trees), not the meshes it shares.
  tiles.calculateBytesUsed = (tile, model) => (model ? ownBytes(model) : null);
  tiles.lruCache.maxBytesSize = 256 * 2 ** 20;
  tiles.setCamera(camera);
  tiles.setResolutionFromRenderer(camera, renderer);
  state.frame.decompose(tiles.group.position, tiles.group.quaternion, tiles.group.scale);
  tiles.addEventListener('load-model', ({ scene: model }) => {
    const t0 = performance.now();
    model.traverse((o) => { if (o.isInstancedMesh) { prepare(o); share(o); } });
    combine(model);
    colourTrees(model);
    if (!state.report) colourSpecies(countSpecies(model));
    spent.loads += performance.now() - t0;
    if (probe.firstTreesMs == null && index === state.epoch) {
      // The first frame with trees in it is the next one drawn.
      requestAnimationFrame(() => { probe.firstTreesMs ??= performance.now(); });
    }
    redraw();
  });
  tiles.addEventListener('needs-render', redraw);
  tiles.addEventListener('needs-update', redraw);
  tiles.addEventListener('tiles-load-end', () => { status(''); redraw(); });
  scene.add(tiles.group);
  state.tilesets.set(index, tiles);
  return tiles;
}

function showEpoch(index) {
  state.epoch = index;
  const epoch = state.city.epochs[index];
  for (const [i, t] of state.tilesets) t.group.visible = i === index;
  const tiles = tilesetOf(index);
  tiles.group.visible = true;
  colourTrees(tiles.group);
  $('epoch').value = String(index);
  $('epoch-label').textContent = epoch.years === 0 ? 'as inventoried' : `+${epoch.years} years`;
  $('counts').textContent = `${epoch.trees.toLocaleString()} trees`;
  probe.shownEpoch = null;
  status('loading tiles…');
  showReportEpoch();
  redraw();
}

// ---- choosing a city ----------------------------------------------------------------------------

function status(text) { $('status').textContent = text || ''; }

async function chooseCity(name) {
  for (const t of state.tilesets.values()) { scene.remove(t.group); t.dispose(); }
  state.tilesets.clear();
  batches.clear();
  forget();
  counted.clear();
  $('card').hidden = true;
  const city = state.cities.find((c) => c.name === name);
  state.city = city;
  history.replaceState(null, '', `?city=${encodeURIComponent(name)}`);
  if (!city || city.problem) { status(city ? city.problem : `no city ${name}`); return; }
  const first = await askJson(city.epochs[0].tileset);
  state.frame = pageFrame(first.root.transform);
  const e = extentOf(first.root.boundingVolume.box);
  drawGround(ground, e, state.basemap, state.city.origin, probe, redraw);
  fitView(e);
  const slider = $('epoch');
  slider.max = String(city.epochs.length - 1);
  slider.disabled = city.epochs.length < 2;
  $('epoch-marks').innerHTML = city.epochs.map((ep, i) =>
    `<span style="left:${city.epochs.length > 1 ? (100 * i) / (city.epochs.length - 1) : 0}%">` +
    `${ep.years === 0 ? 'now' : `+${ep.years}`}</span>`).join('');
  await loadReport(city);
  colourSpecies();
  showEpoch(0);
}

// The view's slope and bearing: 50 degrees up, from 20 degrees west of south.
const UP = (50 * Math.PI) / 180, ROUND = (20 * Math.PI) / 180;

// The default view: from the south-south-west and 50 degrees up, over the middle of the trees,
// just far enough that all of them are in the picture (a census sample spread over kilometres
// as well as a dense demo city); trees too small to see there are drawn as markers.
function fitView(e) {
  const w = e.x1 - e.x0, d = e.n1 - e.n0;
  const cx = (e.x0 + e.x1) / 2, cz = -(e.n0 + e.n1) / 2;
  const half = Math.tan((camera.fov * Math.PI) / 360);
  // The extent turned as the camera sees it, its depth foreshortened by the view's slope; a
  // third spare (the near side is drawn larger than the far), and never nearer than a street's length.
  const across = Math.abs(w * Math.cos(ROUND)) + Math.abs(d * Math.sin(ROUND));
  const deep = (Math.abs(w * Math.sin(ROUND)) + Math.abs(d * Math.cos(ROUND))) * Math.sin(UP);
  const r = Math.max(80, 1.3 * Math.max(across / 2 / (half * camera.aspect), deep / 2 / half));
  controls.target.set(cx, 0, cz);
  lookFrom(r);
  probe.fitted = { distance: r, extent: [w, d] };
}

// The camera `r` metres from the view's centre, 50 degrees up from the south-south-west.
function lookFrom(r) {
  const { x: cx, z: cz } = controls.target;
  camera.position.set(cx - r * Math.cos(UP) * Math.sin(ROUND), r * Math.sin(UP), cz + r * Math.cos(UP) * Math.cos(ROUND));
  camera.far = Math.max(30000, 4 * r);
  camera.updateProjectionMatrix();
  controls.update();
  redraw();
}
// For the browser test: the view `r` metres from the middle (300: the opening view before
// it was fitted).
probe.lookFrom = lookFrom;

// The markers' colours: the report's most common species first; a city without a report, the
// most common in the tiles loaded so far (`speciesInTiles`).
function colourSpecies(counted = null) {
  const species = (counted || state.report?.species || []).slice().sort((a, b) => b.trees - a.trees);
  setSpeciesColours(species.map((s) => s.code));
  const shownSpecies = species.slice(0, PALETTE.length);
  const rest = species.length - shownSpecies.length;
  $('legend').innerHTML = shownSpecies.map((s, i) =>
    `<span><i style="background:${PALETTE[i]}"></i>${esc(s.common)}</span>`).join('') +
    (rest > 0 ? `<span><i style="background:${OTHER_SPECIES}"></i>${rest} other species</span>` : '');
}

// ---- filters ------------------------------------------------------------------------------------

function fillFilters() {
  const species = state.report?.species || [];
  $('f-species').innerHTML = '<option value="">all</option>' + species
    .map((s) => `<option value="${s.code}">${s.common} (${s.code}, ${s.trees})</option>`).join('');
  const e = state.edges;
  const label = (i) => (i === 0 ? `under ${e[0]} cm` : i === e.length ? `${e[e.length - 1]} cm and over`
    : `${e[i - 1]}–${e[i]} cm`);
  $('f-dbh').innerHTML = '<option value="">all</option>' +
    [...Array(e.length + 1).keys()].map((i) => `<option value="${i}">${label(i)}</option>`).join('');
}

function applyFilter() {
  state.filter = {
    species: $('f-species').value,
    dbh: $('f-dbh').value,
    condition: $('f-condition').value,
    benefit: Math.max(0, Number($('f-benefit').value) || 0),
  };
  for (const t of state.tilesets.values()) colourTrees(t.group);
  redraw();
}

// ---- the tree's card --------------------------------------------------------------------------

let down = null;
canvas.addEventListener('pointerdown', (e) => { down = [e.clientX, e.clientY]; });
canvas.addEventListener('pointerup', (e) => {
  if (!down || Math.hypot(e.clientX - down[0], e.clientY - down[1]) > 4) return;
  pick(e.clientX, e.clientY);
});

const raycaster = new T.Raycaster();
function treeAt(clientX, clientY) {
  const tiles = state.tilesets.get(state.epoch);
  if (!tiles) return null;
  const r = canvas.getBoundingClientRect();
  const p = new T.Vector2(((clientX - r.left) / r.width) * 2 - 1, -((clientY - r.top) / r.height) * 2 + 1);
  raycaster.setFromCamera(p, camera);
  for (const hit of raycaster.intersectObjects(batches.meshes(), false)) {
    if (!solidAt(hit.object.material, hit.uv)) continue;
    const ref = hit.instanceId == null ? null : batches.ref(hit.object, hit.instanceId);
    const row = ref && rowOf(ref[0], ref[1]);
    if (row) return row;
  }
  // A marker within a few pixels of the click (its size and a little more).
  const within = (2 * 6) / r.height;
  const ref = batches.markerAt(camera, p.x, p.y, within);
  return ref ? rowOf(ref[0], ref[1]) : null;
}

function pick(clientX, clientY) {
  const t0 = performance.now();
  const row = treeAt(clientX, clientY);
  if (row) showCard(row);
  probe.clicks.push({ ms: performance.now() - t0, id: row ? row.id : null });
  return row;
}
probe.pick = pick;

const f = (v, d = 1) => (v == null || Number.isNaN(v) ? '–' : Number(v).toFixed(d));

async function showCard(row) {
  $('card').hidden = false;
  $('card-title').textContent = `${row.common_name || row.species}: tree ${row.id}`;
  const epoch = state.city.epochs[state.epoch];
  const lines = [
    ['Inventory row', `id ${esc(row.id)}; written as “${esc(row.species_written)}”`],
    ['Grown as', `${esc(row.scientific_name)} (${esc(row.species)}) of the ${esc(row.region)} region`],
    ['Condition', row.condition ? `${row.condition}, as the inventory recorded it` : 'not recorded'],
    ['Epoch', epoch.years === 0 ? 'as inventoried' : `${epoch.years} years after the inventory`],
    ['Age', `${f(row.age_years, 0)} years`],
    ['DBH', `${f(row.dbh_cm)} cm`],
    ['Height, crown', `${f(row.height_m)} m, ${f(row.crown_diameter_m)} m across`],
    ['CO₂ stored, taken up', `${f(row.co2_stored_kg, 0)} kg, ${f(row.co2_sequestered_kg_per_year)} kg a year`],
    ['Rain held', `${f(row.rain_intercepted_m3_per_year, 2)} m³ a year`],
    ['Benefits (Sylva)', `$${f(row.benefits_usd_per_year, 2)} a year: CO₂, rain, air and aesthetics of the ` +
      'grown crown (its energy not computed: no façades)'],
    ['Benefits (i-Tree, typical position)', `$${f(row.typical_benefits_usd_per_year, 2)} a year: energy ` +
      `$${f(row.typical_energy_usd_per_year, 2)}, carbon $${f(row.typical_carbon_usd_per_year, 2)}, ` +
      `stormwater $${f(row.typical_stormwater_usd_per_year, 2)}, air $${f(row.typical_air_quality_usd_per_year, 2)}, ` +
      `aesthetics $${f(row.typical_aesthetics_usd_per_year, 2)}`],
  ];
  $('card-table').innerHTML = lines.map(([k, v]) => `<tr><th>${k}</th><td>${v}</td></tr>`).join('');
  const age = Math.max(1, Math.round(row.age_years));
  const link = `/?region=${encodeURIComponent(row.region)}&species=${encodeURIComponent(row.species)}&age=${age}`;
  $('card-link').innerHTML = `<a id="street-link" href="${link}">Open ${esc(row.common_name || row.species)} ` +
    `at ${age} years on the street page</a>`;
  $('card-note').textContent = 'Growing its species for the charts…';
  try {
    // A busy server (503) is waited for, and the card says what for.
    const growth = await askJson(`/api/growth?region=${encodeURIComponent(row.region)}&species=${encodeURIComponent(row.species)}`,
      (n) => {
        // Every message shown, in order (a real busy server may answer after the first).
        const text = `Growing its species for the charts: ${waitingText(n)}`;
        $('card-note').textContent = text;
        (probe.cardWaited ||= []).push(text);
      });
    if ($('card-title').textContent !== `${row.common_name || row.species}: tree ${row.id}`) return;
    const series = [{ colour: '#2f7d4f', rows: growth.rows }];
    for (const c of document.querySelectorAll('#card-charts canvas')) lineChart(c, c.dataset.q, series, age);
    const year = growth.rows.find((r) => r.age === age) || growth.rows[growth.rows.length - 1];
    const st = year.street;
    const typical = st.typical ? { ...st, value_usd: st.typical.value_usd, net_usd: st.typical.net_usd } : st;
    barChart($('card-bars'), [{ label: `${row.species} at ${year.age}`, colour: '#2f7d4f', street: typical }]);
    $('card-note').textContent = `Charts: the species grown in ${row.region} from planting (solid) against the ` +
      `measured equations (dashed), this tree's age marked; bars: its account at ${year.age} years at typical ` +
      `position, as on the street page.`;
    probe.cardCharts = (probe.cardCharts || 0) + 1;
  } catch (err) {
    $('card-note').textContent = `No charts: ${err.message}`;
  }
}

// ---- the report ---------------------------------------------------------------------------------

async function loadReport(city) {
  state.report = null;
  const files = city.report;
  $('report-files').innerHTML = ['html', 'csv', 'json'].filter((k) => files[k])
    .map((k) => `<a href="${files[k]}" download>${k.toUpperCase()}</a>`).join(' ');
  if (!files.json) {
    $('report-summary').innerHTML = '<p class="note">No report: run <code>sylva city --report</code> to write one beside the tiles.</p>';
    $('report-frame').hidden = true;
    fillFilters();
    return;
  }
  try {
    state.report = await askJson(files.json);
  } catch (err) {
    $('report-summary').innerHTML = `<p class="note">The report cannot be read: ${esc(err.message)}</p>`;
  }
  $('report-frame').hidden = !files.html;
  if (files.html) $('report-frame').src = files.html;
  fillFilters();
}

function showReportEpoch() {
  if (!state.report) return;
  $('report-summary').innerHTML = epochTable(state.report, state.city.epochs[state.epoch].years);
}

// ---- for the browser test ------------------------------------------------------------------------

// Whether a click at (x, y) reaches the scene: no panel, legend or card lies over it (the view
// turns while the test times it, so a tree may end up under one).
const onCanvas = (x, y) => document.elementFromPoint(x, y) === canvas;

// Where some drawn trees stand on the screen (mid-height of each instance, inside the canvas
// and not under a panel), so that the test clicks trees as a user would.
probe.treePoints = (most = 20) => {
  const out = [];
  const r = canvas.getBoundingClientRect();
  const m = new T.Matrix4(), p = new T.Vector3();
  for (const mesh of batches.meshes()) {
    for (let i = 0; i < mesh.count && out.length < most * 20; i++) {
      const [tile, k] = batches.ref(mesh, i);
      const row = rowOf(tile, k);
      mesh.getMatrixAt(i, m);
      p.setFromMatrixPosition(m);
      p.y += 0.45 * (row?.height_m || 4);
      p.project(camera);
      const x = r.left + ((p.x + 1) / 2) * r.width, y = r.top + ((1 - p.y) / 2) * r.height;
      if (Math.abs(p.x) < 0.9 && Math.abs(p.y) < 0.9 && p.z < 1 && onCanvas(x, y)) {
        out.push({ x, y, id: row?.id, depth: p.z });
      }
    }
  }
  // Nearest first: a tree in front of another is the one a click reaches.
  return out.sort((a, b) => a.depth - b.depth).slice(0, most);
};

// What the last frame drew, and the shown tiles by depth.
probe.drawn = () => {
  const levels = {};
  const tiles = state.tilesets.get(state.epoch);
  tiles?.forEachLoadedModel((model, tile) => {
    const d = tile.internal.depth;
    if (model.parent && model.visible) levels[d] = (levels[d] || 0) + 1;
  });
  return {
    triangles: renderer.info.render.triangles, calls: renderer.info.render.calls, levels, batches: spent.calls,
    markers: batches.markers.n,
    // The trees coarse tiles leave out of their meshes, drawn as their own dots.
    leftOut: batches.leftOutShown,
  };
};

// Where markers stand on the screen and a click reaches them, and their trees' ids (at most
// `most`, spread over all).
probe.markerPoints = (most = 20) => {
  const m = batches.markers, out = [], p = new T.Vector3();
  const r = canvas.getBoundingClientRect();
  const every = Math.max(1, Math.floor(m.n / most));
  for (let i = 0; i < m.n && out.length < most; i += every) {
    // Markers of the trees a coarse tile leaves out have no card to open.
    if (!m.refs[i]) continue;
    p.fromArray(m.position, 3 * i).project(camera);
    const x = r.left + ((p.x + 1) / 2) * r.width, y = r.top + ((1 - p.y) / 2) * r.height;
    if (Math.abs(p.x) < 0.95 && Math.abs(p.y) < 0.95 && p.z < 1 && onCanvas(x, y)) {
      const [tile, k] = m.refs[i];
      out.push({ x, y, id: rowOf(tile, k)?.id });
    }
  }
  return out;
};

// The trees' places on the screen: how many of the loaded tiles' trees lie inside the picture
// (each tree's sphere centre, from its tile's data), for the test of the fitted view.
probe.treesInPicture = () => {
  let inside = 0, all = 0;
  const p = new T.Vector3(), m = new T.Matrix4();
  state.tilesets.get(state.epoch)?.group.traverse((o) => {
    const s = o.userData.sylva;
    if (!o.isInstancedMesh || !s?.merged) return;
    for (let i = 0; i < s.n; i++) {
      all++;
      m.fromArray(s.matrices, 16 * i).premultiply(o.matrixWorld);
      p.setFromMatrixPosition(m).project(camera);
      if (Math.abs(p.x) <= 1 && Math.abs(p.y) <= 1 && p.z < 1) inside++;
    }
  });
  return { inside, all };
};

// Trees of the shown epoch's loaded tiles, lit (the filter keeps them) and dimmed.
probe.lit = () => {
  let lit = 0, dim = 0;
  state.tilesets.get(state.epoch)?.group.traverse((o) => {
    if (!o.isInstancedMesh) return;
    for (const [row, on] of trees(o)) if (row) { if (on) lit++; else dim++; }
  });
  return { lit, dim };
};

// Turns the view about its centre, a degree a frame, for `ms`; resolves to the frames drawn
// and the time they took.
probe.turn = (ms) => new Promise((done) => {
  const t0 = performance.now(), n0 = frames.length;
  const step = () => {
    const now = performance.now();
    if (now - t0 >= ms) { done({ frames: frames.length - n0, ms: now - t0 }); return; }
    const v = camera.position.clone().sub(controls.target).applyAxisAngle(new T.Vector3(0, 1, 0), Math.PI / 180);
    camera.position.copy(controls.target).add(v);
    controls.update();
    redraw();
    requestAnimationFrame(step);
  };
  requestAnimationFrame(step);
});

// ---- start --------------------------------------------------------------------------------------

async function start() {
  const listed = await askJson('/api/cities');
  state.cities = listed.cities;
  state.edges = listed.dbh_class_edges_cm;
  state.basemap = listed.basemap;
  const bad = state.cities.filter((c) => c.problem);
  probe.problems = bad.map((c) => c.problem);
  $('problems').hidden = bad.length === 0;
  $('problem-list').innerHTML = bad.map((c) => `<li><b>${esc(c.name)}</b>: ${esc(c.problem)}</li>`).join('');
  const good = state.cities.filter((c) => !c.problem);
  $('city').innerHTML = good.map((c) => `<option value="${esc(c.name)}">${esc(c.name)} ` +
    `(${Number(c.trees).toLocaleString()} trees)</option>`).join('');
  if (!good.length) {
    status(state.cities.length ? 'No city here can be shown: see the list on the right.'
      : 'No city: start the server with sylva serve --city DIR (a folder sylva city wrote).');
    probe.ready = true;
    return;
  }
  const asked = new URLSearchParams(location.search).get('city');
  const name = good.some((c) => c.name === asked) ? asked : good[0].name;
  $('city').value = name;
  $('city').onchange = (e) => chooseCity(e.target.value);
  $('epoch').oninput = (e) => showEpoch(Number(e.target.value));
  for (const id of ['f-species', 'f-dbh', 'f-condition', 'f-benefit']) $(id).onchange = applyFilter;
  $('f-benefit').oninput = applyFilter;
  resize();
  await chooseCity(name);
  probe.ready = true;
}

start().catch((err) => { status(`The city view failed: ${err.message}`); probe.error = err.message; });
